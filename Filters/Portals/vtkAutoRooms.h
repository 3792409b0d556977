/**
 * @file    vtkAutoRooms.h
 * @brief   Rooms and portals generated for a scene that has none, when it looks architectural:
 *          the decision `scenevis --cull auto` and vtkSceneVisPlanner share.
 *
 * Generation (vtkGenerateRooms) is not linear and most scenes are not buildings, so it is tried
 * only on a scene that passes a cheap test (vtkArchitecturalLook: few enough polygons, most of
 * their area in axis planes, and most of that area facing a polygon turned back towards it
 * across open space, as floors face ceilings and walls face walls, along every axis), under a
 * processor-time
 * budget and stopping at the first leak; the result is used only with at least 2 rooms, 1 portal
 * and no leak. Every outcome comes with the sentence a culling reason quotes.
 *
 * Plain values and functions (not wrapped for Python): vtkGenerateRooms is the filter users call.
 */
#ifndef vtkAutoRooms_h
#define vtkAutoRooms_h

#include "SceneVisFiltersPortalsModule.h" // For export macro

#include <vtkIntArray.h>     // For vtkSmartPointer<vtkIntArray>
#include <vtkPolyData.h>     // For vtkSmartPointer<vtkPolyData>
#include <vtkSmartPointer.h> // For vtkSmartPointer

#include <cstddef> // For std::size_t
#include <string>  // For std::string

/// What the cheap test found, and why.
struct SCENEVISFILTERSPORTALS_EXPORT vtkArchitecturalLook
{
  bool LooksArchitectural = false;
  std::size_t Polygons = 0;
  /// Share of the polygon area lying in axis planes of the best axis: facing along it (floors,
  /// ceilings) or perpendicular to it (walls). 1.0 for the demo building and Freedoom MAP01, 0.95
  /// for the ctf_gate1 level, but also 0.96 for the cad demo (boxes); 0.04 for the bunny.
  double AlignedArea = 0.0;
  /// Of the area facing along an axis, the share facing a polygon turned towards it further
  /// along (a floor under a ceiling, walls across a room).
  double EnclosedArea = 0.0;
  /// The same share per axis, the least of the axes facing at least a tenth of that area: rooms
  /// are closed along every axis (floors under ceilings as well as walls across from walls),
  /// while boxes standing side by side face one another only sideways.
  double LeastEnclosedAxis = 0.0;
  double Milliseconds = 0.0;
  std::string Reason; ///< the numbers, and which limit failed

  /// Limits of the test. Measured: aligned area the demo building 0.74, MAP01 0.98, ctf_gate1
  /// 0.72; enclosed area the cad demo 0.01-0.02 (a box's face looks at the next part only where
  /// one happens to stand), spheres and the bunny 0.
  static constexpr double MinimumAlignedArea = 0.7;
  static constexpr double MinimumEnclosedArea = 0.5;
  /// Measured least enclosed axis: the demo building 0.73 (y), the Python example's row of rooms
  /// 1.0, Freedoom MAP01 0.92, the OpenArena levels of at most 10,000 polygons 0.23-0.94; a
  /// 24 x 24 grid of boxes on a plane 0 (z: nothing above their tops), which otherwise passes
  /// (0.64 enclosed) and whose gaps generate 1,104 narrow "rooms" in 2.2 s. A lattice of boxes in
  /// all three axes still passes: its gaps are rooms and portals of a kind.
  static constexpr double MinimumLeastEnclosedAxis = 0.2;
  /// Generation is not linear: the demo building's 3,484 polygons take 1.0 s, MAP01's 6,857
  /// 2.3 s, the oa_koth2 level's 7,668 11 s (it leaks: not used), the 200-part cad demo's 9,776
  /// 8.5 s, MAP12's 67,170 25 s. Above this many polygons it is not tried (generate once with
  /// vtkGenerateRooms or `scenevis portals`, then give the portals).
  static constexpr std::size_t MaximumPolygons = 10000;

  /// The test, linear in the polygons and strips of @p model (0.2-10 ms on the scenes above).
  static vtkArchitecturalLook Of(vtkPolyData* model);
};

/// Rooms and portals for a scene without them, and whether to use them.
struct SCENEVISFILTERSPORTALS_EXPORT vtkAutoRooms
{
  /// At least 2 rooms, 1 portal and no leak: Rooms and Portals are set.
  bool Used = false;
  /// Generation was tried (the scene looked architectural).
  bool Tried = false;
  /// The room of every cell of the model (an int array named as asked), and the portals
  /// (RoomA, RoomB): null unless Used.
  vtkSmartPointer<vtkIntArray> Rooms;
  vtkSmartPointer<vtkPolyData> Portals;
  int RoomCount = 0;
  std::size_t PortalCount = 0;
  std::size_t ExteriorPortals = 0;
  std::size_t LeakCells = 0;
  double Milliseconds = 0.0; ///< the test and the generation
  /// When Used: "generated R rooms, P portals (E to the outside, 0 leak cells) in T ms because
  /// <the test's numbers>"; otherwise what was found and why it is not used, starting with
  /// "rooms and portals not generated: " or "generating rooms and portals failed" or "rooms and
  /// portals generated".
  std::string Reason;

  /// Processor seconds generation may take here (vtkGenerateRooms::BudgetSeconds): what a scene
  /// that looks architectural but leaks (every real level tried) costs before its first frame on
  /// a quiet machine. Three times the building's 1.0 s; processor time, so the building is not
  /// stopped on a loaded machine (at load 5-9 its wall time reached 3.1 s).
  static constexpr double BudgetSeconds = 3.0;

  /// The test, then generation when it passes (see the file comment), stopping after
  /// @p budgetSeconds of processor time (0: no limit).
  static vtkAutoRooms Generate(
    vtkPolyData* model, const char* roomArrayName = "RoomId", double budgetSeconds = BudgetSeconds);
};

#endif
