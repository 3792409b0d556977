#include "scenevis/BspBuilder.h"
#include "scenevis/BspTraversal.h"
#include "scenevis/OrderOracle.h"
#include "scenevis/Scenes.h"
#include "../../Testing/PolygonSoups.h"
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <string>
using namespace scenevis;
PolygonMesh loadStl(const std::string& path)
{
  PolygonMesh mesh; std::ifstream in(path, std::ios::binary); char header[80]; std::uint32_t count = 0;
  in.read(header, 80); in.read(reinterpret_cast<char*>(&count), 4);
  std::map<std::array<float, 3>, std::uint32_t> ids;
  for (std::uint32_t t = 0; t < count; ++t) {
    char record[50]; in.read(record, 50); std::uint32_t tri[3];
    for (int k = 0; k < 3; ++k) { std::array<float, 3> p; std::memcpy(p.data(), record + 12 + 12 * k, 12);
      auto it = ids.find(p); if (it == ids.end()) it = ids.emplace(p, mesh.addPoint({ p[0], p[1], p[2] })).first; tri[k] = it->second; }
    mesh.addPolygon(tri, 3);
  }
  return mesh;
}
void rotate(PolygonMesh& mesh)
{
  const glm::dvec3 k = glm::normalize(glm::dvec3(1.0, 2.0, 3.0)); const double c = std::cos(0.7), s = std::sin(0.7);
  for (glm::dvec3& p : mesh.points) p = p * c + glm::cross(k, p) * s + k * glm::dot(k, p) * (1.0 - c);
}
int main(int argc, char** argv)
{
  std::string scene = argv[1];
  bool thorough = argc > 2 && std::string(argv[2]) == "T";
  int check = argc > 3 ? std::atoi(argv[3]) : 0;
  PolygonMesh mesh;
  if (scene == "bunny") mesh = loadStl("/root/.cache/scenevis-data/npm/node_modules/stl-models/objects/bunny.bin.stl");
  else if (scene == "engine") mesh = loadStl("/tmp/engine.stl");
  else if (scene.rfind("sphere", 0) == 0) mesh = testsupport::uvSphere(std::stoul(scene.substr(6)));
  else if (scene.rfind("rot", 0) == 0) { mesh = testsupport::uvSphere(std::stoul(scene.substr(3))); rotate(mesh); }
  else if (scene.rfind("grid", 0) == 0) mesh = scenes::sphereGrid(4, 0.8, 1.0, scenes::trianglesPerSphereFor(std::stoul(scene.substr(4)))).mesh;
  bsp::BuildConfig config; if (thorough) config.effort = bsp::BuildConfig::Effort::Thorough;
  if (const char* e = std::getenv("X_CAND")) config.candidates = std::atoi(e);
  if (const char* e = std::getenv("X_SAMPLE")) config.samplePolygons = std::atoi(e);
  if (const char* e = std::getenv("X_SPLITW")) config.splitWeight = std::atof(e);
  if (std::getenv("X_SB")) config.score = bsp::BuildConfig::Score::SplitsAndBalance;
  if (const char* e = std::getenv("X_SEED")) config.seed = std::atoi(e);
  bsp::Tree tree = bsp::build(mesh, config);
  const auto& st = tree.statistics;
  std::vector<std::uint32_t> order;
  auto t0 = std::chrono::steady_clock::now();
  int reps = 20;
  for (int r = 0; r < reps; ++r) bsp::order(tree, View::perspective({3.0*std::cos(r), 3.0*std::sin(r), 0.5}), bsp::Direction::BackToFront, order);
  double orderMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count() / reps;
  std::printf("%-12s %s in=%zu frag=%zu ratio=%.3f nodes=%zu depth=%zu build=%.3fs order=%.2fms\n", scene.c_str(), thorough ? "T" : "D",
    mesh.polygonCount(), st.fragments, double(st.fragments) / st.inputPolygons, st.nodes, st.depth, st.buildSeconds, orderMs);
  if (check > 0) {
    auto polys = oracle::fragmentPolygons(tree);
    glm::dvec3 c = mesh.bounds().center(); double r = mesh.bounds().diagonal();
    oracle::OracleConfig oc; oc.samplesPerOverlap = 1;
    for (int i = 0; i < check; ++i) {
      glm::dvec3 eye = c + r * glm::dvec3(std::cos(i * 2.1), std::sin(i * 1.3), std::cos(i * 0.7) * 0.8) * (i % 3 == 0 ? 0.3 : 1.5);
      View v = View::perspective(eye);
      bsp::order(tree, v, bsp::Direction::BackToFront, order);
      auto rep = oracle::checkOrder(polys, order, v, oc);
      std::printf("  eye %d: violations=%zu constrained=%zu\n", i, rep.violations.size(), rep.constrainedPairs);
    }
  }
}
