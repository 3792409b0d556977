/**
 * @class   vtkScenePlanRule
 * @brief   The rule "only the effects a scene calls for": from the facts of a scene (parts,
 *          triangles, translucency, rooms and portals, what the camera sees) to the culling and
 *          translucency methods that pay for themselves, each with its reason.
 *
 * One rule for every user: vtkSceneVisPlanner applies it to a renderer's props every frame, and
 * the scenevis command line (--cull auto, --sort auto) to the scenes it loads, so both decide
 * alike and quote the same facts. The rule is a pure function of the facts (no VTK objects), so
 * the planner can evaluate it on nudged facts for hysteresis and tests can call it directly.
 *
 * Culling methods (ChooseCulling):
 * - "portals": rooms and portals exist (cells and portals);
 * - "occlusion": ManyProps+ parts, an estimated opaque depth complexity of
 *   OcclusionDepthComplexity or more, and either fixed actors (facts.fixedActors) or at most
 *   MaxTranslucentForActors translucent and less than MinInViewForNoCulling of the triangles in
 *   view (vtkOcclusionCuller);
 * - "octree": the same with a lower depth complexity (vtkOcclusionCuller without occlusion);
 * - "chunked-occlusion" / "none" for ManyProps+ small opaque parts that may be drawn as one mesh
 *   (not fixed actors; fewer than SmallPartTriangles triangles per part on average, as the
 *   surfaces of a game level): one mesh in chunks of SmallPartChunkSize triangles, with occlusion
 *   between the chunks from ChunkOcclusionTriangles triangles on (when the estimated opaque depth
 *   complexity reaches OcclusionDepthComplexity; "chunked" below it), else "none";
 * - "chunked": HugeMesh+ opaque triangles otherwise (vtkChunkedPolyDataMapper);
 * - "none": small scenes, and scenes whose parts may be drawn as one mesh instead (not fixed
 *   actors) that are in full view or translucent.
 *
 * Translucency methods (ChooseTranslucency): "none" (opaque), "oit" (translucent but chunked:
 * only an order-independent method survives the chunks' reordering), "multi-actor" (translucent
 * polygons in several actors: vtkBSPTranslucentPass; also one mesh of parts that may be split
 * whose translucent parts' boxes overlap little: see SplitsIntoParts()), "bsp-mapper" (one
 * translucent mesh: vtkBSPSortedPolyDataMapper).
 *
 * The thresholds and why they are what they are: see the constants below.
 *
 * @sa vtkSceneVisPlanner
 */
#ifndef vtkScenePlanRule_h
#define vtkScenePlanRule_h

#include "SceneVisRenderingAutoModule.h" // For export macro
#include "vtkType.h"                     // For vtkIdType

#include <cstddef> // For std::size_t
#include <string>  // For std::string
#include <vector>  // For std::vector

class vtkCamera;

/// What the rule decides on, and what reports quote as the reason. Plain data.
struct SCENEVISRENDERINGAUTO_EXPORT vtkScenePlanFacts
{
  vtkIdType polygons = 0;
  vtkIdType triangles = 0;
  std::size_t parts = 1;            ///< actors (planner) / distinct PartId values (command line)
  double translucentFraction = 0.0; ///< of the polygons: opacity < 1 or RGBA alpha < 255
  int rooms = 0;                    ///< distinct RoomId values >= 0
  vtkIdType portals = 0;
  /// Fraction of the triangles in parts whose bounds meet the camera's view (the side planes of
  /// its frustum); < 0 when not measured.
  double inView = -1.0;
  /// Sum of the screen rectangles of the parts in view over the area they cover: the rectangle
  /// bounding them, clipped to the viewport (a box reaching the eye's plane covers the whole
  /// viewport): how many parts a covered pixel lies in, on average; < 0 when not measured.
  double depthComplexity = -1.0;
  /// The parts are actors the application draws as they are (vtkSceneVisPlanner, instances of
  /// the command line): drawing them as one mesh instead is not an option, so with ManyProps+
  /// of them the choice is which culler, never whether (see ChooseCulling()).
  bool fixedActors = false;
  /// Parts with translucent polygons, and the fraction of all the triangles that lie in
  /// translucent parts whose bounding box overlaps another translucent part's box
  /// (MeasureOverlap()); < 0 when not measured.
  std::size_t translucentParts = 0;
  double translucentOverlap = -1.0;

  /// The facts in one line, as the reports quote them.
  std::string Summary() const;
};

/// A method chosen by the rule and why (the reason without the facts line).
struct SCENEVISRENDERINGAUTO_EXPORT vtkScenePlanChoice
{
  std::string Method;
  std::string Reason;
  /// "chunked" / "chunked-occlusion": the triangles per chunk the rule chose (0: the mapper's
  /// default).
  int ChunkSize = 0;
};

