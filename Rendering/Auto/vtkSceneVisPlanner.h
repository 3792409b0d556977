/**
 * @class   vtkSceneVisPlanner
 * @brief   Gives a renderer only the visibility effects its scene calls for: the culler, the
 *          translucency order and the mappers that pay for themselves, re-planned as the scene
 *          and the view change.
 *
 * One line in an ordinary VTK program:
 * @code
 * vtkSceneVisPlanner::Attach(renderer); // owned by the renderer from now on
 * @endcode
 * or, owning the planner yourself:
 * @code
 * vtkNew<vtkSceneVisPlanner> planner;
 * planner->SetRenderer(renderer); // SetRenderer(nullptr) or the planner's end undoes its work
 * @endcode
 * Either way the planner observes the renderer's StartEvent, which VTK fires at the beginning of
 * every vtkRenderer::Render() before the cullers run, and calls Plan() there. Plan() can also be
 * called directly (then without the observer).
 *
 * What it looks at (the facts, vtkScenePlanFacts): the renderer's visible vtkActors whose mapper
 * is a vtkPolyDataMapper with input: their number (parts), polygons and triangles, the fraction
 * of translucent polygons (property opacity < 1, or the RGBA unsigned-char scalars the mapper
 * colours with directly: cell scalars counted per cell, point scalars by the fraction of
 * translucent points; a lookup table that is not opaque makes all of the actor translucent) and,
 * with vtkScenePlanRule::ManyProps+ actors, how much of the triangles the camera sees and the
 * estimated depth complexity (the in-view actors' screen rectangles over the area they span);
 * the rooms and portals of the portals given with SetPortals(), or of those it generated for
 * actors that look like a building (SetGenerateRooms; by default in the background,
 * SetGenerateRoomsInBackground). Other props (volumes, 2D actors,
 * assemblies) are left alone and not counted. The actors are the application's: with ManyProps+
 * of them the planner always culls (facts.fixedActors, see vtkScenePlanRule).
 *
 * What it decides: vtkScenePlanRule, the same rule as the scenevis command line (--cull auto,
 * --sort auto), so both quote the same facts and reasons. What it installs:
 * - culling "octree" / "occlusion": one vtkOcclusionCuller, with occlusion culling off or on
 *   (switching between the two keeps its hierarchy); it replaces the renderer's
 *   vtkFrustumCoverageCullers, which come back when culling is no longer planned. Other cullers
 *   the application added are left in place.
 * - culling "portals" (portals set, naming rooms): one vtkPortalCuller with those portals and
 *   RoomIdArrayName, in place of the coverage cullers likewise; the actors' rooms are read by it
 *   (field or cell data of that name, see vtkPortalCuller); with generated portals, the rooms
 *   of the actors' cells are given to it (vtkPortalCuller::SetPropCellRooms).
 * - culling "chunked": the opaque actors holding at least ChunkedMinimumTriangles draw through a
 *   vtkChunkedPolyDataMapper (a shallow copy of their mapper: same input and colouring).
 * - culling "none": nothing; the renderer keeps its default culler.
 * - translucency "multi-actor": a vtkOrderedTranslucentPass whose translucent step is a
 *   vtkBSPTranslucentPass (exact order across actors).
 * - translucency "bsp-mapper": the one translucent actor draws through a
 *   vtkBSPSortedPolyDataMapper (a shallow copy of its mapper), under a vtkOrderedTranslucentPass.
 * - translucency "none": no pass of the planner's.
 * A render pass is installed only on a renderer without one (or with the planner's own): a
 * renderer that has its own pass keeps it (a warning says so once). Mappers are swapped only for
 * actors whose mapper is a plain vtkOpenGLPolyDataMapper; when the plan no longer needs a swap,
 * the actor gets its own mapper back, and an application that sets another mapper wins.
 *
 * When: a frame in which nothing changed costs a few comparisons (no prop is visited): the
 * planner observes ModifiedEvent of the actors it counts, their properties, user matrices,
 * mappers and mapper inputs, and compares the prop collection's MTime and the camera's view
 * (position, focal point, view up, angle, projection, viewport size; not the clipping range).
 * - The scene changed (props added, removed, shown, hidden or modified): the facts are read
 *   again, only for the actors whose observed objects changed (or all of them when the prop
 *   collection changed). When the scene's own facts changed (parts, polygons, triangles,
 *   translucency), the plan follows at once: translucency is a matter of correctness, not speed.
 * - Only the view changed, or props only moved, with ManyProps+ actors: the view facts are
 *   measured again, and a different culling plan is adopted only when it is clear of the
 *   thresholds by ViewMargin (the rule gives it for the depth complexity and the fraction of the
 *   triangles out of view both scaled by 1 - ViewMargin and by 1 + ViewMargin) for SwitchFrames
 *   renders in a row (hysteresis: a camera flying into the scene flips once).
 * Data produced upstream of a mapper during a render is seen at the next render.
 *
 * The decision as data: GetCullMethod(), GetTranslucencyMethod(), GetReason() (with the facts
 * line the command line prints), GetFacts(), GetPlanCount() (plans adopted), GetInspectionCount()
 * (scene readings), GetViewMeasurementCount().
 *
 * Bad input: without a renderer Plan() warns and does nothing; a renderer without props gets
 * nothing installed (a warning, once until props appear); actors whose mapper has no input, and
 * actors with NaN bounds (counted in view, covering nothing) are reported by a warning once each.
 *
 * @sa vtkScenePlanRule vtkOctreeCuller vtkOcclusionCuller vtkChunkedPolyDataMapper
 * vtkBSPTranslucentPass vtkBSPSortedPolyDataMapper vtkOrderedTranslucentPass
 */
