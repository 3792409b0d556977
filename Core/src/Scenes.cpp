#include "scenevis/Scenes.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

namespace scenevis
{
namespace scenes
{

bool Scene::hasTranslucency() const
{
  return std::any_of(parts.begin(), parts.end(), [](const Part& p) { return p.opacity < 1.0; });
}

std::size_t triangleCount(const PolygonMesh& mesh)
{
  std::size_t count = 0;
  for (std::size_t i = 0; i < mesh.polygonCount(); ++i)
  {
    const std::uint32_t n = mesh.polygonSize(i);
    count += n >= 3 ? n - 2 : 0;
  }
  return count;
}

namespace
{

constexpr double kPi = 3.14159265358979323846;
constexpr std::uint32_t kMaxId = std::numeric_limits<std::uint32_t>::max();

/// splitmix64 (Steele, Lea, Flood 2014): tiny, fast, and its output is fixed by the algorithm, so
/// scenes are identical across compilers and standard libraries (std:: distributions are not).
class Random
{
public:
  explicit Random(std::uint64_t seed)
    : state_(seed)
  {
  }

  std::uint64_t next()
  {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  /// Uniform in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(next() >> 11) * (1.0 / 9007199254740992.0); }
  double uniform(double a, double b) { return a + (b - a) * uniform(); }
  /// Log-uniform in [a, b): as many 1-2 mm parts as 10-20 mm parts, like real assemblies.
  double logUniform(double a, double b) { return a * std::pow(b / a, uniform()); }
  /// Uniform integer in [0, n), n > 0.
  std::uint32_t below(std::uint32_t n)
  {
    return static_cast<std::uint32_t>(((next() >> 32) * n) >> 32);
  }
  bool chance(double p) { return uniform() < p; }

private:
  std::uint64_t state_;
};

glm::dvec3 clampColour(const glm::dvec3& c)
{
  return glm::clamp(c, glm::dvec3(0.0), glm::dvec3(1.0));
}

void checkIdRange(std::size_t points, std::size_t indices)
{
  if (points > kMaxId || indices > kMaxId)
  {
    throw std::length_error("scenevis::scenes: scene exceeds 32-bit point ids / offsets");
  }
}

/// Appends polygons while keeping `part` in step; used by every generator.
void addTriangle(PolygonMesh& mesh, std::uint32_t a, std::uint32_t b, std::uint32_t c)
{
  mesh.indices.push_back(a);
  mesh.indices.push_back(b);
  mesh.indices.push_back(c);
  mesh.offsets.push_back(static_cast<std::uint32_t>(mesh.indices.size()));
}

// ----------------------------------------------------------------------------------------------
// Surfaces of revolution: one engine for spheres and every CAD shape.
// ----------------------------------------------------------------------------------------------

/**
 * A profile in the (r, z) half-plane (x = r >= 0, y = z), revolved around the z axis. Traversed
 * counter-clockwise around the solid cross-section (interior on the left), which makes the
 * revolved triangles face outward (see revolve()). Open profiles start and end on the axis
 * (r == 0 exactly): those end points become single pole points, which keeps the surface closed
 * without degenerate triangles. Closed profiles (washers, tori) never touch the axis and do not
 * repeat their first point.
 */
struct Profile
{
  std::vector<glm::dvec2> points;
  bool closed = false;

  void start(const glm::dvec2& p, bool isClosed)
  {
    points.clear();
    points.push_back(p);
    closed = isClosed;
  }
  void lineTo(const glm::dvec2& p, int pieces)
  {
    const glm::dvec2 a = points.back();
    for (int k = 1; k <= pieces; ++k)
    {
      points.push_back(a + (p - a) * (static_cast<double>(k) / pieces));
    }
  }
  /// Arc around `centre` from the current point's angle a0 to a1 (radians, a1 > a0 = CCW).
  void arcTo(const glm::dvec2& centre, double radius, double a0, double a1, int pieces)
  {
    for (int k = 1; k <= pieces; ++k)
    {
      const double a = a0 + (a1 - a0) * (static_cast<double>(k) / pieces);
      points.push_back(centre + radius * glm::dvec2(std::cos(a), std::sin(a)));
    }
  }
  /// Ends a closed loop that came back to its start: drop the duplicate.
  void closeLoop() { points.pop_back(); }
  /// Open profiles: snap the end points onto the axis so the poles are exact.
  void snapPoles()
  {
    points.front().x = 0.0;
    points.back().x = 0.0;
  }

  std::size_t rings() const { return closed ? points.size() : points.size() - 2; }
  std::size_t triangles(int segments) const
  {
    // Closed: a quad band per profile edge. Open: the two pole edges give fans (1 triangle per
    // segment), every other edge a quad band (2 per segment): 2 * (n - 3) + 2 = 2 * (n - 2).
    return 2 * static_cast<std::size_t>(segments) * rings();
  }
  std::size_t pointCount(int segments) const
  {
    return static_cast<std::size_t>(segments) * rings() + (closed ? 0 : 2);
  }
};

/**
 * Emits the revolved surface: ring k is profile point k swept over `segments` angles starting
 * at `phase`, mapped to world by `linear * p + translation`. For a counter-clockwise profile the
 * surface derivative d/dtheta x d/dt points outward (e.g. the side of a cylinder at theta = 0:
 * +y x +z = +x), so each quad is wound (k, j), (k, j+1), (k+1, j+1), (k+1, j): theta first.
 * `linear` must have a positive determinant, or the winding would flip.
 */
void revolve(const Profile& profile,
             int segments,
             double phase,
             const glm::dmat3& linear,
             const glm::dvec3& translation,
             PolygonMesh& mesh,
             std::vector<glm::dvec2>& trig)
{
  trig.resize(static_cast<std::size_t>(segments));
  for (int j = 0; j < segments; ++j)
  {
    const double a = phase + 2.0 * kPi * j / segments;
    trig[static_cast<std::size_t>(j)] = glm::dvec2(std::cos(a), std::sin(a));
  }
  const auto base = static_cast<std::uint32_t>(mesh.points.size());
  const std::size_t n = profile.points.size();
  const auto segs = static_cast<std::uint32_t>(segments);
  auto emit = [&](const glm::dvec3& local) { mesh.points.push_back(linear * local + translation); };

  // Point ids: open profiles put the first pole first, then the rings, then the last pole.
  const std::size_t firstRing = profile.closed ? 0 : 1;
  const std::size_t lastRing = profile.closed ? n - 1 : n - 2;
  if (!profile.closed)
  {
    emit(glm::dvec3(0.0, 0.0, profile.points.front().y));
  }
  for (std::size_t k = firstRing; k <= lastRing; ++k)
  {
    const glm::dvec2 rz = profile.points[k];
    for (const glm::dvec2& cs : trig)
    {
      emit(glm::dvec3(rz.x * cs.x, rz.x * cs.y, rz.y));
    }
  }
  const std::uint32_t ringBase = base + (profile.closed ? 0u : 1u);
  const std::uint32_t lastPole = ringBase + static_cast<std::uint32_t>(profile.rings()) * segs;
  if (!profile.closed)
  {
    emit(glm::dvec3(0.0, 0.0, profile.points.back().y));
  }
  auto ring = [&](std::size_t k, std::uint32_t j)
  { return ringBase + static_cast<std::uint32_t>(k - firstRing) * segs + (j % segs); };

  const std::size_t edges = profile.closed ? n : n - 1;
  for (std::size_t e = 0; e < edges; ++e)
  {
    const std::size_t k0 = e;
    const std::size_t k1 = (e + 1) % n;
    for (std::uint32_t j = 0; j < segs; ++j)
    {
      if (!profile.closed && k0 == 0)
      {
        addTriangle(mesh, base, ring(k1, j + 1), ring(k1, j));
      }
      else if (!profile.closed && k1 == n - 1)
      {
        addTriangle(mesh, ring(k0, j), ring(k0, j + 1), lastPole);
      }
      else
      {
        addTriangle(mesh, ring(k0, j), ring(k0, j + 1), ring(k1, j + 1));
        addTriangle(mesh, ring(k0, j), ring(k1, j + 1), ring(k1, j));
      }
    }
  }
}

/// UV sphere resolution: stacks latitude bands, slices ~ 2 * stacks, closest to `triangles`.
std::pair<int, int> sphereResolution(std::size_t triangles)
{
  // Three indices per triangle must fit the 32-bit ids; checking here, before the int
  // conversions below, keeps huge requests from overflowing them.
  checkIdRange(0, triangles > kMaxId / 3 ? kMaxId + std::size_t(1) : 3 * triangles);
  const double t = static_cast<double>(triangles);
  const int stacks = std::max(2, static_cast<int>(std::lround(std::sqrt(t / 4.0) + 0.5)));
  const int slices =
    std::max(3, static_cast<int>(std::lround(t / (2.0 * static_cast<double>(stacks - 1)))));
  return { slices, stacks };
}

void sphereProfile(double radius, int stacks, Profile& profile)
{
  profile.start(glm::dvec2(0.0, -radius), false);
  profile.arcTo(glm::dvec2(0.0), radius, -0.5 * kPi, 0.5 * kPi, stacks);
  profile.snapPoles();
}

Box boundsOf(const PolygonMesh& mesh, std::size_t firstPoint)
{
  Box box;
  for (std::size_t i = firstPoint; i < mesh.points.size(); ++i)
  {
    box.extend(mesh.points[i]);
  }
  return box;
}

} // namespace

// ---------------------------------------------------------------------------------------------
// (a) Spheres
// ---------------------------------------------------------------------------------------------

PolygonMesh sphere(const glm::dvec3& center, double radius, std::size_t triangles)
{
  if (!(radius > 0.0))
  {
    throw std::invalid_argument("scenevis::scenes::sphere: radius must be positive");
  }
  const auto [slices, stacks] = sphereResolution(triangles);
  Profile profile;
  sphereProfile(radius, stacks, profile);
  checkIdRange(profile.pointCount(slices), 3 * profile.triangles(slices));
  PolygonMesh mesh;
  mesh.points.reserve(profile.pointCount(slices));
  mesh.indices.reserve(3 * profile.triangles(slices));
  mesh.offsets.reserve(profile.triangles(slices) + 1);
  std::vector<glm::dvec2> trig;
  revolve(profile, slices, 0.0, glm::dmat3(1.0), center, mesh, trig);
  return mesh;
}

std::size_t trianglesPerSphereFor(std::size_t total, int n)
{
  if (n < 1)
  {
    throw std::invalid_argument("scenevis::scenes::trianglesPerSphereFor: n must be >= 1");
  }
  const auto count =
    static_cast<std::size_t>(n) * static_cast<std::size_t>(n) * static_cast<std::size_t>(n);
  return std::max<std::size_t>(1, (total + count / 2) / count);
}

Scene sphereGrid(int n, double radius, double spacing, std::size_t trianglesPerSphere)
{
  if (n < 1 || !(radius > 0.0) || !(spacing > 0.0))
  {
    throw std::invalid_argument("scenevis::scenes::sphereGrid: n, radius, spacing must be > 0");
  }
  const auto [slices, stacks] = sphereResolution(trianglesPerSphere);
  Profile profile;
  sphereProfile(radius, stacks, profile);
  const auto count =
    static_cast<std::size_t>(n) * static_cast<std::size_t>(n) * static_cast<std::size_t>(n);
  const std::size_t triangles = count * profile.triangles(slices);
  checkIdRange(count * profile.pointCount(slices), 3 * triangles);

  Scene scene;
  scene.mesh.points.reserve(count * profile.pointCount(slices));
  scene.mesh.indices.reserve(3 * triangles);
  scene.mesh.offsets.reserve(triangles + 1);
  scene.part.reserve(triangles);
  scene.parts.reserve(count);
  std::vector<glm::dvec2> trig;
  const double half = 0.5 * (n - 1);
  const double colourStep = n > 1 ? 0.8 / (n - 1) : 0.0;
  for (int k = 0; k < n; ++k)
  {
    for (int j = 0; j < n; ++j)
    {
      for (int i = 0; i < n; ++i)
      {
        const glm::dvec3 center = (glm::dvec3(i, j, k) - half) * spacing;
        const std::size_t firstPoint = scene.mesh.points.size();
        Part part;
        part.name =
          "sphere " + std::to_string(i) + "," + std::to_string(j) + "," + std::to_string(k);
        part.colour = glm::dvec3(0.2) + colourStep * glm::dvec3(i, j, k);
        part.opacity = 0.3;
        part.firstPolygon = static_cast<std::uint32_t>(scene.mesh.polygonCount());
        revolve(profile, slices, 0.0, glm::dmat3(1.0), center, scene.mesh, trig);
        part.polygonCount =
          static_cast<std::uint32_t>(scene.mesh.polygonCount()) - part.firstPolygon;
        part.bounds = boundsOf(scene.mesh, firstPoint);
        scene.part.insert(
          scene.part.end(), part.polygonCount, static_cast<std::uint32_t>(scene.parts.size()));
        scene.parts.push_back(std::move(part));
      }
    }
  }
  return scene;
}

// ---------------------------------------------------------------------------------------------
// (b) Adversarial configurations
// ---------------------------------------------------------------------------------------------

namespace
{

/// Adds a one-polygon part made of fresh points.
void addPolygonPart(Scene& scene,
                    const std::vector<glm::dvec3>& corners,
                    const char* name,
                    const glm::dvec3& colour,
                    double opacity)
{
  std::vector<std::uint32_t> ids;
  for (const glm::dvec3& p : corners)
  {
    ids.push_back(scene.mesh.addPoint(p));
  }
  Part part;
  part.name = name;
  part.colour = colour;
  part.opacity = opacity;
  part.firstPolygon = scene.mesh.addPolygon(ids.data(), ids.size());
  part.polygonCount = 1;
  for (const glm::dvec3& p : corners)
  {
    part.bounds.extend(p);
  }
  scene.part.push_back(static_cast<std::uint32_t>(scene.parts.size()));
  scene.parts.push_back(std::move(part));
}

} // namespace

Scene cyclicQuads()
{
  // Strip i runs along the triangle edge V_i -> V_{i+1}, extended past both corners, rising from
  // z = -h at its start to +h at its end. Near corner V_{i+1} strip i is at its high end and
  // strip i+1 at its low end, so i lies above i+1 there: the cycle 0 > 1 > 2 > 0. The overlap
  // regions are small compared to the strip length, so the separation there stays about h.
  constexpr double extension = 0.35;
  constexpr double halfWidth = 0.18;
  constexpr double h = 0.3;
  std::array<glm::dvec2, 3> v;
  for (int i = 0; i < 3; ++i)
  {
    const double a = 0.5 * kPi + 2.0 * kPi * i / 3.0;
    v[static_cast<std::size_t>(i)] = glm::dvec2(std::cos(a), std::sin(a));
  }
  const std::array<const char*, 3> names{ "quad 0", "quad 1", "quad 2" };
  const std::array<glm::dvec3, 3> colours{ glm::dvec3(0.9, 0.15, 0.1),
                                           glm::dvec3(0.1, 0.8, 0.2),
                                           glm::dvec3(0.15, 0.3, 0.95) };
  Scene scene;
  for (std::size_t i = 0; i < 3; ++i)
  {
    const glm::dvec2 d = glm::normalize(v[(i + 1) % 3] - v[i]);
    const glm::dvec2 left(-d.y, d.x);
    const glm::dvec2 s = v[i] - extension * d;
    const glm::dvec2 e = v[(i + 1) % 3] + extension * d;
    // Right edge first, then the left one: counter-clockwise seen from +z.
    const std::vector<glm::dvec3> corners{ glm::dvec3(s - halfWidth * left, -h),
                                           glm::dvec3(e - halfWidth * left, h),
                                           glm::dvec3(e + halfWidth * left, h),
                                           glm::dvec3(s + halfWidth * left, -h) };
    addPolygonPart(scene, corners, names[i], colours[i], 0.5);
  }
  return scene;
}

Scene interpenetratingTriangles()
{
  // A lies in the plane z = y / 2, B in z = -y / 2: they cross on the line y = z = 0, where A
  // covers x in [-0.62, 0.22] and B covers [-0.22, 0.62]. The common segment [-0.22, 0.22] ends
  // on an edge of each, so each triangle has an edge piercing the other's interior.
  Scene scene;
  addPolygonPart(
    scene,
    { glm::dvec3(-1.0, -0.8, -0.4), glm::dvec3(0.6, -0.8, -0.4), glm::dvec3(-0.2, 0.9, 0.45) },
    "triangle A",
    glm::dvec3(1.0, 0.55, 0.1),
    0.5);
  addPolygonPart(
    scene,
    { glm::dvec3(0.2, -0.9, 0.45), glm::dvec3(1.0, 0.8, -0.4), glm::dvec3(-0.6, 0.8, -0.4) },
    "triangle B",
    glm::dvec3(0.1, 0.8, 0.9),
    0.5);
  return scene;
}

// ---------------------------------------------------------------------------------------------
// (c) CAD assembly
// ---------------------------------------------------------------------------------------------

namespace
{

enum class Kind : std::uint8_t
{
  Baseplate,
  Housing,
  Screw,
  Washer,
  Nut,
  Cylinder,
  Block,
  Ball,
  Ring,
  Knob
};

const char* kindName(Kind kind)
{
  switch (kind)
  {
    case Kind::Baseplate:
      return "baseplate";
    case Kind::Housing:
      return "housing";
    case Kind::Screw:
      return "screw";
    case Kind::Washer:
      return "washer";
    case Kind::Nut:
      return "nut";
    case Kind::Cylinder:
      return "cylinder";
    case Kind::Block:
      return "block";
    case Kind::Ball:
      return "ball";
    case Kind::Ring:
      return "ring";
    case Kind::Knob:
      return "knob";
  }
  return "part";
}

bool isBox(Kind kind)
{
  return kind == Kind::Baseplate || kind == Kind::Housing || kind == Kind::Block;
}

/// Everything needed to emit one part; ~120 bytes, so 100k parts cost 12 MB.
struct PartSpec
{
  Kind kind = Kind::Block;
  /// Shape parameters (mm), meaning per kind; boxes: half extents.
  double a = 1.0, b = 1.0, c = 1.0;
  glm::dmat3 linear{ 1.0 };
  glm::dvec3 translation{ 0.0 };
  glm::dvec3 colour{ 1.0 };
  double opacity = 1.0;
  double weight = 1.0; ///< Share of the triangle budget.
  int segments = 8;
  int sub = 1;
};

/// Builds the kind's profile at resolution (segments, sub); returns the revolve phase.
double buildProfile(const PartSpec& s, int segments, int sub, Profile& p)
{
  const int arcPieces = std::max(2, segments / 2);
  switch (s.kind)
  {
    case Kind::Baseplate:
    case Kind::Housing:
    case Kind::Block:
    {
      // Unit box as a 4-sided revolution: corners at radius sqrt(2), phase 45 degrees, so the
      // square is [-1, 1]^2; PartSpec::linear scales it to the half extents.
      const double r = std::sqrt(2.0);
      p.start(glm::dvec2(0.0, -1.0), false);
      p.lineTo(glm::dvec2(r, -1.0), sub);
      p.lineTo(glm::dvec2(r, 1.0), sub);
      p.lineTo(glm::dvec2(0.0, 1.0), sub);
      p.snapPoles();
      return 0.25 * kPi;
    }
    case Kind::Screw:
    {
      // a = shank radius, b = shank length, c = head radius; chamfered tip, flat head.
      const double head = 0.7 * s.c;
      p.start(glm::dvec2(0.0, 0.0), false);
      p.lineTo(glm::dvec2(0.7 * s.a, 0.0), 1);
      p.lineTo(glm::dvec2(s.a, 0.3 * s.a), 1);
      p.lineTo(glm::dvec2(s.a, s.b), sub);
      p.lineTo(glm::dvec2(s.c, s.b), 1);
      p.lineTo(glm::dvec2(s.c, s.b + head), 1);
      p.lineTo(glm::dvec2(0.0, s.b + head), std::max(1, sub / 2));
      p.snapPoles();
      return 0.0;
    }
    case Kind::Washer:
    case Kind::Nut:
    {
      // a = inner radius, b = outer radius, c = thickness; a rectangle swept into an annulus.
      p.start(glm::dvec2(s.a, 0.0), true);
      p.lineTo(glm::dvec2(s.b, 0.0), sub);
      p.lineTo(glm::dvec2(s.b, s.c), sub);
      p.lineTo(glm::dvec2(s.a, s.c), sub);
      p.lineTo(glm::dvec2(s.a, 0.0), sub);
      p.closeLoop();
      return 0.0;
    }
    case Kind::Cylinder:
    {
      // a = radius, b = half length.
      const int cap = std::max(1, sub / 2);
      p.start(glm::dvec2(0.0, -s.b), false);
      p.lineTo(glm::dvec2(s.a, -s.b), cap);
      p.lineTo(glm::dvec2(s.a, s.b), sub);
      p.lineTo(glm::dvec2(0.0, s.b), cap);
      p.snapPoles();
      return 0.0;
    }
    case Kind::Ball:
      sphereProfile(s.a, arcPieces, p);
      return 0.0;
    case Kind::Ring:
    {
      // a = major radius, b = minor radius: a torus (o-ring).
      p.start(glm::dvec2(s.a + s.b, 0.0), true);
      p.arcTo(glm::dvec2(s.a, 0.0), s.b, 0.0, 2.0 * kPi, std::max(3, arcPieces));
      p.closeLoop();
      return 0.0;
    }
    case Kind::Knob:
    {
      // a = bottom radius, b = top radius, c = height: a frustum.
      const int cap = std::max(1, sub / 2);
      p.start(glm::dvec2(0.0, 0.0), false);
      p.lineTo(glm::dvec2(s.a, 0.0), cap);
      p.lineTo(glm::dvec2(s.b, s.c), sub);
      p.lineTo(glm::dvec2(0.0, s.c), cap);
      p.snapPoles();
      return 0.0;
    }
  }
  return 0.0;
}

/// Picks (segments, sub) for about `budget` triangles and stores them in `s`; returns the count.
std::size_t chooseResolution(PartSpec& s, double budget, Profile& p)
{
  constexpr int kMaxSub = 4096;
  if (isBox(s.kind) || s.kind == Kind::Nut)
  {
    // Fixed polygonal cross-section; only the profile subdivision can grow.
    s.segments = s.kind == Kind::Nut ? 6 : 4;
  }
  else
  {
    // Round parts: about as many segments around as the square root of the budget, so the
    // triangles stay roughly square; at least 8 so that small parts still look round.
    const double segs = std::sqrt(std::max(budget, 1.0));
    s.segments = std::clamp(2 * static_cast<int>(std::lround(0.5 * segs)), 8, 1024);
  }
  // The count is affine in sub for a fixed segment count: solve from two samples.
  buildProfile(s, s.segments, 1, p);
  const auto t1 = static_cast<double>(p.triangles(s.segments));
  buildProfile(s, s.segments, 2, p);
  const double slope = static_cast<double>(p.triangles(s.segments)) - t1;
  s.sub = 1;
  if (slope > 0.0 && budget > t1)
  {
    s.sub = std::clamp(1 + static_cast<int>(std::lround((budget - t1) / slope)), 1, kMaxSub);
  }
  buildProfile(s, s.segments, s.sub, p);
  return p.triangles(s.segments);
}

/// Rotation taking local +z to world +z (axis 0), +x (1) or +y (2), then turning by `angle`
/// about world z. Proper rotations only (det = +1): revolve() relies on it for the winding.
glm::dmat3 orientation(int axis, double angle)
{
  glm::dmat3 lie(1.0); // columns are the images of local x, y, z
  if (axis == 1)
  {
    lie = glm::dmat3(glm::dvec3(0, 0, -1), glm::dvec3(0, 1, 0), glm::dvec3(1, 0, 0));
  }
  else if (axis == 2)
  {
    lie = glm::dmat3(glm::dvec3(1, 0, 0), glm::dvec3(0, 0, -1), glm::dvec3(0, 1, 0));
  }
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  const glm::dmat3 turn(glm::dvec3(c, s, 0), glm::dvec3(-s, c, 0), glm::dvec3(0, 0, 1));
  return turn * lie;
}

/// Local z range and maximum radius of a non-box kind, for standing parts on the board.
void localExtent(const PartSpec& s, double& zmin, double& zmax, double& rmax)
{
  switch (s.kind)
  {
    case Kind::Screw:
      zmin = 0.0;
      zmax = s.b + 0.7 * s.c;
      rmax = s.c;
      return;
    case Kind::Washer:
    case Kind::Nut:
      zmin = 0.0;
      zmax = s.c;
      rmax = s.b;
      return;
    case Kind::Cylinder:
      zmin = -s.b;
      zmax = s.b;
      rmax = s.a;
      return;
    case Kind::Ball:
      zmin = -s.a;
      zmax = s.a;
      rmax = s.a;
      return;
    case Kind::Ring:
      zmin = -s.b;
      zmax = s.b;
      rmax = s.a + s.b;
      return;
    case Kind::Knob:
      zmin = 0.0;
      zmax = s.c;
      rmax = std::max(s.a, s.b);
      return;
    default:
      zmin = -s.c;
      zmax = s.c;
      rmax = std::max(s.a, s.b);
      return;
  }
}

/// Random shape parameters and appearance of a small part.
void randomSmallPart(PartSpec& s, Random& rng)
{
  const double pick = rng.uniform();
  if (pick < 0.25)
  {
    s.kind = Kind::Screw;
    s.a = rng.logUniform(0.8, 4.0);
    s.b = s.a * rng.uniform(3.0, 10.0);
    s.c = s.a * 1.8;
    s.colour = glm::dvec3(0.72, 0.72, 0.75);
  }
  else if (pick < 0.40)
  {
    s.kind = Kind::Washer;
    s.a = rng.logUniform(1.0, 5.0);
    s.b = s.a * rng.uniform(1.8, 2.4);
    s.c = s.a * rng.uniform(0.15, 0.3);
    s.colour = glm::dvec3(0.8, 0.68, 0.35);
  }
  else if (pick < 0.50)
  {
    s.kind = Kind::Nut;
    s.a = rng.logUniform(1.0, 5.0);
    s.b = 2.0 * s.a;
    s.c = 1.6 * s.a;
    s.colour = glm::dvec3(0.45, 0.45, 0.5);
  }
  else if (pick < 0.65)
  {
    s.kind = Kind::Cylinder;
    s.a = rng.logUniform(0.8, 8.0);
    s.b = s.a * rng.uniform(0.5, 3.0);
    static const std::array<glm::dvec3, 4> palette{ glm::dvec3(0.2, 0.3, 0.8),
                                                    glm::dvec3(0.85, 0.85, 0.8),
                                                    glm::dvec3(0.3, 0.3, 0.3),
                                                    glm::dvec3(0.7, 0.4, 0.2) };
    s.colour = palette[rng.below(4)];
  }
  else if (pick < 0.80)
  {
    s.kind = Kind::Block;
    s.a = rng.logUniform(0.75, 7.5);
    s.b = rng.logUniform(0.75, 7.5);
    s.c = rng.logUniform(0.25, 3.0);
    s.colour = rng.chance(0.6) ? glm::dvec3(0.15, 0.15, 0.17) : glm::dvec3(0.55, 0.5, 0.45);
  }
  else if (pick < 0.88)
  {
    s.kind = Kind::Ball;
    s.a = rng.logUniform(0.8, 8.0);
    s.colour = glm::dvec3(0.8, 0.2, 0.15);
  }
  else if (pick < 0.95)
  {
    s.kind = Kind::Ring;
    s.a = rng.logUniform(2.0, 12.0);
    s.b = s.a * rng.uniform(0.1, 0.25);
    s.colour = glm::dvec3(0.1, 0.1, 0.1);
  }
  else
  {
    s.kind = Kind::Knob;
    s.a = rng.logUniform(2.0, 10.0);
    s.b = s.a * rng.uniform(0.5, 0.9);
    s.c = s.a * rng.uniform(0.5, 1.5);
    s.colour = glm::dvec3(0.9, 0.5, 0.1);
  }
  // A little per-part variation so neighbouring parts of one kind can be told apart.
  s.colour = clampColour(s.colour * rng.uniform(0.85, 1.15));
}

/// Characteristic size (mm) of a part, for the triangle budget.
double partSize(const PartSpec& s)
{
  double zmin = 0.0, zmax = 0.0, rmax = 0.0;
  localExtent(s, zmin, zmax, rmax);
  return std::max(zmax - zmin, 2.0 * rmax);
}

} // namespace

Scene cadAssembly(std::size_t parts,
                  std::size_t trianglesPerPart,
                  std::uint64_t seed,
                  const glm::dvec3& origin)
{
  if (parts < 1 || trianglesPerPart < 1)
  {
    throw std::invalid_argument("scenevis::scenes::cadAssembly: parts and trianglesPerPart >= 1");
  }
  if (parts > kMaxId)
  {
    throw std::length_error("scenevis::scenes::cadAssembly: too many parts");
  }
  Random rng(seed);
  constexpr double kPitch = 20.0;         // grid cell, mm
  constexpr double kBoardHalfThick = 0.8; // a 1.6 mm board, top face at z = 0
  const std::size_t housings = std::min<std::size_t>(1 + parts / 5000, parts - 1);
  const std::size_t small = parts - 1 - housings;
  const auto grid = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(small))));
  const double half = 0.5 * kPitch * static_cast<double>(std::max<std::size_t>(grid, 4));

