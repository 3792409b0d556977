#include "vtkChunkedPolyDataMapper.h"

#include "vtkAbstractMapper.h"
#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLHelper.h"
#include "vtkOpenGLIndexBufferObject.h"
#include "vtkOpenGLVertexBufferObjectGroup.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkSmartPointer.h"
#include "vtkTypeInt32Array.h"
#include "vtk_glew.h"

#include "vtkOcclusionRecordFile.h"

#include "scenevis/Frustum.h"
#include "scenevis/NormalCone.h"
#include "scenevis/OcclusionBuffer.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <utility>

vtkStandardNewMacro(vtkChunkedPolyDataMapper);

namespace
{
namespace sc = scenevis::culling;
namespace so = scenevis::occlusion;

struct Node
{
  glm::dvec3 lo{ 0.0 }, hi{ 0.0 };
  sc::NormalCone cone;
  std::uint32_t firstChunk = 0, endChunk = 0;
  std::uint32_t right = 0; ///< 0: leaf (left child = this + 1 otherwise)
};

double SecondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
/**
 * The cell arrays of @p input that @p mapper can draw with, which the copy must carry: the cell
 * scalars its scalar mode selects (every cell array when it selects a field array by index, as
 * indices must not move), cell normals, ghost flags, and the arrays its selection settings name.
 * The others (e.g. a PartId, 8 bytes per triangle: 0.39 GB on the 48.6M-triangle engine grid)
 * stay in the input only; choosing another array to colour by copies it then.
 */
std::vector<vtkAbstractArray*> CellArraysToCopy(vtkOpenGLPolyDataMapper* mapper, vtkPolyData* input)
{
  std::vector<vtkAbstractArray*> wanted;
  vtkCellData* cd = input->GetCellData();
  const int mode = mapper->GetScalarMode();
  if (mapper->GetArrayAccessMode() == VTK_GET_ARRAY_BY_ID &&
    (mode == VTK_SCALAR_MODE_USE_CELL_FIELD_DATA || mode == VTK_SCALAR_MODE_USE_FIELD_DATA))
  {
    for (int a = 0; a < cd->GetNumberOfArrays(); ++a)
    {
      wanted.push_back(cd->GetAbstractArray(a));
    }
    return wanted;
  }
  auto add = [&](vtkAbstractArray* array)
  {
    if (array && std::find(wanted.begin(), wanted.end(), array) == wanted.end())
    {
      wanted.push_back(array);
    }
  };
  int cellFlag = 0;
  vtkAbstractArray* scalars = vtkAbstractMapper::GetAbstractScalars(input, mode,
    mapper->GetArrayAccessMode(), mapper->GetArrayId(), mapper->GetArrayName(), cellFlag);
  if (cellFlag == 1)
  {
    add(scalars);
  }
  add(cd->GetNormals());
  for (const char* name : std::initializer_list<const char*>{ vtkDataSetAttributes::GhostArrayName(),
         mapper->GetCellIdArrayName(),
         mapper->GetProcessIdArrayName(), mapper->GetCompositeIdArrayName() })
  {
    if (name)
    {
      add(cd->GetAbstractArray(name));
    }
  }
  return wanted;
}

} // namespace

//------------------------------------------------------------------------------
struct vtkChunkedPolyDataMapper::Internals
{
  // Partition of the current input.
  vtkPolyData* Input = nullptr; // compared only, never dereferenced
  vtkMTimeType InputMTime = 0;
  int BuiltChunkSize = 0;
  vtkSmartPointer<vtkPolyData> Chunked;  // null: the input has no polygons or strips
  vtkIdType PolyBase = 0;                // cells before the polygons (verts + lines)
  std::vector<std::uint32_t> InputCellOf; // triangle k of the copy -> input cell id
  std::vector<std::uint32_t> ChunkBegin; // chunk c: triangles [b[c], b[c+1]) of the copy
  std::vector<Node> Nodes;               // depth first, root 0 (none without triangles)
  bool HasSurface = false;               // polygons or strips in the input
  bool DrawsCopy = false;                // the last render drew the copy, not the input
  // The input's cell arrays the copy carries (those the superclass can draw with, see
  // CellArraysToCopy), as of partition build number CopiedFrom.
  std::vector<vtkAbstractArray*> CopiedCellArrays;
  vtkIdType CopiedFrom = -1;
  vtkMTimeType CopiedForMapperTime = 0; // the mapper's MTime when they were last chosen
  void CopyCellData(vtkPolyData* input, const std::vector<vtkAbstractArray*>& wanted);
  vtkCellArray* UploadedPolys = nullptr; // the copy's polygons in the triangle index buffer
  vtkMTimeType UploadedPolysTime = 0;    // ... as of this MTime
  bool WarnedMismatch = false;

  // This frame.
  bool Cull = false;
  bool Skipped = false;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> Ranges; // (first triangle, count)
  std::vector<std::uint32_t> DrawnChunks;

  // Per-frame traversal parameters.
  sc::Frustum Frustum;
  bool UseFrustum = true;
  bool UseCones = false;
  bool Parallel = false;
  glm::dvec3 EyeModel{ 0.0 }, DopModel{ 0.0, 0.0, -1.0 };
  double MinPixels = 0.0;
  double PixelsPerUnit = 0.0;
  double Model[16];
  double MaxScale = 1.0;
  glm::dvec3 EyeWorld{ 0.0 }, ViewDirWorld{ 0.0, 0.0, -1.0 };

  // Occlusion (OcclusionCulling): the copy's triangles (3 point ids each, chunk order): its own
  // 32-bit connectivity, else a copy built on first use per partition; each chunk's edge
  // neighbours inside the chunk (chunk-local triangle ids), built the first time the chunk
  // occludes; the depth buffer; chunk scratch.
  const std::uint32_t* OccluderIds = nullptr;
  std::vector<std::uint32_t> OccluderTriangles;
  std::vector<std::vector<std::uint32_t>> ChunkNeighborTables;
  bool OccluderDataBuilt = false;
  bool UseOcclusion = false;
  so::FaceCulling OccluderFaces = so::FaceCulling::None;
  so::MaskedDepthBuffer Depth;
  vtkOcclusionRecordFile Recording; // after Depth: closed before it goes
  glm::dmat4 ClipFromModel{ 1.0 };
  std::vector<glm::dvec4> ChunkClip;
  std::vector<std::uint32_t> ChunkIndices;
  std::vector<double> ChunkXyz;
  vtkIdType CulledOcclusion = 0;

  void BuildOccluderData();
  void DrawChunkOccluder(std::uint32_t chunk);
  double Nearness(const Node& n) const;

