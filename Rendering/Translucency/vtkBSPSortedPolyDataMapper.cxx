#include "vtkBSPSortedPolyDataMapper.h"

#include "vtkBSPSortUtilities.h"

#include "vtkBSPFragmentSet.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkIdTypeArray.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLIndexBufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLVertexBufferObjectGroup.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkStateStorage.h"
#include "vtkUnsignedCharArray.h"
#include "vtk_glew.h"

#include "scenevis/BspBuilder.h"
#include "scenevis/BspTraversal.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>

vtkStandardNewMacro(vtkBSPSortedPolyDataMapper);

namespace
{
namespace bsp = scenevis::bsp;

double SecondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Whether drawing @p input with the mapper's colour settings needs per-fragment vertices
/// (cell scalars, or cell normals without point normals).
bool NeedsCellExpansion(vtkMapper* mapper, vtkPolyData* input)
{
  if (mapper->GetScalarVisibility())
  {
    int cellFlag = 0;
    vtkAbstractArray* scalars =
      vtkAbstractMapper::GetAbstractScalars(input, mapper->GetScalarMode(),
        mapper->GetArrayAccessMode(), mapper->GetArrayId(), mapper->GetArrayName(), cellFlag);
    if (scalars && cellFlag == 1)
    {
      return true;
    }
  }
  return input->GetCellData()->GetNormals() != nullptr &&
    input->GetPointData()->GetNormals() == nullptr;
}

/**
 * Classes of cells whose values are the same bits in every cell array of @p cellData: cells of
 * one class may share expanded vertices (each vertex carries its cell's values). Every cell is a
 * class of its own when an array is not numeric. Cells are sorted by a hash of their values, and
 * neighbours in that order compared in full: 16 bytes a cell however many distinct values there
 * are (cell normals, a scalar field).
 */
std::vector<std::uint32_t> CellValueClasses(vtkCellData* cellData, vtkIdType cellCount)
{
  const auto n = static_cast<std::size_t>(cellCount);
  std::vector<std::uint32_t> classOf(n);
  std::vector<vtkDataArray*> arrays;
  std::size_t width = 0;
  for (int a = 0; a < cellData->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* array = vtkDataArray::SafeDownCast(cellData->GetAbstractArray(a));
    if (!array || array->GetNumberOfTuples() < cellCount)
    {
      for (std::size_t c = 0; c < n; ++c)
      {
        classOf[c] = static_cast<std::uint32_t>(c);
      }
      return classOf;
    }
    arrays.push_back(array);
    width += static_cast<std::size_t>(array->GetNumberOfComponents());
  }
  // The values of cell c, as bytes (8 per component).
  const auto values = [&arrays](vtkIdType c, std::vector<double>& out)
  {
    std::size_t at = 0;
    for (vtkDataArray* array : arrays)
    {
      array->GetTuple(c, out.data() + at);
      at += static_cast<std::size_t>(array->GetNumberOfComponents());
    }
  };
  std::vector<double> tuple(width), other(width);
  std::vector<std::pair<std::uint64_t, std::uint32_t>> hashed(n);
  for (std::size_t c = 0; c < n; ++c)
  {
    values(static_cast<vtkIdType>(c), tuple);
    std::uint64_t h = 1469598103934665603ull; // FNV-1a over the bytes
    const auto* bytes = reinterpret_cast<const unsigned char*>(tuple.data());
    for (std::size_t b = 0; b < width * sizeof(double); ++b)
    {
      h = (h ^ bytes[b]) * 1099511628211ull;
    }
    hashed[c] = { h, static_cast<std::uint32_t>(c) };
  }
  std::sort(hashed.begin(), hashed.end());
  // Within a run of equal hashes, a cell joins the class of the nearest earlier cell of the run
  // with the same bytes (runs of different values are rare: hash collisions).
  std::uint32_t classes = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    const std::uint32_t c = hashed[i].second;
    values(c, tuple);
    bool found = false;
    for (std::size_t j = i; !found && j > 0 && hashed[j - 1].first == hashed[i].first; --j)
    {
      values(hashed[j - 1].second, other);
      if (std::memcmp(tuple.data(), other.data(), width * sizeof(double)) == 0)
      {
        classOf[c] = classOf[hashed[j - 1].second];
        found = true;
      }
    }
    if (!found)
    {
      classOf[c] = classes++;
    }
  }
  return classOf;
}

