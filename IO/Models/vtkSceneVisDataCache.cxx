// The fetched-data cache; see vtkSceneVisDataCache.h.
#include "vtkSceneVisDataCache.h"

#include <cstdlib>
#include <fstream>

namespace scenevis
{

std::string DataDirectory()
{
  if (const char* dir = std::getenv("SCENEVIS_DATA_DIR"))
  {
    return dir;
  }
  const char* home = std::getenv("HOME");
  return std::string(home ? home : ".") + "/.cache/scenevis-data";
}

std::string DataFile(const std::string& key)
{
  const std::string dir = DataDirectory();
  std::ifstream manifest(dir + "/manifest.txt");
  std::string line;
  while (std::getline(manifest, line))
  {
    if (line.rfind(key + "=", 0) == 0)
    {
      const std::string path = dir + "/" + line.substr(key.size() + 1);
      return std::ifstream(path).good() ? path : std::string();
    }
  }
  return std::string();
}

} // namespace scenevis