  // Statistics.
  vtkIdType NodesVisited = 0, ChunksTested = 0, ChunksDrawn = 0, CulledFrustum = 0, CulledCone = 0,
            CulledSize = 0, TrianglesDrawn = 0, DrawCalls = 0;
  vtkIdType PartitionBuilds = 0, VertexBufferBuilds = 0;
  double PartitionTime = 0.0, CullTime = 0.0;

  std::uint64_t TotalTriangles() const
  {
    return this->ChunkBegin.empty() ? 0 : this->ChunkBegin.back();
  }
  std::uint32_t ChunkCount() const
  {
    return this->ChunkBegin.empty() ? 0 : static_cast<std::uint32_t>(this->ChunkBegin.size() - 1);
  }

  void Build(vtkPolyData* input, int chunkSize);
  void Emit(std::uint32_t firstChunk, std::uint32_t endChunk)
  {
    const std::uint64_t first = this->ChunkBegin[firstChunk];
    const std::uint64_t count = this->ChunkBegin[endChunk] - first;
    this->ChunksDrawn += endChunk - firstChunk;
    this->TrianglesDrawn += static_cast<vtkIdType>(count);
    for (std::uint32_t c = firstChunk; c < endChunk; ++c)
    {
      this->DrawnChunks.push_back(c);
    }
    if (count == 0)
    {
      return;
    }
    if (!this->Ranges.empty() && this->Ranges.back().first + this->Ranges.back().second == first)
    {
      this->Ranges.back().second += count;
    }
    else
    {
      this->Ranges.emplace_back(first, count);
    }
  }
  void Traverse(std::uint32_t node, std::uint8_t mask);
  bool SmallFeature(const Node& n) const;
};