/// The scalar mode that finds, in the expanded point data, what `mode` found in the cell data.
int ExpandedScalarMode(int mode)
{
  switch (mode)
  {
    case VTK_SCALAR_MODE_USE_CELL_DATA:
      return VTK_SCALAR_MODE_USE_POINT_DATA;
    case VTK_SCALAR_MODE_USE_CELL_FIELD_DATA:
      return VTK_SCALAR_MODE_USE_POINT_FIELD_DATA;
    default:
      return mode;
  }
}
} // namespace

//------------------------------------------------------------------------------
struct vtkBSPSortedPolyDataMapper::Internals
{
  // Where the fragments come from: our own tree (standalone) or vtkBSPTranslucentPass.
  bool External = false;
  std::shared_ptr<const vtkBSPFragmentSet> Fragments;

  // Standalone tree and its order.
  std::unique_ptr<bsp::Tree> Tree;
  std::unique_ptr<bsp::IncrementalOrder> Order; // a tree without ordered leaves
  std::vector<std::uint32_t> FullOrder;         // one with them: a full order per camera move
  vtkPolyData* TreeInput = nullptr;             // compared only, never dereferenced
  vtkMTimeType TreeInputMTime = 0;
  int TreeLeafSize = 0; // OrderedLeafSize the tree was built with
  bool HaveView = false;
  scenevis::View LastView;

  // Geometry drawn (built once per fragment set).
  vtkSmartPointer<vtkPolyData> RenderData;
  const vtkBSPFragmentSet* RenderDataFor = nullptr;
  bool RenderDataExpanded = false;
  vtkMTimeType RenderDataMapperMTime = 0;
  std::vector<unsigned int> TriIndices;       // triangles of every fragment, fragment id order
  std::vector<std::uint32_t> TriOffsets{ 0 }; // fragment f: TriIndices[TriOffsets[f]..[f+1])
  vtkPolyData* BuffersBuiltFrom = nullptr;    // compared only
  bool DrewFragments = false;

  // Order in the index buffer.
  std::vector<std::uint32_t> UploadedOrder; // fragment ids as in the IBO (valid if IBOHasOrder)
  std::vector<std::size_t> UploadedAt;      // where each of them starts in the IBO (indices)
  bool IBOHasOrder = false;
  std::vector<std::uint32_t> PendingOrder; // external order to upload
  bool PendingDirty = false;
  std::vector<unsigned int> Scratch;
  vtkIdType DrawFirst = -1;
  vtkIdType DrawCount = -1;

  // State of the current render (set in UpdateCameraShiftScale).
  bool Expanded = false;
  bool Sortable = false;
  int SavedScalarMode = VTK_SCALAR_MODE_DEFAULT;

  // Instrumentation.
  vtkIdType IndexUploads = 0;
  vtkIdType PartialIndexUploads = 0;
  std::size_t LastUploadIndices = 0; // indices sent to the GPU by the last upload
  vtkIdType OrderUpdates = 0;
  vtkIdType TreeBuilds = 0;
  vtkIdType VertexBufferBuilds = 0;
  double LastBuildTime = 0.0;
  double LastOrderTime = 0.0;
  double LastUploadTime = 0.0;

  /// Index ranges [first, end) of the buffer rewritten by UploadChanges (scratch, kept).
  std::vector<std::pair<std::size_t, std::size_t>> Runs;

