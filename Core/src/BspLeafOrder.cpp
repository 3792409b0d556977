#include "scenevis/BspTraversal.h"

#include "BspSide.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace scenevis
{
namespace bsp
{
namespace
{

using detail::sideValue;

/// Lowest set bit's index (x != 0).
inline std::uint32_t lowestBit(std::uint64_t x)
{
#if defined(__GNUC__) || defined(__clang__)
  return static_cast<std::uint32_t>(__builtin_ctzll(x));
#else
  std::uint32_t k = 0;
  while (!(x & 1u))
  {
    x >>= 1;
    ++k;
  }
  return k;
#endif
}

/**
 * Whether some ray from `eye` may pass through both fragments. It may not when a plane through
 * the eye separates them; the planes separating two convex polygons form a convex cone generated
 * by the separating planes through three of their vertices (an edge of one and a vertex of the
 * other, or a polygon's own plane), so such a plane exists exactly when two of those generators
 * put the eye on different sides (in the verdict sense of LeafPair). Tolerances as in the build.
 */
bool mayOverlap(const Tree& tree, const Fragment& a, const Fragment& b, const glm::dvec4& eye)
{
  const double tol = tree.tolerance;
  // Corners only: conforming fragments (makeConforming) carry the split points of their
  // neighbours on their edges, so a long thin fragment can have dozens of vertices in a line.
  // Those add no separating plane and no side, and refusing such fragments (as counting them
  // against a fixed buffer did) confirms precedences no ray realises, so the leaf falls back for
  // nothing. A vertex is dropped when it repeats the last kept one or continues its direction to
  // the next vertex (within 1e-12 rad): it then lies on a segment between two others, never at a
  // corner, so the polygon keeps its shape.
  constexpr std::uint32_t kMaxCorners = 64;
  auto corners = [&tree](const Fragment& f, glm::dvec3* out) -> std::uint32_t
  {
    const std::uint32_t* ids = tree.fragmentVertices.data() + f.first;
    std::uint32_t m = 0;
    glm::dvec3 last = tree.points[ids[f.count - 1]] - tree.origin;
    for (std::uint32_t k = 0; k < f.count; ++k)
    {
      const glm::dvec3 point = tree.points[ids[k]] - tree.origin;
      const glm::dvec3 next = tree.points[ids[k + 1 == f.count ? 0 : k + 1]] - tree.origin;
      const glm::dvec3 u = point - last;
      const glm::dvec3 v = next - point;
      const double lu = glm::length(u);
      const double lv = glm::length(v);
      const bool straight =
        lv > 0.0 && glm::dot(u, v) > 0.0 && glm::length(glm::cross(u, v)) <= 1e-12 * lu * lv;
      if (!(lu > 0.0) || straight)
      {
        continue;
      }
      if (m == kMaxCorners)
      {
        return kMaxCorners + 1;
      }
      out[m++] = point;
      last = point;
    }
    return m;
  };
  glm::dvec3 pa[kMaxCorners];
  glm::dvec3 pb[kMaxCorners];
  const std::uint32_t ca = corners(a, pa);
  const std::uint32_t cb = corners(b, pb);
  if (ca < 3 || cb < 3 || ca > kMaxCorners || cb > kMaxCorners)
  {
    return true; // degenerate, or too many corners: assume the worst
  }
  bool seen[2] = { false, false };
  // Plane through p, q, r; returns true once both verdicts have been seen.
  auto generator = [&](const glm::dvec3& p, const glm::dvec3& q, const glm::dvec3& r) -> bool
  {
    glm::dvec3 n = glm::cross(q - p, r - p);
    const double length = glm::length(n);
    if (!(length > 0.0) || !std::isfinite(length))
    {
      return false;
    }
    n /= length;
    const double d = -glm::dot(n, p);
    auto classify = [&](const glm::dvec3* points, std::uint32_t count)
    {
      int sides = 0;
      for (std::uint32_t k = 0; k < count; ++k)
      {
        const double s = n.x * points[k].x + n.y * points[k].y + n.z * points[k].z + d;
        sides |= (s > tol ? 1 : 0) | (s < -tol ? 2 : 0);
      }
      return sides;
    };
    const int sa = classify(pa, ca);
    const int sb = classify(pb, cb);
    // Separating: neither straddles, they are not on one side, and not both on the plane.
    if (sa == 3 || sb == 3 || (sa & sb) != 0 || (sa | sb) == 0)
    {
      return false;
    }
    // a behind (sa has no front bit) and b in front, or the reverse (then flip).
    const bool flip = (sa & 1) != 0 || (sb & 2) != 0;
    const bool eyeFront = sideValue(n.x, n.y, n.z, d, eye.x, eye.y, eye.z, eye.w) >= 0.0;
    seen[eyeFront != flip] = true;
    return seen[0] && seen[1];
  };
  for (std::uint32_t i = 0; i < ca; ++i)
  {
    const glm::dvec3& p = pa[i];
    const glm::dvec3& q = pa[i + 1 == ca ? 0 : i + 1];
    for (std::uint32_t j = 0; j < cb; ++j)
    {
      if (generator(p, q, pb[j]))
      {
        return false;
      }
    }
  }
  for (std::uint32_t j = 0; j < cb; ++j)
  {
    const glm::dvec3& p = pb[j];
    const glm::dvec3& q = pb[j + 1 == cb ? 0 : j + 1];
    for (std::uint32_t i = 0; i < ca; ++i)
    {
      if (generator(p, q, pa[i]))
      {
        return false;
      }
    }
  }
  return !(generator(pa[0], pa[1], pa[2]) || generator(pb[0], pb[1], pb[2]));
}

/// A set of leaf indices: W 64-bit words, so a leaf of up to 64 W polygons.
template <std::uint32_t W>
struct Bits
{
  std::uint64_t word[W];

  void clear() { std::fill(word, word + W, std::uint64_t{ 0 }); }
  void set(std::uint32_t i) { word[i >> 6] |= std::uint64_t{ 1 } << (i & 63); }
  void reset(std::uint32_t i) { word[i >> 6] &= ~(std::uint64_t{ 1 } << (i & 63)); }
  bool test(std::uint32_t i) const { return ((word[i >> 6] >> (i & 63)) & 1u) != 0; }
  bool any() const
  {
    std::uint64_t all = 0;
    for (std::uint32_t w = 0; w < W; ++w)
    {
      all |= word[w];
    }
    return all != 0;
  }
  bool intersects(const Bits& other) const
  {
    std::uint64_t common = 0;
    for (std::uint32_t w = 0; w < W; ++w)
    {
      common |= word[w] & other.word[w];
    }
    return common != 0;
  }
  /// The lowest index in both sets (they must intersect).
  std::uint32_t lowestCommon(const Bits& other) const
  {
    std::uint32_t w = 0;
    while ((word[w] & other.word[w]) == 0)
    {
      ++w;
    }
    return w * 64 + lowestBit(word[w] & other.word[w]);
  }
  /// The first n indices.
  static Bits firstN(std::uint32_t n)
  {
    Bits bits;
    for (std::uint32_t w = 0; w < W; ++w)
    {
      const std::uint32_t begin = w * 64;
      bits.word[w] = n >= begin + 64 ? ~std::uint64_t{ 0 }
        : n > begin                  ? (std::uint64_t{ 1 } << (n - begin)) - 1
                                     : 0;
    }
    return bits;
  }
};

/**
 * The topological sort of orderLeaf() on rows of W words. `verdict(plane)` is the stored plane's
 * verdict for the eye (see LeafPair).
 */
template <std::uint32_t W, typename Verdict>
bool sortLeaf(const Tree& tree, const OrderedLeaf& leaf, const glm::dvec4& eye,
  const Verdict& verdict, std::uint32_t* out)
{
  // before[j]: the polygons that must be drawn before j (back to front).
  // Only the leaf's rows are cleared (most leaves are far smaller than kMaxLeafPolygons).
  const std::uint32_t n = leaf.fragmentCount;
  Bits<W> before[kMaxLeafPolygons];
  for (std::uint32_t j = 0; j < n; ++j)
  {
    before[j].clear();
  }
  const LeafPair* pairs = tree.leafPairs.data() + leaf.firstPair;
  for (std::uint32_t k = 0; k < leaf.pairCount; ++k)
  {
    const LeafPair& pair = pairs[k];
    const bool firstBefore = verdict(pair.planes[0]);
    bool agree = true;
    for (std::uint32_t m = 1; m < kPairPlanes && pair.planes[m] != kNoPlane && agree; ++m)
    {
      agree = verdict(pair.planes[m]) == firstBefore;
    }
    if (!agree)
    {
      continue; // two planes disagree: no ray from this eye passes through both
    }
    if (firstBefore)
    {
      before[pair.second].set(pair.first);
    }
    else
    {
      before[pair.first].set(pair.second);
    }
  }
  // Layers of Kahn's algorithm: every polygon with nothing left before it; a layer's polygons
  // constrain none of each other (an edge would keep its target out of the layer).
  Bits<W> remaining = Bits<W>::firstN(n);
  Bits<W> realised[kMaxLeafPolygons]; // precedences confirmed by mayOverlap
  bool stalled = false;
  while (remaining.any())
  {
    Bits<W> ready;
    ready.clear();
    for (std::uint32_t w = 0; w < W; ++w)
    {
      for (std::uint64_t r = remaining.word[w]; r != 0; r &= r - 1)
      {
        const std::uint32_t j = w * 64 + lowestBit(r);
        if (!before[j].intersects(remaining))
        {
          ready.set(j);
        }
      }
    }
    if (!ready.any())
    {
      // A stall: the stored planes only tell which polygon would be nearer if a ray met both, so
      // a cycle may use precedences that no ray from this eye realises. Walk back along
      // predecessors (every polygon left has one) to a cycle; drop its unrealised precedences
      // and retry, or report it when all are realised (checked ones are remembered).
      if (!stalled)
      {
        for (std::uint32_t j = 0; j < n; ++j)
        {
          realised[j].clear();
        }
        stalled = true;
      }
      const Fragment* fragments = tree.fragments.data() + leaf.firstFragment;
      std::uint32_t path[kMaxLeafPolygons + 1];
      Bits<W> onPath;
      onPath.clear();
      std::uint32_t length = 0;
      std::uint32_t j = remaining.lowestCommon(remaining);
      while (!onPath.test(j))
      {
        onPath.set(j);
        path[length++] = j;
        j = before[j].lowestCommon(remaining);
      }
      bool dropped = false;
      for (std::uint32_t t = length; t-- > 0;)
      {
        // path[t] has predecessor path[t + 1] (or j, which closes the cycle).
        const std::uint32_t to = path[t];
        const std::uint32_t from = t + 1 < length ? path[t + 1] : j;
        if (!realised[to].test(from))
        {
          if (mayOverlap(tree, fragments[from], fragments[to], eye))
          {
            realised[to].set(from);
          }
          else
          {
            before[to].reset(from);
            dropped = true;
          }
        }
        if (to == j)
        {
          break; // the cycle is path[t] .. path[length - 1] back to j
        }
      }
      if (!dropped)
      {
        return false;
      }
      continue;
    }
    for (std::uint32_t w = 0; w < W; ++w)
    {
      remaining.word[w] &= ~ready.word[w];
      for (std::uint64_t r = ready.word[w]; r != 0; r &= r - 1)
      {
        *out++ = w * 64 + lowestBit(r);
      }
    }
  }
  return true;
}

} // namespace

bool orderLeaf(const Tree& tree, const OrderedLeaf& leaf, const glm::dvec4& eye, std::uint32_t* out)
{
  // Side bits of the leaf's planes, 64 per word: its own planes and the pairs' (kMaxLeafPlanes).
  constexpr std::uint32_t kWords = (kMaxLeafPlanes + 63) / 64;
  std::uint64_t side[kWords];
  const glm::dvec4* planes = tree.leafPlanes.data() + leaf.firstPlane;
  for (std::uint32_t w = 0; w * 64 < leaf.planeCount; ++w)
  {
    std::uint64_t bits = 0;
    const std::uint32_t end = std::min(leaf.planeCount, w * 64 + 64);
    for (std::uint32_t p = w * 64; p < end; ++p)
    {
      const glm::dvec4& q = planes[p];
      bits |=
        static_cast<std::uint64_t>(sideValue(q.x, q.y, q.z, q.w, eye.x, eye.y, eye.z, eye.w) >= 0.0)
        << (p - w * 64);
    }
    side[w] = bits;
  }
  auto verdict = [&side](std::uint16_t plane) -> bool
  {
    const std::uint32_t p = plane & ~kFlipPlane;
    return (((side[p >> 6] >> (p & 63)) & 1u) != 0) != ((plane & kFlipPlane) != 0);
  };
  // Rows as short as the leaf allows: most leaves fit one word.
  if (leaf.fragmentCount <= 64)
  {
    return sortLeaf<1>(tree, leaf, eye, verdict, out);
  }
  if (leaf.fragmentCount <= 128)
  {
    return sortLeaf<2>(tree, leaf, eye, verdict, out);
  }
  static_assert(kMaxLeafPolygons <= 256, "rows of at most 4 words");
  return sortLeaf<4>(tree, leaf, eye, verdict, out);
}

} // namespace bsp
} // namespace scenevis
