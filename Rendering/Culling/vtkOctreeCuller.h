/**
 * @class   vtkOctreeCuller
 * @brief   Hierarchical view culling of many props: a BVH over the props' bounds.
 *
 * vtkFrustumCoverageCuller (installed in every vtkRenderer) tests every prop's bounding sphere
 * against the frustum every frame, O(props) with a virtual GetBounds() (and a pipeline update)
 * per prop, and sorts with an O(n^2) insertion sort. vtkOctreeCuller keeps a bounding volume
 * hierarchy (BVH; the name follows the issue, the structure is a BVH, see scenevis/Bvh.h for why)
 * over the props' world bounds and culls whole subtrees per test:
 *
 * - frustum culling (default on): exact p-/n-vertex box test with plane masking and temporal
 *   coherence; never culls a prop whose box intersects the frustum;
 * - distance culling (MaximumDistance, off by default): props farther than that from the eye;
 * - small-feature culling (MinimumPixelSize, off by default): APPROXIMATE, culls props whose
 *   bounding sphere projects below that many pixels although they may cover a few pixels;
 * - normal-cone culling (NormalConeCulling, off by default): an actor drawn with back-face
 *   culling (vtkProperty::BackfaceCullingOn, surface representation, no edges, polygons only)
 *   whose triangles all face away from the eye is culled by one conservative cone test. A closed
 *   surface is never culled this way (its normals span all directions): this pays off for
 *   actors that are patches or open surfaces.
 *
 * Use:
 * @code
 * vtkNew<vtkOctreeCuller> culler;
 * renderer->GetCullers()->RemoveAllItems(); // replace vtkFrustumCoverageCuller (recommended)
 * renderer->AddCuller(culler);
 * @endcode
 * It can also run after vtkFrustumCoverageCuller (AddCuller alone): then it receives the props
 * that culler kept, which it maps onto its hierarchy without rebuilding it; but that culler's
 * per-prop cost remains and it culls props with uninitialized bounds itself. After
 * vtkPortalCuller (portals first, then this culler or vtkOcclusionCuller) likewise: the
 * hierarchy is built over the renderer's visible props, so the different subset the portal
 * culler hands over at each frame costs no rebuild; vtkOcclusionCuller neither tests nor draws
 * as occluders the props that culler removed.
 *
 * vtkCuller contract (vtkCompactingCuller): props that are culled are moved to the end of the list
 * (the drawn ones keep their relative order unless SortingStyle says otherwise) and listLength is
 * shortened; when @p initialized is set the drawn props' render-time multipliers are kept
 * (multiplied by 1), otherwise set to 1; initialized is set to 1. Culled props' multipliers are not
 * touched (no other code reads them past listLength). 2D props (GetBounds() == nullptr) and props
 * with uninitialized, empty or NaN bounds are never culled (a warning is given once per culler for
 * the latter). Without a valid camera or viewport nothing is culled (warning once).
 *
 * Updates: the hierarchy is rebuilt only when props appear (or more than half of those it knows
 * are gone from the renderer); a prop whose bounds change is refit in O(log n). How changes are
 * found is the UpdateMode:
 * - UPDATE_ON_EVENTS (default): event-driven dirty tracking; a frame costs O(changed props) plus
 *   the traversal. The culler observes ModifiedEvent (and DeleteEvent) on, per prop: the prop;
 *   for a plain vtkActor (class vtkActor / vtkOpenGLActor) also its user matrix, its property
 *   (only with NormalConeCulling), its mapper (a vtkPolyDataMapper), the mapper's input
 *   vtkPolyData, that polydata's vtkPoints and their data array, and every algorithm upstream of
 *   the mapper (up to 64). An object shared by many props is observed once. A fired event marks
 *   the dependent props; at the next Cull() only those re-read their bounds (and dependencies).
 *   Detected therefore: SetPosition / SetOrientation / RotateX.. / SetScale / SetOrigin /
 *   SetUserMatrix / SetMapper, user-matrix SetElement / DeepCopy / Modified(), SetInputData /
 *   SetInputConnection, a new output of the pipeline, point edits followed by Modified() on the
 *   points, their array or the polydata, parameter changes of any upstream algorithm (also of
 *   culled props, whose pipeline has not executed). Polled every frame instead (GetBounds() as in
 *   UPDATE_BOUNDS_EVERY_FRAME, O(such props)): props that are not plain vtkActors (vtkFollower,
 *   vtkLODActor, vtkAssembly, volumes, ...), actors with a user transform other than the one
 *   SetUserMatrix() makes (its inputs and concatenations change it silently), mappers that are
 *   not vtkPolyDataMappers or whose input is not a vtkPolyData, and pipelines of more than 64
 *   algorithms. NOT detected: writing memory directly (e.g. through GetPointer() or
 *   vtkMatrix4x4::Element) without calling Modified(), changes to cell connectivity alone (no
 *   Modified() on the polydata), and time-dependent pipeline output without a Modified() (call
 *   InvalidateProp() for those). Props that leave the
 *   renderer stop being observed at the next Cull() whose list changed; props that another
 *   culler removed from the list stay observed (their events are kept until they are back);
 *   all observers go with the culler or when the mode is changed.
 * - UPDATE_BOUNDS_EVERY_FRAME: GetBounds() of every prop every frame, like
 *   vtkFrustumCoverageCuller (same pipeline updates); always correct.
 * - UPDATE_ON_MODIFIED: GetBounds() only for props whose MTime, mapper MTime or mapper input
 *   MTime changed since the last frame (moves through SetPosition/SetUserMatrix/..., new input
 *   data, SetInputData with modified points). Not seen: changes upstream of the mapper's input
 *   that have not executed yet for a culled prop; call InvalidateProp() for those.
 * - UPDATE_MANUAL: no per-prop checks at all (static scenes, fastest); call InvalidateProp() or
 *   InvalidateAllProps() after moving props.
 *
 * SortingStyle as in vtkFrustumCoverageCuller (VTK_CULLER_SORT_*): front-to-back by the depth of
 * the bounds' centre, for early depth rejection of opaque geometry (translucent props are drawn
 * in their own pass; their relative order matters only with plain alpha blending, where
 * BACK_TO_FRONT is the right choice). 2D props stay first in their original order. The visible
 * placements of a vtkInstancedActor are handed to it in the same depth order, which it draws them
 * in.
 *
 * Statistics of the last Cull(): nodes visited, props tested / culled (by reason) / drawn,
 * triangles drawn (polygons of the props' polydata). After another culler, vtkOctreeCuller's
 * props culled by each reason (whole subtrees) and props tested count the hierarchy's props,
 * those that culler removed included; vtkOcclusionCuller's count only this list's (its traversal
 * leaves the others out). Drawn and triangles drawn count this list's.
 *
 * vtkInstancedActor: each placement is a prop of its own in the hierarchy (its box: the mesh's
 * box corners through the placement's model matrix), culled by frustum, distance, size and, in
 * vtkOcclusionCuller, occlusion (a visible placement occludes with its own matrix); normal-cone
 * culling does not apply to placements. The actor stays in the list while any placement is
 * kept and is told which ones to draw (vtkInstancedActor::SetVisiblePlacements); when its
 * number of placements changes the hierarchy is rebuilt. The hierarchy's statistics (tested,
 * culled by reason, triangles drawn) count placements; NumberOfPropsDrawn / NumberOfPropsCulled
 * count the entries of the prop list.
 *
 * @sa vtkCuller vtkFrustumCoverageCuller vtkRenderer::AddCuller
 */

