#include "vtkBSPTranslucentPass.h"

#include "vtkBSPSortUtilities.h"

#include "vtkBSPFragmentSet.h"
#include "vtkBSPSortedPolyDataMapper.h"

#include "vtkActor.h"
#include "vtkAlgorithm.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkScalarsToColors.h"
#include "vtkRenderState.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkTexture.h"
#include "vtkWeakPointer.h"

#include "scenevis/BspBuilder.h"
#include "scenevis/BspTraversal.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

vtkStandardNewMacro(vtkBSPTranslucentPass);

namespace
{
namespace bsp = scenevis::bsp;

double SecondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// The polydata a sortable actor draws, or nullptr when the actor cannot be sorted.
vtkPolyDataMapper* SortableMapper(vtkActor* actor)
{
  auto* mapper = vtkPolyDataMapper::SafeDownCast(actor->GetMapper());
  if (!mapper || !actor->GetVisibility())
  {
    return nullptr;
  }
  vtkProperty* property = actor->GetProperty();
  if (property->GetRepresentation() != VTK_SURFACE || property->GetEdgeVisibility())
  {
    return nullptr;
  }
  return mapper;
}

/// What of a mapper's state its helper copies (compared instead of the MTime, which VTK bumps
/// during ordinary renders).
std::vector<double> MapperSettings(vtkPolyDataMapper* mapper)
{
  std::vector<double> s;
  s.push_back(mapper->GetScalarVisibility());
  s.push_back(mapper->GetScalarMode());
  s.push_back(mapper->GetColorMode());
  s.push_back(mapper->GetArrayAccessMode());
  s.push_back(mapper->GetArrayId());
  s.push_back(mapper->GetArrayComponent());
  s.push_back(mapper->GetInterpolateScalarsBeforeMapping());
  s.push_back(mapper->GetUseLookupTableScalarRange());
  s.push_back(mapper->GetScalarRange()[0]);
  s.push_back(mapper->GetScalarRange()[1]);
  s.push_back(mapper->GetStatic());
  s.push_back(static_cast<double>(mapper->GetResolveCoincidentTopology()));
  if (const char* name = mapper->GetArrayName())
  {
    for (const char* c = name; *c; ++c)
    {
      s.push_back(*c);
    }
  }
  s.push_back(-1.0);
  // The lookup table object (shared with the helper; its own changes reach both).
  s.push_back(static_cast<double>(reinterpret_cast<std::uintptr_t>(mapper->GetLookupTable())));
  s.push_back(static_cast<double>(reinterpret_cast<std::uintptr_t>(mapper->GetClippingPlanes())));
  return s;
}

struct Run
{
  std::size_t actor;
  vtkIdType firstIndex;
  vtkIdType indexCount;
};
} // namespace

struct vtkBSPTranslucentPass::Internals
{
  struct Entry
  {
    vtkWeakPointer<vtkActor> Actor;
    vtkSmartPointer<vtkBSPSortedPolyDataMapper> Helper;
    std::vector<double> MapperSettings;
    vtkPolyDataMapper* Mapper = nullptr; // compared only
    vtkPolyData* Input = nullptr;        // compared only
    vtkMTimeType InputMTime = 0;
    std::array<double, 16> Matrix{};
    std::shared_ptr<vtkBSPFragmentSet> Fragments;
    std::vector<std::uint32_t> LocalOrder;
    vtkIdType Cursor = 0;
  };
  std::vector<Entry> Entries;

  std::unique_ptr<bsp::Tree> Tree;
  std::unique_ptr<bsp::IncrementalOrder> Order;
  std::vector<std::uint32_t> FragmentActor; // global fragment -> entry
  std::vector<std::uint32_t> FragmentLocal; // global fragment -> fragment id within its entry
  std::vector<Run> Runs;
  bool RunsValid = false;
  bool HaveView = false;
  scenevis::View LastView;

  vtkIdType TreeBuilds = 0;
  vtkIdType OrderUpdates = 0;
  vtkIdType UploadsOfReleasedHelpers = 0;
  double LastBuildTime = 0.0;
  double LastOrderTime = 0.0;

