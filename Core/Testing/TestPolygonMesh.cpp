#include "scenevis/PolygonMesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using scenevis::PolygonMesh;

TEST(PolygonMesh, StoresPolygonsInCsrLayout)
{
  PolygonMesh mesh;
  for (int i = 0; i < 5; ++i)
  {
    mesh.addPoint({ double(i), 0.0, 0.0 });
  }
  mesh.addPolygon({ 0, 1, 2 });
  mesh.addPolygon({ 1, 2, 3, 4 });
  ASSERT_EQ(mesh.polygonCount(), 2u);
  EXPECT_EQ(mesh.polygonSize(0), 3u);
  EXPECT_EQ(mesh.polygonSize(1), 4u);
  EXPECT_EQ(mesh.polygon(1)[3], 4u);
}

TEST(PolygonMesh, AppendOffsetsPointIds)
{
  PolygonMesh a;
  a.addPoint({ 0, 0, 0 });
  a.addPoint({ 1, 0, 0 });
  a.addPoint({ 0, 1, 0 });
  a.addPolygon({ 0, 1, 2 });
  PolygonMesh b = a;
  EXPECT_EQ(b.append(a), 1u);
  EXPECT_EQ(b.polygon(1)[0], 3u);
  EXPECT_DOUBLE_EQ(b.area(), 1.0);
}

TEST(PolygonMesh, BoundsIgnoreNonFinitePoints)
{
  PolygonMesh mesh;
  mesh.addPoint({ 0, 0, 0 });
  mesh.addPoint({ std::numeric_limits<double>::quiet_NaN(), 0, 0 });
  mesh.addPoint({ 2, 3, 4 });
  const scenevis::Box box = mesh.bounds();
  EXPECT_EQ(box.lo, glm::dvec3(0, 0, 0));
  EXPECT_EQ(box.hi, glm::dvec3(2, 3, 4));
  EXPECT_TRUE(scenevis::Box().empty());
}

TEST(PolygonMesh, NewellNormalIsExactFarFromOrigin)
{
  // A unit square at 1e7: the normal must still have length 2 * area.
  PolygonMesh mesh;
  const double o = 1e7;
  mesh.addPoint({ o, o, o });
  mesh.addPoint({ o + 1, o, o });
  mesh.addPoint({ o + 1, o + 1, o });
  mesh.addPoint({ o, o + 1, o });
  mesh.addPolygon({ 0, 1, 2, 3 });
  const glm::dvec3 n = scenevis::newellNormal(mesh.points.data(), mesh.polygon(0), 4);
  EXPECT_DOUBLE_EQ(n.z, 2.0);
  EXPECT_DOUBLE_EQ(n.x, 0.0);
}