  /**
   * The index buffer holds UploadedOrder and Scratch mirrors it: rewrite in Scratch only the
   * fragments whose place in @p order changed, and send only those index ranges
   * (glBufferSubData; ranges closer than a few kilobytes are sent as one). The incremental order
   * moves few fragments per small camera step. Sends everything (glBufferData) when more than
   * half changed. Returns false, with the mirror left to be rebuilt, when @p order does not lay
   * out the same number of indices (another set of fragments).
   */
  bool UploadChanges(vtkOpenGLIndexBufferObject* ibo, const std::vector<std::uint32_t>& order)
  {
    constexpr std::size_t kGap = 1024; // indices: smaller gaps are sent along with their runs
    this->Runs.clear();
    std::size_t at = 0, dirty = 0;
    unsigned int* mirror = this->Scratch.data();
    std::uint32_t* old = this->UploadedOrder.data();
    const std::size_t n = order.size();
    for (std::size_t i = 0; i < n;)
    {
      if (order[i] == old[i] && at == this->UploadedAt[i])
      {
        // Where the buffer already holds this fragment: skip the whole stretch that is unchanged
        // (a fast scan; the fragments before the next change start where they did).
        const std::size_t next = static_cast<std::size_t>(
          std::mismatch(order.begin() + static_cast<std::ptrdiff_t>(i), order.end(),
            this->UploadedOrder.begin() + static_cast<std::ptrdiff_t>(i))
            .first -
          order.begin());
        at = next < n ? this->UploadedAt[next] : this->Scratch.size();
        i = next;
        continue;
      }
      const std::uint32_t f = order[i];
      const std::size_t first = this->TriOffsets[f], count = this->TriOffsets[f + 1] - first;
      if (at + count > this->Scratch.size())
      {
        return false;
      }
      std::copy(
        this->TriIndices.data() + first, this->TriIndices.data() + first + count, mirror + at);
      if (!this->Runs.empty() && at <= this->Runs.back().second + kGap)
      {
        dirty += at + count - this->Runs.back().second;
        this->Runs.back().second = at + count;
      }
      else
      {
        this->Runs.emplace_back(at, at + count);
        dirty += count;
      }
      old[i] = f;
      this->UploadedAt[i] = at;
      at += count;
      ++i;
    }
    if (at != this->Scratch.size())
    {
      return false;
    }
    if (dirty > this->Scratch.size() / 2)
    {
      ibo->Upload(this->Scratch, vtkOpenGLBufferObject::ElementArrayBuffer);
      this->LastUploadIndices = this->Scratch.size();
    }
    else
    {
      // Bound as Upload() leaves it (the element array binding belongs to the mapper's VAO).
      ibo->Bind();
      for (const auto& run : this->Runs)
      {
        glBufferSubData(GL_ELEMENT_ARRAY_BUFFER,
          static_cast<GLintptr>(run.first * sizeof(unsigned int)),
          static_cast<GLsizeiptr>((run.second - run.first) * sizeof(unsigned int)),
          mirror + run.first);
      }
      ++this->PartialIndexUploads;
      this->LastUploadIndices = dirty;
    }
    return true;
  }

  void Upload(
    vtkOpenGLIndexBufferObject* ibo, const std::vector<std::uint32_t>& order, bool partial)
  {
    const auto start = std::chrono::steady_clock::now();
    if (partial && this->IBOHasOrder && order.size() == this->UploadedOrder.size() && ibo->GetHandle() &&
      static_cast<std::size_t>(ibo->IndexCount) == this->Scratch.size() &&
      this->UploadChanges(ibo, order))
    {
      ++this->IndexUploads;
      this->LastUploadTime = SecondsSince(start);
      return;
    }
    std::size_t total = 0;
    for (std::uint32_t f : order)
    {
      total += this->TriOffsets[f + 1] - this->TriOffsets[f];
    }
    this->Scratch.resize(total);
    this->UploadedAt.resize(order.size());
    unsigned int* out = this->Scratch.data();
    for (std::size_t i = 0; i < order.size(); ++i)
    {
      const std::uint32_t f = order[i];
      this->UploadedAt[i] = static_cast<std::size_t>(out - this->Scratch.data());
      const unsigned int* first = this->TriIndices.data() + this->TriOffsets[f];
      const unsigned int* last = this->TriIndices.data() + this->TriOffsets[f + 1];
      out = std::copy(first, last, out);
    }
    if (total > 0)
    {
      ibo->Upload(this->Scratch, vtkOpenGLBufferObject::ElementArrayBuffer);
    }
    ibo->IndexCount = total;
    this->LastUploadIndices = total;
    this->UploadedOrder = order;
    this->IBOHasOrder = true;
    ++this->IndexUploads;
    this->LastUploadTime = SecondsSince(start);
  }

  void BuildRenderData(vtkMapper* mapper, bool expand);
};

//------------------------------------------------------------------------------
void vtkBSPSortedPolyDataMapper::Internals::BuildRenderData(vtkMapper* mapper, bool expand)
{
  const vtkBSPFragmentSet& set = *this->Fragments;
  vtkPolyData* input = set.Input;

  // Positions and point data over input + split points.
  vtkNew<vtkPoints> points;
  vtkNew<vtkPointData> pointData;
  vtkBSPSortUtilities::InterpolateSplitPoints(
    input, set.Splits.data(), set.Splits.size(), points, pointData);

  // The triangles of every fragment (size - 2 each; no flat ones where its sides carry split
  // points), as indices into set.Vertices.
  const std::size_t fragmentCount = set.FragmentCount();
  this->TriOffsets.assign(fragmentCount + 1, 0);
  for (std::size_t f = 0; f < fragmentCount; ++f)
  {
    const std::uint32_t n = set.Offsets[f + 1] - set.Offsets[f];
    this->TriOffsets[f + 1] = this->TriOffsets[f] + 3 * (n - 2);
  }
  std::vector<std::uint32_t> triangleCorners;
  triangleCorners.reserve(this->TriOffsets.back());
  vtkBSPSortUtilities::TriangulateFragments(input, set.Splits.data(), set.Splits.size(),
    set.Offsets.data(), fragmentCount, set.Vertices.data(), triangleCorners);
  this->TriIndices.resize(this->TriOffsets.back());
  auto result = vtkSmartPointer<vtkPolyData>::New();
  if (!expand)
  {
    std::transform(triangleCorners.begin(), triangleCorners.end(), this->TriIndices.begin(),
      [&set](std::uint32_t corner) { return set.Vertices[corner]; });
    result->SetPoints(points);
    result->GetPointData()->ShallowCopy(pointData);
    result->SetVerts(input->GetVerts());
    result->SetLines(input->GetLines());
  }
  else
  {
    // Each fragment's vertices carry its cell's values as point values. A vertex is shared by
    // the fragments that use the same point and whose cells have the same values in every cell
    // array (the cells of one part, say): the same attributes, so the same image, with a
    // fraction of the vertices to shade and store (a vertex of its own per fragment corner was
    // 5.5M vertices for the 1M-triangle sphere grid, 1.18M shared).
    const std::vector<std::uint32_t> cellClass =
      CellValueClasses(input->GetCellData(), input->GetNumberOfCells());
    const std::size_t corners = set.Vertices.size();
    std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(corners);
    std::vector<vtkIdType> cellOfCorner(corners);
    for (std::size_t f = 0; f < fragmentCount; ++f)
    {
      const std::uint64_t cls = cellClass[static_cast<std::size_t>(set.Cells[f])];
      for (std::uint32_t i = set.Offsets[f]; i < set.Offsets[f + 1]; ++i)
      {
        keyed[i] = { (cls << 32) | set.Vertices[i], i };
        cellOfCorner[i] = set.Cells[f];
      }
    }
    std::sort(keyed.begin(), keyed.end());
    // One vertex per distinct key, from the first corner with it.
    std::vector<std::uint32_t> vertexOf(corners);
    std::vector<vtkIdType> sourcePoint, sourceCell;
    for (std::size_t k = 0; k < corners; ++k)
    {
      if (k == 0 || keyed[k].first != keyed[k - 1].first)
      {
        sourcePoint.push_back(set.Vertices[keyed[k].second]);
        sourceCell.push_back(cellOfCorner[keyed[k].second]);
      }
      vertexOf[keyed[k].second] = static_cast<std::uint32_t>(sourcePoint.size() - 1);
    }
    const vtkIdType numExpanded = static_cast<vtkIdType>(sourcePoint.size());
    vtkNew<vtkPoints> expandedPoints;
    expandedPoints->SetDataType(points->GetDataType());
    expandedPoints->SetNumberOfPoints(numExpanded);
    for (vtkIdType i = 0; i < numExpanded; ++i)
    {
      expandedPoints->SetPoint(i, points->GetPoint(sourcePoint[static_cast<std::size_t>(i)]));
    }
    std::transform(triangleCorners.begin(), triangleCorners.end(), this->TriIndices.begin(),
      [&vertexOf](std::uint32_t corner) { return vertexOf[corner]; });
    auto gather = [numExpanded](vtkAbstractArray* source, const std::vector<vtkIdType>& from)
    {
      vtkAbstractArray* array = source->NewInstance();
      if (!array)
      {
        return vtkSmartPointer<vtkAbstractArray>();
      }
      array->SetName(source->GetName());
      array->SetNumberOfComponents(source->GetNumberOfComponents());
      array->SetNumberOfTuples(numExpanded);
      for (vtkIdType i = 0; i < numExpanded; ++i)
      {
        array->SetTuple(i, from[static_cast<std::size_t>(i)], source);
      }
      if (auto* data = vtkDataArray::SafeDownCast(source))
      {
        if (data->GetLookupTable())
        {
          vtkDataArray::SafeDownCast(array)->SetLookupTable(data->GetLookupTable());
        }
      }
      return vtkSmartPointer<vtkAbstractArray>::Take(array);
    };
    // Point data = the cell arrays in cell-data order (so array ids keep meaning), the cell
    // scalars as active scalars, then point normals / texture coordinates if the input has them.
    vtkPointData* outPD = result->GetPointData();
    vtkCellData* inCD = input->GetCellData();
    int cellFlag = 0;
    vtkAbstractArray* cellScalars =
      vtkAbstractMapper::GetAbstractScalars(input, mapper->GetScalarMode(),
        mapper->GetArrayAccessMode(), mapper->GetArrayId(), mapper->GetArrayName(), cellFlag);
    for (int a = 0; a < inCD->GetNumberOfArrays(); ++a)
    {
      vtkAbstractArray* source = inCD->GetAbstractArray(a);
      auto copy = gather(source, sourceCell);
      if (!copy)
      {
        continue;
      }
      const int index = outPD->AddArray(copy);
      if (source == cellScalars && cellFlag == 1)
      {
        outPD->SetActiveAttribute(index, vtkDataSetAttributes::SCALARS);
      }
      if (source == inCD->GetNormals() && !pointData->GetNormals())
      {
        outPD->SetActiveAttribute(index, vtkDataSetAttributes::NORMALS);
      }
    }
    if (vtkDataArray* normals = pointData->GetNormals())
    {
      auto copy = gather(normals, sourcePoint);
      const int index = copy ? outPD->AddArray(copy) : -1;
      if (index >= 0)
      {
        outPD->SetActiveAttribute(index, vtkDataSetAttributes::NORMALS);
      }
    }
    if (vtkDataArray* tcoords = pointData->GetTCoords())
    {
      auto copy = gather(tcoords, sourcePoint);
      const int index = copy ? outPD->AddArray(copy) : -1;
      if (index >= 0)
      {
        outPD->SetActiveAttribute(index, vtkDataSetAttributes::TCOORDS);
      }
    }
    result->SetPoints(expandedPoints);
  }
  vtkNew<vtkIdTypeArray> offsets;
  const vtkIdType numTriangles = static_cast<vtkIdType>(this->TriIndices.size() / 3);
  offsets->SetNumberOfTuples(numTriangles + 1);
  for (vtkIdType t = 0; t <= numTriangles; ++t)
  {
    offsets->SetValue(t, 3 * t);
  }
  vtkNew<vtkIdTypeArray> connectivity;
  connectivity->SetNumberOfTuples(static_cast<vtkIdType>(this->TriIndices.size()));
  std::copy(this->TriIndices.begin(), this->TriIndices.end(), connectivity->GetPointer(0));
  vtkNew<vtkCellArray> polys;
  polys->SetData(offsets, connectivity);
  result->SetPolys(polys);

  this->RenderData = result;
  this->RenderDataFor = this->Fragments.get();
  this->RenderDataExpanded = expand;
  this->IBOHasOrder = false;
}