  void Clear()
  {
    for (Entry& entry : this->Entries)
    {
      this->UploadsOfReleasedHelpers += entry.Helper->GetNumberOfIndexUploads();
    }
    this->Entries.clear();
    this->Order.reset();
    this->Tree.reset();
    this->FragmentActor.clear();
    this->FragmentLocal.clear();
    this->Runs.clear();
    this->RunsValid = false;
    this->HaveView = false;
  }

  void Build();
  void UpdateRuns();
};

//------------------------------------------------------------------------------
void vtkBSPTranslucentPass::Internals::Build()
{
  const auto start = std::chrono::steady_clock::now();
  this->Order.reset();
  this->Tree.reset();
  this->RunsValid = false;
  this->HaveView = false;

  // One world-space polygon soup; actor k owns points [pointStart[k], pointStart[k+1]) and
  // polygons [polygonStart[k], polygonStart[k+1]).
  scenevis::PolygonMesh mesh;
  std::vector<vtkIdType> cellOf;
  std::vector<std::uint32_t> pointStart{ 0 };
  std::vector<std::uint32_t> polygonStart{ 0 };
  vtkNew<vtkMatrix4x4> matrix;
  for (Entry& entry : this->Entries)
  {
    matrix->DeepCopy(entry.Matrix.data());
    vtkBSPSortUtilities::AppendPolygons(entry.Input, matrix, mesh, cellOf);
    pointStart.push_back(static_cast<std::uint32_t>(mesh.points.size()));
    polygonStart.push_back(static_cast<std::uint32_t>(mesh.polygonCount()));
  }
  auto tree = std::make_unique<bsp::Tree>(bsp::build(mesh, vtkBSPFragmentSet::BuildConfig()));

  // Which actor every point belongs to, and its id within that actor's fragment set.
  const std::size_t inputPoints = tree->inputPointCount;
  std::vector<std::uint32_t> pointActor(tree->points.size());
  std::vector<std::uint32_t> pointLocal(tree->points.size());
  for (std::size_t k = 0; k < this->Entries.size(); ++k)
  {
    for (std::uint32_t p = pointStart[k]; p < pointStart[k + 1]; ++p)
    {
      pointActor[p] = static_cast<std::uint32_t>(k);
      pointLocal[p] = p - pointStart[k];
    }
  }
  std::vector<std::shared_ptr<vtkBSPFragmentSet>> sets(this->Entries.size());
  for (std::size_t k = 0; k < this->Entries.size(); ++k)
  {
    sets[k] = std::make_shared<vtkBSPFragmentSet>();
    sets[k]->Input = this->Entries[k].Input;
  }
  for (std::size_t s = 0; s < tree->splitPoints.size(); ++s)
  {
    const bsp::SplitPoint& split = tree->splitPoints[s];
    const std::size_t id = inputPoints + s;
    // A split point lies on an edge of one polygon, so both ends belong to the same actor.
    const std::uint32_t k = pointActor[split.a];
    vtkBSPFragmentSet& set = *sets[k];
    pointActor[id] = k;
    pointLocal[id] = static_cast<std::uint32_t>(
      static_cast<std::size_t>(set.Input->GetNumberOfPoints()) + set.Splits.size());
    set.Splits.push_back({ pointLocal[split.a], pointLocal[split.b], split.t });
  }
  const std::size_t fragmentCount = tree->fragments.size();
  this->FragmentActor.resize(fragmentCount);
  this->FragmentLocal.resize(fragmentCount);
  for (std::size_t g = 0; g < fragmentCount; ++g)
  {
    const bsp::Fragment& fragment = tree->fragments[g];
    const auto k = static_cast<std::uint32_t>(
      std::upper_bound(polygonStart.begin(), polygonStart.end(), fragment.source) -
      polygonStart.begin() - 1);
    vtkBSPFragmentSet& set = *sets[k];
    this->FragmentActor[g] = k;
    this->FragmentLocal[g] = static_cast<std::uint32_t>(set.FragmentCount());
    for (std::uint32_t v = 0; v < fragment.count; ++v)
    {
      set.Vertices.push_back(pointLocal[tree->fragmentVertices[fragment.first + v]]);
    }
    set.Offsets.push_back(static_cast<std::uint32_t>(set.Vertices.size()));
    set.Cells.push_back(cellOf[fragment.source]);
  }
  for (std::size_t k = 0; k < this->Entries.size(); ++k)
  {
    this->Entries[k].Fragments = sets[k];
    this->Entries[k].Helper->SetExternalFragments(sets[k]);
  }
  this->Tree = std::move(tree);
  this->Order = std::make_unique<bsp::IncrementalOrder>(*this->Tree, bsp::Direction::BackToFront);
  ++this->TreeBuilds;
  this->LastBuildTime = SecondsSince(start);
}

