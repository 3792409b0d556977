// makeConforming (BspBuilder.h): split points inserted into the fragment edges they lie on, so
// that the fragments meet edge to edge (no T-junctions).
#include "scenevis/BspBuilder.h"
#include "scenevis/ConvexTriangulation.h"

#include <algorithm>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

namespace scenevis
{
namespace bsp
{
namespace
{
std::uint64_t edgeKey(std::uint32_t a, std::uint32_t b)
{
  const std::uint32_t lo = std::min(a, b), hi = std::max(a, b);
  return (static_cast<std::uint64_t>(lo) << 32) | hi;
}

/**
 * The lines split points lie on. Every split point was made on an edge (a, b) of a fragment; that
 * edge lies along a "carrier": an edge between two points that was never itself a piece of a
 * longer split edge (an input polygon's edge, or the chord a split drew across a polygon). A
 * split point lies on its edge's carrier at a parameter in (0, 1) (0 at the carrier's smaller
 * id). Two fragments beside each other share their common line's carrier, so inserting into
 * every fragment edge the carrier's points that lie strictly between its end points gives both
 * the same vertices along it.
 */
class Carriers
{
public:
  Carriers(std::size_t inputPointCount, const std::vector<SplitPoint>& splitPoints)
    : Base(static_cast<std::uint32_t>(inputPointCount))
  {
    const std::size_t n = splitPoints.size();
    CarrierOf.resize(n);
    ParameterOf.resize(n);
    for (std::size_t i = 0; i < n; ++i)
    {
      const SplitPoint& s = splitPoints[i];
      double pa = 0.0, pb = 0.0;
      const std::uint32_t c = carrierOf(s.a, s.b, &pa, &pb, true);
      CarrierOf[i] = c;
      ParameterOf[i] = pa + s.t * (pb - pa);
      Lines[c].points.emplace_back(ParameterOf[i], Base + static_cast<std::uint32_t>(i));
    }
    for (Line& line : Lines)
    {
      std::sort(line.points.begin(), line.points.end());
    }
  }

  /// Appends to @p out the points strictly between @p u and @p v on their carrier, in order
  /// from u to v.
  void between(std::uint32_t u, std::uint32_t v, std::vector<std::uint32_t>& out)
  {
    double pu = 0.0, pv = 0.0;
    const std::uint32_t c = carrierOf(u, v, &pu, &pv, false);
    if (c == kNone)
    {
      return;
    }
    const auto& points = Lines[c].points;
    const double lo = std::min(pu, pv), hi = std::max(pu, pv);
    auto first = std::upper_bound(points.begin(), points.end(), std::make_pair(lo, kNone));
    auto last = std::lower_bound(points.begin(), points.end(), std::make_pair(hi, 0u));
    if (first >= last)
    {
      return;
    }
    const std::size_t start = out.size();
    for (auto it = first; it != last; ++it)
    {
      if (it->second != u && it->second != v)
      {
        out.push_back(it->second);
      }
    }
    if (pu > pv)
    {
      std::reverse(out.begin() + static_cast<std::ptrdiff_t>(start), out.end());
    }
  }

private:
  struct Line
  {
    std::uint32_t lo, hi;
    std::vector<std::pair<double, std::uint32_t>> points; ///< (parameter, point id), sorted
  };

  bool isSplit(std::uint32_t p) const { return p >= Base; }

  /// Whether @p p lies on carrier @p c, and its parameter there.
  bool on(std::uint32_t p, std::uint32_t c, double* parameter) const
  {
    const Line& line = Lines[c];
    if (p == line.lo || p == line.hi)
    {
      *parameter = p == line.lo ? 0.0 : 1.0;
      return true;
    }
    if (isSplit(p) && CarrierOf[p - Base] == c)
    {
      *parameter = ParameterOf[p - Base];
      return true;
    }
    return false;
  }

  /// The carrier of edge (@p a, @p b) and both points' parameters on it; a new carrier (the
  /// edge itself) when @p create, else kNone when the edge has none with points.
  std::uint32_t carrierOf(std::uint32_t a, std::uint32_t b, double* pa, double* pb, bool create)
  {
    for (const std::uint32_t p : { a, b })
    {
      if (isSplit(p))
      {
        const std::uint32_t c = CarrierOf[p - Base];
        if (on(a, c, pa) && on(b, c, pb))
        {
          return c;
        }
      }
    }
    const std::uint64_t key = edgeKey(a, b);
    auto it = ByEdge.find(key);
    if (it == ByEdge.end())
    {
      if (!create)
      {
        return kNone;
      }
      it = ByEdge.emplace(key, static_cast<std::uint32_t>(Lines.size())).first;
      Lines.push_back(Line{ std::min(a, b), std::max(a, b), {} });
    }
    *pa = a < b ? 0.0 : 1.0;
    *pb = a < b ? 1.0 : 0.0;
    return it->second;
  }

  std::uint32_t Base;
  std::vector<std::uint32_t> CarrierOf;
  std::vector<double> ParameterOf;
  std::vector<Line> Lines;
  std::unordered_map<std::uint64_t, std::uint32_t> ByEdge;
};
} // namespace

std::size_t makeConforming(Tree& tree)
{
  return makeConforming(
    tree.fragments, tree.fragmentVertices, tree.points, tree.inputPointCount, tree.splitPoints);
}

std::size_t makeConforming(std::vector<Fragment>& fragments,
  std::vector<std::uint32_t>& fragmentVertices, const std::vector<glm::dvec3>& points,
  std::size_t inputPointCount, const std::vector<SplitPoint>& splitPoints)
{
  if (splitPoints.empty())
  {
    return 0;
  }
  Carriers carriers(inputPointCount, splitPoints);
  std::vector<std::uint32_t> vertices;
  vertices.reserve(fragmentVertices.size());
  std::size_t inserted = 0;
  std::vector<glm::dvec3> corners;
  for (Fragment& f : fragments)
  {
    const auto first = static_cast<std::uint32_t>(vertices.size());
    for (std::uint32_t k = 0; k < f.count; ++k)
    {
      const std::uint32_t u = fragmentVertices[f.first + k];
      const std::uint32_t v = fragmentVertices[f.first + (k + 1 == f.count ? 0 : k + 1)];
      vertices.push_back(u);
      const std::size_t before = vertices.size();
      carriers.between(u, v, vertices);
      inserted += vertices.size() - before;
    }
    const std::uint32_t count = static_cast<std::uint32_t>(vertices.size()) - first;
    if (count > f.count)
    {
      // The inserted points lie on the fragment's sides, so a fan from a vertex on such a side
      // makes flat triangles and spans the side with one edge (the T-junction again, for the
      // fan triangulation renderers use): start the polygon at the cleanest apex.
      corners.clear();
      for (std::uint32_t k = first; k < first + count; ++k)
      {
        corners.push_back(points[vertices[k]]);
      }
      const std::size_t apex = cleanestFanApex(corners.data(), count);
      std::rotate(vertices.begin() + first, vertices.begin() + first + apex, vertices.end());
    }
    f.first = first;
    f.count = count;
  }
  fragmentVertices = std::move(vertices);
  return inserted;
}

} // namespace bsp
} // namespace scenevis
