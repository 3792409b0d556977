#include "scenevis/PainterSort.h"

#include "scenevis/BspBuilder.h"

#include "PolygonPieces.h"
#include "Triangulate.h"

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <utility>

namespace scenevis
{
namespace painter
{
namespace
{

constexpr double kHalfPi = 1.57079632679489661923;
constexpr std::uint32_t kNone = 0xffffffffu;
/// Cones wider than this half-angle are unbounded (cos(89.9 degrees)).
constexpr double kMinConeCos = 1.7453283658983088e-3;
/// Perspective test (5): both cones must fit within this angle of the common projection axis.
constexpr double kMaxProjectionAngle = kHalfPi - 0.02;
/// A cycle search looks at most at this many fragments of the chain of moves.
constexpr std::size_t kMaxCycleSearch = 32;

using detail::planeBasis;

/// A live or dead convex fragment of a piece, with its per-view data.
struct Frag
{
  std::uint32_t piece;
  std::uint32_t first; // into Impl::Verts
  std::uint32_t count;
  std::uint32_t stackPos = kNone; // position in the move stack (marked), or kNone
  bool alive = true;
  bool edgeOn = false;
  bool bounded = false; // perspective: cone valid; parallel: always true
  double zmin = 0.0;
  double zmax = 0.0;
  // Perspective: cone axis and cos / sin of its half-angle. Parallel: image box in (x, y) of
  // axis (lo) and (c, s) (hi) -- see Impl::computeView.
  glm::dvec3 axis{ 0.0 };
  double c = 0.0;
  double s = 0.0;
};

struct Entry
{
  double zmax;
  std::uint32_t frag;
};

/// Farthest first; ties by fragment id (deterministic).
bool before(const Entry& a, const Entry& b)
{
  return a.zmax > b.zmax || (a.zmax == b.zmax && a.frag < b.frag);
}

struct EdgeKey
{
  std::uint32_t lo;
  std::uint32_t hi;
  std::uint32_t plane;
  bool operator==(const EdgeKey& o) const { return lo == o.lo && hi == o.hi && plane == o.plane; }
};

struct EdgeKeyHash
{
  std::size_t operator()(const EdgeKey& k) const
  {
    std::uint64_t h = (static_cast<std::uint64_t>(k.lo) << 32) | k.hi;
    h ^= static_cast<std::uint64_t>(k.plane) * 0x9e3779b97f4a7c15ull;
    h ^= h >> 29;
    h *= 0xbf58476d1ce4e5b9ull;
    h ^= h >> 32;
    return static_cast<std::size_t>(h);
  }
};

/// Range of signed distances (positive toward the eye) of a fragment's vertices to a plane.
struct Range
{
  double lo;
  double hi;
};

} // namespace

struct Sorter::Impl
{
  Config Cfg;
  double Tol = 0.0;
  glm::dvec3 Origin{ 0.0 };
  Statistics Norm;

  std::vector<glm::dvec3> InputPoints;
  std::vector<glm::dvec3> InputLocal;
  std::vector<glm::dvec4> PiecePlane; // (n, d), |n| = 1, relative to Origin
  std::vector<std::uint32_t> PieceSource;
  std::vector<std::uint32_t> PieceFirst;
  std::vector<std::uint32_t> PieceCount;
  std::vector<std::uint32_t> PieceVerts;

  // Per sort.
  Result* Out = nullptr;
  Statistics* St = nullptr;
  bool Parallel = false;
  glm::dvec3 Eye{ 0.0 }; // perspective: local eye
  glm::dvec3 Dir{ 0.0 }; // parallel: view direction (into the scene)
  glm::dvec3 ScreenU{ 0.0 };
  glm::dvec3 ScreenV{ 0.0 };
  std::vector<glm::dvec3> Pts; // local points: input, then split points
  std::vector<glm::dvec4> Planes; // piece planes, then fallback (bisection) planes
  std::vector<double> EyeSign;    // per piece: +1 when the eye is in front of its plane
  std::vector<std::uint32_t> Verts;
  std::vector<Frag> Frags;
  std::vector<Entry> Main;
  std::vector<Entry> Extra;
  std::size_t MainCursor = 0;
  std::size_t ExtraCursor = 0;
  std::vector<std::uint32_t> Stack;
  std::unordered_map<EdgeKey, std::uint32_t, EdgeKeyHash> Cache;
  std::size_t MaxSplits = 0;
  std::vector<std::uint32_t> FrontScratch;
  std::vector<std::uint32_t> BackScratch;
  std::vector<glm::dvec2> ProjA;
  std::vector<glm::dvec2> ProjB;