//------------------------------------------------------------------------------
void vtkChunkedPolyDataMapper::Internals::Build(vtkPolyData* input, int chunkSize)
{
  this->Chunked = nullptr;
  this->OccluderDataBuilt = false;
  this->OccluderIds = nullptr;
  this->OccluderTriangles.clear();
  this->ChunkNeighborTables.clear();
  this->InputCellOf.clear();
  this->ChunkBegin.clear();
  this->Nodes.clear();
  this->HasSurface = false;
  this->Input = input;
  this->InputMTime = input->GetMTime();
  this->BuiltChunkSize = chunkSize;
  this->PolyBase = input->GetNumberOfVerts() + input->GetNumberOfLines();
  vtkCellArray* polys = input->GetNumberOfPolys() > 0 ? input->GetPolys() : nullptr;
  vtkCellArray* strips = input->GetNumberOfStrips() > 0 ? input->GetStrips() : nullptr;
  vtkPoints* points = input->GetPoints();
  this->HasSurface = polys || strips;
  if (!points || !this->HasSurface)
  {
    return; // nothing to cull: the superclass draws the input itself
  }
  const vtkIdType numPoints = points->GetNumberOfPoints();
  if (numPoints > std::numeric_limits<std::uint32_t>::max() ||
    input->GetNumberOfCells() >= std::numeric_limits<std::uint32_t>::max())
  {
    return; // beyond VTK's 32-bit index buffers: the superclass draws the input itself
  }
  const auto start = std::chrono::steady_clock::now();

  // Point access without a virtual call per coordinate for the common array types.
  vtkDataArray* pointData = points->GetData();
  const double* dptr = nullptr;
  const float* fptr = nullptr;
  if (auto* d = vtkDoubleArray::SafeDownCast(pointData))
  {
    dptr = d->GetPointer(0);
  }
  else if (auto* f = vtkFloatArray::SafeDownCast(pointData))
  {
    fptr = f->GetPointer(0);
  }
  auto point = [&](vtkIdType id) -> glm::dvec3
  {
    if (dptr)
    {
      return glm::dvec3(dptr[3 * id], dptr[3 * id + 1], dptr[3 * id + 2]);
    }
    if (fptr)
    {
      return glm::dvec3(fptr[3 * id], fptr[3 * id + 1], fptr[3 * id + 2]);
    }
    double p[3];
    points->GetPoint(id, p);
    return glm::dvec3(p[0], p[1], p[2]);
  };

  // The triangle list we draw and cull. Polygons are fanned from their first point and strips
  // split with alternating winding, exactly as vtkOpenGLIndexBufferObject does (so the pixels
  // are those of vtkOpenGLPolyDataMapper). Triangles with two points at the same coordinates
  // cover no pixel and are left out: VTK leaves them out of its index buffer too (polygons only,
  // compared by coordinates in the point type; float to double keeps equality, and NaN compares
  // unequal in both), and with none left every cell we hand VTK is a triangle it keeps, whatever
  // the rule of the VTK version: our triangle k is exactly triangle k of the index buffer.
  // Triangles with a point id out of range (invalid input; VTK would read out of bounds) are
  // left out as well.
  // 32-bit ids (points and cells fit, see above): 16 bytes per triangle, a third of 64-bit ids,
  // while the copy's own arrays are built beside them.
  std::vector<std::array<std::uint32_t, 3>> tris;
  std::vector<std::uint32_t> triCell; // triangle -> input cell id
  const vtkIdType polyCount = polys ? polys->GetNumberOfCells() : 0;
  const vtkIdType expected = (polys ? polys->GetNumberOfConnectivityIds() - 2 * polyCount : 0) +
    (strips ? strips->GetNumberOfConnectivityIds() - 2 * strips->GetNumberOfCells() : 0);
  tris.reserve(static_cast<std::size_t>(std::max<vtkIdType>(expected, 0)));
  triCell.reserve(tris.capacity());
  auto addTriangle = [&](vtkIdType a, vtkIdType b, vtkIdType c, vtkIdType cell)
  {
    if (a < 0 || b < 0 || c < 0 || a >= numPoints || b >= numPoints || c >= numPoints)
    {
      return;
    }
    const glm::dvec3 pa = point(a), pb = point(b), pc = point(c);
    if (pa == pb || pb == pc || pa == pc)
    {
      return;
    }
    tris.push_back({ static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b),
      static_cast<std::uint32_t>(c) });
    triCell.push_back(static_cast<std::uint32_t>(cell));
  };
  for (int kind = 0; kind < 2; ++kind)
  {
    vtkCellArray* cells = kind == 0 ? polys : strips;
    if (cells)
    {
      auto it = vtk::TakeSmartPointer(cells->NewIterator());
      const vtkIdType base = this->PolyBase + (kind == 0 ? 0 : polyCount);
      vtkIdType k = 0;
      for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell(), ++k)
      {
        vtkIdType npts = 0;
        const vtkIdType* ids = nullptr;
        it->GetCurrentCell(npts, ids);
        for (vtkIdType j = 0; j + 2 < npts; ++j)
        {
          if (kind == 0)
          {
            addTriangle(ids[0], ids[j + 1], ids[j + 2], base + k);
          }
          else
          {
            addTriangle(ids[j], ids[j + 1 + j % 2], ids[j + 1 + (j + 1) % 2], base + k);
          }
        }
      }
    }
  }
  const std::size_t nt = tris.size();
  if (nt >= std::numeric_limits<std::uint32_t>::max() ||
    nt >= static_cast<std::size_t>(std::numeric_limits<int>::max() / 3))
  {
    return; // beyond glDrawRangeElements' GLsizei / gl_PrimitiveID
  }

  // Median splits along the largest centroid extent, over items that carry their centroid (the
  // splits stream through memory instead of looking each centroid up).
  struct Item
  {
    std::array<float, 3> centroid;
    std::uint32_t triangle;
  };
  std::vector<Item> items(nt);
  for (std::size_t t = 0; t < nt; ++t)
  {
    const glm::dvec3 c = (point(tris[t][0]) + point(tris[t][1]) + point(tris[t][2])) / 3.0;
    items[t] = { { static_cast<float>(c.x), static_cast<float>(c.y), static_cast<float>(c.z) },
      static_cast<std::uint32_t>(t) };
  }
  const auto limit = static_cast<std::uint32_t>(chunkSize);
  std::vector<glm::dvec3> normals;
  // Leaf: box of its finite points and normal cone of its triangles (as wound when drawn).
  auto makeLeaf = [&](std::uint32_t nodeIndex, std::uint32_t begin, std::uint32_t end)
  {
    // The splits left the chunk's triangles in arbitrary order; the input's order keeps the
    // vertex locality of the mesh and the plain mapper's order (coplanar z ties) inside a chunk.
    std::sort(items.begin() + begin, items.begin() + end,
      [](const Item& a, const Item& b) { return a.triangle < b.triangle; });
    Node& node = this->Nodes[nodeIndex];
    const auto chunk = static_cast<std::uint32_t>(this->ChunkBegin.size());
    this->ChunkBegin.push_back(begin);
    node.firstChunk = chunk;
    node.endChunk = chunk + 1;
    scenevis::Box box;
    normals.clear();
    for (std::uint32_t i = begin; i < end; ++i)
    {
      const auto& t = tris[items[i].triangle];
      const glm::dvec3 p0 = point(t[0]), p1 = point(t[1]), p2 = point(t[2]);
      for (const glm::dvec3& p : { p0, p1, p2 })
      {
        if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))
        {
          box.extend(p);
        }
      }
      normals.push_back(glm::cross(p1 - p0, p2 - p0)); // non-finite: the chunk gets no cone
    }
    if (box.empty())
    {
      box.lo = box.hi = glm::dvec3(0.0); // nothing drawable: a point, culled or not, is harmless
    }
    node.lo = box.lo;
    node.hi = box.hi;
    node.cone = sc::normalConeOf(normals);
  };
  // Recursive build (depth first, left first; depth ~ log2(chunks)): node ids and chunk order
  // follow the in-order leaf sequence, so every subtree covers a contiguous chunk range.
  std::function<std::uint32_t(std::uint32_t, std::uint32_t)> build =
    [&](std::uint32_t begin, std::uint32_t end) -> std::uint32_t
  {
    const auto nodeIndex = static_cast<std::uint32_t>(this->Nodes.size());
    this->Nodes.emplace_back();
    if (end - begin <= limit)
    {
      makeLeaf(nodeIndex, begin, end);
      return nodeIndex;
    }
    // The split axis from the centroids' extent, read from at most 4096 of them spread over the
    // range (the axis only steers the split; the median below is exact): a full scan per node
    // cost a pass over all triangles per tree level (13 levels at 12M triangles).
    glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    const std::uint32_t stride = std::max<std::uint32_t>(1, (end - begin) / 4096);
    for (std::uint32_t i = begin; i < end; i += stride)
    {
      const auto& c = items[i].centroid;
      lo = glm::min(lo, glm::dvec3(c[0], c[1], c[2]));
      hi = glm::max(hi, glm::dvec3(c[0], c[1], c[2]));
    }
    const glm::dvec3 extent = hi - lo;
    const int axis =
      extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    const std::uint32_t mid = begin + (end - begin) / 2;
    std::nth_element(items.begin() + begin, items.begin() + mid, items.begin() + end,
      [axis](const Item& a, const Item& b) { return a.centroid[axis] < b.centroid[axis]; });
    build(begin, mid);
    const std::uint32_t right = build(mid, end);
    Node& node = this->Nodes[nodeIndex];
    const Node& left = this->Nodes[nodeIndex + 1];
    const Node& r = this->Nodes[right];
    node.right = right;
    node.firstChunk = left.firstChunk;
    node.endChunk = r.endChunk;
    node.lo = glm::min(left.lo, r.lo);
    node.hi = glm::max(left.hi, r.hi);
    node.cone = sc::merge(left.cone, r.cone);
    return nodeIndex;
  };
  if (nt > 0)
  {
    build(0, static_cast<std::uint32_t>(nt));
    // Inflate against float rounding on the GPU (positions, shift-scale, matrices in float).
    const glm::dvec3 rootSize = this->Nodes[0].hi - this->Nodes[0].lo;
    const double margin = 1e-5 * glm::length(rootSize) + 1e-30;
    for (Node& n : this->Nodes)
    {
      n.lo -= margin;
      n.hi += margin;
    }
  }
  this->ChunkBegin.push_back(static_cast<std::uint32_t>(nt));

  // The copy drawn: the input's points, point data, verts and lines, and our triangles in chunk
  // order as its polygons (no strips: theirs are among our triangles).
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->SetPoints(points);
  out->GetPointData()->ShallowCopy(input->GetPointData());
  out->GetFieldData()->ShallowCopy(input->GetFieldData());
  if (input->GetNumberOfVerts() > 0)
  {
    out->SetVerts(input->GetVerts());
  }
  if (input->GetNumberOfLines() > 0)
  {
    out->SetLines(input->GetLines());
  }
  vtkNew<vtkCellArray> newPolys;
  if (numPoints < std::numeric_limits<std::int32_t>::max())
  {
    newPolys->Use32BitStorage();
  }
  newPolys->AllocateExact(static_cast<vtkIdType>(nt), static_cast<vtkIdType>(3 * nt));
  this->InputCellOf.resize(nt);
  for (std::size_t k = 0; k < nt; ++k)
  {
    const auto& t = tris[items[k].triangle];
    const vtkIdType ids[3] = { t[0], t[1], t[2] };
    newPolys->InsertNextCell(3, ids);
    this->InputCellOf[k] = triCell[items[k].triangle];
  }
  out->SetPolys(newPolys);
  // The scratch goes back before the cell data is copied (the peak of a big model's setup).
  decltype(tris)().swap(tris);
  decltype(triCell)().swap(triCell);
  decltype(items)().swap(items);
  this->Chunked = out;
  this->PartitionTime = SecondsSince(start);
  ++this->PartitionBuilds;
}