//------------------------------------------------------------------------------
void vtkBSPTranslucentPass::Internals::UpdateRuns()
{
  for (Entry& entry : this->Entries)
  {
    entry.LocalOrder.clear();
    entry.Cursor = 0;
  }
  this->Runs.clear();
  const std::size_t none = static_cast<std::size_t>(-1);
  std::size_t current = none;
  for (std::uint32_t g : this->Order->order())
  {
    const std::uint32_t k = this->FragmentActor[g];
    Entry& entry = this->Entries[k];
    const std::uint32_t local = this->FragmentLocal[g];
    const vtkIdType indices = 3 *
      (static_cast<vtkIdType>(entry.Fragments->Offsets[local + 1] - entry.Fragments->Offsets[local]) -
        2);
    if (k != current)
    {
      this->Runs.push_back({ k, entry.Cursor, 0 });
      current = k;
    }
    this->Runs.back().indexCount += indices;
    entry.Cursor += indices;
    entry.LocalOrder.push_back(local);
  }
  for (Entry& entry : this->Entries)
  {
    entry.Helper->SetExternalOrder(entry.LocalOrder);
  }
  this->RunsValid = true;
}

//------------------------------------------------------------------------------
vtkBSPTranslucentPass::vtkBSPTranslucentPass()
  : Internal(new Internals)
{
}

//------------------------------------------------------------------------------
vtkBSPTranslucentPass::~vtkBSPTranslucentPass() = default;

//------------------------------------------------------------------------------
void vtkBSPTranslucentPass::ReleaseGraphicsResources(vtkWindow* w)
{
  for (Internals::Entry& entry : this->Internal->Entries)
  {
    entry.Helper->ReleaseGraphicsResources(w);
  }
  this->Superclass::ReleaseGraphicsResources(w);
}

