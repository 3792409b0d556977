// vtkChunkedPolyDataMapper on a mesh with every cell kind real CAD data brings: triangles with two
// points at the same place (same id, and different ids at the same coordinates), polygons of 7
// and 12 points (some with coincident points), triangle strips (some with repeated points), and
// verts and lines in the same polydata. Against a plain vtkPolyDataMapper drawing the same input,
// over many cameras:
//  (a) the triangle list: as many triangles as VTK's own index buffer rule gives for the polygons
//      plus the non-degenerate strip triangles;
//  (b) culling is never skipped, fewer triangles than the whole mesh are drawn when the camera
//      sees part of it, and every polygon / strip of the exact visible set (ID buffer) is drawn
//      (0 false negatives);
//  (c) cell scalars colour the right cells: unlit, one unique colour per input cell, the culled
//      image equals the plain mapper's pixel for pixel;
//  (d) back-face culling: normal cones cull (cameras below the surface), images still equal;
//  (e) picking: cell ids of a hardware selection mapped by GetInputCellId() are exactly the ids
//      the plain mapper's selection reports;
//  (f) wireframe: the plain mapper's image (polygon outlines, not our triangles), culling
//      reported as skipped; empty input, verts and lines only, polygons that are all
//      degenerate: drawn without a warning, nothing reported as skipped.
#include "vtkChunkedPolyDataMapper.h"

#include "ChunkedMapperTesting.h"

#include "scenevis/testing/IdBuffer.h"
#include "scenevis/testing/ImageCompare.h"
#include "scenevis/testing/RenderWindow.h"
#include "scenevis/testing/StrictVtkOutput.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkIdTypeArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkOpenGLIndexBufferObject.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkRendererCollection.h>
#include <vtkUnsignedCharArray.h>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <random>
#include <string>
#include <vector>

namespace
{
namespace st = scenevis::testing;

bool Check(bool ok, const std::string& what)
{
  std::cout << (ok ? "ok   " : "FAIL ") << what << "\n";
  return ok;
}

/// A field of separate planar tiles over a wavy height field (no two cells coplanar and
/// overlapping, so pixels never depend on the drawing order), each tile one cell kind.
struct CellZoo
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> verts, lines, polys, strips;
  vtkIdType stripTriangles = 0; // strip triangles without coincident points

  vtkIdType Add(double x, double y, double z) { return this->points->InsertNextPoint(x, y, z); }

  /// Regular @p n-gon around (cx, cy) at height z; @p coincide: the point after index 3 gets its
  /// own id at the coordinates of point 3, and point 7 is repeated by id.
  void Polygon(double cx, double cy, double z, int n, double r, bool coincide)
  {
    std::vector<vtkIdType> ids;
    for (int k = 0; k < n; ++k)
    {
      const double a = 2.0 * M_PI * k / n + 0.1;
      ids.push_back(this->Add(cx + r * std::cos(a), cy + r * std::sin(a), z));
      if (coincide && k == 3)
      {
        ids.push_back(this->Add(cx + r * std::cos(a), cy + r * std::sin(a), z));
      }
      if (coincide && k == 7)
      {
        ids.push_back(ids.back());
      }
    }
    this->polys->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
  }

