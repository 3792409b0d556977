// ID renders; see vtkSceneVisIdBuffer.h.
#include <vtk_glew.h> // first: GLEW must precede any other OpenGL header

#include "vtkSceneVisIdBuffer.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkIdTypeArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkOpenGLPolyDataMapper.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLState.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkRendererCollection.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <sstream>
#include <stdexcept>

/**
 * Mapper for ID renders. With DepthTest off it disables GL_DEPTH_TEST right around its own draw
 * calls (through vtkOpenGLState, so VTK's state cache stays coherent, and restored afterwards).
 * Doing it at draw time is robust against the renderer and passes, which re-enable the depth test
 * before the opaque pass.
 */
class vtkSceneVisIdBufferMapper : public vtkOpenGLPolyDataMapper
{
public:
  static vtkSceneVisIdBufferMapper* New();
  vtkTypeMacro(vtkSceneVisIdBufferMapper, vtkOpenGLPolyDataMapper);

  bool DepthTest = true;

  void RenderPieceDraw(vtkRenderer* renderer, vtkActor* actor) override
  {
    auto* window = vtkOpenGLRenderWindow::SafeDownCast(renderer->GetRenderWindow());
    if (this->DepthTest || !window)
    {
      this->Superclass::RenderPieceDraw(renderer, actor);
      return;
    }
    vtkOpenGLState* state = window->GetState();
    vtkOpenGLState::ScopedglEnableDisable savedDepthTest(state, GL_DEPTH_TEST);
    state->vtkglDisable(GL_DEPTH_TEST);
    this->Superclass::RenderPieceDraw(renderer, actor);
  }

protected:
  vtkSceneVisIdBufferMapper() = default;
  ~vtkSceneVisIdBufferMapper() override = default;

private:
  vtkSceneVisIdBufferMapper(const vtkSceneVisIdBufferMapper&) = delete;
  void operator=(const vtkSceneVisIdBufferMapper&) = delete;
};
vtkStandardNewMacro(vtkSceneVisIdBufferMapper);

namespace scenevis
{
namespace idbuffer
{
namespace
{
void RequirePolygonsOnly(vtkPolyData* polys)
{
  if (!polys)
  {
    throw std::invalid_argument("ID buffer: no polydata");
  }
  if (polys->GetNumberOfVerts() || polys->GetNumberOfLines() || polys->GetNumberOfStrips())
  {
    throw std::invalid_argument("ID buffer: the polydata must contain polygons only (VTK draws "
                                "verts, lines, polys and strips in separate batches, which would "
                                "break the cell order)");
  }
}
} // namespace

IdImage RenderIdBuffer(
  vtkRenderWindow* window, vtkPolyData* polys, vtkCamera* camera, const IdRenderOptions& options)
{
  RequirePolygonsOnly(polys);
  if (!window)
  {
    throw std::invalid_argument("ID buffer: no render window");
  }
  const vtkIdType cells = polys->GetNumberOfCells();
  vtkDataArray* original = nullptr;
  if (!options.originalIdArray.empty())
  {
    original = polys->GetCellData()->GetArray(options.originalIdArray.c_str());
    if (!original || original->GetNumberOfTuples() != cells ||
      original->GetNumberOfComponents() != 1)
    {
      throw std::invalid_argument(
        "ID buffer: no 1-component cell array '" + options.originalIdArray + "' for every cell");
    }
  }

  // Colour per cell: id + 1 in 24 bits.
  vtkNew<vtkUnsignedCharArray> colours;
  colours->SetName("scenevis_id_colour");
  colours->SetNumberOfComponents(3);
  colours->SetNumberOfTuples(cells);
  for (vtkIdType cell = 0; cell < cells; ++cell)
  {
    const double id = original ? original->GetComponent(cell, 0) : double(cell);
    if (id < 0 || id > double(kMaxEncodableId))
    {
      throw std::invalid_argument("ID buffer: id " + std::to_string(id) + " of cell " +
        std::to_string(cell) + " does not fit 24 bits");
    }
    const auto value = static_cast<std::uint32_t>(id) + 1u;
    unsigned char* rgb = colours->GetPointer(3 * cell);
    rgb[0] = static_cast<unsigned char>((value >> 16) & 0xFFu);
    rgb[1] = static_cast<unsigned char>((value >> 8) & 0xFFu);
    rgb[2] = static_cast<unsigned char>(value & 0xFFu);
  }
  vtkNew<vtkPolyData> coloured;
  coloured->SetPoints(polys->GetPoints());
  coloured->SetPolys(polys->GetPolys());
  coloured->GetCellData()->SetScalars(colours);

  vtkNew<vtkSceneVisIdBufferMapper> mapper;
  mapper->DepthTest = options.depthTest;
  mapper->SetInputData(coloured);
  mapper->ScalarVisibilityOn();
  mapper->SetScalarModeToUseCellData();
  mapper->SetColorModeToDirectScalars(); // the bytes are used as they are, no lookup table
  mapper->InterpolateScalarsBeforeMappingOff();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->LightingOff();
  actor->GetProperty()->SetInterpolationToFlat();
  actor->GetProperty()->SetOpacity(1.0); // opaque: no blending, opaque pass only
  actor->GetProperty()->SetRepresentationToSurface();
  actor->GetProperty()->EdgeVisibilityOff();

  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0, 0, 0);
  renderer->SetUseFXAA(false);
  renderer->SetUseDepthPeeling(0);
  renderer->AddActor(actor);
  if (camera)
  {
    renderer->GetActiveCamera()->DeepCopy(camera);
  }
  else
  {
    renderer->ResetCamera();
  }

