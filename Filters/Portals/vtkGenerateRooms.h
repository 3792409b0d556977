/**
 * @class   vtkGenerateRooms
 * @brief   Finds the rooms of an architectural model and the portals between them, from its
 *          geometry alone.
 *
 * Real buildings come without portals; vtkPortalCuller is only as useful as the portals a user
 * can get. This filter finds them: from walls, floors and ceilings whose openings (doors,
 * windows, stair holes) are holes, it finds the rooms and one convex portal polygon per opening
 * (scenevis/PortalGeneration.h in the VTK-free core: a solid-leaf BSP over the polygons, whose
 * empty cells are joined into rooms across every open face that is not an opening).
 *
 * Input: polydata whose polygons and triangle strips bound the rooms and face into them (other
 * cells take no part). Translucent cells (RGBA cell scalars with alpha below 255, when
 * TranslucentCellsAreSeeThrough is on) are glass: they get a room but do not close an opening.
 *
 * Outputs, the portal scene format that vtkPortalCuller and `scenevis cull --portals` read:
 * - port 0: the input (shallow copy) with an int cell array RoomArrayName ("RoomId"): the room
 *   of every polygon and strip, 0 .. rooms-1, or -1 (outside: facades, cells that are not
 *   polygons, dropped polygons, and everything when no rooms were found);
 * - port 1 (GetPortalsOutput): one planar convex polygon per portal with int cell arrays "RoomA"
 *   and "RoomB" (RoomB -1 for a portal to the outside);
 * - port 2 (GetLeaksOutput): one vertex per leak found, at a point of the gap's cell: where the
 *   outside reaches in through something that is not an opening (a missing wall, a crack).
 *
 * Conservative by construction on models that do not leak: no portal is smaller than the
 * opening it stands for. A model that leaks gets no rooms (every cell -1, no portals, the leaks
 * named in a warning and in the leaks output): through a leak no room labelling is conservative
 * (on two leaking game levels, hydronex2 and ps9ctf, the rooms lost pixels in 5-10 views of
 * 33-42; scenevis/PortalGeneration.h says why). KeepRoomsWithLeaks keeps them anyway, with a
 * warning. Generation never fails silently: GetStatus()
 * and GetStatusMessage() say why there are no rooms (empty input, only degenerate or NaN polygons,
 * over the time budget, leaks), and a warning names leaks and dropped polygons.
 *
 * Cost: not linear (the demo building's 2,250 polygons about 0.5 s, a 67,000-polygon level about
 * 25 s, one core); BudgetSeconds bounds it.
 *
 * @code
 * vtkNew<vtkGenerateRooms> rooms;
 * rooms->SetInputConnection(reader->GetOutputPort());
 * rooms->Update();
 * culler->SetPortals(rooms->GetPortalsOutput()); // actors per RoomId value (e.g. vtkThreshold)
 * @endcode
 *
 * @sa vtkPortalCuller
 */

#ifndef vtkGenerateRooms_h
#define vtkGenerateRooms_h

#include "SceneVisFiltersPortalsModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

#include <memory> // For std::unique_ptr

namespace scenevis
{
namespace portals
{
struct GeneratedPortals;
}
}

