/**
 * @file    vtkSceneVisIdBuffer.h
 * @brief   ID renders: which cells of a polydata are visible from a camera (the exact visible
 *          set), and whether a drawing order resolves visibility like the depth test does.
 *
 * The pixel-exact ground truth for visibility, ordering and culling: `scenevis cull --exact`
 * reports a culler's false negatives and over-draw against it, `scenevis bench` counts the pixels a
 * sort draws out of order, and the tests assert on both.
 *
 * RenderIdBuffer() draws a vtkPolyData with one flat, unlit, unblended colour per cell that
 * encodes (id + 1) in 24 RGB bits (R = bits 16..23, G = 8..15, B = 0..7; 0 = background) and reads
 * the ids back per pixel:
 *  - depthTest = true:  the exact visible set (EVS) at image precision (depth function GL_LEQUAL:
 *    among exactly coplanar fragments the cell drawn last wins);
 *  - depthTest = false: a painter's image: cells are drawn in the polydata's cell order and every
 *    fragment overwrites the previous one, so the LAST cell drawn at a pixel wins.
 * To test an order, pass polydata whose cells are already in that order plus a cell-data array
 * mapping each cell to its original id (ReorderCells() builds both).
 *
 * Requirements on the input (checked; std::invalid_argument otherwise):
 *  - polygons only (triangles / convex polygons in GetPolys()): VTK's mapper draws verts, lines,
 *    polys and strips as separate batches in that fixed order, which would break the cell order;
 *  - ids (original ids, or cell indices) below 2^24 - 1.
 * The window must have MSAA off (scenevis::headless::MakeRenderWindow does that, but any OpenGL
 * window works: this module does not need the OSMesa one); the render turns off lighting,
 * blending, FXAA and depth peeling itself and uses the colours as direct scalars.
 * The window's own renderers are detached during the ID render and re-attached afterwards.
 *
 * Images are row-major with the origin at the bottom-left (VTK's convention).
 *
 * @code
 * // Which cells does the camera see? (CMake: SceneVis::RenderingIdBuffer)
 * const scenevis::idbuffer::IdImage ids =
 *   scenevis::idbuffer::RenderVisibleIds(window, polydata, renderer->GetActiveCamera());
 * const std::vector<std::uint32_t> visibleCells = scenevis::idbuffer::VisibleSet(ids);
 * @endcode
 *
 * Plain functions and value types in namespace scenevis::idbuffer (not wrapped for Python).
 */
#ifndef vtkSceneVisIdBuffer_h
#define vtkSceneVisIdBuffer_h

#include "SceneVisRenderingIdBufferModule.h" // For export macro

#include <vtkSmartPointer.h> // For vtkSmartPointer
#include <vtkType.h>         // For vtkIdType

#include <cstddef> // For std::size_t
#include <cstdint> // For std::uint32_t
#include <string>  // For std::string
#include <vector>  // For std::vector

class vtkCamera;
class vtkImageData;
class vtkPolyData;
class vtkRenderWindow;

namespace scenevis
{
namespace idbuffer
{

/// Pixel value of an ID image where no cell was drawn.
constexpr std::uint32_t kNoId = 0xFFFFFFFFu;
/// Largest id that fits the 24-bit encoding (id + 1 < 2^24).
constexpr std::uint32_t kMaxEncodableId = (1u << 24) - 2;

/// Per-pixel cell ids of a render (kNoId where nothing was drawn).
struct IdImage
{
  int width = 0;
  int height = 0;
  std::vector<std::uint32_t> ids; ///< width * height, row-major, bottom row first

