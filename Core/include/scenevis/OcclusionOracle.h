#pragma once
/**
 * @file OcclusionOracle.h
 * @brief The brute-force reference for occlusion culling: a ray through the centre of every pixel
 *        (the sample OpenGL uses), exact to double precision, with no margins.
 *
 * visiblePixels() counts the pixels at which some point of a box lies nearer than every occluder
 * triangle (between the near and the far plane). A conservative occlusion test (OcclusionBuffer.h)
 * may report a box hidden only when this count is 0. Cost: width x height x triangles ray tests:
 * for tests and fuzzing at small resolutions only.
 */

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <utility>
#include <vector>

namespace scenevis
{
namespace occlusion
{

struct OracleTriangle
{
  glm::dvec3 a, b, c;
};

/// Pixels of a @p width x @p height viewport (camera @p clipFromWorld, OpenGL conventions) at
/// which part of the box [lo, hi] is in front of all @p occluders (both faces occlude).
int visiblePixels(const glm::dmat4& clipFromWorld, int width, int height,
  const std::vector<OracleTriangle>& occluders, const glm::dvec3& lo, const glm::dvec3& hi);

/// Per pixel (row-major, bottom row first): the index of the box of @p boxes (xmin, ymin, zmin,
/// xmax, ymax, zmax: lo then hi) nearest along its ray, as if the boxes were opaque, or -1.
std::vector<int> nearestBoxPerPixel(const glm::dmat4& clipFromWorld, int width, int height,
  const std::vector<std::pair<glm::dvec3, glm::dvec3>>& boxes);

} // namespace occlusion
} // namespace scenevis
