/**
 * @class   vtkPortalCuller
 * @brief   Cells-and-portals occlusion culling for architectural models.
 *
 * Indoors, walls hide almost everything. The model is split into rooms joined by portals (doors,
 * windows, stair holes); every frame the view is clipped through the portals the eye can see
 * (Luebke & Georges, "Portals and Mirrors", 1995) and props of rooms that cannot be seen are
 * culled. The geometry is in the VTK-free core (scenevis/PortalGraph.h, PortalTraversal.h,
 * PortalPvs.h); this class converts VTK data and honours the vtkCuller contract.
 *
 * Scene description (loadable from VTK XML PolyData, e.g. with vtkXMLPolyDataReader):
 * - Portals (SetPortals): one planar polygon per portal (convex or concave) with two integer
 *   cell-data arrays "RoomA" and "RoomB" naming the rooms it joins (-1 = outside).
 * - Room of each prop, first match wins: SetPropRoom(prop, room); SetPropCellRooms(prop, rooms)
 *   (one room per cell, given apart from the prop's data); a one-tuple field-data array
 *   named RoomIdArrayName ("RoomId") on the actor's mapper input; a cell-data array of that name
 *   (an actor whose cells span several rooms is drawn when any of them may be seen). Props with no
 *   room are only frustum-culled. The polygons of actors with room ids locate the eye (an eye in
 *   no room: see OutsidePolicy).
 *
 * Modes: MODE_EXACT_FRUSTUM (default; narrowing by the portal's edges, tighter),
 * MODE_SCREEN_RECTANGLES (Luebke-Georges screen rectangles, cheaper per portal, looser),
 * MODE_PVS (precomputed potentially visible sets of the eye's rooms + frustum; computed on first
 * use or with ComputePVS(), saved with SavePVS() and loaded with LoadPVS()), MODE_OFF.
 * All modes are conservative under the cells-and-portals assumption (a room is closed except at
 * its portals, and the near plane does not reach through walls): a prop that covers a pixel is
 * never culled. Fallbacks to frustum-only culling (never to an empty image): eye in no room,
 * a room whose portal names a missing room (leaky), a parallel projection whose near plane
 * touches the building's bounds (warned once; a parallel view from outside the building is
 * traversed like a perspective one, entering through the exterior portals), unusable camera.
 *
 * vtkCuller contract (vtkCompactingCuller): culled props are moved to the end of the
 * list, which is shortened; drawn props keep their order; with @p initialized set their
 * render-time multipliers are kept (multiplied by 1), otherwise set to 1; initialized is set to
 * 1; the returned total is never 0 while props remain. 2D props and props with uninitialized
 * bounds are never culled.
 *
 * Cost per frame: the traversal, a box test per prop of the rooms it reached (a prop in no room
 * or in a room id no room has: a frustum test), and one comparison per prop of the list for the
 * contract's compaction; not a visibility test per prop of a big building.
 *
 * The scene is rebuilt when the renderer's props or the portals change, or after
 * InvalidateScene() (call it after moving actors or changing their data).
 *
 * Statistics of the last Cull(): rooms visited, portals traversed, props and triangles drawn,
 * cull time.
 *
 * @code
 * vtkNew<vtkPortalCuller> culler;
 * culler->SetPortals(portalsPolyData);
 * renderer->AddCuller(culler); // after vtkFrustumCoverageCuller, or replace it
 * @endcode
 *
 * @sa vtkCuller vtkFrustumCoverageCuller vtkOctreeCuller
 */

#ifndef vtkPortalCuller_h
#define vtkPortalCuller_h

#include "SceneVisRenderingPortalsModule.h" // For export macro
#include "vtkCompactingCuller.h" // For the superclass

#include <memory> // For std::unique_ptr
#include <string> // For std::string

class vtkDataArray;
class vtkPolyData;
class vtkProp;

class SCENEVISRENDERINGPORTALS_EXPORT vtkPortalCuller : public vtkCompactingCuller
{
public:
  static vtkPortalCuller* New();
  vtkTypeMacro(vtkPortalCuller, vtkCompactingCuller);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  double Cull(vtkRenderer* ren, vtkProp** propList, int& listLength, int& initialized) override;

  ///@{
  /// The portals: polygons with "RoomA"/"RoomB" integer cell data (see the class comment).
  void SetPortals(vtkPolyData* portals);
  vtkPolyData* GetPortals();
  ///@}

  enum Modes
  {
    MODE_OFF = 0,
    MODE_SCREEN_RECTANGLES,
    MODE_EXACT_FRUSTUM,
    MODE_PVS
  };
  ///@{
  /// How rooms are found visible. Default MODE_EXACT_FRUSTUM.
  vtkSetClampMacro(Mode, int, MODE_OFF, MODE_PVS);
  vtkGetMacro(Mode, int);
  ///@}

  enum OutsidePolicies
  {
    /// Outside all rooms' bounds: enter through exterior portals; in a wall or gap: frustum only.
    OUTSIDE_EXTERIOR_PORTALS = 0,
    /// In no room: frustum only.
    OUTSIDE_FRUSTUM_ONLY
  };
  ///@{
  /// What an eye in no room sees. Default OUTSIDE_EXTERIOR_PORTALS.
  vtkSetClampMacro(OutsidePolicy, int, OUTSIDE_EXTERIOR_PORTALS, OUTSIDE_FRUSTUM_ONLY);
  vtkGetMacro(OutsidePolicy, int);
  ///@}

