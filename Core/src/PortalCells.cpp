#include "PortalCells.h"

#include "scenevis/PortalGeometry.h"

#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace scenevis
{
namespace detail
{
namespace
{

using Poly = std::vector<glm::dvec3>;
using bsp::kNone;
using portals::geometry::newellOf;

double distance(const glm::dvec4& plane, const glm::dvec3& p)
{
  return glm::dot(glm::dvec3(plane), p) + plane.w;
}

enum class Side
{
  Front,
  Back,
  On,
  Split
};

/// Splits @p in by @p plane; vertices within @p tol of it go to both halves, so the halves of a
/// polygon split at a shared vertex keep it, and nothing thinner than @p tol is made.
Side split(const Poly& in, const glm::dvec4& plane, double tol, Poly& front, Poly& back)
{
  front.clear();
  back.clear();
  thread_local std::vector<double> d;
  d.resize(in.size());
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (std::size_t i = 0; i < in.size(); ++i)
  {
    d[i] = distance(plane, in[i]);
    lo = std::min(lo, d[i]);
    hi = std::max(hi, d[i]);
  }
  if (lo >= -tol && hi <= tol)
  {
    return Side::On;
  }
  if (lo >= -tol)
  {
    return Side::Front;
  }
  if (hi <= tol)
  {
    return Side::Back;
  }
  for (std::size_t i = 0; i < in.size(); ++i)
  {
    const std::size_t j = (i + 1) % in.size();
    if (d[i] > tol)
    {
      front.push_back(in[i]);
    }
    else if (d[i] < -tol)
    {
      back.push_back(in[i]);
    }
    else
    {
      front.push_back(in[i]);
      back.push_back(in[i]);
    }
    if ((d[i] > tol && d[j] < -tol) || (d[i] < -tol && d[j] > tol))
    {
      const glm::dvec3 p = in[i] + (d[i] / (d[i] - d[j])) * (in[j] - in[i]);
      front.push_back(p);
      back.push_back(p);
    }
  }
  return Side::Split;
}

/// Fewer than 3 points, or narrower than @p tol (twice the area over the longest edge).
bool sliver(const Poly& p, double tol)
{
  if (p.size() < 3)
  {
    return true;
  }
  double longest = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    longest = std::max(longest, glm::length(p[(i + 1) % p.size()] - p[i]));
  }
  return glm::length(newellOf(p)) <= 2.0 * tol * longest;
}

glm::dvec3 meanOf(const Poly& p)
{
  glm::dvec3 c(0.0);
  for (const glm::dvec3& q : p)
  {
    c += q;
  }
  return c / static_cast<double>(p.size());
}

Box boundsOf(const Poly& p)
{
  Box b;
  for (const glm::dvec3& q : p)
  {
    b.extend(q);
  }
  return b;
}

bool overlap(const Box& a, const Box& b, double tol)
{
  for (int k = 0; k < 3; ++k)
  {
    if (a.lo[k] > b.hi[k] + tol || b.lo[k] > a.hi[k] + tol)
    {
      return false;
    }
  }
  return true;
}

/**
 * Places @p poly in the subtree hanging at slot (@p parent, @p side) (parent kNone: the whole
 * tree) and calls emit(cell, piece) for each piece that reaches an empty slot. A piece lying in
 * a descendant's plane goes to the side @p inward points to: the side of that plane where the
 * region the polygon bounds lies.
 */
template <class Emit>
void place(const bsp::Tree& tree, Poly poly, std::uint32_t parent, int side,
  const glm::dvec3& inward, Emit&& emit)
{
  struct Item
  {
    Poly poly;
    std::uint32_t parent;
    int side;
  };
  std::vector<Item> stack;
  stack.push_back(Item{ std::move(poly), parent, side });
  Poly front, back;
  while (!stack.empty())
  {
    Item item = std::move(stack.back());
    stack.pop_back();
    std::uint32_t child = tree.root;
    if (item.parent != kNone)
    {
      const bsp::Node& p = tree.nodes[item.parent];
      child = item.side == 0 ? p.front : p.back;
    }
    if (child == kNone)
    {
      emit(cellOf(item.parent, item.side), item.poly);
      continue;
    }
    const glm::dvec4& plane = tree.nodes[child].plane;
    switch (split(item.poly, plane, tree.tolerance, front, back))
    {
      case Side::Front:
        stack.push_back(Item{ std::move(item.poly), child, 0 });
        break;
      case Side::Back:
        stack.push_back(Item{ std::move(item.poly), child, 1 });
        break;
      case Side::On:
        stack.push_back(
          Item{ std::move(item.poly), child, glm::dot(glm::dvec3(plane), inward) > 0.0 ? 0 : 1 });
        break;
      case Side::Split:
        if (!sliver(front, tree.tolerance))
        {
          stack.push_back(Item{ front, child, 0 });
        }
        if (!sliver(back, tree.tolerance))
        {
          stack.push_back(Item{ back, child, 1 });
        }
        break;
    }
  }
}

/// The part of @p plane inside @p box, counter-clockwise around its normal.
Poly planeInBox(const glm::dvec4& plane, const Box& box)
{
  const glm::dvec3 n(plane);
  const glm::dvec3 c = box.center();
  const glm::dvec3 p0 = c - distance(plane, c) * n;
  glm::dvec3 u, v;
  portals::geometry::planeBasis(n, u, v);
  const double r = 2.0 * box.diagonal() + 1.0;
  Poly poly{ p0 - r * u - r * v, p0 + r * u - r * v, p0 + r * u + r * v, p0 - r * u + r * v };
  Poly clipped;
  for (int k = 0; k < 3; ++k)
  {
    glm::dvec4 lo(0.0), hi(0.0);
    lo[k] = 1.0;
    lo.w = -box.lo[k];
    hi[k] = -1.0;
    hi.w = box.hi[k];
    portals::geometry::clipPolygon(poly, lo, 0.0, clipped);
    portals::geometry::clipPolygon(clipped, hi, 0.0, poly);
  }
  return poly;
}

struct LocalFragment
{
  Poly poly;
  glm::dvec3 normal; ///< Unit, of the fragment's own winding.
  Box bounds;
  bool facesFront; ///< Its normal agrees with the node's.
  std::uint32_t source;
};

/// Subtracts the node's fragments from @p face: records which sides they face, keeps the open
/// remainder.
void subtractFragments(const bsp::Tree& tree, const std::vector<LocalFragment>& fragments,
  std::uint32_t faceIndex, CellComplex& out)
{
  const double tol = tree.tolerance;
  const CellFace& face = out.faces[faceIndex];
  std::vector<Poly> remaining{ face.polygon }, next;
  Poly inside, outside, cur;
  for (const LocalFragment& f : fragments)
  {
    next.clear();
    for (Poly& r : remaining)
    {
      if (!overlap(f.bounds, boundsOf(r), tol))
      {
        next.push_back(std::move(r));
        continue;
      }
      cur = std::move(r);
      bool covered = true;
      for (std::size_t k = 0; k < f.poly.size() && covered; ++k)
      {
        const glm::dvec3& a = f.poly[k];
        const glm::dvec3 edge = f.poly[(k + 1) % f.poly.size()] - a;
        const double len = glm::length(edge);
        if (len == 0.0)
        {
          continue;
        }
        const glm::dvec3 in = glm::cross(f.normal, edge) / len;
        const glm::dvec4 plane(in, -glm::dot(in, a));
        switch (split(cur, plane, tol, inside, outside))
        {
          case Side::Back:
            next.push_back(std::move(cur));
            covered = false;
            break;
          case Side::Split:
            if (!sliver(outside, tol))
            {
              next.push_back(outside);
            }
            cur = inside;
            covered = !sliver(cur, tol);
            break;
          case Side::Front:
          case Side::On:
            break;
        }
      }
      if (covered && !sliver(cur, tol))
      {
        const double area = polygonArea(cur);
        const std::uint32_t faced = f.facesFront ? face.front : face.back;
        out.facedArea[faced] += area;
        out.backedArea[f.facesFront ? face.back : face.front] += area;
        out.coverage.push_back(
          CellComplex::Coverage{ f.source, faced, f.facesFront ? face.back : face.front, area });
      }
    }
    std::swap(remaining, next);
  }
  for (Poly& r : remaining)
  {
    if (!sliver(r, tol))
    {
      out.open.push_back(OpenPiece{ faceIndex, std::move(r) });
    }
  }
}

void addToCell(CellComplex& out, std::uint32_t cell, const Poly& poly, const glm::dvec3& outward)
{
  const double area = polygonArea(poly);
  const glm::dvec3 c = meanOf(poly);
  out.volume[cell] += area * glm::dot(outward, c) / 3.0;
  out.centroid[cell] += area * c;
  out.boundaryArea[cell] += area;
  out.vertices[cell].insert(out.vertices[cell].end(), poly.begin(), poly.end());
}

} // namespace

std::vector<glm::dvec3> fragmentPolygon(const bsp::Tree& tree, const bsp::Fragment& f)
{
  Poly poly(f.count);
  for (std::uint32_t k = 0; k < f.count; ++k)
  {
    poly[k] = tree.points[tree.fragmentVertices[f.first + k]] - tree.origin;
  }
  return poly;
}

double polygonArea(const std::vector<glm::dvec3>& poly)
{
  return 0.5 * glm::length(newellOf(poly));
}

bool insideConvexPolygon(const std::vector<glm::dvec3>& poly, const glm::dvec3& p, double tol)
{
  const glm::dvec3 w = newellOf(poly);
  const double wl = glm::length(w);
  if (poly.size() < 3 || wl == 0.0)
  {
    return false;
  }
  for (std::size_t k = 0; k < poly.size(); ++k)
  {
    const glm::dvec3 edge = poly[(k + 1) % poly.size()] - poly[k];
    const double len = glm::length(edge);
    if (len == 0.0)
    {
      continue;
    }
    if (glm::dot(glm::cross(w, edge), p - poly[k]) / (wl * len) <= tol)
    {
      return false;
    }
  }
  return true;
}

CellComplex buildCellComplex(const bsp::Tree& tree, const Box& box)
{
  CellComplex out;
  const std::size_t nodes = tree.nodes.size();
  out.cellCount = 2 * nodes;
  out.isCell.assign(out.cellCount, 0);
  out.facedArea.assign(out.cellCount, 0.0);
  out.backedArea.assign(out.cellCount, 0.0);
  out.touchesBox.assign(out.cellCount, 0);
  out.volume.assign(out.cellCount, 0.0);
  out.centroid.assign(out.cellCount, glm::dvec3(0.0));
  out.boundaryArea.assign(out.cellCount, 0.0);
  out.vertices.assign(out.cellCount, {});
  if (tree.empty())
  {
    return out;
  }
  std::vector<std::uint32_t> parent(nodes, kNone);
  std::vector<int> parentSide(nodes, 0);
  for (std::uint32_t n = 0; n < nodes; ++n)
  {
    const bsp::Node& node = tree.nodes[n];
    out.isCell[cellOf(n, 0)] = node.front == kNone;
    out.isCell[cellOf(n, 1)] = node.back == kNone;
    for (int s = 0; s < 2; ++s)
    {
      const std::uint32_t child = s == 0 ? node.front : node.back;
      if (child != kNone)
      {
        parent[child] = n;
        parentSide[child] = s;
      }
    }
  }

  std::vector<LocalFragment> fragments;
  Poly clipped;
  for (std::uint32_t n = 0; n < nodes; ++n)
  {
    const bsp::Node& node = tree.nodes[n];
    const glm::dvec3 normal(node.plane);
    // The node's region: the box cut by every ancestor's half-space.
    Poly poly = planeInBox(node.plane, box);
    for (std::uint32_t m = n; parent[m] != kNone && poly.size() >= 3; m = parent[m])
    {
      const glm::dvec4& p = tree.nodes[parent[m]].plane;
      portals::geometry::clipPolygon(poly, parentSide[m] == 0 ? p : -p, 0.0, clipped);
      std::swap(poly, clipped);
    }
    if (sliver(poly, tree.tolerance))
    {
      continue;
    }
    const std::size_t firstFace = out.faces.size();
    place(tree, std::move(poly), n, 0, normal,
      [&](std::uint32_t front, const Poly& piece)
      {
        place(tree, piece, n, 1, -normal,
          [&](std::uint32_t back, const Poly& shared) {
            out.faces.push_back(CellFace{ n, front, back, shared });
          });
      });

    fragments.clear();
    for (std::uint32_t k = 0; k < node.fragmentCount; ++k)
    {
      LocalFragment f;
      f.poly = fragmentPolygon(tree, tree.fragments[node.firstFragment + k]);
      const glm::dvec3 w = newellOf(f.poly);
      if (glm::length(w) == 0.0)
      {
        continue;
      }
      f.normal = glm::normalize(w);
      f.bounds = boundsOf(f.poly);
      f.facesFront = glm::dot(f.normal, normal) > 0.0;
      f.source = tree.fragments[node.firstFragment + k].source;
      fragments.push_back(std::move(f));
    }
    for (std::size_t i = firstFace; i < out.faces.size(); ++i)
    {
      const CellFace& face = out.faces[i];
      addToCell(out, face.front, face.polygon, -normal);
      addToCell(out, face.back, face.polygon, normal);
      subtractFragments(tree, fragments, static_cast<std::uint32_t>(i), out);
    }
  }

  // The box's faces, to find the cells at the edge of the world.
  for (int k = 0; k < 3; ++k)
  {
    for (int s = 0; s < 2; ++s)
    {
      glm::dvec4 plane(0.0);
      plane[k] = s == 0 ? 1.0 : -1.0; // inward normal
      plane.w = s == 0 ? -box.lo[k] : box.hi[k];
      const glm::dvec3 inward(plane);
      Box grown = box;
      grown.lo -= glm::dvec3(1.0);
      grown.hi += glm::dvec3(1.0);
      place(tree, planeInBox(plane, grown), kNone, 0, inward,
        [&](std::uint32_t cell, const Poly& piece)
        {
          out.touchesBox[cell] = 1;
          addToCell(out, cell, piece, -inward);
        });
    }
  }
  for (std::size_t c = 0; c < out.cellCount; ++c)
  {
    if (out.boundaryArea[c] > 0.0)
    {
      out.centroid[c] /= out.boundaryArea[c];
    }
  }
  return out;
}

BoxGrid::BoxGrid(const std::vector<Box>& boxes, double tolerance)
  : Tolerance(tolerance)
{
  for (const Box& b : boxes)
  {
    this->All.extend(b);
  }
  if (boxes.empty())
  {
    this->All.extend(glm::dvec3(0.0));
  }
  // About one box per cell over the axes the boxes spread along: a flat set (the fragments of
  // one plane) gets a 2D grid, a set on a line a 1D one. Sizing a flat set by its volume made
  // the cells tiny and the ratio below too large for an int (UB the portal generation fuzzer
  // found; on x86 it happened to give one cell), and clamping it gave 256 x 256 mostly empty
  // cells per plane, which made the openings step 3-10x slower.
  const glm::dvec3 extent = this->All.hi - this->All.lo;
  const double largest = std::max({ extent.x, extent.y, extent.z });
  bool spread[3];
  int axes = 0;
  double measure = 1.0;
  for (int k = 0; k < 3; ++k)
  {
    spread[k] = extent[k] > 1e-6 * largest; // false for NaN
    if (spread[k])
    {
      ++axes;
      measure *= extent[k];
    }
  }
  const double size = axes > 0
    ? std::pow(measure / static_cast<double>(std::max<std::size_t>(boxes.size(), 1)), 1.0 / axes)
    : 0.0;
  for (int k = 0; k < 3; ++k)
  {
    const double cells = spread[k] && size > 0.0 ? extent[k] / size : 0.0;
    this->Dims[k] = cells >= 1.0 ? static_cast<int>(std::min(cells, 256.0)) : 1;
  }
  this->Cells.resize(static_cast<std::size_t>(this->Dims[0]) * this->Dims[1] * this->Dims[2]);
  for (std::uint32_t i = 0; i < boxes.size(); ++i)
  {
    int lo[3], hi[3];
    this->range(boxes[i], lo, hi);
    for (int z = lo[2]; z <= hi[2]; ++z)
      for (int y = lo[1]; y <= hi[1]; ++y)
        for (int x = lo[0]; x <= hi[0]; ++x)
          this->Cells[(static_cast<std::size_t>(z) * this->Dims[1] + y) * this->Dims[0] + x]
            .push_back(i);
  }
  this->Seen.assign(boxes.size(), kNone);
}

void BoxGrid::range(const Box& b, int lo[3], int hi[3]) const
{
  for (int k = 0; k < 3; ++k)
  {
    const double extent = this->All.hi[k] - this->All.lo[k];
    if (!(extent > 0.0))
    {
      lo[k] = hi[k] = 0;
      continue;
    }
    const double scale = this->Dims[k] / extent;
    const double a = std::floor((b.lo[k] - this->Tolerance - this->All.lo[k]) * scale);
    const double c = std::floor((b.hi[k] + this->Tolerance - this->All.lo[k]) * scale);
    lo[k] = static_cast<int>(std::clamp(a, 0.0, this->Dims[k] - 1.0));
    hi[k] = static_cast<int>(std::clamp(c, 0.0, this->Dims[k] - 1.0));
  }
}

const std::vector<std::uint32_t>& BoxGrid::near(const Box& box)
{
  this->Near.clear();
  ++this->Query;
  int lo[3], hi[3];
  this->range(box, lo, hi);
  for (int z = lo[2]; z <= hi[2]; ++z)
    for (int y = lo[1]; y <= hi[1]; ++y)
      for (int x = lo[0]; x <= hi[0]; ++x)
        for (const std::uint32_t i :
          this->Cells[(static_cast<std::size_t>(z) * this->Dims[1] + y) * this->Dims[0] + x])
        {
          if (this->Seen[i] != this->Query)
          {
            this->Seen[i] = this->Query;
            this->Near.push_back(i);
          }
        }
  std::sort(this->Near.begin(), this->Near.end());
  return this->Near;
}

std::size_t splitCellsAtOpenings(bsp::Tree& tree, const CellComplex& cx)
{
  const double tol = tree.tolerance;
  const std::size_t nodes = tree.nodes.size();
  std::vector<std::uint32_t> parent(nodes, kNone);
  std::vector<int> parentSide(nodes, 0);
  for (std::uint32_t n = 0; n < nodes; ++n)
  {
    for (int s = 0; s < 2; ++s)
    {
      const std::uint32_t child = s == 0 ? tree.nodes[n].front : tree.nodes[n].back;
      if (child != kNone)
      {
        parent[child] = n;
        parentSide[child] = s;
      }
    }
  }
  struct Candidate
  {
    Poly poly;
    Box bounds;
    glm::dvec4 plane;
  };
  std::vector<Candidate> fragments;
  for (std::uint32_t n = 0; n < nodes; ++n)
  {
    const bsp::Node& node = tree.nodes[n];
    for (std::uint32_t k = 0; k < node.fragmentCount; ++k)
    {
      Candidate c;
      c.poly = fragmentPolygon(tree, tree.fragments[node.firstFragment + k]);
      c.bounds = boundsOf(c.poly);
      c.plane = node.plane;
      fragments.push_back(std::move(c));
    }
  }
  std::vector<Box> boxes;
  for (const Candidate& f : fragments)
  {
    boxes.push_back(f.bounds);
  }
  BoxGrid grid(boxes, tol);

  std::vector<std::pair<std::uint32_t, glm::dvec4>> splits;
  Poly clipped, work;
  for (std::uint32_t cell = 0; cell < cx.cellCount; ++cell)
  {
    const auto& vertices = cx.vertices[cell];
    if (!cx.isCell[cell] || vertices.empty())
    {
      continue;
    }
    Box bounds;
    for (const glm::dvec3& v : vertices)
    {
      bounds.extend(v);
    }
    const std::vector<std::uint32_t>& near = grid.near(bounds);
    for (const std::uint32_t i : near)
    {
      const Candidate& f = fragments[i];
      if (!overlap(bounds, f.bounds, tol))
      {
        continue;
      }
      double below = 0.0, above = 0.0;
      for (const glm::dvec3& v : vertices)
      {
        const double d = distance(f.plane, v);
        below = std::min(below, d);
        above = std::max(above, d);
      }
      if (below >= -tol || above <= tol)
      {
        continue; // the plane does not cross the cell
      }
      // Does the polygon touch the cell (its closure, within tolerance)?
      work = f.poly;
      const std::uint32_t node = cell / 2;
      glm::dvec4 half = (cell % 2) == 0 ? tree.nodes[node].plane : -tree.nodes[node].plane;
      portals::geometry::clipPolygon(work, half, tol, clipped);
      for (std::uint32_t m = node; !clipped.empty() && parent[m] != kNone; m = parent[m])
      {
        const glm::dvec4& p = tree.nodes[parent[m]].plane;
        std::swap(work, clipped);
        portals::geometry::clipPolygon(work, parentSide[m] == 0 ? p : -p, tol, clipped);
      }
      if (!clipped.empty())
      {
        splits.emplace_back(cell, f.plane);
        break;
      }
    }
  }
  for (const auto& [cell, plane] : splits)
  {
    bsp::Node node;
    node.plane = plane;
    const auto id = static_cast<std::uint32_t>(tree.nodes.size());
    bsp::Node& owner = tree.nodes[cell / 2];
    (cell % 2 == 0 ? owner.front : owner.back) = id;
    tree.nodes.push_back(node);
  }
  return splits.size();
}

std::uint32_t locateCell(const bsp::Tree& tree, const glm::dvec3& p)
{
  std::uint32_t node = tree.root;
  while (node != kNone)
  {
    const bsp::Node& n = tree.nodes[node];
    const int side = distance(n.plane, p) >= 0.0 ? 0 : 1;
    const std::uint32_t child = side == 0 ? n.front : n.back;
    if (child == kNone)
    {
      return cellOf(node, side);
    }
    node = child;
  }
  return kNone;
}

bool segmentHitsFragment(const bsp::Tree& tree, const glm::dvec3& a, const glm::dvec3& b)
{
  struct Segment
  {
    std::uint32_t node;
    glm::dvec3 a, b;
  };
  const double tol = tree.tolerance;
  std::vector<Segment> stack{ Segment{ tree.root, a, b } };
  Poly poly;
  while (!stack.empty())
  {
    const Segment s = stack.back();
    stack.pop_back();
    if (s.node == kNone)
    {
      continue;
    }
    const bsp::Node& n = tree.nodes[s.node];
    const double da = distance(n.plane, s.a), db = distance(n.plane, s.b);
    if (da > tol && db > tol)
    {
      stack.push_back(Segment{ n.front, s.a, s.b });
      continue;
    }
    if (da < -tol && db < -tol)
    {
      stack.push_back(Segment{ n.back, s.a, s.b });
      continue;
    }
    if (std::abs(da) <= tol && std::abs(db) <= tol)
    {
      // Along the plane: its fragments are edge-on and block nothing.
      stack.push_back(Segment{ n.front, s.a, s.b });
      stack.push_back(Segment{ n.back, s.a, s.b });
      continue;
    }
    const double t = std::clamp(da / (da - db), 0.0, 1.0);
    const glm::dvec3 m = s.a + t * (s.b - s.a);
    for (std::uint32_t k = 0; k < n.fragmentCount; ++k)
    {
      // fragmentPolygon() into one buffer: no allocation per fragment tested.
      const bsp::Fragment& f = tree.fragments[n.firstFragment + k];
      poly.resize(f.count);
      for (std::uint32_t v = 0; v < f.count; ++v)
      {
        poly[v] = tree.points[tree.fragmentVertices[f.first + v]] - tree.origin;
      }
      if (insideConvexPolygon(poly, m, -tol))
      {
        return true;
      }
    }
    const bool aFront = da >= 0.0;
    stack.push_back(Segment{ aFront ? n.front : n.back, s.a, m });
    stack.push_back(Segment{ aFront ? n.back : n.front, m, s.b });
  }
  return false;
}

} // namespace detail
} // namespace scenevis
