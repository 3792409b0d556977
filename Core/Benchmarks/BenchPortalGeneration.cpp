// Rooms and portals generated from a model (PortalGeneration.h), written in the portal scene
// format and compared with authored ones when given. A thin driver: it reads, calls the core,
// prints figures, writes.
//
//   scenevis_portal_gen_bench --scene MODEL.vtp [--out PREFIX] [--room-array RoomId]
//                             [--authored-portals PORTALS.vtp] [--depth D]
//                             [--tolerance R] [--enclosure E] [--passage T]   (GenerationConfig)
//   scenevis_portal_gen_bench --building FLOORS,X,Y,SEED [--out PREFIX] [--cameras-out FILE]
//
// --out writes PREFIX.vtp (the model with the generated RoomId) and PREFIX-portals.vtp (RoomA,
// RoomB), which scenevis_pvs_bench and `scenevis cull` read; with --building also the hand-made
// rooms and portals as PREFIX-authored.vtp and PREFIX-authored-portals.vtp, to compare;
// --cameras-out writes 4 cameras per room of the building (eye 1.6 m above the floor at 30 % /
// 70 % of the room, 90 degrees, looking along +-x and +-y) for `scenevis --cameras`. With the
// model's own room array and its authored portals, it reports how authored rooms map onto generated
// ones (by polygon area) and whether each authored portal between two different generated rooms
// lies inside a generated portal joining them (moved at most D along the generated portal's
// normal). It studies the rooms found, so a model that leaks keeps them (keepRoomsWithLeaks: not
// conservative, which `scenevis portals` says and withholds them for).
#include "PortalSceneFile.h"
#include "PortalSceneWriter.h"
#include "scenevis/PortalGeneration.h"
#include "scenevis/PortalGeometry.h"
#include "scenevis/Scenes.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <map>
#include <string>
#include <vector>

using namespace scenevis;
using namespace scenevis::portals;