//------------------------------------------------------------------------------
vtkBSPSortedPolyDataMapper::vtkBSPSortedPolyDataMapper()
  : Internal(new Internals)
{
}

//------------------------------------------------------------------------------
vtkBSPSortedPolyDataMapper::~vtkBSPSortedPolyDataMapper() = default;

//------------------------------------------------------------------------------
vtkIdType vtkBSPSortedPolyDataMapper::GetNumberOfIndexUploads() const
{
  return this->Internal->IndexUploads;
}

//------------------------------------------------------------------------------
vtkIdType vtkBSPSortedPolyDataMapper::GetNumberOfPartialIndexUploads() const
{
  return this->Internal->PartialIndexUploads;
}

//------------------------------------------------------------------------------
vtkIdType vtkBSPSortedPolyDataMapper::GetLastUploadIndexCount() const
{
  return static_cast<vtkIdType>(this->Internal->LastUploadIndices);
}

vtkIdType vtkBSPSortedPolyDataMapper::GetNumberOfOrderUpdates() const
{
  return this->Internal->OrderUpdates;
}

vtkIdType vtkBSPSortedPolyDataMapper::GetNumberOfTreeBuilds() const
{
  return this->Internal->TreeBuilds;
}

vtkIdType vtkBSPSortedPolyDataMapper::GetNumberOfVertexBufferBuilds() const
{
  return this->Internal->VertexBufferBuilds;
}

vtkIdType vtkBSPSortedPolyDataMapper::GetNumberOfFragments() const
{
  return this->Internal->Fragments
    ? static_cast<vtkIdType>(this->Internal->Fragments->FragmentCount())
    : 0;
}

vtkIdType vtkBSPSortedPolyDataMapper::GetNumberOfFragmentTriangles() const
{
  return static_cast<vtkIdType>(this->Internal->TriOffsets.back() / 3);
}

vtkIdType vtkBSPSortedPolyDataMapper::GetNumberOfFragmentVertices() const
{
  vtkPolyData* data = this->Internal->RenderData;
  return data ? data->GetNumberOfPoints() : 0;
}

bool vtkBSPSortedPolyDataMapper::GetLastRenderDrewFragments() const
{
  return this->Internal->DrewFragments;
}

double vtkBSPSortedPolyDataMapper::GetLastBuildTime() const
{
  return this->Internal->LastBuildTime;
}

double vtkBSPSortedPolyDataMapper::GetLastOrderTime() const
{
  return this->Internal->LastOrderTime;
}

