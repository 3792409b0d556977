#pragma once
/**
 * @file PortalTraversal.h
 * @brief Per-frame cells-and-portals visibility: which rooms, and which boxes in them, can be seen.
 *
 * The view is clipped through the portals the eye can see (Luebke & Georges 1995), with an
 * explicit work list (no recursion, no depth limit). A "region" is the set of view rays that may
 * reach a room through one chain of portals. Two narrowing modes:
 *
 * - ScreenRectangles (Luebke-Georges): a region is an axis-aligned rectangle in normalised device
 *   coordinates. Crossing a portal intersects it with the screen bounding rectangle of the portal
 *   (clipped at the eye plane and the far plane). Cheap; loose for oblique portals.
 * - ExactFrustum: a region is a convex cone from the eye: the rectangle plus one plane through the
 *   eye and each edge of the portal polygon after clipping it by the current region. Tighter.
 *
 * Guarantee (both modes): every view ray that reaches a room's geometry through portals lies in a
 * region of that room, so culling objects with boxVisible() never removes a visible object
 * (assumptions in PortalGraph.h). Details that keep it so:
 * - The work list follows every portal from every region, whatever the path (no "visited" stop):
 *   a room reached twice by different paths gets the union of its regions, and cycles terminate
 *   because a region contained in one the room already has is not expanded again (a ray crosses a
 *   portal plane only once, so walking back adds nothing new and is absorbed this way).
 * - A room with more than maxRegionsPerRoom (16) regions has them merged into their bounding
 *   rectangle (bigger, so still conservative); a room merged 4 times in a frame gets the whole
 *   view as its region (merged rectangles, which have no entry plane, can otherwise creep by the
 *   clipping slack round a cycle of rooms for millions of merges). Together these bound the work
 *   per frame: a room attaches at most (maxRegionsPerRoom + 1) x 5 regions.
 * - The work list expands the widest region first (the area of its screen rectangle): a room
 *   reached by several paths then tends to get its widest region before the narrower ones, which
 *   are found contained and not expanded, and rooms fill up to the merge bound less often.
 *   Freedoom MAP12 from its player starts, against the last-in first-out order with 8 regions per
 *   room: 385 -> 110 regions expanded and 25 -> 0 merges a frame, 89.8 -> 46.8 rooms reached.
 *   Any order reaches every room some ray reaches.
 * - Portals are clipped at the eye plane, not the near plane: a ray may cross a doorway before the
 *   near plane and still show what is behind it. A portal closer to the eye than the near-plane
 *   corners (the eye stands in it) makes both its rooms start rooms with the whole frustum; a
 *   portal whose plane passes through the eye (seen edge-on) or that is not planar passes the
 *   region on un-narrowed.
 * - Parallel projection: the rays are parallel lines starting on the near rectangle, so the
 *   near plane (not an eye plane) clips portals, and exact narrowing uses the planes through each
 *   portal edge that contain the view direction (screen rectangles work unchanged); a portal
 *   parallel to the view direction is edge-on. Rays start outside the building when the near
 *   rectangle's box is outside the building's bounds (the usual orthographic overview from
 *   outside): the traversal starts from the outside node and enters through exterior portals.
 * - Fallback to frustum-only culling (every room visible, boxes tested against the view frustum):
 *   eye in no room (OutsidePolicy), a leaky room reached, a parallel projection whose near
 *   rectangle touches the building's bounds (it may cut through walls into several rooms and
 *   wall voids) or with the FrustumOnly outside policy, or an invalid view matrix.
 *
 * - Entry planes (portal-plane culling): every ray of a region made by crossing planar portal P
 *   has crossed P's plane, away from the eye, and a ray crosses a plane once. So from that region
 *   P itself is never crossed again, and a portal entirely on the eye's side of P's plane (beyond
 *   the slack) cannot be reached; in exact mode the next portal is also clipped to the far side
 *   of P's plane (with the slack). Regions passed on through an edge-on or non-planar portal keep
 *   their entry plane (their rays still crossed it); merged and start regions have none. A
 *   region counts as contained in one with an entry plane only if it came through the same
 *   portal or its clipped portal lies beyond that plane (else its rays may reach portals the
 *   other's may not).
 * - Per frame, each portal is clipped by the eye plane and the far plane once, on first use, and
 *   kept for every region that tests it (the per-frame cache of clipped portal polygons), with
 *   its screen rectangle.
 * - Containment is tested before work, not after: a crossing whose largest possible region (the
 *   cached portal within the parent's rectangle; clipping keeps a polygon inside its input's
 *   hull) lies in a region the room already has stops before any clipping, and a new region's
 *   planes are made only once it is known not to lie in one. Planes that keep all of a polygon
 *   do not copy it. On open levels most crossings end in containment (Freedoom MAP12 from its
 *   player starts: 838 of 1,281 a frame).
 *
 * Tolerances: planes are compared with a slack of 10x PortalGraph::tolerance() and rectangles are
 * grown by 1e-9 in NDC, always in the direction that keeps more. A region counts as contained in
 * another (and is not expanded) when its portal polygon is within 10 slacks of the other's edge
 * planes: each crossing may grow a region by one slack, and a region that went round a cycle of
 * rooms must still be recognised (1e-7 of the scene size: far below a pixel).
 */

