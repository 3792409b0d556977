#include "vtkPainterSortFilter.h"

#include "vtkBSPSortUtilities.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
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

#include "scenevis/PainterSort.h"

#include <algorithm>
#include <chrono>
#include <numeric>

vtkStandardNewMacro(vtkPainterSortFilter);

namespace
{
namespace painter = scenevis::painter;

double SecondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
} // namespace

struct vtkPainterSortFilter::Internals
{

  // What the current sorter was built from.
  painter::Config Config;
  vtkMTimeType InputMTime = 0;
  vtkWeakPointer<vtkPolyData> Input;

  std::unique_ptr<painter::Sorter> Sorter;
  std::vector<vtkIdType> CellOfSource; // core polygon id -> input cell id
  painter::Result Result;              // reused across sorts
  std::vector<std::uint32_t> CellOfFragment; // output rank -> input cell id
  std::vector<std::uint32_t> Order;          // front to back: fragment indices reversed

  vtkIdType Builds = 0;
  vtkIdType Sorts = 0;
  vtkIdType Removed = 0;
  double LastBuildTime = 0.0;
  double LastSortTime = 0.0;
  double LastOrderTime = 0.0;
};

//------------------------------------------------------------------------------
vtkPainterSortFilter::vtkPainterSortFilter()
  : Internal(new Internals)
{
}

//------------------------------------------------------------------------------
vtkPainterSortFilter::~vtkPainterSortFilter() = default;

//------------------------------------------------------------------------------
vtkIdType vtkPainterSortFilter::GetNumberOfFragments() const
{
  return this->Internal->Sorter
    ? static_cast<vtkIdType>(this->Internal->Result.fragments.size())
    : 0;
}

vtkIdType vtkPainterSortFilter::GetNumberOfSplits() const
{
  return this->Internal->Sorter
    ? static_cast<vtkIdType>(this->Internal->Result.statistics.splits)
    : 0;
}

vtkIdType vtkPainterSortFilter::GetNumberOfRemovedPolygons() const
{
  return this->Internal->Removed;
}

vtkIdType vtkPainterSortFilter::GetNumberOfForcedEmissions() const
{
  return this->Internal->Sorter
    ? static_cast<vtkIdType>(this->Internal->Result.statistics.forcedEmissions)
    : 0;
}

double vtkPainterSortFilter::GetLastSortTime() const
{
  return this->Internal->LastSortTime;
}

double vtkPainterSortFilter::GetLastOrderTime() const
{
  return this->Internal->LastOrderTime;
}

double vtkPainterSortFilter::GetLastBuildTime() const
{
  return this->Internal->LastBuildTime;
}

vtkIdType vtkPainterSortFilter::GetNumberOfBuilds() const
{
  return this->Internal->Builds;
}

vtkIdType vtkPainterSortFilter::GetNumberOfSorts() const
{
  return this->Internal->Sorts;
}

//------------------------------------------------------------------------------
int vtkPainterSortFilter::RequestData(vtkInformation* vtkNotUsed(request),
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

  // Normalise only when the input or the settings changed.
  painter::Config config;
  config.relativeTolerance = this->RelativeTolerance;
  config.maxSplitsPerPolygon = this->MaxSplitsPerPolygon;
  const bool configChanged = !internal.Sorter ||
    config.relativeTolerance != internal.Config.relativeTolerance ||
    config.maxSplitsPerPolygon != internal.Config.maxSplitsPerPolygon;
  const bool inputChanged = internal.Input != input || input->GetMTime() != internal.InputMTime;
  if (configChanged || inputChanged)
  {
    const auto buildStart = std::chrono::steady_clock::now();
    internal.Sorter.reset();
    internal.CellOfSource.clear();
    scenevis::PolygonMesh mesh;
    if (!this->PolygonsForInput(input, output, mesh, internal.CellOfSource))
    {
      return 1;
    }
    internal.Sorter = std::make_unique<painter::Sorter>(mesh, config);
    const painter::Statistics& stats = internal.Sorter->normalisation();
    internal.Removed =
      this->ReportRemovedPolygons(stats.invalidPolygons, stats.degeneratePolygons);
    internal.Config = config;
    internal.Input = input;
    internal.InputMTime = input->GetMTime();
    internal.LastBuildTime = SecondsSince(buildStart);
    ++internal.Builds;
  }

  // The whole order, again: the painter's algorithm has no incremental update.
  const auto orderStart = std::chrono::steady_clock::now();
  painter::Result& result = internal.Result;
  internal.Sorter->sort(view, result);
  internal.LastSortTime = SecondsSince(orderStart);
  ++internal.Sorts;
  if (result.statistics.forcedEmissions > 0)
  {
    vtkWarningMacro("The split cap was reached: " << result.statistics.forcedEmissions
                                                  << " conflict(s) emitted unresolved; the order "
                                                     "may be wrong there.");
  }

  const std::size_t count = result.fragments.size();
  const std::uint32_t* order = nullptr; // back to front: the result's own order
  if (this->Direction == VTK_DIRECTION_FRONT_TO_BACK)
  {
    internal.Order.resize(count);
    std::iota(internal.Order.rbegin(), internal.Order.rend(), std::uint32_t(0));
    order = internal.Order.data();
  }
  // Input cell of the fragment drawn at each rank.
  internal.CellOfFragment.resize(count);
  for (std::size_t r = 0; r < count; ++r)
  {
    const std::size_t f = order ? order[r] : r;
    internal.CellOfFragment[r] =
      static_cast<std::uint32_t>(internal.CellOfSource[result.fragments[f].source]);
  }

  // Points: the input's, then this view's split points, with all point data interpolated.
  vtkNew<vtkPoints> points;
  vtkBSPSortUtilities::InterpolateSplitPoints(
    input, result.splitPoints.data(), result.splitPoints.size(), points, output->GetPointData());
  output->SetPoints(points);
  output->SetVerts(input->GetVerts());
  output->SetLines(input->GetLines());
  output->SetPolys(vtkBSPSortUtilities::EmitPolygons(result.fragments.data(),
    result.fragmentVertices.data(), result.fragmentVertices.size(), result.points.size(), order,
    count));

  // Cell data: pass-through cells keep their data, fragments take their source cell's.
  this->EmitCellData(input->GetCellData(), input->GetNumberOfVerts() + input->GetNumberOfLines(),
    input->GetCellData(), internal.CellOfFragment.data(), internal.CellOfFragment.data(), count,
    output->GetCellData());
  internal.LastOrderTime = SecondsSince(orderStart);
  return 1;
}

//------------------------------------------------------------------------------
void vtkPainterSortFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "RelativeTolerance: " << this->RelativeTolerance << "\n";
  os << indent << "MaxSplitsPerPolygon: " << this->MaxSplitsPerPolygon << "\n";
  os << indent << "NumberOfFragments: " << this->GetNumberOfFragments() << "\n";
  os << indent << "NumberOfSplits: " << this->GetNumberOfSplits() << "\n";
  os << indent << "NumberOfBuilds: " << this->GetNumberOfBuilds() << "\n";
  os << indent << "NumberOfSorts: " << this->GetNumberOfSorts() << "\n";
}
