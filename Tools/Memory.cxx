#include "Memory.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>

namespace scenevis
{
namespace tool
{
namespace
{

/// The value in kB of the line "@p key: N kB" of a /proc file, in bytes; 0 if absent.
std::uint64_t ProcKilobytes(const char* file, const std::string& key)
{
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line))
  {
    if (line.compare(0, key.size(), key) == 0 && line.size() > key.size() &&
      line[key.size()] == ':')
    {
      return std::strtoull(line.c_str() + key.size() + 1, nullptr, 10) * 1024;
    }
  }
  return 0;
}

/// The first number in @p file ("max" and unreadable files give 0).
std::uint64_t FileNumber(const char* file)
{
  std::ifstream in(file);
  std::string text;
  if (!(in >> text) || text.empty() || text[0] < '0' || text[0] > '9')
    return 0;
  return std::strtoull(text.c_str(), nullptr, 10);
}

/// "2G", "512M", "1000000": bytes; 0 if not a number.
std::uint64_t ParseBytes(const char* text)
{
  char* end = nullptr;
  const double value = std::strtod(text, &end);
  if (end == text || !(value > 0.0))
    return 0;
  double scale = 1.0;
  switch (*end)
  {
    case 'k':
    case 'K':
      scale = 1e3;
      break;
    case 'm':
    case 'M':
      scale = 1e6;
      break;
    case 'g':
    case 'G':
      scale = 1e9;
      break;
    case 't':
    case 'T':
      scale = 1e12;
      break;
    default:
      break;
  }
  return static_cast<std::uint64_t>(value * scale);
}

} // namespace

ResidentMemory ReadResidentMemory()
{
  ResidentMemory memory;
  memory.current = ProcKilobytes("/proc/self/status", "VmRSS");
  memory.peak = ProcKilobytes("/proc/self/status", "VmHWM");
  return memory;
}

std::uint64_t AvailableMemory()
{
  if (const char* limit = std::getenv("SCENEVIS_MEMORY_LIMIT"))
  {
    if (const std::uint64_t bytes = ParseBytes(limit))
      return bytes;
  }
  std::uint64_t available = ProcKilobytes("/proc/meminfo", "MemAvailable");
  const std::uint64_t cgroupMax = FileNumber("/sys/fs/cgroup/memory.max");
  if (cgroupMax > 0)
  {
    const std::uint64_t used = FileNumber("/sys/fs/cgroup/memory.current");
    const std::uint64_t left = cgroupMax > used ? cgroupMax - used : 0;
    if (available == 0 || left < available)
      available = left;
  }
  return available;
}

VtpHeader ReadVtpHeader(const std::string& path)
{
  VtpHeader header;
  std::ifstream in(path, std::ios::binary);
  if (!in)
    return header;
  // The XML header precedes any appended data; 1 MB holds thousands of pieces' headers.
  std::string text(1 << 20, '\0');
  in.read(&text[0], static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<std::size_t>(in.gcount()));
  const auto appended = text.find("<AppendedData");
  if (appended != std::string::npos)
    text.resize(appended);
  if (!std::regex_search(text, std::regex("<VTKFile[^>]*type=\"PolyData\"")))
    return header;
  const std::regex piece("<Piece\\b([^>]*)>");
  const std::regex points("NumberOfPoints=\"([0-9]+)\"");
  const std::regex polys("NumberOfPolys=\"([0-9]+)\"");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), piece);
       it != std::sregex_iterator(); ++it)
  {
    const std::string attributes = (*it)[1].str();
    std::smatch match;
    if (std::regex_search(attributes, match, points))
      header.points += std::strtoull(match[1].str().c_str(), nullptr, 10);
    if (std::regex_search(attributes, match, polys))
      header.polys += std::strtoull(match[1].str().c_str(), nullptr, 10);
    header.valid = true;
  }
  return header;
}

std::string FormatBytes(std::uint64_t bytes)
{
  const char* units[] = { "B", "kB", "MB", "GB", "TB" };
  double value = static_cast<double>(bytes);
  int unit = 0;
  while (value >= 1000.0 && unit < 4)
  {
    value /= 1000.0;
    ++unit;
  }
  char text[32];
  std::snprintf(
    text, sizeof(text), value < 10.0 && unit > 0 ? "%.1f %s" : "%.0f %s", value, units[unit]);
  return text;
}

} // namespace tool
} // namespace scenevis
