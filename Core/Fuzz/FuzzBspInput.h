#pragma once
/**
 * @file FuzzBspInput.h
 * @brief The byte format FuzzBsp decodes, shared by the fuzzer and the seed-corpus writer.
 *
 * Every byte string is a valid input: reads past the end yield 0, counts are taken modulo small
 * bounds, so libFuzzer's mutations always decode to something. Layout:
 *
 *   config      C: bit0 FirstInList (else Scored), bit1 no free planes, bits2-3 relative
 *                  tolerance {1e-10, 1e-12, 1e-9, 1e-10}, bits4-5 samplePolygons {128, 1, 4, 128},
 *                  bit6 add the 1e7 offset to every point and eye, bit7 flip its sign pattern
 *   candidates  1 + b % 16
 *   seed        b
 *   points      n = b % 33, then n coordinates triples (coord below)
 *   polygons    m = 1 + b % 24, then m polygons: kind = b % 6
 *                 0 triangle        3 point refs
 *                 1 parallelogram   3 point refs a, b, c; adds the point a + c - b (exact on the grid)
 *                 2 general         count = 1 + b % 9, then that many point refs (repeats, non-planar,
 *                                   concave, self-intersecting: anything)
 *                 3 copy            of polygon (b % polygons so far), mode b: bits0-2 shift scale
 *                                   kCopyScales, bit3 reversed winding; 3 grid bytes: shift direction
 *                 4 rectangle       axis b % 3, plane coord, then u0 u1 v0 v1 coords: 4 new points
 *                 5 fan             the previous polygon's last two point ids + 1 point ref
 *               A point ref is b % n, or an out-of-range id when b == 255 or n == 0.
 *   view        V: bit0 parallel, bits1-2 eye mode, bit3 FrontToBack, bits4-6 number of moves
 *                 parallel: direction = 3 coords
 *                 mode 0: eye = 3 coords;  1: on polygon (b)'s plane: p0 + s (p1 - p0) + t (p2 - p0)
 *                 with s, t grid coords;  2: at point (b);  3: far: bounds centre + grid direction
 *                 * 4^(b % 12)
 *   moves       each: type = b % 6 (see FuzzBsp.cpp: small step, new point, onto a tree point,
 *               onto a node plane, parallel, back to the first eye)
 *
 * coord: b < 0xD0 grid (b % 33 - 16) / 8 in [-2, 2]; 0xD0..0xDF near-grid: grid(b2) +
 * (b3 - 128) * 2^-(20 + 2 (b - 0xD0)); 0xE0/E1 +-1e30; 0xE2/E3 +-1e300; 0xE4/E5 +-1e-300;
 * 0xE6 denormal 5e-324; 0xE7 NaN; 0xE8/E9 +-Inf; 0xEA 1e7 + grid(b2); 0xEB 1e15 + grid(b2);
 * 0xEC raw little-endian double (8 bytes); above: grid.
 */

#include <cstdint>
#include <cstring>
#include <vector>

namespace scenevis
{
namespace fuzz
{

enum Coord : std::uint8_t
{
  kGridEnd = 0xD0,
  kNearGrid = 0xD0, // .. 0xDF
  kHugePos = 0xE0,
  kHugeNeg = 0xE1,
  kOverflowPos = 0xE2,
  kOverflowNeg = 0xE3,
  kTinyPos = 0xE4,
  kTinyNeg = 0xE5,
  kDenormal = 0xE6,
  kNaN = 0xE7,
  kInfPos = 0xE8,
  kInfNeg = 0xE9,
  kFar1e7 = 0xEA,
  kFar1e15 = 0xEB,
  kRaw = 0xEC,
};

enum PolygonKind : std::uint8_t
{
  kTriangle = 0,
  kParallelogram = 1,
  kGeneral = 2,
  kCopy = 3,
  kRectangle = 4,
  kFan = 5,
};

enum MoveKind : std::uint8_t
{
  kSmallStep = 0,
  kNewPoint = 1,
  kOntoTreePoint = 2,
  kOntoNodePlane = 3,
  kParallel = 4,
  kBackToFirst = 5,
};

/// Shift scales of a copied polygon: exact duplicates, below / around / above the BSP's (1e-10)
/// and the oracle's (1e-9) relative tolerances (scene diagonal ~ 1-7), and well apart.
constexpr double kCopyScales[8] = { 0.0, 0x1p-40, 0x1p-34, 0x1p-31, 0x1p-30, 0x1p-20, 0x1p-6, 1.0 };

constexpr std::uint8_t kMaxPointsMod = 33;
constexpr std::uint8_t kMaxPolygonsMod = 24;

/// Reads bytes; past the end it yields zeros.
class Reader
{
public:
  Reader(const std::uint8_t* data, std::size_t size)
    : Data(data)
    , Size(size)
  {
  }
  std::uint8_t byte()
  {
    if (Pos >= Size)
    {
      return 0;
    }
    return Data[Pos++];
  }
  double raw()
  {
    std::uint8_t bytes[8];
    for (std::uint8_t& b : bytes)
    {
      b = byte();
    }
    double v;
    std::memcpy(&v, bytes, sizeof v);
    return v;
  }

private:
  const std::uint8_t* Data;
  std::size_t Size;
  std::size_t Pos = 0;
};

/// The grid value of a byte: (b % 33 - 16) / 8.
inline double gridValue(std::uint8_t b)
{
  return (static_cast<int>(b % 33) - 16) / 8.0;
}

/// Writer side, for the seed corpus.
class Writer
{
public:
  std::vector<std::uint8_t> bytes;
  void byte(int b) { bytes.push_back(static_cast<std::uint8_t>(b)); }
  /// A grid coordinate (v must be k / 8 with k in [-16, 16]); anything else is written raw.
  void coord(double v)
  {
    const double k = v * 8.0 + 16.0;
    if (k >= 0.0 && k <= 32.0 && k == static_cast<double>(static_cast<int>(k)))
    {
      byte(static_cast<int>(k));
      return;
    }
    byte(kRaw);
    std::uint8_t b[8];
    std::memcpy(b, &v, sizeof v);
    for (std::uint8_t x : b)
    {
      byte(x);
    }
  }
};

} // namespace fuzz
} // namespace scenevis