  void normalise(const PolygonMesh& mesh);
  void run(const View& view, Result& result);

  double distance(const glm::dvec4& plane, std::uint32_t id) const
  {
    const glm::dvec3& p = Pts[id];
    return plane.x * p.x + plane.y * p.y + plane.z * p.z + plane.w;
  }
  /// Signed distances of f's vertices to the plane of `piece`, positive on the eye's side.
  Range range(const Frag& f, std::uint32_t piece) const
  {
    const glm::dvec4& plane = Planes[piece];
    const double sign = EyeSign[piece];
    Range r{ std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity() };
    for (std::uint32_t k = 0; k < f.count; ++k)
    {
      const double d = sign * distance(plane, Verts[f.first + k]);
      r.lo = std::min(r.lo, d);
      r.hi = std::max(r.hi, d);
    }
    return r;
  }
  bool straddles(const Frag& f, std::uint32_t plane) const
  {
    bool front = false;
    bool back = false;
    for (std::uint32_t k = 0; k < f.count; ++k)
    {
      const double d = distance(Planes[plane], Verts[f.first + k]);
      front |= d > Tol;
      back |= d < -Tol;
    }
    return front && back;
  }

  void computeView(Frag& f) const;
  bool extentsDisjoint(const Frag& p, const Frag& q) const;
  /// Test (5); sets `undecided` when the projection test cannot be made.
  bool projectionsDisjoint(const Frag& p, const Frag& q, bool& undecided);
  bool canPrecede(const Frag& p, const Frag& q);
  bool swappedCanPrecede(const Frag& q, const Frag& p);
  std::uint32_t splitPoint(std::uint32_t plane, std::uint32_t a, std::uint32_t b);
  void split(std::uint32_t frag, std::uint32_t plane);
  bool bisect(std::uint32_t frag);
  void insertExtra(std::uint32_t frag);
  void unstackFrom(std::uint32_t frag);
  void emit(std::uint32_t frag);
  bool resolveCycle(std::uint32_t p, std::uint32_t q);
  std::uint32_t head();
};

void Sorter::Impl::normalise(const PolygonMesh& mesh)
{
  const Box bounds = mesh.bounds();
  Origin = bounds.empty() ? glm::dvec3(0.0) : bounds.center();
  const double diagonal = bounds.diagonal();
  Tol = Cfg.relativeTolerance * (diagonal > 0.0 ? diagonal : 1.0);
  Norm.tolerance = Tol;
  InputPoints = mesh.points;
  InputLocal.resize(InputPoints.size());
  for (std::size_t i = 0; i < InputPoints.size(); ++i)
  {
    InputLocal[i] = InputPoints[i] - Origin;
  }
  detail::PolygonPieces pieces;
  detail::PieceCounts counts;
  detail::splitIntoPieces(mesh, InputLocal, Tol, pieces, counts);
  Norm.inputPolygons = mesh.polygonCount();
  Norm.invalidPolygons = counts.invalid;
  Norm.degeneratePolygons = counts.degenerate;
  Norm.triangulatedPolygons = counts.triangulated;
  PiecePlane = std::move(pieces.plane);
  PieceSource = std::move(pieces.source);
  PieceCount = std::move(pieces.count);
  PieceVerts = std::move(pieces.verts);
  PieceFirst.resize(PieceCount.size());
  std::uint32_t first = 0;
  for (std::size_t p = 0; p < PieceCount.size(); ++p)
  {
    PieceFirst[p] = first;
    first += PieceCount[p];
  }
  Norm.pieces = PieceSource.size();
}

void Sorter::Impl::computeView(Frag& f) const
{
  const std::uint32_t* ids = Verts.data() + f.first;
  if (Parallel)
  {
    double zmin = std::numeric_limits<double>::infinity();
    double zmax = -zmin;
    glm::dvec2 lo(zmin);
    glm::dvec2 hi(zmax);
    glm::dvec3 mean(0.0);
    for (std::uint32_t k = 0; k < f.count; ++k)
    {
      const glm::dvec3& p = Pts[ids[k]];
      const double z = glm::dot(p, Dir);
      zmin = std::min(zmin, z);
      zmax = std::max(zmax, z);
      const glm::dvec2 xy(glm::dot(p, ScreenU), glm::dot(p, ScreenV));
      lo = glm::min(lo, xy);
      hi = glm::max(hi, xy);
      mean += p;
    }
    mean /= static_cast<double>(f.count);
    double radius = 0.0;
    for (std::uint32_t k = 0; k < f.count; ++k)
    {
      radius = std::max(radius, glm::length(Pts[ids[k]] - mean));
    }
    f.zmin = zmin;
    f.zmax = zmax;
    f.axis = glm::dvec3(lo, 0.0);
    f.c = hi.x;
    f.s = hi.y;
    f.bounded = true;
    f.edgeOn = radius * std::abs(glm::dot(glm::dvec3(Planes[f.piece]), Dir)) <= Tol;
    return;
  }
  // Perspective: distances from the eye, and a bounding cone of directions.
  const glm::dvec4& plane = Planes[f.piece];
  const glm::dvec3 n(plane);
  const double h = glm::dot(n, Eye) + plane.w;
  f.edgeOn = std::abs(h) <= Tol;
  double zmax = 0.0;
  glm::dvec3 sum(0.0);
  bool nearEye = false;
  for (std::uint32_t k = 0; k < f.count; ++k)
  {
    const glm::dvec3 q = Pts[ids[k]] - Eye;
    const double d = glm::length(q);
    zmax = std::max(zmax, d);
    if (d <= Tol)
    {
      nearEye = true;
    }
    else
    {
      sum += q / d;
    }
  }
  // Nearest point: the foot of the perpendicular when it is inside, otherwise on an edge.
  const glm::dvec3 foot = Eye - h * n;
  bool inside = true;
  double zmin = std::numeric_limits<double>::infinity();
  for (std::uint32_t k = 0; k < f.count; ++k)
  {
    const glm::dvec3& a = Pts[ids[k]];
    const glm::dvec3& b = Pts[ids[k + 1 == f.count ? 0 : k + 1]];
    const glm::dvec3 e = b - a;
    if (glm::dot(glm::cross(e, foot - a), n) < 0.0)
    {
      inside = false;
    }
    const double ee = glm::dot(e, e);
    const double t = ee > 0.0 ? std::clamp(glm::dot(Eye - a, e) / ee, 0.0, 1.0) : 0.0;
    zmin = std::min(zmin, glm::length(Eye - (a + e * t)));
  }
  f.zmin = inside ? std::min(zmin, std::abs(h)) : zmin;
  f.zmax = zmax;
  f.bounded = false;
  const double sumLength = glm::length(sum);
  if (!nearEye && sumLength > 0.0)
  {
    f.axis = sum / sumLength;
    double c = 1.0;
    for (std::uint32_t k = 0; k < f.count; ++k)
    {
      const glm::dvec3 q = glm::normalize(Pts[ids[k]] - Eye);
      c = std::min(c, glm::dot(f.axis, q));
    }
    if (c > kMinConeCos)
    {
      // Widen by a few ulps so rounding of the directions cannot make touching cones disjoint.
      c = std::max(kMinConeCos, c - 1e-12);
      f.c = c;
      f.s = std::sqrt(std::max(0.0, 1.0 - c * c));
      f.bounded = true;
    }
  }
}

bool Sorter::Impl::extentsDisjoint(const Frag& p, const Frag& q) const
{
  if (Parallel)
  {
    // lo = axis.xy, hi = (c, s); touching boxes are not disjoint.
    return p.c < q.axis.x || q.c < p.axis.x || p.s < q.axis.y || q.s < p.axis.y;
  }
  if (!p.bounded || !q.bounded)
  {
    return false;
  }
  // angle(axes) > thetaP + thetaQ  <=>  cos(angle) < cos(thetaP + thetaQ) (both below 90 deg).
  return glm::dot(p.axis, q.axis) < p.c * q.c - p.s * q.s;
}

bool Sorter::Impl::projectionsDisjoint(const Frag& p, const Frag& q, bool& undecided)
{
  undecided = false;
  glm::dvec3 u;
  glm::dvec3 v;
  glm::dvec3 a;
  double eps = Tol;
  if (Parallel)
  {
    u = ScreenU;
    v = ScreenV;
    a = Dir;
  }
  else
  {
    if (!p.bounded || !q.bounded)
    {
      undecided = true;
      return false;
    }
    const glm::dvec3 sum = p.axis + q.axis;
    const double length = glm::length(sum);
    if (!(length > 1e-6))
    {
      undecided = true;
      return false;
    }
    a = sum / length;
    const double reachP = std::acos(std::clamp(glm::dot(a, p.axis), -1.0, 1.0)) + std::acos(p.c);
    const double reachQ = std::acos(std::clamp(glm::dot(a, q.axis), -1.0, 1.0)) + std::acos(q.c);
    if (!(reachP < kMaxProjectionAngle && reachQ < kMaxProjectionAngle))
    {
      undecided = true;
      return false;
    }
    planeBasis(a, u, v);
    // A width w in the image plane at distance 1 is at least w * t in the scene at distance t.
    eps = Tol / std::max({ p.zmax, q.zmax, Tol });
  }
  auto project = [&](const Frag& f, std::vector<glm::dvec2>& out)
  {
    out.resize(f.count);
    for (std::uint32_t k = 0; k < f.count; ++k)
    {
      const glm::dvec3& point = Pts[Verts[f.first + k]];
      if (Parallel)
      {
        out[k] = glm::dvec2(glm::dot(point, u), glm::dot(point, v));
      }
      else
      {
        const glm::dvec3 r = point - Eye;
        const double z = glm::dot(r, a);
        out[k] = glm::dvec2(glm::dot(r, u), glm::dot(r, v)) / z;
      }
    }
  };
  project(p, ProjA);
  project(q, ProjB);
  // Separating axis test over the edge normals of both convex images. Images that overlap by at
  // most eps (touching neighbours, rounding) count as disjoint.
  auto separatedBy = [&](const std::vector<glm::dvec2>& edges)
  {
    const std::size_t m = edges.size();
    for (std::size_t k = 0; k < m; ++k)
    {
      const glm::dvec2 e = edges[k + 1 == m ? 0 : k + 1] - edges[k];
      const double length = glm::length(e);
      if (!(length > 0.0))
      {
        continue;
      }
      const glm::dvec2 normal(-e.y / length, e.x / length);
      double loA = std::numeric_limits<double>::infinity();
      double hiA = -loA;
      double loB = loA;
      double hiB = -loA;
      for (const glm::dvec2& x : ProjA)
      {
        const double d = glm::dot(normal, x);
        loA = std::min(loA, d);
        hiA = std::max(hiA, d);
      }
      for (const glm::dvec2& x : ProjB)
      {
        const double d = glm::dot(normal, x);
        loB = std::min(loB, d);
        hiB = std::max(hiB, d);
      }
      if (hiA <= loB + eps || hiB <= loA + eps)
      {
        return true;
      }
    }
    return false;
  };
  return separatedBy(ProjA) || separatedBy(ProjB);
}

bool Sorter::Impl::canPrecede(const Frag& p, const Frag& q)
{
  ++St->pairs;
  ++St->depthExtent.evaluated;
  if (p.zmin >= q.zmax - Tol)
  {
    ++St->depthExtent.passed;
    return true;
  }
  ++St->screenExtent.evaluated;
  if (extentsDisjoint(p, q))
  {
    ++St->screenExtent.passed;
    return true;
  }
  if (p.edgeOn || q.edgeOn)
  {
    ++St->edgeOnPairs;
    return true;
  }
  ++St->behindPlane.evaluated;
  if (range(p, q.piece).hi <= Tol)
  {
    ++St->behindPlane.passed;
    return true;
  }
  ++St->inFrontOfPlane.evaluated;
  if (range(q, p.piece).lo >= -Tol)
  {
    ++St->inFrontOfPlane.passed;
    return true;
  }
  ++St->projection.evaluated;
  bool undecided = false;
  if (projectionsDisjoint(p, q, undecided))
  {
    ++St->projection.passed;
    return true;
  }
  if (undecided)
  {
    ++St->undecidedProjections;
  }
  return false;
}

bool Sorter::Impl::swappedCanPrecede(const Frag& q, const Frag& p)
{
  ++St->swapped.evaluated;
  const bool ok = q.zmin >= p.zmax - Tol || range(q, p.piece).hi <= Tol ||
    range(p, q.piece).lo >= -Tol;
  if (ok)
  {
    ++St->swapped.passed;
  }
  return ok;
}

std::uint32_t Sorter::Impl::splitPoint(std::uint32_t plane, std::uint32_t a, std::uint32_t b)
{
  const std::uint32_t lo = std::min(a, b);
  const std::uint32_t hi = std::max(a, b);
  const EdgeKey key{ lo, hi, plane };
  const auto found = Cache.find(key);
  if (found != Cache.end())
  {
    return found->second;
  }
  // Always from the smaller id, so every fragment with this edge gets the same bits.
  const double slo = distance(Planes[plane], lo);
  const double shi = distance(Planes[plane], hi);
  const double t = slo / (slo - shi);
  const glm::dvec3 localLo = Pts[lo];
  const glm::dvec3 localHi = Pts[hi];
  const glm::dvec3 worldLo = Out->points[lo];
  const glm::dvec3 worldHi = Out->points[hi];
  Pts.push_back(localLo + (localHi - localLo) * t);
  Out->points.push_back(worldLo + (worldHi - worldLo) * t);
  Out->splitPoints.push_back(bsp::SplitPoint{ lo, hi, t });
  const auto id = static_cast<std::uint32_t>(Out->points.size() - 1);
  Cache.emplace(key, id);
  return id;
}

void Sorter::Impl::unstackFrom(std::uint32_t frag)
{
  const std::uint32_t pos = Frags[frag].stackPos;
  if (pos == kNone)
  {
    return;
  }
  while (Stack.size() > pos)
  {
    Frags[Stack.back()].stackPos = kNone;
    Stack.pop_back();
  }
}

void Sorter::Impl::insertExtra(std::uint32_t frag)
{
  const Entry e{ Frags[frag].zmax, frag };
  const auto it = std::upper_bound(Extra.begin(), Extra.end(), e, before);
  const auto pos = static_cast<std::size_t>(it - Extra.begin());
  Extra.insert(it, e);
  if (pos < ExtraCursor)
  {
    ExtraCursor = pos;
  }
}

void Sorter::Impl::split(std::uint32_t frag, std::uint32_t plane)
{
  unstackFrom(frag);
  const Frag f = Frags[frag];
  FrontScratch.clear();
  BackScratch.clear();
  for (std::uint32_t k = 0; k < f.count; ++k)
  {
    const std::uint32_t id = Verts[f.first + k];
    const std::uint32_t next = Verts[f.first + (k + 1 == f.count ? 0 : k + 1)];
    const double dk = distance(Planes[plane], id);
    const double dn = distance(Planes[plane], next);
    const int ck = dk > Tol ? 1 : (dk < -Tol ? -1 : 0);
    const int cn = dn > Tol ? 1 : (dn < -Tol ? -1 : 0);
    if (ck >= 0)
    {
      FrontScratch.push_back(id);
    }
    if (ck <= 0)
    {
      BackScratch.push_back(id);
    }
    if (ck * cn < 0)
    {
      const std::uint32_t s = splitPoint(plane, id, next);
      FrontScratch.push_back(s);
      BackScratch.push_back(s);
    }
  }
  Frags[frag].alive = false;
  for (const std::vector<std::uint32_t>* part : { &BackScratch, &FrontScratch })
  {
    Frag piece;
    piece.piece = f.piece;
    piece.first = static_cast<std::uint32_t>(Verts.size());
    piece.count = static_cast<std::uint32_t>(part->size());
    Verts.insert(Verts.end(), part->begin(), part->end());
    computeView(piece);
    Frags.push_back(piece);
    insertExtra(static_cast<std::uint32_t>(Frags.size() - 1));
  }
  ++St->splits;
}

bool Sorter::Impl::bisect(std::uint32_t frag)
{
  const Frag& f = Frags[frag];
  glm::dvec3 mean(0.0);
  glm::dvec3 longest(0.0);
  for (std::uint32_t k = 0; k < f.count; ++k)
  {
    const glm::dvec3& a = Pts[Verts[f.first + k]];
    const glm::dvec3& b = Pts[Verts[f.first + (k + 1 == f.count ? 0 : k + 1)]];
    mean += a;
    if (glm::length(b - a) > glm::length(longest))
    {
      longest = b - a;
    }
  }
  mean /= static_cast<double>(f.count);
  if (!(glm::length(longest) > 0.0))
  {
    return false;
  }
  const glm::dvec3 n = glm::normalize(longest);
  Planes.emplace_back(n, -glm::dot(n, mean));
  EyeSign.push_back(1.0);
  const auto plane = static_cast<std::uint32_t>(Planes.size() - 1);
  if (!straddles(f, plane))
  {
    return false; // thinner than the tolerance
  }
  split(frag, plane);
  return true;
}

void Sorter::Impl::emit(std::uint32_t frag)
{
  Frag& f = Frags[frag];
  f.alive = false;
  if (f.stackPos != kNone)
  {
    unstackFrom(frag);
  }
  Out->fragments.push_back(bsp::Fragment{ PieceSource[f.piece],
    static_cast<std::uint32_t>(Out->fragmentVertices.size()), f.count });
  Out->fragmentVertices.insert(Out->fragmentVertices.end(), Verts.begin() + f.first,
    Verts.begin() + f.first + f.count);
}

std::uint32_t Sorter::Impl::head()
{
  if (!Stack.empty())
  {
    return Stack.back();
  }
  while (MainCursor < Main.size() && !Frags[Main[MainCursor].frag].alive)
  {
    ++MainCursor;
  }
  while (ExtraCursor < Extra.size() && !Frags[Extra[ExtraCursor].frag].alive)
  {
    ++ExtraCursor;
  }
  const bool haveMain = MainCursor < Main.size();
  const bool haveExtra = ExtraCursor < Extra.size();
  if (!haveMain && !haveExtra)
  {
    return kNone;
  }
  if (haveMain && (!haveExtra || before(Main[MainCursor], Extra[ExtraCursor])))
  {
    return Main[MainCursor].frag;
  }
  return Extra[ExtraCursor].frag;
}

bool Sorter::Impl::resolveCycle(std::uint32_t p, std::uint32_t q)
{
  // The cycle: q (marked, at stackPos) .. p (top). Prefer splitting q by p's plane, then p by
  // q's, then any member straddling another member's plane (nearest the top first).
  std::vector<std::uint32_t> members{ q, p };
  const std::size_t from = Frags[q].stackPos;
  for (std::size_t i = Stack.size(); i-- > from + 1 && members.size() < kMaxCycleSearch;)
  {
    if (Stack[i] != p)
    {
      members.push_back(Stack[i]);
    }
  }
  for (std::uint32_t x : members)
  {
    for (std::uint32_t y : members)
    {
      if (x != y && straddles(Frags[x], Frags[y].piece))
      {
        split(x, Frags[y].piece);
        return true;
      }
    }
  }
  if (bisect(q) || bisect(p))
  {
    ++St->fallbackSplits;
    return true;
  }
  return false;
}

void Sorter::Impl::run(const View& view, Result& result)
{
  const auto startTime = std::chrono::steady_clock::now();
  Out = &result;
  St = &result.statistics;
  result.statistics = Norm;
  result.fragments.clear();
  result.fragmentVertices.clear();
  result.points = InputPoints;
  result.inputPointCount = InputPoints.size();
  result.splitPoints.clear();

  const View local = view.relativeTo(Origin);
  Parallel = local.isParallel();
  Eye = glm::dvec3(local.eye);
  if (Parallel)
  {
    Dir = -glm::normalize(glm::dvec3(local.eye));
    planeBasis(Dir, ScreenU, ScreenV);
  }
  Pts = InputLocal;
  Planes = PiecePlane;
  const std::size_t pieces = PiecePlane.size();
  EyeSign.resize(pieces);
  for (std::size_t i = 0; i < pieces; ++i)
  {
    const glm::dvec4& pl = PiecePlane[i];
    const double side = pl.x * local.eye.x + pl.y * local.eye.y + pl.z * local.eye.z +
      pl.w * local.eye.w;
    EyeSign[i] = side >= 0.0 ? 1.0 : -1.0;
  }
  Verts = PieceVerts;
  Frags.clear();
  Frags.reserve(pieces + pieces / 4);
  Main.clear();
  Extra.clear();
  Stack.clear();
  Cache.clear();
  MainCursor = 0;
  ExtraCursor = 0;
  for (std::size_t i = 0; i < pieces; ++i)
  {
    Frag f;
    f.piece = static_cast<std::uint32_t>(i);
    f.first = PieceFirst[i];
    f.count = PieceCount[i];
    computeView(f);
    Frags.push_back(f);
    Main.push_back(Entry{ f.zmax, static_cast<std::uint32_t>(i) });
  }
  std::sort(Main.begin(), Main.end(), before);
  const double factor = std::max(0.0, Cfg.maxSplitsPerPolygon);
  MaxSplits = static_cast<std::size_t>(factor * static_cast<double>(pieces)) +
    (factor > 0.0 ? 64 : 0);

  if (!Cfg.newellTests)
  {
    for (const Entry& e : Main)
    {
      emit(e.frag);
    }
  }
  else
  {
    for (;;)
    {
      const std::uint32_t p = head();
      if (p == kNone)
      {
        break;
      }
      // Scan every other remaining fragment whose depth extent overlaps p's; both lists are
      // sorted by farthest depth, so the scan of each ends where test (1) passes.
      std::uint32_t conflict = kNone;
      const double limit = Frags[p].zmin + Tol;
      for (const std::vector<Entry>* list : { &Main, &Extra })
      {
        const std::size_t begin = list == &Main ? MainCursor : ExtraCursor;
        for (std::size_t i = begin; i < list->size(); ++i)
        {
          const Entry& e = (*list)[i];
          if (e.zmax <= limit)
          {
            ++St->depthExtent.evaluated;
            ++St->depthExtent.passed;
            break;
          }
          if (e.frag == p || !Frags[e.frag].alive)
          {
            continue;
          }
          if (!canPrecede(Frags[p], Frags[e.frag]))
          {
            conflict = e.frag;
            break;
          }
        }
        if (conflict != kNone)
        {
          break;
        }
      }
      if (conflict == kNone)
      {
        emit(p);
        continue;
      }
      const std::uint32_t q = conflict;
      const bool capped = St->splits >= MaxSplits;
      if (swappedCanPrecede(Frags[q], Frags[p]))
      {
        if (Frags[q].stackPos == kNone)
        {
          Frags[q].stackPos = static_cast<std::uint32_t>(Stack.size());
          Stack.push_back(q);
          ++St->moves;
          continue;
        }
        // q was moved before and would have to move again: a cycle.
        if (!capped && resolveCycle(p, q))
        {
          ++St->cyclesResolved;
          continue;
        }
      }
      else if (!capped)
      {
        // Neither may go first: split one by the other's plane.
        bool done = true;
        if (straddles(Frags[p], Frags[q].piece))
        {
          split(p, Frags[q].piece);
        }
        else if (straddles(Frags[q], Frags[p].piece))
        {
          split(q, Frags[p].piece);
        }
        else if (bisect(p))
        {
          ++St->fallbackSplits;
        }
        else
        {
          done = false;
        }
        if (done)
        {
          ++St->intersectionSplits;
          continue;
        }
      }
      ++St->forcedEmissions;
      emit(p);
    }
  }
  if (Cfg.conformingFragments)
  {
    St->conformingVertices = bsp::makeConforming(result.fragments, result.fragmentVertices,
      result.points, result.inputPointCount, result.splitPoints);
  }
  St->fragments = result.fragments.size();
  St->sortSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - startTime).count();
  Out = nullptr;
  St = nullptr;
}

Sorter::Sorter(const PolygonMesh& mesh, const Config& config)
  : P(std::make_unique<Impl>())
{
  P->Cfg = config;
  P->normalise(mesh);
}

Sorter::~Sorter() = default;
Sorter::Sorter(Sorter&&) noexcept = default;
Sorter& Sorter::operator=(Sorter&&) noexcept = default;

void Sorter::sort(const View& view, Result& result)
{
  P->run(view, result);
}

Result Sorter::sort(const View& view)
{
  Result result;
  P->run(view, result);
  return result;
}

const Statistics& Sorter::normalisation() const
{
  return P->Norm;
}

Result sort(const PolygonMesh& mesh, const View& view, const Config& config)
{
  Sorter sorter(mesh, config);
  return sorter.sort(view);
}

} // namespace painter
} // namespace scenevis
