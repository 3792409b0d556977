#include "vtkBSPTranslucentPass.h"

#include "vtkBSPSortUtilities.h"

#include "vtkBSPFragmentSet.h"
#include "vtkBSPPassOrder.h"
#include "vtkBSPSortedPolyDataMapper.h"

#include "vtkActor.h"
#include "vtkAlgorithm.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkMapperPolyData.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPlaneCollection.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderState.h"
#include "vtkRenderer.h"
#include "vtkScalarsToColors.h"
#include "vtkShaderProperty.h"
#include "vtkSmartPointer.h"
#include "vtkTexture.h"
#include "vtkUnsignedCharArray.h"
#include "vtkWeakPointer.h"

#include "scenevis/BspBuilder.h"
#include "scenevis/BspTraversal.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <map>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

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

/**
 * The polydata a sortable mapper draws: its input, or the one visible non-empty polydata block
 * of a composite input drawn without per-block colours, opacities or materials (ParaView's
 * representations draw a polydata as a one-block multiblock through
 * vtkCompositePolyDataMapper2, with block visibilities). Else nullptr: the actor is drawn
 * unsorted.
 */
vtkPolyData* SortableInput(vtkPolyDataMapper* mapper)
{
  std::vector<vtkPolyData*> leaves;
  if (!vtkMapperPolyData::Collect(mapper, leaves, true) || leaves.size() != 1)
  {
    return nullptr;
  }
  return leaves.front();
}

/**
 * Draws @p helper for @p actor. vtkOpenGLActor draws the mapper it is given; other actor classes
 * may draw a mapper of their own choosing (ParaView's vtkPVLODActor ignores the one given), so
 * they are drawn through @p device, a plain OpenGL actor with their property, back-face
 * property, texture, shader property and matrix (the "device" actor vtkLODActor uses itself).
 */