  ///@{
  /// Name of the field/cell-data array with the room of an actor's cells. Default "RoomId".
  vtkSetStringMacro(RoomIdArrayName);
  vtkGetStringMacro(RoomIdArrayName);
  ///@}

  ///@{
  /// Explicit room of a prop (-1: outside), taking precedence over data arrays.
  /// SetPropCellRooms: the room of each cell of a prop's polydata instead (one value per cell, as
  /// the RoomIdArrayName cell array would give them; e.g. vtkGenerateRooms' output for the
  /// application's own actors), without touching the application's data; null forgets it. A
  /// prop's SetPropRoom wins over its cell rooms. Remove* forget both.
  void SetPropRoom(vtkProp* prop, int room);
  void SetPropCellRooms(vtkProp* prop, vtkDataArray* rooms);
  void RemovePropRoom(vtkProp* prop);
  void RemoveAllPropRooms();
  ///@}

  /// Rebuild the room graph at the next Cull() (after moving props or changing their data).
  void InvalidateScene();

  ///@{
  /// Potentially visible sets. ComputePVS() builds the scene from @p ren's props if needed and
  /// fires vtkCommand::ProgressEvent (call data: double* fraction). Save/Load use a small text
  /// file tied to the graph (a file for another scene is refused with a warning).
  bool ComputePVS(vtkRenderer* ren);
  bool SavePVS(const char* fileName);
  bool LoadPVS(vtkRenderer* ren, const char* fileName);
  ///@}

  enum PVSMethods
  {
    /// Might-see floods, then the clipped portal flow within them, on all cores (scales to
    /// thousands of rooms; see scenevis/PortalPvs.h).
    PVS_PORTAL_FLOW = 0,
    /// The separating-plane walk of every portal sequence (exponential on big levels).
    PVS_SEPARATING_PLANES
  };
  ///@{
  /// How ComputePVS() (and MODE_PVS on first use) computes the sets. Default PVS_PORTAL_FLOW.
  vtkSetClampMacro(PVSMethod, int, PVS_PORTAL_FLOW, PVS_SEPARATING_PLANES);
  vtkGetMacro(PVSMethod, int);
  ///@}

  ///@{
  /// Wall-clock budget of the portal flow in seconds (0, the default: none). Each portal's flow
  /// gets a share of it and then closes: what its open branches might still see is kept whole
  /// (conservative, looser); GetPVSDegradedPortals() says how many closed early.
  vtkSetClampMacro(PVSBudgetSeconds, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(PVSBudgetSeconds, double);
  ///@}

  ///@{
  /// The last computed PVS: milliseconds, mean rooms per set, directed portals whose flow closed
  /// early (budget), and whether the budget ran out.
  vtkGetMacro(PVSComputeTime, double);
  vtkGetMacro(PVSAverageSetSize, double);
  vtkGetMacro(PVSDegradedPortals, vtkIdType);
  vtkGetMacro(PVSBudgetExceeded, bool);
  ///@}

  ///@{
  /// Statistics of the last Cull().
  vtkGetMacro(NumberOfRooms, int);
  vtkGetMacro(NumberOfRoomsVisited, int);
  vtkGetMacro(NumberOfPortalsTraversed, int);
  vtkGetMacro(NumberOfPropsDrawn, int);
  vtkGetMacro(NumberOfPropsCulled, int);
  vtkGetMacro(NumberOfTrianglesDrawn, vtkIdType);
  vtkGetMacro(NumberOfTrianglesTotal, vtkIdType);
  /// Milliseconds spent in the last Cull() (scene rebuilds included).
  vtkGetMacro(LastCullTime, double);
  /// Whether the last Cull() fell back to frustum-only culling (or culled nothing).
  vtkGetMacro(FrustumOnly, bool);
  /// Why: "" (no fallback), "eye in no room", "leaky room", "parallel projection with the near
  /// plane in the building", ...
  const char* GetFallbackReason() const;
  /// Validation issues of the portal graph (one line each), "" when clean.
  const char* GetGraphReport() const;
  ///@}

protected:
  vtkPortalCuller();
  ~vtkPortalCuller() override;

  int Mode = MODE_EXACT_FRUSTUM;
  int PVSMethod = PVS_PORTAL_FLOW;
  double PVSBudgetSeconds = 0.0;
  double PVSComputeTime = 0.0;
  double PVSAverageSetSize = 0.0;
  vtkIdType PVSDegradedPortals = 0;
  bool PVSBudgetExceeded = false;
  int OutsidePolicy = OUTSIDE_EXTERIOR_PORTALS;
  char* RoomIdArrayName = nullptr;

  int NumberOfRooms = 0;
  int NumberOfRoomsVisited = 0;
  int NumberOfPortalsTraversed = 0;
  int NumberOfPropsDrawn = 0;
  int NumberOfPropsCulled = 0;
  vtkIdType NumberOfTrianglesDrawn = 0;
  vtkIdType NumberOfTrianglesTotal = 0;
  double LastCullTime = 0.0;
  bool FrustumOnly = false;

private:
  vtkPortalCuller(const vtkPortalCuller&) = delete;
  void operator=(const vtkPortalCuller&) = delete;

  /// (Re)build props, room geometry and the portal graph if needed; whether culling can run.
  bool EnsureScene(vtkRenderer* ren);
  /// Compute the PVS of the current graph with the PVS settings; progress events if asked.
  bool ComputePVSOfScene(bool progressEvents);

  class vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif
