// Specification: PortalGraph::inside() on rooms of thousands of polygons (real levels' merged
// rooms; parity() then reads only the polygons whose projection along its ray holds the eye, see
// PortalGraph::RayGrid) answers as the room's shape does: a jittered sphere and a finely
// tessellated L-shaped prism 1e7 units from the origin, 4,000 random points each, those farther
// than 0.1 % of the room's size from its boundary.
#include "scenevis/PolygonMesh.h"
#include "scenevis/PortalGraph.h"

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

using namespace scenevis;
using namespace scenevis::portals;

namespace
{
constexpr double kPi = 3.14159265358979323846;

/// A sphere of radius ~5 as rows x 2 rows quads (triangles at the poles), every point moved
/// radially by up to 0.2 %: quads that are not quite planar, as real meshes have.
void AddSphere(PolygonMesh& mesh, std::vector<std::int32_t>& rooms, int room, int rowCount)
{
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(0.998, 1.002);
  const int columns = 2 * rowCount;
  std::vector<std::uint32_t> ids;
  for (int i = 0; i <= rowCount; ++i)
  {
    for (int j = 0; j < columns; ++j)
    {
      const double theta = kPi * i / rowCount, phi = 2.0 * kPi * j / columns;
      const double r = 5.0 * ((i == 0 || i == rowCount) ? 1.0 : jitter(rng));
      ids.push_back(mesh.addPoint({ r * std::sin(theta) * std::cos(phi),
        r * std::sin(theta) * std::sin(phi), r * std::cos(theta) }));
    }
  }
  auto at = [&](int i, int j) { return ids[static_cast<std::size_t>(i * columns + j % columns)]; };
  for (int i = 0; i < rowCount; ++i)
  {
    for (int j = 0; j < columns; ++j)
    {
      // Outward-facing order does not matter to the parity test.
      if (i == 0)
      {
        mesh.addPolygon({ at(0, j), at(1, j), at(1, j + 1) });
      }
      else if (i == rowCount - 1)
      {
        mesh.addPolygon({ at(i, j), at(i + 1, j), at(i, j + 1) });
      }
      else
      {
        mesh.addPolygon({ at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1) });
      }
      rooms.push_back(room);
    }
  }
}

/// The L (0,0)-(10,0)-(10,4)-(4,4)-(4,10)-(0,10), 3 high, at @p offset, every face cut into
/// squares of @p step.
void AddTessellatedL(PolygonMesh& mesh, std::vector<std::int32_t>& rooms, int room,
  const glm::dvec3& offset, double step)
{
  auto quad = [&](glm::dvec3 origin, glm::dvec3 du, glm::dvec3 dv, double lu, double lv)
  {
    const int nu = static_cast<int>(std::lround(lu / step)),
              nv = static_cast<int>(std::lround(lv / step));
    for (int a = 0; a < nu; ++a)
    {
      for (int b = 0; b < nv; ++b)
      {
        const glm::dvec3 p = offset + origin + du * (a * step) + dv * (b * step);
        mesh.addPolygon({ mesh.addPoint(p), mesh.addPoint(p + du * step),
          mesh.addPoint(p + du * step + dv * step), mesh.addPoint(p + dv * step) });
        rooms.push_back(room);
      }
    }
  };
  const glm::dvec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  // Floor and ceiling: the L as two rectangles.
  for (const double h : { 0.0, 3.0 })
  {
    quad({ 0, 0, h }, x, y, 10, 4);
    quad({ 0, 4, h }, x, y, 4, 6);
  }
  const std::vector<glm::dvec2> outline = { { 0, 0 }, { 10, 0 }, { 10, 4 }, { 4, 4 }, { 4, 10 },
    { 0, 10 } };
  for (std::size_t k = 0; k < outline.size(); ++k)
  {
    const glm::dvec2 a = outline[k], b = outline[(k + 1) % outline.size()];
    const glm::dvec2 d = b - a;
    const double length = std::abs(d.x) + std::abs(d.y); // axis-aligned
    quad({ a.x, a.y, 0 }, glm::dvec3(d / length, 0.0), z, length, 3);
  }
}

bool InL(const glm::dvec3& q)
{
  return q.z > 0 && q.z < 3 && q.x > 0 && q.y > 0 &&
    ((q.x < 10 && q.y < 4) || (q.x < 4 && q.y < 10));
}

double DistanceToLBoundary(const glm::dvec3& q)
{
  // Distance to the nearest face plane within the L's extent: a lower bound is enough to skip
  // points near the boundary.
  double d = std::min({ std::abs(q.z), std::abs(q.z - 3) });
  for (const double c : { 0.0, 4.0, 10.0 })
  {
    d = std::min({ d, std::abs(q.x - c), std::abs(q.y - c) });
  }
  return d;
}
} // namespace

TEST(PortalInside, RoomsOfThousandsOfPolygonsAnswerAsTheirShape)
{
  PolygonMesh mesh;
  std::vector<std::int32_t> rooms;
  AddSphere(mesh, rooms, 0, 40);
  const glm::dvec3 offset(1e7, -3e6, 250.0);
  AddTessellatedL(mesh, rooms, 1, offset, 0.25);
  CellSceneInput in;
  in.mesh = &mesh;
  in.roomOfPolygon = rooms;
  const PortalGraph g = PortalGraph::build(in);
  ASSERT_EQ(g.roomCount(), 2);
  ASSERT_GT(g.rooms()[0].polygonCount, 3000u);
  ASSERT_GT(g.rooms()[1].polygonCount, 3000u);

  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int sphereIn = 0, sphereOut = 0, sphereWrong = 0;
  for (int k = 0; k < 4000; ++k)
  {
    const glm::dvec3 q(5.5 * unit(rng), 5.5 * unit(rng), 5.5 * unit(rng));
    const double r = glm::length(q);
    if (std::abs(r - 5.0) < 0.02) // the jitter (0.2 % of 5) plus 0.1 % of the size
    {
      continue;
    }
    const bool truth = r < 5.0;
    (truth ? sphereIn : sphereOut)++;
    sphereWrong += g.inside(0, q) != truth ? 1 : 0;
  }
  int lIn = 0, lOut = 0, lWrong = 0;
  for (int k = 0; k < 4000; ++k)
  {
    const glm::dvec3 local(5.0 + 5.5 * unit(rng), 5.0 + 5.5 * unit(rng), 1.5 + 2.0 * unit(rng));
    if (DistanceToLBoundary(local) < 0.01)
    {
      continue;
    }
    const bool truth = InL(local);
    (truth ? lIn : lOut)++;
    lWrong += g.inside(1, offset + local) != truth ? 1 : 0;
  }
  EXPECT_GT(sphereIn, 1000);
  EXPECT_GT(sphereOut, 1000);
  EXPECT_GT(lIn, 1000);
  EXPECT_GT(lOut, 1000);
  EXPECT_EQ(sphereWrong, 0) << "of " << sphereIn + sphereOut << " points";
  EXPECT_EQ(lWrong, 0) << "of " << lIn + lOut << " points";
}