  void Tile(int kind, double x, double y, double z)
  {
    const double s = 0.8;
    switch (kind)
    {
      case 0: // a triangle, a triangle degenerate by id, a quad
      {
        const vtkIdType a = this->Add(x, y, z), b = this->Add(x + s, y, z),
                        c = this->Add(x + s, y + 0.4 * s, z), d = this->Add(x, y + 0.4 * s, z);
        const vtkIdType e = this->Add(x, y + 0.5 * s, z), f = this->Add(x + s, y + 0.5 * s, z),
                        g = this->Add(x + 0.5 * s, y + s, z);
        const vtkIdType quad[4] = { a, b, c, d }, tri[3] = { e, f, g }, bad[3] = { e, f, f };
        this->polys->InsertNextCell(4, quad);
        this->polys->InsertNextCell(3, tri);
        this->polys->InsertNextCell(3, bad);
        break;
      }
      case 1: // degenerate by coordinates: b2 is a second id at b's place
      {
        const vtkIdType a = this->Add(x, y, z), b = this->Add(x + s, y, z),
                        b2 = this->Add(x + s, y, z), c = this->Add(x + s, y + s, z),
                        d = this->Add(x, y + s, z);
        const vtkIdType flat[3] = { a, b, b2 }, quad[4] = { a, b, b2, c }, tri[3] = { a, c, d };
        this->polys->InsertNextCell(3, flat); // no triangle at all
        this->polys->InsertNextCell(4, quad); // one triangle: (a, b2, c)
        this->polys->InsertNextCell(3, tri);
        break;
      }
      case 2:
        this->Polygon(x + 0.5 * s, y + 0.5 * s, z, 7, 0.45 * s, false);
        break;
      case 3:
        this->Polygon(x + 0.5 * s, y + 0.5 * s, z, 12, 0.45 * s, false);
        break;
      case 4:
        this->Polygon(x + 0.5 * s, y + 0.5 * s, z, 12, 0.45 * s, true);
        break;
      default: // a strip, and one with a repeated point (degenerate triangles); facing +z like
               // the polygons, so that normal cones can cull from below
      {
        std::vector<vtkIdType> ids;
        for (int k = 0; k < 8; ++k)
        {
          ids.push_back(this->Add(x + 0.125 * s * k, y + (k % 2 ? 0.0 : 0.4 * s), z));
        }
        this->strips->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
        this->stripTriangles += 6;
        ids.clear();
        for (int k = 0; k < 6; ++k)
        {
          ids.push_back(this->Add(x + 0.16 * s * k, y + 0.5 * s + (k % 2 ? 0.0 : 0.4 * s), z));
          if (k == 2)
          {
            // Twice: one repeat would flip the winding of the rest of the strip.
            ids.push_back(ids.back());
            ids.push_back(ids.back());
          }
        }
        this->strips->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
        this->stripTriangles += 3; // 8 points, 6 triangles, 3 with point 2 twice or more
        break;
      }
    }
  }

  vtkSmartPointer<vtkPolyData> Build(int grid)
  {
    for (int i = 0; i < grid; ++i)
    {
      for (int j = 0; j < grid; ++j)
      {
        const double z = 2.0 * std::sin(0.45 * i) * std::cos(0.35 * j) + 0.013 * (i * grid + j);
        this->Tile((i * 7 + j * 3) % 6, i, j, z);
        if ((i + j) % 9 == 0)
        {
          // Verts and lines well above the tiles: never at the depth of a triangle.
          const vtkIdType p = this->Add(i + 0.4, j + 0.4, z + 1.5);
          this->verts->InsertNextCell(1, &p);
          const vtkIdType l[3] = { this->Add(i, j, z + 2.0), this->Add(i + 0.7, j + 0.3, z + 2.1),
            this->Add(i + 0.4, j + 0.8, z + 2.2) };
          this->lines->InsertNextCell(3, l);
        }
      }
    }
    auto mesh = vtkSmartPointer<vtkPolyData>::New();
    mesh->SetPoints(this->points);
    mesh->SetVerts(this->verts);
    mesh->SetLines(this->lines);
    mesh->SetPolys(this->polys);
    mesh->SetStrips(this->strips);
    // One unique colour per cell (an odd multiplier is a bijection modulo 2^24), spread so that
    // neighbouring cells differ in every channel: a wrong gl_PrimitiveID offset shows.
    vtkNew<vtkUnsignedCharArray> colors;
    colors->SetName("CellColors");
    colors->SetNumberOfComponents(3);
    colors->SetNumberOfTuples(mesh->GetNumberOfCells());
    for (vtkIdType c = 0; c < mesh->GetNumberOfCells(); ++c)
    {
      const std::uint32_t v = (static_cast<std::uint32_t>(c + 1) * 2654435761u) & 0xFFFFFFu;
      colors->SetTypedTuple(c,
        std::vector<unsigned char>{ static_cast<unsigned char>(v >> 16),
          static_cast<unsigned char>(v >> 8), static_cast<unsigned char>(v) }
          .data());
    }
    mesh->GetCellData()->SetScalars(colors);
    return mesh;
  }
};