//------------------------------------------------------------------------------
void vtkChunkedPolyDataMapper::Internals::CopyCellData(
  vtkPolyData* input, const std::vector<vtkAbstractArray*>& wanted)
{
  this->CopiedCellArrays = wanted;
  this->CopiedFrom = this->PartitionBuilds;
  vtkCellData* outCD = this->Chunked->GetCellData();
  outCD->Initialize();
  // One tuple per cell of the copy, that of the input cell it comes from.
  vtkCellData* inCD = input->GetCellData();
  const vtkIdType numCells = input->GetNumberOfCells();
  const auto triangles = static_cast<vtkIdType>(this->InputCellOf.size());
  const vtkIdType outCells = this->PolyBase + triangles;
  vtkNew<vtkIdList> source;
  for (int a = 0; a < inCD->GetNumberOfArrays(); ++a)
  {
    vtkAbstractArray* array = inCD->GetAbstractArray(a);
    if (!array || array->GetNumberOfTuples() != numCells ||
      std::find(wanted.begin(), wanted.end(), array) == wanted.end())
    {
      continue;
    }
    if (source->GetNumberOfIds() == 0)
    {
      source->SetNumberOfIds(outCells);
      for (vtkIdType i = 0; i < this->PolyBase; ++i)
      {
        source->SetId(i, i);
      }
      for (vtkIdType k = 0; k < triangles; ++k)
      {
        source->SetId(this->PolyBase + k, this->InputCellOf[static_cast<std::size_t>(k)]);
      }
    }
    auto copy = vtk::TakeSmartPointer(array->NewInstance());
    copy->SetName(array->GetName());
    copy->SetNumberOfComponents(array->GetNumberOfComponents());
    copy->SetNumberOfTuples(outCells);
    array->GetTuples(source, copy);
    if (auto* data = vtkDataArray::SafeDownCast(array))
    {
      if (data->GetLookupTable())
      {
        vtkDataArray::SafeDownCast(copy)->SetLookupTable(data->GetLookupTable());
      }
    }
    const int index = outCD->AddArray(copy);
    const int attribute = inCD->IsArrayAnAttribute(a);
    if (attribute >= 0)
    {
      outCD->SetActiveAttribute(index, attribute);
    }
  }
}

//------------------------------------------------------------------------------
bool vtkChunkedPolyDataMapper::Internals::SmallFeature(const Node& n) const
{
  // World-space bounding sphere of the box (APPROXIMATE test).
  const glm::dvec3 c = 0.5 * (n.lo + n.hi);
  const double r = 0.5 * glm::length(n.hi - n.lo) * this->MaxScale;
  const double* m = this->Model;
  const glm::dvec3 cw(m[0] * c.x + m[1] * c.y + m[2] * c.z + m[3],
    m[4] * c.x + m[5] * c.y + m[6] * c.z + m[7], m[8] * c.x + m[9] * c.y + m[10] * c.z + m[11]);
  double pixels = 2.0 * r * this->PixelsPerUnit;
  if (!this->Parallel)
  {
    const double depth = glm::dot(cw - this->EyeWorld, this->ViewDirWorld);
    if (depth <= r)
    {
      return false;
    }
    pixels /= depth;
  }
  return pixels < this->MinPixels;
}

//------------------------------------------------------------------------------
void vtkChunkedPolyDataMapper::Internals::Traverse(std::uint32_t index, std::uint8_t mask)
{
  const Node& n = this->Nodes[index];
  ++this->NodesVisited;
  const std::uint32_t chunks = n.endChunk - n.firstChunk;
  if (this->UseFrustum && mask)
  {
    std::uint8_t hint = sc::kPlaneCount;
    if (!sc::testBoxMasked(this->Frustum, n.lo, n.hi, mask, hint))
    {
      this->CulledFrustum += chunks;
      return;
    }
  }
  if (this->UseCones && n.cone.canCull())
  {
    const glm::dvec3 c = 0.5 * (n.lo + n.hi);
    const double r = 0.5 * glm::length(n.hi - n.lo);
    const bool back = this->Parallel ? sc::backFacingAlong(n.cone, this->DopModel)
                                     : sc::backFacingFromEye(n.cone, c, r, this->EyeModel);
    if (back)
    {
      this->CulledCone += chunks;
      return;
    }
  }
  if (this->UseOcclusion && this->Depth.boxOccluded(n.lo, n.hi))
  {
    this->CulledOcclusion += chunks;
    return;
  }
  const bool leaf = n.right == 0;
  if (leaf)
  {
    ++this->ChunksTested;
    if (this->MinPixels > 0.0 && this->SmallFeature(n))
    {
      ++this->CulledSize;
      return;
    }
    this->Emit(n.firstChunk, n.endChunk);
    if (this->UseOcclusion)
    {
      this->DrawChunkOccluder(n.firstChunk); // before anything farther is tested
    }
    return;
  }
  // Entirely inside and nothing else to test below: one range for the whole subtree.
  if ((!this->UseFrustum || mask == 0) && !this->UseCones && this->MinPixels <= 0.0 &&
    !this->UseOcclusion)
  {
    this->Emit(n.firstChunk, n.endChunk);
    return;
  }
  if (this->UseOcclusion &&
    this->Nearness(this->Nodes[n.right]) < this->Nearness(this->Nodes[index + 1]))
  {
    this->Traverse(n.right, mask); // front to back: what is drawn first occludes the rest
    this->Traverse(index + 1, mask);
    return;
  }
  this->Traverse(index + 1, mask);
  this->Traverse(n.right, mask);
}

//------------------------------------------------------------------------------
double vtkChunkedPolyDataMapper::Internals::Nearness(const Node& n) const
{
  if (this->Parallel)
  {
    const glm::dvec3& d = this->DopModel;
    return std::min(n.lo.x * d.x, n.hi.x * d.x) + std::min(n.lo.y * d.y, n.hi.y * d.y) +
      std::min(n.lo.z * d.z, n.hi.z * d.z);
  }
  const glm::dvec3 gap =
    glm::max(glm::max(n.lo - this->EyeModel, this->EyeModel - n.hi), glm::dvec3(0.0));
  return glm::dot(gap, gap);
}