//------------------------------------------------------------------------------
void vtkBSPTranslucentPass::Render(const vtkRenderState* s)
{
  this->NumberOfRenderedProps = 0;
  Internals& internal = *this->Internal;
  vtkRenderer* renderer = s->GetRenderer();
  if (renderer->GetSelector())
  {
    this->RenderFilteredTranslucentPolygonalGeometry(s);
    return;
  }

  // Which translucent actors take part; others are drawn first, as vtkTranslucentPass would.
  std::vector<vtkActor*> sorted;
  std::vector<vtkPolyDataMapper*> mappers;
  std::vector<vtkPolyData*> inputs;
  for (int i = 0; i < s->GetPropArrayCount(); ++i)
  {
    vtkProp* prop = s->GetPropArray()[i];
    if (!prop->HasKeys(s->GetRequiredKeys()))
    {
      continue;
    }
    vtkActor* actor = vtkActor::SafeDownCast(prop);
    vtkPolyDataMapper* mapper = actor ? SortableMapper(actor) : nullptr;
    vtkPolyData* input = nullptr;
    if (mapper && actor->HasTranslucentPolygonalGeometry())
    {
      if (!mapper->GetStatic() && mapper->GetInputAlgorithm())
      {
        mapper->GetInputAlgorithm()->Update();
      }
      input = mapper->GetInput();
    }
    if (input && input->GetNumberOfPoints() > 0 &&
      input->GetNumberOfPolys() + input->GetNumberOfStrips() > 0)
    {
      sorted.push_back(actor);
      mappers.push_back(mapper);
      inputs.push_back(input);
    }
    else
    {
      this->NumberOfRenderedProps +=
        prop->RenderFilteredTranslucentPolygonalGeometry(renderer, s->GetRequiredKeys());
    }
  }
  if (sorted.empty())
  {
    if (!internal.Entries.empty())
    {
      internal.Clear();
    }
    return;
  }

  // Rebuild only when the set of actors, a matrix, an input or a mapper changed.
  bool rebuild = sorted.size() != internal.Entries.size() || !internal.Tree;
  std::vector<Internals::Entry> entries;
  entries.reserve(sorted.size());
  for (std::size_t k = 0; k < sorted.size(); ++k)
  {
    Internals::Entry entry;
    auto same = std::find_if(internal.Entries.begin(), internal.Entries.end(),
      [&](const Internals::Entry& e) { return e.Actor == sorted[k]; });
    if (same != internal.Entries.end())
    {
      entry = *same;
    }
    else
    {
      entry.Helper = vtkSmartPointer<vtkBSPSortedPolyDataMapper>::New();
    }
    rebuild = rebuild || k >= internal.Entries.size() || internal.Entries[k].Actor != sorted[k];
    entry.Actor = sorted[k];
    const std::vector<double> settings = MapperSettings(mappers[k]);
    if (entry.Mapper != mappers[k] || entry.MapperSettings != settings)
    {
      // Same colour/scalar settings as the actor's own mapper; the pass updates the pipeline.
      // (vtkPolyDataMapper's copy: the OpenGL one also copies deprecated shader-code settings.)
      // The mapper's MTime is not used: VTK touches it during ordinary renders.
      entry.Helper->vtkPolyDataMapper::ShallowCopy(mappers[k]);
      entry.Helper->StaticOn();
      entry.Mapper = mappers[k];
      entry.MapperSettings = settings;
    }
    if (entry.Input != inputs[k] || entry.InputMTime != inputs[k]->GetMTime())
    {
      entry.Input = inputs[k];
      entry.InputMTime = inputs[k]->GetMTime();
      rebuild = true;
    }
    const double* m = &sorted[k]->GetMatrix()->Element[0][0];
    if (!std::equal(m, m + 16, entry.Matrix.begin()))
    {
      std::copy(m, m + 16, entry.Matrix.begin());
      rebuild = true;
    }
    entries.push_back(std::move(entry));
  }
  for (const Internals::Entry& old : internal.Entries)
  {
    if (std::none_of(entries.begin(), entries.end(),
          [&](const Internals::Entry& e) { return e.Helper == old.Helper; }))
    {
      internal.UploadsOfReleasedHelpers += old.Helper->GetNumberOfIndexUploads();
    }
  }
  internal.Entries = std::move(entries);
  if (rebuild)
  {
    internal.Build();
  }

  // Order: incremental, and only when the camera moved.
  const auto orderStart = std::chrono::steady_clock::now();
  vtkCamera* camera = renderer->GetActiveCamera();
  double position[3], focal[3];
  camera->GetPosition(position);
  camera->GetFocalPoint(focal);
  const scenevis::View view = camera->GetParallelProjection()
    ? scenevis::View::parallel(
        { focal[0] - position[0], focal[1] - position[1], focal[2] - position[2] })
    : scenevis::View::perspective({ position[0], position[1], position[2] });
  if (!internal.HaveView || view.eye != internal.LastView.eye)
  {
    const auto& stats = internal.Order->update(view);
    ++internal.OrderUpdates;
    if (!internal.HaveView || stats.nodesFlipped > 0 || stats.fragmentsMoved > 0)
    {
      internal.RunsValid = false;
    }
    internal.HaveView = true;
    internal.LastView = view;
  }
  if (!internal.RunsValid)
  {
    internal.UpdateRuns();
  }
  internal.LastOrderTime = SecondsSince(orderStart);

  // Draw the runs, each with its actor's property, texture and matrix.
  for (const Run& run : internal.Runs)
  {
    Internals::Entry& entry = internal.Entries[run.actor];
    vtkActor* actor = entry.Actor;
    entry.Helper->SetDrawRange(run.firstIndex, run.indexCount);
    actor->SetIsRenderingTranslucentPolygonalGeometry(true);
    vtkProperty* property = actor->GetProperty();
    property->Render(actor, renderer);
    if (vtkProperty* backface = actor->GetBackfaceProperty())
    {
      backface->BackfaceRender(actor, renderer);
    }
    if (vtkTexture* texture = actor->GetTexture())
    {
      texture->Render(renderer);
    }
    actor->Render(renderer, entry.Helper);
    property->PostRender(actor, renderer);
    if (vtkTexture* texture = actor->GetTexture())
    {
      texture->PostRender(renderer);
    }
    actor->SetIsRenderingTranslucentPolygonalGeometry(false);
    entry.Helper->SetDrawRange(-1, -1);
  }
  this->NumberOfRenderedProps += static_cast<int>(internal.Entries.size());
}