#ifndef vtkOctreeCuller_h
#define vtkOctreeCuller_h

#include "SceneVisRenderingCullingModule.h" // For export macro
#include "vtkCompactingCuller.h"

#include <cstddef> // For std::size_t
#include <memory>  // For std::unique_ptr
#include <string>  // For std::string

class vtkProp;

class SCENEVISRENDERINGCULLING_EXPORT vtkOctreeCuller : public vtkCompactingCuller
{
public:
  static vtkOctreeCuller* New();
  vtkTypeMacro(vtkOctreeCuller, vtkCompactingCuller);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  double Cull(vtkRenderer* ren, vtkProp** propList, int& listLength, int& initialized) override;

  ///@{
  /// Frustum culling (exact, conservative). Default on.
  vtkSetMacro(FrustumCulling, bool);
  vtkGetMacro(FrustumCulling, bool);
  vtkBooleanMacro(FrustumCulling, bool);
  ///@}

  ///@{
  /// APPROXIMATE small-feature culling: props whose bounding sphere projects to a diameter below
  /// this many pixels are culled. 0 (default) = off.
  vtkSetClampMacro(MinimumPixelSize, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MinimumPixelSize, double);
  ///@}

  ///@{
  /// Distance culling: props whose bounds are farther than this from the camera position are
  /// culled. VTK_DOUBLE_MAX (default) = off.
  vtkSetClampMacro(MaximumDistance, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MaximumDistance, double);
  ///@}

  ///@{
  /// Clustered back-face culling of actors drawn with back-face culling. Default off.
  vtkSetMacro(NormalConeCulling, bool);
  vtkGetMacro(NormalConeCulling, bool);
  vtkBooleanMacro(NormalConeCulling, bool);
  ///@}

