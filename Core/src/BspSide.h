#pragma once
// Internal: the side test every BSP traversal shares (BspTraversal.cpp, BspLeafOrder.cpp).

namespace scenevis
{
namespace bsp
{
namespace detail
{

/// The side value of a plane for an eye; >= 0 means in front. The one expression all traversals
/// use (order(), IncrementalOrder::update(), the ordered leaves' planes), evaluated in the same
/// order on the same doubles, so they agree bit for bit on an eye that lies on a plane.
inline double sideValue(
  double px, double py, double pz, double pw, double ex, double ey, double ez, double ew)
{
  return px * ex + py * ey + pz * ez + pw * ew;
}

} // namespace detail
} // namespace bsp
} // namespace scenevis
