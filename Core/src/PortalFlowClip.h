#pragma once
// The polygon work of the portal flow (PortalPvsFlow.cpp): clipping by a plane with a slack, the
// separating planes of two portals (anti-penumbra clipping), directed portals and their bit sets,
// and the worker pool; not installed.
#include "scenevis/PortalGeometry.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <mutex>
#include <thread>
#include <vector>

namespace scenevis
{
namespace portals
{
namespace flow
{
using Winding = std::vector<glm::dvec3>;

/// One way through a portal (the flow splits each portal in two).
struct DirectedPortal
{
  std::int32_t from = 0;
  std::int32_t to = 0;
  glm::dvec4 plane{ 0.0 };  ///< Facing `to`; coordinates relative to the portals' centre.
  Winding winding;          ///< The graph portal's hull, relative to the portals' centre.
  glm::dvec3 centre{ 0.0 }; ///< Of a sphere around the winding (quick side tests).
  double radius = 0.0;
  bool usable = false; ///< Planar with known sides: it may narrow the flow.
};

/// Bit sets of directed portals: words of 64 bits.
inline bool bit(const std::uint64_t* set, std::size_t i)
{
  return (set[i >> 6] >> (i & 63)) & 1u;
}
inline void setBit(std::uint64_t* set, std::size_t i)
{
  set[i >> 6] |= std::uint64_t(1) << (i & 63);
}
inline std::size_t popcount(const std::uint64_t* set, std::size_t words)
{
  std::size_t n = 0;
  for (std::size_t w = 0; w < words; ++w)
  {
    n += static_cast<std::size_t>(__builtin_popcountll(set[w]));
  }
  return n;
}

inline double maxDistance(const Winding& w, const glm::dvec4& plane)
{
  double d = -std::numeric_limits<double>::infinity();
  for (const auto& p : w)
  {
    d = std::max(d, geometry::planeDistance(plane, p));
  }
  return d;
}
inline double minDistance(const Winding& w, const glm::dvec4& plane)
{
  double d = std::numeric_limits<double>::infinity();
  for (const auto& p : w)
  {
    d = std::min(d, geometry::planeDistance(plane, p));
  }
  return d;
}

/// Clips @p w in place to dot(plane, p) >= -slack (@p scratch is reused); false when < 3 points.
inline bool chop(
  Winding& w, const glm::dvec4& plane, double slack, Winding& scratch, bool* changed = nullptr)
{
  bool allIn = true;
  for (const auto& p : w)
  {
    if (geometry::planeDistance(plane, p) < -slack)
    {
      allIn = false;
      break;
    }
  }
  if (allIn)
  {
    return w.size() >= 3;
  }
  if (changed)
  {
    *changed = true;
  }
  geometry::clipPolygon(w, plane, slack, scratch);
  w.swap(scratch);
  return w.size() >= 3;
}

/**
 * Appends to @p out the planes through an edge of @p source and a vertex of @p pass that have
 * the source behind and the pass in front, facing the pass: a line through both continues in
 * front. With @p flip (called with the two swapped) they face away from the first argument.
 * One plane per edge (the first found) is enough to be conservative.
 */
inline void findSeparators(
  const Winding& source, const Winding& pass, bool flip, double on, std::vector<glm::dvec4>& out)
{
  const std::size_t ns = source.size();
  for (std::size_t i = 0; i < ns; ++i)
  {
    const glm::dvec3& a = source[i];
    const std::size_t l = (i + 1) % ns;
    const glm::dvec3 v1 = source[l] - a;
    const double len1 = glm::length(v1);
    if (len1 == 0.0)
    {
      continue;
    }
    for (const glm::dvec3& pj : pass)
    {
      const glm::dvec3 v2 = pj - a;
      glm::dvec3 n = glm::cross(v1, v2);
      const double len = glm::length(n);
      if (!(len > 1e-7 * len1 * glm::length(v2)))
      {
        continue; // the vertex is (nearly) on the edge's line: no well-defined plane
      }
      n /= len;
      glm::dvec4 plane(n, -glm::dot(n, a));
      double lo = 0.0, hi = 0.0;
      for (std::size_t k = 0; k < ns; ++k)
      {
        if (k == i || k == l)
        {
          continue;
        }
        const double d = geometry::planeDistance(plane, source[k]);
        lo = std::min(lo, d);
        hi = std::max(hi, d);
        if (hi > on && lo < -on)
        {
          break; // settled: numerically not convex
        }
      }
      if (hi > on && lo < -on)
      {
        continue; // numerically not convex
      }
      if (hi <= on && lo >= -on)
      {
        continue; // in the source's plane
      }
      if (hi > on)
      {
        plane = -plane; // the source behind
      }
      bool front = false, behind = false;
      for (const glm::dvec3& q : pass)
      {
        const double d = geometry::planeDistance(plane, q);
        behind = behind || d < -on;
        front = front || d > on;
        if (behind)
        {
          break; // settled: not separating
        }
      }
      if (behind || !front)
      {
        continue; // not separating
      }
      out.push_back(flip ? -plane : plane);
      break;
    }
  }
}

/// The separating planes of (source, pass) and of (pass, source), each facing beyond the pass.
inline void separators(
  const Winding& source, const Winding& pass, double on, std::vector<glm::dvec4>& out)
{
  out.clear();
  findSeparators(source, pass, false, on, out);
  findSeparators(pass, source, true, on, out);
}

/// Clips @p target by @p planes in turn; false when nothing is left.
inline bool chopAll(
  Winding& target, const std::vector<glm::dvec4>& planes, double slack, Winding& scratch)
{
  for (const glm::dvec4& plane : planes)
  {
    if (!chop(target, plane, slack, scratch))
    {
      return false;
    }
  }
  return true;
}

/**
 * chop() for a polygon known to lie in the sphere (@p centre, @p radius) -- a portal or any
 * clipped part of it: the sphere decides a plane it does not straddle without the vertices.
 */
inline bool chopWithin(Winding& w, const glm::dvec4& plane, const glm::dvec3& centre, double radius,
  double slack, Winding& scratch)
{
  const double d = geometry::planeDistance(plane, centre);
  if (d - radius >= -slack)
  {
    return w.size() >= 3; // wholly kept
  }
  if (d + radius < -slack)
  {
    return false; // wholly behind
  }
  return chop(w, plane, slack, scratch);
}

/// chopAll() for a polygon within a sphere (chopWithin()); the planes that reject the whole
/// sphere are looked for first, before any clipping.
inline bool chopAllWithin(Winding& target, const std::vector<glm::dvec4>& planes,
  const glm::dvec3& centre, double radius, double slack, Winding& scratch)
{
  for (const glm::dvec4& plane : planes)
  {
    if (geometry::planeDistance(plane, centre) + radius < -slack)
    {
      return false;
    }
  }
  for (const glm::dvec4& plane : planes)
  {
    if (!chopWithin(target, plane, centre, radius, slack, scratch))
    {
      return false;
    }
  }
  return true;
}

/**
 * The convex hull of the points of @p a and @p b, which lie in one plane of unit normal
 * @p normal, into @p out (counter-clockwise around the normal); returns its area. @p work is
 * scratch space. The merged flow's union of the polygons that reached one portal.
 */
inline double mergeHull(const Winding& a, const Winding& b, const glm::dvec3& normal, Winding& out,
  std::vector<glm::dvec3>& work)
{
  glm::dvec3 u, v;
  geometry::planeBasis(normal, u, v);
  // work[i] = (x, y, index into a then b): sorted by x then y (Andrew's monotone chain).
  work.clear();
  for (std::size_t i = 0; i < a.size() + b.size(); ++i)
  {
    const glm::dvec3& q = i < a.size() ? a[i] : b[i - a.size()];
    work.emplace_back(glm::dot(q, u), glm::dot(q, v), static_cast<double>(i));
  }
  std::sort(work.begin(), work.end(),
    [](const glm::dvec3& p, const glm::dvec3& q)
    { return p.x < q.x || (p.x == q.x && p.y < q.y); });
  auto cross = [](const glm::dvec3& o, const glm::dvec3& p, const glm::dvec3& q)
  { return (p.x - o.x) * (q.y - o.y) - (p.y - o.y) * (q.x - o.x); };
  const std::size_t n = work.size();
  std::vector<glm::dvec3> h(2 * n + 1);
  std::size_t k = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    while (k >= 2 && cross(h[k - 2], h[k - 1], work[i]) <= 0.0)
    {
      --k;
    }
    h[k++] = work[i];
  }
  for (std::size_t i = n - 1, t = k + 1; i > 0; --i)
  {
    while (k >= t && cross(h[k - 2], h[k - 1], work[i - 1]) <= 0.0)
    {
      --k;
    }
    h[k++] = work[i - 1];
  }
  out.clear();
  double area = 0.0;
  for (std::size_t i = 0; i + 1 < k; ++i)
  {
    const auto idx = static_cast<std::size_t>(h[i].z);
    out.push_back(idx < a.size() ? a[idx] : b[idx - a.size()]);
    area += h[i].x * h[i + 1].y - h[i + 1].x * h[i].y;
  }
  return 0.5 * area;
}

/// Runs @p work(i) for i in [0, count) on @p threads threads, calling @p tick about every 50 ms
/// on this thread; tick returns false to ask the workers to stop (they check Shared::stop).
template <class Work, class Tick>
void runParallel(std::size_t count, int threads, Work work, Tick tick)
{
  std::atomic<std::size_t> next{ 0 }, finished{ 0 };
  std::mutex m;
  std::condition_variable cv;
  auto worker = [&]()
  {
    for (;;)
    {
      const std::size_t i = next.fetch_add(1);
      if (i >= count)
      {
        break;
      }
      work(i);
      if (finished.fetch_add(1) + 1 == count)
      {
        std::lock_guard<std::mutex> lock(m);
        cv.notify_all();
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t)
  {
    pool.emplace_back(worker);
  }
  {
    std::unique_lock<std::mutex> lock(m);
    while (finished.load() < count)
    {
      cv.wait_for(lock, std::chrono::milliseconds(50));
      lock.unlock();
      tick(finished.load());
      lock.lock();
    }
  }
  for (auto& t : pool)
  {
    t.join();
  }
}

} // namespace flow
} // namespace portals
} // namespace scenevis
