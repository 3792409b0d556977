#include "scenevis/BspBuilder.h"
#include <array>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <vector>
using namespace scenevis;
int main()
{
  std::ifstream in("/tmp/engine.stl", std::ios::binary); char header[80]; std::uint32_t count = 0;
  in.read(header, 80); in.read(reinterpret_cast<char*>(&count), 4);
  std::vector<std::array<float, 9>> tris(count);
  for (auto& t : tris) { char r[50]; in.read(r, 50); std::memcpy(t.data(), r + 12, 36); }
  std::ifstream pf("/tmp/engine.stl.parts"); std::vector<std::size_t> b; std::size_t x; while (pf >> x) b.push_back(x);
  std::size_t input = 0, frags = 0; double secs = 0;
  for (std::size_t p = 0; p + 1 < b.size(); ++p) {
    PolygonMesh mesh; std::map<std::array<float, 3>, std::uint32_t> ids;
    for (std::size_t t = b[p]; t < b[p + 1]; ++t) { std::uint32_t tri[3];
      for (int k = 0; k < 3; ++k) { std::array<float, 3> q{ tris[t][3*k], tris[t][3*k+1], tris[t][3*k+2] };
        auto it = ids.find(q); if (it == ids.end()) it = ids.emplace(q, mesh.addPoint({ q[0], q[1], q[2] })).first; tri[k] = it->second; }
      mesh.addPolygon(tri, 3); }
    auto tree = bsp::build(mesh);
    input += tree.statistics.inputPolygons; frags += tree.statistics.fragments; secs += tree.statistics.buildSeconds;
  }
  std::printf("engine per part: input %zu fragments %zu ratio %.3f build %.2fs\n", input, frags, double(frags) / input, secs);
}
