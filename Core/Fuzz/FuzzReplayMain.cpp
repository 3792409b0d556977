// A main() for FuzzBsp without libFuzzer (any compiler): runs LLVMFuzzerTestOneInput on every file
// given, or on every file of every directory given. CTest runs it on corpus/ and crashes/, so the
// seed corpus and every reproducer stay regression tests in the ordinary and the sanitizer builds.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace
{
int runFile(const std::filesystem::path& path)
{
  std::ifstream file(path, std::ios::binary);
  if (!file)
  {
    std::fprintf(stderr, "cannot read %s\n", path.string().c_str());
    return 1;
  }
  const std::vector<char> bytes(
    (std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  std::fprintf(stderr, "replay %s (%zu bytes)\n", path.string().c_str(), bytes.size());
  LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  return 0;
}
} // namespace

int main(int argc, char** argv)
{
  int failures = 0;
  std::size_t files = 0;
  for (int i = 1; i < argc; ++i)
  {
    const std::filesystem::path arg(argv[i]);
    if (std::filesystem::is_directory(arg))
    {
      std::vector<std::filesystem::path> entries;
      for (const auto& entry : std::filesystem::directory_iterator(arg))
      {
        if (entry.is_regular_file() && entry.path().filename().string()[0] != '.' &&
          entry.path().filename() != "README.md")
        {
          entries.push_back(entry.path());
        }
      }
      std::sort(entries.begin(), entries.end());
      for (const auto& path : entries)
      {
        failures += runFile(path);
        ++files;
      }
    }
    else
    {
      failures += runFile(arg);
      ++files;
    }
  }
  std::printf("replayed %zu inputs, %d unreadable\n", files, failures);
  return failures == 0 ? 0 : 1;
}