//------------------------------------------------------------------------------
void vtkChunkedPolyDataMapper::Internals::BuildOccluderData()
{
  this->OccluderDataBuilt = true;
  this->OccluderIds = nullptr;
  this->OccluderTriangles.clear();
  vtkPoints* points = this->Chunked ? this->Chunked->GetPoints() : nullptr;
  if (!points)
  {
    return;
  }
  vtkIdType npts = 0;
  const vtkIdType* pts = nullptr;
  vtkCellArray* polys = this->Chunked->GetPolys();
  // Neighbours per chunk, on first use: a chunk is drawn as an occluder on its own, so only edges
  // between two of its triangles can be inner edges (the others are outline edges either way).
  // A whole-mesh table cost a sort of every edge before the first frame (the first cull of the
  // 12.1M-triangle engine grid: 7.7 s with it, 0.4 s without).
  this->ChunkNeighborTables.assign(this->ChunkCount(), std::vector<std::uint32_t>());
  if (!polys->IsStorage64Bit())
  {
    // The copy's connectivity is already 3 non-negative 32-bit ids per triangle in chunk order
    // (12 bytes per triangle not copied: 0.58 GB on the 48.6M-triangle grid).
    this->OccluderIds =
      reinterpret_cast<const std::uint32_t*>(polys->GetConnectivityArray32()->GetPointer(0));
    return;
  }
  this->OccluderTriangles.reserve(static_cast<std::size_t>(3 * polys->GetNumberOfCells()));
  for (vtkIdType c = 0; c < polys->GetNumberOfCells(); ++c)
  {
    polys->GetCellAtId(c, npts, pts);
    for (vtkIdType k = 0; k < 3; ++k)
    {
      this->OccluderTriangles.push_back(static_cast<std::uint32_t>(pts[k]));
    }
  }
  this->OccluderIds = this->OccluderTriangles.data();
}

//------------------------------------------------------------------------------
void vtkChunkedPolyDataMapper::Internals::DrawChunkOccluder(std::uint32_t chunk)
{
  const std::uint32_t begin = this->ChunkBegin[chunk], end = this->ChunkBegin[chunk + 1];
  vtkPoints* points = this->Chunked->GetPoints();
  this->ChunkClip.clear();
  this->ChunkIndices.clear();
  // Each triangle with its own three vertices (a shared vertex is transformed from the same
  // coordinates by the same matrix: bit-identical).
  std::vector<std::uint32_t>& neighbors = this->ChunkNeighborTables[chunk];
  const bool build = neighbors.empty();
  std::vector<double>& xyz = this->ChunkXyz;
  xyz.clear();
  for (std::uint32_t t = begin; t < end; ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      double p[3];
      points->GetPoint(this->OccluderIds[3 * std::size_t(t) + k], p);
      this->ChunkIndices.push_back(static_cast<std::uint32_t>(this->ChunkClip.size()));
      this->ChunkClip.push_back(this->ClipFromModel * glm::dvec4(p[0], p[1], p[2], 1.0));
      if (build)
        xyz.insert(xyz.end(), p, p + 3);
    }
  }
  if (build)
  {
    // Corners welded by coordinates, as over the whole mesh; neighbours in other chunks are
    // outline edges (conservative).
    neighbors = so::buildTriangleNeighbors(
      xyz.data(), xyz.size() / 3, this->ChunkIndices.data(), end - begin);
  }
  this->Depth.drawTriangles(this->ChunkClip.data(), this->ChunkClip.size(),
    this->ChunkIndices.data(), end - begin, this->OccluderFaces, neighbors.data());
}

//------------------------------------------------------------------------------
vtkChunkedPolyDataMapper::vtkChunkedPolyDataMapper()
  : Internal(new Internals)
{
}

vtkChunkedPolyDataMapper::~vtkChunkedPolyDataMapper() = default;

//------------------------------------------------------------------------------
vtkIdType vtkChunkedPolyDataMapper::GetNumberOfChunks() const
{
  return this->Internal->ChunkCount();
}
vtkIdType vtkChunkedPolyDataMapper::GetNumberOfTriangles() const
{
  return static_cast<vtkIdType>(this->Internal->TotalTriangles());
}
vtkIdType vtkChunkedPolyDataMapper::GetNumberOfNodesVisited() const
{
  return this->Internal->NodesVisited;
}
vtkIdType vtkChunkedPolyDataMapper::GetNumberOfChunksTested() const
{
  return this->Internal->ChunksTested;
}
vtkIdType vtkChunkedPolyDataMapper::GetNumberOfChunksDrawn() const
{
  return this->Internal->ChunksDrawn;
}
vtkIdType vtkChunkedPolyDataMapper::GetNumberOfChunksCulledByFrustum() const
{
  return this->Internal->CulledFrustum;
}
vtkIdType vtkChunkedPolyDataMapper::GetNumberOfChunksCulledByNormalCone() const
{
  return this->Internal->CulledCone;
}
vtkIdType vtkChunkedPolyDataMapper::GetNumberOfChunksCulledByOcclusion() const
{
  return this->Internal->CulledOcclusion;
}

vtkIdType vtkChunkedPolyDataMapper::GetNumberOfChunksCulledBySize() const
{
  return this->Internal->CulledSize;
}
vtkIdType vtkChunkedPolyDataMapper::GetNumberOfTrianglesDrawn() const
{
  return this->Internal->TrianglesDrawn;
}
vtkIdType vtkChunkedPolyDataMapper::GetNumberOfDrawCalls() const
{
  return this->Internal->DrawCalls;
}
bool vtkChunkedPolyDataMapper::GetCullingSkipped() const
{
  return this->Internal->Skipped;
}
double vtkChunkedPolyDataMapper::GetLastPartitionTime() const
{
  return this->Internal->PartitionTime;
}
double vtkChunkedPolyDataMapper::GetLastCullTime() const
{
  return this->Internal->CullTime;
}
unsigned long vtkChunkedPolyDataMapper::GetCopyMemorySize() const
{
  const Internals& in = *this->Internal;
  if (!in.Chunked)
  {
    return 0;
  }
  return in.Chunked->GetPolys()->GetActualMemorySize() +
    in.Chunked->GetCellData()->GetActualMemorySize() +
    static_cast<unsigned long>(in.InputCellOf.capacity() * sizeof(std::uint32_t) / 1024);
}
vtkIdType vtkChunkedPolyDataMapper::GetNumberOfPartitionBuilds() const
{
  return this->Internal->PartitionBuilds;
}
vtkIdType vtkChunkedPolyDataMapper::GetNumberOfVertexBufferBuilds() const
{
  return this->Internal->VertexBufferBuilds;
}

void vtkChunkedPolyDataMapper::GetDrawnCellIds(std::vector<vtkIdType>& cellIds) const
{
  const Internals& in = *this->Internal;
  cellIds.clear();
  if (!in.Chunked)
  {
    return;
  }
  // Several triangles (maybe in different chunks) come from one polygon or strip: each once.
  std::vector<bool> seen;
  auto add = [&](std::uint32_t first, std::uint32_t end)
  {
    for (std::uint32_t k = first; k < end; ++k)
    {
      const vtkIdType id = in.InputCellOf[k];
      const auto slot = static_cast<std::size_t>(id - in.PolyBase);
      if (slot >= seen.size())
      {
        seen.resize(slot + 1, false);
      }
      if (!seen[slot])
      {
        seen[slot] = true;
        cellIds.push_back(id);
      }
    }
  };
  if (in.Skipped)
  {
    add(0, static_cast<std::uint32_t>(in.InputCellOf.size()));
    return;
  }
  for (const std::uint32_t c : in.DrawnChunks)
  {
    add(in.ChunkBegin[c], in.ChunkBegin[c + 1]);
  }
}

vtkIdType vtkChunkedPolyDataMapper::GetInputCellId(vtkIdType id) const
{
  const Internals& in = *this->Internal;
  if (id < 0)
  {
    return -1;
  }
  if (!in.Chunked || !in.DrawsCopy || id < in.PolyBase)
  {
    return id; // the input itself is drawn, or a vert / line (shared with the input)
  }
  const auto k = static_cast<std::size_t>(id - in.PolyBase);
  return k < in.InputCellOf.size() ? static_cast<vtkIdType>(in.InputCellOf[k]) : -1;
}

//------------------------------------------------------------------------------
vtkUnsignedCharArray* vtkChunkedPolyDataMapper::MapScalars(double alpha)
{
  int cellFlag = 0;
  return this->MapScalars(
    this->CurrentInput ? this->CurrentInput : this->GetInput(), alpha, cellFlag);
}

//------------------------------------------------------------------------------
void vtkChunkedPolyDataMapper::BuildBufferObjects(vtkRenderer* ren, vtkActor* act)
{
  ++this->Internal->VertexBufferBuilds;
  this->Superclass::BuildBufferObjects(ren, act);
}

//------------------------------------------------------------------------------
void vtkChunkedPolyDataMapper::BuildIBO(vtkRenderer* ren, vtkActor* act, vtkPolyData* poly)
{
  // The copy drawn as a plain surface: its 32-bit connectivity is exactly the triangle index
  // buffer VTK would build (3 ids per triangle, none degenerate, none dropped), so it is uploaded
  // in place instead of through VTK's temporary vector of the same indices (12 bytes per
  // triangle beside everything else at the peak of the first render: 0.58 GB on the
  // 48.6M-triangle engine grid). Everything else is VTK's own.
  Internals& in = *this->Internal;
  vtkProperty* property = act->GetProperty();
  vtkCellArray* polys = poly->GetPolys();
  if (!in.DrawsCopy || poly != in.Chunked || polys->IsStorage64Bit() ||
    property->GetRepresentation() != VTK_SURFACE || property->GetEdgeVisibility() ||
    property->GetVertexVisibility())
  {
    in.UploadedPolys = nullptr;
    this->Superclass::BuildIBO(ren, act, poly);
    return;
  }
  // VTK builds the index buffers of the verts and lines (the input's) from a polydata without
  // polygons; when it rebuilt anything, it emptied the triangles' buffer too.
  vtkNew<vtkPolyData> rest;
  rest->SetPoints(poly->GetPoints());
  rest->SetVerts(poly->GetVerts());
  rest->SetLines(poly->GetLines());
  rest->GetPointData()->ShallowCopy(poly->GetPointData());
  vtkStateStorage before;
  before = this->IBOBuildState;
  this->Superclass::BuildIBO(ren, act, rest);
  if (!(this->IBOBuildState != before) && in.UploadedPolys == polys &&
    in.UploadedPolysTime == polys->GetMTime())
  {
    return;
  }
  vtkOpenGLIndexBufferObject* ibo = this->Primitives[PrimitiveTris].IBO;
  vtkTypeInt32Array* ids = polys->GetConnectivityArray32();
  const auto count = static_cast<std::size_t>(ids->GetNumberOfValues());
  ibo->IndexCount = 0;
  if (count > 0 &&
    ibo->Upload(reinterpret_cast<const unsigned int*>(ids->GetPointer(0)), count,
      vtkOpenGLBufferObject::ElementArrayBuffer))
  {
    ibo->IndexCount = count;
  }
  in.UploadedPolys = polys;
  in.UploadedPolysTime = polys->GetMTime();
}

//------------------------------------------------------------------------------
void vtkChunkedPolyDataMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Internal->UploadedPolys = nullptr; // the buffers go with the context
  this->Superclass::ReleaseGraphicsResources(window);
}

//------------------------------------------------------------------------------
void vtkChunkedPolyDataMapper::UpdateCameraShiftScale(vtkRenderer* ren, vtkActor* actor)
{
  // vtkOpenGLPolyDataMapper::RenderPiece has updated the pipeline and set CurrentInput to the
  // input; swap in the reordered copy before anything builds buffers from it.
  Internals& in = *this->Internal;
  vtkPolyData* input = this->CurrentInput;
  if (input != in.Input || input->GetMTime() != in.InputMTime ||
    in.BuiltChunkSize != this->ChunkSize)
  {
    in.Build(input, this->ChunkSize);
  }
  // Which cell arrays the copy carries depends on the partition (the input) and on the mapper's
  // colouring settings only: looked at again when either changed, not every frame.
  if (in.Chunked &&
    (in.CopiedFrom != in.PartitionBuilds || in.CopiedForMapperTime != this->GetMTime()))
  {
    in.CopiedForMapperTime = this->GetMTime();
    const std::vector<vtkAbstractArray*> wanted = CellArraysToCopy(this, input);
    if (in.CopiedFrom != in.PartitionBuilds || wanted != in.CopiedCellArrays)
    {
      in.CopyCellData(input, wanted);
    }
  }
  // Wireframe, points and edges show the outlines of the cells: those of the input's polygons,
  // not of our triangles (a quad would show its diagonal). Nothing is culled then anyway.
  vtkProperty* property = actor->GetProperty();
  const bool drawsCopy =
    in.Chunked && property->GetRepresentation() == VTK_SURFACE && !property->GetEdgeVisibility();
  if (drawsCopy != in.DrawsCopy)
  {
    // The mapped colours and the buffers are cached against the MTimes of the mapper and of the
    // data drawn, which say nothing about which of the two is drawn.
    in.DrawsCopy = drawsCopy;
    this->Modified();
  }
  if (in.DrawsCopy)
  {
    this->CurrentInput = in.Chunked;
  }
  this->Superclass::UpdateCameraShiftScale(ren, actor);
}