double vtkBSPSortedPolyDataMapper::GetLastUploadTime() const
{
  return this->Internal->LastUploadTime;
}

void vtkBSPSortedPolyDataMapper::GetFragmentOrder(std::vector<vtkIdType>& cellIds) const
{
  cellIds.clear();
  const Internals& internal = *this->Internal;
  if (!internal.Fragments || !internal.IBOHasOrder)
  {
    return;
  }
  cellIds.reserve(internal.UploadedOrder.size());
  for (std::uint32_t f : internal.UploadedOrder)
  {
    cellIds.push_back(internal.Fragments->Cells[f]);
  }
}

//------------------------------------------------------------------------------
void vtkBSPSortedPolyDataMapper::SetExternalFragments(
  std::shared_ptr<const vtkBSPFragmentSet> fragments)
{
  Internals& internal = *this->Internal;
  internal.External = true;
  internal.Tree.reset();
  internal.Order.reset();
  internal.Fragments = std::move(fragments);
  internal.PendingOrder.clear();
  internal.PendingDirty = true;
  internal.IBOHasOrder = false;
}

void vtkBSPSortedPolyDataMapper::SetExternalOrder(const std::vector<std::uint32_t>& order)
{
  Internals& internal = *this->Internal;
  if (!internal.IBOHasOrder || order != internal.UploadedOrder)
  {
    internal.PendingOrder = order;
    internal.PendingDirty = true;
  }
}

void vtkBSPSortedPolyDataMapper::InvalidateExternalGeometry()
{
  this->Internal->RenderData = nullptr;
  this->Internal->RenderDataFor = nullptr;
}

void vtkBSPSortedPolyDataMapper::SetDrawRange(vtkIdType firstIndex, vtkIdType indexCount)
{
  this->Internal->DrawFirst = firstIndex;
  this->Internal->DrawCount = indexCount;
}

//------------------------------------------------------------------------------
vtkUnsignedCharArray* vtkBSPSortedPolyDataMapper::MapScalars(double alpha)
{
  // The superclass maps the scalars of GetInput(); ours are those of the geometry drawn.
  int cellFlag = 0;
  return this->MapScalars(
    this->CurrentInput ? this->CurrentInput : this->GetInput(), alpha, cellFlag);
}

//------------------------------------------------------------------------------
void vtkBSPSortedPolyDataMapper::BuildBufferObjects(vtkRenderer* ren, vtkActor* act)
{
  ++this->Internal->VertexBufferBuilds;
  this->Internal->BuffersBuiltFrom = this->CurrentInput;
  this->Superclass::BuildBufferObjects(ren, act);
}

//------------------------------------------------------------------------------
bool vtkBSPSortedPolyDataMapper::GetNeedToRebuildBufferObjects(vtkRenderer* ren, vtkActor* act)
{
  // The superclass compares MTimes only; we also switch between the input and the fragments.
  const bool superclassNeeds = this->Superclass::GetNeedToRebuildBufferObjects(ren, act);
  return superclassNeeds || this->Internal->BuffersBuiltFrom != this->CurrentInput;
}

//------------------------------------------------------------------------------
void vtkBSPSortedPolyDataMapper::BuildIBO(vtkRenderer* ren, vtkActor* act, vtkPolyData* poly)
{
  vtkStateStorage before;
  before = this->IBOBuildState;
  this->Superclass::BuildIBO(ren, act, poly);
  if (before != this->IBOBuildState)
  {
    // The superclass wrote the triangles in fragment order: our order must be uploaded again.
    this->Internal->IBOHasOrder = false;
  }
}

//------------------------------------------------------------------------------
void vtkBSPSortedPolyDataMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Internal->IBOHasOrder = false;
  this->Superclass::ReleaseGraphicsResources(window);
}

