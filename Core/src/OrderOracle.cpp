#include "scenevis/OrderOracle.h"

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <unordered_map>
#include <utility>

namespace scenevis
{
namespace oracle
{
namespace
{

using Polygon2 = std::vector<glm::dvec2>;
using LVec = glm::vec<3, long double, glm::defaultp>;

// Unit roundoff of double (half an ulp, relative).
constexpr double kUnitRoundoff = 0.5 * DBL_EPSILON;

// Rule 2: a plane whose tilt bound, over the scene diagonal, exceeds this many depth tolerances is
// not trusted.
constexpr double kUntrustedTilt = 64.0;

LVec toLong(const glm::dvec3& p)
{
  return LVec(p.x, p.y, p.z);
}

bool isFinite(const glm::dvec3& p)
{
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

double cross2(const glm::dvec2& a, const glm::dvec2& b)
{
  return a.x * b.y - a.y * b.x;
}

double signedArea(const Polygon2& poly)
{
  double twice = 0.0;
  for (std::size_t i = 0, n = poly.size(); i < n; ++i)
  {
    twice += cross2(poly[i], poly[(i + 1) % n]);
  }
  return 0.5 * twice;
}

// The vertex average: inside every convex polygon, and unlike the area centroid it stays accurate
// for overlaps of tiny area (the centroid formula divides by the area).
glm::dvec2 vertexMean(const Polygon2& poly)
{
  glm::dvec2 mean(0.0);
  for (const glm::dvec2& p : poly)
  {
    mean += p;
  }
  return mean / static_cast<double>(poly.size());
}

// Sutherland-Hodgman step: keeps the part of `poly` where value(p) >= 0. Works for any convex
// region bounded by such half-spaces; a crossing is only made on a strict sign change, so a vertex
// lying on the boundary is kept once and never duplicated.
template<class Point, class Value>
void clipHalfSpace(std::vector<Point>& poly, std::vector<Point>& scratch, const Value& value)
{
  scratch.clear();
  const std::size_t n = poly.size();
  if (n == 0)
  {
    return;
  }
  double va = value(poly[n - 1]);
  for (std::size_t i = 0; i < n; ++i)
  {
    const Point& a = poly[(i + n - 1) % n];
    const Point& b = poly[i];
    const double vb = value(b);
    if ((va > 0.0 && vb < 0.0) || (va < 0.0 && vb > 0.0))
    {
      const double t = va / (va - vb);
      scratch.push_back(a + (b - a) * t);
    }
    if (vb >= 0.0)
    {
      scratch.push_back(b);
    }
    va = vb;
  }
  poly.swap(scratch);
}

// A polygon ready for ray casting, in coordinates relative to the local origin.
struct Prepared
{
  std::vector<glm::dvec3> points;
  glm::dvec3 normal{ 0.0 }; // unit; zero when the polygon covers no area
  glm::dvec3 point{ 0.0 };  // on the plane (vertex average)
  bool valid = false;
  // The same in long double, for re-casting witness rays: the vertices relative to the local
  // origin (the subtraction done in long double), the unit Newell normal and the vertex mean.
  std::vector<LVec> pointsL;
  LVec normalL{ 0.0L };
  LVec meanL{ 0.0L };
  double extent = 0.0; // diagonal of the polygon's own bounding box (>= its diameter)
  double tilt = 0.0;   // bound on the angle between the fitted and the intended plane (radians)
};

// A polygon's image in one projection; `poly` is counter-clockwise.
struct Projected
{
  std::uint32_t id;
  Polygon2 poly;
  glm::dvec2 lo;
  glm::dvec2 hi;
  double area;
};

// One projection: image point s maps to the ray origin + t * direction with
// perspective: origin 0, direction right*s.x + up*s.y + forward;
// parallel:    origin right*s.x + up*s.y, direction forward.
struct Frame
{
  glm::dvec3 right;
  glm::dvec3 up;
  glm::dvec3 forward;
};

struct PairState
{
  bool lowFarther = false;  // the smaller id was seen farther
  bool highFarther = false; // the larger id was seen farther
  glm::dvec3 witness{ 0.0 };
  double separation = 0.0;
  bool hasWitness = false;
};

class Checker
{
public:
  Checker(const std::vector<Polygon>& polygons, const View& view, const OracleConfig& config)
    : Config(config)
    , Parallel(view.isParallel())
  {
    Box bounds;
    double maxAbs = 0.0;
    for (const Polygon& poly : polygons)
    {
      for (const glm::dvec3& p : poly)
      {
        if (isFinite(p))
        {
          bounds.extend(p);
          maxAbs = std::max({ maxAbs, std::abs(p.x), std::abs(p.y), std::abs(p.z) });
        }
      }
    }
    Diagonal = bounds.diagonal();
    DepthTolerance = config.relativeDepthTolerance * Diagonal + 16.0 * DBL_EPSILON * maxAbs;

    if (Parallel)
    {
      Origin = bounds.empty() ? glm::dvec3(0.0) : bounds.center();
      Direction = -glm::dvec3(view.eye);
    }
    else
    {
      Origin = glm::dvec3(view.eye) / view.eye.w;
    }

    Polys.resize(polygons.size());
    for (std::size_t i = 0; i < polygons.size(); ++i)
    {
      prepare(polygons[i], Polys[i]);
    }
  }

  double depthTolerance() const { return DepthTolerance; }
  std::size_t untrustedPolygons() const { return UntrustedPolygons; }
  std::size_t unconfirmedRays() const { return UnconfirmedRays; }

  /// Finds every overlapping pair in every projection and records the depth relations seen.
  void run()
  {
    if (Parallel)
    {
      const glm::dvec3 f = glm::normalize(Direction);
      // Any right-handed frame around f; the choice does not affect the verdict.
      const glm::dvec3 helper = std::abs(f.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
      const glm::dvec3 r = glm::normalize(glm::cross(helper, f));
      runFrame(Frame{ r, glm::cross(f, r), f });
      return;
    }
    for (int axis = 0; axis < 3; ++axis)
    {
      for (double sign : { 1.0, -1.0 })
      {
        glm::dvec3 f(0.0);
        glm::dvec3 r(0.0);
        glm::dvec3 u(0.0);
        f[axis] = sign;
        r[(axis + 1) % 3] = 1.0;
        u[(axis + 2) % 3] = 1.0;
        runFrame(Frame{ r, u, f });
      }
    }
  }

  const std::unordered_map<std::uint64_t, PairState>& pairs() const { return Pairs; }

  static std::uint64_t key(std::uint32_t low, std::uint32_t high)
  {
    return (static_cast<std::uint64_t>(low) << 32) | high;
  }

private:
  void prepare(const Polygon& poly, Prepared& out)
  {
    out.valid = false;
    if (poly.size() < 3 || !std::all_of(poly.begin(), poly.end(), isFinite))
    {
      return;
    }
    out.points.resize(poly.size());
    glm::dvec3 mean(0.0);
    for (std::size_t i = 0; i < poly.size(); ++i)
    {
      out.points[i] = poly[i] - Origin; // exact for points near the origin chosen (Sterbenz)
      mean += out.points[i];
    }
    mean /= static_cast<double>(poly.size());
    // Newell's normal relative to the mean: its rounding error scales with the polygon's own
    // size, not with its distance from the local origin.
    glm::dvec3 n(0.0);
    for (std::size_t i = 0, count = poly.size(); i < count; ++i)
    {
      const glm::dvec3 a = out.points[i] - mean;
      const glm::dvec3 b = out.points[(i + 1) % count] - mean;
      n += glm::cross(a, b);
    }
    const double length = glm::length(n);
    if (!(length > 0.0) || !std::isfinite(length))
    {
      return;
    }
    out.normal = n / length;
    out.point = mean;

    // The plane again in long double, from the vertices relative to the origin subtracted in long
    // double (exact for all but extreme exponent ranges), for the witness re-check (see sample).
    out.pointsL.resize(poly.size());
    LVec meanL(0.0L);
    glm::dvec3 lo = poly[0];
    glm::dvec3 hi = poly[0];
    double maxAbs = 0.0;
    for (std::size_t i = 0; i < poly.size(); ++i)
    {
      out.pointsL[i] = toLong(poly[i]) - toLong(Origin);
      meanL += out.pointsL[i];
      lo = glm::min(lo, poly[i]);
      hi = glm::max(hi, poly[i]);
      maxAbs = std::max({ maxAbs, std::abs(poly[i].x), std::abs(poly[i].y), std::abs(poly[i].z) });
    }
    meanL /= static_cast<long double>(poly.size());
    LVec nL(0.0L);
    for (std::size_t i = 0, count = poly.size(); i < count; ++i)
    {
      nL += glm::cross(out.pointsL[i] - meanL, out.pointsL[(i + 1) % count] - meanL);
    }
    const long double twiceArea = glm::length(nL);
    if (!(twiceArea > 0.0L))
    {
      return;
    }
    out.normalL = nL / twiceArea;
    out.meanL = meanL;
    // Plane uncertainty (rule 2 of the header). Width w = 2 area / extent; residual r = largest
    // distance of a vertex from the fitted plane. Each vertex may be off its intended position by
    // the rounding of its coordinates, u |coordinate|, or (when larger) by the measured residual;
    // that tilts the plane by about 2 max(u |c|, r) / w, plus the rounding of the normal's own
    // double computation (~8 eps extent / w).
    long double residual = 0.0L;
    for (const LVec& p : out.pointsL)
    {
      residual = std::max(residual, std::abs(glm::dot(out.normalL, p - meanL)));
    }
    out.extent = glm::length(hi - lo);
    const double width = static_cast<double>(twiceArea) / out.extent;
    const double wobble = std::max(kUnitRoundoff * maxAbs, static_cast<double>(residual));
    out.tilt = (8.0 * DBL_EPSILON * out.extent + 2.0 * wobble) / width;
    // Across the scene (the largest distance between two hit points) that tilt moves a measured
    // separation by tilt x diagonal. Up to kUntrustedTilt depth tolerances the re-check's slack
    // (confirm) absorbs it; beyond, the plane is mostly rounding and constrains nothing.
    if (!(out.tilt * Diagonal <= kUntrustedTilt * DepthTolerance))
    {
      ++UntrustedPolygons;
      return;
    }
    // Seen edge-on within the tolerance: the polygon's image is thinner than its own positional
    // uncertainty, so which rays pass through it is not determined; it constrains nothing. For a
    // perspective view that is a plane passing within the tolerance of the eye; for a parallel
    // one a polygon whose extent along the view direction is within the tolerance.
    if (Parallel)
    {
      double radius = 0.0;
      for (const glm::dvec3& p : out.points)
      {
        radius = std::max(radius, glm::length(p - mean));
      }
      if (radius * std::abs(glm::dot(out.normal, glm::normalize(Direction))) <= DepthTolerance)
      {
        return;
      }
    }
    else if (std::abs(glm::dot(out.normal, mean)) <= DepthTolerance)
    {
      return;
    }
    out.valid = true;
  }

  bool project(const Prepared& poly, const Frame& frame, Polygon2& out)
  {
    // To frame coordinates (u, v, w); for a perspective view w is the depth along the face axis.
    Work3.clear();
    for (const glm::dvec3& p : poly.points)
    {
      Work3.emplace_back(
        glm::dot(p, frame.right), glm::dot(p, frame.up), glm::dot(p, frame.forward));
    }
    out.clear();
    if (Parallel)
    {
      for (const glm::dvec3& p : Work3)
      {
        out.emplace_back(p.x, p.y);
      }
      return true;
    }
    // The face frustum |u| <= w, |v| <= w, plus a near plane so that the central projection is
    // bounded. The near plane only removes points within a 1e-12 fraction of the scene of the eye.
    const double nearDistance = std::max(1e-12 * Diagonal, 1e-300);
    clipHalfSpace(Work3, Scratch3, [](const glm::dvec3& p) { return p.z - p.x; });
    clipHalfSpace(Work3, Scratch3, [](const glm::dvec3& p) { return p.z + p.x; });
    clipHalfSpace(Work3, Scratch3, [](const glm::dvec3& p) { return p.z - p.y; });
    clipHalfSpace(Work3, Scratch3, [](const glm::dvec3& p) { return p.z + p.y; });
    clipHalfSpace(
      Work3, Scratch3, [nearDistance](const glm::dvec3& p) { return p.z - nearDistance; });
    if (Work3.size() < 3)
    {
      return false;
    }
    for (const glm::dvec3& p : Work3)
    {
      out.emplace_back(p.x / p.z, p.y / p.z);
    }
    return true;
  }

  void runFrame(const Frame& frame)
  {
    Images.clear();
    Polygon2 image;
    for (std::size_t i = 0; i < Polys.size(); ++i)
    {
      if (!Polys[i].valid || !project(Polys[i], frame, image) || image.size() < 3)
      {
        continue;
      }
      double area = signedArea(image);
      if (area < 0.0)
      {
        std::reverse(image.begin(), image.end());
        area = -area;
      }
      if (!(area > 0.0))
      {
        continue; // seen edge-on: covers no ray
      }
      Projected item{ static_cast<std::uint32_t>(i), image, image[0], image[0], area };
      for (const glm::dvec2& p : image)
      {
        item.lo = glm::min(item.lo, p);
        item.hi = glm::max(item.hi, p);
      }
      Images.push_back(std::move(item));
    }

    // Sweep over the image bounding boxes along x: only boxes that overlap are intersected.
    std::sort(Images.begin(), Images.end(),
      [](const Projected& a, const Projected& b) { return a.lo.x < b.lo.x; });
    const double areaFloor = 1e-24 * (Parallel ? Diagonal * Diagonal : 1.0);
    for (std::size_t i = 0; i < Images.size(); ++i)
    {
      const Projected& a = Images[i];
      for (std::size_t j = i + 1; j < Images.size() && Images[j].lo.x <= a.hi.x; ++j)
      {
        const Projected& b = Images[j];
        if (b.lo.y > a.hi.y || a.lo.y > b.hi.y)
        {
          continue;
        }
        testPair(a, b, frame, areaFloor);
      }
    }
  }

  void testPair(const Projected& a, const Projected& b, const Frame& frame, double areaFloor)
  {
    // Clip a's image by every edge of b's (both counter-clockwise and convex).
    Overlap = a.poly;
    for (std::size_t e = 0, n = b.poly.size(); e < n && Overlap.size() >= 3; ++e)
    {
      const glm::dvec2 p0 = b.poly[e];
      const glm::dvec2 edge = b.poly[(e + 1) % n] - p0;
      clipHalfSpace(Overlap, Scratch2, [&](const glm::dvec2& p) { return cross2(edge, p - p0); });
    }
    if (Overlap.size() < 3)
    {
      return;
    }
    const double area = signedArea(Overlap);
    if (!(area > std::max(Config.relativeAreaTolerance * std::min(a.area, b.area), areaFloor)))
    {
      return;
    }

    const std::uint32_t low = std::min(a.id, b.id);
    const std::uint32_t high = std::max(a.id, b.id);
    const Prepared& pl = Polys[low];
    const Prepared& ph = Polys[high];
    const glm::dvec2 c = vertexMean(Overlap);

    // An overlap thinner than the depth tolerance is where the polygons touch up to rounding (a
    // shared edge, a common line through the eye, a cube-map face border), not a common ray. The
    // width is area / diameter; in a perspective image, a displacement d at image point (x, y)
    // turns the ray by at least d / (1 + x^2 + y^2) >= d / 3 radians, which at the nearer hit
    // distance is at least d * t / 3 in the scene.
    double diameter = 0.0;
    for (std::size_t i = 0; i < Overlap.size(); ++i)
    {
      for (std::size_t j = i + 1; j < Overlap.size(); ++j)
      {
        diameter = std::max(diameter, glm::length(Overlap[i] - Overlap[j]));
      }
    }
    double width = area / diameter;
    if (!Parallel)
    {
      const glm::dvec3 d = glm::normalize(frame.right * c.x + frame.up * c.y + frame.forward);
      const double nearer = std::min(glm::dot(pl.normal, pl.point) / glm::dot(pl.normal, d),
        glm::dot(ph.normal, ph.point) / glm::dot(ph.normal, d));
      width *= nearer / 3.0;
    }
    if (!(width > DepthTolerance))
    {
      return;
    }

    PairState& state = Pairs[Checker::key(low, high)];
    const std::size_t vertexSamples = std::min<std::size_t>(
      static_cast<std::size_t>(std::max(Config.samplesPerOverlap - 1, 0)), Overlap.size());
    for (std::size_t k = 0; k <= vertexSamples; ++k)
    {
      glm::dvec2 s = c;
      if (k > 0)
      {
        s = 0.5 * (c + Overlap[(k - 1) * Overlap.size() / vertexSamples]);
      }
      glm::dvec3 origin(0.0);
      glm::dvec3 direction = frame.forward;
      if (Parallel)
      {
        origin = frame.right * s.x + frame.up * s.y;
      }
      else
      {
        direction = frame.right * s.x + frame.up * s.y + frame.forward;
      }
      sample(pl, ph, origin, glm::normalize(direction), state);
    }
  }

  void sample(const Prepared& a, const Prepared& b, const glm::dvec3& origin,
    const glm::dvec3& direction, PairState& state)
  {
    const double ca = glm::dot(a.normal, direction);
    const double cb = glm::dot(b.normal, direction);
    if (ca == 0.0 || cb == 0.0)
    {
      return;
    }
    const double ta = glm::dot(a.normal, a.point - origin) / ca;
    const double tb = glm::dot(b.normal, b.point - origin) / cb;
    if (!Parallel && (!(ta > 0.0) || !(tb > 0.0)))
    {
      return; // only possible through rounding at the eye; such a ray proves nothing
    }
    // Perpendicular separation: how far each hit point is from the other polygon's plane (the
    // smaller of the two). Grazing rays do not inflate it.
    const double separation = (ta - tb) * std::min(std::abs(ca), std::abs(cb));
    if (std::abs(separation) <= DepthTolerance)
    {
      return;
    }
    bool& seen = separation > 0.0 ? state.lowFarther : state.highFarther;
    if (seen)
    {
      return; // already witnessed by a confirmed ray
    }
    long double taL = 0.0L;
    if (!confirm(a, b, origin, direction, separation > 0.0, taL))
    {
      ++UnconfirmedRays;
      return;
    }
    seen = true;
    if (!state.hasWitness)
    {
      state.hasWitness = true;
      state.witness = Origin + glm::dvec3(toLong(origin) + taL * toLong(direction));
      state.separation = separation;
    }
  }

  /**
   * Where the ray origin + t direction (long double) meets polygon `p`'s fitted plane: t and the
   * cosine with the normal; false when the hit is not inside the actual vertex loop by at least
   * `margin` from every edge (measured in the plane).
   */
  static bool hitInside(const Prepared& p, const LVec& origin, const LVec& direction,
    long double margin, long double& t, long double& cosine)
  {
    cosine = glm::dot(p.normalL, direction);
    if (cosine == 0.0L)
    {
      return false;
    }
    t = glm::dot(p.normalL, p.meanL - origin) / cosine;
    const LVec x = origin + t * direction;
    for (std::size_t i = 0, n = p.pointsL.size(); i < n; ++i)
    {
      const LVec edge = p.pointsL[(i + 1) % n] - p.pointsL[i];
      const long double length = glm::length(edge);
      if (length == 0.0L)
      {
        continue; // repeated vertex
      }
      if (!(glm::dot(p.normalL, glm::cross(edge, x - p.pointsL[i])) >= margin * length))
      {
        return false;
      }
    }
    cosine = std::abs(cosine);
    return true;
  }

  /**
   * Rule 1 of the header: re-casts a constraining sample ray in long double against both
   * polygons' actual vertices. Confirmed only when the ray passes through both interiors with a
   * margin of the depth tolerance, in front of the eye, and sees the same polygon farther by more
   * than the depth tolerance plus what the two planes' tilt bounds allow over the distance between
   * the hits. `aFarther` is the double verdict; `ta` receives the long double hit distance on a.
   */
  bool confirm(const Prepared& a, const Prepared& b, const glm::dvec3& origin,
    const glm::dvec3& direction, bool aFarther, long double& ta) const
  {
    const LVec o = toLong(origin);
    LVec d = toLong(direction);
    d /= glm::length(d);
    const long double margin = DepthTolerance;
    long double tb = 0.0L;
    long double ca = 0.0L;
    long double cb = 0.0L;
    if (!hitInside(a, o, d, margin, ta, ca) || !hitInside(b, o, d, margin, tb, cb))
    {
      return false;
    }
    if (!Parallel && (!(ta > 0.0L) || !(tb > 0.0L)))
    {
      return false;
    }
    const long double gap = ta - tb; // distance between the hits, signed
    const long double separation = gap * std::min(ca, cb);
    const long double slack = DepthTolerance + a.tilt * (std::abs(gap) + a.extent) +
      b.tilt * (std::abs(gap) + b.extent);
    return aFarther ? separation > slack : -separation > slack;
  }

  OracleConfig Config;
  bool Parallel;
  glm::dvec3 Origin{ 0.0 };
  glm::dvec3 Direction{ 0.0, 0.0, 1.0 };
  double Diagonal = 0.0;
  double DepthTolerance = 0.0;
  std::vector<Prepared> Polys;
  std::vector<Projected> Images;
  std::vector<glm::dvec3> Work3;
  std::vector<glm::dvec3> Scratch3;
  Polygon2 Overlap;
  Polygon2 Scratch2;
  std::unordered_map<std::uint64_t, PairState> Pairs;
  std::size_t UntrustedPolygons = 0;
  std::size_t UnconfirmedRays = 0;
};

} // namespace

OracleReport checkOrder(const std::vector<Polygon>& polygons,
  const std::vector<std::uint32_t>& order, const View& view, const OracleConfig& config)
{
  const std::size_t n = polygons.size();
  if (order.size() != n)
  {
    throw std::invalid_argument("checkOrder: order is not a permutation of the polygon ids");
  }
  std::vector<std::size_t> position(n, n);
  for (std::size_t i = 0; i < n; ++i)
  {
    if (order[i] >= n || position[order[i]] != n)
    {
      throw std::invalid_argument("checkOrder: order is not a permutation of the polygon ids");
    }
    position[order[i]] = i;
  }

  Checker checker(polygons, view, config);
  checker.run();

  OracleReport report;
  report.depthTolerance = checker.depthTolerance();
  report.untrustedPolygons = checker.untrustedPolygons();
  report.unconfirmedRays = checker.unconfirmedRays();
  for (const auto& entry : checker.pairs())
  {
    const PairState& state = entry.second;
    if (!state.lowFarther && !state.highFarther)
    {
      continue;
    }
    ++report.constrainedPairs;
    report.conflictingPairs += (state.lowFarther && state.highFarther) ? 1 : 0;
    const auto low = static_cast<std::uint32_t>(entry.first >> 32);
    const auto high = static_cast<std::uint32_t>(entry.first & 0xffffffffu);
    // Violated when some ray sees the later polygon farther.
    if (state.lowFarther && position[low] > position[high])
    {
      report.violations.push_back(Violation{ low, high });
    }
    else if (state.highFarther && position[high] > position[low])
    {
      report.violations.push_back(Violation{ high, low });
    }
  }
  std::sort(report.violations.begin(), report.violations.end(),
    [](const Violation& a, const Violation& b)
    { return a.farther != b.farther ? a.farther < b.farther : a.nearer < b.nearer; });
  return report;
}

OracleReport checkOrder(const PolygonMesh& mesh, const std::vector<std::uint32_t>& order,
  const View& view, const OracleConfig& config)
{
  return checkOrder(polygonsOf(mesh), order, view, config);
}

PairRelation relate(
  const Polygon& a, const Polygon& b, const View& view, const OracleConfig& config)
{
  Checker checker({ a, b }, view, config);
  checker.run();
  PairRelation result;
  const auto found = checker.pairs().find(Checker::key(0, 1));
  if (found == checker.pairs().end())
  {
    return result;
  }
  const PairState& state = found->second;
  if (state.lowFarther && state.highFarther)
  {
    result.relation = Relation::Conflicting;
  }
  else if (state.lowFarther)
  {
    result.relation = Relation::FirstFarther;
  }
  else if (state.highFarther)
  {
    result.relation = Relation::SecondFarther;
  }
  result.witness = state.witness;
  result.separation = state.separation;
  return result;
}

std::vector<Polygon> polygonsOf(const PolygonMesh& mesh)
{
  std::vector<Polygon> result(mesh.polygonCount());
  for (std::size_t i = 0; i < mesh.polygonCount(); ++i)
  {
    const std::uint32_t* ids = mesh.polygon(i);
    for (std::uint32_t k = 0; k < mesh.polygonSize(i); ++k)
    {
      // An out-of-range id makes the polygon invalid (ignored), as a NaN point would.
      result[i].push_back(ids[k] < mesh.points.size()
                            ? mesh.points[ids[k]]
                            : glm::dvec3(std::numeric_limits<double>::quiet_NaN()));
    }
  }
  return result;
}

std::vector<Polygon> fragmentPolygons(const bsp::Tree& tree)
{
  std::vector<Polygon> result(tree.fragments.size());
  for (std::size_t i = 0; i < tree.fragments.size(); ++i)
  {
    const bsp::Fragment& fragment = tree.fragments[i];
    result[i].reserve(fragment.count);
    for (std::uint32_t k = 0; k < fragment.count; ++k)
    {
      result[i].push_back(tree.points[tree.fragmentVertices[fragment.first + k]]);
    }
  }
  return result;
}

} // namespace oracle
} // namespace scenevis