/// A camera around a random point of the bounds; below the surface when @p below.
void RandomCamera(vtkCamera* camera, std::mt19937_64& gen, const double* b, int i, bool below)
{
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const glm::dvec3 lo(b[0], b[2], b[4]), hi(b[1], b[3], b[5]);
  const glm::dvec3 size = hi - lo;
  const glm::dvec3 focal = lo + glm::dvec3(u(gen), u(gen), u(gen)) * size;
  glm::dvec3 dir = glm::normalize(glm::dvec3(u(gen) - 0.5, u(gen) - 0.5, u(gen) * 0.8 + 0.2));
  dir.z = below ? -dir.z : dir.z;
  const double distance = glm::length(size) * (0.05 + 0.6 * u(gen));
  const glm::dvec3 eye = focal + dir * distance;
  camera->SetFocalPoint(focal.x, focal.y, focal.z);
  camera->SetPosition(eye.x, eye.y, eye.z);
  camera->SetViewUp(0, 0, 1);
  camera->OrthogonalizeViewUp();
  camera->SetViewAngle(20.0 + 40.0 * u(gen));
  camera->SetParallelProjection(i % 6 == 5);
  camera->SetParallelScale(distance * 0.4);
}

void Unlit(vtkActor* actor, vtkPolyDataMapper* mapper)
{
  mapper->SetScalarModeToUseCellData();
  mapper->SetColorModeToDirectScalars();
  actor->GetProperty()->LightingOff();
}

/// (f) Inputs with nothing or nothing but degenerate triangles to draw.
bool SmallInputs(vtkRenderWindow* window)
{
  bool ok = true;
  vtkNew<vtkPoints> points;
  const vtkIdType a = points->InsertNextPoint(0, 0, 0), b = points->InsertNextPoint(1, 0, 0),
                  b2 = points->InsertNextPoint(1, 0, 0), c = points->InsertNextPoint(0, 1, 0);
  vtkNew<vtkPolyData> empty;
  vtkNew<vtkPolyData> wires;
  wires->SetPoints(points);
  vtkNew<vtkCellArray> verts, lines, polys;
  verts->InsertNextCell(1, &a);
  const vtkIdType line[2] = { a, c };
  lines->InsertNextCell(2, line);
  wires->SetVerts(verts);
  wires->SetLines(lines);
  vtkNew<vtkPolyData> flat;
  flat->SetPoints(points);
  const vtkIdType t1[3] = { a, b, b2 }, t2[3] = { a, c, c };
  polys->InsertNextCell(3, t1);
  polys->InsertNextCell(3, t2);
  flat->SetPolys(polys);
  flat->SetVerts(verts);
  const char* names[] = { "empty input", "verts and lines only", "all polygons degenerate" };
  vtkPolyData* inputs[] = { empty, wires, flat };
  for (int i = 0; i < 3; ++i)
  {
    vtkNew<vtkChunkedPolyDataMapper> mapper;
    mapper->SetInputData(inputs[i]);
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    vtkNew<vtkRenderer> renderer;
    renderer->AddActor(actor);
    renderer->GetActiveCamera()->SetPosition(0.5, 0.5, 3);
    renderer->GetActiveCamera()->SetFocalPoint(0.5, 0.5, 0);
    window->GetRenderers()->RemoveAllItems();
    window->AddRenderer(renderer);
    window->Render();
    ok &= Check(!mapper->GetCullingSkipped() && mapper->GetNumberOfTriangles() == 0 &&
        mapper->GetNumberOfTrianglesDrawn() == 0,
      std::string(names[i]) + ": drawn, no triangle, not reported as skipped");
  }
  window->GetRenderers()->RemoveAllItems();
  return ok;
}
} // namespace

