// libFuzzer target for the occlusion buffer (OcclusionBuffer.h): arbitrary bytes -> a small
// viewport, a perspective or parallel camera, a few occluder triangles (shared edges, edges
// through pixel centres, the near plane cutting them, offsets of 1e7, NaN and huge values) drawn
// with or without edge neighbours and face culling, by either rasterizer, and a few boxes. Checked
// against the brute-force ray oracle (OcclusionOracle.h), not just "no crash": a box reported
// occluded must have no pixel where part of it is in front of every drawn occluder.
//
// Guard: the oracle is consulted only for conditioned input (every coordinate finite and within
// 1e8); outside it the sanitizers judge. SCENEVIS_FUZZ_SELFTEST=1 checks that the oracle catches
// a buffer that claims every box occluded (must abort); SCENEVIS_FUZZ_VERBOSE=1 prints, per input,
// how many boxes were reported occluded and confirmed by the oracle.
#include "scenevis/OcclusionBuffer.h"
#include "scenevis/OcclusionOracle.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <vector>

namespace
{
using namespace scenevis::occlusion;

/// Reads bytes as small numbers; past the end, zeros.
struct Reader
{
  const std::uint8_t* data;
  std::size_t size, at = 0;
  std::uint8_t byte() { return at < size ? data[at++] : 0; }
  /// A coordinate: mostly on a coarse grid (shared values, edges through pixel centres), now and
  /// then an awkward value.
  double coordinate()
  {
    const std::uint8_t kind = byte();
    const double grid = (static_cast<int>(byte()) - 128) / 8.0;
    switch (kind % 16)
    {
      case 0:
        return grid + (static_cast<int>(byte()) - 128) * 1e-7; // near-coincident
      case 1:
        return grid * 1e3; // far away
      case 2:
        return kind == 2 ? std::numeric_limits<double>::quiet_NaN() : grid;
      case 3:
        return kind == 3 ? 1e30 : grid;
      default:
        return grid;
    }
  }
};

bool conditioned(const glm::dvec3& p)
{
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && std::abs(p.x) < 1e8 &&
    std::abs(p.y) < 1e8 && std::abs(p.z) < 1e8;
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  Reader in{ data, size };
  const int width = 4 + in.byte() % 60, height = 4 + in.byte() % 40;
  const std::uint8_t flags = in.byte();
  const bool parallel = flags & 1, withNeighbors = flags & 2, offset = flags & 4;
  const FaceCulling culling = (flags & 8) ? FaceCulling::Back : FaceCulling::None;
  // Both rasterizers (OcclusionBuffer.h, "Two rasterizers"): the float one unless bit 4 is set.
  const MaskedDepthBuffer::Rasterizer rasterizer =
    (flags & 16) ? MaskedDepthBuffer::Rasterizer::Exact : MaskedDepthBuffer::Rasterizer::Float;
  const glm::dvec3 origin = offset ? glm::dvec3(1e7, -1e7, 5e6) : glm::dvec3(0.0);
  glm::dvec3 eye(in.coordinate(), in.coordinate() - 20.0, in.coordinate());
  glm::dvec3 target(in.coordinate() * 0.2, in.coordinate() * 0.2, in.coordinate() * 0.2);
  bool ok = conditioned(eye) && conditioned(target) && glm::length(target - eye) > 1e-3;
  if (!ok)
  {
    eye = glm::dvec3(0, -20, 0);
    target = glm::dvec3(0.0);
  }
  const double znear = 0.05 + in.byte() / 64.0, zfar = znear + 5.0 + in.byte();
  const glm::dvec3 dir = glm::normalize(target - eye);
  const glm::dvec3 up = std::abs(dir.z) > 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 0, 1);
  const double aspect = double(width) / height;
  const glm::dmat4 view = glm::lookAt(eye + origin, target + origin, up);
  const glm::dmat4 projection = parallel
    ? glm::ortho(-6.0 * aspect, 6.0 * aspect, -6.0, 6.0, znear, zfar)
    : glm::perspective(glm::radians(20.0 + in.byte() % 140), aspect, znear, zfar);
  const glm::dmat4 clipFromWorld = projection * view;

  // Occluders: triangles over a shared pool of points (so edges are shared).
  std::vector<glm::dvec3> points(3 + in.byte() % 24);
  bool conditionedInput = true;
  for (glm::dvec3& p : points)
  {
    p = glm::dvec3(in.coordinate(), in.coordinate(), in.coordinate()) + origin;
    conditionedInput = conditionedInput && conditioned(p);
  }
  std::vector<std::uint32_t> indices;
  const int triangles = 1 + in.byte() % 24;
  for (int t = 0; t < 3 * triangles; ++t)
  {
    indices.push_back(in.byte() % points.size());
  }
  std::vector<glm::dvec4> clip;
  std::vector<double> xyz;
  for (const glm::dvec3& p : points)
  {
    clip.push_back(clipFromWorld * glm::dvec4(p, 1.0));
    xyz.insert(xyz.end(), { p.x, p.y, p.z });
  }
  const std::vector<std::uint32_t> neighbors =
    buildTriangleNeighbors(xyz.data(), points.size(), indices.data(), indices.size() / 3);
  MaskedDepthBuffer buffer;
  buffer.rasterizer = rasterizer;
  buffer.resize(width, height);
  buffer.setClipFromWorld(clipFromWorld);
  buffer.drawTriangles(clip.data(), clip.size(), indices.data(), indices.size() / 3, culling,
    withNeighbors ? neighbors.data() : nullptr);

  // What OpenGL would draw: every triangle, or (back faces culled) those facing the eye (the sign
  // of det[x y w] in clip space).
  std::vector<OracleTriangle> drawn;
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3)
  {
    const glm::dvec4& a = clip[indices[t]];
    const glm::dvec4& b = clip[indices[t + 1]];
    const glm::dvec4& c = clip[indices[t + 2]];
    const double det = a.x * (b.y * c.w - b.w * c.y) - a.y * (b.x * c.w - b.w * c.x) +
      a.w * (b.x * c.y - b.y * c.x);
    if (culling == FaceCulling::None || det > 0.0)
    {
      drawn.push_back({ points[indices[t]], points[indices[t + 1]], points[indices[t + 2]] });
    }
  }
  const bool selftest = std::getenv("SCENEVIS_FUZZ_SELFTEST") != nullptr;
  const int boxes = 1 + in.byte() % 8;
  int confirmed = 0;
  for (int k = 0; k < boxes; ++k)
  {
    const glm::dvec3 c = glm::dvec3(in.coordinate(), in.coordinate(), in.coordinate()) + origin;
    const glm::dvec3 half(
      in.byte() / 32.0 + 1e-3, in.byte() / 32.0 + 1e-3, in.byte() / 32.0 + 1e-3);
    const bool occluded = selftest || buffer.boxOccluded(c - half, c + half);
    if (occluded && conditionedInput && conditioned(c))
    {
      const int visible = visiblePixels(clipFromWorld, width, height, drawn, c - half, c + half);
      if (visible > 0)
      {
        std::fprintf(stderr,
          "occlusion fuzz: box %d reported occluded but visible at %d pixels (%dx%d, %s, "
          "neighbours %d, culling %d)\n",
          k, visible, width, height, parallel ? "parallel" : "perspective", int(withNeighbors),
          int(culling));
        std::abort();
      }
      ++confirmed;
    }
  }
  if (std::getenv("SCENEVIS_FUZZ_VERBOSE"))
  {
    std::fprintf(stderr, "occlusion fuzz: %d boxes, %d occluded and confirmed by the oracle\n",
      boxes, confirmed);
  }
  return 0;
}
