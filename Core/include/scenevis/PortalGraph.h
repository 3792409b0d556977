#pragma once
/**
 * @file PortalGraph.h
 * @brief Cells-and-portals scene description, its validation and eye location.
 *
 * The model (Teller & Sequin 1991; Luebke & Georges 1995) is split into cells ("rooms") joined by
 * portals (openings: doors, windows, stair holes). Everything a room contains is seen from another
 * room only through a chain of portals, which is what the traversal (PortalTraversal.h) and the
 * potentially visible sets (PortalPvs.h) exploit.
 *
 * Scene description (CellSceneInput; the VTK layer reads the same from VTK XML PolyData):
 * - geometry: polygons, each with a room id (>= 0) or kOutsideRoom (-1, the outside world:
 *   facade, roof, terrain). Rooms need not be convex, and may overlap (then an eye in both is
 *   treated as in both).
 * - portals: one planar polygon each (>= 3 points, convex or concave) with the two room ids it
 *   joins (either may be kOutsideRoom).
 *
 * Assumption behind every guarantee: a room's boundary is closed except at its portals (rays
 * leave a room only through one of its portals), and the camera's near plane does not reach
 * through a wall (the eye is farther from walls than the near-plane distance; eyes closer to a
 * portal than that are handled, see locate()).
 *
 * Validation (build()): problems are collected in a PortalGraphReport and the graph is made
 * conservative rather than rejected:
 * - a portal with fewer than 3 points, non-finite points or zero area: error, dropped (nothing is
 *   seen through a zero-area opening);
 * - a dangling room id (< -1, or naming a room that has no geometry and no other portal when the
 *   room count is given): error; the valid room of that portal is marked leaky, and a traversal
 *   that reaches a leaky room falls back to frustum-only culling (anything may be behind it);
 * - a portal joining a room to itself: warning, dropped (it can only show that room);
 * - a non-planar portal (a vertex farther than 1e-3 of its size from its plane): warning; it is
 *   kept as "wide open": the view passes through it un-narrowed;
 * - a concave or self-intersecting portal: info; its convex hull in its plane is used;
 * - duplicate portals (same rooms, same points within tolerance): warning, one is kept.
 */

#include "scenevis/PolygonMesh.h"