/// A part's world box and triangles: what the view estimate (MeasureView) looks at.
struct SCENEVISRENDERINGAUTO_EXPORT vtkScenePlanPartBox
{
  double Box[6] = { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX,
    VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
  vtkIdType Triangles = 0;
  bool Translucent = false; ///< has translucent polygons (what MeasureOverlap looks at)
};

class SCENEVISRENDERINGAUTO_EXPORT vtkScenePlanRule
{
public:
  /// From this many parts, culling whole props pays for its hierarchy (-> octree).
  static constexpr std::size_t ManyProps = 100;
  /// From this many triangles in one opaque mesh, culling chunks inside it pays (-> chunked):
  /// the 64 spheres at 1M triangles seen from inside the grid draw 10x faster chunked (19k of 1M
  /// triangles drawn), and a full view costs about the same either way.
  static constexpr vtkIdType HugeMesh = 500000;
  /// Prop culling draws one actor per part, which translucency then orders across actors
  /// (vtkBSPTranslucentPass); above this fraction of translucent polygons that sort interleaves
  /// the parts' fragments into thousands of draw calls (2CylinderEngine at opacity 0.4: 32k draw
  /// calls, 4.3 s a frame), so one mesh in BSP order is kept instead.
  static constexpr double MaxTranslucentForActors = 0.25;
  /// Prop culling costs VTK per-actor work every frame; when the camera sees at least this
  /// fraction of the triangles, culling cannot pay for that (the cad demo in full view: 1.2-1.5x
  /// slower than one mesh; seen from close up: 1.4-1.7x faster).
  static constexpr double MinInViewForNoCulling = 0.9;
  // With fixed actors (vtkSceneVisPlanner) there is no one mesh to fall back on, and culling
  // pays at any fraction in view: the planner's "none" keeps VTK's vtkFrustumCoverageCuller,
  // which costs more per frame than vtkOcclusionCuller's hierarchy (scenevis_planner_path_bench,
  // 40 frames from an overview into the scene: a real level of 4,239 actors 1.19x, the cad demo
  // 1.13x, the 2CylinderEngine 1.04x slower with VTK's culler than with the octree).
  /// Estimated opaque depth complexity (facts.depthComplexity times the opaque fraction of the
  /// polygons: translucent parts hide nothing) from which occlusion culling is preferred to
  /// frustum culling alone: most of what is in view is then hidden behind nearer parts (the
  /// 2CylinderEngine grid 4 x 4 seen down a row: 86 parts drawn per part seen with frustum
  /// culling, 2 with occlusion; BENCHMARKS.md). The value 4 is a first estimate, not yet
  /// calibrated over many scenes.
  static constexpr double OcclusionDepthComplexity = 4.0;
  /**
   * Below this many triangles per part on average, ManyProps+ opaque parts that may be merged are
   * drawn as one mesh rather than one actor each: an actor costs VTK about 37 us per frame
   * (llvmpipe; 1,319 actors of a level seen from far away: 49 ms against 2.6 ms as one mesh),
   * more than its few triangles. Measured on 12 real game levels (3.9-11.3 triangles per
   * surface, 8 cameras each; BENCHMARKS.md "Game levels drawn as one mesh"): drawing the level
   * as one mesh ("none") was faster than the octree on every level (median ratio 2.03) and than
   * occlusion culling of the actors on 10 of 12.
   */
  static constexpr double SmallPartTriangles = 16.0;
  /// From this many triangles, such a merged mesh is drawn in chunks with occlusion between them
  /// ("chunked-occlusion"); below it, whole ("none"). The same levels: chunked-occlusion beat
  /// "none" on each of the 4 levels of 16k-29k triangles (octree / this 2.82 vs 2.61, 2.59 vs
  /// 2.05, 4.11 vs 2.95, 1.81 vs 1.60), and lost or tied on each of the 8 of 2k-8k.
  static constexpr vtkIdType ChunkOcclusionTriangles = 10000;
  /// Triangles per chunk for the merged mesh of small parts: a level's 16k-29k triangles in a
  /// few hundred chunks (64 and 256 measured alike; the mapper's 2,048 leaves 2-14 chunks,
  /// too few to cull).
  static constexpr int SmallPartChunkSize = 64;