int TestChunkedPolyDataMapperCells(int, char*[])
{
  st::StrictVtkOutput vtkOutput;
  bool ok = true;
  const int cameras = 24;

  CellZoo zoo;
  vtkSmartPointer<vtkPolyData> mesh = zoo.Build(24);
  const char* idName = "InputCellId";
  vtkSmartPointer<vtkPolyData> idMesh = chunked_testing::TrianglesWithInputIds(mesh, idName);

  // (a) VTK's own rule for the polygons, plus the strip triangles that cover pixels.
  std::vector<unsigned int> vtkIndices;
  vtkOpenGLIndexBufferObject::AppendTriangleIndexBuffer(
    vtkIndices, mesh->GetPolys(), mesh->GetPoints(), 0, nullptr, nullptr);
  const auto expectedTriangles = static_cast<vtkIdType>(vtkIndices.size() / 3) + zoo.stripTriangles;

  vtkSmartPointer<vtkRenderWindow> window = st::MakeRenderWindow(400, 300);
  vtkSmartPointer<vtkRenderWindow> idWindow = st::MakeRenderWindow(400, 300);
  vtkNew<vtkRenderer> plainRenderer, chunkedRenderer;
  vtkNew<vtkPolyDataMapper> plainMapper;
  plainMapper->SetInputData(mesh);
  vtkNew<vtkChunkedPolyDataMapper> chunkedMapper;
  chunkedMapper->SetInputData(mesh);
  chunkedMapper->SetChunkSize(64);
  vtkNew<vtkActor> plain, chunked;
  plain->SetMapper(plainMapper);
  chunked->SetMapper(chunkedMapper);
  Unlit(plain, plainMapper);
  Unlit(chunked, chunkedMapper);
  plainRenderer->AddActor(plain);
  chunkedRenderer->AddActor(chunked);
  vtkNew<vtkCamera> camera;
  plainRenderer->SetActiveCamera(camera);
  chunkedRenderer->SetActiveCamera(camera);
  double bounds[6];
  mesh->GetBounds(bounds);
  auto show = [&](vtkRenderer* renderer)
  {
    window->GetRenderers()->RemoveAllItems();
    window->AddRenderer(renderer);
    renderer->ResetCameraClippingRange(bounds);
  };
  auto renderWith = [&](vtkRenderer* renderer)
  {
    show(renderer);
    return st::CaptureImage(window);
  };

  std::mt19937_64 gen(1313);
  std::size_t mismatches = 0, missing = 0, partial = 0, skipped = 0, coneCulled = 0;
  std::size_t drawnSum = 0, visibleSum = 0, selectionMismatches = 0, selectedSum = 0;
  vtkIdType total = 0;
  for (int pass = 0; pass < 2; ++pass)
  {
    // 0: frustum culling; 1: back-face culling on, half the cameras below the surface.
    plain->GetProperty()->SetBackfaceCulling(pass == 1);
    chunked->GetProperty()->SetBackfaceCulling(pass == 1);
    for (int c = 0; c < cameras; ++c)
    {
      RandomCamera(camera, gen, bounds, c, pass == 1 && c % 2 == 1);
      vtkSmartPointer<vtkImageData> reference = renderWith(plainRenderer);
      vtkSmartPointer<vtkImageData> image = renderWith(chunkedRenderer);
      total = chunkedMapper->GetNumberOfTriangles();
      const vtkIdType drawn = chunkedMapper->GetNumberOfTrianglesDrawn();
      skipped += chunkedMapper->GetCullingSkipped() ? 1 : 0;
      partial += drawn < total ? 1 : 0;
      drawnSum += static_cast<std::size_t>(drawn);
      coneCulled += static_cast<std::size_t>(chunkedMapper->GetNumberOfChunksCulledByNormalCone());
      std::cout << "pass " << pass << " camera " << c << ": drew " << drawn << " of " << total
                << " triangles, " << chunkedMapper->GetNumberOfChunksDrawn() << " of "
                << chunkedMapper->GetNumberOfChunks() << " chunks in "
                << chunkedMapper->GetNumberOfDrawCalls() << " draw calls, chunks culled by frustum "
                << chunkedMapper->GetNumberOfChunksCulledByFrustum() << ", by normal cone "
                << chunkedMapper->GetNumberOfChunksCulledByNormalCone() << "\n";
      std::string why;
      if (!st::ImagesIdentical(reference, image, &why))
      {
        ++mismatches;
        std::cout << "pass " << pass << " camera " << c << ": image differs: " << why << "\n";
      }
      if (pass == 0)
      {
        std::vector<vtkIdType> drawnCells;
        chunkedMapper->GetDrawnCellIds(drawnCells);
        const std::vector<std::uint32_t> drawnIds(drawnCells.begin(), drawnCells.end());
        const std::vector<std::uint32_t> visible =
          st::VisibleSet(st::RenderVisibleIds(idWindow, idMesh, camera, idName));
        visibleSum += visible.size();
        const st::CullingCheck check = st::CullingIsConservative(visible, drawnIds);
        missing += check.missing.size();
        if (!check.conservative)
        {
          std::cout << "camera " << c << ": " << check.Summary() << "\n";
        }
      }
      if (c % 4 == 0)
      {
        // (e) Picking: the chunked mapper draws its copy; ids mapped back must be the input's.
        show(chunkedRenderer);
        const std::set<vtkIdType> picked = chunked_testing::SelectedCells(
          chunkedRenderer, [&](vtkIdType id) { return chunkedMapper->GetInputCellId(id); });
        show(plainRenderer);
        const std::set<vtkIdType> truth =
          chunked_testing::SelectedCells(plainRenderer, [](vtkIdType id) { return id; });
        selectedSum += truth.size();
        if (picked != truth)
        {
          ++selectionMismatches;
          std::cout << "pass " << pass << " camera " << c << ": selection of " << picked.size()
                    << " cells mapped back, " << truth.size() << " selected by the plain mapper\n";
        }
      }
    }
  }
  std::cout << "mesh: " << mesh->GetNumberOfVerts() << " verts, " << mesh->GetNumberOfLines()
            << " lines, " << mesh->GetNumberOfPolys() << " polygons, " << mesh->GetNumberOfStrips()
            << " strips; " << total << " triangles drawn at most\n";
  ok &= Check(total == expectedTriangles,
    "(a) triangle list: " + std::to_string(total) + " triangles, VTK's index buffer rule gives " +
      std::to_string(expectedTriangles));
  ok &= Check(skipped == 0, "(b) culling never skipped (" + std::to_string(skipped) + ")");
  ok &= Check(partial * 4 >= static_cast<std::size_t>(2 * cameras) * 3,
    "(b) fewer triangles than the mesh drawn for most cameras (" + std::to_string(partial) +
      " of " + std::to_string(2 * cameras) + "; " + std::to_string(drawnSum) + " of " +
      std::to_string(2 * cameras * total) + " in all)");
  ok &= Check(missing == 0 && visibleSum > 0,
    "(b) 0 false negatives against the ID-buffer EVS (" + std::to_string(missing) + " of " +
      std::to_string(visibleSum) + " visible cells)");
  ok &= Check(mismatches == 0,
    "(c, d) culled images with cell scalars identical to the plain mapper's (" +
      std::to_string(mismatches) + " cameras differ)");
  ok &= Check(coneCulled > 0, "(d) normal cones cull (" + std::to_string(coneCulled) + ")");
  ok &= Check(selectionMismatches == 0 && selectedSum > 0,
    "(e) picked cells mapped by GetInputCellId() = the plain mapper's selection (" +
      std::to_string(selectedSum) + " cells)");
  ok &= Check(chunkedMapper->GetInputCellId(-1) == -1 &&
      chunkedMapper->GetInputCellId(mesh->GetNumberOfVerts() + mesh->GetNumberOfLines() + total) ==
        -1 &&
      chunkedMapper->GetInputCellId(0) == 0,
    "(e) GetInputCellId: verts keep their ids, ids past the copy give -1");
  ok &= Check(chunkedMapper->GetNumberOfVertexBufferBuilds() <= 2,
    "vertex buffers built once per property state (" +
      std::to_string(chunkedMapper->GetNumberOfVertexBufferBuilds()) + ")");
  // Wireframe and edges outline the input's polygons (no fan diagonals): the input is drawn.
  for (vtkActor* a : { plain.GetPointer(), chunked.GetPointer() })
  {
    a->GetProperty()->SetBackfaceCulling(false);
    a->GetProperty()->SetRepresentationToWireframe();
  }
  RandomCamera(camera, gen, bounds, 0, false);
  vtkSmartPointer<vtkImageData> plainWires = renderWith(plainRenderer);
  vtkSmartPointer<vtkImageData> chunkedWires = renderWith(chunkedRenderer);
  std::string why;
  const bool sameWires = st::ImagesIdentical(plainWires, chunkedWires, &why);
  ok &= Check(
    sameWires && chunkedMapper->GetCullingSkipped() && chunkedMapper->GetInputCellId(1000) == 1000,
    "wireframe: the input drawn as the plain mapper draws it, ids unmapped " + why);
  // And a surface again: the copy's connectivity goes back into the triangle index buffer (which
  // the wireframe's outline indices replaced), culling resumes.
  for (vtkActor* a : { plain.GetPointer(), chunked.GetPointer() })
  {
    a->GetProperty()->SetRepresentationToSurface();
  }
  vtkSmartPointer<vtkImageData> plainSurface = renderWith(plainRenderer);
  vtkSmartPointer<vtkImageData> chunkedSurface = renderWith(chunkedRenderer);
  const bool sameSurface = st::ImagesIdentical(plainSurface, chunkedSurface, &why);
  ok &= Check(sameSurface && !chunkedMapper->GetCullingSkipped() &&
      chunkedMapper->GetNumberOfTrianglesDrawn() > 0,
    "surface after wireframe: the copy drawn again, as the plain mapper draws the input " + why);
  // The copy carries only the cell arrays the mapper can draw with: a part array nobody colours
  // by stays in the input (8 bytes per triangle not copied); colouring by it copies it, and the
  // image is the plain mapper's.
  vtkNew<vtkIdTypeArray> partIds;
  partIds->SetName("Part");
  partIds->SetNumberOfTuples(mesh->GetNumberOfCells());
  for (vtkIdType c = 0; c < mesh->GetNumberOfCells(); ++c)
  {
    partIds->SetValue(c, c % 7);
  }
  mesh->GetCellData()->AddArray(partIds);
  renderWith(chunkedRenderer);
  const unsigned long lean = chunkedMapper->GetCopyMemorySize();
  for (vtkPolyDataMapper* m : std::initializer_list<vtkPolyDataMapper*>{ plainMapper, chunkedMapper })
  {
    m->SetScalarModeToUseCellFieldData();
    m->SelectColorArray("Part");
    m->SetColorModeToMapScalars();
    m->SetScalarRange(0.0, 6.0);
  }
  vtkSmartPointer<vtkImageData> plainParts = renderWith(plainRenderer);
  vtkSmartPointer<vtkImageData> chunkedParts = renderWith(chunkedRenderer);
  const unsigned long withParts = chunkedMapper->GetCopyMemorySize();
  const bool sameParts = st::ImagesIdentical(plainParts, chunkedParts, &why);
  ok &= Check(sameParts && withParts > lean && !chunkedMapper->GetCullingSkipped(),
    "cell arrays: an array nobody draws is not copied (" + std::to_string(lean) + " kB), one "
    "chosen to colour by is (" + std::to_string(withParts) + " kB) and drawn as the plain mapper "
    "draws it " + why);
  ok &= SmallInputs(window);
  return vtkOutput.ExitCode(ok ? EXIT_SUCCESS : EXIT_FAILURE);
}