#include "scenevis/Frustum.h"
#include "scenevis/PortalGraph.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace scenevis
{
namespace portals
{

class PortalPvs;

enum class NarrowingMode
{
  ScreenRectangles, ///< Luebke-Georges screen-space rectangles.
  ExactFrustum      ///< Planes through the eye and the clipped portal's edges.
};

/// The camera of a frame.
struct PortalView
{
  /// Clip-from-world matrix, OpenGL conventions (see Frustum.h).
  glm::dmat4 clipFromWorld{ 1.0 };
  /// The eye (camera position).
  glm::dvec3 eye{ 0.0 };
  bool parallel = false;

  /// From VTK's row-major composite projection matrix (vtkMatrix4x4::GetData()).
  static PortalView fromRowMajor(const double m[16], const glm::dvec3& eye, bool parallel);
};

struct TraversalOptions
{
  NarrowingMode mode = NarrowingMode::ExactFrustum;
  OutsidePolicy outside = OutsidePolicy::ExteriorPortals;
  /// Regions kept per room before they are merged into their bounding rectangle. A merged
  /// rectangle has no edge planes: it lets through more than its regions did, and the rooms
  /// behind it get wider regions in turn. 16 (8 before): Freedoom MAP12 from its player starts
  /// reaches 46.8 rooms instead of 89.8 with 0 merges, at 1.02M instead of 2.51M instructions a
  /// traversal (BENCHMARKS.md, "The exact traversal: the widest region first").
  std::size_t maxRegionsPerRoom = 16;
  /// Distance below which the eye "stands in" a portal; < 0: the distance from the eye to the
  /// near-plane corners of the view (what the near plane can reach).
  double nearDistance = -1.0;
};

/// Why a frame fell back to frustum-only culling.
enum class Fallback
{
  None,
  EyeInNoRoom,
  LeakyRoom,
  ParallelProjection, ///< Parallel projection with the near rectangle inside the building's bounds
  InvalidView
};

/// Per-frame statistics.
struct FrameStats
{
  std::size_t startRooms = 0;       ///< Nodes the traversal started from.
  std::size_t roomsVisited = 0;     ///< Nodes with at least one region (incl. the outside).
  std::size_t regionsExpanded = 0;  ///< Work-list entries processed.
  std::size_t portalsTested = 0;    ///< Portal crossings attempted.
  std::size_t portalsTraversed = 0; ///< Crossings that produced a new region.
  std::size_t regionsSubsumed = 0;  ///< New regions contained in an existing one (not expanded).
  std::size_t regionsMerged = 0;    ///< Merges into a bounding rectangle.
  std::size_t portalsBehind = 0;    ///< Crossings skipped by the entry plane (or its own portal).
  Fallback fallback = Fallback::None;
  // Filled by cullObjects():
  std::size_t objectsDrawn = 0;
  std::size_t objectsTotal = 0;
  std::uint64_t trianglesDrawn = 0;
  std::uint64_t trianglesTotal = 0;
};

/// Something to cull: a box in a room (node id of the graph; -1: in no room, frustum only).
struct PortalObject
{
  std::int32_t node = -1;
  Box bounds;
  std::uint64_t triangles = 0;
};

/**
 * The traversal and its result for one frame. Keep one instance and call run() every frame: it
 * reuses its buffers (no allocation in steady state).
 */
class PortalTraversal
{
public:
  /// Traverse @p graph for @p view. The graph must outlive the queries of this frame.
  void run(const PortalGraph& graph, const PortalView& view, const TraversalOptions& options);

  /// PVS mode: the union of the PVS of the eye's rooms, each room with the whole frustum.
  void runPvs(const PortalGraph& graph,
    const PortalPvs& pvs,
    const PortalView& view,
    const TraversalOptions& options);

  /// Frustum-only: every node visible, boxes tested against the view frustum.
  void runFrustumOnly(const PortalGraph& graph, const PortalView& view);

  /// Whether node @p node (room, or the outside node) may be seen at all.
  bool nodeVisible(std::int32_t node) const;

  /// Whether a box in node @p node may be seen (node < 0 or unknown: frustum test only).
  bool boxVisible(std::int32_t node, const Box& box) const;

  /// Nodes that may be seen, in the order they were first reached.
  const std::vector<std::int32_t>& visibleNodes() const { return this->Visible; }

  /// Cull @p objects: visible[i] = 1 if object i may be seen; fills the object counts of stats().
  void cullObjects(const std::vector<PortalObject>& objects, std::vector<std::uint8_t>& visible);

  const FrameStats& stats() const { return this->Stats; }
  const culling::Frustum& frustum() const { return this->ViewFrustum; }
  /// The rectangles (xmin, ymin, xmax, ymax in NDC) of a node's regions, for drawing/debugging.
  std::vector<glm::dvec4> regionRectangles(std::int32_t node) const;

private:
  struct Region
  {
    glm::dvec4 rect;               ///< xmin, ymin, xmax, ymax (NDC)
    std::uint32_t firstPlane = 0;  ///< Into Planes: 4 rectangle planes, then edge planes.
    std::uint32_t planeCount = 0;
    std::uint32_t firstVertex = 0; ///< Into Vertices: the clipped portal (exact mode).
    std::uint32_t vertexCount = 0;
    std::uint32_t edgePlanes = 0;
    /// The planar portal whose crossing made it (-1: none), and that portal's plane facing away
    /// from the eye (the rays' side after the crossing).
    std::int32_t via = -1;
    glm::dvec4 entry{ 0.0 };
  };
  /// A portal clipped by the eye and far planes, once per frame (stamp = the frame's).
  struct ClippedPortal
  {
    std::uint32_t stamp = 0;
    std::uint32_t first = 0; ///< Into ClippedVertices.
    std::uint32_t count = 0; ///< < 3: nothing of it in front of the eye and before the far plane.
    glm::dvec4 rect{ 0.0 };  ///< Its NDC bounds (ndcBounds()).
  };
  struct Work
  {
    double area; ///< Of the region's rectangle (NDC): the work list expands the widest first.
    std::int32_t node;
    std::uint32_t region;
    std::uint32_t generation; ///< Stale when the node's regions were merged since.
  };
  /// The work list's heap order: the widest region on top, the oldest of equally wide ones.
  static bool narrower(const Work& a, const Work& b)
  {
    return a.area < b.area || (a.area == b.area && a.region > b.region);
  }
  void push(std::int32_t node, std::uint32_t region, std::uint32_t generation);

  bool begin(const PortalGraph& graph, const PortalView& view, const TraversalOptions& options);
  void fallBack(Fallback why);
  std::uint32_t addRegion(const glm::dvec4& rect);
  bool attach(std::int32_t node, std::uint32_t region, bool checkSubsumed);
  /// What the containment test reads of a region: its rectangle, entry portal and clipped portal.
  struct RegionShape
  {
    glm::dvec4 rect;
    std::int32_t via;
    const glm::dvec3* vertices;
    std::uint32_t vertexCount;
  };
  RegionShape shapeOf(const Region& r) const;
  /// Whether @p inner lies in @p outer (see the tolerances above).
  bool subsumed(const RegionShape& inner, const Region& outer) const;
  /// Whether @p inner lies in one of the regions @p node already has.
  bool subsumedInNode(std::int32_t node, const RegionShape& inner) const;
  /// A portal seen from one of its nodes, with what the first tests read (kept together).
  struct Exit
  {
    glm::dvec3 lo, hi;    ///< The portal's bounds.
    std::uint32_t portal; ///< Index in the graph's portals.
    std::int32_t to;      ///< The node on its other side.
  };
  void buildExits(const PortalGraph& graph);
  /// The planes each exit of one expansion is tested against first, read once per expansion:
  /// the parent's entry plane (when it has one) and its four rectangle planes. A portal whose box
  /// lies wholly beyond one of them (by more than the slack) cannot be crossed. The far, front
  /// and edge planes are left to the clipping, which drops such a portal as surely (tested
  /// before crossing only where no clipping follows: edge-on and non-planar portals).
  struct ExitGate
  {
    glm::dvec4 planes[5];
    int count = 0;
    bool entryFirst = false; ///< planes[0] is the parent's entry plane.
    double slack = 0.0;
    /// The first plane the box (@p lo, @p hi) lies wholly beyond (by more than the slack), or -1.
    int firstBeyond(const glm::dvec3& lo, const glm::dvec3& hi) const;
  };
  ExitGate exitGate(const Region& parent) const;
  /// Cross every exit of the node of @p w that passes the gate of its region.
  void expand(const Work& w);
  /// Cross @p exit from region @p from (@p parent: a copy of it); the exit passed the gate.
  void crossPortal(const Exit& exit, std::uint32_t from, const Region& parent);
  /// The portal clipped by the eye and far planes (cached for the frame).
  const ClippedPortal& clippedPortal(std::uint32_t index);
  glm::dvec4 rectPlane(int side, double value) const;
  /// The NDC bounding rectangle of a polygon in front of the eye, grown by the rectangle slack.
  glm::dvec4 ndcBounds(const glm::dvec3* poly, std::size_t count) const;
  void startRegion(std::int32_t node, bool expand);
  /// The start nodes of a frame (falls back when there are none to trust).
  EyeLocation startNodes(
    const PortalGraph& graph, const PortalView& view, const TraversalOptions& options);

  const PortalGraph* Graph = nullptr;
  TraversalOptions Options;
  PortalView View;
  culling::Frustum ViewFrustum;
  glm::dvec4 Rows[4]{}; ///< Rows of clipFromWorld.
  glm::dvec4 FrontPlane{ 0.0 };
  glm::dvec3 Direction{ 0.0 }; ///< Parallel projection: the (unit) direction of the view rays.
  Box NearBox;                 ///< Parallel projection: bounds of the near rectangle.
  double PlaneSlack = 0.0;
  double NearDistance = 0.0;
  bool FrustumOnly = false;
  FrameStats Stats;

  std::vector<Region> Regions;
  std::vector<glm::dvec4> Planes;
  std::vector<glm::dvec3> Vertices;
  /// Per node: its region ids (a node's list is rebuilt when merged).
  std::vector<std::vector<std::uint32_t>> NodeRegions;
  std::vector<std::uint32_t> NodeGeneration;
  std::vector<std::int32_t> Visible;
  std::vector<Work> WorkList; ///< The work list: a heap by narrower().
  std::vector<glm::dvec3> ClipA, ClipB;
  std::vector<ClippedPortal> Clipped;
  /// Per node, its exits: Exits[ExitStart[n] .. ExitStart[n + 1]) (rebuilt with the graph).
  std::vector<Exit> Exits;
  std::vector<std::uint32_t> ExitStart;
  std::vector<glm::dvec3> ClippedVertices;
  std::uint32_t Frame = 0;
  /// The graph of the previous frame (address, fingerprint and node count): when it is the same
  /// graph, only the nodes it visited are reset.
  const PortalGraph* LastGraph = nullptr;
  std::uint64_t LastFingerprint = 0;
  std::size_t LastNodes = 0;
};

} // namespace portals
} // namespace scenevis
