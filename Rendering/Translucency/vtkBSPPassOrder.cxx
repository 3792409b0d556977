#include "vtkBSPPassOrder.h"

#include "vtkBSPFragmentSet.h"
#include "vtkBSPSortUtilities.h"

#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPolyData.h"

#include "scenevis/BspBuilder.h"
#include "scenevis/PartOrder.h"

#include <algorithm>

namespace bsp = scenevis::bsp;
namespace parts = scenevis::parts;

namespace
{
glm::dmat4 FromRowMajor(const std::array<double, 16>& m)
{
  glm::dmat4 g;
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      g[c][r] = m[4 * r + c];
    }
  }
  return g;
}
} // namespace

//------------------------------------------------------------------------------
void vtkBSPPassOrder::Clear()
{
  this->Units.clear();
  this->GroupUnit.clear();
  this->WorldTree.reset();
  this->WorldCells.clear();
  this->Parts.reset();
  this->PartMeshKeys.clear();
  this->Meshes.clear();
  this->FragmentActor.clear();
  this->Offsets.assign(1, 0);
  this->Vertices.clear();
  this->Cells.clear();
  this->ActorSplits.clear();
  this->LastGroups.clear();
  this->GlobalOrder.clear();
  this->HaveOrder = false;
  this->LastTreesBuilt = 0;
}

std::size_t vtkBSPPassOrder::Splits() const
{
  std::size_t n = 0;
  for (const auto& s : this->ActorSplits)
  {
    n += s.size();
  }
  return n;
}

//------------------------------------------------------------------------------
void vtkBSPPassOrder::AddUnit(Unit unit, const std::vector<std::uint32_t>& sourceMember,
  const std::vector<vtkIdType>& sourceCell, const std::vector<vtkIdType>& inputPoints)
{
  const bsp::Tree& tree = *unit.Tree;
  const std::size_t treePoints = tree.inputPointCount;
  // Which member a tree point belongs to, and its id among that actor's points.
  const auto memberOfPoint = [&](std::uint32_t p)
  {
    return static_cast<std::uint32_t>(
      std::upper_bound(unit.MemberBase.begin(), unit.MemberBase.end(), p) -
      unit.MemberBase.begin() - 1);
  };
  std::vector<std::uint32_t> splitLocal(tree.splitPoints.size());
  std::vector<std::uint32_t> splitMember(tree.splitPoints.size());
  const auto local = [&](std::uint32_t member, std::uint32_t p)
  {
    return p < treePoints ? p - unit.MemberBase[member]
                          : splitLocal[static_cast<std::size_t>(p - treePoints)];
  };
  for (std::size_t s = 0; s < tree.splitPoints.size(); ++s)
  {
    const bsp::SplitPoint& split = tree.splitPoints[s];
    // A split point lies on an edge of one polygon: both ends belong to the same actor.
    const std::uint32_t member =
      split.a < treePoints ? memberOfPoint(split.a) : splitMember[split.a - treePoints];
    const std::uint32_t actor = unit.Members[member];
    auto& splits = this->ActorSplits[actor];
    splitMember[s] = member;
    splitLocal[s] =
      static_cast<std::uint32_t>(inputPoints[actor]) + static_cast<std::uint32_t>(splits.size());
    splits.push_back({ local(member, split.a), local(member, split.b), split.t });
  }
  unit.FirstFragment = static_cast<std::uint32_t>(this->FragmentActor.size());
  for (const bsp::Fragment& fragment : tree.fragments)
  {
    const std::uint32_t member = sourceMember.empty() ? 0 : sourceMember[fragment.source];
    this->FragmentActor.push_back(unit.Members[member]);
    for (std::uint32_t v = 0; v < fragment.count; ++v)
    {
      this->Vertices.push_back(local(member, tree.fragmentVertices[fragment.first + v]));
    }
    this->Offsets.push_back(static_cast<std::uint32_t>(this->Vertices.size()));
    this->Cells.push_back(sourceCell[fragment.source]);
  }
  unit.UnitOrder = std::make_unique<bsp::IncrementalOrder>(tree, bsp::Direction::BackToFront);
  this->Units.push_back(std::move(unit));
}

