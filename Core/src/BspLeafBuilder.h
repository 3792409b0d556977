#pragma once
// Private to the BSP builder: what BspBuilder.cpp and the ordered-leaf analysis
// (BspLeafBuilder.cpp) share. Ordered leaves themselves are described in BspTree.h.

#include "scenevis/BspTree.h"

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <vector>

namespace scenevis
{
namespace bsp
{
namespace detail
{

/// Where a fragment lies relative to a plane (bit 0: a vertex in front, bit 1: one behind).
enum Side : std::uint8_t
{
  On = 0,
  Front = 1,
  Back = 2,
  Straddle = 3
};

/// A convex planar piece of a normalised input polygon; vertex ids index BuildGeometry::verts.
struct Frag
{
  std::uint32_t piece;
  std::uint32_t first;
  std::uint32_t count;
};

/// The builder's current geometry, read-only: points relative to Tree::origin, the vertex arena,
/// each piece's plane, and the plane tolerance. Pointers, because the arrays grow between calls.
struct BuildGeometry
{
  const glm::dvec3* points = nullptr;
  const std::uint32_t* verts = nullptr;
  const glm::dvec4* piecePlanes = nullptr;
  double tolerance = 0.0;

  double signedDistance(const glm::dvec4& plane, std::uint32_t id) const
  {
    const glm::dvec3& p = points[id];
    return plane.x * p.x + plane.y * p.y + plane.z * p.z + plane.w;
  }

  Side classify(const glm::dvec4& plane, const Frag& f) const
  {
    bool front = false;
    bool back = false;
    const std::uint32_t* ids = verts + f.first;
    for (std::uint32_t k = 0; k < f.count; ++k)
    {
      const double s = signedDistance(plane, ids[k]);
      front |= s > tolerance;
      back |= s < -tolerance;
    }
    return static_cast<Side>((front ? Front : On) | (back ? Back : On));
  }
};

/**
 * The pair analysis of an ordered leaf: for a list of fragments, the separating planes and pairs
 * an OrderedLeaf stores (BspTree.h), and whether the pairs could form a cycle. Keeps its scratch
 * between calls; one per builder (not shared between threads).
 */
class LeafBuilder
{
public:
  /**
   * Analyses `list[0..n)` (n <= kMaxLeafPolygons). True: `planes` (the fragments' own planes, then
   * the pairs' other planes, indices local to the leaf) and `pairs` describe the leaf, and
   * `mayCycle` says whether its pair graph has a cycle (then it needs a fallback). False: some
   * pair intersects (or touches too closely to tell), and the list must be split.
   */
  bool analyse(const BuildGeometry& geometry, const Frag* list, std::uint32_t n);

  std::vector<glm::dvec4> planes;
  std::vector<LeafPair> pairs;
  bool mayCycle = false;

private:
  /// A plane with `a` behind and `b` in front (each within tolerance), from the axes between their
  /// edges and normals; false when none of them separates the pair.
  bool separatingPlane(const Frag& a, const Frag& b, glm::dvec4& plane) const;
  /// Appends to Generators every plane through an edge of one of `a`, `b` and a vertex of the
  /// other that separates them, oriented with `a` behind.
  void separatingGenerators(const Frag& a, const Frag& b);

  BuildGeometry G;
  std::vector<std::uint32_t> Roots;
  std::vector<glm::dvec4> Generators;
};

} // namespace detail
} // namespace bsp
} // namespace scenevis
