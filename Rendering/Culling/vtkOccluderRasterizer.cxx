#include "vtkOccluderRasterizer.h"

#include "vtkActor.h"
#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkMapperPolyData.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace so = scenevis::occlusion;

namespace
{
/// Triangles per run whose box is tested before the run is rasterized (see
/// scenevis::occlusion::TriangleClusters).
constexpr std::size_t kTrianglesPerCluster = 32;

/// Whether polygon @p ids (n >= 4 points) is planar and convex: then its fan covers exactly it.
bool PlanarConvex(vtkPoints* points, const vtkIdType* ids, vtkIdType n)
{
  std::vector<glm::dvec3> p(static_cast<std::size_t>(n));
  for (vtkIdType i = 0; i < n; ++i)
  {
    double x[3];
    points->GetPoint(ids[i], x);
    p[static_cast<std::size_t>(i)] = glm::dvec3(x[0], x[1], x[2]);
  }
  // Newell normal, then every corner must turn the same way and every point lie on the plane.
  glm::dvec3 normal(0.0);
  double size = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    const glm::dvec3& a = p[i];
    const glm::dvec3& b = p[(i + 1) % p.size()];
    normal +=
      glm::dvec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
    size = std::max(size, glm::length(b - a));
  }
  const double length = glm::length(normal);
  if (!(length > 0.0) || !std::isfinite(length))
  {
    return false;
  }
  normal /= length;
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    const glm::dvec3& a = p[i];
    const glm::dvec3& b = p[(i + 1) % p.size()];
    const glm::dvec3& c = p[(i + 2) % p.size()];
    if (glm::dot(glm::cross(b - a, c - b), normal) < 0.0 ||
      std::abs(glm::dot(a - p[0], normal)) > 1e-9 * size)
    {
      return false;
    }
  }
  return true;
}
} // namespace

void vtkOccluderRasterizer::BeginFrame(int width, int height, const double m[16])
{
  ++this->Frame;
  std::copy(m, m + 16, this->ClipFromWorld);
  if (this->DepthBuffer.width() != width || this->DepthBuffer.height() != height)
  {
    this->DepthBuffer.resize(width, height);
  }
  else
  {
    this->DepthBuffer.clear();
  }
  glm::dmat4 clipFromWorld;
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      clipFromWorld[c][r] = m[4 * r + c];
    }
  }
  this->DepthBuffer.setClipFromWorld(clipFromWorld);
  this->OccludersDrawn = 0;
  this->OccludersSkipped = 0;
  this->OccluderTriangles = 0;
  this->DrawSeconds = 0.0;
  if (this->CacheBytes > this->CacheBudget)
  {
    this->Evict();
  }
}

void vtkOccluderRasterizer::Evict()
{
  // Oldest first, never what the previous frame used (it is likely to be needed again).
  std::vector<std::pair<std::uint64_t, vtkPolyData*>> byAge;
  for (const auto& entry : this->Meshes)
  {
    if (entry.second.LastFrame + 1 < this->Frame)
    {
      byAge.emplace_back(entry.second.LastFrame, entry.first);
    }
  }
  std::sort(byAge.begin(), byAge.end());
  for (const auto& old : byAge)
  {
    if (this->CacheBytes <= this->CacheBudget / 2)
    {
      break;
    }
    const auto it = this->Meshes.find(old.second);
    this->CacheBytes -= it->second.Bytes();
    this->Meshes.erase(it);
  }
}