class SCENEVISFILTERSPORTALS_EXPORT vtkGenerateRooms : public vtkPolyDataAlgorithm
{
public:
  static vtkGenerateRooms* New();
  vtkTypeMacro(vtkGenerateRooms, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Name of the output's room cell array. Default "RoomId". Input arrays of that name are
  /// replaced, in cell data and in field data (vtkPortalCuller reads a field array first).
  vtkSetStringMacro(RoomArrayName);
  vtkGetStringMacro(RoomArrayName);
  ///@}

  ///@{
  /// Share of a planar open region's outline that must lie against polygons of its own plane for
  /// the region to be an opening (a door in a wall: its jambs and lintel). Default 0.45.
  vtkSetClampMacro(OpeningEnclosure, double, 0.0, 1.0);
  vtkGetMacro(OpeningEnclosure, double);
  ///@}

  ///@{
  /// Rooms with volume / (largest opening area)^1.5 below this are passages (the tunnel a door
  /// makes through a thick wall) and join a neighbour. Default 0.5.
  vtkSetClampMacro(PassageThickness, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(PassageThickness, double);
  ///@}

  ///@{
  /// Growth of the scene box around the input bounds, as a fraction of their diagonal.
  /// Default 0.1.
  vtkSetClampMacro(Margin, double, 1e-3, 10.0);
  vtkGetMacro(Margin, double);
  ///@}

  ///@{
  /// Processor seconds generation may take (0, the default: no limit). Past it, no rooms:
  /// status STATUS_OVER_BUDGET, every cell in room -1, no portals (never a partial answer).
  vtkSetClampMacro(BudgetSeconds, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(BudgetSeconds, double);
  ///@}

  ///@{
  /// Stop at the first leak found: a leaking model then costs much less and gives no rooms, one
  /// leak point. For callers that use rooms only when nothing leaks. Default off: every leak is
  /// found (and counted; no rooms unless KeepRoomsWithLeaks).
  vtkSetMacro(StopAtFirstLeak, bool);
  vtkGetMacro(StopAtFirstLeak, bool);
  vtkBooleanMacro(StopAtFirstLeak, bool);
  ///@}

  ///@{
  /// With leaks, still give the rooms found (the rooms behind a leak merged into the outside).
  /// Not conservative: the portals may hide visible cells. Default off: a model that leaks gets
  /// no rooms (status OK, every cell -1, no portals) and a warning.
  vtkSetMacro(KeepRoomsWithLeaks, bool);
  vtkGetMacro(KeepRoomsWithLeaks, bool);
  vtkBooleanMacro(KeepRoomsWithLeaks, bool);
  ///@}

  ///@{
  /// Whether cells with alpha below 255 in 4-component unsigned char cell scalars are see-through
  /// (glass: they do not close an opening). Default on.
  vtkSetMacro(TranslucentCellsAreSeeThrough, bool);
  vtkGetMacro(TranslucentCellsAreSeeThrough, bool);
  vtkBooleanMacro(TranslucentCellsAreSeeThrough, bool);
  ///@}

  /// The portals (output port 1) and the leak points (output port 2).
  vtkPolyData* GetPortalsOutput();
  vtkPolyData* GetLeaksOutput();

  enum Statuses
  {
    STATUS_OK = 0,
    STATUS_EMPTY_INPUT,       ///< No polygons.
    STATUS_NO_VALID_POLYGONS, ///< Every polygon was degenerate or touched a NaN/Inf point.
    STATUS_OVER_BUDGET,       ///< Stopped after BudgetSeconds; no rooms.
    STATUS_NOT_RUN            ///< Before the first update.
  };

  ///@{
  /// The last generation: its status and, when not STATUS_OK or when a model that leaks got no
  /// rooms, why (one line).
  int GetStatus() const;
  const char* GetStatusMessage() const;
  ///@}

  ///@{
  /// Counts of the last generation.
  int GetNumberOfRooms() const;                 ///< Rooms, without the outside.
  vtkIdType GetNumberOfPortals() const;         ///< All portals,
  vtkIdType GetNumberOfExteriorPortals() const; ///< of which to the outside.
  vtkIdType GetNumberOfLeakCells()
    const; ///< Cells where the outside leaks in (see StopAtFirstLeak).
  vtkIdType GetNumberOfDroppedPolygons() const; ///< Degenerate or NaN/Inf: room -1.
  vtkIdType GetNumberOfSeeThroughPolygons() const;
  double GetGenerationTime() const; ///< Seconds, the core's generation alone.
  ///@}

#ifndef __VTK_WRAP__
  /// Everything the core returned for the last update (statistics, leak points), for callers
  /// in C++; an empty result before the first.
  const scenevis::portals::GeneratedPortals& GetResult() const;
#endif

protected:
  vtkGenerateRooms();
  ~vtkGenerateRooms() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  // Defaults: the core's (scenevis::portals::GenerationConfig), set in the constructor.
  char* RoomArrayName = nullptr;
  double OpeningEnclosure;
  double PassageThickness;
  double Margin;
  double BudgetSeconds;
  bool StopAtFirstLeak;
  bool KeepRoomsWithLeaks;
  bool TranslucentCellsAreSeeThrough = true;

private:
  vtkGenerateRooms(const vtkGenerateRooms&) = delete;
  void operator=(const vtkGenerateRooms&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
