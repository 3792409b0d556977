// One BSP over every polygon of a scene against the two-level order (scenevis/PartTree.h): parts
// ordered as wholes by separating planes, each part by its own tree, parts that no plane
// separates by one world-space tree. Side by side in one run, per scene:
//   fragments per input polygon (what a renderer draws), trees' build time (one thread), and
//   the complete back-to-front order per view (mean over 36 eyes on a circle around the scene;
//   two levels: the groups' order and each group's full order, as a renderer keeps them).
//
//   build/bin/scenevis_part_order_bench [--smoke]
//
// Scenes: the 64 overlapping spheres and the 1,000-part CAD demo (vtkDemoSceneSource) and the
// 2CylinderEngine glTF (`engine-glb`, 115 parts; skipped when not fetched), parts from their
// "PartId" cell array, each in world coordinates with an identity matrix (flattened files name
// no instances); one sphere mesh placed 8 x 8 times 2.5 radii apart; the engine's 115 parts
// placed 3 x 3 times (1,035 parts of 115 meshes), each copy turned about z. "After one part
// moved": the last part shifted by 1 % of the scene's diagonal and the top level built again
// with the previous tree (one BSP would build everything again: its build column).
// --smoke: small scenes only (CI).
#include "vtkBSPSortUtilities.h"
#include "vtkDemoSceneSource.h"

#include "scenevis/BspBuilder.h"
#include "scenevis/BspTraversal.h"
#include "scenevis/PartOrder.h"
#include "scenevis/PartTree.h"
#include "scenevis/Scenes.h"
#include "scenevis/testing/Models.h"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <glm/gtc/matrix_transform.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <vector>