  // Pass 1: shapes, placements and budget weights. All random draws happen here, in part order,
  // so the resolution passes below cannot change the scene's layout.
  std::vector<PartSpec> specs(parts);
  {
    PartSpec& board = specs[0];
    board.kind = Kind::Baseplate;
    board.a = half + 10.0;
    board.b = half + 10.0;
    board.c = kBoardHalfThick;
    board.linear =
      glm::dmat3(glm::dvec3(board.a, 0, 0), glm::dvec3(0, board.b, 0), glm::dvec3(0, 0, board.c));
    board.translation = glm::dvec3(0.0, 0.0, -kBoardHalfThick);
    board.colour = glm::dvec3(0.1, 0.4, 0.2);
  }
  for (std::size_t h = 1; h <= housings; ++h)
  {
    PartSpec& s = specs[h];
    s.kind = Kind::Housing;
    s.a = rng.uniform(30.0, 100.0);
    s.b = rng.uniform(30.0, 100.0);
    s.c = rng.uniform(20.0, 60.0);
    const double angle = rng.uniform(0.0, 2.0 * kPi);
    const glm::dvec2 at(rng.uniform(-half, half), rng.uniform(-half, half));
    s.linear = orientation(0, angle) *
               glm::dmat3(glm::dvec3(s.a, 0, 0), glm::dvec3(0, s.b, 0), glm::dvec3(0, 0, s.c));
    s.translation = glm::dvec3(at, s.c);
    s.colour = clampColour(glm::dvec3(0.6, 0.65, 0.75) * rng.uniform(0.9, 1.1));
    // Every other housing is translucent, hiding nested parts only partly: sorting work.
    s.opacity = (h % 2 == 1) ? 0.35 : 1.0;
  }
  for (std::size_t i = 0; i < small; ++i)
  {
    PartSpec& s = specs[1 + housings + i];
    randomSmallPart(s, rng);
    if (rng.chance(0.02))
    {
      s.opacity = 0.5;
    }
    const int axis =
      (s.kind == Kind::Cylinder || s.kind == Kind::Ring) ? static_cast<int>(rng.below(3)) : 0;
    const double angle = rng.uniform(0.0, 2.0 * kPi);
    glm::dmat3 scale(1.0);
    if (isBox(s.kind))
    {
      scale = glm::dmat3(glm::dvec3(s.a, 0, 0), glm::dvec3(0, s.b, 0), glm::dvec3(0, 0, s.c));
    }
    s.linear = orientation(axis, angle) * scale;
    double zmin = 0.0, zmax = 0.0, rmax = 0.0;
    localExtent(s, zmin, zmax, rmax);
    if (rng.chance(0.2))
    {
      // Nested: somewhere inside a housing (mounted at any height), overlapping freely.
      const PartSpec& box = specs[1 + rng.below(static_cast<std::uint32_t>(housings))];
      const glm::dvec3 local(
        rng.uniform(-0.8, 0.8), rng.uniform(-0.8, 0.8), rng.uniform(-0.8, 0.8));
      s.translation = box.linear * local + box.translation;
    }
    else
    {
      // On the board: a jittered grid cell; parts up to 2 pitches wide overlap neighbours.
      const double cx = (static_cast<double>(i % grid) + 0.5) * kPitch - half;
      const double cy = (static_cast<double>(i / grid) + 0.5) * kPitch - half;
      const glm::dvec2 at(cx + rng.uniform(-0.35, 0.35) * kPitch,
                          cy + rng.uniform(-0.35, 0.35) * kPitch);
      // Standing parts rest on their lowest local z; lying ones on their radius.
      const double lift = axis == 0 ? -zmin * (isBox(s.kind) ? s.c : 1.0) : rmax;
      s.translation = glm::dvec3(at, lift);
    }
  }
  for (PartSpec& s : specs)
  {
    // Bigger parts get finer tessellation, but sub-linearly (as CAD exporters do with a
    // chordal tolerance): a 100 mm housing gets ~5x the triangles of a 4 mm screw.
    s.weight = std::sqrt(std::max(partSize(s), 0.5));
    s.translation += origin;
  }

