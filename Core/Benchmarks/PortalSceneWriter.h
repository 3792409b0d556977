#pragma once
// The portal scene format written without VTK, for the core benchmarks and tools: VTK XML PolyData
// with every array appended in raw binary (little-endian, UInt64 headers), which both VTK's reader
// and PortalSceneFile.h read. Points are Float64, connectivity and offsets Int64, cell arrays
// Int32.
#include "scenevis/PolygonMesh.h"
#include "scenevis/PortalGraph.h"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace scenevis
{
namespace bench
{

/// Polygons (CSR: polygon i is connectivity[offsets[i-1] .. offsets[i])) and Int32 cell arrays.
inline void writeRawVtp(const std::string& path, const std::vector<glm::dvec3>& points,
  const std::vector<std::int64_t>& connectivity, const std::vector<std::int64_t>& offsets,
  const std::map<std::string, std::vector<std::int32_t>>& cellInts)
{
  std::string xml = "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" "
                    "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n<PolyData>\n";
  xml += "<Piece NumberOfPoints=\"" + std::to_string(points.size()) +
    "\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"" +
    std::to_string(offsets.size()) + "\">\n";
  std::string blob;
  auto append = [&](const void* data, std::uint64_t bytes)
  {
    const std::size_t offset = blob.size();
    blob.append(reinterpret_cast<const char*>(&bytes), 8);
    blob.append(reinterpret_cast<const char*>(data), bytes);
    return std::to_string(offset);
  };
  xml += "<CellData>\n";
  for (const auto& [name, values] : cellInts)
  {
    if (values.size() != offsets.size())
    {
      throw std::runtime_error(path + ": cell array " + name + " has the wrong size");
    }
    xml += "<DataArray type=\"Int32\" Name=\"" + name +
      "\" NumberOfComponents=\"1\" format=\"appended\" offset=\"" +
      append(values.data(), values.size() * sizeof(std::int32_t)) + "\"/>\n";
  }
  xml += "</CellData>\n<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" "
         "format=\"appended\" offset=\"" +
    append(points.data(), points.size() * sizeof(glm::dvec3)) + "\"/>\n</Points>\n<Polys>\n";
  xml += "<DataArray type=\"Int64\" Name=\"connectivity\" NumberOfComponents=\"1\" "
         "format=\"appended\" offset=\"" +
    append(connectivity.data(), connectivity.size() * sizeof(std::int64_t)) + "\"/>\n";
  xml += "<DataArray type=\"Int64\" Name=\"offsets\" NumberOfComponents=\"1\" "
         "format=\"appended\" offset=\"" +
    append(offsets.data(), offsets.size() * sizeof(std::int64_t)) + "\"/>\n";
  xml += "</Polys>\n</Piece>\n</PolyData>\n<AppendedData encoding=\"raw\">\n_";
  std::ofstream out(path, std::ios::binary);
  out << xml << blob << "\n</AppendedData>\n</VTKFile>\n";
  if (!out)
  {
    throw std::runtime_error(path + ": cannot write");
  }
}

/// The model with a room id per polygon (array @p roomArray), and its portals with RoomA/RoomB.
inline void writePortalScene(const std::string& modelPath, const std::string& portalsPath,
  const std::string& roomArray, const PolygonMesh& mesh, const portals::CellSceneInput& scene)
{
  std::vector<std::int64_t> connectivity(mesh.indices.begin(), mesh.indices.end());
  std::vector<std::int64_t> offsets(mesh.offsets.begin() + 1, mesh.offsets.end());
  writeRawVtp(
    modelPath, mesh.points, connectivity, offsets, { { roomArray, scene.roomOfPolygon } });
  std::vector<glm::dvec3> points;
  connectivity.clear();
  offsets.clear();
  std::vector<std::int32_t> a, b;
  for (const portals::PortalDesc& p : scene.portals)
  {
    for (const glm::dvec3& q : p.polygon)
    {
      connectivity.push_back(static_cast<std::int64_t>(points.size()));
      points.push_back(q);
    }
    offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
    a.push_back(p.roomA);
    b.push_back(p.roomB);
  }
  writeRawVtp(portalsPath, points, connectivity, offsets, { { "RoomA", a }, { "RoomB", b } });
}

} // namespace bench
} // namespace scenevis