namespace
{

bool inside(const PortalDesc& portal, const std::vector<glm::dvec3>& polygon, double depth)
{
  const glm::dvec3 n = glm::normalize(geometry::newellOf(portal.polygon));
  const std::vector<glm::dvec3> hull = planarConvexHull(portal.polygon, n);
  const double tol = 1e-6 * (1.0 + glm::length(hull[0]));
  for (const glm::dvec3& p : polygon)
  {
    const double h = glm::dot(n, p - hull[0]);
    if (std::abs(h) > depth + tol || !geometry::insideConvex(hull, n, p - h * n, tol))
    {
      return false;
    }
  }
  return true;
}

void compare(const PolygonMesh& mesh, const std::vector<std::int64_t>& authoredRoom,
  const std::vector<PortalDesc>& authoredPortals, const GeneratedPortals& g, double depth)
{
  std::map<std::int64_t, std::map<std::int32_t, double>> areas;
  for (std::size_t i = 0; i < authoredRoom.size(); ++i)
  {
    const glm::dvec3 n = newellNormal(mesh.points.data(), mesh.polygon(i), mesh.polygonSize(i));
    areas[authoredRoom[i]][g.roomOfPolygon[i]] += 0.5 * glm::length(n);
  }
  std::map<std::int64_t, std::int32_t> roomOf;
  std::map<std::int32_t, std::size_t> authoredPer;
  std::size_t toOutside = 0;
  for (const auto& [authored, generated] : areas)
  {
    double best = -1.0;
    for (const auto& [room, area] : generated)
    {
      if (room >= 0 && area > best)
      {
        best = area;
        roomOf[authored] = room;
      }
    }
    if (authored >= 0 && best < 0.0)
    {
      roomOf[authored] = kOutsideRoom;
      ++toOutside;
    }
    if (authored >= 0)
    {
      ++authoredPer[roomOf[authored]];
    }
  }
  std::size_t separating = 0, covered = 0, coveredByUnion = 0;
  for (const PortalDesc& a : authoredPortals)
  {
    const auto ia = roomOf.find(a.roomA), ib = roomOf.find(a.roomB);
    const std::int32_t ra = a.roomA < 0 || ia == roomOf.end() ? kOutsideRoom : ia->second;
    const std::int32_t rb = a.roomB < 0 || ib == roomOf.end() ? kOutsideRoom : ib->second;
    if (ra == rb)
    {
      continue;
    }
    ++separating;
    std::vector<const PortalDesc*> joining;
    for (const PortalDesc& p : g.portals)
    {
      if ((p.roomA == ra && p.roomB == rb) || (p.roomA == rb && p.roomB == ra))
      {
        joining.push_back(&p);
      }
    }
    bool one = false;
    for (const PortalDesc* p : joining)
    {
      one = one || inside(*p, a.polygon, depth);
    }
    covered += one;
    // Several generated portals may share the opening: each of its sample points (corners,
    // edge middles, points halfway to the centre, the centre) must be in one of them.
    glm::dvec3 centre(0.0);
    for (const glm::dvec3& q : a.polygon)
    {
      centre += q / static_cast<double>(a.polygon.size());
    }
    std::vector<glm::dvec3> samples{ centre };
    for (std::size_t k = 0; k < a.polygon.size(); ++k)
    {
      const glm::dvec3& q = a.polygon[k];
      samples.push_back(q);
      samples.push_back(0.5 * (q + a.polygon[(k + 1) % a.polygon.size()]));
      samples.push_back(0.5 * (q + centre));
    }
    bool all = true;
    for (const glm::dvec3& q : samples)
    {
      bool in = false;
      for (const PortalDesc* p : joining)
      {
        in = in || inside(*p, { q }, depth);
      }
      all = all && in;
    }
    coveredByUnion += all;
    if (!all && separating - coveredByUnion <= 4)
    {
      std::printf("  not covered: authored portal %d-%d (generated rooms %d-%d, %zu joining):",
        a.roomA, a.roomB, ra, rb, joining.size());
      for (const glm::dvec3& q : a.polygon)
      {
        std::printf(" (%.3f %.3f %.3f)", q.x, q.y, q.z);
      }
      std::printf("\n");
    }
  }
  std::size_t largest = 0;
  for (const auto& [room, count] : authoredPer)
  {
    largest = room >= 0 ? std::max(largest, count) : largest;
  }
  std::printf("authored: %zu rooms -> %zu generated rooms (up to %zu authored in one; %zu with "
              "no polygon in a room); %zu portals, %zu between different generated rooms, %zu "
              "of those inside a generated portal joining them (%zu inside their union)\n",
    areas.size() - areas.count(-1), authoredPer.size() - authoredPer.count(kOutsideRoom), largest,
    toOutside, authoredPortals.size(), separating, covered, coveredByUnion);
}

void print(const GeneratedPortals& g)
{
  const GenerationStatistics& s = g.statistics;
  std::printf(
    "generated: status %d%s%s; %zu polygons (%zu blocking, %zu dropped), %zu BSP nodes "
    "+ %zu opening splits, %zu cells (%zu air), %zu faces, %zu open (%zu in openings); "
    "rooms %zu (%zu before %zu passages merged); portals %zu (%zu exterior); leak "
    "cells %zu; polygons facing solid %zu; %.2f s (BSP %.2f s, cells %.2f s, openings %.2f s)\n",
    static_cast<int>(g.status), g.message.empty() ? "" : ": ", g.message.c_str(), s.inputPolygons,
    s.blockingPolygons, s.droppedPolygons, s.bspNodes, s.openingSplits, s.cells, s.airCells,
    s.faces, s.openFaces, s.openingFaces, s.rooms, s.roomsBeforePassages, s.passagesMerged,
    s.portals, s.exteriorPortals, s.leakCells, s.polygonsWithoutRoom, s.totalSeconds, s.bspSeconds,
    s.cellSeconds, s.openingSeconds);
  for (std::size_t k = 0; k < g.leakPoints.size() && k < 8; ++k)
  {
    std::printf(
      "  leak near %.3f %.3f %.3f\n", g.leakPoints[k].x, g.leakPoints[k].y, g.leakPoints[k].z);
  }
}

std::vector<PortalDesc> readPortals(const std::string& path)
{
  const bench::RawPolyData raw = bench::readRawVtp(path);
  std::vector<PortalDesc> out;
  std::int64_t start = 0;
  for (std::size_t c = 0; c < raw.offsets.size(); ++c)
  {
    PortalDesc p;
    for (std::int64_t k = start; k < raw.offsets[c]; ++k)
    {
      p.polygon.push_back(raw.points.at(static_cast<std::size_t>(raw.connectivity.at(k))));
    }
    start = raw.offsets[c];
    p.roomA = static_cast<std::int32_t>(raw.cellInts.at("RoomA").at(c));
    p.roomB = static_cast<std::int32_t>(raw.cellInts.at("RoomB").at(c));
    out.push_back(std::move(p));
  }
  return out;
}

} // namespace

