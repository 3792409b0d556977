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
  return text.str();
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
      (facts.translucentFraction <= MaxTranslucentForActors &&
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
  bool translucent, bool chunked, bool severalActors, std::size_t actors)
{
  if (!translucent)
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
