// OpenGL occlusion queries over bounding boxes, for the comparison in scenevis_occlusion_bench:
// the other way to cull by occlusion (Bittner et al.'s CHC/CHC++ and Mattausch's CHC++ build on
// them). One GL_ANY_SAMPLES_PASSED query per box, drawn with depth test and no colour or depth
// writes against the depth buffer of what the renderer drew this frame; then every result is
// read back (a full wait, as a culler that must decide before drawing would). Run it from the
// renderer's EndEvent, while its framebuffer is bound. On llvmpipe the queries themselves are
// rasterized on the CPU: measured, not assumed.
#ifndef scenevis_bench_OcclusionQueries_h
#define scenevis_bench_OcclusionQueries_h

#include <array>
#include <vector>

class vtkRenderer;

namespace scenevis
{
namespace bench
{

struct QueryResult
{
  std::vector<char> visible; ///< per box: some sample passed the depth test
  double issueMs = 0.0;      ///< drawing the boxes inside their queries
  double waitMs = 0.0;       ///< reading every result back
  bool ok = false;           ///< queries and shaders available
};

/// Queries @p boxes (xmin, xmax, ymin, ymax, zmin, zmax) with @p renderer's camera.
QueryResult QueryBoxes(vtkRenderer* renderer, const std::vector<std::array<double, 6>>& boxes);

} // namespace bench
} // namespace scenevis

#endif