void DrawWith(vtkActor* actor, vtkBSPSortedPolyDataMapper* helper, vtkRenderer* renderer,
  vtkSmartPointer<vtkActor>& device)
{
  if (actor->IsA("vtkOpenGLActor"))
  {
    actor->Render(renderer, helper);
    return;
  }
  if (!device)
  {
    device = vtkSmartPointer<vtkActor>::New(); // the OpenGL back-end's actor
  }
  device->SetProperty(actor->GetProperty());
  device->SetBackfaceProperty(actor->GetBackfaceProperty());
  device->SetTexture(actor->GetTexture());
  device->SetShaderProperty(actor->GetShaderProperty());
  device->SetUserMatrix(actor->GetMatrix());
  device->SetIsRenderingTranslucentPolygonalGeometry(true);
  device->Render(renderer, helper);
  device->SetIsRenderingTranslucentPolygonalGeometry(false);
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

/**
 * Whether @p mapper colours @p input by cell scalars that are the same in every cell (a part of
 * one material, as model readers and part splitting make them): such an actor can be batched
 * with its colour baked into its points. O(cells); the pass calls it when the input or the
 * mapper's settings change.
 */
bool UniformCellScalars(vtkPolyDataMapper* mapper, vtkPolyData* input)
{
  if (!mapper->GetScalarVisibility())
  {
    return false;
  }
  int cellFlag = 0;
  vtkDataArray* scalars =
    vtkDataArray::SafeDownCast(vtkAbstractMapper::GetAbstractScalars(input, mapper->GetScalarMode(),
      mapper->GetArrayAccessMode(), mapper->GetArrayId(), mapper->GetArrayName(), cellFlag));
  if (!scalars || cellFlag != 1 || scalars->GetNumberOfTuples() < 1)
  {
    return false;
  }
  const int components = scalars->GetNumberOfComponents();
  std::vector<double> first(static_cast<std::size_t>(components));
  std::vector<double> tuple(first.size());
  scalars->GetTuple(0, first.data());
  for (vtkIdType i = 1; i < scalars->GetNumberOfTuples(); ++i)
  {
    scalars->GetTuple(i, tuple.data());
    if (tuple != first)
    {
      return false;
    }
  }
  return true;
}

/// The settings that must be equal for actors to share one helper mapper: everything of their
/// look except colour and opacity, which are baked per point. Empty when the actor cannot share
/// one (texture, shader code, cell colours that vary, ...). @p uniformCellScalars: what
/// UniformCellScalars() says of the actor.
std::vector<double> BatchKey(
  vtkActor* actor, vtkPolyDataMapper* mapper, vtkPolyData* input, bool uniformCellScalars)
{
  std::vector<double> key;
  vtkProperty* property = actor->GetProperty();
  const std::string mapperClass = mapper->GetClassName();
  if (actor->GetTexture() || actor->GetBackfaceProperty() || property->GetNumberOfTextures() > 0 ||
    property->GetInterpolation() == VTK_PBR ||
    (mapperClass != "vtkOpenGLPolyDataMapper" && mapperClass != "vtkBSPSortedPolyDataMapper"))
  {
    return key;
  }
  if (vtkPlaneCollection* planes = mapper->GetClippingPlanes())
  {
    if (planes->GetNumberOfItems() > 0)
    {
      return key;
    }
  }
  vtkShaderProperty* shaders = actor->GetShaderProperty();
  if (shaders->HasVertexShaderCode() || shaders->HasFragmentShaderCode() ||
    shaders->HasGeometryShaderCode() || shaders->GetNumberOfShaderReplacements() > 0)
  {
    return key;
  }
  bool scalarColors = false;
  if (mapper->GetScalarVisibility())
  {
    int cellFlag = 0;
    vtkAbstractArray* scalars =
      vtkAbstractMapper::GetAbstractScalars(input, mapper->GetScalarMode(),
        mapper->GetArrayAccessMode(), mapper->GetArrayId(), mapper->GetArrayName(), cellFlag);
    // Cell colours that vary would need per-fragment vertices (one colour per cell is baked
    // into the points); scalars interpolated before mapping are coloured by texture lookup per
    // pixel, which per-point colours cannot reproduce.
    if (scalars &&
      ((cellFlag != 0 && !(cellFlag == 1 && uniformCellScalars)) ||
        mapper->GetInterpolateScalarsBeforeMapping()))
    {
      return key;
    }
    scalarColors = scalars != nullptr;
  }
  const bool pointNormals = input->GetPointData()->GetNormals() != nullptr;
  if (!pointNormals && input->GetCellData()->GetNormals())
  {
    return key;
  }
  // Baked colours feed both the ambient and the diffuse term (as VTK 9.1 does with point
  // colours); without scalars that is only the actor's look if both colours agree.
  const double* ambient = property->GetAmbientColor();
  const double* diffuse = property->GetDiffuseColor();
  if (!scalarColors && property->GetAmbient() > 0.0 && !std::equal(ambient, ambient + 3, diffuse))
  {
    return key;
  }
  key = { 1.0, static_cast<double>(property->GetLighting()),
    static_cast<double>(property->GetInterpolation()), property->GetAmbient(),
    property->GetDiffuse(), property->GetSpecular(), property->GetSpecularPower(),
    static_cast<double>(property->GetBackfaceCulling()),
    static_cast<double>(property->GetFrontfaceCulling()), pointNormals ? 1.0 : 0.0,
    static_cast<double>(mapper->GetResolveCoincidentTopology()) };
  double factor = 0.0, units = 0.0;
  mapper->GetRelativeCoincidentTopologyPolygonOffsetParameters(factor, units);
  key.push_back(factor);
  key.push_back(units);
  if (property->GetSpecular() > 0.0)
  {
    const double* specular = property->GetSpecularColor();
    key.insert(key.end(), specular, specular + 3);
  }
  return key;
}

/// What the baked colours of a batched actor depend on besides its input and mapper settings.
std::vector<double> ColorKey(vtkActor* actor, vtkPolyDataMapper* mapper)
{
  vtkProperty* property = actor->GetProperty();
  const double* diffuse = property->GetDiffuseColor();
  std::vector<double> key(diffuse, diffuse + 3);
  key.push_back(property->GetOpacity());
  key.push_back(static_cast<double>(mapper->GetLookupTable()->GetMTime()));
  return key;
}

struct Run
{
  std::size_t group;
  vtkIdType firstIndex;
  vtkIdType indexCount;
};
} // namespace

struct vtkBSPTranslucentPass::Internals
{
  /// Draws helpers for actors that ignore the mapper given to Render (see DrawWith).
  vtkSmartPointer<vtkActor> Device;

  struct Entry
  {
    vtkWeakPointer<vtkActor> Actor;
    // Draws the actor when it is not batched; maps its scalars to colours when it is.
    vtkSmartPointer<vtkBSPSortedPolyDataMapper> Helper;
    std::vector<double> MapperSettings;
    vtkPolyDataMapper* Mapper = nullptr; // compared only
    vtkPolyData* Input = nullptr;        // compared only
    vtkMTimeType InputMTime = 0;
    std::array<double, 16> Matrix{};
    std::vector<double> BatchKey; // empty: cannot be batched
    bool UniformCellScalars = false; // see UniformCellScalars(), for Input and MapperSettings
    std::vector<double> ColorKey; // batched actors only
    std::size_t Group = 0;
    vtkIdType PointOffset = 0; // first point in its group's polydata
  };
  std::vector<Entry> Entries;

