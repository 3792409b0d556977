#pragma once
// The portal scene format read without VTK, for the core benchmarks: a model .vtp with an integer
// room cell array and a portals .vtp with RoomA/RoomB (see `scenevis --help`). Only what the
// repository's converters write (scripts/wad-to-portals.py, scripts/q3bsp-to-vtp.py): VTK XML
// PolyData with every array "appended" in raw binary, little-endian, header_type UInt32 or
// UInt64. Any other .vtp (ascii, base64, compressed) is refused with a message: read it with
// `scenevis cull` instead, which uses VTK's reader.
#include "scenevis/PortalGraph.h"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace scenevis
{
namespace bench
{

struct RawPolyData
{
  std::vector<glm::dvec3> points;
  std::vector<std::int64_t> connectivity, offsets;
  std::map<std::string, std::vector<std::int64_t>> cellInts; ///< integer cell arrays by name
};

inline std::string attribute(const std::string& tag, const std::string& name)
{
  const std::string key = " " + name + "=\"";
  const auto at = tag.find(key);
  if (at == std::string::npos)
  {
    return "";
  }
  const auto start = at + key.size();
  return tag.substr(start, tag.find('"', start) - start);
}

inline RawPolyData readRawVtp(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    throw std::runtime_error(path + ": cannot open");
  }
  std::ostringstream buffer;
  buffer << in.rdbuf();
  const std::string data = buffer.str();
  const std::string marker = "<AppendedData encoding=\"raw\">";
  const auto appended = data.find(marker);
  if (appended == std::string::npos || data.find("<PolyData>") == std::string::npos)
  {
    throw std::runtime_error(path + ": not a .vtp with raw appended data (read it with scenevis)");
  }
  const auto payload = data.find('_', appended + marker.size()) + 1;
  const std::string head = data.substr(0, appended);
  const bool header64 = head.find("header_type=\"UInt64\"") != std::string::npos;
  if (head.find("byte_order=\"BigEndian\"") != std::string::npos ||
    head.find("compressor=") != std::string::npos)
  {
    throw std::runtime_error(path + ": big-endian or compressed .vtp (read it with scenevis)");
  }
  RawPolyData out;
  std::string section;
  for (std::size_t pos = head.find('<'); pos != std::string::npos; pos = head.find('<', pos + 1))
  {
    const std::string tag = head.substr(pos, head.find('>', pos) - pos + 1);
    for (const char* s : { "CellData", "PointData", "Points", "Polys", "Verts", "Lines", "Strips" })
    {
      const std::string open = std::string("<") + s;
      if (tag.compare(0, open.size(), open) == 0 &&
        (tag.size() == open.size() + 1 || tag[open.size()] == ' ' || tag[open.size()] == '>'))
      {
        section = s;
      }
    }
    if (tag.compare(0, 10, "<DataArray") != 0)
    {
      continue;
    }
    if (attribute(tag, "format") != "appended")
    {
      throw std::runtime_error(path + ": array not in raw appended format (read it with scenevis)");
    }
    const std::string type = attribute(tag, "type"), name = attribute(tag, "Name");
    const std::size_t offset = payload + std::stoull(attribute(tag, "offset"));
    std::uint64_t bytes = 0;
    if (offset + 8 > data.size())
    {
      throw std::runtime_error(path + ": array " + name + " outside the file");
    }
    if (header64)
    {
      std::memcpy(&bytes, data.data() + offset, 8);
    }
    else
    {
      std::uint32_t b32 = 0;
      std::memcpy(&b32, data.data() + offset, 4);
      bytes = b32;
    }
    const char* raw = data.data() + offset + (header64 ? 8 : 4);
    if (raw + bytes > data.data() + data.size())
    {
      throw std::runtime_error(path + ": array " + name + " outside the file");
    }
    std::vector<double> values;
    auto take = [&](auto zero)
    {
      using T = decltype(zero);
      values.resize(bytes / sizeof(T));
      for (std::size_t i = 0; i < values.size(); ++i)
      {
        T v;
        std::memcpy(&v, raw + i * sizeof(T), sizeof(T));
        values[i] = static_cast<double>(v);
      }
    };
    if (type == "Float32")
      take(float());
    else if (type == "Float64")
      take(double());
    else if (type == "Int32")
      take(std::int32_t());
    else if (type == "Int64")
      take(std::int64_t());
    else if (type == "UInt8")
      continue; // colours
    else
      throw std::runtime_error(path + ": array type " + type + " not read here");
    if (section == "Points")
    {
      for (std::size_t i = 0; i + 2 < values.size(); i += 3)
      {
        out.points.emplace_back(values[i], values[i + 1], values[i + 2]);
      }
    }
    else if (section == "Polys" && (name == "connectivity" || name == "offsets"))
    {
      auto& target = name == "connectivity" ? out.connectivity : out.offsets;
      target.assign(values.begin(), values.end());
    }
    else if (section == "CellData" && type.find("Int") == 0)
    {
      out.cellInts[name].assign(values.begin(), values.end());
    }
  }
  return out;
}

/// The model and its portals as the graph's input (@p mesh receives the polygons).
inline portals::CellSceneInput readPortalScene(const std::string& modelPath,
  const std::string& portalsPath, const std::string& roomArray, PolygonMesh& mesh)
{
  const RawPolyData model = readRawVtp(modelPath);
  const RawPolyData doors = readRawVtp(portalsPath);
  const auto rooms = model.cellInts.find(roomArray);
  if (rooms == model.cellInts.end() || rooms->second.size() != model.offsets.size())
  {
    throw std::runtime_error(modelPath + ": no cell array " + roomArray + " (one per polygon)");
  }
  const auto a = doors.cellInts.find("RoomA"), b = doors.cellInts.find("RoomB");
  if (a == doors.cellInts.end() || b == doors.cellInts.end() ||
    a->second.size() != doors.offsets.size() || b->second.size() != doors.offsets.size())
  {
    throw std::runtime_error(portalsPath + ": no cell arrays RoomA and RoomB (one per polygon)");
  }
  portals::CellSceneInput input;
  mesh = PolygonMesh();
  for (const glm::dvec3& p : model.points)
  {
    mesh.addPoint(p);
  }
  std::int64_t start = 0;
  std::vector<std::uint32_t> ids;
  for (std::size_t c = 0; c < model.offsets.size(); ++c)
  {
    ids.clear();
    for (std::int64_t k = start; k < model.offsets[c]; ++k)
    {
      const std::int64_t id = model.connectivity.at(static_cast<std::size_t>(k));
      if (id < 0 || static_cast<std::size_t>(id) >= model.points.size())
      {
        throw std::runtime_error(modelPath + ": cell " + std::to_string(c) + " uses point " +
          std::to_string(id) + " of only " + std::to_string(model.points.size()));
      }
      ids.push_back(static_cast<std::uint32_t>(id));
    }
    start = model.offsets[c];
    mesh.addPolygon(ids.data(), ids.size());
    input.roomOfPolygon.push_back(static_cast<std::int32_t>(rooms->second[c]));
  }
  start = 0;
  for (std::size_t c = 0; c < doors.offsets.size(); ++c)
  {
    portals::PortalDesc portal;
    for (std::int64_t k = start; k < doors.offsets[c]; ++k)
    {
      const std::int64_t id = doors.connectivity.at(static_cast<std::size_t>(k));
      if (id < 0 || static_cast<std::size_t>(id) >= doors.points.size())
      {
        throw std::runtime_error(portalsPath + ": cell " + std::to_string(c) + " uses point " +
          std::to_string(id) + " of only " + std::to_string(doors.points.size()));
      }
      portal.polygon.push_back(doors.points[static_cast<std::size_t>(id)]);
    }
    start = doors.offsets[c];
    portal.roomA = static_cast<std::int32_t>(a->second[c]);
    portal.roomB = static_cast<std::int32_t>(b->second[c]);
    input.portals.push_back(std::move(portal));
  }
  input.mesh = &mesh;
  return input;
}

} // namespace bench
} // namespace scenevis