#include <glm/ext/vector_int3.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace scenevis
{
namespace scenes
{
struct BuildingScene;
}

namespace portals
{

/// Room id of the outside world in the input (the graph maps it to node outsideNode()).
constexpr std::int32_t kOutsideRoom = -1;

/// One opening in the input: a planar polygon and the two rooms it joins.
struct PortalDesc
{
  std::vector<glm::dvec3> polygon;
  std::int32_t roomA = 0;
  std::int32_t roomB = 0;
};

/// The input of PortalGraph::build().
struct CellSceneInput
{
  /// Geometry; may be null (then rooms are located by their portals' and boxes' bounds only).
  const PolygonMesh* mesh = nullptr;
  /// Per polygon of `mesh`: its room, or kOutsideRoom. Ids < -1 are reported and ignored.
  std::vector<std::int32_t> roomOfPolygon;
  std::vector<PortalDesc> portals;
  /// Number of rooms (ids 0 .. roomCount-1); < 0: one more than the largest id in use.
  std::int32_t roomCount = -1;
};

/// One problem found by PortalGraph::build().
struct PortalIssue
{
  enum class Severity
  {
    Info,
    Warning,
    Error
  };
  Severity severity = Severity::Warning;
  std::int32_t portal = -1; ///< Input portal index, or -1.
  std::int32_t room = -1;   ///< Room id concerned, or -1.
  std::string message;
};

struct PortalGraphReport
{
  std::vector<PortalIssue> issues;
  std::size_t count(PortalIssue::Severity severity) const;
  std::size_t errors() const { return count(PortalIssue::Severity::Error); }
  std::size_t warnings() const { return count(PortalIssue::Severity::Warning); }
  /// All issues, one line each ("error: portal 3: ...").
  std::string summary() const;
};

/// A portal of the graph: a planar convex polygon between two nodes.
struct GraphPortal
{
  std::int32_t input = -1; ///< Index in CellSceneInput::portals.
  std::int32_t nodeA = 0;  ///< Node ids (rooms, or PortalGraph::outsideNode()).
  std::int32_t nodeB = 0;
  /// Convex hull of the input polygon in its plane, counter-clockwise around `plane.xyz`.
  std::vector<glm::dvec3> hull;
  /// Unit normal and offset: dot(plane.xyz, p) + plane.w = signed distance.
  glm::dvec4 plane{ 0.0, 0.0, 1.0, 0.0 };
  Box bounds;
  glm::dvec3 centroid{ 0.0 };
  /// False for a non-planar input: traversals pass the view through it un-narrowed.
  bool planar = true;

  std::int32_t other(std::int32_t node) const { return node == nodeA ? nodeB : nodeA; }
};

/// A node of the graph: a room, or the outside world.
struct GraphRoom
{
  /// Bounds of the room's polygons and portals (empty for a room without either).
  Box bounds;
  /// Portals (indices in PortalGraph::portals()) with this room on one side.
  std::vector<std::uint32_t> portals;
  /// Boundary polygons for the inside test: [first, first + count) in the graph's polygon store.
  std::uint32_t firstPolygon = 0;
  std::uint32_t polygonCount = 0;
  /// A portal of this room names a room that does not exist: anything may be seen through it.
  bool leaky = false;
};

/// Where an eye is: the nodes a traversal must start from.
struct EyeLocation
{
  /// Nodes containing the eye (several for overlapping rooms or an eye in / near a portal).
  std::vector<std::int32_t> nodes;
  /// True when the eye is in no room and not outside the building: frustum-only culling.
  bool unknown = false;
  /// Nodes added because the eye is within the near distance of one of their portals.
  std::size_t nearPortalNodes = 0;
};

/// How an eye that is in no room is treated.
enum class OutsidePolicy
{
  /// Outside the bounds of all rooms: start from the outside node (enter through exterior
  /// portals); in no room but within the building's bounds (inside a wall, a gap): frustum only.
  ExteriorPortals,
  /// In no room: always frustum only.
  FrustumOnly
};

/**
 * Rooms and portals as a graph, with a robust inside test per room. Immutable after build();
 * all queries are const and thread-safe.
 */
class PortalGraph
{
public:
  /// Validate @p input (see the file comment) and build the graph. Never throws for bad data.
  static PortalGraph build(const CellSceneInput& input, PortalGraphReport* report = nullptr);

  /// Rooms are nodes 0 .. roomCount()-1; the outside world is node roomCount().
  std::int32_t roomCount() const { return this->RoomCount; }
  std::int32_t outsideNode() const { return this->RoomCount; }
  std::int32_t nodeCount() const { return this->RoomCount + 1; }
  /// Node of an input room id (kOutsideRoom -> outsideNode()); -1 for an invalid id.
  std::int32_t nodeOf(std::int32_t roomId) const;

  const std::vector<GraphRoom>& rooms() const { return this->Rooms; }
  const std::vector<GraphPortal>& portals() const { return this->Portals; }
  /// Bounds of all rooms (not the outside geometry).
  const Box& buildingBounds() const { return this->BuildingBounds; }
  /// Absolute geometric tolerance (1e-9 of the scene size, at least 1e-12).
  double tolerance() const { return this->Tolerance; }
  bool anyLeaky() const { return this->AnyLeaky; }
  /// A hash of the graph's topology and portal geometry (PVS files carry it).
  std::uint64_t fingerprint() const { return this->Fingerprint; }

  /**
   * Whether @p p is inside room @p room: its bounds (within tolerance) contain p and a majority of
   * three rays from p cross the room's boundary (its polygons, minus those covering one of its
   * portals such as glass panes, plus its portals) an odd number of times. Rooms without
   * polygons use their bounds alone. The outside node is never "inside" by this test.
   */
  bool inside(std::int32_t room, const glm::dvec3& p) const;

  /**
   * The nodes a traversal starts from for an eye at @p eye: every room inside() says contains it
   * (the union for overlapping rooms), plus both nodes of every portal closer than @p nearDistance
   * to the eye (an eye standing in a doorway, or whose near plane reaches through the opening).
   * In no room: see OutsidePolicy.
   *
   * Cost: sub-linear in the number of rooms and portals. A uniform grid over the building (about
   * one cell per room, built by build()) lists the rooms and portals whose bounds touch each
   * cell; only the rooms listed in the eye's cell get the ray-parity test (which reads only the
   * polygons whose projection along the ray holds the eye, see RayGrid), and only the portals
   * of the cells within @p nearDistance get the distance test.
   */
  EyeLocation locate(const glm::dvec3& eye,
    double nearDistance,
    OutsidePolicy policy = OutsidePolicy::ExteriorPortals) const;

  /// Grid cells per axis of the locate() grid (statistics and tests).
  glm::ivec3 gridDimensions() const { return this->Grid.dims; }

private:
  /// Uniform grid over boxes: per cell, the items whose (tolerance-grown) box touches it (CSR).
  struct BoxGrid
  {
    Box bounds;
    glm::ivec3 dims{ 0, 0, 0 };
    glm::dvec3 inverseCell{ 0.0 };
    std::vector<std::uint32_t> roomStart, rooms;     ///< size cells + 1, and room ids
    std::vector<std::uint32_t> portalStart, portals; ///< size cells + 1, and portal indices
    bool empty() const { return this->dims.x == 0; }
    /// Cell index range [lo, hi] per axis touched by [a, b] (clamped); false if outside.
    bool cellRange(const glm::dvec3& a, const glm::dvec3& b, glm::ivec3& lo, glm::ivec3& hi) const;
  };
  void buildGrid();

  struct BoundaryPolygon
  {
    std::uint32_t first = 0; ///< Into PolygonPoints.
    std::uint32_t count = 0;
    glm::dvec4 plane{ 0.0 };
    int axis = 2; ///< Dominant axis of the normal (dropped for the 2D point-in-polygon test).
    /// The points' range in the second kept axis (y): a point below it or on its top crosses no
    /// edge. Beyond xBeyond in the first (x: the range's top plus far more than the crossing's
    /// rounding) a point has no crossing to its right.
    double yLo = 0.0, yHi = 0.0, xBeyond = 0.0;
  };
  /// Crossings (mod 2) of the ray from @p p along ray direction @p direction (src/PortalRays.h)
  /// with room @p room's boundary polygons.
  int parity(std::int32_t room, const glm::dvec3& p, int direction) const;

  /**
   * Per room and ray direction: the room's boundary polygons bucketed by their bounds projected
   * along the direction (grown by a margin far above the rounding of the crossing test), in a
   * uniform 2D grid. A ray's line meets a polygon only where the polygon's projection holds the
   * ray's start, so parity() reads only the polygons of that cell: the same crossings, for
   * rooms of thousands of polygons (real levels' merged rooms). Rooms with fewer polygons than
   * kRayGridMinPolygons have no grid (cells 0) and every polygon is read.
   */
  struct RayGrid
  {
    double u0 = 0.0, v0 = 0.0, inverseCell = 0.0;
    int nu = 0, nv = 0;
    std::vector<std::uint32_t> start, polygons; ///< CSR per cell (u + nu v): polygon indices
  };
  static constexpr std::uint32_t kRayGridMinPolygons = 32;
  void buildRayGrids();

  std::int32_t RoomCount = 0;
  std::vector<GraphRoom> Rooms;
  std::vector<GraphPortal> Portals;
  std::vector<BoundaryPolygon> Polygons;
  std::vector<glm::dvec3> PolygonPoints;
  Box BuildingBounds;
  BoxGrid Grid;
  std::vector<RayGrid> RayGrids; ///< 3 per room (src/PortalRays.h's directions)
  double Tolerance = 1e-12;
  bool AnyLeaky = false;
  std::uint64_t Fingerprint = 0;
};

/// The cells-and-portals input of a generated building (geometry, room ids and its portals).
CellSceneInput cellSceneOf(const scenes::BuildingScene& building);

/// Convex hull of coplanar points projected on the plane with unit normal @p normal,
/// counter-clockwise around it (Andrew's monotone chain). Collinear points are dropped.
std::vector<glm::dvec3> planarConvexHull(const std::vector<glm::dvec3>& points,
  const glm::dvec3& normal);

} // namespace portals
} // namespace scenevis
