#include "vtkBSPSortFilter.h"

#include "vtkBSPSortUtilities.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkWeakPointer.h"

#include "scenevis/BspBuilder.h"
#include "scenevis/BspTraversal.h"

#include <chrono>
#include <cmath>
#include <sstream>

vtkStandardNewMacro(vtkBSPSortFilter);

namespace
{
namespace bsp = scenevis::bsp;

double SecondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

} // namespace

struct vtkBSPSortFilter::Internals
{

  // What the current tree was built from.
  bsp::BuildConfig Config;
  vtkMTimeType InputMTime = 0;
  vtkWeakPointer<vtkPolyData> Input;
  int BuiltDirection = -1;

  std::unique_ptr<bsp::Tree> Tree;
  std::unique_ptr<bsp::IncrementalOrder> Order; // trees without ordered leaves
  std::vector<std::uint32_t> FullOrder;         // trees with them: a full order per update
  std::vector<vtkIdType> CellOfSource; // core polygon id -> input cell id

  // Output pieces that do not depend on the view: points + point data, verts, lines, and the cell
  // data of verts/lines followed by one tuple per fragment (in fragment id order).
  vtkSmartPointer<vtkPolyData> Cache;
  vtkSmartPointer<vtkCellData> FragmentCellData;
  std::vector<std::uint32_t> CellOfFragment; // input cell of every fragment (fragment id order)
  std::vector<std::uint32_t> CellOfRank;     // the same in output order (per frame scratch)
  vtkIdType NumberOfPassThroughCells = 0;

  vtkIdType Builds = 0;
  vtkIdType Removed = 0;
  double LastBuildTime = 0.0;
  double LastOrderTime = 0.0;
  vtkIdType LastNodesVisited = 0;
  vtkIdType LastOrderedFragments = 0;
  bsp::OrderStatistics LastLeaves;
};

//------------------------------------------------------------------------------
vtkBSPSortFilter::vtkBSPSortFilter()
  : Internal(new Internals)
{
}

//------------------------------------------------------------------------------
vtkBSPSortFilter::~vtkBSPSortFilter() = default;

//------------------------------------------------------------------------------
vtkIdType vtkBSPSortFilter::GetNumberOfFragments() const
{
  return this->Internal->Tree ? static_cast<vtkIdType>(this->Internal->Tree->fragments.size()) : 0;
}

vtkIdType vtkBSPSortFilter::GetNumberOfSplits() const
{
  return this->Internal->Tree ? static_cast<vtkIdType>(this->Internal->Tree->statistics.splits) : 0;
}

vtkIdType vtkBSPSortFilter::GetNumberOfRemovedPolygons() const
{
  return this->Internal->Removed;
}

vtkIdType vtkBSPSortFilter::GetTreeDepth() const
{
  return this->Internal->Tree ? static_cast<vtkIdType>(this->Internal->Tree->statistics.depth) : 0;
}

double vtkBSPSortFilter::GetLastBuildTime() const
{
  return this->Internal->LastBuildTime;
}

double vtkBSPSortFilter::GetLastOrderTime() const
{
  return this->Internal->LastOrderTime;
}

vtkIdType vtkBSPSortFilter::GetNumberOfBuilds() const
{
  return this->Internal->Builds;
}

vtkIdType vtkBSPSortFilter::GetLastNodesVisited() const
{
  return this->Internal->LastNodesVisited;
}

vtkIdType vtkBSPSortFilter::GetLastNumberOfOrderedFragments() const
{
  return this->Internal->LastOrderedFragments;
}

vtkIdType vtkBSPSortFilter::GetLastLeavesSorted() const
{
  return static_cast<vtkIdType>(this->Internal->LastLeaves.leavesSorted);
}

vtkIdType vtkBSPSortFilter::GetLastLeavesFallenBack() const
{
  return static_cast<vtkIdType>(this->Internal->LastLeaves.leavesFallenBack);
}