//------------------------------------------------------------------------------
void vtkBSPSortedPolyDataMapper::UpdateCameraShiftScale(vtkRenderer* ren, vtkActor* actor)
{
  // vtkOpenGLPolyDataMapper::RenderPiece has updated the pipeline and set CurrentInput to the
  // input; this is the first hook it calls after that. Swap in the fragment geometry here, so
  // that everything that follows (buffer objects, shaders, draw) works on it.
  vtkPolyData* input = this->CurrentInput;
  Internals& internal = *this->Internal;
  const bool translucent = actor->IsRenderingTranslucentPolygonalGeometry() && !ren->GetSelector();
  vtkProperty* property = actor->GetProperty();
  const bool sortable =
    translucent && property->GetRepresentation() == VTK_SURFACE && !property->GetEdgeVisibility();

  // Standalone: (re)build the tree once the actor is drawn translucent, and when the input changes.
  if (!internal.External && (sortable || internal.Tree) &&
    (!internal.Tree || internal.TreeInput != input ||
      internal.TreeInputMTime != input->GetMTime() ||
      internal.TreeLeafSize != this->OrderedLeafSize))
  {
    const auto start = std::chrono::steady_clock::now();
    internal.Order.reset();
    internal.Tree.reset();
    internal.HaveView = false;
    scenevis::PolygonMesh mesh;
    std::vector<vtkIdType> cellOf;
    vtkBSPSortUtilities::AppendPolygons(input, nullptr, mesh, cellOf);
    bsp::BuildConfig config = vtkBSPFragmentSet::BuildConfig();
    config.orderedLeafSize = static_cast<std::uint32_t>(this->OrderedLeafSize);
    auto tree = std::make_unique<bsp::Tree>(bsp::build(mesh, config));
    auto fragments = std::make_shared<vtkBSPFragmentSet>();
    fragments->Input = input;
    fragments->Splits = tree->splitPoints;
    fragments->Offsets.reserve(tree->fragments.size() + 1);
    fragments->Vertices.reserve(tree->fragmentVertices.size());
    fragments->Cells.reserve(tree->fragments.size());
    for (const bsp::Fragment& fragment : tree->fragments)
    {
      fragments->Vertices.insert(fragments->Vertices.end(),
        tree->fragmentVertices.begin() + fragment.first,
        tree->fragmentVertices.begin() + fragment.first + fragment.count);
      fragments->Offsets.push_back(static_cast<std::uint32_t>(fragments->Vertices.size()));
      fragments->Cells.push_back(cellOf[fragment.source]);
    }
    const std::size_t removed =
      tree->statistics.invalidPolygons + tree->statistics.degeneratePolygons;
    if (removed > 0)
    {
      vtkWarningMacro("Removed " << removed
                                 << " polygon(s) with non-finite points, invalid point ids, fewer "
                                    "than 3 distinct points or zero area.");
    }
    internal.Tree = std::move(tree);
    internal.Fragments = std::move(fragments);
    internal.TreeInput = input;
    internal.TreeInputMTime = input->GetMTime();
    internal.TreeLeafSize = this->OrderedLeafSize;
    internal.LastBuildTime = SecondsSince(start);
    ++internal.TreeBuilds;
  }

  // The geometry drawn: the fragments (built once per fragment set) while sorting, otherwise the
  // input itself. An actor that became opaque thus draws its own triangles again, not the 2-3x
  // as many split fragments (switching costs one vertex buffer build each way; the tree and the
  // fragments are kept for when it turns translucent again).
  vtkPolyData* drawn = input;
  bool expanded = false;
  if (internal.Fragments && internal.Fragments->FragmentCount() > 0 &&
    (internal.External || sortable))
  {
    const bool expand = NeedsCellExpansion(this, internal.Fragments->Input);
    if (!internal.RenderData || internal.RenderDataFor != internal.Fragments.get() ||
      internal.RenderDataExpanded != expand ||
      (expand && internal.RenderDataMapperMTime != this->GetMTime()))
    {
      internal.BuildRenderData(this, expand);
      internal.RenderDataMapperMTime = this->GetMTime();
    }
    drawn = internal.RenderData;
    expanded = internal.RenderDataExpanded;
  }
  this->CurrentInput = drawn;
  internal.DrewFragments = drawn != input;
  internal.Expanded = expanded;
  internal.Sortable = sortable;
  this->Superclass::UpdateCameraShiftScale(ren, actor);
}

