// Recordings of occluder rasterization: what a MaskedDepthBuffer was asked to draw, cull by
// cull, written as it happens and replayed later into another buffer, so the rasterizer can be
// timed, profiled and compared between builds on exactly the input a real cull gave it, away
// from VTK, OpenGL and the machine's load (scenevis_occlusion_replay).
//
// Recording: set MaskedDepthBuffer::recorder. Every setClipFromWorld() starts a cull (the
// buffer's size and camera) and every drawTriangles() adds a draw: the buffer's margins and
// polygon offset at the call, the triangles with their vertices in clip space (the model-point
// overload's vertices transformed as it transforms them: the same bits), face culling, edge
// neighbours and run boxes. Replaying a cull's draws into a buffer of its size and camera gives
// the recorded buffer bit for bit: its tiles and its drawing statistics (box tests are not
// recorded).
//
// The file format (machine byte order; a recording is for the machine that made it): the 8
// bytes "SVOREC01", then records, each led by an int32 tag:
//   tag 1, a cull: int32 width, int32 height, glm::dmat4 clipFromWorld (16 doubles, glm's
//     column-major order);
//   tag 2, one drawTriangles() call of the current cull: double coverageMargin, depthMargin,
//     polygonOffsetFactor, polygonOffsetDepth; uint64 vertexCount, triangleCount; int32
//     culling (FaceCulling), hasNeighbors, hasClusters; vertexCount glm::dvec4 clip vertices;
//     3 triangleCount uint32 indices; if hasNeighbors 3 triangleCount uint32 neighbours; if
//     hasClusters a glm::dmat4 clipFromModel, uint64 trianglesPerCluster and 6 doubles per run.
#ifndef scenevis_OcclusionRecording_h
#define scenevis_OcclusionRecording_h

#include "scenevis/OcclusionBuffer.h"

#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

namespace scenevis
{
namespace occlusion
{

/// One drawTriangles() call as recorded.
struct RecordedDraw
{
  double coverageMargin = 1.0 / 64.0;
  double depthMargin = 1e-6;
  double polygonOffsetFactor = 0.0;
  double polygonOffsetDepth = 0.0;
  FaceCulling culling = FaceCulling::None;
  std::vector<glm::dvec4> clip;       ///< every vertex in clip space
  std::vector<std::uint32_t> indices; ///< 3 per triangle
  bool hasNeighbors = false;
  std::vector<std::uint32_t> neighbors; ///< 3 per triangle when hasNeighbors
  bool hasClusters = false;
  glm::dmat4 clipFromModel{ 1.0 };       ///< of the run boxes (TriangleClusters)
  std::uint64_t trianglesPerCluster = 0; ///< > 0 when hasClusters
  std::vector<double> boxes;             ///< 6 per run when hasClusters
};

/// One cull: the buffer's size and camera (setClipFromWorld()), then its draws in order.
struct RecordedCull
{
  int width = 0, height = 0;
  glm::dmat4 clipFromWorld{ 1.0 };
  std::vector<RecordedDraw> draws;
};

/**
 * Writes what a MaskedDepthBuffer draws to a binary stream (see the file comment), for as long
 * as it is the buffer's recorder. The stream must outlive the recorder; a draw before the first
 * cull starts a cull of size 0 x 0. good() is false once a write has failed.
 */
class OcclusionRecorder
{
public:
  explicit OcclusionRecorder(std::ostream& out);

  /// Called by MaskedDepthBuffer::setClipFromWorld().
  void beginCull(int width, int height, const glm::dmat4& clipFromWorld);
  /// Called by both MaskedDepthBuffer::drawTriangles(), before drawing: @p buffer gives the
  /// margins and the offset; exactly one of @p clip and @p model holds the vertices.
  void draw(const MaskedDepthBuffer& buffer, const glm::dvec4* clip, const ModelVertices* model,
    std::size_t vertexCount, const std::uint32_t* indices, std::size_t triangleCount,
    FaceCulling culling, const std::uint32_t* neighbors, const TriangleClusters* clusters);

  bool good() const;
  std::size_t culls() const { return culls_; }
  std::size_t draws() const { return draws_; }

private:
  std::ostream& out_;
  std::vector<glm::dvec4> clip_; // scratch: model vertices in clip space
  std::size_t culls_ = 0, draws_ = 0;
};

/// Writes @p culls as a recording would hold them (the same bytes, the header included).
void writeOcclusionRecording(std::ostream& out, const std::vector<RecordedCull>& culls);

/**
 * Reads a recording. False with @p error naming the first byte of the record at fault (0: the
 * header) and what is wrong (not a
 * recording, a record cut short, an unknown tag, counts beyond what is left of the stream or
 * 2^28, a size outside 0..16384, a face culling outside the enum, a flag other than 0 or 1,
 * margins or an offset not finite, margins outside 0..1, a polygon offset factor beyond 1e4 or
 * depth beyond 1, runs of 0 triangles); @p culls then
 * holds the culls read before it. Never allocates more than the stream can fill.
 */
bool readOcclusionRecording(std::istream& in, std::vector<RecordedCull>& culls, std::string& error);

/// Sizes @p buffer and gives it the cull's camera (what the recorded buffer had when the cull
/// began); then replayDraws() may run any number of times.
void prepareReplay(MaskedDepthBuffer& buffer, const RecordedCull& cull);
/// Clears @p buffer and draws the cull's draws with their settings: the recorded buffer after
/// the cull, bit for bit (given prepareReplay() and the same rasterizer).
void replayDraws(MaskedDepthBuffer& buffer, const RecordedCull& cull);

} // namespace occlusion
} // namespace scenevis

#endif
