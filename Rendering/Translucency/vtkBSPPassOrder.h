/**
 * @file vtkBSPPassOrder.h
 * @brief (private header) The fragments vtkBSPTranslucentPass draws and their back-to-front
 * order, from one world-space BSP over every actor (one level) or from the two-level order of
 * scenevis/PartTree.h (actors as parts).
 *
 * Both are "units": a BSP tree, the actors whose polygons it holds ("members", each with its
 * points at a base id in the tree) and the transform that takes a world view into the tree's
 * coordinates. One level is one unit over every actor in world coordinates. Two levels: a unit
 * per group of the parts::Tree, either an actor alone with the tree of its input in the input's
 * own coordinates (kept across rebuilds for as long as the input is unchanged, and shared by the
 * actors that draw the same input), or a Shape over the actors no plane separates. The global
 * order is the units' orders one after the other, in the groups' order for the view.
 *
 * Fragments are described per actor, in the actor's own point ids: ids below its input's point
 * count are its input's points, id `count + i` is its split point i, at lerp(a, b, t) of two
 * smaller ids of the same actor (affine maps keep lerps, so this holds in the actor's input
 * coordinates whatever coordinates the tree was built in).
 */
#ifndef vtkBSPPassOrder_h
#define vtkBSPPassOrder_h

#include "vtkType.h"

#include "scenevis/BspTraversal.h"
#include "scenevis/BspTree.h"
#include "scenevis/PartTree.h"
#include "scenevis/PolygonMesh.h"
#include "scenevis/View.h"

#include <glm/mat4x4.hpp>

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <utility>
#include <vector>

class vtkPolyData;

class vtkBSPPassOrder
{
public:
  struct Actor
  {
    vtkPolyData* Input = nullptr;
    vtkMTimeType InputMTime = 0;
    std::array<double, 16> Matrix{}; ///< VTK's row-major model-to-world matrix.
  };

  /// Builds the units for @p actors (their inputs must stay alive until the next Build).
  void Build(const std::vector<Actor>& actors, bool twoLevels);
  /// Brings Order() up to date for @p view; true when it changed (always on the first call).
  bool Update(const scenevis::View& view);
  /// Global fragment ids, back to front.
  const std::vector<std::uint32_t>& Order() const;
  void Clear();

  ///@{
  /// Per global fragment: its actor, its vertices (actor point ids, see the file comment) at
  /// Vertices[Offsets[f] .. Offsets[f + 1]) and its input cell id.
  std::vector<std::uint32_t> FragmentActor;
  std::vector<std::uint32_t> Offsets{ 0 };
  std::vector<std::uint32_t> Vertices;
  std::vector<vtkIdType> Cells;
  ///@}
  /// Per actor: its split points, in actor point ids.
  std::vector<std::vector<scenevis::bsp::SplitPoint>> ActorSplits;

  std::size_t FragmentCount() const { return this->FragmentActor.size(); }
  std::size_t Splits() const;
  /// BSP trees built by the last Build (input trees and shapes; one level: 1).
  std::size_t TreesBuilt() const { return this->LastTreesBuilt; }
  /// Groups and shapes of the two-level order (0 for one level).
  std::size_t Groups() const { return this->Parts ? this->Parts->groups.size() : 0; }
  std::size_t Shapes() const { return this->Parts ? this->Parts->shapes.size() : 0; }

private:
  struct Unit
  {
    const scenevis::bsp::Tree* Tree = nullptr;
    glm::dmat4 TreeFromWorld{ 1.0 };
    std::vector<std::uint32_t> Members;    ///< Actors.
    std::vector<std::uint32_t> MemberBase; ///< First point id of each member in Tree.
    std::uint32_t FirstFragment = 0;
    std::unique_ptr<scenevis::bsp::IncrementalOrder> UnitOrder;
  };
  /// An input's polygons in its own coordinates, and (once a lone actor needs it) its tree.
  struct InputMesh
  {
    scenevis::PolygonMesh Mesh;
    std::vector<vtkIdType> CellOf;
    std::unique_ptr<scenevis::bsp::Tree> Tree;
  };

  /// Appends @p unit's fragments and split points (per tree polygon: its member, empty for
  /// all 0, and its input cell id).
  void AddUnit(Unit unit, const std::vector<std::uint32_t>& sourceMember,
    const std::vector<vtkIdType>& sourceCell, const std::vector<vtkIdType>& inputPoints);

  std::vector<Unit> Units;
  std::vector<std::uint32_t> GroupUnit; ///< Two levels: the unit of each group.
  std::unique_ptr<scenevis::bsp::Tree> WorldTree;
  std::vector<vtkIdType> WorldCells;
  // Two levels: meshes by input (and its MTime), the part tree and the meshes it was built on.
  std::map<std::pair<vtkPolyData*, vtkMTimeType>, std::unique_ptr<InputMesh>> Meshes;
  std::vector<std::pair<vtkPolyData*, vtkMTimeType>> PartMeshKeys; ///< Of the part tree's meshes.
  std::unique_ptr<scenevis::parts::Tree> Parts;
  std::vector<std::uint32_t> GroupScratch;
  std::vector<std::uint32_t> LastGroups;
  std::vector<std::uint32_t> GlobalOrder;
  bool HaveOrder = false;
  std::size_t LastTreesBuilt = 0;
};

#endif
// VTK-HeaderTest-Exclude: vtkBSPPassOrder.h
