// Writes the seed corpus of FuzzPortalGeneration into <dir> (CTest runs it before replaying the
// seeds as Fuzz.PortalCorpus; nothing is committed). Usage: scenevis_fuzz_make_portal_corpus <dir>
// Byte layout (see FuzzPortalGeneration.cpp): flags (1 offset 1e7, 2 degenerate/NaN polygons,
// 4 free triangles, 8 a door or window to the outside, 16 again with stopAtFirstLeak, 32 one
// polygon dropped, 64 and 128 the exterior wall of flag 8's opening), rooms along x and y (1 + b %
// 3 each), their sizes, the height, then per wall between neighbours a byte (b % 3 == 0: closed)
// and the opening's width, place, door or window (even: door, without a bottom byte), bottom and
// top; flag 8's opening the same way after them.
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

int main(int argc, char** argv)
{
  if (argc != 2)
  {
    std::fprintf(stderr, "usage: %s <dir>\n", argv[0]);
    return 2;
  }
  using Bytes = std::vector<std::uint8_t>;
  const std::vector<std::pair<std::string, Bytes>> seeds = {
    { "one-closed-room", {} },
    { "two-rooms-a-door", { 0, 1, 0, 2, 2, 2, 1, 1, 128, 128, 0, 0, 200 } },
    { "two-rooms-a-window", { 0, 1, 0, 2, 2, 2, 1, 1, 100, 50, 1, 100, 100 } },
    { "two-rooms-a-wide-door", { 0, 1, 0, 7, 7, 7, 3, 1, 255, 0, 0, 0, 255 } },
    { "two-rooms-a-narrow-slit", { 0, 1, 0, 0, 0, 0, 0, 1, 0, 255, 1, 255, 0 } },
    { "row-of-three", { 0, 2, 0, 1, 2, 3, 4, 1, 1, 90, 30, 0, 0, 180, 2, 200, 120, 0, 0, 90 } },
    { "three-by-three",
      { 0, 2, 2, 0, 1, 2, 3, 4, 5, 1, 1, 10, 20, 0, 0, 200, 2, 200, 100, 1, 50, 50, 1, 30, 40, 0,
        60, 90, 0, 0, 250, 1, 128, 128, 0, 0, 128, 0, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1,
        1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1 } },
    { "window-to-the-outside", { 8, 1, 0, 2, 2, 2, 1, 1, 128, 128, 0, 200, 128, 128, 1, 60, 128 } },
    // Doors from the floor to the outside (issue 14), one per exterior wall: x = 0, far x, y = 0,
    // far y; the last with stopAtFirstLeak and far from the origin.
    { "door-to-the-outside", { 8, 1, 0, 2, 2, 2, 1, 1, 128, 128, 0, 200, 128, 100, 0, 200 } },
    { "door-to-the-outside-far-x-wall",
      { 72, 1, 1, 7, 2, 2, 3, 1, 1, 128, 128, 0, 200, 1, 90, 30, 0, 180, 0, 0, 128, 100, 0, 200 } },
    { "door-to-the-outside-y-wall",
      { 136, 2, 0, 2, 4, 1, 1, 1, 1, 200, 50, 0, 150, 1, 50, 50, 0, 150, 255, 0, 0, 255 } },
    { "door-to-the-outside-far-y-wall-stop-at-first-leak",
      { 217, 0, 2, 2, 1, 4, 7, 2, 1, 128, 128, 0, 200, 1, 60, 60, 0, 250, 40, 200, 0, 100 } },
    { "far-from-the-origin",
      { 1, 1, 1, 2, 2, 2, 2, 1, 1, 128, 128, 0, 0, 200, 2, 30, 30, 0, 0, 100 } },
    { "degenerate-and-nan-polygons",
      { 2, 1, 0, 2, 2, 2, 1, 1, 128, 128, 0, 0, 200, 3, 10, 20, 30, 0, 40, 50, 60, 1, 70, 80, 90, 2,
        100, 110, 120, 3 } },
    { "stop-at-first-leak-three-by-three",
      { 16, 2, 2, 0, 1, 2, 3, 4, 5, 1, 1, 10, 20, 0, 0, 200, 2, 200, 100, 1, 50, 50, 1, 30, 40 } },
    { "stop-at-first-leak-free-triangles",
      { 20, 1, 0, 2, 2, 2, 1, 1, 128, 128, 0, 0, 200, 7, 0, 0, 0, 0, 0, 255, 0, 0, 0, 0, 255, 0, 0,
        0, 255, 0, 0, 255, 255, 0 } },
    { "stop-at-first-leak-window",
      { 24, 1, 0, 2, 2, 2, 1, 1, 128, 128, 0, 200, 128, 128, 1, 60, 128 } },
    { "stop-at-first-leak-missing-ceiling", { 48, 2, 0, 1, 2, 3, 4, 1, 1, 90, 30, 0, 0, 180, 7 } },
    { "free-triangles",
      { 4, 1, 0, 2, 2, 2, 1, 1, 128, 128, 0, 0, 200, 7, 0, 10, 20, 30, 1, 40, 50, 60, 2, 70, 80, 90,
        0, 128, 128, 128, 0, 200, 10, 100, 0, 10, 200, 100 } },
  };
  for (const auto& [name, bytes] : seeds)
  {
    const std::string path = std::string(argv[1]) + "/" + name;
    std::ofstream out(path, std::ios::binary);
    out.write(
      reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    if (!out)
    {
      std::fprintf(stderr, "cannot write %s\n", path.c_str());
      return 1;
    }
  }
  std::printf("wrote %zu corpus files to %s\n", seeds.size(), argv[1]);
  return 0;
}