//------------------------------------------------------------------------------
void vtkBSPPassOrder::Build(const std::vector<Actor>& actors, bool twoLevels)
{
  this->Units.clear();
  this->GroupUnit.clear();
  this->FragmentActor.clear();
  this->Offsets.assign(1, 0);
  this->Vertices.clear();
  this->Cells.clear();
  this->ActorSplits.assign(actors.size(), {});
  this->LastGroups.clear();
  this->GlobalOrder.clear();
  this->HaveOrder = false;
  this->LastTreesBuilt = 0;
  std::vector<vtkIdType> inputPoints;
  for (const Actor& actor : actors)
  {
    inputPoints.push_back(actor.Input->GetNumberOfPoints());
  }
  const bsp::BuildConfig config = vtkBSPFragmentSet::BuildConfig();

  if (!twoLevels)
  {
    // One world-space soup: actor k owns points from base[k] and polygons from first[k].
    this->Parts.reset();
    this->PartMeshKeys.clear();
    this->Meshes.clear();
    scenevis::PolygonMesh mesh;
    this->WorldCells.clear();
    Unit unit;
    std::vector<std::uint32_t> sourceMember;
    vtkNew<vtkMatrix4x4> matrix;
    for (std::uint32_t k = 0; k < actors.size(); ++k)
    {
      unit.Members.push_back(k);
      unit.MemberBase.push_back(static_cast<std::uint32_t>(mesh.points.size()));
      matrix->DeepCopy(actors[k].Matrix.data());
      vtkBSPSortUtilities::AppendPolygons(actors[k].Input, matrix, mesh, this->WorldCells);
      sourceMember.resize(mesh.polygonCount(), k);
    }
    this->WorldTree = std::make_unique<bsp::Tree>(bsp::build(mesh, config));
    this->LastTreesBuilt = 1;
    unit.Tree = this->WorldTree.get();
    this->AddUnit(std::move(unit), sourceMember, this->WorldCells, inputPoints);
    return;
  }
  this->WorldTree.reset();
  this->WorldCells.clear();

  // The distinct inputs (kept from earlier builds while unchanged) and the actors as parts.
  using Key = std::pair<vtkPolyData*, vtkMTimeType>;
  std::map<Key, std::uint32_t> meshOf;
  std::vector<const InputMesh*> partMeshes;
  std::vector<Key> partKeys;
  std::vector<parts::Part> placed;
  for (const Actor& actor : actors)
  {
    const Key key(actor.Input, actor.InputMTime);
    auto found = meshOf.emplace(key, static_cast<std::uint32_t>(partMeshes.size()));
    if (found.second)
    {
      std::unique_ptr<InputMesh>& mesh = this->Meshes[key];
      if (!mesh)
      {
        mesh = std::make_unique<InputMesh>();
        vtkBSPSortUtilities::AppendPolygons(actor.Input, nullptr, mesh->Mesh, mesh->CellOf);
      }
      partMeshes.push_back(mesh.get());
      partKeys.push_back(key);
    }
    placed.push_back(parts::Part{ found.first->second, FromRowMajor(actor.Matrix) });
  }
  for (auto it = this->Meshes.begin(); it != this->Meshes.end();)
  {
    it = meshOf.count(it->first) ? std::next(it) : this->Meshes.erase(it);
  }
  // Shapes of the last build are kept only when mesh ids mean the same meshes.
  const bool sameMeshes = partKeys == this->PartMeshKeys;
  this->PartMeshKeys = partKeys;
  std::vector<const scenevis::PolygonMesh*> meshes;
  for (const InputMesh* m : partMeshes)
  {
    meshes.push_back(&m->Mesh);
  }
  parts::BuildConfig partConfig;
  partConfig.shapeConfig = config;
  auto tree = std::make_unique<parts::Tree>(
    parts::build(meshes, placed, partConfig, sameMeshes ? this->Parts.get() : nullptr));
  this->Parts = std::move(tree);
  const parts::Tree& partTree = *this->Parts;
  this->LastTreesBuilt = partTree.statistics.shapes - partTree.statistics.reusedShapes;

  // A unit per group.
  for (const parts::Group& group : partTree.groups)
  {
    this->GroupUnit.push_back(static_cast<std::uint32_t>(this->Units.size()));
    Unit unit;
    unit.Members = group.parts;
    if (group.single())
    {
      const std::uint32_t actor = group.parts.front();
      InputMesh& mesh = *this->Meshes[Key(actors[actor].Input, actors[actor].InputMTime)];
      if (!mesh.Tree)
      {
        mesh.Tree = std::make_unique<bsp::Tree>(bsp::build(mesh.Mesh, config));
        ++this->LastTreesBuilt;
      }
      unit.Tree = mesh.Tree.get();
      unit.TreeFromWorld = partTree.modelFromWorld[actor];
      unit.MemberBase = { 0 };
      this->AddUnit(std::move(unit), {}, mesh.CellOf, inputPoints);
      continue;
    }
    const parts::Shape& shape = partTree.shapes[group.shape];
    unit.Tree = &shape.tree;
    unit.TreeFromWorld = group.shapeFromWorld;
    std::uint32_t base = 0;
    for (const std::uint32_t actor : group.parts)
    {
      unit.MemberBase.push_back(base);
      base += static_cast<std::uint32_t>(partMeshes[placed[actor].mesh]->Mesh.points.size());
    }
    std::vector<vtkIdType> cells(shape.polygonMember.size());
    for (std::size_t i = 0; i < cells.size(); ++i)
    {
      const std::uint32_t actor = group.parts[shape.polygonMember[i]];
      cells[i] = partMeshes[placed[actor].mesh]->CellOf[shape.polygonSource[i]];
    }
    this->AddUnit(std::move(unit), shape.polygonMember, cells, inputPoints);
  }
}