  // Detach the window's renderers so that only the ID render is in the image.
  std::vector<vtkSmartPointer<vtkRenderer>> saved;
  vtkRendererCollection* renderers = window->GetRenderers();
  renderers->InitTraversal();
  while (vtkRenderer* other = renderers->GetNextItem())
  {
    saved.emplace_back(other);
  }
  for (auto& other : saved)
  {
    window->RemoveRenderer(other);
  }
  window->AddRenderer(renderer);
  // After AddRenderer: the near-plane tolerance depends on the window's depth bits (0.001 with
  // 24 bits, else 0.01 of the far distance), and a near plane 1% away looks through walls.
  if (!camera || !options.cameraClippingRange)
  {
    renderer->ResetCameraClippingRange();
  }
  window->Render();
  const int* size = window->GetSize();
  IdImage image;
  image.width = size[0];
  image.height = size[1];
  vtkNew<vtkUnsignedCharArray> pixels;
  window->GetPixelData(0, 0, size[0] - 1, size[1] - 1, 0, pixels);
  window->RemoveRenderer(renderer);
  renderer->ReleaseGraphicsResources(window);
  for (auto& other : saved)
  {
    window->AddRenderer(other);
  }

  const std::size_t count = static_cast<std::size_t>(image.width) * image.height;
  if (static_cast<std::size_t>(pixels->GetNumberOfTuples()) != count)
  {
    throw std::runtime_error("ID buffer: could not read back the pixels");
  }
  image.ids.resize(count);
  const unsigned char* p = pixels->GetPointer(0);
  for (std::size_t i = 0; i < count; ++i, p += 3)
  {
    const std::uint32_t value = (std::uint32_t(p[0]) << 16) | (std::uint32_t(p[1]) << 8) | p[2];
    image.ids[i] = value == 0 ? kNoId : value - 1;
  }
  return image;
}

IdImage RenderVisibleIds(vtkRenderWindow* window, vtkPolyData* polys, vtkCamera* camera,
  const std::string& originalIdArray)
{
  IdRenderOptions options;
  options.depthTest = true;
  options.originalIdArray = originalIdArray;
  return RenderIdBuffer(window, polys, camera, options);
}

IdImage RenderPainterIds(vtkRenderWindow* window, vtkPolyData* polys, vtkCamera* camera,
  const std::string& originalIdArray)
{
  IdRenderOptions options;
  options.depthTest = false;
  options.originalIdArray = originalIdArray;
  return RenderIdBuffer(window, polys, camera, options);
}

std::vector<std::uint32_t> VisibleSet(const IdImage& image)
{
  std::vector<std::uint32_t> ids;
  for (std::uint32_t id : image.ids)
  {
    if (id != kNoId)
    {
      ids.push_back(id);
    }
  }
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  return ids;
}

std::vector<std::uint8_t> ComputeEdgeMask(const IdImage& zbufferIds)
{
  const int w = zbufferIds.width;
  const int h = zbufferIds.height;
  std::vector<std::uint8_t> mask(zbufferIds.ids.size(), 0);
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      const std::uint32_t centre = zbufferIds.At(x, y);
      bool edge = false;
      for (int dy = -1; dy <= 1 && !edge; ++dy)
      {
        for (int dx = -1; dx <= 1 && !edge; ++dx)
        {
          const int nx = x + dx;
          const int ny = y + dy;
          if (nx >= 0 && ny >= 0 && nx < w && ny < h && zbufferIds.At(nx, ny) != centre)
          {
            edge = true;
          }
        }
      }
      mask[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) +
        static_cast<std::size_t>(x)] = edge ? 1 : 0;
    }
  }
  return mask;
}

std::string OrderComparison::Summary() const
{
  std::ostringstream text;
  if (!this->problem.empty())
  {
    text << "not comparable: " << this->problem;
  }
  else
  {
    text << this->mismatchedPixels << " of " << this->comparedPixels
         << " non-edge pixels differ between the painter's and the z-buffer image ("
         << this->edgePixels << " edge pixels excluded)";
  }
  return text.str();
}