//------------------------------------------------------------------------------
void vtkChunkedPolyDataMapper::RenderPieceStart(vtkRenderer* ren, vtkActor* actor)
{
  this->Superclass::RenderPieceStart(ren, actor); // buffers up to date
  Internals& in = *this->Internal;
  const auto start = std::chrono::steady_clock::now();
  in.Ranges.clear();
  in.DrawnChunks.clear();
  in.NodesVisited = in.ChunksTested = in.ChunksDrawn = in.CulledFrustum = in.CulledCone =
    in.CulledSize = in.TrianglesDrawn = in.DrawCalls = in.CulledOcclusion = 0;
  in.UseOcclusion = false;
  in.Cull = false;
  in.Skipped = true;
  vtkProperty* property = actor->GetProperty();
  bool usable = in.Chunked && this->CurrentInput == in.Chunked.GetPointer() &&
    !ren->GetSelector() && property->GetRepresentation() == VTK_SURFACE &&
    !property->GetEdgeVisibility() && !property->GetVertexVisibility();
  if (usable &&
    static_cast<std::uint64_t>(this->Primitives[PrimitiveTris].IBO->IndexCount) !=
      3 * in.TotalTriangles())
  {
    usable = false;
    if (!in.WarnedMismatch)
    {
      in.WarnedMismatch = true;
      // Cannot happen with VTK 9.1 (every cell of the copy is a triangle it keeps); guards
      // against a VTK whose index buffer would not be one triangle per cell of the copy.
      vtkWarningMacro("The triangle index buffer holds "
        << this->Primitives[PrimitiveTris].IBO->IndexCount / 3 << " triangles, the chunk "
        << "partition " << in.TotalTriangles() << ": drawing everything (warned once).");
    }
  }
  vtkCamera* cam = ren->GetActiveCamera();
  int* size = ren->GetSize();
  if (usable && cam && size && size[0] > 0 && size[1] > 0)
  {
    const double aspect = ren->GetTiledAspectRatio();
    vtkMatrix4x4* model = actor->GetMatrix();
    vtkNew<vtkMatrix4x4> clipFromModel;
    vtkMatrix4x4::Multiply4x4(
      cam->GetCompositeProjectionTransformMatrix(aspect, -1, 1), model, clipFromModel);
    in.Frustum = sc::Frustum::fromRowMajor(&clipFromModel->GetData()[0]);
    usable = std::isfinite(aspect) && aspect > 0.0 && in.Frustum.valid();
    std::copy(model->GetData(), model->GetData() + 16, in.Model);
    double eye[4] = { 0, 0, 0, 1 }, dop[3];
    cam->GetPosition(eye);
    cam->GetDirectionOfProjection(dop);
    in.EyeWorld = glm::dvec3(eye[0], eye[1], eye[2]);
    in.ViewDirWorld = glm::dvec3(dop[0], dop[1], dop[2]);
    in.Parallel = cam->GetParallelProjection() != 0;
    in.UseFrustum = this->FrustumCulling;
    // Normal cones in model coordinates (back-facing is invariant under a transform of positive
    // determinant when the eye / direction of projection are taken into model coordinates).
    const double* m = in.Model;
    const double det3 =
      vtkMath::Determinant3x3(m[0], m[4], m[8], m[1], m[5], m[9], m[2], m[6], m[10]);
    in.UseCones = this->NormalConeCulling && property->GetBackfaceCulling() &&
      !property->GetFrontfaceCulling() && det3 > 0.0 && std::isfinite(det3) && m[12] == 0.0 &&
      m[13] == 0.0 && m[14] == 0.0 && m[15] == 1.0;
    // Occlusion between the mesh's own chunks: only for an opaque surface (translucent chunks
    // hide nothing), with the faces OpenGL draws.
    in.UseOcclusion = this->OcclusionCulling && property->GetOpacity() >= 1.0 &&
      !actor->HasTranslucentPolygonalGeometry() && !property->GetFrontfaceCulling() &&
      (!property->GetBackfaceCulling() || det3 > 0.0);
    if (in.UseOcclusion)
    {
      if (!in.OccluderDataBuilt)
      {
        in.BuildOccluderData();
      }
      in.OccluderFaces =
        property->GetBackfaceCulling() ? so::FaceCulling::Back : so::FaceCulling::None;
      for (int r = 0; r < 4; ++r)
      {
        for (int c = 0; c < 4; ++c)
        {
          in.ClipFromModel[c][r] = clipFromModel->GetElement(r, c);
        }
      }
      in.Recording.BeforeCull(this->OcclusionRecordFile, in.Depth, this);
      if (in.Depth.width() != size[0] || in.Depth.height() != size[1])
      {
        in.Depth.resize(size[0], size[1]);
      }
      else
      {
        in.Depth.clear();
      }
      in.Depth.setClipFromWorld(in.ClipFromModel); // boxes and triangles in model coordinates
    }
    if (in.UseCones || in.UseOcclusion)
    {
      // The eye and direction of projection in model coordinates: for the cone test, and for
      // the front-to-back order of occlusion (which needs no finite values to stay correct).
      vtkNew<vtkMatrix4x4> inverse;
      vtkMatrix4x4::Invert(model, inverse);
      double e[4];
      inverse->MultiplyPoint(eye, e);
      const double* im = inverse->GetData();
      in.EyeModel = glm::dvec3(e[0], e[1], e[2]) / e[3];
      in.DopModel = glm::normalize(glm::dvec3(im[0] * dop[0] + im[1] * dop[1] + im[2] * dop[2],
        im[4] * dop[0] + im[5] * dop[1] + im[6] * dop[2],
        im[8] * dop[0] + im[9] * dop[1] + im[10] * dop[2]));
      in.UseCones = in.UseCones && std::isfinite(in.EyeModel.x) &&
        std::isfinite(in.EyeModel.y) && std::isfinite(in.EyeModel.z) &&
        std::isfinite(in.DopModel.x) && std::isfinite(in.DopModel.y) &&
        std::isfinite(in.DopModel.z);
    }
    in.MinPixels = this->MinimumPixelSize;
    if (in.MinPixels > 0.0)
    {
      const double pixels = cam->GetUseHorizontalViewAngle() ? size[0] : size[1];
      in.PixelsPerUnit = in.Parallel
        ? pixels / (2.0 * cam->GetParallelScale())
        : pixels / (2.0 * std::tan(vtkMath::RadiansFromDegrees(cam->GetViewAngle()) / 2.0));
      in.MaxScale = 0.0;
      for (int col = 0; col < 3; ++col)
      {
        in.MaxScale = std::max(in.MaxScale,
          std::sqrt(m[col] * m[col] + m[4 + col] * m[4 + col] + m[8 + col] * m[8 + col]));
      }
      if (!(std::isfinite(in.PixelsPerUnit) && in.PixelsPerUnit > 0.0))
      {
        in.MinPixels = 0.0;
      }
    }
  }
  else
  {
    usable = false;
  }
  if (usable)
  {
    if (!in.Nodes.empty())
    {
      in.Traverse(0, sc::kAllPlanes);
    }
    if (in.UseOcclusion)
    {
      in.Recording.AfterCull(this->OcclusionRecordFile, this);
      // Front to back visits chunks out of order: draw them in chunk order again (the plain
      // mapper's primitive order) and merge adjacent ranges.
      std::sort(in.Ranges.begin(), in.Ranges.end());
      std::sort(in.DrawnChunks.begin(), in.DrawnChunks.end());
      std::size_t merged = 0;
      for (std::size_t r = 0; r < in.Ranges.size(); ++r)
      {
        if (merged > 0 &&
          in.Ranges[merged - 1].first + in.Ranges[merged - 1].second == in.Ranges[r].first)
        {
          in.Ranges[merged - 1].second += in.Ranges[r].second;
        }
        else
        {
          in.Ranges[merged++] = in.Ranges[r];
        }
      }
      in.Ranges.resize(merged);
    }
    in.Cull = true;
    in.Skipped = false;
  }
  else
  {
    // Nothing to cull is not a fallback.
    in.Skipped = in.HasSurface;
    in.TrianglesDrawn = static_cast<vtkIdType>(in.TotalTriangles());
    in.ChunksDrawn = in.ChunkCount();
  }
  in.CullTime = SecondsSince(start);
}