  std::uint32_t At(int x, int y) const
  {
    return this->ids[static_cast<std::size_t>(y) * static_cast<std::size_t>(this->width) +
      static_cast<std::size_t>(x)];
  }
};

/// Options of RenderIdBuffer().
struct IdRenderOptions
{
  /// true: z-buffered (EVS); false: painter's order = the polydata's cell order.
  bool depthTest = true;
  /// Name of a cell-data array (any numeric type, 1 component) holding each cell's original id;
  /// empty: the id is the cell index.
  std::string originalIdArray;
  /// true: keep @p camera's clipping range (compare with frames drawn with it, e.g. an eye
  /// closer to a wall than a range fitted to the whole scene allows); false: fit it to the data.
  bool cameraClippingRange = false;
};

/**
 * Render the cells of @p polys with ID colours into @p window (its size is the image size) using
 * a copy of @p camera (nullptr: a camera reset to the data bounds). The clipping range is reset
 * to the data bounds so that no cell is clipped by near/far planes (unless
 * IdRenderOptions::cameraClippingRange).
 * @throws std::invalid_argument for non-polygon cells, ids that do not fit or a missing array.
 */
SCENEVISRENDERINGIDBUFFER_EXPORT IdImage RenderIdBuffer(vtkRenderWindow* window, vtkPolyData* polys,
  vtkCamera* camera, const IdRenderOptions& options = IdRenderOptions());

/// RenderIdBuffer() with the depth test on: the exact visible set image.
SCENEVISRENDERINGIDBUFFER_EXPORT IdImage RenderVisibleIds(vtkRenderWindow* window,
  vtkPolyData* polys, vtkCamera* camera, const std::string& originalIdArray = std::string());

/// RenderIdBuffer() with the depth test off: the painter's image of the polydata's cell order.
SCENEVISRENDERINGIDBUFFER_EXPORT IdImage RenderPainterIds(vtkRenderWindow* window,
  vtkPolyData* polys, vtkCamera* camera, const std::string& originalIdArray = std::string());

/// The distinct ids present in @p image (sorted, without kNoId): the EVS for a z-buffered image.
SCENEVISRENDERINGIDBUFFER_EXPORT std::vector<std::uint32_t> VisibleSet(const IdImage& image);

/**
 * Edge mask of a z-buffer ID image: 1 for pixels whose 3x3 neighbourhood (clipped at the image
 * border) contains a different id (another cell or background), else 0. Along silhouettes and
 * intersection lines, rasterisation and depth interpolation may legitimately decide single pixels
 * differently; those pixels are excluded from order comparisons.
 */
SCENEVISRENDERINGIDBUFFER_EXPORT std::vector<std::uint8_t> ComputeEdgeMask(
  const IdImage& zbufferIds);

/// Result of OrderMatchesDepth().
struct SCENEVISRENDERINGIDBUFFER_EXPORT OrderComparison
{
  bool matches = false;             ///< no mismatching pixel (and images comparable)
  std::size_t mismatchedPixels = 0; ///< non-edge pixels where painter id != z-buffer id
  std::size_t comparedPixels = 0;   ///< non-edge pixels compared
  std::size_t edgePixels = 0;       ///< pixels excluded by the edge mask
  std::string problem;              ///< set when the images are not comparable
  std::string Summary() const;
};

/**
 * Whether a painter's image equals the z-buffer image outside the edge mask, i.e. whether the
 * drawing order resolves visibility like the depth test does.
 */
SCENEVISRENDERINGIDBUFFER_EXPORT OrderComparison OrderMatchesDepth(
  const IdImage& painterIds, const IdImage& zbufferIds, const std::vector<std::uint8_t>& edgeMask);

/// OrderMatchesDepth() with ComputeEdgeMask(zbufferIds).
SCENEVISRENDERINGIDBUFFER_EXPORT OrderComparison OrderMatchesDepth(
  const IdImage& painterIds, const IdImage& zbufferIds);

/// Result of CullingIsConservative().
struct SCENEVISRENDERINGIDBUFFER_EXPORT CullingCheck
{
  bool conservative = false;
  std::vector<std::uint32_t> missing; ///< visible ids that were not drawn (sorted)
  std::string Summary() const;
};

/// Whether every id in the EVS image @p evsIds is in @p drawnIds (any order, duplicates ok).
SCENEVISRENDERINGIDBUFFER_EXPORT CullingCheck CullingIsConservative(
  const IdImage& evsIds, const std::vector<std::uint32_t>& drawnIds);

/// Same, with the visible set already extracted (e.g. by VisibleSet()).
SCENEVISRENDERINGIDBUFFER_EXPORT CullingCheck CullingIsConservative(
  const std::vector<std::uint32_t>& visibleSet, const std::vector<std::uint32_t>& drawnIds);

/**
 * A copy of @p polys whose cells are those of @p order, in that order (each entry a cell index of
 * @p polys), with a vtkIdTypeArray named @p originalIdArray in the cell data giving each new cell's
 * index in @p polys. Points are shared. Polygons only (see file comment).
 */
SCENEVISRENDERINGIDBUFFER_EXPORT vtkSmartPointer<vtkPolyData> ReorderCells(vtkPolyData* polys,
  const std::vector<vtkIdType>& order, const std::string& originalIdArray = "scenevis_original_id");

/// False-colour RGB image of an ID image (background black) for looking at failures.
SCENEVISRENDERINGIDBUFFER_EXPORT vtkSmartPointer<vtkImageData> IdImageToColor(const IdImage& image);

} // namespace idbuffer
} // namespace scenevis

#endif