//------------------------------------------------------------------------------
int vtkBSPSortFilter::RequestData(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  Internals& internal = *this->Internal;

  // The view, in the input's coordinates (or an error and pass-through).
  scenevis::View view;
  if (!this->ViewForInput(input, output, view))
  {
    return 1;
  }

  // Rebuild only when the input or the partition settings changed.
  bsp::BuildConfig config;
  config.partition = this->PartitionMode == PARTITION_FIRST_IN_LIST
    ? bsp::BuildConfig::Partition::FirstInList
    : bsp::BuildConfig::Partition::Scored;
  config.candidates = this->CandidateCount;
  config.splitWeight = this->SplitWeight;
  config.seed = this->Seed;
  config.relativeTolerance = this->RelativeTolerance;
  config.orderedLeafSize = static_cast<std::uint32_t>(this->OrderedLeafSize);
  config.threads = 0; // the tree is identical for any thread count; use every core
  const bool configChanged = !internal.Tree || config.partition != internal.Config.partition ||
    config.candidates != internal.Config.candidates ||
    config.splitWeight != internal.Config.splitWeight || config.seed != internal.Config.seed ||
    config.relativeTolerance != internal.Config.relativeTolerance ||
    config.orderedLeafSize != internal.Config.orderedLeafSize;
  const bool inputChanged = internal.Input != input || input->GetMTime() != internal.InputMTime;
  const auto buildStart = std::chrono::steady_clock::now();
  if (configChanged || inputChanged)
  {
    internal.Order.reset();
    internal.Tree.reset();
    internal.CellOfSource.clear();
    scenevis::PolygonMesh mesh;
    if (!this->PolygonsForInput(input, output, mesh, internal.CellOfSource))
    {
      return 1;
    }

    this->UpdateProgress(0.0);
    auto tree = std::make_unique<bsp::Tree>(bsp::build(mesh, config, [this](double fraction) {
      this->UpdateProgress(0.9 * fraction);
      return this->GetAbortExecute() == 0;
    }));
    if (tree->empty() && this->GetAbortExecute())
    {
      output->ShallowCopy(input);
      return 1;
    }
    const bsp::BuildStatistics& stats = tree->statistics;
    internal.Removed =
      this->ReportRemovedPolygons(stats.invalidPolygons, stats.degeneratePolygons);

    // View-independent part of the output: points and interpolated point data.
    internal.Cache = vtkSmartPointer<vtkPolyData>::New();
    vtkNew<vtkPoints> points;
    vtkBSPSortUtilities::InterpolateSplitPoints(input, tree->splitPoints.data(),
      tree->splitPoints.size(), points, internal.Cache->GetPointData());
    internal.Cache->SetPoints(points);
    internal.Cache->SetVerts(input->GetVerts());
    internal.Cache->SetLines(input->GetLines());

    // Cell data: the pass-through verts and lines first, then one tuple per fragment.
    vtkCellData* inCD = input->GetCellData();
    internal.NumberOfPassThroughCells = input->GetNumberOfVerts() + input->GetNumberOfLines();
    const vtkIdType numFragments = static_cast<vtkIdType>(tree->fragments.size());
    internal.FragmentCellData = vtkSmartPointer<vtkCellData>::New();
    internal.FragmentCellData->CopyAllocate(inCD, numFragments);
    internal.CellOfFragment.resize(tree->fragments.size());
    for (vtkIdType f = 0; f < numFragments; ++f)
    {
      const vtkIdType cell =
        internal.CellOfSource[tree->fragments[static_cast<std::size_t>(f)].source];
      internal.FragmentCellData->CopyData(inCD, cell, f);
      internal.CellOfFragment[static_cast<std::size_t>(f)] = static_cast<std::uint32_t>(cell);
    }

    internal.Tree = std::move(tree);
    internal.Config = config;
    internal.Input = input;
    internal.InputMTime = input->GetMTime();
    internal.LastBuildTime = SecondsSince(buildStart);
    ++internal.Builds;
  }

  // Order: incremental when only the view changed; a full traversal for a tree with ordered
  // leaves (their fragments drawn depend on the view).
  const auto orderStart = std::chrono::steady_clock::now();
  const bsp::Direction dir = this->Direction == VTK_DIRECTION_FRONT_TO_BACK
    ? bsp::Direction::FrontToBack
    : bsp::Direction::BackToFront;
  internal.LastLeaves = bsp::OrderStatistics();
  if (!internal.Tree->leaves.empty())
  {
    bsp::order(*internal.Tree, view, dir, internal.FullOrder, &internal.LastLeaves);
    internal.LastNodesVisited = static_cast<vtkIdType>(internal.Tree->nodes.size());
  }
  else
  {
    if (!internal.Order || internal.BuiltDirection != this->Direction)
    {
      internal.Order = std::make_unique<bsp::IncrementalOrder>(*internal.Tree, dir);
      internal.BuiltDirection = this->Direction;
    }
    const auto& updateStats = internal.Order->update(view);
    internal.LastNodesVisited = static_cast<vtkIdType>(updateStats.nodesVisited);
  }
  const std::vector<std::uint32_t>& order =
    internal.Tree->leaves.empty() ? internal.Order->order() : internal.FullOrder;
  internal.LastOrderedFragments = static_cast<vtkIdType>(order.size());

  // Emit the fragments in order. This runs on every camera change, so it works on raw arrays
  // (32-bit cell storage when the ids fit) and in parallel.
  const bsp::Tree& tree = *internal.Tree;
  output->SetPoints(internal.Cache->GetPoints());
  output->GetPointData()->ShallowCopy(internal.Cache->GetPointData());
  output->SetVerts(internal.Cache->GetVerts());
  output->SetLines(internal.Cache->GetLines());
  output->SetPolys(vtkBSPSortUtilities::EmitPolygons(tree.fragments.data(),
    tree.fragmentVertices.data(), tree.fragmentVertices.size(), tree.points.size(), order.data(),
    order.size()));

  // Cell data: pass-through cells keep their data, fragments take their source cell's.
  internal.CellOfRank.resize(order.size());
  for (std::size_t r = 0; r < order.size(); ++r)
  {
    internal.CellOfRank[r] = internal.CellOfFragment[order[r]];
  }
  this->EmitCellData(input->GetCellData(), internal.NumberOfPassThroughCells,
    internal.FragmentCellData, order.data(), internal.CellOfRank.data(), order.size(),
    output->GetCellData());
  internal.LastOrderTime = SecondsSince(orderStart);
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkBSPSortFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "PartitionMode: "
     << (this->PartitionMode == PARTITION_FIRST_IN_LIST ? "FirstInList" : "Scored") << "\n";
  os << indent << "CandidateCount: " << this->CandidateCount << "\n";
  os << indent << "SplitWeight: " << this->SplitWeight << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "RelativeTolerance: " << this->RelativeTolerance << "\n";
  os << indent << "OrderedLeafSize: " << this->OrderedLeafSize << "\n";
  os << indent << "NumberOfFragments: " << this->GetNumberOfFragments() << "\n";
  os << indent << "NumberOfSplits: " << this->GetNumberOfSplits() << "\n";
  os << indent << "TreeDepth: " << this->GetTreeDepth() << "\n";
  os << indent << "NumberOfBuilds: " << this->GetNumberOfBuilds() << "\n";
  os << indent << "LastNumberOfOrderedFragments: " << this->GetLastNumberOfOrderedFragments()
     << "\n";
}
