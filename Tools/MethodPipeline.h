// The translucency methods of --sort as one pipeline on a renderer (actors, mappers, sorters and
// render passes) with what the reports say about them: sort and build times, fragments, the
// drawn order for the ID-buffer oracle.
#ifndef scenevis_tool_MethodPipeline_h
#define scenevis_tool_MethodPipeline_h

#include "Instances.h"
#include "Progress.h"
#include "vtkBSPSortFilter.h"
#include "vtkBSPSortedPolyDataMapper.h"
#include "vtkBSPTranslucentPass.h"
#include "vtkChunkedPolyDataMapper.h"
#include "vtkOrderedTranslucentPass.h"
#include "vtkPainterSortFilter.h"

#include <vtkActor.h>
#include <vtkDepthSortPolyData.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkPolyDataAlgorithm.h>
#include <vtkPolyDataMapper.h>
#include <vtkSmartPointer.h>

#include <ostream>
#include <string>
#include <vector>

class vtkRenderer;

namespace scenevis
{
namespace tool
{

/// One translucency method set up on a renderer: what `render`, `cull` and `bench` share. The
/// caller owns the renderer (background, camera, cullers); the pipeline adds its actors and pass.
/// With @p groups of more than one polydata, one actor per group is drawn (for prop culling; the
/// method must then be none, oit, multi-actor or peel:N); multi-actor draws one actor per group
/// (the parts) and one actor without @p groups. @p chunked draws the one mesh through
/// vtkChunkedPolyDataMapper (method none, oit or peel:N). With @p instanced, @p groups are its
/// meshes: one mapper per mesh, one actor per placement (its matrix as the user matrix), or with
/// @p instancedProps one vtkInstancedActor per mesh holding its placements (placement i with id
/// i). @p pd may be null when more than one group is drawn (the flattened scene they came from
/// released).
class MethodPipeline
{
public:
  MethodPipeline(const std::string& method, vtkPolyData* pd, vtkRenderer* renderer,
    bool showProgress, const std::vector<vtkSmartPointer<vtkPolyData>>* groups = nullptr,
    bool chunked = false, const InstancedScene* instanced = nullptr, bool instancedProps = false);

  /// Brings a filter's order up to date for the camera (before rendering); milliseconds.
  double Update();

  /// Whether the last frame computed a new order (false for methods without one and for frames
  /// whose camera did not move). Call after rendering it.
  bool Sorted() const { return this->OrderCount() != this->OrderCountBefore; }

  /// Whether the per-frame sort happens inside the render (the mapper and the pass).
  bool SortsInRender() const
  {
    return this->Method == "bsp-mapper" || this->Method == "multi-actor";
  }

  /// Sort time of the last frame in ms (call after rendering it); 0 for methods without a sort
  /// and for frames whose order did not need updating.
  double LastSortMs() const;

  /// One-off preparation in ms: the BSP build (filter, mapper, pass) or the painter's
  /// normalisation; 0 otherwise.
  double BuildMs() const;

  /// Polygons drawn in the last frame.
  vtkIdType Fragments() const;

  /// VTK actors (with instanced props: one per mesh).
  int Parts() const { return static_cast<int>(this->Actors.size()); }
  /// What a culler culls one by one: the placements of instanced props, else the actors.
  vtkIdType Placements() const
  {
    return this->PerMesh ? this->PlacementCount : static_cast<vtkIdType>(this->Actors.size());
  }
  bool InstancedProps() const { return this->PerMesh; }
  const std::vector<vtkSmartPointer<vtkActor>>& GetActors() const { return this->Actors; }
  vtkChunkedPolyDataMapper* GetChunkedMapper() const { return this->Chunked; }

  /**
   * The polygons in the order they were drawn in the last frame, for the ID-buffer oracle, or
   * nullptr when the method has no drawing order (oit, peel) or does not expose its fragments
   * (bsp-mapper: its split fragments live in its vertex buffers only).
   */
  vtkSmartPointer<vtkPolyData> DrawnOrder() const;

  /// Method-specific JSON members (with a leading comma) and one line of text.
  void Describe(std::ostream& json, std::ostream& text) const;

private:
  /// Changes whenever the order is (re)computed: the sorter's output time, the mapper's and the
  /// pass's order updates.
  vtkMTimeType OrderCount() const;

  std::string Method;
  vtkSmartPointer<vtkPolyData> Input;
  vtkIdType InputPolygons = 0;
  std::vector<vtkSmartPointer<vtkActor>> Actors;
  vtkSmartPointer<vtkPolyDataMapper> Mapper;
  vtkSmartPointer<vtkChunkedPolyDataMapper> Chunked;
  vtkNew<vtkBSPSortedPolyDataMapper> BspMapper;
  vtkNew<vtkBSPSortFilter> Bsp;
  vtkNew<vtkPainterSortFilter> Painter;
  vtkNew<vtkDepthSortPolyData> DepthSort;
  vtkNew<vtkOrderedTranslucentPass> OrderedPass;
  vtkNew<vtkBSPTranslucentPass> BspPass;
  vtkNew<ProgressBar> Progress;
  vtkPolyDataAlgorithm* Sorter = nullptr;
  double LastUpdateMs = 0.0;
  vtkMTimeType OrderCountBefore = 0;
  vtkIdType InstancedPolygons = 0; ///< --instances: the placed meshes' polygons
  bool PerMesh = false;            ///< vtkInstancedActors, one per mesh
  vtkIdType PlacementCount = 0;
};

/**
 * Ends the process at once (everything written and flushed) when the scene has more than
 * kFastExitActors actors: VTK 9.1 releases each vertex buffer with a scan of the window's whole
 * buffer cache (vtkOpenGLVertexBufferObjectCache::RemoveVBO), so destroying n mappers costs
 * O(n^2): 14 s after the last frame for the 11,500 parts of the 12M-triangle engine grid.
 */
void ExitNowIfManyActors(int actors);

} // namespace tool
} // namespace scenevis

#endif
