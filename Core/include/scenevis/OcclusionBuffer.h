#pragma once
/**
 * @file OcclusionBuffer.h
 * @brief A conservative software depth buffer for occlusion culling: opaque occluders are
 *        rasterized into it, bounding boxes of occludees are tested against it.
 *
 * Contract (what "conservative" means here): a box reported occluded has no pixel of the final
 * image in which anything inside it is nearer than the occluders drawn into the buffer, provided
 * that those occluders are drawn opaque by the real renderer with the same camera and viewport.
 * There is no "few pixels" threshold.
 *
 * How it stays conservative at every pixel of the real image:
 * - The buffer has the viewport's resolution and samples the same points as OpenGL: the pixel
 *   centres (i + 0.5, j + 0.5) in window coordinates. Near the outline of an occluder (edges with
 *   no neighbour triangle, silhouette edges between a front- and a back-facing neighbour, edges
 *   made by the near plane) a pixel counts as covered only if its centre is at least
 *   `coverageMargin` pixels inside, so vertex snapping and float rounding in the GPU (llvmpipe
 *   snaps to 1/256 pixel) cannot make OpenGL leave uncovered a pixel that the buffer believes
 *   covered. Inside an occluder (an edge shared by two triangles of the same facing, given by
 *   the caller's neighbour table, see buildTriangleNeighbors()) both triangles evaluate the same
 *   edge function bit for bit with opposite signs and a tie rule gives every pixel centre to
 *   exactly one of them: a mesh is watertight, also where edges pass exactly through pixel
 *   centres (common in axis-aligned CAD views). Without a neighbour table every edge is an
 *   outline edge (still conservative, occludes less).
 * - Depths are window depths in [0, 1] as OpenGL's depth test sees them (z_ndc / 2 + 1/2, smaller
 *   is nearer). An occluder's depth over a tile is bounded from above exactly (the maximum of its
 *   plane over the tile's corners, clamped by its farthest vertex) plus `depthMargin`; an
 *   occludee's depth is its nearest corner minus `depthMargin`. A 24-bit depth buffer has steps of
 *   6e-8; the default margin is 16 steps.
 * - Occluder triangles are clipped against the near plane in clip space (what is in front of the
 *   near plane is not drawn by OpenGL either); occludee boxes are clipped against the near and
 *   side planes, and what remains is tested (its nearest depth and screen rectangle).
 *
 * Representation (the idea of Intel's Masked Software Occlusion Culling, Hasselgren et al. 2016,
 * reduced to its core, our own code): the screen is split into tiles of 8 x 4 pixels. A tile keeps
 * - z0: a depth that every pixel of the tile has something at least as near as (the "reference
 *   layer"; +inf while nothing covers the whole tile), and
 * - a working layer (mask, z1): the pixels of `mask` have something at least as near as z1.
 * Triangles of different occluders merge in the working layer; when its mask becomes full, z0
 * becomes min(z0, z1). This is what lets a mesh of many small triangles occlude: no single
 * triangle needs to cover a tile. Occludee tests read one depth per tile (z0): a box is occluded
 * when its nearest depth is behind z0 of every tile its screen rectangle touches, or, in a tile
 * where it is not, behind z1 with all of the rectangle's pixels of that tile in the working
 * layer's mask (occluders smaller than a tile, box edges). The tiles are the hierarchy's first
 * level (Greene's hierarchical z-buffer: one max depth per block).
 *
 * Cost: per occluder vertex, one projection and its pixel-centre span; per triangle, integer
 * min / max of those spans (most triangles of a detailed mesh cover no pixel centre) and its
 * facing, decided for batches of 32 triangles at once without a branch per triangle
 * (src/OcclusionFront.h), then for the rest a test against the depth every tile of its span
 * already has (a second level, one bound per 4 x 4 tiles, answers most of them): a triangle
 * hidden there is dropped before its set-up.
 * The others get per row of tiles their four scanlines' intervals of covered centres, and a
 * coverage mask of 32 pixels per tile between those intervals' ends (byte compares with SSE2).
 * Per occludee box, 8 corner projections and one comparison per tile. Memory: 12 bytes per tile
 * and 4 per 4 x 4 tiles (0.38 bytes per pixel): 183,800 bytes at 800x600, 882 kB at 1920x1200.
 *
 * Two rasterizers (member `rasterizer`; both obey the contract above, the tests run both):
 * - Exact (the default): per row of tiles, the interval of pixel centres inside the triangle on
 *   each of the row's four scanlines, exact: a centre is inside an edge when the edge function in
 *   double (canonical end-point order, as above) passes the margin or tie test, and along a
 *   scanline that evaluated function is monotone (each IEEE operation is), so each edge's inside
 *   centres are a half-line of columns. Its end comes from the edge's crossing of the scanline,
 *   taken as is where the crossing is farther from a pixel column than a bound on the rounding
 *   of both the crossing and the edge function (1e-9 of the coordinates, millions of times the
 *   true bound), else found by evaluating the edge function at the columns around it (rare:
 *   crossings within that bound of a centre, nearly horizontal edges). With SSE2 most edges'
 *   crossings are taken in 32.32 fixed point (four scanlines by two 64-bit adds), the bound
 *   widened by the fixed point's truncation. So every centre claimed
 *   is one the edge function in double puts inside by the margin on outline edges, and on an
 *   interior edge the two triangles, which evaluate the same canonical function with opposite
 *   signs, give every centre to exactly one of them (the tie rule). A tile's 32-bit mask is a
 *   few byte compares of its four intervals (SSE2; elsewhere a loop with the same bits), and
 *   only the tiles between the intervals' ends are visited (src/OcclusionScanline.h).
 * - Float (opt-in; SSE2, the x86-64 baseline, elsewhere the exact one draws): per row of
 *   tiles, each edge's crossings of the row's four scanlines, x = px + (y - py) dx / dy, in one
 *   float register, turned into each scanline's first and last covered pixel; a tile's 32-bit
 *   mask is then a few byte compares of those bounds against the tile's columns. Triangles
 *   with a window coordinate beyond 2^14 pixels, an edge flatter than 1 / 65536 (but not
 *   horizontal) or an edge collapsed in float go to the exact rasterizer. Why it is
 *   conservative:
 *   - Outline edges: the float crossing differs from the crossing of the double edge by at most
 *     a bound computed per edge (the vertices' rounding to float, 2^-24 of the coordinates,
 *     carried along the edge's extension to the scanlines tested, plus the rounding of the
 *     crossing's few operations), taken four times over; the crossing is moved inward by the
 *     coverage margin plus that bound, and a pixel counts only if its centre is strictly on the
 *     inner side. So every pixel claimed is inside the double triangle by the margin.
 *   - Horizontal edges decide whole scanlines, in double from the float coordinates, with the
 *     same margin and bound.
 *   - Interior edges (shared, same facing): both triangles round the shared vertices to the
 *     same floats and compute the crossing from the canonical end point with the same
 *     operations, so the crossing is the same bit for bit and the tie rule gives every pixel
 *     centre to exactly one of them (watertight, as in the exact rasterizer); the float error
 *     only moves which of the two (both drawn by OpenGL) owns a centre within the bound of the
 *     edge. The depth there is the neighbour's, which differs from this triangle's plane by at
 *     most the distance times the gradient: that product is added to the tile's depth bound.
 *     A triangle drawn by the exact rasterizer next to one drawn in float may leave a centre on
 *     their shared edge to neither (a crack: less occlusion, never a false one).
 *   - Depth: the tile's bound is the exact rasterizer's (double plane at the tile's corner
 *     centres, rounding bound, farthest vertex, polygon offset), rounded up to float, plus the
 *     interior-edge term above: never nearer than what OpenGL writes at a claimed pixel.
 *
 * Units: the caller gives the clip-from-world matrix (glm, OpenGL clip conventions as in
 * Frustum.h) and the viewport size in pixels; triangles are given in clip space (x, y, z, w),
 * so a caller transforms each mesh's points once with clipFromWorld * worldFromModel.
 */

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace scenevis
{
namespace occlusion
{

/// Which faces of an occluder OpenGL draws (front = counter-clockwise in window coordinates).
enum class FaceCulling
{
  None,  ///< both sides are drawn: both occlude
  Back,  ///< back faces culled: only front faces occlude
  Front, ///< front faces culled: only back faces occlude
  Both   ///< nothing is drawn: nothing occludes
};

/// No neighbour across this edge (see buildTriangleNeighbors()).
constexpr std::uint32_t kNoNeighbor = 0xFFFFFFFFu;

/**
 * Edge neighbours of a triangle list for MaskedDepthBuffer::drawTriangles: out[3 t + k] is the
 * triangle sharing edge k (vertex k to vertex k + 1) of triangle t, or kNoNeighbor. Vertices are
 * welded by exact coordinates (meshes that duplicate points at creases still count as one
 * surface). An edge counts as shared only when exactly two triangles use it, in opposite
 * directions (consistently oriented); anything else (boundary, non-manifold, flipped) has no
 * neighbour, which is always conservative. A triangle with two points in one place (real CAD
 * meshes have many; OpenGL draws nothing of it) is left out: it has no neighbours and is no
 * neighbour, so that the edge it lies on still joins the two triangles on either side.
 * @p xyz: 3 coordinates per point.
 */
std::vector<std::uint32_t> buildTriangleNeighbors(
  const double* xyz, std::size_t pointCount, const std::uint32_t* indices, std::size_t triangleCount);

/**
 * Whether the triangles form closed, consistently oriented surfaces: every triangle with three
 * distinct points has a neighbour across each edge in @p neighbors (buildTriangleNeighbors() of
 * the same triangles). Then every back face lies behind a front face of the same surface from
 * any eye outside it, and an occluder drawn with its back faces culled hides as much. False for
 * no triangles or an index out of range.
 */
bool closedSurface(const double* xyz, std::size_t pointCount, const std::uint32_t* indices,
  std::size_t triangleCount, const std::vector<std::uint32_t>& neighbors);

/**
 * Bounds of consecutive runs of an occluder's triangles, for MaskedDepthBuffer::drawTriangles:
 * run r holds triangles [r * trianglesPerCluster, (r + 1) * trianglesPerCluster) and lies in the
 * model-space box boxes[6 r .. 6 r + 5] (x0 x1 y0 y1 z0 z1, as VTK's bounds); @p clipFromModel
 * maps model points to the clip space of the triangles' vertices. A run whose box is behind the
 * whole-tile depth of every tile it touches is skipped before its vertices are projected: each
 * of its triangles would have been rejected by the same test (exact: the buffer is the same).
 */
struct TriangleClusters
{
  glm::dmat4 clipFromModel{ 1.0 };
  const double* boxes = nullptr;
  std::size_t trianglesPerCluster = 0;
};

/**
 * An occluder's points in model space, for the drawTriangles() overload that maps them to clip
 * space itself: only the points of triangles that are looked at (not those of runs skipped by
 * TriangleClusters) are transformed, each once, when a triangle first uses it. Exactly one of
 * @p xyzFloat and @p xyzDouble (3 coordinates per point). A point's clip coordinates are
 * m[0][r] x + m[1][r] y + m[2][r] z + m[3][r] for row r of @p clipFromModel, summed left to right
 * in double: the same bits as glm's clipFromModel * (x, y, z, 1), so both overloads give the same
 * buffer.
 */
struct ModelVertices
{
  glm::dmat4 clipFromModel{ 1.0 };
  const float* xyzFloat = nullptr;
  const double* xyzDouble = nullptr;

  /// Point @p i in clip space, as drawTriangles() transforms it (left to right, as glm's
  /// matrix-vector product).
  glm::dvec4 clip(std::size_t i) const
  {
    const glm::dmat4& m = clipFromModel;
    double x, y, z;
    if (xyzFloat)
    {
      const float* p = xyzFloat + 3 * i;
      x = p[0], y = p[1], z = p[2];
    }
    else
    {
      const double* p = xyzDouble + 3 * i;
      x = p[0], y = p[1], z = p[2];
    }
    return glm::dvec4(m[0][0] * x + m[1][0] * y + m[2][0] * z + m[3][0],
      m[0][1] * x + m[1][1] * y + m[2][1] * z + m[3][1],
      m[0][2] * x + m[1][2] * y + m[2][2] * z + m[3][2],
      m[0][3] * x + m[1][3] * y + m[2][3] * z + m[3][3]);
  }
};

/// Model-space boxes of runs of @p trianglesPerCluster triangles (6 doubles per run, see
/// TriangleClusters). @p xyz: 3 coordinates per point; indices out of range are ignored.
std::vector<double> buildTriangleClusters(const double* xyz, std::size_t pointCount,
  const std::uint32_t* indices, std::size_t triangleCount, std::size_t trianglesPerCluster);

/// Counters since the last clear().
struct BufferStats
{
  std::size_t trianglesIn = 0;        ///< triangles handed to drawTriangles()
  std::size_t trianglesDrawn = 0;     ///< ... that touched at least one tile
  std::size_t trianglesRejected = 0;  ///< degenerate, back-facing, off-screen, non-finite, behind
  std::size_t clustersTested = 0;     ///< TriangleClusters runs tested before their triangles
  std::size_t clustersHidden = 0;     ///< ... skipped whole (their triangles count as rejected)
  std::size_t tilesUpdated = 0;       ///< tile updates with a non-empty coverage mask
  std::size_t boxesTested = 0;
  std::size_t boxesOccluded = 0;
};

/// Pixel centres [x0, x1] x [y0, y1] (integers) that a triangle may cover (MaskedDepthBuffer's
/// front end, src/OcclusionFront.h).
struct CentreSpan
{
  int x0, x1, y0, y1;
};

/// Which way a triangle faces as MaskedDepthBuffer's neighbour test sees it (the sign of its
/// doubled window area; None: degenerate or not finite), or not known yet (front end,
/// src/OcclusionFront.h). One byte, not a character type (see MaskedDepthBuffer::VertexState).
enum class TriangleFacing : std::int8_t
{
  Back = -1,
  None = 0,
  Front = 1,
  Unknown = 2
};

class OcclusionRecorder;

class MaskedDepthBuffer
{
public:
  static constexpr int kTileWidth = 8;
  static constexpr int kTileHeight = 4;

  struct Tile
  {
    float z0;           ///< every pixel has an occluder at least this near (+inf: none known)
    float z1;           ///< pixels of mask have an occluder at least this near
    std::uint32_t mask; ///< working layer coverage, bit (y * 8 + x) for pixel (x, y) of the tile
  };

  /// Which arithmetic rasterizes triangles (see "Two rasterizers" in the file comment).
  enum class Rasterizer
  {
    Exact, ///< double edge functions, exact intervals of pixel centres per scanline
    Float  ///< float scanline crossings, a row of tiles at a time (SSE2; elsewhere Exact)
  };
  /// Exact by default: Float runs about 11 % fewer instructions in drawTriangles, but its wider
  /// outline margins occlude less. Measured through vtkOcclusionCuller (BENCHMARKS.md, "Float or
  /// exact by default"): engine row 38 parts kept for 18 visible (Exact: 36); 12 real levels,
  /// 137 cameras, median over-draw 2.02 (Exact: 1.99); no cull-time gain above the noise.
  Rasterizer rasterizer = Rasterizer::Exact;

  /// Pixels inward from every triangle edge that a covered pixel centre must keep.
  double coverageMargin = 1.0 / 64.0;
  /// Window-depth margin added to occluder depths and taken from occludee depths.
  double depthMargin = 1e-6;
  /**
   * OpenGL polygon offset of the occluders drawn next (glPolygonOffset(factor, units) pushes
   * their depth back by factor * max(|dz/dx|, |dz/dy|) + units * r): the same push is added to
   * their depth bounds. Set before drawTriangles() for occluders drawn with an offset.
   */
  double polygonOffsetFactor = 0.0;
  double polygonOffsetDepth = 0.0; ///< units * r, in window depth

  /// When set, every setClipFromWorld() (a cull) and drawTriangles() call is written to it
  /// before it takes effect (scenevis/OcclusionRecording.h); null (default): nothing is. A
  /// copy of the buffer writes to the same recorder.
  OcclusionRecorder* recorder = nullptr;

  /// Size in pixels (the viewport's). Clears. Sizes below 1 give an empty buffer that occludes
  /// nothing.
  void resize(int width, int height);
  int width() const { return width_; }
  int height() const { return height_; }
  int tilesX() const { return tilesX_; }
  int tilesY() const { return tilesY_; }

  /// Forget every occluder (z0 = +inf everywhere) and reset the statistics.
  void clear();

  /// The camera of this frame (glm convention: clip = clipFromWorld * (p, 1)); used by the box
  /// tests. Occluder triangles are given in clip space directly.
  void setClipFromWorld(const glm::dmat4& clipFromWorld);
  const glm::dmat4& clipFromWorld() const { return clipFromWorld_; }

  /**
   * Rasterize triangles as occluders. @p clip: vertices in clip space; @p indices: 3 per
   * triangle, each < @p vertexCount (others are rejected). Triangles with non-finite vertices,
   * zero area, culled faces or nothing in front of the near plane are rejected (counted).
   * @p neighbors: optional, from buildTriangleNeighbors() for these indices; it makes shared edges
   * watertight (see the file comment). @p clusters: optional bounds of runs of the triangles
   * (see TriangleClusters): hidden runs are skipped whole, with the same result.
   */
  void drawTriangles(const glm::dvec4* clip,
    std::size_t vertexCount,
    const std::uint32_t* indices,
    std::size_t triangleCount,
    FaceCulling culling = FaceCulling::None,
    const std::uint32_t* neighbors = nullptr,
    const TriangleClusters* clusters = nullptr);
  /// drawTriangles() of model-space points transformed lazily (see ModelVertices): the same
  /// buffer as transforming every point first, without the cost of the skipped runs' points.
  void drawTriangles(const ModelVertices& model, std::size_t vertexCount,
    const std::uint32_t* indices, std::size_t triangleCount,
    FaceCulling culling = FaceCulling::None, const std::uint32_t* neighbors = nullptr,
    const TriangleClusters* clusters = nullptr);

  /// Whether the world-space box [lo, hi] is hidden behind the occluders drawn so far (see the
  /// file comment). Only the part of the box inside the frustum (sides and near plane) is
  /// tested. Empty or non-finite boxes, and boxes outside the frustum, are not occluded.
  bool boxOccluded(const glm::dvec3& lo, const glm::dvec3& hi);

  /**
   * Whether everything in the window-space rectangle [x0, x1] x [y0, y1] (pixels, continuous
   * coordinates) at window depth >= @p nearestDepth is hidden. Every pixel whose centre may lie
   * in the rectangle is checked (one pixel more on each side against rounding).
   */
  bool rectOccluded(double x0, double y0, double x1, double y1, double nearestDepth) const;

  /// The depth every pixel of the tile holding pixel (x, y) is known to be covered at (+inf if
  /// none): for tests and debugging images.
  float tileDepth(int x, int y) const;
  const std::vector<Tile>& tiles() const { return tiles_; }

  const BufferStats& stats() const { return stats_; }
  /// Changes whenever a test's answer may change (a tile written, the buffer cleared, resized or
  /// given another camera): two tests of the same box at the same revision answer alike, so a
  /// caller may keep the first answer instead of asking again.
  std::uint64_t revision() const { return revision_; }
  std::size_t memoryBytes() const
  {
    return tiles_.capacity() * sizeof(Tile) + blockZ0_.capacity() * sizeof(float);
  }

private:
  /// The centres of the viewport that a triangle with vertices' spans @p a, @p b, @p c may
  /// cover (empty: x0 > x1 or y0 > y1).
  CentreSpan triangleSpan(const CentreSpan& a, const CentreSpan& b, const CentreSpan& c) const;
  /// Both drawTriangles(): @p model null, @p clip holds every vertex; otherwise @p clip is
  /// ignored and vertices are transformed into clip_ when first used.
  void drawTrianglesFrom(const glm::dvec4* clip, const ModelVertices* model,
    std::size_t vertexCount, const std::uint32_t* indices, std::size_t triangleCount,
    FaceCulling culling, const std::uint32_t* neighbors, const TriangleClusters* clusters);
  void drawClippedTriangle(const glm::dvec4* v, FaceCulling culling, unsigned outlineEdges);
  void drawWindowTriangle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
    FaceCulling culling, unsigned outlineEdges);
  /// A triangle OpenGL draws (doubled signed area @p area2) whose centres lie in @p span.
  void drawFrontTriangle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
    double area2, const CentreSpan& span, unsigned outlineEdges);
  /// drawFrontTriangle() by the float rasterizer; false (nothing done) for a triangle it leaves
  /// to the exact one (coordinates beyond its range, nearly horizontal edges, no SSE2).
  bool drawFrontTriangleFloat(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
    double area2, const CentreSpan& span, unsigned outlineEdges);
  void updateTile(Tile& tile, std::uint32_t mask, float depth, std::uint32_t outside);
  /// Whether a triangle whose centres lie in @p span is behind the whole-tile depth of every
  /// tile it touches (it would add nothing: most triangles of the parts behind the nearest
  /// ones), found before its set-up.
  bool hidden(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
    const CentreSpan& span);
  /// Whether model-space box @p box (x0 x1 y0 y1 z0 z1) mapped by @p clipFromModel is behind
  /// the whole-tile depth of every tile it may touch (false if it reaches the near plane).
  bool boxBehindTiles(const glm::dmat4& clipFromModel, const double* box);
  /// Whether every tile of [tx0, tx1] x [ty0, ty1] has z0 <= @p depth (nothing nearer to add).
  bool behindTiles(int tx0, int ty0, int tx1, int ty1, double depth);
  /// After tile (tx, ty)'s z0 went down from @p oldZ0: its block's bound follows.
  void lowerBlock(int tx, int ty, float oldZ0);
  /// The largest z0 of block (bx, by)'s tiles.
  float largestZ0(int bx, int by) const;

  /// Blocks of kBlockTiles x kBlockTiles tiles, each with a bound on its tiles' z0: the second
  /// level of the hierarchy, so that a triangle hidden behind the buffer is found so in a
  /// read or two.
  static constexpr int kBlockTiles = 4;

  int width_ = 0, height_ = 0, tilesX_ = 0, tilesY_ = 0;
  std::vector<Tile> tiles_;
  int blocksX_ = 0;
  /// Per block: a bound on its tiles' z0 (none is farther), or NaN: not known, found again when
  /// the block is next read.
  std::vector<float> blockZ0_;
  /// Per tile column / row: bits of pixels beyond the viewport (they count as covered).
  std::vector<std::uint32_t> outsideX_, outsideY_;
  // drawTriangles scratch: window coordinates, centre spans and state per vertex.
  std::vector<glm::dvec4> clip_; // ModelVertices transformed (valid where vertexState_ != 3)
  std::vector<glm::dvec3> window_;
  std::vector<CentreSpan> centres_;
  /// A vertex's state in drawTriangles (see drawTrianglesFrom): one byte, but not a character
  /// type, so that storing it does not make the compiler assume that any member (the scratch
  /// vectors' pointers, the viewport) may have changed and load them again.
  enum VertexState : std::uint8_t
  {
    kVertexNotFinite = 0,
    kVertexFront = 1,  ///< in front of the near plane: window coordinates valid
    kVertexBehind = 2, ///< finite, behind the near plane: its triangles are clipped
    kVertexUnseen = 3  ///< not projected yet
  };
  std::vector<VertexState> vertexState_;
  /// Per triangle of the current drawTriangles() call with neighbours: its facing where the
  /// front end has found it (TriangleFacing::Unknown elsewhere).
  std::vector<TriangleFacing> facing_;
  glm::dmat4 clipFromWorld_{ 1.0 };
  /// World-space corners of the near plane's rectangle (a box holding one reaches the eye's
  /// near plane on screen: never occluded); valid only if nearCornersValid_.
  glm::dvec3 nearCorners_[4];
  bool nearCornersValid_ = false;
  BufferStats stats_;
  std::uint64_t revision_ = 0;
};

} // namespace occlusion
} // namespace scenevis
