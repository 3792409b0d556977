#pragma once
/**
 * @file Scenes.h
 * @brief Deterministic demo and test scenes, generated in the VTK-free core.
 *
 * Every generator returns a polygon soup (PolygonMesh) plus per-polygon metadata, so the same
 * scene drives unit tests, benchmarks and the VTK examples without files on disk. Contracts
 * shared by all generators:
 *
 * - Deterministic: the output is a pure function of the arguments (a private splitmix64 stream
 *   seeded by `seed`; never std::random_device or rand()). Same arguments, same machine ->
 *   bit-identical mesh. Different seeds give different scenes where a seed is taken.
 * - Parts are contiguous polygon ranges: Scene::parts[k] covers polygons
 *   [firstPolygon, firstPolygon + polygonCount) and `part[i]` is the index of the part polygon i
 *   is in, so a VTK layer can make one actor per part or one merged mesh with a part-id array.
 * - Closed surfaces (sphere(), sphereGrid(), every cadAssembly() part) are 2-manifold within the
 *   part: every edge is used by exactly two triangles, once in each direction, and all triangles
 *   wind counter-clockwise seen from outside (Newell normals point out). Back-face and
 *   normal-cone culling are therefore valid on them.
 * - Polygons are triangles (spheres, CAD) or planar convex quads (cyclicQuads, building).
 * - Colours are linear RGB in [0, 1]; opacity in (0, 1], 1 = opaque.
 *
 * Limits: point ids and CSR offsets are 32-bit, so a scene holds at most ~1.4e9 triangles; the
 * generators throw std::length_error beyond that and std::invalid_argument on non-positive sizes.
 */

