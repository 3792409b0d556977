#include "vtkScenePlanRule.h"

#include "vtkCamera.h"
#include "vtkMatrix4x4.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

constexpr std::size_t vtkScenePlanRule::ManyProps;
constexpr vtkIdType vtkScenePlanRule::HugeMesh;
constexpr double vtkScenePlanRule::MaxTranslucentForActors;
constexpr double vtkScenePlanRule::MinInViewForNoCulling;
constexpr double vtkScenePlanRule::OcclusionDepthComplexity;
constexpr double vtkScenePlanRule::MaxOverlapToSplit;
constexpr std::size_t vtkScenePlanRule::MinPartsToSplit;
constexpr std::size_t vtkScenePlanRule::MaxPartsToSplit;
constexpr std::size_t vtkScenePlanRule::OverlapTestsPerPart;

std::string vtkScenePlanFacts::Summary() const
{
  std::ostringstream text;
  text << parts << (parts == 1 ? " part, " : " parts, ") << triangles << " triangles, "
       << std::setprecision(3) << 100.0 * translucentFraction << " % translucent, " << rooms
       << " rooms, " << portals << " portals";
  if (inView >= 0.0)
    text << ", " << 100.0 * inView << " % of the triangles in view";
  if (depthComplexity >= 0.0)
    text << ", estimated depth complexity " << depthComplexity;
  if (translucentOverlap >= 0.0)
    text << ", " << 100.0 * translucentOverlap << " % of the triangles in translucent parts ("
         << translucentParts << ") whose boxes overlap another's";
  return text.str();
}

bool vtkScenePlanRule::SplitsIntoParts(const vtkScenePlanFacts& facts)
{
  return !facts.fixedActors && facts.translucentFraction > 0.0 && facts.parts <= MaxPartsToSplit &&
    facts.translucentParts >= MinPartsToSplit &&
    static_cast<double>(facts.triangles) >= SmallPartTriangles * static_cast<double>(facts.parts) &&
    facts.translucentOverlap >= 0.0 && facts.translucentOverlap < MaxOverlapToSplit;
}