  // Pass 2: share the triangle budget. Floors (a box needs 16 triangles) make the total a
  // non-linear function of the scale, so a few fixed-point steps bring it close to the target.
  Profile profile;
  const double target = static_cast<double>(parts) * static_cast<double>(trianglesPerPart);
  double weightSum = 0.0;
  for (const PartSpec& s : specs)
  {
    weightSum += s.weight;
  }
  double scale = target / weightSum;
  std::size_t triangles = 0;
  for (int iteration = 0; iteration < 4; ++iteration)
  {
    triangles = 0;
    for (PartSpec& s : specs)
    {
      triangles += chooseResolution(s, scale * s.weight, profile);
    }
    scale *= target / static_cast<double>(triangles);
  }
  std::size_t pointTotal = 0;
  for (PartSpec& s : specs)
  {
    buildProfile(s, s.segments, s.sub, profile);
    pointTotal += profile.pointCount(s.segments);
  }
  checkIdRange(pointTotal, 3 * triangles);

  // Pass 3: emit into exactly reserved storage (10M triangles: no reallocation copies).
  Scene scene;
  scene.mesh.points.reserve(pointTotal);
  scene.mesh.indices.reserve(3 * triangles);
  scene.mesh.offsets.reserve(triangles + 1);
  scene.part.reserve(triangles);
  scene.parts.reserve(parts);
  std::vector<glm::dvec2> trig;
  for (std::size_t i = 0; i < parts; ++i)
  {
    const PartSpec& s = specs[i];
    const double phase = buildProfile(s, s.segments, s.sub, profile);
    const std::size_t firstPoint = scene.mesh.points.size();
    Part part;
    part.name = i == 0 ? std::string(kindName(s.kind))
                       : std::string(kindName(s.kind)) + "#" + std::to_string(i);
    part.colour = s.colour;
    part.opacity = s.opacity;
    part.firstPolygon = static_cast<std::uint32_t>(scene.mesh.polygonCount());
    revolve(profile, s.segments, phase, s.linear, s.translation, scene.mesh, trig);
    part.polygonCount = static_cast<std::uint32_t>(scene.mesh.polygonCount()) - part.firstPolygon;
    part.bounds = boundsOf(scene.mesh, firstPoint);
    scene.part.insert(scene.part.end(), part.polygonCount, static_cast<std::uint32_t>(i));
    scene.parts.push_back(std::move(part));
  }
  return scene;
}

// ---------------------------------------------------------------------------------------------
// (d) Building
// ---------------------------------------------------------------------------------------------

namespace
{

/// Corners of {a*u + b*v + c*(u x v) : a in [a0, a1], b in [b0, b1]}, counter-clockwise
/// around u x v. u, v are orthonormal; c is the plane's offset along the normal u x v.
std::array<glm::dvec3, 4> rectCorners(const glm::dvec3& u,
                                      const glm::dvec3& v,
                                      double c,
                                      double a0,
                                      double a1,
                                      double b0,
                                      double b1)
{
  const glm::dvec3 n = glm::cross(u, v) * c;
  return { a0 * u + b0 * v + n, a1 * u + b0 * v + n, a1 * u + b1 * v + n, a0 * u + b1 * v + n };
}

/// One output part while it is being built: polygons and their room ids.
struct Layer
{
  PolygonMesh mesh;
  std::vector<std::int32_t> room;

