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
 *    mapper, surface representation without edges, visible, currently translucent);
 * 2. builds ONE BSP tree over their polygons in world coordinates (each fragment remembers its
 *    actor); fragments of an actor split by another actor's plane get interpolated attributes;
 * 3. gives every actor a helper vtkBSPSortedPolyDataMapper whose vertex buffers hold that actor's
 *    fragments (built once per tree) and whose index buffer holds the actor's fragments in the
 *    global order;
 * 4. draws the global order as runs of consecutive fragments of one actor: each run is one draw
 *    call of that actor's helper over a range of its index buffer, with the actor's own property,
 *    texture, matrix, scalars and lookup table.
 *
 * Work per frame:
 * - the set of sorted actors, an actor's matrix, an actor's input or mapper changed: the tree is
 *   rebuilt (GetNumberOfTreeBuilds(), GetLastBuildTime());
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
  vtkIdType GetNumberOfDrawCalls() const;   ///< Runs drawn in the last frame.
  vtkIdType GetNumberOfTreeBuilds() const;  ///< Since construction.
  vtkIdType GetNumberOfOrderUpdates() const; ///< Incremental order updates since construction.
  vtkIdType GetNumberOfIndexUploads() const; ///< Index buffer uploads of all helpers.
  double GetLastBuildTime() const;          ///< Seconds.
  double GetLastOrderTime() const;          ///< Seconds: order update + runs.
  ///@}

  /**
   * The fragments of the last frame in world coordinates, as polygons in drawing order (first
   * drawn first), with cell data "ActorIndex" (index of GetSortedActor) and "FragmentId".
   * Empty when nothing was sorted.
   */
  void GetOrderedFragments(vtkPolyData* output) const;

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