vtkScenePlanChoice vtkScenePlanRule::ChooseCulling(const vtkScenePlanFacts& facts)
{
  vtkScenePlanChoice plan;
  const bool rooms = facts.rooms > 0 && facts.portals > 0;
  const bool opaque = facts.translucentFraction == 0.0;
  std::ostringstream why;
  if (rooms)
  {
    plan.Method = "portals";
    why << facts.rooms << " rooms and " << facts.portals
        << " portals: cells and portals skip the rooms the eye cannot see through them";
  }
  else if (facts.parts >= ManyProps && !facts.fixedActors && opaque &&
    static_cast<double>(facts.triangles) < SmallPartTriangles * static_cast<double>(facts.parts))
  {
    const double perPart = static_cast<double>(facts.triangles) / static_cast<double>(facts.parts);
    why << facts.parts << " opaque parts of " << std::setprecision(3) << perPart
        << " triangles on average (< " << SmallPartTriangles
        << "): an actor per part costs more than its triangles, so they are drawn as one mesh";
    if (facts.triangles >= ChunkOcclusionTriangles)
    {
      const bool hidden = facts.depthComplexity >= OcclusionDepthComplexity;
      plan.Method = hidden ? "chunked-occlusion" : "chunked";
      plan.ChunkSize = SmallPartChunkSize;
      why << " in chunks of " << SmallPartChunkSize << " triangles (" << facts.triangles
          << " triangles >= " << ChunkOcclusionTriangles << ")";
      if (hidden)
        why << ", chunks hidden behind nearer ones culled (estimated depth complexity "
            << facts.depthComplexity << " >= " << OcclusionDepthComplexity << ")";
    }
    else
    {
      plan.Method = "none";
      why << ", whole (" << facts.triangles << " triangles < " << ChunkOcclusionTriangles
          << ": culling its chunks does not pay)";
    }
  }
  else if (facts.parts >= ManyProps &&
    (facts.fixedActors ||
      ((facts.translucentFraction <= MaxTranslucentForActors || SplitsIntoParts(facts)) &&
        facts.inView < MinInViewForNoCulling)))
  {
    const double opaqueDepth = facts.depthComplexity * (1.0 - facts.translucentFraction);
    if (opaqueDepth >= OcclusionDepthComplexity)
    {
      plan.Method = "occlusion";
      why << facts.parts << " parts (>= " << ManyProps
          << ") and an estimated opaque depth complexity of " << std::setprecision(3) << opaqueDepth
          << " (>= " << OcclusionDepthComplexity
          << "): most of what is in view is hidden, so parts hidden behind nearer opaque ones "
             "are culled too";
    }
    else
    {
      plan.Method = "octree";
      if (facts.fixedActors)
        why << facts.parts << " actors (>= " << ManyProps
            << "), drawn as they are: the BVH culls whole subtrees, and costs less per frame "
               "than VTK's frustum coverage culler even when everything is in view";
      else
        why << facts.parts << " parts (>= " << ManyProps
            << "): one actor per part, culled by the BVH a whole subtree at a time";
    }
  }
  else if (facts.triangles >= HugeMesh && opaque)
  {
    plan.Method = "chunked";
    why << facts.triangles << " triangles (>= " << HugeMesh << ") in " << facts.parts
        << (facts.parts == 1 ? " part" : " parts")
        << ", opaque: chunks of the one mesh are culled inside its buffers";
  }
  else
  {
    plan.Method = "none";
    if (facts.parts >= ManyProps && facts.inView >= MinInViewForNoCulling)
      why << facts.parts << " parts, but the first camera sees " << std::setprecision(3)
          << 100.0 * facts.inView << " % of the triangles (>= " << 100.0 * MinInViewForNoCulling
          << " %): culling would draw nearly all of them as many actors";
    else if (facts.parts >= ManyProps)
      why << facts.parts << " parts but " << std::setprecision(3)
          << 100.0 * facts.translucentFraction << " % translucent (> "
          << 100.0 * MaxTranslucentForActors
          << " %): one mesh in BSP order draws faster than sorting that many actors' "
             "fragments across actors";
    else if (facts.triangles >= HugeMesh)
      why << facts.triangles << " triangles but translucent (" << std::setprecision(3)
          << 100.0 * facts.translucentFraction
          << " %): chunked drawing would break the sorted order, so everything is drawn";
    else
      why << facts.parts << (facts.parts == 1 ? " part" : " parts") << " (< " << ManyProps
          << ") and " << facts.triangles << " triangles (< " << HugeMesh << ")"
          << (opaque ? ", opaque" : "") << ": drawing everything costs less than culling";
  }
  plan.Reason = why.str();
  return plan;
}

vtkScenePlanChoice vtkScenePlanRule::ChooseTranslucency(
  const vtkScenePlanFacts& facts, bool chunked, bool severalActors, std::size_t actors)
{
  if (facts.translucentFraction <= 0.0)
  {
    return { "none", "the scene is opaque: no sorting needed" };
  }
  if (chunked)
  {
    return { "oit",
      "translucent, but chunked drawing reorders the polygons: VTK's weighted OIT "
      "(order independent, approximate)" };
  }
  if (severalActors)
  {
    return { "multi-actor",
      "translucent polygons in " + std::to_string(actors) +
        " actors (prop culling): exact order across actors with vtkBSPTranslucentPass" };
  }
  if (SplitsIntoParts(facts))
  {
    std::ostringstream why;
    why << "the mesh's " << facts.translucentParts << " translucent parts overlap little ("
        << std::setprecision(3) << 100.0 * facts.translucentOverlap
        << " % of the triangles are in translucent parts whose boxes overlap another's, < "
        << 100.0 * MaxOverlapToSplit
        << " %): split into one actor per part, ordered as wholes by vtkBSPTranslucentPass "
           "(polygons split only where parts cannot be separated)";
    return { "multi-actor", why.str() };
  }
  // The mapper, not the filter: the same exact order, but only the index buffer changes per
  // frame (scripts/culling-report.py, docs/auto-vs-fixed.csv: 1.1-1.3x faster frames).
  return { "bsp-mapper",
    "the scene has translucent polygons: exact order with the BSP tree, rewritten in the "
    "index buffer only (vtkBSPSortedPolyDataMapper)" };
}