  /// Adds rectCorners(...) as a quad. Every building polygon goes through here, so the facing
  /// rule lives in one place: to face along n, pick (u, v) with u x v = n.
  void rect(const glm::dvec3& u,
            const glm::dvec3& v,
            double c,
            double a0,
            double a1,
            double b0,
            double b1,
            std::int32_t roomId)
  {
    if (a1 - a0 <= 1e-9 || b1 - b0 <= 1e-9)
    {
      return; // an opening flush with an edge leaves no piece on that side
    }
    const std::array<glm::dvec3, 4> q = rectCorners(u, v, c, a0, a1, b0, b1);
    const std::uint32_t first = mesh.addPoint(q[0]);
    mesh.addPoint(q[1]);
    mesh.addPoint(q[2]);
    mesh.addPoint(q[3]);
    mesh.addPolygon({ first, first + 1, first + 2, first + 3 });
    room.push_back(roomId);
  }

  /// Adds a polygon with points of its own.
  void polygon(const std::vector<glm::dvec3>& pts, std::int32_t roomId)
  {
    std::array<std::uint32_t, 8> ids{};
    const std::size_t count = std::min(pts.size(), ids.size());
    for (std::size_t k = 0; k < count; ++k)
    {
      ids[k] = mesh.addPoint(pts[k]);
    }
    mesh.addPolygon(ids.data(), count);
    room.push_back(roomId);
  }

  /**
   * A face in the plane x[n] = c (facing +n if @p positive, else -n), cut into the cells of the
   * grid A x B (sorted lines along axes a = (n+1)%3 and b = (n+2)%3, first and last = its
   * extent), minus the cell @p hole {a0, a1, b0, b1} (values taken from A and B) if given.
   * @p extras lists, per border (b = B.front(), b = B.back(), a = A.front(), a = A.back()), the
   * coordinates of the neighbouring face's vertices on it: a cell whose border side contains
   * some is emitted as a fan of triangles (from a corner whose sides have none, else from its
   * centre), so that it has a vertex wherever the neighbour does (no T-junction, hence no
   * rasterisation crack); other cells are quads.
   * Every coordinate comes from A, B, c or @p extras unchanged, so shared vertices are
   * bit-identical.
   */
  void grid(int n, double c, bool positive, const std::vector<double>& A,
    const std::vector<double>& B, const double* hole,
    const std::array<const std::vector<double>*, 4>& extras, std::int32_t roomId)
  {
    const int a = (n + 1) % 3;
    const int b = (n + 2) % 3;
    auto point = [&](double va, double vb)
    {
      glm::dvec3 p(0.0);
      p[n] = c;
      p[a] = va;
      p[b] = vb;
      return p;
    };
    std::vector<glm::dvec3> ring;
    for (std::size_t j = 0; j + 1 < B.size(); ++j)
    {
      for (std::size_t i = 0; i + 1 < A.size(); ++i)
      {
        const double a0 = A[i], a1 = A[i + 1], b0 = B[j], b1 = B[j + 1];
        if (hole && a0 == hole[0] && a1 == hole[1] && b0 == hole[2] && b1 == hole[3])
        {
          continue;
        }
        // Counter-clockwise in (a, b): along b0, up a1, back along b1, down a0.
        auto add = [&](const std::vector<double>* values, double lo, double hi, bool ascending,
                     bool alongA, double fixed)
        {
          if (!values)
          {
            return;
          }
          const std::size_t first = ring.size();
          for (const double v : *values)
          {
            if (v > lo && v < hi)
            {
              ring.push_back(alongA ? point(v, fixed) : point(fixed, v));
            }
          }
          // Values are sorted ascending; walk them the way the ring goes.
          if (!ascending)
          {
            std::reverse(ring.begin() + static_cast<std::ptrdiff_t>(first), ring.end());
          }
        };
        ring.clear();
        std::array<std::size_t, 4> corner{};
        corner[0] = ring.size();
        ring.push_back(point(a0, b0));
        add(j == 0 ? extras[0] : nullptr, a0, a1, true, true, b0);
        corner[1] = ring.size();
        ring.push_back(point(a1, b0));
        add(i + 2 == A.size() ? extras[3] : nullptr, b0, b1, true, false, a1);
        corner[2] = ring.size();
        ring.push_back(point(a1, b1));
        add(j + 2 == B.size() ? extras[1] : nullptr, a0, a1, false, true, b1);
        corner[3] = ring.size();
        ring.push_back(point(a0, b1));
        add(i == 0 ? extras[2] : nullptr, b0, b1, false, false, a0);
        const std::size_t count = ring.size();
        auto emit = [&](const glm::dvec3& p, const glm::dvec3& q, const glm::dvec3& r)
        {
          if (positive)
          {
            polygon({ p, q, r }, roomId);
          }
          else
          {
            polygon({ r, q, p }, roomId);
          }
        };
        if (count == 4)
        {
          if (!positive)
          {
            std::reverse(ring.begin(), ring.end());
          }
          polygon(ring, roomId);
          continue;
        }
        // Side k runs from corner k to corner k + 1. A corner whose two sides carry no extra
        // vertex can be the apex of a fan (count - 2 triangles, none degenerate); otherwise
        // fan around the centre (count triangles).
        auto plain = [&](int k)
        {
          const std::size_t from = corner[static_cast<std::size_t>(k)];
          const std::size_t to = k == 3 ? count : corner[static_cast<std::size_t>(k + 1)];
          return to - from == 1;
        };
        int apex = -1;
        for (int k = 0; k < 4 && apex < 0; ++k)
        {
          if (plain(k) && plain((k + 3) % 4))
          {
            apex = k;
          }
        }
        if (apex >= 0)
        {
          const std::size_t first = corner[static_cast<std::size_t>(apex)];
          for (std::size_t k = 1; k + 1 < count; ++k)
          {
            emit(ring[first], ring[(first + k) % count], ring[(first + k + 1) % count]);
          }
          continue;
        }
        const glm::dvec3 centre = point(0.5 * (a0 + a1), 0.5 * (b0 + b1));
        for (std::size_t k = 0; k < count; ++k)
        {
          emit(centre, ring[k], ring[(k + 1) % count]);
        }
      }
    }
  }

  /// The axis-aligned rectangle [lo, hi] (lo[n] == hi[n]) facing +n or -n; @p extras (sorted
  /// coordinates along the other in-plane axis) lie on its edge where axis @p edgeAxis equals
  /// @p edgeAt (see grid()).
  void axisRect(int n, bool positive, const glm::dvec3& lo, const glm::dvec3& hi,
    std::int32_t roomId, const std::vector<double>* extras = nullptr, int edgeAxis = -1,
    double edgeAt = 0.0)
  {
    const int a = (n + 1) % 3;
    const int b = (n + 2) % 3;
    const std::vector<double> A{ lo[a], hi[a] };
    const std::vector<double> B{ lo[b], hi[b] };
    std::array<const std::vector<double>*, 4> e{};
    if (extras && edgeAxis == b)
    {
      e[edgeAt == lo[b] ? 0 : 1] = extras;
    }
    else if (extras && edgeAxis == a)
    {
      e[edgeAt == lo[a] ? 2 : 3] = extras;
    }
    grid(n, lo[n], positive, A, B, nullptr, e, roomId);
  }

  /// A closed box, outward-facing.
  void box(const glm::dvec3& lo, const glm::dvec3& hi, std::int32_t roomId)
  {
    const glm::dvec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
    rect(y, x, -lo.z, lo.y, hi.y, lo.x, hi.x, roomId); // -z
    rect(x, y, hi.z, lo.x, hi.x, lo.y, hi.y, roomId);  // +z
    rect(x, z, -lo.y, lo.x, hi.x, lo.z, hi.z, roomId); // -y
    rect(z, x, hi.y, lo.z, hi.z, lo.x, hi.x, roomId);  // +y
    rect(z, y, -lo.x, lo.z, hi.z, lo.y, hi.y, roomId); // -x
    rect(y, z, hi.x, lo.y, hi.y, lo.z, hi.z, roomId);  // +x
  }
};

/// Element-wise on purpose: GCC 12 at -O3 reports a bogus -Wnonnull for vector::assign/insert
/// of a range into an empty vector of glm vectors, which -Werror turns into a build break.
void setPolygon(Portal& portal, const std::array<glm::dvec3, 4>& corners)
{
  portal.polygon.clear();
  portal.polygon.reserve(corners.size());
  for (const glm::dvec3& p : corners)
  {
    portal.polygon.push_back(p);
  }
}

enum LayerId
{
  kWalls,
  kFloors,
  kCeilings,
  kFacade,
  kRoof,
  kStairs,
  kFurniture,
  kGlass,
  kLayerCount
};

struct LayerStyle
{
  const char* name;
  glm::dvec3 colour;
  double opacity;
};

const std::array<LayerStyle, kLayerCount> kLayerStyles{ {
  { "walls", glm::dvec3(0.85, 0.85, 0.8), 1.0 },
  { "floors", glm::dvec3(0.6, 0.5, 0.4), 1.0 },
  { "ceilings", glm::dvec3(0.95, 0.95, 0.95), 1.0 },
  { "facade", glm::dvec3(0.75, 0.5, 0.4), 1.0 },
  { "roof", glm::dvec3(0.4, 0.4, 0.45), 1.0 },
  { "stairs", glm::dvec3(0.5, 0.5, 0.55), 1.0 },
  { "furniture", glm::dvec3(0.55, 0.35, 0.2), 1.0 },
  { "glass", glm::dvec3(0.6, 0.8, 0.9), 0.3 },
} };

constexpr double kDoorWidth = 0.9;
constexpr double kDoorHeight = 2.1;
constexpr double kWindowWidth = 1.2;
constexpr double kWindowSill = 0.9;
constexpr double kWindowTop = 2.2;
constexpr int kRisers = 16; // 3 m / 16 = 0.1875 m rise: more than half a slab, see below
constexpr double kTread = 0.25;

/// Union-find for the per-floor spanning tree of doors.
struct DisjointSets
{
  std::vector<int> parent;
  explicit DisjointSets(int n)
    : parent(static_cast<std::size_t>(n))
  {
    std::iota(parent.begin(), parent.end(), 0);
  }
  int find(int i)
  {
    while (parent[static_cast<std::size_t>(i)] != i)
    {
      i = parent[static_cast<std::size_t>(i)] =
        parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
    }
    return i;
  }
  bool unite(int a, int b)
  {
    a = find(a);
    b = find(b);
    if (a == b)
    {
      return false;
    }
    parent[static_cast<std::size_t>(a)] = b;
    return true;
  }
};

} // namespace