  /// What one run draws: one actor with its own helper, or a batch of compatible actors.
  struct Group
  {
    std::vector<std::size_t> Members;
    bool Batched = false;
    vtkSmartPointer<vtkBSPSortedPolyDataMapper> Helper; // batched only
    vtkSmartPointer<vtkActor> Actor;                    // batched only: identity matrix
    vtkSmartPointer<vtkPolyData> Points;                // batched only: world points, colours
    vtkMTimeType PropertyMTime = 0;
    std::shared_ptr<vtkBSPFragmentSet> Fragments;
    std::vector<std::uint32_t> LocalOrder;
    vtkIdType Cursor = 0;

    vtkBSPSortedPolyDataMapper* DrawingMapper(const std::vector<Entry>& entries) const
    {
      return this->Batched ? this->Helper.Get() : entries[this->Members[0]].Helper.Get();
    }
    vtkActor* DrawingActor(const std::vector<Entry>& entries) const
    {
      return this->Batched ? this->Actor.Get() : entries[this->Members[0]].Actor.Get();
    }
  };
  std::vector<Group> Groups;
  // Batched helpers (mapper + actor) kept across rebuilds so their shaders and buffers are reused.
  std::vector<std::pair<vtkSmartPointer<vtkBSPSortedPolyDataMapper>, vtkSmartPointer<vtkActor>>>
    BatchHelpers;

  vtkBSPPassOrder Source; // the fragments and their order
  bool Built = false;
  bool TwoLevels = true;
  std::vector<std::uint32_t> FragmentGroup; // global fragment -> group
  std::vector<std::uint32_t> FragmentLocal; // global fragment -> fragment id within its group
  std::vector<Run> Runs;
  bool RunsValid = false;
  bool HaveView = false;
  scenevis::View LastView;
  bool Batching = true;

  vtkIdType TreeBuilds = 0;
  vtkIdType OrderUpdates = 0;
  vtkIdType ColorBakes = 0;
  vtkIdType UploadsOfReleasedHelpers = 0;
  double LastBuildTime = 0.0;
  double LastOrderTime = 0.0;

  void Clear()
  {
    for (Entry& entry : this->Entries)
    {
      this->UploadsOfReleasedHelpers += entry.Helper->GetNumberOfIndexUploads();
    }
    for (auto& helper : this->BatchHelpers)
    {
      this->UploadsOfReleasedHelpers += helper.first->GetNumberOfIndexUploads();
    }
    this->Entries.clear();
    this->Groups.clear();
    this->BatchHelpers.clear();
    this->Source.Clear();
    this->Built = false;
    this->FragmentGroup.clear();
    this->FragmentLocal.clear();
    this->Runs.clear();
    this->RunsValid = false;
    this->HaveView = false;
  }

  /// Group of every entry: equal non-empty keys form a batch when there are at least two.
  std::vector<Group> Partition() const;
  bool SamePartition(const std::vector<Group>& groups) const;
  void Build(std::vector<Group> groups);
  void BakeColors(Group& group);
  void UpdateRuns();
};

//------------------------------------------------------------------------------
std::vector<vtkBSPTranslucentPass::Internals::Group> vtkBSPTranslucentPass::Internals::Partition()
  const
{
  // rep[k]: the first entry with k's key (k itself when it cannot be batched).
  const std::size_t n = this->Entries.size();
  std::vector<std::size_t> rep(n);
  std::vector<std::size_t> count(n, 0);
  std::map<std::vector<double>, std::size_t> firstWithKey;
  for (std::size_t k = 0; k < n; ++k)
  {
    rep[k] = k;
    const std::vector<double>& key = this->Entries[k].BatchKey;
    if (this->Batching && !key.empty())
    {
      rep[k] = firstWithKey.emplace(key, k).first->second;
    }
    ++count[rep[k]];
  }
  std::vector<Group> groups;
  std::vector<std::size_t> batchGroup(n, n);
  for (std::size_t k = 0; k < n; ++k)
  {
    if (count[rep[k]] < 2)
    {
      Group single;
      single.Members = { k };
      groups.push_back(std::move(single));
      continue;
    }
    if (batchGroup[rep[k]] == n)
    {
      batchGroup[rep[k]] = groups.size();
      Group batch;
      batch.Batched = true;
      groups.push_back(std::move(batch));
    }
    groups[batchGroup[rep[k]]].Members.push_back(k);
  }
  return groups;
}

