#include "vtkBSPSortFilter.h"

#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIdList.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkProp3D.h"
#include "vtkSmartPointer.h"
#include "vtkWeakPointer.h"

#include "scenevis/BspBuilder.h"
#include "scenevis/BspTraversal.h"

#include <chrono>
#include <cmath>
#include <sstream>

vtkStandardNewMacro(vtkBSPSortFilter);
vtkCxxSetObjectMacro(vtkBSPSortFilter, Camera, vtkCamera);

namespace
{
namespace bsp = scenevis::bsp;

double SecondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

bool IsFinite(const double v[3])
{
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

/// The core's input: the polygons of `input` (strips as their triangles), and for each core
/// polygon the input cell id it came from.
void ToPolygonMesh(vtkPolyData* input, scenevis::PolygonMesh& mesh, std::vector<vtkIdType>& cellOf)
{
  const vtkIdType numPoints = input->GetNumberOfPoints();
  mesh.points.resize(static_cast<std::size_t>(numPoints));
  for (vtkIdType i = 0; i < numPoints; ++i)
  {
    double p[3];
    input->GetPoint(i, p);
    mesh.points[static_cast<std::size_t>(i)] = { p[0], p[1], p[2] };
  }
  // Cell ids follow VTK's order: verts, lines, polys, strips.
  const vtkIdType firstPoly = input->GetNumberOfVerts() + input->GetNumberOfLines();
  std::vector<std::uint32_t> ids;
  vtkIdType npts = 0;
  const vtkIdType* pts = nullptr;
  vtkCellArray* polys = input->GetPolys();
  vtkIdType cellId = firstPoly;
  for (polys->InitTraversal(); polys->GetNextCell(npts, pts); ++cellId)
  {
    ids.assign(pts, pts + npts);
    mesh.addPolygon(ids.data(), ids.size());
    cellOf.push_back(cellId);
  }
  vtkCellArray* strips = input->GetStrips();
  for (strips->InitTraversal(); strips->GetNextCell(npts, pts); ++cellId)
  {
    for (vtkIdType k = 0; k + 2 < npts; ++k)
    {
      // Alternate the winding so every triangle of the strip faces the same way.
      if (k % 2 == 0)
      {
        mesh.addPolygon({ static_cast<std::uint32_t>(pts[k]), static_cast<std::uint32_t>(pts[k + 1]),
          static_cast<std::uint32_t>(pts[k + 2]) });
      }
      else
      {
        mesh.addPolygon({ static_cast<std::uint32_t>(pts[k + 1]), static_cast<std::uint32_t>(pts[k]),
          static_cast<std::uint32_t>(pts[k + 2]) });
      }
      cellOf.push_back(cellId);
    }
  }
}
} // namespace

struct vtkBSPSortFilter::Internals
{
  vtkWeakPointer<vtkProp3D> Prop3D;

  // What the current tree was built from.
  bsp::BuildConfig Config;
  vtkMTimeType InputMTime = 0;
  vtkWeakPointer<vtkPolyData> Input;
  int BuiltDirection = -1;

  std::unique_ptr<bsp::Tree> Tree;
  std::unique_ptr<bsp::IncrementalOrder> Order;
  std::vector<vtkIdType> CellOfSource; // core polygon id -> input cell id

  // Output pieces that do not depend on the view: points + point data, verts, lines, and the cell
  // data of verts/lines followed by one tuple per fragment (in fragment id order).
  vtkSmartPointer<vtkPolyData> Cache;
  vtkSmartPointer<vtkCellData> FragmentCellData;
  vtkSmartPointer<vtkIdTypeArray> FragmentOriginalIds;
  vtkIdType NumberOfPassThroughCells = 0;