double vtkScenePlanRule::MeasureView(const std::vector<vtkScenePlanPartBox>& parts,
  vtkCamera* camera, double aspect, double* depthComplexity)
{
  vtkIdType total = 0;
  for (const vtkScenePlanPartBox& part : parts)
    total += part.Triangles;
  if (total == 0 || !camera)
  {
    return 1.0; // nothing to see (depthComplexity left unmeasured)
  }
  double planes[24]; // left, right, bottom, top, near, far: ax + by + cz + d >= 0 inside
  camera->GetFrustumPlanes(aspect, planes);
  vtkMatrix4x4* projection = camera->GetCompositeProjectionTransformMatrix(aspect, -1, 1);
  double covered = 0.0;
  double bounding[4] = { 1.0, -1.0, 1.0, -1.0 }; // of the in-view rectangles, x0 x1 y0 y1
  vtkIdType inView = 0;
  for (const vtkScenePlanPartBox& part : parts)
  {
    const bool finite =
      std::all_of(part.Box, part.Box + 6, [](double v) { return !std::isnan(v); });
    bool outside = false;
    for (int k = 0; k < 4 && !outside && finite; ++k)
    {
      const double* plane = planes + 4 * k;
      double distance = plane[3];
      for (int a = 0; a < 3; ++a)
        distance += plane[a] * (plane[a] >= 0.0 ? part.Box[2 * a + 1] : part.Box[2 * a]);
      outside = distance < 0.0;
    }
    inView += outside ? 0 : part.Triangles;
    if (!outside && finite && depthComplexity)
    {
      // Screen rectangle in normalized device coordinates ([-1, 1]^2, area 4).
      double x0 = 1.0, x1 = -1.0, y0 = 1.0, y1 = -1.0;
      bool whole = false;
      for (int k = 0; k < 8 && !whole; ++k)
      {
        const double p[4] = { part.Box[k & 1], part.Box[2 + ((k >> 1) & 1)],
          part.Box[4 + ((k >> 2) & 1)], 1.0 };
        double q[4];
        projection->MultiplyPoint(p, q);
        if (!(q[3] > 0.0))
        {
          whole = true;
          break;
        }
        x0 = std::min(x0, q[0] / q[3]);
        x1 = std::max(x1, q[0] / q[3]);
        y0 = std::min(y0, q[1] / q[3]);
        y1 = std::max(y1, q[1] / q[3]);
      }
      if (whole)
      {
        x0 = y0 = -1.0;
        x1 = y1 = 1.0;
      }
      x0 = std::max(x0, -1.0);
      y0 = std::max(y0, -1.0);
      x1 = std::min(x1, 1.0);
      y1 = std::min(y1, 1.0);
      if (x1 > x0 && y1 > y0)
      {
        covered += (x1 - x0) * (y1 - y0);
        bounding[0] = std::min(bounding[0], x0);
        bounding[1] = std::max(bounding[1], x1);
        bounding[2] = std::min(bounding[2], y0);
        bounding[3] = std::max(bounding[3], y1);
      }
    }
  }
  if (depthComplexity)
  {
    const double area = bounding[1] > bounding[0] && bounding[3] > bounding[2]
      ? (bounding[1] - bounding[0]) * (bounding[3] - bounding[2])
      : 0.0;
    *depthComplexity = area > 0.0 ? covered / area : 0.0;
  }
  return static_cast<double>(inView) / static_cast<double>(total);
}