BuildingScene building(int floors, int roomsX, int roomsY, std::uint64_t seed)
{
  if (floors < 1 || roomsX < 1 || roomsY < 1)
  {
    throw std::invalid_argument("scenevis::scenes::building: floors, roomsX, roomsY must be >= 1");
  }
  const double t = kWallThickness;
  const double slab = kSlabThickness;
  const double storey = kStoreyHeight;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const int perFloor = roomsX * roomsY;
  if (static_cast<double>(floors) * perFloor > 1e7)
  {
    throw std::length_error("scenevis::scenes::building: too many rooms");
  }
  const double originX = -0.5 * roomsX * kRoomSizeX;
  const double originY = -0.5 * roomsY * kRoomSizeY;
  auto gridX = [&](int i) { return originX + i * kRoomSizeX; };
  auto gridY = [&](int i) { return originY + i * kRoomSizeY; };
  auto roomId = [&](int f, int ix, int iy) { return f * perFloor + iy * roomsX + ix; };
  Random rng(seed);

  // Stairwells: one random cell per 5 x 5 block, the same cell on every floor.
  std::vector<char> stairCell(static_cast<std::size_t>(perFloor), 0);
  if (floors > 1)
  {
    for (int by = 0; by < roomsY; by += 5)
    {
      for (int bx = 0; bx < roomsX; bx += 5)
      {
        const int ix =
          bx + static_cast<int>(rng.below(static_cast<std::uint32_t>(std::min(5, roomsX - bx))));
        const int iy =
          by + static_cast<int>(rng.below(static_cast<std::uint32_t>(std::min(5, roomsY - by))));
        stairCell[static_cast<std::size_t>(iy * roomsX + ix)] = 1;
      }
    }
  }

  // Openings, decided per wall (not per room side) so both faces of a wall agree: the centre
  // along the wall in world coordinates, NaN for none. xOpen: walls on grid line x = gridX(g)
  // (g = 0 .. roomsX), row iy; yOpen: walls on y = gridY(g), column ix. Interior walls get
  // doors, the outermost grid lines windows.
  std::vector<double> xOpen(static_cast<std::size_t>(floors * roomsY * (roomsX + 1)), nan);
  std::vector<double> yOpen(static_cast<std::size_t>(floors * roomsX * (roomsY + 1)), nan);
  auto xIndex = [&](int f, int g, int iy)
  { return static_cast<std::size_t>((f * roomsY + iy) * (roomsX + 1) + g); };
  auto yIndex = [&](int f, int ix, int g)
  { return static_cast<std::size_t>((f * roomsX + ix) * (roomsY + 1) + g); };
  auto openingCentre = [&](double lo, double hi, double width)
  {
    const double margin = 0.5 * t + 0.3 + 0.5 * width;
    return rng.uniform(lo + margin, hi - margin);
  };
  struct Edge
  {
    bool alongX; // true: wall on an x grid line between (g-1, i) and (g, i)
    int g;
    int i;
  };
  std::vector<Edge> edges;
  for (int f = 0; f < floors; ++f)
  {
    edges.clear();
    for (int iy = 0; iy < roomsY; ++iy)
    {
      for (int g = 1; g < roomsX; ++g)
      {
        edges.push_back({ true, g, iy });
      }
    }
    for (int ix = 0; ix < roomsX; ++ix)
    {
      for (int g = 1; g < roomsY; ++g)
      {
        edges.push_back({ false, g, ix });
      }
    }
    for (std::size_t k = edges.size(); k > 1; --k)
    {
      std::swap(edges[k - 1], edges[rng.below(static_cast<std::uint32_t>(k))]);
    }
    // Kruskal on a shuffled edge list = a random spanning tree: every room is reachable.
    DisjointSets sets(perFloor);
    for (const Edge& e : edges)
    {
      const int a = e.alongX ? e.i * roomsX + e.g - 1 : (e.g - 1) * roomsX + e.i;
      const int b = e.alongX ? a + 1 : a + roomsX;
      const bool tree = sets.unite(a, b);
      if (tree || rng.chance(0.3))
      {
        if (e.alongX)
        {
          xOpen[xIndex(f, e.g, e.i)] = openingCentre(gridY(e.i), gridY(e.i + 1), kDoorWidth);
        }
        else
        {
          yOpen[yIndex(f, e.i, e.g)] = openingCentre(gridX(e.i), gridX(e.i + 1), kDoorWidth);
        }
      }
    }
    for (int iy = 0; iy < roomsY; ++iy)
    {
      for (int g : { 0, roomsX })
      {
        if (rng.chance(0.75))
        {
          xOpen[xIndex(f, g, iy)] = openingCentre(gridY(iy), gridY(iy + 1), kWindowWidth);
        }
      }
    }
    for (int ix = 0; ix < roomsX; ++ix)
    {
      for (int g : { 0, roomsY })
      {
        if (rng.chance(0.75))
        {
          yOpen[yIndex(f, ix, g)] = openingCentre(gridX(ix), gridX(ix + 1), kWindowWidth);
        }
      }
    }
  }

  BuildingScene scene;
  std::array<Layer, kLayerCount> layers;
  const glm::dvec3 ex(1, 0, 0), ey(0, 1, 0), ez(0, 0, 1);
  scene.rooms.reserve(static_cast<std::size_t>(floors * perFloor));
  for (int f = 0; f < floors; ++f)
  {
    const double z0 = f * storey;
    const double z1 = (f + 1) * storey;
    const double zFloor = z0 + 0.5 * slab;
    const double zCeiling = z1 - 0.5 * slab;
    for (int iy = 0; iy < roomsY; ++iy)
    {
      for (int ix = 0; ix < roomsX; ++ix)
      {
        const std::int32_t id = roomId(f, ix, iy);
        Room room;
        room.id = id;
        room.floor = f;
        room.ix = ix;
        room.iy = iy;
        room.stairwell = stairCell[static_cast<std::size_t>(iy * roomsX + ix)] != 0;
        room.bounds.extend(glm::dvec3(gridX(ix), gridY(iy), z0));
        room.bounds.extend(glm::dvec3(gridX(ix + 1), gridY(iy + 1), z1));
        const double xi0 = gridX(ix) + 0.5 * t;
        const double xi1 = gridX(ix + 1) - 0.5 * t;
        const double yi0 = gridY(iy) + 0.5 * t;
        const double yi1 = gridY(iy + 1) - 0.5 * t;

        // Walls: one side at a time. N points out of this room; (N, U, Z) is right-handed
        // (U = Z x N), and "w" is the coordinate along N, so this room is at w < wc.
        struct Side
        {
          glm::dvec3 n;
          double wc;          // wall centre plane, along n
          double lo, hi;      // cell extent along the wall, world coordinate on its axis
          double opening;     // centre along the wall (world), NaN for none
          std::int32_t other; // neighbour room or kOutside
          bool first, last;   // this cell is the first / last along the wall's axis
        };
        const std::array<Side, 4> sides{ {
          { -ex,
            -gridX(ix),
            gridY(iy),
            gridY(iy + 1),
            xOpen[xIndex(f, ix, iy)],
            ix > 0 ? id - 1 : kOutside,
            iy == 0,
            iy == roomsY - 1 },
          { ex,
            gridX(ix + 1),
            gridY(iy),
            gridY(iy + 1),
            xOpen[xIndex(f, ix + 1, iy)],
            ix + 1 < roomsX ? id + 1 : kOutside,
            iy == 0,
            iy == roomsY - 1 },
          { -ey,
            -gridY(iy),
            gridX(ix),
            gridX(ix + 1),
            yOpen[yIndex(f, ix, iy)],
            iy > 0 ? id - roomsX : kOutside,
            ix == 0,
            ix == roomsX - 1 },
          { ey,
            gridY(iy + 1),
            gridX(ix),
            gridX(ix + 1),
            yOpen[yIndex(f, ix, iy + 1)],
            iy + 1 < roomsY ? id + roomsX : kOutside,
            ix == 0,
            ix == roomsX - 1 },
        } };
        // The room's shell: four wall faces, floor and ceiling on the interior box
        // [xi0, xi1] x [yi0, yi1] x [zFloor, zCeiling], each cut on the grid of its own
        // openings, plus the reveals of every opening out to the wall's (or slab's) centre
        // plane, where the portal is. Faces are numbered 2 * axis + (0: low side, 1: high side)
        // and list their grid lines per axis; where two faces meet, each also gets the other's
        // vertices on the shared edge (Layer::grid), so the shell has no T-junction.
        const double lo[3] = { xi0, yi0, zFloor };
        const double hi[3] = { xi1, yi1, zCeiling };
        const double centre[3][2] = { { gridX(ix), gridX(ix + 1) }, { gridY(iy), gridY(iy + 1) },
          { z0, z1 } };
        std::array<std::array<std::vector<double>, 3>, 6> lines;
        std::array<std::array<double, 4>, 6> holes{};
        std::array<bool, 6> hasHole{};
        // Floor-level openings (doors) whose threshold lies on the floor's edge.
        std::array<bool, 6> doorAt{};
        std::array<double, 6> g0s{}, g1s{}, oz0s{}, oz1s{};
        for (int face = 0; face < 6; ++face)
        {
          const int n = face / 2;
          for (int axis = 0; axis < 3; ++axis)
          {
            if (axis != n)
            {
              lines[static_cast<std::size_t>(face)][static_cast<std::size_t>(axis)] = { lo[axis],
                hi[axis] };
            }
          }
        }
        const double xs = xi0 + 0.3;
        const double hx0 = xs + 0.5;
        const double hx1 = xs + (kRisers - 1) * kTread + 0.3;
        const double hy0 = yi0 + 0.1;
        const double hy1 = yi0 + 1.3;
        const bool holeBelow = room.stairwell && f > 0;
        const bool holeAbove = room.stairwell && f + 1 < floors;
        for (int face : { 4, 5 })
        {
          if (face == 4 ? holeBelow : holeAbove)
          {
            auto& l = lines[static_cast<std::size_t>(face)];
            l[0] = { xi0, hx0, hx1, xi1 };
            l[1] = { yi0, hy0, hy1, yi1 };
            holes[static_cast<std::size_t>(face)] = { hx0, hx1, hy0, hy1 };
            hasHole[static_cast<std::size_t>(face)] = true;
          }
        }
        // Side k of `sides` is face: -x 0, +x 1, -y 2, +y 3.
        for (int k = 0; k < 4; ++k)
        {
          const Side& side = sides[static_cast<std::size_t>(k)];
          if (std::isnan(side.opening))
          {
            continue;
          }
          const bool exterior = side.other == kOutside;
          const double width = exterior ? kWindowWidth : kDoorWidth;
          const double g0 = side.opening - 0.5 * width;
          const double g1 = side.opening + 0.5 * width;
          const double oz0 = zFloor + (exterior ? kWindowSill : 0.0);
          const double oz1 = zFloor + (exterior ? kWindowTop : kDoorHeight);
          const int along = k < 2 ? 1 : 0;
          auto& l = lines[static_cast<std::size_t>(k)];
          l[static_cast<std::size_t>(along)] = { lo[along], g0, g1, hi[along] };
          l[2] = exterior ? std::vector<double>{ zFloor, oz0, oz1, zCeiling }
                          : std::vector<double>{ zFloor, oz1, zCeiling };
          // Hole in the face's (a, b) = ((n+1)%3, (n+2)%3) coordinates: x walls (y, z), y walls
          // (z, x).
          holes[static_cast<std::size_t>(k)] = k < 2 ? std::array<double, 4>{ g0, g1, oz0, oz1 }
                                                     : std::array<double, 4>{ oz0, oz1, g0, g1 };
          hasHole[static_cast<std::size_t>(k)] = true;
          doorAt[static_cast<std::size_t>(k)] = !exterior;
          g0s[static_cast<std::size_t>(k)] = g0;
          g1s[static_cast<std::size_t>(k)] = g1;
          oz0s[static_cast<std::size_t>(k)] = oz0;
          oz1s[static_cast<std::size_t>(k)] = oz1;
        }
        const std::array<LayerId, 6> layerOf{ kWalls, kWalls, kWalls, kWalls, kFloors, kCeilings };
        for (int face = 0; face < 6; ++face)
        {
          const int n = face / 2;
          const int a = (n + 1) % 3;
          const int b = (n + 2) % 3;
          const auto& own = lines[static_cast<std::size_t>(face)];
          auto neighbour = [&](int axis, int sideOf, int along) {
            return &lines[static_cast<std::size_t>(2 * axis + sideOf)]
                         [static_cast<std::size_t>(along)];
          };
          const std::array<const std::vector<double>*, 4> extras{ neighbour(b, 0, a),
            neighbour(b, 1, a), neighbour(a, 0, b), neighbour(a, 1, b) };
          layers[layerOf[static_cast<std::size_t>(face)]].grid(n, face % 2 ? hi[n] : lo[n],
            face % 2 == 0, // faces into the room
            own[static_cast<std::size_t>(a)], own[static_cast<std::size_t>(b)],
            hasHole[static_cast<std::size_t>(face)] ? holes[static_cast<std::size_t>(face)].data()
                                                    : nullptr,
            extras, id);
        }
        // Reveals of the wall openings, from the room face to the wall's centre plane.
        for (int k = 0; k < 4; ++k)
        {
          if (!hasHole[static_cast<std::size_t>(k)])
          {
            continue;
          }
          const int n = k / 2;
          const int along = k < 2 ? 1 : 0;
          const double wFace = k % 2 ? hi[n] : lo[n];
          const double wMid = centre[n][k % 2];
          const double w0 = std::min(wFace, wMid), w1 = std::max(wFace, wMid);
          const double g0 = g0s[static_cast<std::size_t>(k)], g1 = g1s[static_cast<std::size_t>(k)];
          const double oz0 = oz0s[static_cast<std::size_t>(k)],
                       oz1 = oz1s[static_cast<std::size_t>(k)];
          glm::dvec3 rlo(0.0), rhi(0.0);
          rlo[n] = w0;
          rhi[n] = w1;
          // Jambs: facing into the opening.
          for (int end = 0; end < 2; ++end)
          {
            glm::dvec3 jlo = rlo, jhi = rhi;
            jlo[along] = jhi[along] = end ? g1 : g0;
            jlo[2] = oz0;
            jhi[2] = oz1;
            layers[kWalls].axisRect(along, end == 0, jlo, jhi, id);
          }
          // Lintel (facing down) and sill or threshold (facing up); a threshold's inner edge
          // lies on the floor's edge and takes the floor's vertices there.
          glm::dvec3 llo = rlo, lhi = rhi;
          llo[along] = g0;
          lhi[along] = g1;
          llo[2] = lhi[2] = oz1;
          layers[kWalls].axisRect(2, false, llo, lhi, id);
          llo[2] = lhi[2] = oz0;
          if (doorAt[static_cast<std::size_t>(k)])
          {
            layers[kWalls].axisRect(
              2, true, llo, lhi, id, &lines[4][static_cast<std::size_t>(along)], n, wFace);
          }
          else
          {
            layers[kWalls].axisRect(2, true, llo, lhi, id);
          }
        }
        // Stair shaft sides inside the slab, from the room face to the slab's centre plane.
        auto shaft = [&](Layer& layer, double zl, double zh)
        {
          layer.axisRect(0, true, glm::dvec3(hx0, hy0, zl), glm::dvec3(hx0, hy1, zh), id);
          layer.axisRect(0, false, glm::dvec3(hx1, hy0, zl), glm::dvec3(hx1, hy1, zh), id);
          layer.axisRect(1, true, glm::dvec3(hx0, hy0, zl), glm::dvec3(hx1, hy0, zh), id);
          layer.axisRect(1, false, glm::dvec3(hx0, hy1, zl), glm::dvec3(hx1, hy1, zh), id);
        };
        if (holeBelow)
        {
          shaft(layers[kFloors], z0, zFloor);
        }
        if (holeAbove)
        {
          shaft(layers[kCeilings], zCeiling, z1);
        }

        for (const Side& side : sides)
        {
          const glm::dvec3 n = side.n;
          const glm::dvec3 u = glm::cross(ez, n);
          // World axis of the wall is +-u; map world extents to the u coordinate.
          const double sign = u.x + u.y; // +1 or -1
          auto along = [sign](double a, double b)
          { return sign > 0 ? std::make_pair(a, b) : std::make_pair(-b, -a); };
          const bool exterior = side.other == kOutside;
          const bool open = !std::isnan(side.opening);
          const double width = exterior ? kWindowWidth : kDoorWidth;
          const std::pair<double, double> gap =
            along(side.opening - 0.5 * width, side.opening + 0.5 * width);
          const double o0 = gap.first;
          const double o1 = gap.second;
          const double oz0 = zFloor + (exterior ? kWindowSill : 0.0);
          const double oz1 = zFloor + (exterior ? kWindowTop : kDoorHeight);
          if (open)
          {
            // One portal per opening: doors from the lower id (the -x / -y room), whose
            // +x / +y side this is; windows from their room.
            if (exterior || side.other > id)
            {
              Portal portal;
              portal.kind = exterior ? PortalKind::Window : PortalKind::Door;
              portal.roomA = id;
              portal.roomB = side.other;
              const std::array<glm::dvec3, 4> q = rectCorners(u, ez, side.wc, o0, o1, oz0, oz1);
              setPolygon(portal, q);
              portal.normal = n;
              scene.portals.push_back(std::move(portal));
              if (exterior)
              {
                layers[kGlass].rect(u, ez, side.wc, o0, o1, oz0, oz1, id);
              }
            }
          }
        }

        // The stair flight runs along +x near the -y wall, up to the hole in the slab above.
        if (holeAbove)
        {
          Portal portal;
          portal.kind = PortalKind::Stair;
          portal.roomA = id;
          portal.roomB = roomId(f + 1, ix, iy);
          const std::array<glm::dvec3, 4> q = rectCorners(ex, ey, z1, hx0, hx1, hy0, hy1);
          setPolygon(portal, q);
          portal.normal = ez;
          scene.portals.push_back(std::move(portal));
          // Solid steps; the last riser is the upper floor itself. The top step's top is
          // z1 + slab/2 - rise < z1 because rise > slab/2, so steps stay in this room's cell.
          const double rise = storey / kRisers;
          for (int k = 0; k + 1 < kRisers; ++k)
          {
            layers[kStairs].box(
              glm::dvec3(xs + k * kTread, yi0 + 0.2, zFloor),
              glm::dvec3(xs + (k + 1) * kTread, yi0 + 1.2, zFloor + (k + 1) * rise),
              id);
          }
        }
        if (!room.stairwell)
        {
          const int pieces = 1 + static_cast<int>(rng.below(3));
          for (int k = 0; k < pieces; ++k)
          {
            const glm::dvec3 size(
              rng.uniform(0.4, 2.0), rng.uniform(0.4, 1.5), rng.uniform(0.4, 2.0));
            const glm::dvec3 corner(rng.uniform(xi0 + 0.05, xi1 - 0.05 - size.x),
              rng.uniform(yi0 + 0.05, yi1 - 0.05 - size.y), zFloor);
            layers[kFurniture].box(corner, corner + size, id);
          }
        }
        scene.rooms.push_back(room);
      }
    }
  }
  // Facade, roof and underside: the outside of the building, closed except for the windows.
  // Like the room shells, every face is cut on the grid of its own window and takes its
  // neighbours' vertices on shared edges (Layer::grid), so there is no crack to see a room
  // through from outside. Facade face (side k, floor f, cell i): side k as the room faces
  // (0: -x, 1: +x, 2: -y, 3: +y), in the plane half a wall outside the outer grid line, cell i
  // along the side (extended by half a wall at the building's corners), floor f from slab centre
  // to slab centre (extended by half a slab to the roof and the underside).
  const double bx0 = gridX(0) - 0.5 * t;
  const double bx1 = gridX(roomsX) + 0.5 * t;
  const double by0 = gridY(0) - 0.5 * t;
  const double by1 = gridY(roomsY) + 0.5 * t;
  const double zTop = floors * storey + 0.5 * slab;
  const double zBottom = 0.0 * storey - 0.5 * slab;
  auto cellsAlong = [&](int k) { return k < 2 ? roomsY : roomsX; };
  auto windowAt = [&](int k, int f, int i)
  {
    return k < 2 ? xOpen[xIndex(f, k == 0 ? 0 : roomsX, i)]
                 : yOpen[yIndex(f, i, k == 2 ? 0 : roomsY)];
  };
  auto alongLines = [&](int k, int f, int i)
  {
    const int last = cellsAlong(k) - 1;
    const double lo = i == 0 ? (k < 2 ? by0 : bx0) : (k < 2 ? gridY(i) : gridX(i));
    const double hi = i == last ? (k < 2 ? by1 : bx1) : (k < 2 ? gridY(i + 1) : gridX(i + 1));
    const double open = windowAt(k, f, i);
    if (std::isnan(open))
    {
      return std::vector<double>{ lo, hi };
    }
    return std::vector<double>{ lo, open - 0.5 * kWindowWidth, open + 0.5 * kWindowWidth, hi };
  };
  auto zLines = [&](int k, int f, int i)
  {
    const double z0 = f * storey;
    const double zFloor = z0 + 0.5 * slab;
    const double fz0 = z0 - (f == 0 ? 0.5 * slab : 0.0);
    const double fz1 = (f + 1) * storey + (f == floors - 1 ? 0.5 * slab : 0.0);
    if (std::isnan(windowAt(k, f, i)))
    {
      return std::vector<double>{ fz0, fz1 };
    }
    return std::vector<double>{ fz0, zFloor + kWindowSill, zFloor + kWindowTop, fz1 };
  };
  // Union of the along-lines of a side's cells on floor f: the roof's or underside's edge there.
  auto sideLines = [&](int k, int f)
  {
    std::vector<double> all;
    for (int i = 0; i < cellsAlong(k); ++i)
    {
      const std::vector<double> l = alongLines(k, f, i);
      all.insert(all.end(), l.begin(), l.end());
    }
    std::sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end()), all.end());
    return all;
  };
  for (int k = 0; k < 4; ++k)
  {
    const int n = k / 2;
    const double wOuter = k == 0 ? bx0 : k == 1 ? bx1 : k == 2 ? by0 : by1;
    const double wMid = k == 0 ? gridX(0)
      : k == 1                 ? gridX(roomsX)
      : k == 2                 ? gridY(0)
                               : gridY(roomsY);
    // The sides meeting this one at its low and high ends, and their cell there.
    const int loSide = k < 2 ? 2 : 0, hiSide = k < 2 ? 3 : 1;
    for (int f = 0; f < floors; ++f)
    {
      for (int i = 0; i < cellsAlong(k); ++i)
      {
        const std::vector<double> along = alongLines(k, f, i);
        const std::vector<double> z = zLines(k, f, i);
        const std::vector<double> below = f > 0 ? alongLines(k, f - 1, i) : std::vector<double>();
        const std::vector<double> above =
          f + 1 < floors ? alongLines(k, f + 1, i) : std::vector<double>();
        const std::vector<double> left =
          i > 0 ? zLines(k, f, i - 1) : zLines(loSide, f, k % 2 ? cellsAlong(loSide) - 1 : 0);
        const std::vector<double> right = i + 1 < cellsAlong(k)
          ? zLines(k, f, i + 1)
          : zLines(hiSide, f, k % 2 ? cellsAlong(hiSide) - 1 : 0);
        const bool open = along.size() == 4;
        std::array<double, 4> hole{};
        // Grid axes: x sides (a, b) = (y, z); y sides (a, b) = (z, x).
        std::array<const std::vector<double>*, 4> extras{};
        // The hole exists only where there is a window (4 lines along, 4 in z); without one,
        // along and z hold just the two ends.
        if (n == 0)
        {
          if (open)
            hole = { along[1], along[2], z[1], z[2] };
          extras = { &below, &above, &left, &right };
        }
        else
        {
          if (open)
            hole = { z[1], z[2], along[1], along[2] };
          extras = { &left, &right, &below, &above };
        }
        layers[kFacade].grid(n, wOuter,
          k % 2 == 1, // faces out of the building
          n == 0 ? along : z, n == 0 ? z : along, open ? hole.data() : nullptr, extras, kOutside);
        if (open)
        {
          // The outer half of the window's reveals, facing into the opening.
          const int al = n == 0 ? 1 : 0;
          glm::dvec3 rlo(0.0), rhi(0.0);
          rlo[n] = std::min(wOuter, wMid);
          rhi[n] = std::max(wOuter, wMid);
          for (int end = 0; end < 2; ++end)
          {
            glm::dvec3 jlo = rlo, jhi = rhi;
            jlo[al] = jhi[al] = along[static_cast<std::size_t>(1 + end)];
            jlo[2] = z[1];
            jhi[2] = z[2];
            layers[kFacade].axisRect(al, end == 0, jlo, jhi, kOutside);
          }
          glm::dvec3 llo = rlo, lhi = rhi;
          llo[al] = along[1];
          lhi[al] = along[2];
          llo[2] = lhi[2] = z[2];
          layers[kFacade].axisRect(2, false, llo, lhi, kOutside);
          llo[2] = lhi[2] = z[1];
          layers[kFacade].axisRect(2, true, llo, lhi, kOutside);
        }
      }
    }
  }
  // Roof (facing up) and underside (facing down), with the facade's vertices on their edges.
  for (const bool roof : { true, false })
  {
    const int f = roof ? floors - 1 : 0;
    const std::vector<double> lx0 = sideLines(0, f), lx1 = sideLines(1, f);
    const std::vector<double> ly0 = sideLines(2, f), ly1 = sideLines(3, f);
    // Axes (a, b) = (x, y): borders y = by0 (side 2), y = by1 (side 3), x = bx0 (0), x = bx1 (1).
    layers[kRoof].grid(2, roof ? zTop : zBottom, roof, { bx0, bx1 }, { by0, by1 }, nullptr,
      { &ly0, &ly1, &lx0, &lx1 }, kOutside);
  }

  for (std::size_t l = 0; l < layers.size(); ++l)
  {
    const Layer& layer = layers[l];
    Part part;
    part.name = kLayerStyles[l].name;
    part.colour = kLayerStyles[l].colour;
    part.opacity = kLayerStyles[l].opacity;
    part.firstPolygon = scene.mesh.append(layer.mesh);
    part.polygonCount = static_cast<std::uint32_t>(layer.mesh.polygonCount());
    part.bounds = layer.mesh.bounds();
    scene.part.insert(scene.part.end(), part.polygonCount, static_cast<std::uint32_t>(l));
    scene.room.insert(scene.room.end(), layer.room.begin(), layer.room.end());
    scene.parts.push_back(std::move(part));
  }
  return scene;
}

} // namespace scenes
} // namespace scenevis