//------------------------------------------------------------------------------
void vtkBSPSortedPolyDataMapper::RenderPieceStart(vtkRenderer* ren, vtkActor* actor)
{
  Internals& internal = *this->Internal;
  // Cell scalars became point scalars: look for them there (without touching the MTime); restored
  // in RenderPieceFinish.
  internal.SavedScalarMode = this->ScalarMode;
  if (internal.Expanded)
  {
    this->ScalarMode = ExpandedScalarMode(this->ScalarMode);
  }
  this->Superclass::RenderPieceStart(ren, actor);
  const bool sortable = internal.Sortable;

  // Re-order the index buffer (only what the scene calls for).
  vtkOpenGLIndexBufferObject* ibo = this->Primitives[PrimitiveTris].IBO;
  if (internal.External)
  {
    if (internal.PendingDirty || !internal.IBOHasOrder)
    {
      const auto start = std::chrono::steady_clock::now();
      if (internal.PendingDirty)
      {
        internal.Upload(ibo, internal.PendingOrder, this->PartialIndexUploads);
      }
      else
      {
        internal.Upload(ibo, internal.UploadedOrder, false);
      }
      internal.PendingDirty = false;
      internal.LastOrderTime = SecondsSince(start);
    }
  }
  else if (sortable && internal.Tree && !internal.Tree->empty())
  {
    scenevis::View view;
    if (vtkBSPSortUtilities::ViewFromCamera(ren->GetActiveCamera(), actor->GetMatrix(), view))
    {
      const bool moved = !internal.HaveView || view.eye != internal.LastView.eye;
      if (moved || !internal.IBOHasOrder)
      {
        const auto start = std::chrono::steady_clock::now();
        bool changed = !internal.IBOHasOrder;
        const bool leaves = !internal.Tree->leaves.empty();
        if (leaves)
        {
          // Which fragments a view draws depends on the view: a full order, uploaded when it
          // differs from the last one.
          if (moved)
          {
            bsp::order(*internal.Tree, view, bsp::Direction::BackToFront, internal.FullOrder);
            changed = changed || internal.FullOrder != internal.UploadedOrder;
          }
        }
        else
        {
          if (!internal.Order)
          {
            internal.Order =
              std::make_unique<bsp::IncrementalOrder>(*internal.Tree, bsp::Direction::BackToFront);
            changed = true;
          }
          if (moved)
          {
            const auto& stats = internal.Order->update(view);
            changed = changed || stats.nodesFlipped > 0 || stats.fragmentsMoved > 0 ||
              internal.UploadedOrder.empty();
          }
        }
        if (moved)
        {
          ++internal.OrderUpdates;
          internal.HaveView = true;
          internal.LastView = view;
        }
        if (changed)
        {
          internal.Upload(
            ibo, leaves ? internal.FullOrder : internal.Order->order(), this->PartialIndexUploads);
        }
        internal.LastOrderTime = SecondsSince(start);
      }
    }
  }
}

//------------------------------------------------------------------------------
void vtkBSPSortedPolyDataMapper::RenderPieceFinish(vtkRenderer* ren, vtkActor* actor)
{
  this->Superclass::RenderPieceFinish(ren, actor);
  this->ScalarMode = this->Internal->SavedScalarMode;
}

//------------------------------------------------------------------------------
void vtkBSPSortedPolyDataMapper::RenderPieceDraw(vtkRenderer* ren, vtkActor* actor)
{
  Internals& internal = *this->Internal;
  if (internal.DrawCount < 0)
  {
    this->Superclass::RenderPieceDraw(ren, actor);
    return;
  }
  // A run of vtkBSPTranslucentPass: only index range [DrawFirst, DrawFirst + DrawCount) of the
  // triangles (surface representation, no edges: the pass only sends such actors).
  if (internal.DrawCount == 0)
  {
    return;
  }
  vtkOpenGLHelper& tris = this->Primitives[PrimitiveTris];
  this->DrawingVertices = false;
  this->DrawingSelection = false;
  this->UpdateShaders(tris, ren, actor);
  const int numVerts = this->VBOs->GetNumberOfTuples("vertexMC");
  tris.IBO->Bind();
  glDrawRangeElements(GL_TRIANGLES, 0, static_cast<GLuint>(numVerts - 1),
    static_cast<GLsizei>(internal.DrawCount), GL_UNSIGNED_INT,
    reinterpret_cast<const GLvoid*>(
      static_cast<std::uintptr_t>(internal.DrawFirst) * sizeof(GLuint)));
  tris.IBO->Release();
}

//------------------------------------------------------------------------------
void vtkBSPSortedPolyDataMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "OrderedLeafSize: " << this->OrderedLeafSize << "\n";
  os << indent << "NumberOfFragments: " << this->GetNumberOfFragments() << "\n";
  os << indent << "NumberOfIndexUploads: " << this->GetNumberOfIndexUploads() << "\n";
  os << indent << "PartialIndexUploads: " << this->PartialIndexUploads << "\n";
  os << indent << "NumberOfPartialIndexUploads: " << this->GetNumberOfPartialIndexUploads()
     << "\n";
  os << indent << "LastUploadIndexCount: " << this->GetLastUploadIndexCount() << "\n";
  os << indent << "NumberOfOrderUpdates: " << this->GetNumberOfOrderUpdates() << "\n";
  os << indent << "NumberOfTreeBuilds: " << this->GetNumberOfTreeBuilds() << "\n";
  os << indent << "NumberOfVertexBufferBuilds: " << this->GetNumberOfVertexBufferBuilds() << "\n";
}
