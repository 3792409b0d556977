#include "BspLeafBuilder.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>

namespace scenevis
{
namespace bsp
{
namespace detail
{

bool LeafBuilder::separatingPlane(const Frag& a, const Frag& b, glm::dvec4& plane) const
{
  const std::uint32_t* ia = G.verts + a.first;
  const std::uint32_t* ib = G.verts + b.first;
  auto edge = [this](const std::uint32_t* ids, std::uint32_t count, std::uint32_t k)
  { return G.points[ids[k + 1 == count ? 0 : k + 1]] - G.points[ids[k]]; };
  auto tryAxis = [&](glm::dvec3 d) -> bool
  {
    const double length = glm::length(d);
    if (!(length > 0.0) || !std::isfinite(length))
    {
      return false;
    }
    d /= length;
    double loA = std::numeric_limits<double>::infinity();
    double hiA = -loA;
    double loB = loA;
    double hiB = -loA;
    for (std::uint32_t k = 0; k < a.count; ++k)
    {
      const double s = glm::dot(d, G.points[ia[k]]);
      loA = std::min(loA, s);
      hiA = std::max(hiA, s);
    }
    for (std::uint32_t k = 0; k < b.count; ++k)
    {
      const double s = glm::dot(d, G.points[ib[k]]);
      loB = std::min(loB, s);
      hiB = std::max(hiB, s);
    }
    glm::dvec4 candidate;
    if (hiA - loB <= G.tolerance)
    {
      candidate = glm::dvec4(d, -0.5 * (hiA + loB));
    }
    else if (hiB - loA <= G.tolerance)
    {
      candidate = glm::dvec4(-d, 0.5 * (hiB + loA));
    }
    else
    {
      return false;
    }
    // The verdict is the classification the partition planes get, so the leaf's order is exact
    // in the same sense as the tree's.
    const Side sa = G.classify(candidate, a);
    const Side sb = G.classify(candidate, b);
    if ((sa & Front) || (sb & Back) || (sa == On && sb == On))
    {
      return false;
    }
    plane = candidate;
    return true;
  };
  const glm::dvec3 na(G.piecePlanes[a.piece]);
  const glm::dvec3 nb(G.piecePlanes[b.piece]);
  for (std::uint32_t i = 0; i < a.count; ++i)
  {
    const glm::dvec3 ea = edge(ia, a.count, i);
    for (std::uint32_t j = 0; j < b.count; ++j)
    {
      if (tryAxis(glm::cross(ea, edge(ib, b.count, j))))
      {
        return true;
      }
    }
    if (tryAxis(glm::cross(na, ea)))
    {
      return true;
    }
  }
  for (std::uint32_t j = 0; j < b.count; ++j)
  {
    if (tryAxis(glm::cross(nb, edge(ib, b.count, j))))
    {
      return true;
    }
  }
  return false;
}

void LeafBuilder::separatingGenerators(const Frag& a, const Frag& b)
{
  auto add = [this, &a, &b](const glm::dvec3& p, const glm::dvec3& q, const glm::dvec3& r)
  {
    glm::dvec3 n = glm::cross(q - p, r - p);
    const double length = glm::length(n);
    if (!(length > 0.0) || !std::isfinite(length))
    {
      return;
    }
    n /= length;
    glm::dvec4 plane(n, -glm::dot(n, p));
    Side sa = G.classify(plane, a);
    Side sb = G.classify(plane, b);
    if (sa == Straddle || sb == Straddle || (sa & sb) != 0 || (sa | sb) == On)
    {
      return;
    }
    if ((sa & Front) || (sb & Back))
    {
      plane = -plane;
    }
    Generators.push_back(plane);
  };
  for (int pass = 0; pass < 2; ++pass)
  {
    const Frag& e = pass == 0 ? a : b;
    const Frag& v = pass == 0 ? b : a;
    for (std::uint32_t i = 0; i < e.count; ++i)
    {
      const glm::dvec3& p = G.points[G.verts[e.first + i]];
      const glm::dvec3& q = G.points[G.verts[e.first + (i + 1 == e.count ? 0 : i + 1)]];
      for (std::uint32_t j = 0; j < v.count; ++j)
      {
        add(p, q, G.points[G.verts[v.first + j]]);
      }
    }
  }
}

bool LeafBuilder::analyse(const BuildGeometry& geometry, const Frag* list, std::uint32_t n)
{
  G = geometry;
  planes.clear();
  pairs.clear();
  for (std::uint32_t i = 0; i < n; ++i)
  {
    planes.push_back(G.piecePlanes[list[i].piece]);
  }
  // Union-find over the stored pairs: a cycle of precedences needs a cycle of pairs.
  Roots.resize(n);
  for (std::uint32_t i = 0; i < n; ++i)
  {
    Roots[i] = i;
  }
  auto findRoot = [this](std::uint32_t i)
  {
    while (Roots[i] != i)
    {
      i = Roots[i] = Roots[Roots[i]];
    }
    return i;
  };
  mayCycle = false;
  for (std::uint32_t i = 0; i < n; ++i)
  {
    for (std::uint32_t j = i + 1; j < n; ++j)
    {
      const Side sj = G.classify(planes[i], list[j]);
      const Side si = G.classify(planes[j], list[i]);
      if (sj == On || si == On)
      {
        continue; // coplanar: any order is exact (as for a node's own fragments)
      }
      // Plane i: fragment i lies on it; the verdict "i before j" holds from the front when j is
      // in front. Plane j likewise with the roles swapped. Normals are kept oriented as
      // "i behind, j in front" to pick the other planes.
      LeafPair pair{ static_cast<std::uint8_t>(i), static_cast<std::uint8_t>(j), {} };
      std::fill(std::begin(pair.planes), std::end(pair.planes), kNoPlane);
      std::uint32_t used = 0;
      glm::dvec3 chosen[kPairPlanes];
      if (sj != Straddle)
      {
        pair.planes[used] = static_cast<std::uint16_t>(i | (sj == Back ? kFlipPlane : 0));
        chosen[used++] = glm::dvec3(planes[i]) * (sj == Back ? -1.0 : 1.0);
      }
      if (si != Straddle)
      {
        pair.planes[used] = static_cast<std::uint16_t>(j | (si == Front ? kFlipPlane : 0));
        chosen[used++] = glm::dvec3(planes[j]) * (si == Front ? -1.0 : 1.0);
      }
      // More separating planes, each as far in direction from those chosen as possible: the more
      // different they are, the more eyes see two of them disagree (and the pair unordered).
      Generators.clear();
      separatingGenerators(list[i], list[j]);
      if (used == 0 && Generators.empty())
      {
        glm::dvec4 plane;
        if (!separatingPlane(list[i], list[j], plane))
        {
          return false; // they intersect (or touch too closely to tell): split this list
        }
        Generators.push_back(plane);
      }
      while (used < kPairPlanes && !Generators.empty() && planes.size() < kMaxLeafPlanes)
      {
        std::size_t best = 0;
        double bestDot = std::numeric_limits<double>::infinity();
        for (std::size_t g = 0; g < Generators.size(); ++g)
        {
          double worst = -1.0;
          for (std::uint32_t m = 0; m < used; ++m)
          {
            worst = std::max(worst, glm::dot(glm::dvec3(Generators[g]), chosen[m]));
          }
          if (worst < bestDot)
          {
            bestDot = worst;
            best = g;
          }
        }
        if (bestDot > 0.9999)
        {
          break; // nothing new in direction
        }
        pair.planes[used] = static_cast<std::uint16_t>(planes.size());
        chosen[used++] = glm::dvec3(Generators[best]);
        planes.push_back(Generators[best]);
        Generators[best] = Generators.back();
        Generators.pop_back();
      }
      if (used == 0)
      {
        return false; // a separating plane exists but the leaf has no room left for it
      }
      pairs.push_back(pair);
      const std::uint32_t ri = findRoot(i);
      const std::uint32_t rj = findRoot(j);
      mayCycle |= ri == rj;
      Roots[ri] = rj;
    }
  }

  return true;
}

} // namespace detail
} // namespace bsp
} // namespace scenevis