OrderComparison OrderMatchesDepth(
  const IdImage& painterIds, const IdImage& zbufferIds, const std::vector<std::uint8_t>& edgeMask)
{
  OrderComparison result;
  if (painterIds.width != zbufferIds.width || painterIds.height != zbufferIds.height ||
    painterIds.ids.size() != zbufferIds.ids.size() || edgeMask.size() != zbufferIds.ids.size())
  {
    result.problem = "image or mask sizes differ";
    return result;
  }
  for (std::size_t i = 0; i < zbufferIds.ids.size(); ++i)
  {
    if (edgeMask[i])
    {
      ++result.edgePixels;
      continue;
    }
    ++result.comparedPixels;
    if (painterIds.ids[i] != zbufferIds.ids[i])
    {
      ++result.mismatchedPixels;
    }
  }
  result.matches = result.mismatchedPixels == 0;
  return result;
}

OrderComparison OrderMatchesDepth(const IdImage& painterIds, const IdImage& zbufferIds)
{
  return OrderMatchesDepth(painterIds, zbufferIds, ComputeEdgeMask(zbufferIds));
}

std::string CullingCheck::Summary() const
{
  std::ostringstream text;
  if (this->conservative)
  {
    text << "conservative: every visible id was drawn";
    return text.str();
  }
  text << this->missing.size() << " visible id(s) not drawn:";
  std::size_t shown = 0;
  for (std::uint32_t id : this->missing)
  {
    if (++shown > 20)
    {
      text << " ...";
      break;
    }
    text << " " << id;
  }
  return text.str();
}

CullingCheck CullingIsConservative(
  const std::vector<std::uint32_t>& visibleSet, const std::vector<std::uint32_t>& drawnIds)
{
  std::vector<std::uint32_t> drawn(drawnIds);
  std::sort(drawn.begin(), drawn.end());
  CullingCheck result;
  for (std::uint32_t id : visibleSet)
  {
    if (id != kNoId && !std::binary_search(drawn.begin(), drawn.end(), id))
    {
      result.missing.push_back(id);
    }
  }
  std::sort(result.missing.begin(), result.missing.end());
  result.missing.erase(
    std::unique(result.missing.begin(), result.missing.end()), result.missing.end());
  result.conservative = result.missing.empty();
  return result;
}

CullingCheck CullingIsConservative(
  const IdImage& evsIds, const std::vector<std::uint32_t>& drawnIds)
{
  return CullingIsConservative(VisibleSet(evsIds), drawnIds);
}

vtkSmartPointer<vtkPolyData> ReorderCells(
  vtkPolyData* polys, const std::vector<vtkIdType>& order, const std::string& originalIdArray)
{
  RequirePolygonsOnly(polys);
  const vtkIdType cells = polys->GetNumberOfCells();
  vtkNew<vtkCellArray> reordered;
  vtkNew<vtkIdTypeArray> originalIds;
  originalIds->SetName(originalIdArray.c_str());
  originalIds->SetNumberOfTuples(static_cast<vtkIdType>(order.size()));
  vtkIdType index = 0;
  for (vtkIdType cell : order)
  {
    if (cell < 0 || cell >= cells)
    {
      throw std::invalid_argument(
        "ReorderCells: cell index " + std::to_string(cell) + " out of range");
    }
    vtkIdType npts = 0;
    const vtkIdType* pts = nullptr;
    polys->GetPolys()->GetCellAtId(cell, npts, pts);
    reordered->InsertNextCell(npts, pts);
    originalIds->SetValue(index++, cell);
  }
  auto result = vtkSmartPointer<vtkPolyData>::New();
  result->SetPoints(polys->GetPoints());
  result->SetPolys(reordered);
  result->GetCellData()->AddArray(originalIds);
  return result;
}

vtkSmartPointer<vtkImageData> IdImageToColor(const IdImage& image)
{
  vtkNew<vtkUnsignedCharArray> rgb;
  rgb->SetNumberOfComponents(3);
  rgb->SetNumberOfTuples(static_cast<vtkIdType>(image.ids.size()));
  for (std::size_t i = 0; i < image.ids.size(); ++i)
  {
    unsigned char* p = rgb->GetPointer(static_cast<vtkIdType>(3 * i));
    const std::uint32_t id = image.ids[i];
    if (id == kNoId)
    {
      p[0] = p[1] = p[2] = 0;
      continue;
    }
    // A cheap integer hash spreads neighbouring ids over distinct, bright colours.
    std::uint32_t h = (id + 1u) * 2654435761u;
    p[0] = static_cast<unsigned char>(64 + ((h >> 8) & 0xBF));
    p[1] = static_cast<unsigned char>(64 + ((h >> 16) & 0xBF));
    p[2] = static_cast<unsigned char>(64 + ((h >> 24) & 0xBF));
  }
  auto result = vtkSmartPointer<vtkImageData>::New();
  result->SetDimensions(image.width, image.height, 1);
  result->GetPointData()->SetScalars(rgb);
  return result;
}

} // namespace idbuffer
} // namespace scenevis