bool vtkBSPTranslucentPass::Internals::SamePartition(const std::vector<Group>& groups) const
{
  if (groups.size() != this->Groups.size())
  {
    return false;
  }
  for (std::size_t g = 0; g < groups.size(); ++g)
  {
    if (groups[g].Batched != this->Groups[g].Batched ||
      groups[g].Members != this->Groups[g].Members)
    {
      return false;
    }
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkBSPTranslucentPass::Internals::BakeColors(Group& group)
{
  auto* colors = vtkUnsignedCharArray::SafeDownCast(group.Points->GetPointData()->GetScalars());
  unsigned char* out = colors->GetPointer(0);
  for (std::size_t k : group.Members)
  {
    Entry& entry = this->Entries[k];
    vtkActor* actor = entry.Actor;
    vtkProperty* property = actor->GetProperty();
    const double opacity = property->GetOpacity();
    const vtkIdType count = entry.Input->GetNumberOfPoints();
    unsigned char* first = out + 4 * entry.PointOffset;
    vtkUnsignedCharArray* mapped = nullptr;
    bool uniform = false;
    if (entry.Helper->GetScalarVisibility())
    {
      // The helper is a copy of the actor's mapper (settings and lookup table): the colours the
      // actor would show, with its opacity multiplied in as VTK's opacity uniform would.
      // Cell colours reach here only when every cell has the same one (the batch key): that
      // colour goes to every point.
      int cellFlag = 0;
      mapped = entry.Helper->MapScalars(entry.Input, opacity, cellFlag);
      uniform = mapped && cellFlag == 1 && mapped->GetNumberOfTuples() > 0;
      if (mapped && !uniform && (cellFlag != 0 || mapped->GetNumberOfTuples() != count))
      {
        mapped = nullptr;
      }
    }
    if (mapped)
    {
      const int components = mapped->GetNumberOfComponents();
      const unsigned char* in = mapped->GetPointer(0);
      const auto scaledAlpha = static_cast<unsigned char>(std::lround(255.0 * opacity));
      const int step = uniform ? 0 : components;
      for (vtkIdType i = 0; i < count; ++i, in += step)
      {
        unsigned char* rgba = first + 4 * i;
        switch (components)
        {
          case 1:
            rgba[0] = rgba[1] = rgba[2] = in[0];
            rgba[3] = scaledAlpha;
            break;
          case 2:
            rgba[0] = rgba[1] = rgba[2] = in[0];
            rgba[3] = in[1];
            break;
          case 3:
            std::copy(in, in + 3, rgba);
            rgba[3] = scaledAlpha;
            break;
          default:
            std::copy(in, in + 4, rgba);
            break;
        }
      }
    }
    else
    {
      const double* color = property->GetDiffuseColor();
      const unsigned char rgba[4] = { static_cast<unsigned char>(std::lround(255.0 * color[0])),
        static_cast<unsigned char>(std::lround(255.0 * color[1])),
        static_cast<unsigned char>(std::lround(255.0 * color[2])),
        static_cast<unsigned char>(std::lround(255.0 * opacity)) };
      for (vtkIdType i = 0; i < count; ++i)
      {
        std::copy(rgba, rgba + 4, first + 4 * i);
      }
    }
    entry.ColorKey = ColorKey(actor, entry.Mapper);
  }
  colors->Modified();
  group.Helper->InvalidateExternalGeometry();
  ++this->ColorBakes;
}

//------------------------------------------------------------------------------
void vtkBSPTranslucentPass::Internals::Build(std::vector<Group> groups)
{
  const auto start = std::chrono::steady_clock::now();
  this->RunsValid = false;
  this->HaveView = false;
  std::vector<vtkBSPPassOrder::Actor> actors;
  for (const Entry& entry : this->Entries)
  {
    actors.push_back({ entry.Input, entry.InputMTime, entry.Matrix });
  }
  this->Source.Build(actors, this->TwoLevels);
  this->Built = true;

  // The geometry every group draws: an actor's own input, or for a batch the world-space points
  // (and normals) of its actors one after the other, with baked colours.
  std::size_t batches = 0;
  for (std::size_t g = 0; g < groups.size(); ++g)
  {
    Group& group = groups[g];
    for (std::size_t k : group.Members)
    {
      this->Entries[k].Group = g;
      this->Entries[k].PointOffset = 0;
    }
    if (!group.Batched)
    {
      continue;
    }
    if (batches == this->BatchHelpers.size())
    {
      auto helper = vtkSmartPointer<vtkBSPSortedPolyDataMapper>::New();
      helper->StaticOn();
      helper->ScalarVisibilityOn();
      helper->SetScalarModeToUsePointData();
      helper->SetColorModeToDirectScalars();
      helper->InterpolateScalarsBeforeMappingOff();
      auto actor = vtkSmartPointer<vtkActor>::New();
      actor->SetMapper(helper);
      this->BatchHelpers.emplace_back(helper, actor);
    }
    group.Helper = this->BatchHelpers[batches].first;
    group.Actor = this->BatchHelpers[batches].second;
    ++batches;

    vtkIdType total = 0;
    for (std::size_t k : group.Members)
    {
      this->Entries[k].PointOffset = total;
      total += this->Entries[k].Input->GetNumberOfPoints();
    }
    const bool normals = this->Entries[group.Members[0]].Input->GetPointData()->GetNormals();
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    points->SetNumberOfPoints(total);
    vtkNew<vtkFloatArray> normalArray;
    normalArray->SetName("Normals");
    normalArray->SetNumberOfComponents(3);
    normalArray->SetNumberOfTuples(normals ? total : 0);
    for (std::size_t k : group.Members)
    {
      const Entry& entry = this->Entries[k];
      const double* m = entry.Matrix.data();
      // Normals go through the inverse transpose of the linear part.
      vtkNew<vtkMatrix4x4> normalMatrix;
      normalMatrix->DeepCopy(m);
      normalMatrix->Invert();
      normalMatrix->Transpose();
      vtkPoints* in = entry.Input->GetPoints();
      vtkDataArray* inNormals = entry.Input->GetPointData()->GetNormals();
      const vtkIdType count = entry.Input->GetNumberOfPoints();
      for (vtkIdType i = 0; i < count; ++i)
      {
        double p[3];
        in->GetPoint(i, p);
        double w = m[12] * p[0] + m[13] * p[1] + m[14] * p[2] + m[15];
        w = w != 0.0 ? 1.0 / w : 1.0;
        points->SetPoint(entry.PointOffset + i,
          (m[0] * p[0] + m[1] * p[1] + m[2] * p[2] + m[3]) * w,
          (m[4] * p[0] + m[5] * p[1] + m[6] * p[2] + m[7]) * w,
          (m[8] * p[0] + m[9] * p[1] + m[10] * p[2] + m[11]) * w);
        if (normals && inNormals)
        {
          double n[3];
          inNormals->GetTuple(i, n);
          const double(*a)[4] = normalMatrix->Element;
          double r[3] = { a[0][0] * n[0] + a[0][1] * n[1] + a[0][2] * n[2],
            a[1][0] * n[0] + a[1][1] * n[1] + a[1][2] * n[2],
            a[2][0] * n[0] + a[2][1] * n[1] + a[2][2] * n[2] };
          const double length = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
          if (length > 0.0)
          {
            r[0] /= length;
            r[1] /= length;
            r[2] /= length;
          }
          normalArray->SetTuple(entry.PointOffset + i, r);
        }
      }
    }
    vtkNew<vtkUnsignedCharArray> colors;
    colors->SetName("Colors");
    colors->SetNumberOfComponents(4);
    colors->SetNumberOfTuples(total);
    group.Points = vtkSmartPointer<vtkPolyData>::New();
    group.Points->SetPoints(points);
    group.Points->GetPointData()->SetScalars(colors);
    if (normals)
    {
      group.Points->GetPointData()->SetNormals(normalArray);
    }
    group.Helper->SetInputData(group.Points);
  }
  for (std::size_t b = batches; b < this->BatchHelpers.size(); ++b)
  {
    this->UploadsOfReleasedHelpers += this->BatchHelpers[b].first->GetNumberOfIndexUploads();
  }
  this->BatchHelpers.resize(batches);

  // Every group's fragment set: its actors' split points after its input points (an actor's
  // point id p becomes PointOffset + p below its input's count, else its split's id here), and
  // the fragments in global order.
  std::vector<std::shared_ptr<vtkBSPFragmentSet>> sets(groups.size());
  for (std::size_t g = 0; g < groups.size(); ++g)
  {
    sets[g] = std::make_shared<vtkBSPFragmentSet>();
    sets[g]->Input =
      groups[g].Batched ? groups[g].Points.Get() : this->Entries[groups[g].Members[0]].Input;
  }
  const vtkBSPPassOrder& source = this->Source;
  std::vector<vtkIdType> splitBase(this->Entries.size());
  for (std::size_t k = 0; k < this->Entries.size(); ++k)
  {
    const Entry& entry = this->Entries[k];
    vtkBSPFragmentSet& set = *sets[entry.Group];
    const vtkIdType inputPoints = entry.Input->GetNumberOfPoints();
    splitBase[k] = set.Input->GetNumberOfPoints() + static_cast<vtkIdType>(set.Splits.size());
    const auto toSet = [&](std::uint32_t p)
    {
      return static_cast<std::uint32_t>(
        p < inputPoints ? entry.PointOffset + p : splitBase[k] + (p - inputPoints));
    };
    for (const bsp::SplitPoint& split : source.ActorSplits[k])
    {
      set.Splits.push_back({ toSet(split.a), toSet(split.b), split.t });
    }
  }
  const std::size_t fragmentCount = source.FragmentCount();
  this->FragmentGroup.resize(fragmentCount);
  this->FragmentLocal.resize(fragmentCount);
  for (std::size_t f = 0; f < fragmentCount; ++f)
  {
    const std::uint32_t k = source.FragmentActor[f];
    const Entry& entry = this->Entries[k];
    const auto g = static_cast<std::uint32_t>(entry.Group);
    vtkBSPFragmentSet& set = *sets[g];
    const vtkIdType inputPoints = entry.Input->GetNumberOfPoints();
    this->FragmentGroup[f] = g;
    this->FragmentLocal[f] = static_cast<std::uint32_t>(set.FragmentCount());
    for (std::uint32_t v = source.Offsets[f]; v < source.Offsets[f + 1]; ++v)
    {
      const std::uint32_t p = source.Vertices[v];
      set.Vertices.push_back(static_cast<std::uint32_t>(
        p < inputPoints ? entry.PointOffset + p : splitBase[k] + (p - inputPoints)));
    }
    set.Offsets.push_back(static_cast<std::uint32_t>(set.Vertices.size()));
    set.Cells.push_back(source.Cells[f]);
  }
  this->Groups = std::move(groups);
  for (std::size_t g = 0; g < this->Groups.size(); ++g)
  {
    Group& group = this->Groups[g];
    group.Fragments = sets[g];
    group.DrawingMapper(this->Entries)->SetExternalFragments(sets[g]);
    if (group.Batched)
    {
      this->BakeColors(group);
    }
  }
  ++this->TreeBuilds;
  this->LastBuildTime = SecondsSince(start);
}

//------------------------------------------------------------------------------
void vtkBSPTranslucentPass::Internals::UpdateRuns()
{
  for (Group& group : this->Groups)
  {
    group.LocalOrder.clear();
    group.Cursor = 0;
  }
  this->Runs.clear();
  const std::size_t none = static_cast<std::size_t>(-1);
  std::size_t current = none;
  for (std::uint32_t f : this->Source.Order())
  {
    const std::uint32_t g = this->FragmentGroup[f];
    Group& group = this->Groups[g];
    const std::uint32_t local = this->FragmentLocal[f];
    const std::vector<std::uint32_t>& offsets = group.Fragments->Offsets;
    const vtkIdType indices = 3 * (static_cast<vtkIdType>(offsets[local + 1] - offsets[local]) - 2);
    if (g != current)
    {
      this->Runs.push_back({ g, group.Cursor, 0 });
      current = g;
    }
    this->Runs.back().indexCount += indices;
    group.Cursor += indices;
    group.LocalOrder.push_back(local);
  }
  for (Group& group : this->Groups)
  {
    group.DrawingMapper(this->Entries)->SetExternalOrder(group.LocalOrder);
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
  for (auto& helper : this->Internal->BatchHelpers)
  {
    helper.first->ReleaseGraphicsResources(w);
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
      input = SortableInput(mapper);
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

  // Rebuild only when the set of actors, a matrix, an input or the grouping changed.
  bool rebuild = sorted.size() != internal.Entries.size() || !internal.Built;
  std::vector<bool> mapperChanged(sorted.size(), false);
  std::vector<Internals::Entry> entries;
  entries.reserve(sorted.size());
  // Last frame's entry of each actor: at the same index when the actors did not change (the
  // usual frame), else looked up by actor (a map made only then: no scan per actor).
  std::unordered_map<vtkActor*, std::size_t> previous;
  auto previousEntry = [&](std::size_t k) -> const Internals::Entry*
  {
    if (k < internal.Entries.size() && internal.Entries[k].Actor == sorted[k])
    {
      return &internal.Entries[k];
    }
    if (previous.empty())
    {
      for (std::size_t e = 0; e < internal.Entries.size(); ++e)
      {
        previous.emplace(internal.Entries[e].Actor.Get(), e);
      }
    }
    const auto found = previous.find(sorted[k]);
    return found == previous.end() ? nullptr : &internal.Entries[found->second];
  };
  for (std::size_t k = 0; k < sorted.size(); ++k)
  {
    Internals::Entry entry;
    if (const Internals::Entry* same = previousEntry(k))
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
      mapperChanged[k] = true;
    }
    bool inputChanged = false; // its cell colours' uniformity is found again below
    if (entry.Input != inputs[k] || entry.InputMTime != inputs[k]->GetMTime())
    {
      entry.Input = inputs[k];
      entry.InputMTime = inputs[k]->GetMTime();
      rebuild = true;
      inputChanged = true;
    }
    if (entry.Helper->GetInputDataObject(0, 0) != inputs[k])
    {
      // A composite input (see SortableInput): the helper, a copy of the mapper, would read the
      // composite; it draws the polydata block.
      entry.Helper->SetInputData(inputs[k]);
    }
    const double* m = &sorted[k]->GetMatrix()->Element[0][0];
    if (!std::equal(m, m + 16, entry.Matrix.begin()))
    {
      std::copy(m, m + 16, entry.Matrix.begin());
      rebuild = true;
    }
    if (mapperChanged[k] || inputChanged)
    {
      entry.UniformCellScalars = UniformCellScalars(mappers[k], inputs[k]);
    }
    entry.BatchKey = internal.Batching
      ? BatchKey(sorted[k], mappers[k], inputs[k], entry.UniformCellScalars)
      : std::vector<double>();
    entries.push_back(std::move(entry));
  }
  // Helpers of actors that left: their uploads still count (a set made only when some left).
  bool sameHelpers = entries.size() == internal.Entries.size();
  for (std::size_t k = 0; sameHelpers && k < entries.size(); ++k)
  {
    sameHelpers = entries[k].Helper == internal.Entries[k].Helper;
  }
  if (!sameHelpers)
  {
    std::unordered_set<vtkBSPSortedPolyDataMapper*> kept;
    for (const Internals::Entry& entry : entries)
    {
      kept.insert(entry.Helper.Get());
    }
    for (const Internals::Entry& old : internal.Entries)
    {
      if (kept.count(old.Helper.Get()) == 0)
      {
        internal.UploadsOfReleasedHelpers += old.Helper->GetNumberOfIndexUploads();
      }
    }
  }
  internal.Entries = std::move(entries);
  std::vector<Internals::Group> groups = internal.Partition();
  if (rebuild || !internal.SamePartition(groups))
  {
    internal.Build(std::move(groups));
  }
  else
  {
    // A batched actor's colour, opacity, lookup table or scalar settings changed: bake the
    // colours of its group again (the tree and the order stay).
    for (Internals::Group& group : internal.Groups)
    {
      if (!group.Batched)
      {
        continue;
      }
      bool bake = false;
      for (std::size_t k : group.Members)
      {
        const Internals::Entry& entry = internal.Entries[k];
        bake = bake || mapperChanged[k] || entry.ColorKey != ColorKey(entry.Actor, entry.Mapper);
      }
      if (bake)
      {
        internal.BakeColors(group);
      }
    }
  }
  // The shared property of a batch: its first actor's, with colour and opacity in the points.
  for (Internals::Group& group : internal.Groups)
  {
    if (group.Batched)
    {
      vtkProperty* property = internal.Entries[group.Members[0]].Actor->GetProperty();
      if (group.PropertyMTime != property->GetMTime() ||
        group.Actor->GetProperty()->GetOpacity() != 1.0)
      {
        group.Actor->GetProperty()->DeepCopy(property);
        group.Actor->GetProperty()->SetOpacity(1.0);
        group.PropertyMTime = property->GetMTime();
      }
    }
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
    const bool changed = internal.Source.Update(view);
    ++internal.OrderUpdates;
    if (!internal.HaveView || changed)
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

  // Draw the runs, each with its actor's (or its batch's) property, texture and matrix.
  for (const Run& run : internal.Runs)
  {
    const Internals::Group& group = internal.Groups[run.group];
    vtkBSPSortedPolyDataMapper* helper = group.DrawingMapper(internal.Entries);
    vtkActor* actor = group.DrawingActor(internal.Entries);
    helper->SetDrawRange(run.firstIndex, run.indexCount);
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
    DrawWith(actor, helper, renderer, internal.Device);
    property->PostRender(actor, renderer);
    if (vtkTexture* texture = actor->GetTexture())
    {
      texture->PostRender(renderer);
    }
    actor->SetIsRenderingTranslucentPolygonalGeometry(false);
    helper->SetDrawRange(-1, -1);
  }
  this->NumberOfRenderedProps += static_cast<int>(internal.Entries.size());
}

//------------------------------------------------------------------------------
int vtkBSPTranslucentPass::GetNumberOfBatchGroups() const
{
  return static_cast<int>(std::count_if(this->Internal->Groups.begin(),
    this->Internal->Groups.end(), [](const Internals::Group& g) { return g.Batched; }));
}

int vtkBSPTranslucentPass::GetNumberOfBatchedActors() const
{
  int actors = 0;
  for (const Internals::Group& group : this->Internal->Groups)
  {
    actors += group.Batched ? static_cast<int>(group.Members.size()) : 0;
  }
  return actors;
}

vtkIdType vtkBSPTranslucentPass::GetNumberOfColorBakes() const
{
  return this->Internal->ColorBakes;
}

void vtkBSPTranslucentPass::SetBatching(bool batching)
{
  if (this->Internal->Batching != batching)
  {
    this->Internal->Batching = batching;
    this->Modified();
  }
}

bool vtkBSPTranslucentPass::GetBatching() const
{
  return this->Internal->Batching;
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
  return static_cast<vtkIdType>(this->Internal->Source.FragmentCount());
}

vtkIdType vtkBSPTranslucentPass::GetNumberOfSplits() const
{
  return static_cast<vtkIdType>(this->Internal->Source.Splits());
}

int vtkBSPTranslucentPass::GetLastBuildTreeCount() const
{
  return static_cast<int>(this->Internal->Source.TreesBuilt());
}

int vtkBSPTranslucentPass::GetNumberOfPartGroups() const
{
  return static_cast<int>(this->Internal->Source.Groups());
}

void vtkBSPTranslucentPass::SetTwoLevelOrder(bool twoLevels)
{
  if (this->Internal->TwoLevels != twoLevels)
  {
    this->Internal->TwoLevels = twoLevels;
    this->Internal->Built = false; // the next render builds the other way
    this->Modified();
  }
}

bool vtkBSPTranslucentPass::GetTwoLevelOrder() const
{
  return this->Internal->TwoLevels;
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
  for (const auto& helper : this->Internal->BatchHelpers)
  {
    uploads += helper.first->GetNumberOfIndexUploads();
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
  const vtkBSPPassOrder& source = internal.Source;
  if (source.Order().empty())
  {
    return;
  }
  // Every actor's points in world coordinates (its input's, then its split points), one actor
  // after the other.
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  std::vector<vtkIdType> base;
  for (std::size_t k = 0; k < internal.Entries.size(); ++k)
  {
    const Internals::Entry& entry = internal.Entries[k];
    base.push_back(points->GetNumberOfPoints());
    std::vector<std::array<double, 3>> local;
    for (vtkIdType i = 0; i < entry.Input->GetNumberOfPoints(); ++i)
    {
      std::array<double, 3> p;
      entry.Input->GetPoint(i, p.data());
      local.push_back(p);
    }
    for (const bsp::SplitPoint& split : source.ActorSplits[k])
    {
      const std::array<double, 3> a = local[split.a];
      const std::array<double, 3> b = local[split.b];
      local.push_back({ a[0] + split.t * (b[0] - a[0]), a[1] + split.t * (b[1] - a[1]),
        a[2] + split.t * (b[2] - a[2]) });
    }
    const double* m = entry.Matrix.data();
    for (const std::array<double, 3>& p : local)
    {
      double w = m[12] * p[0] + m[13] * p[1] + m[14] * p[2] + m[15];
      w = w != 0.0 ? 1.0 / w : 1.0;
      points->InsertNextPoint((m[0] * p[0] + m[1] * p[1] + m[2] * p[2] + m[3]) * w,
        (m[4] * p[0] + m[5] * p[1] + m[6] * p[2] + m[7]) * w,
        (m[8] * p[0] + m[9] * p[1] + m[10] * p[2] + m[11]) * w);
    }
  }
  vtkNew<vtkCellArray> polys;
  vtkNew<vtkIntArray> actorIndex;
  actorIndex->SetName("ActorIndex");
  vtkNew<vtkIdTypeArray> fragmentId;
  fragmentId->SetName("FragmentId");
  std::vector<vtkIdType> ids;
  for (std::uint32_t f : source.Order())
  {
    const std::uint32_t k = source.FragmentActor[f];
    ids.clear();
    for (std::uint32_t v = source.Offsets[f]; v < source.Offsets[f + 1]; ++v)
    {
      ids.push_back(base[k] + source.Vertices[v]);
    }
    polys->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
    actorIndex->InsertNextValue(static_cast<int>(k));
    fragmentId->InsertNextValue(f);
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
  os << indent << "NumberOfBatchGroups: " << this->GetNumberOfBatchGroups() << "\n";
  os << indent << "Batching: " << this->GetBatching() << "\n";
  os << indent << "NumberOfTreeBuilds: " << this->GetNumberOfTreeBuilds() << "\n";
  os << indent << "TwoLevelOrder: " << this->GetTwoLevelOrder() << "\n";
  os << indent << "NumberOfPartGroups: " << this->GetNumberOfPartGroups() << "\n";
}