  ///@{
  /// VTK_CULLER_SORT_NONE (default), VTK_CULLER_SORT_FRONT_TO_BACK or _BACK_TO_FRONT.
  vtkSetClampMacro(SortingStyle, int, 0, 2);
  vtkGetMacro(SortingStyle, int);
  ///@}

  enum UpdateModes
  {
    UPDATE_BOUNDS_EVERY_FRAME = 0,
    UPDATE_ON_MODIFIED,
    UPDATE_MANUAL,
    UPDATE_ON_EVENTS
  };
  ///@{
  /// How moved props are found (see the class documentation).
  vtkSetClampMacro(UpdateMode, int, UPDATE_BOUNDS_EVERY_FRAME, UPDATE_ON_EVENTS);
  vtkGetMacro(UpdateMode, int);
  ///@}

  /// Re-read the bounds of @p prop at the next Cull().
  void InvalidateProp(vtkProp* prop);
  /// Rebuild the hierarchy at the next Cull().
  void InvalidateAllProps();

  ///@{
  /// Statistics of the last Cull().
  vtkGetMacro(NumberOfNodesVisited, vtkIdType);
  vtkGetMacro(NumberOfPropsTested, vtkIdType);
  vtkGetMacro(NumberOfPropsCulled, vtkIdType);
  vtkGetMacro(NumberOfPropsCulledByFrustum, vtkIdType);
  vtkGetMacro(NumberOfPropsCulledBySize, vtkIdType);
  vtkGetMacro(NumberOfPropsCulledByDistance, vtkIdType);
  vtkGetMacro(NumberOfPropsCulledByNormalCone, vtkIdType);
  vtkGetMacro(NumberOfPropsDrawn, vtkIdType);
  /// Triangles of the props kept, as OpenGL draws them (n - 2 per polygon or strip of n points).
  vtkGetMacro(NumberOfTrianglesDrawn, vtkIdType);
  /// Hierarchy rebuilds and prop refits since construction.
  vtkGetMacro(NumberOfRebuilds, vtkIdType);
  vtkGetMacro(NumberOfRefits, vtkIdType);
  /// UPDATE_ON_EVENTS: objects observed now, and props polled every frame (see above).
  vtkIdType GetNumberOfObservedObjects() const;
  vtkIdType GetNumberOfPolledProps() const;
  /// Whether the last Cull() culled nothing because camera or viewport were unusable.
  vtkGetMacro(CullingSkipped, bool);
  ///@}

protected:
  vtkOctreeCuller();
  ~vtkOctreeCuller() override;

  bool FrustumCulling = true;
  double MinimumPixelSize = 0.0;
  double MaximumDistance = VTK_DOUBLE_MAX;
  bool NormalConeCulling = false;
  int SortingStyle = 0;
  int UpdateMode = UPDATE_ON_EVENTS;

  vtkIdType NumberOfNodesVisited = 0;
  vtkIdType NumberOfPropsTested = 0;
  vtkIdType NumberOfPropsCulled = 0;
  vtkIdType NumberOfPropsCulledByFrustum = 0;
  vtkIdType NumberOfPropsCulledBySize = 0;
  vtkIdType NumberOfPropsCulledByDistance = 0;
  vtkIdType NumberOfPropsCulledByNormalCone = 0;
  vtkIdType NumberOfPropsDrawn = 0;
  vtkIdType NumberOfTrianglesDrawn = 0;
  vtkIdType NumberOfRebuilds = 0;
  vtkIdType NumberOfRefits = 0;
  bool CullingSkipped = false;

  ///@{
  /// Occlusion culling, turned on by the subclass vtkOcclusionCuller (see there): the hierarchy
  /// is traversed front to back, props found visible are rasterized as occluders into a
  /// software depth buffer, and nodes hidden behind them are culled with their subtrees.
  bool OcclusionCulling = false;
  std::size_t OccluderCacheBudget = std::size_t(256) << 20;
  double OccluderMinimumPixelsPerTriangle = 1.0;
  std::string OcclusionRecordFile; ///< see vtkOcclusionCuller::SetOcclusionRecordFile()
  vtkIdType NumberOfOccludersSkipped = 0;
  vtkIdType NumberOfPropsCulledByOcclusion = 0;
  vtkIdType NumberOfOcclusionTests = 0;
  vtkIdType NumberOfOccludersDrawn = 0;
  vtkIdType NumberOfOccluderTriangles = 0;
  double OccluderRasterTime = 0.0; ///< ms this frame rasterizing occluders
  double CullTime = 0.0;           ///< ms of the whole Cull()
  std::size_t DepthBufferBytes = 0;
  std::size_t OccluderCacheBytes = 0;
  ///@}

private:
  vtkOctreeCuller(const vtkOctreeCuller&) = delete;
  void operator=(const vtkOctreeCuller&) = delete;

  class vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif
