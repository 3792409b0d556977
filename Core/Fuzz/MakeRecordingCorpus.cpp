// Writes the seed corpus of FuzzOcclusionRecording into <dir> (CTest runs it before replaying the
// seeds as Fuzz.RecordingCorpus; nothing is committed): small recordings made by recording a
// buffer, as vtkOcclusionCuller does. Usage: scenevis_fuzz_make_recording_corpus <dir>
#include "scenevis/OcclusionBuffer.h"
#include "scenevis/OcclusionRecording.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

namespace
{
using namespace scenevis::occlusion;

/// A quad of two triangles at depth @p z (model space), drawn as the seed's flags say: 1 from
/// model points (else clip vertices), 2 with edge neighbours, 4 with run boxes, 8 a NaN point.
void drawQuad(MaskedDepthBuffer& buffer, const glm::dmat4& clipFromModel, double z, unsigned flags)
{
  std::vector<double> xyz = { -1, -1, z, 1, -1, z, 1, 1, z, -1, 1, z };
  if (flags & 8)
  {
    xyz[0] = std::numeric_limits<double>::quiet_NaN();
  }
  const std::vector<std::uint32_t> indices = { 0, 1, 2, 0, 2, 3 };
  const std::vector<std::uint32_t> neighbors =
    buildTriangleNeighbors(xyz.data(), 4, indices.data(), 2);
  const std::vector<double> boxes = buildTriangleClusters(xyz.data(), 4, indices.data(), 2, 1);
  TriangleClusters clusters;
  clusters.clipFromModel = clipFromModel;
  clusters.boxes = boxes.data();
  clusters.trianglesPerCluster = 1;
  const std::uint32_t* nb = flags & 2 ? neighbors.data() : nullptr;
  const TriangleClusters* runs = flags & 4 ? &clusters : nullptr;
  if (flags & 1)
  {
    ModelVertices model;
    model.clipFromModel = clipFromModel;
    model.xyzDouble = xyz.data();
    buffer.drawTriangles(model, 4, indices.data(), 2, FaceCulling::Back, nb, runs);
  }
  else
  {
    std::vector<glm::dvec4> clip;
    for (int i = 0; i < 4; ++i)
    {
      clip.push_back(clipFromModel * glm::dvec4(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2], 1.0));
    }
    buffer.drawTriangles(clip.data(), 4, indices.data(), 2, FaceCulling::None, nb, runs);
  }
}
} // namespace

int main(int argc, char** argv)
{
  if (argc != 2)
  {
    std::fprintf(stderr, "usage: %s <dir>\n", argv[0]);
    return 2;
  }
  const glm::dmat4 clipFromWorld = glm::perspective(glm::radians(60.0), 4.0 / 3.0, 0.1, 50.0) *
    glm::lookAt(glm::dvec3(0, 0, 4), glm::dvec3(0.0), glm::dvec3(0, 1, 0));
  for (unsigned flags = 0; flags < 16; ++flags)
  {
    const std::string path = std::string(argv[1]) + "/seed-" + std::to_string(flags) + ".rec";
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    OcclusionRecorder recorder(out);
    MaskedDepthBuffer buffer;
    buffer.recorder = &recorder;
    buffer.resize(16 + static_cast<int>(flags), 12);
    buffer.setClipFromWorld(clipFromWorld);
    drawQuad(buffer, clipFromWorld, 0.0, flags);
    buffer.polygonOffsetFactor = flags & 1 ? 1.0 : 0.0;
    drawQuad(buffer, clipFromWorld, -1.0, flags ^ 6);
    if (flags & 4)
    {
      buffer.setClipFromWorld(clipFromWorld); // a second cull
      drawQuad(buffer, clipFromWorld, 0.5, flags);
    }
    if (!out.flush())
    {
      std::fprintf(stderr, "cannot write %s\n", path.c_str());
      return 1;
    }
  }
  return 0;
}