//------------------------------------------------------------------------------
const std::vector<std::uint32_t>& vtkBSPPassOrder::Order() const
{
  return this->Parts || this->Units.empty() ? this->GlobalOrder
                                            : this->Units.front().UnitOrder->order();
}

//------------------------------------------------------------------------------
bool vtkBSPPassOrder::Update(const scenevis::View& view)
{
  bool changed = !this->HaveOrder;
  if (!this->Parts)
  {
    if (!this->Units.empty())
    {
      const auto& stats = this->Units.front().UnitOrder->update(view);
      changed = changed || stats.nodesFlipped > 0 || stats.fragmentsMoved > 0;
    }
    this->HaveOrder = true;
    return changed; // Order() is the one unit's own
  }
  parts::groupOrder(*this->Parts, view, bsp::Direction::BackToFront, this->GroupScratch);
  changed = changed || this->GroupScratch != this->LastGroups;
  for (Unit& unit : this->Units)
  {
    const auto& stats = unit.UnitOrder->update(scenevis::View{ unit.TreeFromWorld * view.eye });
    changed = changed || stats.nodesFlipped > 0 || stats.fragmentsMoved > 0;
  }
  if (changed)
  {
    this->LastGroups = this->GroupScratch;
    this->GlobalOrder.clear();
    for (const std::uint32_t g : this->GroupScratch)
    {
      const Unit& unit = this->Units[this->GroupUnit[g]];
      for (const std::uint32_t f : unit.UnitOrder->order())
      {
        this->GlobalOrder.push_back(unit.FirstFragment + f);
      }
    }
  }
  this->HaveOrder = true;
  return changed;
}