vtkOccluderRasterizer::Mesh* vtkOccluderRasterizer::MeshOf(vtkPolyData* data)
{
  Mesh& mesh = this->Meshes[data];
  if (mesh.Data == data && mesh.LastFrame == this->Frame)
  {
    return &mesh; // checked this frame already (instances share their polydata)
  }
  mesh.LastFrame = this->Frame;
  if (mesh.Data == data && mesh.Time == data->GetMTime())
  {
    return &mesh;
  }
  // New, changed, or a new object at a deleted one's address.
  this->CacheBytes -= mesh.Bytes();
  mesh.Data = data;
  mesh.Time = data->GetMTime();
  mesh.Triangles.clear();
  vtkPoints* points = data->GetPoints();
  const vtkIdType pointCount = points ? points->GetNumberOfPoints() : 0;
  if (pointCount > 0 && pointCount < static_cast<vtkIdType>(UINT32_MAX))
  {
    const vtkIdType* ids = nullptr;
    vtkIdType n = 0;
    vtkCellArray* polys = data->GetPolys();
    for (polys->InitTraversal(); polys->GetNextCell(n, ids);)
    {
      if (n == 3 || (n > 3 && PlanarConvex(points, ids, n)))
      {
        for (vtkIdType i = 1; i + 1 < n; ++i)
        {
          mesh.Triangles.insert(mesh.Triangles.end(),
            { static_cast<std::uint32_t>(ids[0]), static_cast<std::uint32_t>(ids[i]),
              static_cast<std::uint32_t>(ids[i + 1]) });
        }
      }
    }
    vtkCellArray* strips = data->GetStrips();
    for (strips->InitTraversal(); strips->GetNextCell(n, ids);)
    {
      for (vtkIdType j = 0; j + 2 < n; ++j)
      {
        mesh.Triangles.insert(mesh.Triangles.end(),
          { static_cast<std::uint32_t>(ids[j]), static_cast<std::uint32_t>(ids[j + 1 + j % 2]),
            static_cast<std::uint32_t>(ids[j + 1 + (j + 1) % 2]) });
      }
    }
    std::vector<double> xyz(static_cast<std::size_t>(3 * pointCount));
    for (vtkIdType i = 0; i < pointCount; ++i)
    {
      points->GetPoint(i, &xyz[static_cast<std::size_t>(3 * i)]);
    }
    mesh.Neighbors = so::buildTriangleNeighbors(xyz.data(), static_cast<std::size_t>(pointCount),
      mesh.Triangles.data(), mesh.Triangles.size() / 3);
    mesh.Clusters = so::buildTriangleClusters(xyz.data(), static_cast<std::size_t>(pointCount),
      mesh.Triangles.data(), mesh.Triangles.size() / 3, kTrianglesPerCluster);
    mesh.Closed = so::closedSurface(xyz.data(), static_cast<std::size_t>(pointCount),
      mesh.Triangles.data(), mesh.Triangles.size() / 3, mesh.Neighbors);
    double volume = 0.0;
    for (std::size_t t = 0; t + 2 < mesh.Triangles.size(); t += 3)
    {
      const double* a = &xyz[3 * std::size_t(mesh.Triangles[t])];
      const double* b = &xyz[3 * std::size_t(mesh.Triangles[t + 1])];
      const double* c = &xyz[3 * std::size_t(mesh.Triangles[t + 2])];
      volume += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
        a[2] * (b[0] * c[1] - b[1] * c[0]);
    }
    mesh.Outward = volume >= 0.0;
  }
  else
  {
    mesh.Neighbors.clear();
    mesh.Clusters.clear();
  }
  mesh.Triangles.shrink_to_fit();
  mesh.Neighbors.shrink_to_fit();
  mesh.Clusters.shrink_to_fit();
  this->CacheBytes += mesh.Bytes();
  return &mesh;
}