#include "scenevis/PolygonMesh.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace scenevis
{
namespace scenes
{

/// One contiguous polygon range with its appearance.
struct Part
{
  std::string name;
  glm::dvec3 colour{ 1.0, 1.0, 1.0 }; ///< Linear RGB, each in [0, 1].
  double opacity = 1.0;               ///< In (0, 1]; < 1 means the part needs sorting.
  Box bounds;                         ///< Bounds of the part's polygons.
  std::uint32_t firstPolygon = 0;
  std::uint32_t polygonCount = 0;
};

struct Scene
{
  PolygonMesh mesh;
  /// Per polygon: index into `parts`. Size mesh.polygonCount().
  std::vector<std::uint32_t> part;
  std::vector<Part> parts;

  /// True when any part has opacity < 1.
  bool hasTranslucency() const;
};

/// Triangles a fan triangulation of `mesh` yields: sum over polygons of (size - 2).
std::size_t triangleCount(const PolygonMesh& mesh);

// ---------------------------------------------------------------------------------------------
// (a) Spheres: the standard hard translucency scene.
// ---------------------------------------------------------------------------------------------

/**
 * A closed UV sphere of triangles, outward-facing: `slices` meridians and `stacks` latitude bands
 * with single pole points, so it has 2 * slices * (stacks - 1) triangles and
 * slices * (stacks - 1) + 2 points. The resolution is chosen so the count is as close to
 * `triangles` as the formula allows (slices ~ 2 * stacks, at least 3 slices and 2 stacks, so at
 * least 6 triangles). Convex: used as the simplest BSP input (no splits needed).
 */
PolygonMesh sphere(const glm::dvec3& center, double radius, std::size_t triangles);

/// Triangles per sphere so that an n x n x n sphereGrid has about `total` triangles.
std::size_t trianglesPerSphereFor(std::size_t total, int n = 4);

/**
 * n x n x n overlapping translucent spheres on a cubic lattice centred at the origin: sphere
 * (i, j, k) is centred at ((i - (n-1)/2) * spacing, ...), so with the defaults (radius 0.8,
 * spacing 1) every sphere overlaps its 6 neighbours, which makes a per-object sort wrong and a
 * per-triangle sort necessary. Part (i + n*j + n*n*k) is sphere (i, j, k), named "sphere i,j,k",
 * opacity 0.3, colour 0.2 + 0.8 * (i, j, k) / (n - 1) (distinct for every sphere).
 *
 * Sizes: 64 spheres (n = 4) with trianglesPerSphereFor(10'000 / 100'000 / 1'000'000) give
 * 9,984 / 99,712 / 999,936 triangles (within 2 % of the request for >= 1000 per sphere).
 */
Scene sphereGrid(int n = 4,
                 double radius = 0.8,
                 double spacing = 1.0,
                 std::size_t trianglesPerSphere = 320);

// ---------------------------------------------------------------------------------------------
// (b) Small adversarial configurations, laid out to be viewed from +z (camera on the +z axis
//     looking down -z at the origin); they span about [-1.3, 1.3] in x and y.
// ---------------------------------------------------------------------------------------------

/**
 * The classic painter's-algorithm counterexample: three planar quads (thin strips along the
 * edges of an equilateral triangle, each tilted along its length) where quad i overlaps quad
 * i+1 (mod 3) in the projection along z and lies above it (larger z, nearer to a +z viewer)
 * wherever they overlap. "Above" is thus a cycle 0 > 1 > 2 > 0: no order of whole polygons is
 * correct; the quads do not intersect in 3D, so only splitting fixes it. Three parts, one
 * polygon each, red / green / blue, opacity 0.5; all quads face +z (counter-clockwise from +z).
 */
Scene cyclicQuads();

/**
 * Two triangles that pierce each other: an edge of each passes through the interior of the
 * other (they cross along a segment on the line y = 0, z = 0). No order is correct; a BSP must
 * split. Two parts, one triangle each, orange / cyan, opacity 0.5, both facing +z.
 */
Scene interpenetratingTriangles();

// ---------------------------------------------------------------------------------------------
// (c) CAD-like assembly: many closed parts, wildly varied sizes, nested and overlapping.
// ---------------------------------------------------------------------------------------------

/**
 * A CAD-like assembly in millimetres, z up. Part 0 is a baseplate (a thin box) covering a square
 * board of about sqrt(parts) x sqrt(parts) cells of 20 mm; then come 1 + parts / 5000 big
 * housings (boxes 60-200 mm; every other one translucent, opacity 0.35); the remaining parts
 * are small: screws, washers, hex nuts, cylinders (upright or lying), boxes (chips, blocks),
 * spheres, tori (o-rings) and knobs (frustums), sized log-uniformly from about 1 mm to 40 mm.
 * About 80 % stand on a jittered grid on the board (neighbours overlap now and then), 20 % are
 * clustered inside the housings at random heights (nested parts), and about 2 % of the small
 * parts are translucent (opacity 0.5), so the scene has both culling and sorting work.
 *
 * Every part is a closed, outward-facing triangle surface (a surface of revolution: even boxes
 * are 4-sided revolutions, nuts 6-sided), so it is 2-manifold and back-face culling is valid.
 * Parts are named "<kind>#<index>" ("baseplate", "housing#3", "screw#17", ...).
 *
 * Size: the triangle budget parts * trianglesPerPart is shared out with bigger parts getting
 * more (finer tessellation); the total is within about 10 % of the request for
 * trianglesPerPart >= 50 (small shapes have a floor: a box has at least 16 triangles, a nut 48).
 * Supports 10k-100k parts and 10M+ triangles: memory is reserved exactly in a sizing pass;
 * 10M triangles (100k parts x 100, or 10k x 1000) take 0.5-1 s and 330 MB (Release build).
 *
 * @param origin translation added to every point: place the assembly at 1e7 to exercise the
 *        precision of downstream algorithms far from the origin.
 */
Scene cadAssembly(std::size_t parts = 10000,
                  std::size_t trianglesPerPart = 100,
                  std::uint64_t seed = 1,
                  const glm::dvec3& origin = glm::dvec3(0.0));

// ---------------------------------------------------------------------------------------------
// (d) Building: rooms and portals, for portal/cell visibility and occlusion culling.
// ---------------------------------------------------------------------------------------------

/// Room id of the outside world (facade, roof, underside; the far side of windows).
constexpr std::int32_t kOutside = -1;

/// Fixed building dimensions, metres (z up).
constexpr double kRoomSizeX = 5.0;     ///< Grid pitch along x (wall centre to wall centre).
constexpr double kRoomSizeY = 4.0;     ///< Grid pitch along y.
constexpr double kStoreyHeight = 3.0;  ///< Slab centre to slab centre.
constexpr double kWallThickness = 0.2; ///< Interior and exterior walls.
constexpr double kSlabThickness = 0.3; ///< Floor slabs, roof and ground slab.

struct Room
{
  std::int32_t id = 0; ///< == index in BuildingScene::rooms.
  std::int32_t floor = 0;
  std::int32_t ix = 0; ///< Grid column, 0 .. roomsX-1.
  std::int32_t iy = 0; ///< Grid row, 0 .. roomsY-1.
  bool stairwell = false;
  /// The room's cell: wall and slab centre planes, so the room's own polygons lie inside it and
  /// its portals lie on its faces. Neighbouring cells share faces.
  Box bounds;
};

enum class PortalKind
{
  Door,   ///< Between two rooms of one floor; 0.9 m x 2.1 m.
  Window, ///< Between a room and kOutside; 1.2 m x 1.3 m, sill at 0.9 m.
  Stair,  ///< Hole in a slab between stairwell rooms of adjacent floors.
};

/**
 * An opening. `polygon` is a planar convex quad (a rectangle) in the centre plane of the wall or
 * slab, counter-clockwise around `normal`, which points from `roomA` into `roomB`. Doors: roomA
 * is the lower id; windows: roomB == kOutside; stairs: roomA is the lower floor.
 */
struct Portal
{
  PortalKind kind = PortalKind::Door;
  std::int32_t roomA = 0;
  std::int32_t roomB = 0;
  std::vector<glm::dvec3> polygon;
  glm::dvec3 normal{ 0.0, 0.0, 1.0 };
};

struct BuildingScene : Scene
{
  std::vector<Room> rooms;
  /// Per polygon: the room it belongs to, or kOutside. Size mesh.polygonCount().
  std::vector<std::int32_t> room;
  std::vector<Portal> portals;
};

/**
 * A building of `floors` storeys of roomsX x roomsY rooms (ids floor * roomsX * roomsY +
 * iy * roomsX + ix), centred at the origin in x and y, ground floor at z = 0, z up, metres.
 *
 * Geometry (planar quads and triangles, with points of their own each):
 * - Walls have thickness; a wall shared by two rooms is two sets of polygons, one face per side,
 *   each facing into and assigned to its own room. Openings are cut by splitting the face on
 *   the grid of the hole's lines (up to 8 cells around it); the reveals (jambs) inside the wall
 *   thickness are split at the wall's centre plane and each half is assigned to the room on its
 *   side.
 * - Each room has a floor and a ceiling (faces of the slabs, assigned to the room).
 * - Exterior: facade, roof and underside are assigned to kOutside, so from outside the building
 *   is a closed box with window holes.
 * - Watertight: each room's shell (walls, reveals, floor, ceiling, stair shaft) and the outside's
 *   (facade, its reveals, roof, underside) is closed except at its portals, with no T-junction:
 *   where two faces meet, a face whose grid has no vertex where its neighbour has one is cut
 *   into a triangle fan that has it, and shared vertices are bit-identical. Rasterisation
 *   therefore leaves no crack through which another room could show (tested), and across a
 *   portal both sides' edges coincide.
 * - Doors: per floor, a random spanning tree of the room grid gets doors (so every room is
 *   reachable) plus about 30 % of the remaining interior walls.
 * - Windows: each exterior wall of a room gets one with probability 0.75, with a translucent
 *   glass pane (part "glass", opacity 0.3) in the portal plane, assigned to the room.
 * - Stairwells: one random cell per 5 x 5 block of the grid, on every floor; a straight flight
 *   of step boxes leads to a hole in the slab above (one Stair portal per pair of floors).
 * - Furniture: 1-3 random closed boxes per non-stairwell room.
 *
 * Parts (in this order, each contiguous): "walls" (interior faces and jambs), "floors",
 * "ceilings", "facade", "roof" (roof and underside), "stairs", "furniture", "glass".
 * Invariants (tested): every polygon with room r >= 0 lies within rooms[r].bounds; every portal
 * polygon lies on a face of its rooms' cells.
 */
BuildingScene building(int floors = 3, int roomsX = 4, int roomsY = 3, std::uint64_t seed = 1);

/// Parameters of maze(): a level of box rooms meant to make visibility precomputation hard.
struct MazeConfig
{
  int roomsX = 8;
  int roomsY = 8;
  int floors = 2;
  std::uint64_t seed = 1;
  /// Openings per interior wall between rooms of one floor: 0, 1, 2 or 3 with these odds
  /// (normalised). Each is a door, a window or a wide arch of random size.
  double openings[4] = { 0.15, 0.45, 0.3, 0.1 };
  /// Fraction of openings centred in their slot of the wall: walls of one row share their extent
  /// across the row, so centred openings line up into long sight lines.
  double aligned = 0.5;
  double exteriorWindow = 0.5; ///< Chance of a window in each exterior wall of a room.
  double stairHole = 0.12;     ///< Chance of a hole to the room above.
  /// Halls per floor: rectangles of 2 x 2 to hallSize x hallSize rooms whose walls between each
  /// other are open (one opening of 96 % of the wall): open areas cut into many cells, as in
  /// game levels, where portal sequences multiply.
  int hallsPerFloor = 0;
  int hallSize = 6;
};

/**
 * A maze level of floors x roomsX x roomsY box rooms (ids as building()) on a jittered grid:
 * column and row widths 3-8 m, storey heights 2.6-4.5 m, zero-thickness walls in the cells'
 * faces. Openings (each a rectangle strictly inside its face: doors, windows, arches up to 80 %
 * of their slot) are decided per wall, several per wall in slots along it; exterior walls get
 * windows to kOutside, slabs get holes to the room above. Rooms need not all be connected.
 * Geometry: each room's six faces split around their openings (assigned to the room) and the
 * facade (kOutside); parts "walls" and "facade". `rooms[r].bounds` is room r's cell, and every
 * portal lies strictly inside a face shared by its two cells (tests walk segments through it).
 */
BuildingScene maze(const MazeConfig& config);

} // namespace scenes
} // namespace scenevis