double vtkScenePlanRule::MeasureOverlap(const std::vector<vtkScenePlanPartBox>& parts)
{
  std::vector<const vtkScenePlanPartBox*> boxes; // the translucent ones
  double triangles = 0.0, translucentTriangles = 0.0;
  for (const vtkScenePlanPartBox& part : parts)
  {
    triangles += static_cast<double>(part.Triangles);
    const double* b = part.Box;
    if (part.Translucent && std::all_of(b, b + 6, [](double v) { return std::isfinite(v); }) &&
      b[0] <= b[1] && b[2] <= b[3] && b[4] <= b[5])
    {
      boxes.push_back(&part);
      translucentTriangles += static_cast<double>(part.Triangles);
    }
  }
  const std::size_t n = boxes.size();
  if (n < 2 || translucentTriangles <= 0.0)
    return 0.0;
  // The sweep axis: where the boxes' extents cover the least of their span, so the fewest pairs
  // overlap along it.
  int axis = 0;
  double bestCover = VTK_DOUBLE_MAX;
  double magnitude = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    double lo = VTK_DOUBLE_MAX, hi = -VTK_DOUBLE_MAX, extents = 0.0;
    for (const vtkScenePlanPartBox* part : boxes)
    {
      lo = std::min(lo, part->Box[2 * a]);
      hi = std::max(hi, part->Box[2 * a + 1]);
      extents += part->Box[2 * a + 1] - part->Box[2 * a];
    }
    magnitude = std::max({ magnitude, std::abs(lo), std::abs(hi) });
    const double cover = hi > lo ? extents / (hi - lo) : VTK_DOUBLE_MAX;
    if (cover < bestCover)
    {
      bestCover = cover;
      axis = a;
    }
  }
  // Separated along an axis: one box ends where the other begins, up to the rounding of the
  // coordinates and a millionth of the boxes' extents.
  const double rounding = 1e-12 * magnitude;
  const auto overlap = [rounding](const double* p, const double* q)
  {
    for (int a = 0; a < 3; ++a)
    {
      const double tolerance =
        rounding + 1e-6 * std::max(p[2 * a + 1] - p[2 * a], q[2 * a + 1] - q[2 * a]);
      if (p[2 * a + 1] - q[2 * a] <= tolerance || q[2 * a + 1] - p[2 * a] <= tolerance)
        return false;
    }
    return true;
  };
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i)
    order[i] = i;
  std::sort(order.begin(), order.end(),
    [&boxes, axis](std::size_t p, std::size_t q)
    { return boxes[p]->Box[2 * axis] < boxes[q]->Box[2 * axis]; });
  std::vector<char> overlapping(n, 0);
  std::vector<std::size_t> active; // swept boxes that may still reach the next ones
  const std::size_t budget = OverlapTestsPerPart * n;
  std::size_t tests = 0, swept = 0;
  while (swept < n && tests <= budget)
  {
    const std::size_t i = order[swept++];
    const double start = boxes[i]->Box[2 * axis];
    active.erase(
      std::remove_if(active.begin(), active.end(),
        [&boxes, axis, start](std::size_t j) { return boxes[j]->Box[2 * axis + 1] <= start; }),
      active.end());
    for (const std::size_t j : active)
    {
      ++tests;
      if (overlap(boxes[i]->Box, boxes[j]->Box))
        overlapping[i] = overlapping[j] = 1;
    }
    active.push_back(i);
  }
  // Of the swept boxes' triangles, the overlapping ones' share, scaled to the whole scene.
  double sweptTriangles = 0.0, overlappingTriangles = 0.0;
  for (std::size_t k = 0; k < swept; ++k)
  {
    const auto t = static_cast<double>(boxes[order[k]]->Triangles);
    sweptTriangles += t;
    overlappingTriangles += overlapping[order[k]] ? t : 0.0;
  }
  const double share = sweptTriangles > 0.0 ? overlappingTriangles / sweptTriangles : 0.0;
  return share * translucentTriangles / triangles;
}