#ifndef vtkSceneVisPlanner_h
#define vtkSceneVisPlanner_h

#include "SceneVisRenderingAutoModule.h" // For export macro
#include "vtkObject.h"
#include "vtkScenePlanRule.h" // For vtkScenePlanFacts

#include <memory> // For std::unique_ptr

class vtkCuller;
class vtkPolyData;
class vtkRenderer;

class SCENEVISRENDERINGAUTO_EXPORT vtkSceneVisPlanner : public vtkObject
{
public:
  static vtkSceneVisPlanner* New();
  vtkTypeMacro(vtkSceneVisPlanner, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * A planner for @p renderer that the renderer owns (its StartEvent observer keeps it alive):
   * the one line an application adds. Returns it for queries; nullptr (with an error) for a null
   * renderer.
   */
  static vtkSceneVisPlanner* Attach(vtkRenderer* renderer);

  ///@{
  /**
   * The renderer planned for (not reference counted). Setting it observes its StartEvent;
   * setting another one, or nullptr, first undoes everything the planner installed on the
   * previous one (cullers, pass and mappers restored). A planner made by Attach() belongs to its
   * renderer: SetRenderer() on it ends that ownership, so SetRenderer(nullptr) destroys it.
   */
  void SetRenderer(vtkRenderer* renderer);
  vtkRenderer* GetRenderer();
  ///@}

  /// Bring the plan up to date and install it (what the StartEvent observer calls).
  void Plan();

  ///@{
  /**
   * The scene's portals, in vtkPortalCuller's format (one polygon per portal, integer cell
   * arrays RoomA and RoomB), and the name of the actors' room array (default "RoomId"). With
   * portals that name rooms the plan is "portals" (cells and portals). A change (or a new
   * MTime of the portals) is a change of the scene: planned for at the next render.
   */
  void SetPortals(vtkPolyData* portals);
  vtkPolyData* GetPortals();
  void SetRoomIdArrayName(const char* name);
  const char* GetRoomIdArrayName() const;
  ///@}

  ///@{
  /**
   * The plan in force: "none", "octree", "occlusion", "portals" or "chunked"; "none",
   * "multi-actor", "bsp-mapper" or "oit" (the rule's names, as in scenevis --cull / --sort).
   */
  const char* GetCullMethod() const;
  const char* GetTranslucencyMethod() const;
  ///@}

  ///@{
  /**
   * Why, with numbers: the culling reason followed by the facts line in parentheses (as the
   * command line prints it), the translucency reason, and both in one text. They are those of
   * the plan in force, with the facts it was adopted on; GetFacts() has the latest.
   */
  const char* GetCullReason() const;
  const char* GetTranslucencyReason() const;
  const char* GetReason() const;
  ///@}

  /// The facts of the last reading (view facts of the last measurement).
  const vtkScenePlanFacts& GetFacts() const;

  ///@{
  /**
   * Plans adopted (the first one included), readings of the scene, and measurements of the view
   * since the renderer was set.
   */
  vtkGetMacro(PlanCount, int);
  vtkGetMacro(InspectionCount, int);
  vtkGetMacro(ViewMeasurementCount, int);
  ///@}

  /// The culler the planner installed (a vtkOcclusionCuller or vtkPortalCuller), or nullptr.
  vtkCuller* GetCuller() const;

  ///@{
  /// Renders in a row a view-driven change of the culling plan must hold before it is adopted.
  /// Default 5.
  vtkSetClampMacro(SwitchFrames, int, 1, VTK_INT_MAX);
  vtkGetMacro(SwitchFrames, int);
  ///@}

  ///@{
  /// Relative margin by which the view facts must be clear of the rule's thresholds for a
  /// view-driven change. Default 0.2.
  vtkSetClampMacro(ViewMargin, double, 0.0, 0.9);
  vtkGetMacro(ViewMargin, double);
  ///@}

  ///@{
  /// Actors below this many triangles keep their mapper under the "chunked" plan. Default 65536.
  vtkSetClampMacro(ChunkedMinimumTriangles, vtkIdType, 1, VTK_ID_MAX);
  vtkGetMacro(ChunkedMinimumTriangles, vtkIdType);
  ///@}

  /// Milliseconds of the last Plan() call.
  vtkGetMacro(LastPlanTime, double);

  ///@{
  /**
   * Rooms and portals generated for a scene without portals (no SetPortals()), as `scenevis
   * --cull auto` does: when the counted actors (at least 2, at most 10,000 polygons in all) look
   * architectural, rooms and portals are generated once for them in world coordinates
   * (vtkGenerateRooms, stopping at the first leak, at most 3 s of processor time) and used when
   * they are at least 2 rooms and 1 portal with no leak: the plan is then "portals", each actor's
   * cells get their rooms in the portal culler (the application's data is not touched), and the
   * culling reason says what was generated or why not. The rooms hold for the actors as they
   * were: when one moves or changes, they are dropped until the set of actors changes. By
   * default the generation runs in the background and the first renders plan without rooms
   * (SetGenerateRoomsInBackground). Default on. GetNumberOfRoomGenerations() counts the
   * generations run (used or not; one in the background when it has ended).
   */
  void SetGenerateRooms(bool generate);
  vtkGetMacro(GenerateRooms, bool);
  vtkBooleanMacro(GenerateRooms, bool);
  int GetNumberOfRoomGenerations() const;
  ///@}

  ///@{
  /**
   * Generate rooms on a worker thread instead of inside the render that needs them (the demo
   * building's 0.65-0.85 s, up to the budget, would be one frame). The render that would
   * generate copies the actors' polygons into a model of its own (no VTK object shared with the
   * application), starts a worker thread on it (the architectural look's test, then the
   * generation when it passes) and plans as without rooms, its culling reason saying "generating
   * rooms in the background": that frame costs what an ordinary plan costs plus the copy (2-3 ms
   * for the 4,201 polygons of scenevis_planner_path_bench's building-generated, against about
   * 1 s generated in the render). At the first render after the worker has ended, the
   * rooms are used exactly as the synchronous path uses them (and the plan becomes "portals") if
   * the actors are still those they were generated for (same actors, inputs, input MTimes and
   * matrices); otherwise they are discarded and the reason says so. Actors added or removed
   * while it runs: its result is discarded and the new set is generated for when it ends (one
   * worker at a time). A scene that is no building is told so at the render after the test
   * ended, without a change of plan. A generation cannot be interrupted: SetRenderer() and
   * SetGenerateRooms(false) leave it to end and discard it, the planner's end waits for what is
   * left of it (the budget bounds it; it counts the worker thread's processor time, not the
   * renderer's). Default on.
   */
  vtkSetMacro(GenerateRoomsInBackground, bool);
  vtkGetMacro(GenerateRoomsInBackground, bool);
  vtkBooleanMacro(GenerateRoomsInBackground, bool);
  ///@}

  /// Rooms are being generated in the background for the current actors, or have been and will
  /// be adopted (or discarded) by the next Plan().
  bool IsRoomGenerationPending() const;

  /**
   * Blocks until the generation running in the background (if any) has ended, for tests and
   * applications that want the rooms before going on (a still image, a benchmark); the next
   * Plan() (render) adopts them. Returns at once when nothing runs. When the set of actors
   * changed while it ran, that Plan() starts the generation for the new set instead (still
   * pending: wait again). The planner does not render by itself: an application that renders
   * only on demand gets the rooms at its next render.
   */
  void WaitForRoomGeneration();

  ///@{
  /// Processor seconds a generation of rooms may take (0: no limit); past it, no rooms (the plan
  /// says so). Default 3 (vtkAutoRooms::BudgetSeconds, as `--cull auto`).
  vtkSetClampMacro(RoomGenerationBudget, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(RoomGenerationBudget, double);
  ///@}

protected:
  vtkSceneVisPlanner();
  ~vtkSceneVisPlanner() override;

  int PlanCount = 0;
  int InspectionCount = 0;
  int ViewMeasurementCount = 0;
  int SwitchFrames = 5;
  double ViewMargin = 0.2;
  vtkIdType ChunkedMinimumTriangles = 65536;
  double LastPlanTime = 0.0;
  bool GenerateRooms = true;
  bool GenerateRoomsInBackground = true;
  double RoomGenerationBudget; ///< vtkAutoRooms::BudgetSeconds

  /// The renderer's DeleteEvent: forget it without touching it (it is being destroyed).
  void RendererDeleted();

private:
  friend class vtkSceneVisPlannerStart;
  vtkSceneVisPlanner(const vtkSceneVisPlanner&) = delete;
  void operator=(const vtkSceneVisPlanner&) = delete;

  class vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif
