/**
 * @class   vtkBSPTranslucentPass
 * @brief   Translucent pass that draws the polygons of ALL translucent actors in one exact
 *          back-to-front order, each actor with its own property.
 *
 * VTK can depth-sort one merged mesh, but translucent actors with different colours, opacities or
 * lookup tables are drawn one after the other, so where they interpenetrate or interleave in depth
 * the blending is wrong. This pass
 *
 * 1. collects the translucent actors of the renderer that can be sorted (vtkActor, polydata
 *    mapper, surface representation without edges, visible, currently translucent); a composite
 *    input with one visible non-empty polydata block and no per-block colours, opacities or
 *    materials counts as that polydata (how ParaView's representations draw a surface);
 * 2. orders their polygons (each fragment remembers its actor) in two levels (the default,
 *    scenevis/PartTree.h): actors that a plane separates from the others are ordered as wholes,
 *    each by a BSP of its own input in the input's coordinates (built once per input and shared
 *    by the actors that draw it), and only actors that no plane separates share one BSP over
 *    their polygons, so an actor's polygons are split only by the actors it cannot be separated
 *    from; fragments of an actor split by another actor's plane get interpolated attributes.
 *    SetTwoLevelOrder(false): ONE BSP over every polygon in world coordinates;
 * 3. gives every actor (or every batch of actors, see below) a helper vtkBSPSortedPolyDataMapper
 *    whose vertex buffers hold its fragments (built once per tree) and whose index buffer holds
 *    them in the global order;
 * 4. draws the global order as runs: each run is one draw call over a range of an index buffer.
 *
 * Batching. Most actors of a scene differ only in colour and opacity, and drawing every actor
 * with its own property would cost one draw call per change of actor along the order (81.6k
 * draw calls for 64 interleaved spheres). So translucent actors whose properties are equal
 * except for colour and opacity ("compatible": same lighting on/off, interpolation, ambient,
 * diffuse and specular coefficients, specular colour and power, face culling; no texture, no
 * backface property, no PBR, no shader code or replacements, no clipping planes, no cell
 * scalars that differ between cells (one colour in every cell, as model readers and part
 * splitting give a part, is baked like a point colour), no scalar interpolation before mapping,
 * and either point normals on all or on none)
 * form a BATCH GROUP: their polygons are copied into one world-space polydata whose per-point
 * RGBA colours are baked from each actor's own colouring (vtkMapper::MapScalars with the
 * actor's opacity, or the property colour and opacity when it shows no scalars), and one
 * shared helper mapper draws them. A run is then a maximal sequence of consecutive fragments of
 * one group. The image is the same as with per-actor drawing up to 8-bit colour rounding
 * (tested: <= 0.02/255 mean): VTK 9.1 applies point colours to both the ambient and the diffuse
 * term and multiplies the opacity, which is what the baked colours reproduce (an actor without
 * scalars is only compatible if its ambient colour equals its diffuse colour or its ambient
 * coefficient is 0). Incompatible actors, and compatible actors that have no partner, are drawn
 * with their own property, texture, matrix, scalars and lookup table (a helper
 * vtkBSPSortedPolyDataMapper each), as before. A batch costs a copy of its actors' points,
 * normals and colours (world coordinates) next to their own buffers.
 *
 * Work per frame:
 * - the set of sorted actors, an actor's matrix, an actor's input or mapper changed: the order
 *   is rebuilt (GetNumberOfTreeBuilds(), GetLastBuildTime()); with two levels only the top level
 *   and the BSP trees of what changed: a changed input's tree and the shared tree of the actors
 *   a moved actor cannot be separated from (GetLastBuildTreeCount()); trees of unchanged inputs
 *   are kept, at the cost of a copy of each input's polygons in double precision;
 * - the colour, opacity or lookup table of a batched actor changed: the colours of its group are
 *   baked again and the group's vertex buffers rebuilt; no tree rebuild
 *   (GetNumberOfColorBakes());
 * - only the camera moved: the order is updated incrementally; index buffers are re-uploaded only
 *   for actors whose part of the order changed;
 * - nothing changed: no sorting and no uploads, only the draw calls;
 * - no sortable translucent actors: nothing beyond the plain translucent pass (the tree is freed).
 *
 * An actor whose opacity becomes 1 is no longer translucent and drops out of the tree (it is then
 * drawn by the opaque pass). Other translucent props (other mappers, wireframe, edges) are drawn
 * first, unsorted, like vtkTranslucentPass does.
 *
 * Use it as the translucent step of a vtkRenderStepsPass (plain alpha blending):
 * @code
 * vtkNew<vtkOrderedTranslucentPass> steps;   // or vtkRenderStepsPass
 * vtkNew<vtkBSPTranslucentPass> sorted;
 * steps->SetTranslucentPass(sorted);
 * renderer->SetPass(steps);
 * @endcode
 *
 * Limits: verts and lines of sorted actors are not drawn; hardware selection falls back to the
 * plain translucent pass.
 *
 * @sa vtkBSPSortedPolyDataMapper vtkOrderedTranslucentPass vtkTranslucentPass
 */