  /**
   * Below this fraction of the triangles in translucent parts whose boxes overlap another
   * translucent part's box (facts.translucentOverlap), a translucent mesh of MinPartsToSplit+
   * parts that may be split is drawn as one actor per part with vtkBSPTranslucentPass rather
   * than as one mesh with the BSP mapper. The mapper orders every polygon of the mesh in one
   * tree, split by every other part's planes; the pass draws opaque parts as they are, orders
   * translucent parts as wholes and merges into one tree only parts that no plane separates,
   * whose fragments then interleave into many draw calls. Measured (BENCHMARKS.md, "Auto
   * splits a translucent mesh whose translucent parts overlap little"; frame times interleaved,
   * median of 7 rounds of multi-actor / bsp-mapper): the cad demo at 1.1 % 0.80; the cad demo
   * made all translucent at 36 % 0.94 (a tie); the 2CylinderEngine at opacity 0.4 at 100 % 1.30
   * (0.68-3.15). No scene measured between 36 and 100 %: the threshold lies above the tie, short
   * of where the engine loses. Not told apart: the 64 interpenetrating spheres, also 100 %, draw
   * 0.83 split.
   */
  static constexpr double MaxOverlapToSplit = 0.5;
  /// Translucent parts from which splitting a mesh into its parts is considered (one part has
  /// nothing to order across).
  static constexpr std::size_t MinPartsToSplit = 2;
  /// Parts up to which a mesh is split: the multi-actor pass's frame grows faster with the
  /// actors than the mapper's with the triangles. The cad demo at 52 triangles a part, multi-actor
  /// / bsp-mapper in interleaved rounds: 1,000 parts 0.41-0.64, 1,500 parts 0.89-0.96, 2,500
  /// parts 1.55-3.98, 5,000 parts 1.67-3.10 (and at 400 triangles a part 1.27-2.70).
  static constexpr std::size_t MaxPartsToSplit = 1500;

  /// The culling method for @p facts and why.
  static vtkScenePlanChoice ChooseCulling(const vtkScenePlanFacts& facts);

  /**
   * Whether a translucent scene given as one mesh of parts is better drawn as one actor per
   * part (multi-actor) than as one mesh (bsp-mapper): parts that may be split (not
   * facts.fixedActors), no more than MaxPartsToSplit of them, at least MinPartsToSplit
   * translucent ones, of SmallPartTriangles or
   * more triangles on average (an actor costs more than a few triangles: two game levels at
   * opacity 0.4, 3-4 triangles a surface, draw 2-9x slower split although their translucent
   * parts overlap as little as the cad demo's made all translucent), whose boxes overlap little
   * (facts.translucentOverlap measured and below MaxOverlapToSplit).
   */
  static bool SplitsIntoParts(const vtkScenePlanFacts& facts);

  /**
   * The translucency method given the culling: prop culling (or a scene of several translucent
   * actors) needs an order across actors; chunked drawing reorders the polygons chunk by chunk,
   * which only order-independent methods survive. @p severalActors: the translucent polygons
   * are drawn by more than one actor (@p actors of them). A single mesh whose parts
   * SplitsIntoParts() is split and drawn with multi-actor too: the caller then draws one actor
   * per part.
   */
  static vtkScenePlanChoice ChooseTranslucency(
    const vtkScenePlanFacts& facts, bool chunked, bool severalActors, std::size_t actors);

  /**
   * The fraction of the triangles of @p parts that lie in translucent parts (Translucent set,
   * finite box) whose box overlaps another translucent part's box: their intersection has
   * positive extent along every axis beyond a tolerance of 1e-6 of the two boxes' extents
   * (touching parts, a bolt on a plate, do not overlap: a plane separates them; a flat part
   * through a box does). 0 with fewer than two such parts. Weighted by triangles over the whole
   * mesh because that is the share of the one-mesh sort's work that the multi-actor pass may
   * have to do in merged trees. A sweep over the translucent boxes sorted along the axis where
   * they are most spread out (the smallest sum of extents over the span): O(n log n) plus the
   * pairs that overlap along that axis, stopped after OverlapTestsPerPart tests per box on
   * average; the share is then that of the boxes swept so far.
   */
  static double MeasureOverlap(const std::vector<vtkScenePlanPartBox>& parts);
  /// The early stop of MeasureOverlap(): box pair tests per translucent box.
  static constexpr std::size_t OverlapTestsPerPart = 16;

  /**
   * The fraction of the triangles of @p parts whose bounding box meets the side planes of
   * @p camera's frustum (near and far ignored: the clipping range follows the props), and in
   * @p depthComplexity (if not null) the in-view parts' screen rectangles summed over the area
   * of the rectangle bounding them (clipped to the viewport; 0 when nothing is in view).
   * Boxes with NaN or uninitialized coordinates count as in view and cover nothing.
   */
  static double MeasureView(const std::vector<vtkScenePlanPartBox>& parts, vtkCamera* camera,
    double aspect, double* depthComplexity = nullptr);
};

#endif
