#pragma once
// Module-private: MaskedDepthBuffer's tile update and block bookkeeping, inline here because
// both rasterizers (OcclusionBuffer.cpp, OcclusionRasterFloat.cpp) call them once per tile.

#include "scenevis/OcclusionBuffer.h"

#include <algorithm>
#include <limits>

namespace scenevis
{
namespace occlusion
{

inline void MaskedDepthBuffer::lowerBlock(int tx, int ty, float oldZ0)
{
  // Tile indices are never negative: the block by shifts.
  static_assert(kBlockTiles == 4, "blocks of 4 x 4 tiles");
  float& bound = blockZ0_[static_cast<std::size_t>(ty >> 2) * blocksX_ + (tx >> 2)];
  if (oldZ0 >= bound)
  {
    // The block's largest z0 may have gone down: found again when the block is next read (a
    // wall filling a block tile by tile costs one pass over it, not one per tile).
    bound = std::numeric_limits<float>::quiet_NaN();
  }
}

inline void MaskedDepthBuffer::updateTile(
  Tile& tile, std::uint32_t mask, float depth, std::uint32_t outside)
{
  // Invariants: every pixel has an occluder at depth <= z0; every pixel of mask one at <= z1.
  if (!(depth < tile.z0))
  {
    return; // no nearer than what the whole tile already has
  }
  if ((mask | outside) == 0xFFFFFFFFu)
  {
    tile.z0 = depth;
  }
  else if (tile.mask == 0)
  {
    tile.mask = mask;
    tile.z1 = depth;
  }
  else if (tile.z1 - depth > std::min(tile.z0, 1.0f) - tile.z1)
  {
    // The new triangle is much nearer than the working layer: merging would push the layer's
    // depth far back; start the layer again from this triangle (Hasselgren et al.'s heuristic).
    // A tile with no reference layer yet measures from the far plane (window depth 1), as a
    // buffer cleared to the far plane would: with +inf the layer would never restart, and a far
    // part drawn first into a tile would set the depth of the near wall that completes it.
    tile.mask = mask;
    tile.z1 = depth;
  }
  else
  {
    tile.mask |= mask;
    tile.z1 = std::max(tile.z1, depth);
  }
  if (tile.mask != 0 && (tile.mask | outside) == 0xFFFFFFFFu)
  {
    tile.z0 = std::min(tile.z0, tile.z1);
    tile.mask = 0;
  }
  else if (tile.mask != 0 && !(tile.z1 < tile.z0))
  {
    tile.mask = 0; // the working layer says nothing the reference layer does not
  }
}

} // namespace occlusion
} // namespace scenevis