#ifndef vtkBSPTranslucentPass_h
#define vtkBSPTranslucentPass_h

#include "SceneVisRenderingTranslucencyModule.h" // For export macro
#include "vtkDefaultPass.h"

#include <memory> // For std::unique_ptr

class vtkActor;
class vtkPolyData;

class SCENEVISRENDERINGTRANSLUCENCY_EXPORT vtkBSPTranslucentPass : public vtkDefaultPass
{
public:
  static vtkBSPTranslucentPass* New();
  vtkTypeMacro(vtkBSPTranslucentPass, vtkDefaultPass);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void Render(const vtkRenderState* s) override;
  void ReleaseGraphicsResources(vtkWindow* w) override;

  ///@{
  /**
   * State and counters (last frame / since construction).
   */
  int GetNumberOfSortedActors() const;
  vtkActor* GetSortedActor(int index) const;
  vtkIdType GetNumberOfFragments() const;
  vtkIdType GetNumberOfSplits() const;
  vtkIdType GetNumberOfDrawCalls() const;    ///< Runs drawn in the last frame.
  int GetNumberOfBatchGroups() const;        ///< Groups of >= 2 actors drawn by one helper.
  int GetNumberOfBatchedActors() const;      ///< Actors in those groups.
  vtkIdType GetNumberOfColorBakes() const;   ///< Group colour bakes since construction.
  vtkIdType GetNumberOfTreeBuilds() const;   ///< Since construction.
  vtkIdType GetNumberOfOrderUpdates() const; ///< Incremental order updates since construction.
  vtkIdType GetNumberOfIndexUploads() const; ///< Index buffer uploads of all helpers.
  double GetLastBuildTime() const;           ///< Seconds.
  double GetLastOrderTime() const;           ///< Seconds: order update + runs.
  ///@}

  /**
   * The fragments of the last frame in world coordinates, as polygons in drawing order (first
   * drawn first), with cell data "ActorIndex" (index of GetSortedActor) and "FragmentId".
   * Empty when nothing was sorted.
   */
  void GetOrderedFragments(vtkPolyData* output) const;

  ///@{
  /**
   * Two-level order (default on): actors that a plane separates from the others are ordered as
   * wholes, each by a tree of its own input in the input's coordinates, and only actors that no
   * plane separates share a tree (scenevis/PartTree.h). The trees of inputs are kept while the
   * inputs are unchanged and shared by the actors that draw one input, so moving an actor or
   * adding an instance rebuilds only the top level and the shared trees it leaves or joins,
   * and one actor's polygons are not split by the planes of an actor it does not touch. Off:
   * one world-space tree over every actor, built again when any actor moves (the behaviour
   * before two levels; a scene whose actors all overlap costs the same either way).
   * GetNumberOfPartGroups(): groups of the last build (0 when off); GetLastBuildTreeCount():
   * BSP trees the last build had to make (off: 1).
   */
  void SetTwoLevelOrder(bool twoLevels);
  bool GetTwoLevelOrder() const;
  void TwoLevelOrderOn() { this->SetTwoLevelOrder(true); }
  void TwoLevelOrderOff() { this->SetTwoLevelOrder(false); }
  int GetNumberOfPartGroups() const;
  int GetLastBuildTreeCount() const;
  ///@}

  ///@{
  /**
   * Whether compatible actors are batched (default on). Off: every actor is drawn with its own
   * helper mapper (for comparisons).
   */
  void SetBatching(bool batching);
  bool GetBatching() const;
  void BatchingOn() { this->SetBatching(true); }
  void BatchingOff() { this->SetBatching(false); }
  ///@}

protected:
  vtkBSPTranslucentPass();
  ~vtkBSPTranslucentPass() override;

private:
  vtkBSPTranslucentPass(const vtkBSPTranslucentPass&) = delete;
  void operator=(const vtkBSPTranslucentPass&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