  vtkIdType Builds = 0;
  vtkIdType Removed = 0;
  double LastBuildTime = 0.0;
  double LastOrderTime = 0.0;
  vtkIdType LastNodesVisited = 0;
};

//------------------------------------------------------------------------------
vtkBSPSortFilter::vtkBSPSortFilter()
  : Internal(new Internals)
{
}

//------------------------------------------------------------------------------
vtkBSPSortFilter::~vtkBSPSortFilter()
{
  this->SetCamera(nullptr);
}

//------------------------------------------------------------------------------
void vtkBSPSortFilter::SetProp3D(vtkProp3D* prop)
{
  if (this->Internal->Prop3D != prop)
  {
    this->Internal->Prop3D = prop;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
vtkProp3D* vtkBSPSortFilter::GetProp3D()
{
  return this->Internal->Prop3D;
}

//------------------------------------------------------------------------------
vtkMTimeType vtkBSPSortFilter::GetMTime()
{
  vtkMTimeType mTime = this->Superclass::GetMTime();
  if (this->Camera)
  {
    mTime = std::max(mTime, this->Camera->GetMTime());
  }
  if (vtkProp3D* prop = this->Internal->Prop3D)
  {
    mTime = std::max(mTime, prop->GetMTime());
  }
  return mTime;
}

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

//------------------------------------------------------------------------------
int vtkBSPSortFilter::RequestData(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  Internals& internal = *this->Internal;

  if (!this->Camera)
  {
    vtkErrorMacro("No camera set: passing the input through unsorted.");
    output->ShallowCopy(input);
    return 1;
  }

  // The view, in the input's coordinates.
  double position[3], focal[3];
  this->Camera->GetPosition(position);
  this->Camera->GetFocalPoint(focal);
  double eye[4] = { position[0], position[1], position[2], 1.0 };
  double direction[4] = { focal[0] - position[0], focal[1] - position[1], focal[2] - position[2],
    0.0 };
  if (vtkProp3D* prop = internal.Prop3D)
  {
    vtkNew<vtkMatrix4x4> inverse;
    vtkMatrix4x4::Invert(prop->GetMatrix(), inverse);
    inverse->MultiplyPoint(eye, eye);
    inverse->MultiplyPoint(direction, direction);
    if (eye[3] != 0.0)
    {
      for (int i = 0; i < 3; ++i)
      {
        eye[i] /= eye[3];
      }
    }
  }
  const bool parallel = this->Camera->GetParallelProjection() != 0;
  const double directionLength =
    std::sqrt(direction[0] * direction[0] + direction[1] * direction[1] + direction[2] * direction[2]);
  if (!IsFinite(eye) || !IsFinite(direction) || (parallel && !(directionLength > 0.0)))
  {
    vtkErrorMacro("The camera has a non-finite position or no view direction: passing the input "
                  "through unsorted.");
    output->ShallowCopy(input);
    return 1;
  }
  const scenevis::View view = parallel
    ? scenevis::View::parallel({ direction[0], direction[1], direction[2] })
    : scenevis::View::perspective({ eye[0], eye[1], eye[2] });

  // Rebuild only when the input or the partition settings changed.
  bsp::BuildConfig config;
  config.partition = this->PartitionMode == PARTITION_FIRST_IN_LIST
    ? bsp::BuildConfig::Partition::FirstInList
    : bsp::BuildConfig::Partition::Scored;
  config.candidates = this->CandidateCount;
  config.splitWeight = this->SplitWeight;
  config.seed = this->Seed;
  config.relativeTolerance = this->RelativeTolerance;
  const bool configChanged = !internal.Tree || config.partition != internal.Config.partition ||
    config.candidates != internal.Config.candidates ||
    config.splitWeight != internal.Config.splitWeight || config.seed != internal.Config.seed ||
    config.relativeTolerance != internal.Config.relativeTolerance;
  const bool inputChanged = internal.Input != input || input->GetMTime() != internal.InputMTime;
  const auto buildStart = std::chrono::steady_clock::now();
  if (configChanged || inputChanged)
  {
    internal.Order.reset();
    internal.Tree.reset();
    internal.CellOfSource.clear();
    scenevis::PolygonMesh mesh;
    ToPolygonMesh(input, mesh, internal.CellOfSource);

    if (mesh.polygonCount() == 0)
    {
      vtkWarningMacro("The input has no polygons to sort: passing it through.");
      output->ShallowCopy(input);
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
    internal.Removed = static_cast<vtkIdType>(stats.invalidPolygons + stats.degeneratePolygons);
    if (stats.invalidPolygons > 0)
    {
      vtkWarningMacro("Removed " << stats.invalidPolygons
                                 << " polygon(s) with non-finite (NaN/Inf) points or invalid "
                                    "point ids; they cannot be drawn.");
    }
    if (stats.degeneratePolygons > 0)
    {
      vtkWarningMacro("Removed " << stats.degeneratePolygons
                                 << " degenerate polygon(s) (fewer than 3 distinct points or "
                                    "zero area).");
    }

    // View-independent part of the output: points and interpolated point data.
    const vtkIdType numIn = input->GetNumberOfPoints();
    const vtkIdType numOut = static_cast<vtkIdType>(tree->points.size());
    vtkNew<vtkPoints> points;
    points->SetDataType(input->GetPoints() ? input->GetPoints()->GetDataType() : VTK_FLOAT);
    points->SetNumberOfPoints(numOut);
    for (vtkIdType i = 0; i < numOut; ++i)
    {
      const glm::dvec3& p = tree->points[static_cast<std::size_t>(i)];
      points->SetPoint(i, p.x, p.y, p.z);
    }
    internal.Cache = vtkSmartPointer<vtkPolyData>::New();
    internal.Cache->SetPoints(points);
    vtkPointData* outPD = internal.Cache->GetPointData();
    outPD->DeepCopy(input->GetPointData());
    for (int a = 0; a < outPD->GetNumberOfArrays(); ++a)
    {
      vtkAbstractArray* array = outPD->GetAbstractArray(a);
      array->Resize(numOut);
      array->SetNumberOfTuples(numOut);
      for (std::size_t s = 0; s < tree->splitPoints.size(); ++s)
      {
        const bsp::SplitPoint& split = tree->splitPoints[s];
        array->InterpolateTuple(numIn + static_cast<vtkIdType>(s), split.a, array, split.b, array,
          split.t);
      }
    }
    if (vtkDataArray* normals = outPD->GetNormals())
    {
      for (vtkIdType i = numIn; i < numOut; ++i)
      {
        double n[3];
        normals->GetTuple(i, n);
        const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (length > 0.0)
        {
          normals->SetTuple3(i, n[0] / length, n[1] / length, n[2] / length);
        }
      }
    }
    internal.Cache->SetVerts(input->GetVerts());
    internal.Cache->SetLines(input->GetLines());

    // Cell data: the pass-through verts and lines first, then one tuple per fragment.
    vtkCellData* inCD = input->GetCellData();
    internal.NumberOfPassThroughCells = input->GetNumberOfVerts() + input->GetNumberOfLines();
    const vtkIdType numFragments = static_cast<vtkIdType>(tree->fragments.size());
    internal.FragmentCellData = vtkSmartPointer<vtkCellData>::New();
    internal.FragmentCellData->CopyAllocate(inCD, numFragments);
    internal.FragmentOriginalIds = vtkSmartPointer<vtkIdTypeArray>::New();
    internal.FragmentOriginalIds->SetNumberOfTuples(numFragments);
    for (vtkIdType f = 0; f < numFragments; ++f)
    {
      const vtkIdType cell =
        internal.CellOfSource[tree->fragments[static_cast<std::size_t>(f)].source];
      internal.FragmentCellData->CopyData(inCD, cell, f);
      internal.FragmentOriginalIds->SetValue(f, cell);
    }

    internal.Tree = std::move(tree);
    internal.Config = config;
    internal.Input = input;
    internal.InputMTime = input->GetMTime();
    internal.LastBuildTime = SecondsSince(buildStart);
    ++internal.Builds;
  }

  // Order: incremental when only the view changed.
  const auto orderStart = std::chrono::steady_clock::now();
  const bsp::Direction dir = this->Direction == VTK_DIRECTION_FRONT_TO_BACK
    ? bsp::Direction::FrontToBack
    : bsp::Direction::BackToFront;
  if (!internal.Order || internal.BuiltDirection != this->Direction)
  {
    internal.Order = std::make_unique<bsp::IncrementalOrder>(*internal.Tree, dir);
    internal.BuiltDirection = this->Direction;
  }
  const auto& updateStats = internal.Order->update(view);
  internal.LastNodesVisited = static_cast<vtkIdType>(updateStats.nodesVisited);
  const std::vector<std::uint32_t>& order = internal.Order->order();

  // Emit the fragments in order.
  const bsp::Tree& tree = *internal.Tree;
  const vtkIdType numFragments = static_cast<vtkIdType>(order.size());
  vtkNew<vtkIdTypeArray> offsets;
  offsets->SetNumberOfTuples(numFragments + 1);
  vtkNew<vtkIdTypeArray> connectivity;
  std::size_t totalVertices = 0;
  for (std::uint32_t f : order)
  {
    totalVertices += tree.fragments[f].count;
  }
  connectivity->SetNumberOfTuples(static_cast<vtkIdType>(totalVertices));
  vtkIdType* offsetPtr = offsets->GetPointer(0);
  vtkIdType* connPtr = connectivity->GetPointer(0);
  vtkIdType written = 0;
  for (vtkIdType r = 0; r < numFragments; ++r)
  {
    const bsp::Fragment& fragment = tree.fragments[order[static_cast<std::size_t>(r)]];
    offsetPtr[r] = written;
    for (std::uint32_t k = 0; k < fragment.count; ++k)
    {
      connPtr[written++] = tree.fragmentVertices[fragment.first + k];
    }
  }
  offsetPtr[numFragments] = written;
  vtkNew<vtkCellArray> polys;
  polys->SetData(offsets, connectivity);

  output->SetPoints(internal.Cache->GetPoints());
  output->GetPointData()->ShallowCopy(internal.Cache->GetPointData());
  output->SetVerts(internal.Cache->GetVerts());
  output->SetLines(internal.Cache->GetLines());
  output->SetPolys(polys);

  // Cell data: pass-through cells keep their data, fragments take their source cell's.
  const vtkIdType passThrough = internal.NumberOfPassThroughCells;
  vtkCellData* inCD = input->GetCellData();
  vtkCellData* outCD = output->GetCellData();
  outCD->CopyAllocate(inCD, passThrough + numFragments);
  for (vtkIdType c = 0; c < passThrough; ++c)
  {
    outCD->CopyData(inCD, c, c);
  }
  vtkNew<vtkIdList> source;
  vtkNew<vtkIdList> destination;
  source->SetNumberOfIds(numFragments);
  destination->SetNumberOfIds(numFragments);
  for (vtkIdType r = 0; r < numFragments; ++r)
  {
    source->SetId(r, order[static_cast<std::size_t>(r)]);
    destination->SetId(r, passThrough + r);
  }
  outCD->CopyData(internal.FragmentCellData, source, destination);

  if (this->GenerateOrderArrays)
  {
    vtkNew<vtkIdTypeArray> originalIds;
    originalIds->SetName(OriginalCellIdArrayName());
    originalIds->SetNumberOfTuples(passThrough + numFragments);
    vtkNew<vtkIdTypeArray> ranks;
    ranks->SetName(SortRankArrayName());
    ranks->SetNumberOfTuples(passThrough + numFragments);
    for (vtkIdType c = 0; c < passThrough; ++c)
    {
      originalIds->SetValue(c, c);
      ranks->SetValue(c, -1);
    }
    for (vtkIdType r = 0; r < numFragments; ++r)
    {
      originalIds->SetValue(
        passThrough + r, internal.FragmentOriginalIds->GetValue(order[static_cast<std::size_t>(r)]));
      ranks->SetValue(passThrough + r, r);
    }
    outCD->AddArray(originalIds);
    outCD->AddArray(ranks);
  }
  internal.LastOrderTime = SecondsSince(orderStart);
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkBSPSortFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Camera: " << this->Camera << "\n";
  os << indent << "Prop3D: " << this->Internal->Prop3D.GetPointer() << "\n";
  os << indent << "Direction: "
     << (this->Direction == VTK_DIRECTION_BACK_TO_FRONT ? "BackToFront" : "FrontToBack") << "\n";
  os << indent << "PartitionMode: "
     << (this->PartitionMode == PARTITION_FIRST_IN_LIST ? "FirstInList" : "Scored") << "\n";
  os << indent << "CandidateCount: " << this->CandidateCount << "\n";
  os << indent << "SplitWeight: " << this->SplitWeight << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "RelativeTolerance: " << this->RelativeTolerance << "\n";
  os << indent << "GenerateOrderArrays: " << (this->GenerateOrderArrays ? "On" : "Off") << "\n";
  os << indent << "NumberOfFragments: " << this->GetNumberOfFragments() << "\n";
  os << indent << "NumberOfSplits: " << this->GetNumberOfSplits() << "\n";
  os << indent << "TreeDepth: " << this->GetTreeDepth() << "\n";
  os << indent << "NumberOfBuilds: " << this->GetNumberOfBuilds() << "\n";
}
