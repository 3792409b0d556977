#include "scenevis/OcclusionRecording.h"

#include <cmath>
#include <cstring>
#include <istream>
#include <ostream>

namespace scenevis
{
namespace occlusion
{

namespace
{
constexpr char kMagic[8] = { 'S', 'V', 'O', 'R', 'E', 'C', '0', '1' };
constexpr std::int32_t kCullTag = 1;
constexpr std::int32_t kDrawTag = 2;
constexpr std::uint64_t kMaxCount = std::uint64_t(1) << 28;
constexpr std::int32_t kMaxSize = 16384;
constexpr double kMaxOffsetFactor = 1e4;

template <typename T>
void put(std::ostream& out, const T& value)
{
  out.write(reinterpret_cast<const char*>(&value), sizeof value);
}

template <typename T>
void putArray(std::ostream& out, const T* values, std::size_t count)
{
  if (count > 0)
  {
    out.write(
      reinterpret_cast<const char*>(values), static_cast<std::streamsize>(sizeof(T) * count));
  }
}

void putCull(std::ostream& out, int width, int height, const glm::dmat4& clipFromWorld)
{
  put(out, kCullTag);
  put(out, static_cast<std::int32_t>(width));
  put(out, static_cast<std::int32_t>(height));
  put(out, clipFromWorld);
}

/// A draw record. @p clip: @p vertexCount vertices; @p neighbors: 3 per triangle when
/// @p hasNeighbors; @p clusters: null or with 6 box values per run.
void putDraw(std::ostream& out, const double margins[4], std::size_t vertexCount,
  const glm::dvec4* clip, const std::uint32_t* indices, std::size_t triangleCount,
  FaceCulling culling, bool hasNeighbors, const std::uint32_t* neighbors,
  const TriangleClusters* clusters)
{
  put(out, kDrawTag);
  putArray(out, margins, 4);
  put(out, static_cast<std::uint64_t>(vertexCount));
  put(out, static_cast<std::uint64_t>(triangleCount));
  put(out, static_cast<std::int32_t>(culling));
  put(out, static_cast<std::int32_t>(hasNeighbors ? 1 : 0));
  put(out, static_cast<std::int32_t>(clusters ? 1 : 0));
  putArray(out, clip, vertexCount);
  putArray(out, indices, 3 * triangleCount);
  if (hasNeighbors)
  {
    putArray(out, neighbors, 3 * triangleCount);
  }
  if (clusters)
  {
    put(out, clusters->clipFromModel);
    put(out, static_cast<std::uint64_t>(clusters->trianglesPerCluster));
    const std::size_t runs =
      (triangleCount + clusters->trianglesPerCluster - 1) / clusters->trianglesPerCluster;
    putArray(out, clusters->boxes, 6 * runs);
  }
}

/// The run boxes of a recorded draw as drawTriangles() takes them (used when d.hasClusters).
TriangleClusters clustersOf(const RecordedDraw& d)
{
  TriangleClusters clusters;
  clusters.clipFromModel = d.clipFromModel;
  clusters.boxes = d.boxes.data();
  clusters.trianglesPerCluster = static_cast<std::size_t>(d.trianglesPerCluster);
  return clusters;
}

/// Reads from a stream whose remaining size is known, so that no count read from it can make
/// us allocate more than the stream holds.
class Source
{
public:
  Source(std::istream& in, std::string& error)
    : in_(in)
    , error_(error)
  {
    const std::istream::pos_type start = in.tellg();
    in.seekg(0, std::ios::end);
    const std::istream::pos_type end = in.tellg();
    in.seekg(start);
    seekable_ = start != std::istream::pos_type(-1) && end != std::istream::pos_type(-1) && in;
    left_ = seekable_ ? static_cast<std::uint64_t>(end - start) : 0;
  }

  bool seekable() const { return seekable_; }
  std::uint64_t left() const { return left_; }
  std::uint64_t offset() const { return offset_; }

  /// The record read next starts here: errors name its first byte.
  void beginRecord() { record_ = offset_; }

  bool fail(const std::string& what)
  {
    error_ = "byte " + std::to_string(record_) + ": " + what;
    return false;
  }

  /// @p n bytes into @p p, or false (error set) if the stream ends first.
  bool bytes(void* p, std::uint64_t n, const char* what)
  {
    if (n > left_)
    {
      return fail(std::string(what) + " cut short (" + std::to_string(n) + " bytes needed, " +
        std::to_string(left_) + " left)");
    }
    if (n > 0 && !in_.read(static_cast<char*>(p), static_cast<std::streamsize>(n)))
    {
      return fail(std::string("cannot read ") + what);
    }
    left_ -= n;
    offset_ += n;
    return true;
  }

  template <typename T>
  bool get(T& value, const char* what)
  {
    return bytes(&value, sizeof value, what);
  }

  /// @p count elements into @p values (resized only once the stream is known to hold them).
  template <typename T>
  bool array(std::vector<T>& values, std::uint64_t count, const char* what)
  {
    if (count > left_ / sizeof(T))
    {
      return fail(std::string(what) + ": " + std::to_string(count) + " elements, " +
        std::to_string(left_) + " bytes left");
    }
    values.resize(static_cast<std::size_t>(count));
    return bytes(values.data(), sizeof(T) * count, what);
  }

private:
  std::istream& in_;
  std::string& error_;
  bool seekable_ = false;
  std::uint64_t left_ = 0, offset_ = 0, record_ = 0;
};

bool readCull(Source& src, RecordedCull& cull)
{
  std::int32_t width = 0, height = 0;
  if (!src.get(width, "cull width") || !src.get(height, "cull height") ||
    !src.get(cull.clipFromWorld, "cull camera"))
  {
    return false;
  }
  if (width < 0 || height < 0 || width > kMaxSize || height > kMaxSize)
  {
    return src.fail("cull size " + std::to_string(width) + " x " + std::to_string(height) +
      " outside 0.." + std::to_string(kMaxSize));
  }
  cull.width = width;
  cull.height = height;
  return true;
}

bool readDraw(Source& src, RecordedDraw& d)
{
  double margins[4];
  std::uint64_t vertexCount = 0, triangleCount = 0;
  std::int32_t culling = 0, hasNeighbors = 0, hasClusters = 0;
  if (!src.bytes(margins, sizeof margins, "draw margins") ||
    !src.get(vertexCount, "draw vertex count") || !src.get(triangleCount, "draw triangle count") ||
    !src.get(culling, "draw face culling") || !src.get(hasNeighbors, "draw flags") ||
    !src.get(hasClusters, "draw flags"))
  {
    return false;
  }
  for (double m : margins)
  {
    if (!std::isfinite(m))
    {
      return src.fail("draw margin or offset not finite");
    }
  }
  // What a culler may set: margins of at most a pixel and the whole depth range, an offset
  // within glPolygonOffset's practical range.
  if (margins[0] < 0.0 || margins[0] > 1.0 || margins[1] < 0.0 || margins[1] > 1.0)
  {
    return src.fail("draw margin outside 0..1");
  }
  if (std::abs(margins[2]) > kMaxOffsetFactor || std::abs(margins[3]) > 1.0)
  {
    return src.fail(
      "polygon offset beyond +-" + std::to_string(kMaxOffsetFactor) + " (factor) or +-1 (depth)");
  }
  if (vertexCount > kMaxCount || triangleCount > kMaxCount)
  {
    return src.fail("draw of " + std::to_string(vertexCount) + " vertices and " +
      std::to_string(triangleCount) + " triangles: more than 2^28");
  }
  if (culling < 0 || culling > static_cast<std::int32_t>(FaceCulling::Both))
  {
    return src.fail("face culling " + std::to_string(culling) + " is not 0..3");
  }
  if ((hasNeighbors != 0 && hasNeighbors != 1) || (hasClusters != 0 && hasClusters != 1))
  {
    return src.fail("draw flag other than 0 or 1");
  }
  d.coverageMargin = margins[0];
  d.depthMargin = margins[1];
  d.polygonOffsetFactor = margins[2];
  d.polygonOffsetDepth = margins[3];
  d.culling = static_cast<FaceCulling>(culling);
  d.hasNeighbors = hasNeighbors == 1;
  d.hasClusters = hasClusters == 1;
  if (!src.array(d.clip, vertexCount, "draw vertices") ||
    !src.array(d.indices, 3 * triangleCount, "draw indices"))
  {
    return false;
  }
  d.neighbors.clear();
  if (d.hasNeighbors && !src.array(d.neighbors, 3 * triangleCount, "draw neighbours"))
  {
    return false;
  }
  d.boxes.clear();
  if (!d.hasClusters)
  {
    return true;
  }
  if (!src.get(d.clipFromModel, "run boxes' matrix") ||
    !src.get(d.trianglesPerCluster, "triangles per run"))
  {
    return false;
  }
  if (d.trianglesPerCluster == 0 || d.trianglesPerCluster > kMaxCount)
  {
    return src.fail("runs of " + std::to_string(d.trianglesPerCluster) + " triangles");
  }
  const std::uint64_t runs = (triangleCount + d.trianglesPerCluster - 1) / d.trianglesPerCluster;
  return src.array(d.boxes, 6 * runs, "run boxes");
}
} // namespace

OcclusionRecorder::OcclusionRecorder(std::ostream& out)
  : out_(out)
{
  out_.write(kMagic, sizeof kMagic);
}

void OcclusionRecorder::beginCull(int width, int height, const glm::dmat4& clipFromWorld)
{
  putCull(out_, width, height, clipFromWorld);
  ++culls_;
}

void OcclusionRecorder::draw(const MaskedDepthBuffer& buffer, const glm::dvec4* clip,
  const ModelVertices* model, std::size_t vertexCount, const std::uint32_t* indices,
  std::size_t triangleCount, FaceCulling culling, const std::uint32_t* neighbors,
  const TriangleClusters* clusters)
{
  if (culls_ == 0)
  {
    beginCull(0, 0, glm::dmat4(1.0));
  }
  if (model)
  {
    // A model without points draws nothing: recorded without vertices, its triangles are
    // rejected alike (every index out of range).
    const bool points = model->xyzFloat || model->xyzDouble;
    vertexCount = points ? vertexCount : 0;
    clip_.resize(vertexCount);
    for (std::size_t i = 0; i < vertexCount; ++i)
    {
      clip_[i] = model->clip(i);
    }
    clip = clip_.data();
  }
  const TriangleClusters* runs =
    clusters && clusters->boxes && clusters->trianglesPerCluster > 0 ? clusters : nullptr;
  const double margins[4] = { buffer.coverageMargin, buffer.depthMargin, buffer.polygonOffsetFactor,
    buffer.polygonOffsetDepth };
  putDraw(out_, margins, vertexCount, clip, indices, triangleCount, culling, neighbors != nullptr,
    neighbors, runs);
  ++draws_;
}

bool OcclusionRecorder::good() const
{
  return out_.good();
}

void writeOcclusionRecording(std::ostream& out, const std::vector<RecordedCull>& culls)
{
  out.write(kMagic, sizeof kMagic);
  for (const RecordedCull& cull : culls)
  {
    putCull(out, cull.width, cull.height, cull.clipFromWorld);
    for (const RecordedDraw& d : cull.draws)
    {
      const double margins[4] = { d.coverageMargin, d.depthMargin, d.polygonOffsetFactor,
        d.polygonOffsetDepth };
      const TriangleClusters clusters = clustersOf(d);
      putDraw(out, margins, d.clip.size(), d.clip.data(), d.indices.data(), d.indices.size() / 3,
        d.culling, d.hasNeighbors, d.neighbors.data(), d.hasClusters ? &clusters : nullptr);
    }
  }
}

bool readOcclusionRecording(std::istream& in, std::vector<RecordedCull>& culls, std::string& error)
{
  culls.clear();
  error.clear();
  Source src(in, error);
  if (!src.seekable())
  {
    return src.fail("the stream's size cannot be known (not a file or a string)");
  }
  char magic[sizeof kMagic];
  if (!src.bytes(magic, sizeof magic, "header") || std::memcmp(magic, kMagic, sizeof kMagic) != 0)
  {
    return error.empty() ? src.fail("not an occlusion recording (no SVOREC01 header)") : false;
  }
  while (src.left() > 0)
  {
    src.beginRecord();
    std::int32_t tag = 0;
    if (!src.get(tag, "record tag"))
    {
      return false;
    }
    if (tag == kCullTag)
    {
      culls.emplace_back();
      if (!readCull(src, culls.back()))
      {
        culls.pop_back();
        return false;
      }
    }
    else if (tag == kDrawTag)
    {
      if (culls.empty())
      {
        return src.fail("a draw before the first cull");
      }
      RecordedDraw d;
      if (!readDraw(src, d))
      {
        return false;
      }
      culls.back().draws.push_back(std::move(d));
    }
    else
    {
      return src.fail("unknown record tag " + std::to_string(tag));
    }
  }
  return true;
}

void prepareReplay(MaskedDepthBuffer& buffer, const RecordedCull& cull)
{
  buffer.resize(cull.width, cull.height);
  buffer.setClipFromWorld(cull.clipFromWorld);
}

void replayDraws(MaskedDepthBuffer& buffer, const RecordedCull& cull)
{
  buffer.clear();
  for (const RecordedDraw& d : cull.draws)
  {
    buffer.coverageMargin = d.coverageMargin;
    buffer.depthMargin = d.depthMargin;
    buffer.polygonOffsetFactor = d.polygonOffsetFactor;
    buffer.polygonOffsetDepth = d.polygonOffsetDepth;
    const TriangleClusters clusters = clustersOf(d);
    buffer.drawTriangles(d.clip.data(), d.clip.size(), d.indices.data(), d.indices.size() / 3,
      d.culling, d.hasNeighbors ? d.neighbors.data() : nullptr,
      d.hasClusters ? &clusters : nullptr);
  }
}

} // namespace occlusion
} // namespace scenevis