//------------------------------------------------------------------------------
void vtkChunkedPolyDataMapper::RenderPieceDraw(vtkRenderer* ren, vtkActor* actor)
{
  Internals& in = *this->Internal;
  if (!in.Cull)
  {
    in.DrawCalls = this->Primitives[PrimitiveTris].IBO->IndexCount ? 1 : 0;
    this->Superclass::RenderPieceDraw(ren, actor);
    return;
  }
  // Verts and lines, then our triangles, then strips: the superclass's order and primitive id
  // offsets. The superclass draws the others with the remaining primitives' counts set to 0.
  std::size_t counts[PrimitiveEnd];
  for (int i = PrimitiveStart; i < PrimitiveEnd; ++i)
  {
    counts[i] = this->Primitives[i].IBO->IndexCount;
  }
  auto drawOnly = [&](int a, int b)
  {
    for (int i = PrimitiveStart; i < PrimitiveEnd; ++i)
    {
      this->Primitives[i].IBO->IndexCount = (i == a || i == b) ? counts[i] : 0;
    }
    this->Superclass::RenderPieceDraw(ren, actor);
    for (int i = PrimitiveStart; i < PrimitiveEnd; ++i)
    {
      this->Primitives[i].IBO->IndexCount = counts[i];
    }
  };
  if (counts[PrimitivePoints] || counts[PrimitiveLines])
  {
    drawOnly(PrimitivePoints, PrimitiveLines);
  }
  if (counts[PrimitiveTris] && !in.Ranges.empty())
  {
    vtkOpenGLHelper& tris = this->Primitives[PrimitiveTris];
    this->DrawingVertices = false;
    this->DrawingSelection = false;
    this->UpdateShaders(tris, ren, actor);
    const int numVerts = this->VBOs->GetNumberOfTuples("vertexMC");
    const bool primitiveIds = tris.Program && tris.Program->IsUniformUsed("PrimitiveIDOffset");
    tris.IBO->Bind();
    for (const auto& range : in.Ranges)
    {
      if (primitiveIds)
      {
        tris.Program->SetUniformi(
          "PrimitiveIDOffset", this->PrimitiveIDOffset + static_cast<int>(range.first));
      }
      glDrawRangeElements(GL_TRIANGLES, 0, static_cast<GLuint>(numVerts - 1),
        static_cast<GLsizei>(3 * range.second), GL_UNSIGNED_INT,
        reinterpret_cast<const GLvoid*>(
          static_cast<std::uintptr_t>(3 * range.first) * sizeof(GLuint)));
      ++in.DrawCalls;
    }
    tris.IBO->Release();
    if (primitiveIds)
    {
      tris.Program->SetUniformi("PrimitiveIDOffset", this->PrimitiveIDOffset);
    }
  }
  this->PrimitiveIDOffset += static_cast<int>(counts[PrimitiveTris] / 3);
  if (counts[PrimitiveTriStrips])
  {
    drawOnly(PrimitiveTriStrips, PrimitiveTriStrips);
  }
}

//------------------------------------------------------------------------------
void vtkChunkedPolyDataMapper::SetOcclusionRecordFile(const char* fileName)
{
  // Not Modified(): what is drawn does not change, and a newer mapper would rebuild its
  // vertex buffers.
  this->OcclusionRecordFile = fileName ? fileName : "";
}

void vtkChunkedPolyDataMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ChunkSize: " << this->ChunkSize << "\n";
  os << indent << "FrustumCulling: " << this->FrustumCulling << "\n";
  os << indent << "NormalConeCulling: " << this->NormalConeCulling << "\n";
  os << indent << "MinimumPixelSize: " << this->MinimumPixelSize << " (approximate)\n";
  os << indent << "OcclusionCulling: " << this->OcclusionCulling << "\n";
  os << indent << "OcclusionRecordFile: "
     << (this->OcclusionRecordFile.empty() ? "(none)" : this->OcclusionRecordFile) << "\n";
  os << indent << "NumberOfChunks: " << this->GetNumberOfChunks() << "\n";
  os << indent << "NumberOfTrianglesDrawn: " << this->GetNumberOfTrianglesDrawn() << "\n";
  os << indent << "NumberOfDrawCalls: " << this->GetNumberOfDrawCalls() << "\n";
  os << indent << "NumberOfPartitionBuilds: " << this->GetNumberOfPartitionBuilds() << "\n";
  os << indent << "CopyMemorySize: " << this->GetCopyMemorySize() << " kB\n";
  os << indent << "NumberOfVertexBufferBuilds: " << this->GetNumberOfVertexBufferBuilds() << "\n";
}