int main(int argc, char** argv)
{
  std::string scene, out, roomArray = "RoomId", authoredPortals, building, camerasOut;
  double depth = 0.0;
  GenerationConfig config;
  config.keepRoomsWithLeaks = true;
  for (int i = 1; i + 1 < argc; i += 2)
  {
    const std::string key = argv[i], value = argv[i + 1];
    if (key == "--scene")
      scene = value;
    else if (key == "--out")
      out = value;
    else if (key == "--room-array")
      roomArray = value;
    else if (key == "--authored-portals")
      authoredPortals = value;
    else if (key == "--depth")
      depth = std::atof(value.c_str());
    else if (key == "--tolerance")
      config.bsp.relativeTolerance = std::atof(value.c_str());
    else if (key == "--passage")
      config.passageThickness = std::atof(value.c_str());
    else if (key == "--enclosure")
      config.openingEnclosure = std::atof(value.c_str());
    else if (key == "--building")
      building = value;
    else if (key == "--cameras-out")
      camerasOut = value;
    else
    {
      std::fprintf(stderr, "unknown option %s (see the file comment)\n", key.c_str());
      return 2;
    }
  }
  try
  {
    PolygonMesh mesh;
    GenerationInput input;
    std::vector<std::int64_t> authoredRoom;
    std::vector<PortalDesc> authored;
    CellSceneInput authoredScene;
    if (!building.empty())
    {
      int f = 2, x = 4, y = 3, seed = 1;
      std::sscanf(building.c_str(), "%d,%d,%d,%d", &f, &x, &y, &seed);
      const scenes::BuildingScene b = scenes::building(f, x, y, static_cast<std::uint64_t>(seed));
      mesh = b.mesh;
      for (std::size_t i = 0; i < b.part.size(); ++i)
      {
        input.seeThrough.push_back(b.parts[b.part[i]].name == "glass");
        authoredRoom.push_back(b.room[i]);
      }
      for (const scenes::Portal& p : b.portals)
      {
        authored.push_back(PortalDesc{ p.polygon, p.roomA, p.roomB });
      }
      depth = depth > 0.0 ? depth : 0.5 * scenes::kSlabThickness;
      authoredScene = cellSceneOf(b);
      if (!camerasOut.empty())
      {
        std::ofstream cams(camerasOut);
        cams << "[";
        const char* sep = "\n";
        const double dirs[4][2] = { { 1, 0.3 }, { -0.2, 1 }, { -1, -0.4 }, { 0.3, -1 } };
        for (const scenes::Room& r : b.rooms)
        {
          for (int k = 0; k < 4; ++k)
          {
            const double at = k % 2 == 0 ? 0.3 : 0.7;
            const glm::dvec3 eye(r.bounds.lo.x + at * (r.bounds.hi.x - r.bounds.lo.x),
              r.bounds.lo.y + at * (r.bounds.hi.y - r.bounds.lo.y), r.bounds.lo.z + 1.6);
            cams << sep << "{\"eye\": [" << eye.x << ", " << eye.y << ", " << eye.z
                 << "], \"focal\": [" << eye.x + dirs[k][0] << ", " << eye.y + dirs[k][1] << ", "
                 << eye.z << "], \"up\": [0, 0, 1], \"view_angle\": 90, "
                 << "\"clipping_range\": [0.05, 200]}";
            sep = ",\n";
          }
        }
        cams << "\n]\n";
      }
    }
    else if (!scene.empty())
    {
      const bench::RawPolyData raw = bench::readRawVtp(scene);
      mesh.points = raw.points;
      std::int64_t start = 0;
      std::vector<std::uint32_t> ids;
      for (const std::int64_t end : raw.offsets)
      {
        ids.clear();
        for (std::int64_t k = start; k < end; ++k)
        {
          ids.push_back(static_cast<std::uint32_t>(raw.connectivity.at(k)));
        }
        start = end;
        mesh.addPolygon(ids.data(), ids.size());
      }
      const auto rooms = raw.cellInts.find(roomArray);
      if (rooms != raw.cellInts.end())
      {
        authoredRoom = rooms->second;
      }
      if (!authoredPortals.empty())
      {
        authored = readPortals(authoredPortals);
      }
    }
    else
    {
      std::fprintf(stderr, "give --scene MODEL.vtp or --building F,X,Y,SEED\n");
      return 2;
    }
    input.mesh = &mesh;
    const GeneratedPortals g = generatePortals(input, config);
    print(g);
    if (g.status == GenerationStatus::Ok)
    {
      PortalGraphReport report;
      PortalGraph::build(g.cellScene(mesh), &report);
      std::printf("portal graph: %zu errors, %zu warnings\n", report.errors(), report.warnings());
      const std::string summary = report.summary();
      std::printf("%s", summary.substr(0, std::min<std::size_t>(summary.size(), 600)).c_str());
    }
    if (authoredRoom.size() == mesh.polygonCount())
    {
      compare(mesh, authoredRoom, authored, g, depth);
    }
    if (!out.empty())
    {
      bench::writePortalScene(
        out + ".vtp", out + "-portals.vtp", roomArray, mesh, g.cellScene(mesh));
      std::printf("wrote %s.vtp and %s-portals.vtp\n", out.c_str(), out.c_str());
      if (!authoredScene.roomOfPolygon.empty())
      {
        bench::writePortalScene(
          out + "-authored.vtp", out + "-authored-portals.vtp", roomArray, mesh, authoredScene);
      }
    }
    return g.status == GenerationStatus::Ok ? 0 : 1;
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
}