double vtkOccluderRasterizer::ScreenArea(const double bounds[6]) const
{
  const double* b = bounds;
  const int w = this->DepthBuffer.width(), h = this->DepthBuffer.height();
  double x0 = w, x1 = 0, y0 = h, y1 = 0;
  for (int k = 0; k < 8; ++k)
  {
    const double p[3] = { b[k & 1], b[2 + ((k >> 1) & 1)], b[4 + ((k >> 2) & 1)] };
    const double* m = this->ClipFromWorld;
    const double cw = m[12] * p[0] + m[13] * p[1] + m[14] * p[2] + m[15];
    const double cz = m[8] * p[0] + m[9] * p[1] + m[10] * p[2] + m[11];
    if (!(cw > 0.0) || cz + cw < 0.0)
    {
      return double(w) * h;
    }
    const double x = ((m[0] * p[0] + m[1] * p[1] + m[2] * p[2] + m[3]) / cw * 0.5 + 0.5) * w;
    const double y = ((m[4] * p[0] + m[5] * p[1] + m[6] * p[2] + m[7]) / cw * 0.5 + 0.5) * h;
    x0 = std::min(x0, x);
    x1 = std::max(x1, x);
    y0 = std::min(y0, y);
    y1 = std::max(y1, y);
  }
  return std::max(0.0, std::min<double>(x1, w) - std::max(0.0, x0)) *
    std::max(0.0, std::min<double>(y1, h) - std::max(0.0, y0));
}

bool vtkOccluderRasterizer::WorthDrawing(const double lo[3], const double hi[3], vtkIdType triangles)
{
  const double bounds[6] = { lo[0], hi[0], lo[1], hi[1], lo[2], hi[2] };
  if (this->MinimumPixelsPerTriangle > 0.0 && triangles > 0 &&
    this->ScreenArea(bounds) < this->MinimumPixelsPerTriangle * static_cast<double>(triangles))
  {
    ++this->OccludersSkipped;
    return false;
  }
  return true;
}