//------------------------------------------------------------------------------
int vtkBSPTranslucentPass::GetNumberOfSortedActors() const
{
  return static_cast<int>(this->Internal->Entries.size());
}

vtkActor* vtkBSPTranslucentPass::GetSortedActor(int index) const
{
  if (index < 0 || index >= this->GetNumberOfSortedActors())
  {
    return nullptr;
  }
  return this->Internal->Entries[static_cast<std::size_t>(index)].Actor;
}

vtkIdType vtkBSPTranslucentPass::GetNumberOfFragments() const
{
  return this->Internal->Tree ? static_cast<vtkIdType>(this->Internal->Tree->fragments.size()) : 0;
}

vtkIdType vtkBSPTranslucentPass::GetNumberOfSplits() const
{
  return this->Internal->Tree ? static_cast<vtkIdType>(this->Internal->Tree->statistics.splits)
                              : 0;
}

vtkIdType vtkBSPTranslucentPass::GetNumberOfDrawCalls() const
{
  return static_cast<vtkIdType>(this->Internal->Runs.size());
}

vtkIdType vtkBSPTranslucentPass::GetNumberOfTreeBuilds() const
{
  return this->Internal->TreeBuilds;
}

vtkIdType vtkBSPTranslucentPass::GetNumberOfOrderUpdates() const
{
  return this->Internal->OrderUpdates;
}

vtkIdType vtkBSPTranslucentPass::GetNumberOfIndexUploads() const
{
  vtkIdType uploads = this->Internal->UploadsOfReleasedHelpers;
  for (const Internals::Entry& entry : this->Internal->Entries)
  {
    uploads += entry.Helper->GetNumberOfIndexUploads();
  }
  return uploads;
}

double vtkBSPTranslucentPass::GetLastBuildTime() const
{
  return this->Internal->LastBuildTime;
}

double vtkBSPTranslucentPass::GetLastOrderTime() const
{
  return this->Internal->LastOrderTime;
}

//------------------------------------------------------------------------------
void vtkBSPTranslucentPass::GetOrderedFragments(vtkPolyData* output) const
{
  output->Initialize();
  const Internals& internal = *this->Internal;
  if (!internal.Tree || !internal.Order || internal.Order->order().empty())
  {
    return;
  }
  const bsp::Tree& tree = *internal.Tree;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(tree.points.size()));
  for (std::size_t i = 0; i < tree.points.size(); ++i)
  {
    points->SetPoint(static_cast<vtkIdType>(i), tree.points[i].x, tree.points[i].y,
      tree.points[i].z);
  }
  vtkNew<vtkCellArray> polys;
  vtkNew<vtkIntArray> actorIndex;
  actorIndex->SetName("ActorIndex");
  vtkNew<vtkIdTypeArray> fragmentId;
  fragmentId->SetName("FragmentId");
  std::vector<vtkIdType> ids;
  for (std::uint32_t g : internal.Order->order())
  {
    const bsp::Fragment& fragment = tree.fragments[g];
    ids.assign(tree.fragmentVertices.begin() + fragment.first,
      tree.fragmentVertices.begin() + fragment.first + fragment.count);
    polys->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
    actorIndex->InsertNextValue(static_cast<int>(internal.FragmentActor[g]));
    fragmentId->InsertNextValue(g);
  }
  output->SetPoints(points);
  output->SetPolys(polys);
  output->GetCellData()->AddArray(actorIndex);
  output->GetCellData()->AddArray(fragmentId);
}

//------------------------------------------------------------------------------
void vtkBSPTranslucentPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfSortedActors: " << this->GetNumberOfSortedActors() << "\n";
  os << indent << "NumberOfFragments: " << this->GetNumberOfFragments() << "\n";
  os << indent << "NumberOfDrawCalls: " << this->GetNumberOfDrawCalls() << "\n";
  os << indent << "NumberOfTreeBuilds: " << this->GetNumberOfTreeBuilds() << "\n";
}