namespace
{

using Clock = std::chrono::steady_clock;
double Since(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// The scene's polygons, one mesh per value of "PartId" (own point ids per part).
std::vector<scenevis::PolygonMesh> SplitByPart(vtkPolyData* data, scenevis::PolygonMesh& all)
{
  std::vector<vtkIdType> cellOf;
  vtkBSPSortUtilities::AppendPolygons(data, nullptr, all, cellOf);
  vtkDataArray* partIds = data->GetCellData()->GetArray("PartId");
  std::map<long long, std::size_t> partIndex;
  std::vector<scenevis::PolygonMesh> parts;
  std::vector<std::map<std::uint32_t, std::uint32_t>> pointIds;
  for (std::size_t i = 0; i < all.polygonCount(); ++i)
  {
    const long long id = partIds ? static_cast<long long>(partIds->GetTuple1(cellOf[i])) : 0;
    auto inserted = partIndex.emplace(id, parts.size());
    if (inserted.second)
    {
      parts.emplace_back();
      pointIds.emplace_back();
    }
    scenevis::PolygonMesh& part = parts[inserted.first->second];
    auto& ids = pointIds[inserted.first->second];
    std::vector<std::uint32_t> polygon;
    for (std::uint32_t k = 0; k < all.polygonSize(i); ++k)
    {
      const std::uint32_t p = all.polygon(i)[k];
      auto known = ids.emplace(p, static_cast<std::uint32_t>(part.points.size()));
      if (known.second)
      {
        part.points.push_back(all.points[p]);
      }
      polygon.push_back(known.first->second);
    }
    part.addPolygon(polygon.data(), polygon.size());
  }
  return parts;
}

/// Distinct meshes (model coordinates) and their placements.
struct PartScene
{
  std::vector<scenevis::PolygonMesh> meshes;
  std::vector<scenevis::parts::Part> parts;
};

/// One part per "PartId" value, in world coordinates (identity matrices).
PartScene FromPolyData(vtkPolyData* data)
{
  PartScene scene;
  scenevis::PolygonMesh all;
  scene.meshes = SplitByPart(data, all);
  for (std::uint32_t m = 0; m < scene.meshes.size(); ++m)
  {
    scene.parts.push_back(scenevis::parts::Part{ m, glm::dmat4(1.0) });
  }
  return scene;
}

/// Every part's polygons in world coordinates, as one mesh.
scenevis::PolygonMesh Flatten(const PartScene& scene)
{
  scenevis::PolygonMesh all;
  for (const scenevis::parts::Part& part : scene.parts)
  {
    scenevis::PolygonMesh placed = scene.meshes[part.mesh];
    for (glm::dvec3& p : placed.points)
    {
      p = glm::dvec3(part.worldFromModel * glm::dvec4(p, 1.0));
    }
    all.append(placed);
  }
  return all;
}

void Run(const char* name, const PartScene& scene)
{
  const scenevis::PolygonMesh all = Flatten(scene);
  const double polygons = static_cast<double>(all.polygonCount());

  // One level: one tree over everything.
  auto start = Clock::now();
  const scenevis::bsp::Tree one = scenevis::bsp::build(all);
  const double oneBuild = Since(start);

  // Two levels: the top level with the shapes of the groups of several parts, then a tree per
  // distinct mesh (in its own coordinates) that a single-part group draws.
  std::vector<const scenevis::PolygonMesh*> meshPointers;
  for (const scenevis::PolygonMesh& mesh : scene.meshes)
  {
    meshPointers.push_back(&mesh);
  }
  start = Clock::now();
  const scenevis::parts::Tree two = scenevis::parts::build(meshPointers, scene.parts);
  const double topBuild = Since(start);
  start = Clock::now();
  std::vector<scenevis::bsp::Tree> trees(scene.meshes.size());
  std::size_t twoFragments = two.statistics.mergedFragments;
  for (const scenevis::parts::Group& g : two.groups)
  {
    if (g.single())
    {
      scenevis::bsp::Tree& t = trees[two.parts[g.parts.front()].mesh];
      if (t.empty())
      {
        t = scenevis::bsp::build(scene.meshes[two.parts[g.parts.front()].mesh]);
      }
      twoFragments += t.fragments.size();
    }
  }
  const double meshBuild = Since(start);
  std::vector<const scenevis::bsp::Tree*> treePointers;
  for (const scenevis::bsp::Tree& t : trees)
  {
    treePointers.push_back(&t);
  }

  // One part moves by a hundredth of the scene: one BSP builds everything again, the two-level
  // order its top level and the merged groups the part leaves or joins.
  const scenevis::Box box = all.bounds();
  std::vector<scenevis::parts::Part> moved = scene.parts;
  moved.back().worldFromModel =
    glm::translate(glm::dmat4(1.0), glm::dvec3(0.01 * box.diagonal(), 0.0, 0.0)) *
    moved.back().worldFromModel;
  start = Clock::now();
  const scenevis::parts::Tree afterMove = scenevis::parts::build(meshPointers, moved, {}, &two);
  const double moveBuild = Since(start);

  // Complete orders from 36 eyes on a circle at a scene diagonal from its centre.
  const double radius = box.diagonal();
  std::vector<std::uint32_t> order;
  std::vector<std::uint32_t> groups;
  std::vector<std::vector<std::uint32_t>> groupFragments(two.groups.size());
  double oneOrder = 0.0, twoOrder = 0.0;
  for (int i = 0; i < 36; ++i)
  {
    const double a = i * 3.14159265358979323846 / 18.0;
    const scenevis::View view = scenevis::View::perspective(
      box.center() + glm::dvec3(radius * std::cos(a), 0.3 * radius, radius * std::sin(a)));
    start = Clock::now();
    scenevis::bsp::order(one, view, scenevis::bsp::Direction::BackToFront, order);
    oneOrder += Since(start);
    // What a renderer does: the groups' order, then each group's own order (no expansion into
    // parts::Piece, which parts::order adds for callers that want one list).
    start = Clock::now();
    scenevis::parts::groupOrder(two, view, scenevis::bsp::Direction::BackToFront, groups);
    for (const std::uint32_t g : groups)
    {
      const scenevis::parts::Group& group = two.groups[g];
      if (group.single())
      {
        const std::uint32_t part = group.parts.front();
        scenevis::bsp::order(*treePointers[two.parts[part].mesh],
          scenevis::parts::modelView(two, part, view), scenevis::bsp::Direction::BackToFront,
          groupFragments[g]);
      }
      else
      {
        scenevis::bsp::order(two.shapes[group.shape].tree,
          scenevis::View{ group.shapeFromWorld * view.eye }, scenevis::bsp::Direction::BackToFront,
          groupFragments[g]);
      }
    }
    twoOrder += Since(start);
  }
  const scenevis::parts::Statistics& s = two.statistics;
  std::printf("| %s | %.0f | %zu / %zu | %.3f | %.2f | %zu (%zu single, %zu shapes), largest %zu "
              "| %.3f | %.2f + %.2f | %.3f (%zu shapes reused) | %.2f | %.2f |\n",
    name, polygons, scene.parts.size(), scene.meshes.size(), one.fragments.size() / polygons,
    oneBuild, s.groups, s.singlePartGroups, s.shapes, s.largestGroup, twoFragments / polygons,
    topBuild, meshBuild, moveBuild, afterMove.statistics.reusedShapes, 1e3 * oneOrder / 36.0,
    1e3 * twoOrder / 36.0);
}

/// @p mesh placed `nx` x `ny` times, `spacing` apart along x and y, each turned about z.
PartScene Tiled(const PartScene& unit, int nx, int ny, double spacing)
{
  PartScene scene;
  scene.meshes = unit.meshes;
  for (int j = 0; j < ny; ++j)
  {
    for (int i = 0; i < nx; ++i)
    {
      const glm::dmat4 place =
        glm::rotate(glm::translate(glm::dmat4(1.0), glm::dvec3(spacing * i, spacing * j, 0.0)),
          0.3 * (i + nx * j), glm::dvec3(0, 0, 1));
      for (const scenevis::parts::Part& part : unit.parts)
      {
        scene.parts.push_back(scenevis::parts::Part{ part.mesh, place * part.worldFromModel });
      }
    }
  }
  return scene;
}

vtkSmartPointer<vtkPolyData> Demo(int scene, vtkIdType triangles, vtkIdType parts)
{
  vtkNew<vtkDemoSceneSource> source;
  source->SetScene(scene);
  source->SetTriangleCount(triangles);
  source->SetPartCount(parts);
  source->Update();
  return source->GetOutput();
}

} // namespace

int main(int argc, char* argv[])
{
  const bool smoke = argc > 1 && std::strcmp(argv[1], "--smoke") == 0;
  std::printf(
    "| scene | polygons | parts / meshes | one BSP: fragments / polygon | build s | two "
    "levels: groups | fragments / polygon | build s (top + meshes) | after one part moved, "
    "s | order ms, one BSP | order ms, two levels |\n"
    "|---|---|---|---|---|---|---|---|---|---|---|\n");
  // Separate spheres: one mesh placed 64 times, 2.5 radii apart.
  PartScene sphere;
  sphere.meshes.push_back(scenevis::scenes::sphere(glm::dvec3(0.0), 1.0, smoke ? 200 : 4000));
  sphere.parts.push_back(scenevis::parts::Part{ 0, glm::dmat4(1.0) });
  if (smoke)
  {
    Run("64 spheres, 2k", FromPolyData(Demo(vtkDemoSceneSource::SCENE_SPHERE_GRID, 2000, 1)));
    Run("CAD demo, 50 parts", FromPolyData(Demo(vtkDemoSceneSource::SCENE_CAD_ASSEMBLY, 5000, 50)));
    Run("8 x 8 separate spheres", Tiled(sphere, 8, 8, 2.5));
    return 0;
  }
  Run("64 spheres, 19k", FromPolyData(Demo(vtkDemoSceneSource::SCENE_SPHERE_GRID, 19000, 1)));
  Run("64 spheres, 1M", FromPolyData(Demo(vtkDemoSceneSource::SCENE_SPHERE_GRID, 1000000, 1)));
  Run("CAD demo, 1,000 parts",
    FromPolyData(Demo(vtkDemoSceneSource::SCENE_CAD_ASSEMBLY, 200000, 1000)));
  Run("8 x 8 separate spheres, 256k", Tiled(sphere, 8, 8, 2.5));
  const std::string engine = scenevis::testing::DataFile("engine-glb");
  std::string error;
  vtkSmartPointer<vtkPolyData> model =
    engine.empty() ? nullptr : scenevis::testing::LoadModel(engine, &error);
  if (!model)
  {
    std::printf(
      "(2CylinderEngine skipped: %s)\n", engine.empty() ? "engine-glb not fetched" : error.c_str());
    return 0;
  }
  const PartScene engineParts = FromPolyData(model);
  Run("2CylinderEngine", engineParts);
  const scenevis::Box box = Flatten(engineParts).bounds();
  Run("2CylinderEngine, 3 x 3", Tiled(engineParts, 3, 3, 1.2 * box.diagonal()));
  return 0;
}