void vtkOccluderRasterizer::Draw(vtkProp* prop, const double bounds[6], const double* placement)
{
  // dynamic_cast, not SafeDownCast: this runs for every visible prop, and SafeDownCast compares
  // class names along the hierarchy.
  vtkActor* actor = dynamic_cast<vtkActor*>(prop);
  if (!actor || !actor->GetVisibility())
  {
    return;
  }
  vtkPolyDataMapper* mapper = dynamic_cast<vtkPolyDataMapper*>(actor->GetMapper());
  vtkProperty* property = actor->GetProperty();
  // The polydata the mapper draws: its input, or a composite input's visible blocks drawn with
  // the actor's property (blocks with colours or opacities of their own are not occluders).
  if (!mapper || property->GetRepresentation() != VTK_SURFACE || property->GetOpacity() < 1.0 ||
    mapper->GetNumberOfClippingPlanes() > 0 ||
    vtkMapper::GetResolveCoincidentTopology() == VTK_RESOLVE_SHIFT_ZBUFFER ||
    !vtkMapperPolyData::Collect(mapper, this->Leaves, true))
  {
    return;
  }
  const auto start = std::chrono::steady_clock::now();
  auto stopClock = [&]()
  {
    this->DrawSeconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  // Occluder selection first: most visible props of a wide view are skipped by it, before the
  // actor's matrix (which may recompute it) is asked for.
  this->LeafMeshes.clear();
  std::size_t triangles = 0;
  for (vtkPolyData* leaf : this->Leaves)
  {
    if (leaf->GetPoints())
    {
      Mesh* mesh = this->MeshOf(leaf);
      this->LeafMeshes.emplace_back(leaf, mesh);
      triangles += mesh->Triangles.size() / 3;
    }
  }
  if (this->LeafMeshes.empty())
  {
    stopClock();
    return;
  }
  if (this->MinimumPixelsPerTriangle > 0.0 && triangles > 0 &&
    this->ScreenArea(bounds) < this->MinimumPixelsPerTriangle * static_cast<double>(triangles))
  {
    ++this->OccludersSkipped;
    stopClock();
    return;
  }
  double model[16];
  if (placement)
  {
    std::copy(placement, placement + 16, model);
  }
  else
  {
    vtkMatrix4x4::DeepCopy(model, actor->GetMatrix());
  }
  const double determinant = vtkMatrix4x4::Determinant(model);
  so::FaceCulling culling = so::FaceCulling::None;
  if (property->GetBackfaceCulling() || property->GetFrontfaceCulling())
  {
    if (determinant <= 0.0)
    {
      stopClock();
      return;
    }
    culling = property->GetBackfaceCulling()
      ? (property->GetFrontfaceCulling() ? so::FaceCulling::Both : so::FaceCulling::Back)
      : so::FaceCulling::Front;
  }
  so::MaskedDepthBuffer& buffer = this->DepthBuffer;
  buffer.polygonOffsetFactor = 0.0;
  buffer.polygonOffsetDepth = 0.0;
  if (vtkMapper::GetResolveCoincidentTopology() == VTK_RESOLVE_POLYGON_OFFSET)
  {
    double factor = 0.0, units = 0.0;
    mapper->GetCoincidentTopologyPolygonOffsetParameters(factor, units);
    buffer.polygonOffsetFactor = factor;
    buffer.polygonOffsetDepth = units * std::ldexp(1.0, -23); // r of a 24-bit depth buffer, x2
  }
  // Textures or scalars with alpha (checked after the cheap tests: it may map scalars).
  if (actor->HasTranslucentPolygonalGeometry() || !actor->HasOpaqueGeometry())
  {
    stopClock();
    return;
  }
  double m[16];
  vtkMatrix4x4::Multiply4x4(this->ClipFromWorld, model, m);
  bool drawn = false;
  for (const auto& leafMesh : this->LeafMeshes)
  {
    const Mesh& mesh = *leafMesh.second;
    if (mesh.Triangles.empty())
    {
      continue;
    }
    so::FaceCulling faces = culling;
    if (faces == so::FaceCulling::None && mesh.Closed)
    {
      // The actor's matrix may mirror (negative determinant): then outward faces wind clockwise.
      const bool outwardIsFront = mesh.Outward == (determinant > 0.0);
      faces = outwardIsFront ? so::FaceCulling::Back : so::FaceCulling::Front;
    }
    this->DrawMesh(leafMesh.first->GetPoints(), mesh, m, faces);
    this->OccluderTriangles += static_cast<vtkIdType>(mesh.Triangles.size() / 3);
    drawn = true;
  }
  if (drawn)
  {
    ++this->OccludersDrawn;
  }
  stopClock();
}

void vtkOccluderRasterizer::DrawMesh(
  vtkPoints* points, const Mesh& mesh, const double clipFromModel[16], so::FaceCulling culling)
{
  const vtkIdType n = points->GetNumberOfPoints();
  // Runs of triangles behind what the buffer already has are skipped before their vertices
  // are projected (most of a part seen beside or behind a nearer one).
  so::TriangleClusters clusters;
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      clusters.clipFromModel[c][r] = clipFromModel[4 * r + c];
    }
  }
  clusters.boxes = mesh.Clusters.data();
  clusters.trianglesPerCluster = kTrianglesPerCluster;
  const so::TriangleClusters* runs = mesh.Clusters.size() ==
      6 * ((mesh.Triangles.size() / 3 + kTrianglesPerCluster - 1) / kTrianglesPerCluster)
    ? &clusters
    : nullptr;
  // A plain float or double point array is handed over as it is (other arrays are copied to
  // doubles first): the buffer transforms only the points of the triangles it looks at, not
  // those of skipped runs.
  so::ModelVertices vertices;
  vertices.clipFromModel = clusters.clipFromModel;
  if (vtkFloatArray* f = vtkFloatArray::FastDownCast(points->GetData()))
  {
    vertices.xyzFloat = f->GetPointer(0);
  }
  else if (vtkDoubleArray* d = vtkDoubleArray::FastDownCast(points->GetData()))
  {
    vertices.xyzDouble = d->GetPointer(0);
  }
  else
  {
    this->Points.resize(3 * static_cast<std::size_t>(n));
    for (vtkIdType i = 0; i < n; ++i)
    {
      points->GetPoint(i, this->Points.data() + 3 * i);
    }
    vertices.xyzDouble = this->Points.data();
  }
  this->DepthBuffer.drawTriangles(vertices, static_cast<std::size_t>(n), mesh.Triangles.data(),
    mesh.Triangles.size() / 3, culling, mesh.Neighbors.data(), runs);
}
