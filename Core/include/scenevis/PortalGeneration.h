#pragma once
/**
 * @file PortalGeneration.h
 * @brief Rooms and portals found from architectural geometry (issue 14 item 3), VTK-free.
 *
 * Input: a polygon soup of walls, floors, ceilings and furniture whose openings (doors, windows,
 * stair holes) are holes in the walls. Output: a room id per polygon and portal polygons with the
 * two rooms they join: the CellSceneInput the portal graph, traversal and PVS consume (and the
 * portal scene format: RoomId cell array + portals with RoomA/RoomB).
 *
 * Method (the portalization step of Quake-style level compilers, adapted to rooms):
 * 1. A polygon-aligned BSP (BspBuilder.h) over the blocking polygons. Each empty child slot of a
 *    node is a convex cell: the scene box (the input bounds grown by `margin`) cut by the
 *    half-spaces along its path.
 * 2. Cell faces: every node's plane, clipped to the node's region, is pushed down both subtrees
 *    and split there, so each piece separates exactly one cell in front from one behind. The
 *    node's own fragments (the polygons in that plane) are subtracted from each piece: what
 *    remains is open (air can pass), the rest is wall. The six box faces are pushed the same way
 *    to find the cells that touch the scene box. A BSP cuts along a wall's plane only inside the
 *    region of the node holding the wall, so a cell may reach through a doorway from one room
 *    into the next: each cell that a polygon touches (e.g. along a lintel) and whose interior
 *    the polygon's plane crosses is split by that plane, until none is
 *    (GenerationStatistics::openingSplits). Every opening is then a set of faces in its wall's
 *    plane.
 * 3. Air: cells joined through open faces make a space; a space is air when it touches the box
 *    or when more polygon area faces into it (the side normals point to) than turns its back
 *    on it; the others are solid (inside thick walls, inside closed furniture, inside a cabinet
 *    standing against a wall, which the wall faces into). Only open faces between air matter.
 * 4. Openings: open faces are grouped per plane into connected regions. A region is an opening
 *    (a doorway, a window, a hole in a slab) when at least `openingEnclosure` of its outline lies
 *    against polygons in the same plane: a door in a wall has its jambs and lintel in the wall's
 *    plane, while the plane of a table top or of a corridor's corner crosses the room with most of
 *    its outline against other planes. Samples just outside each edge decide it; an open piece a
 *    sample lands in is the edge's neighbour only if it reaches back to the edge (past an edge
 *    shorter than the sampling step, at the end of a sliver between a floor and a slanted wall
 *    the floor stops short of, a sample can land across that wall). A region ends
 *    where a polygon crosses its plane or meets it from one side along the edge: the floor at
 *    the threshold of a door in an exterior wall parts the door from the wall's plane below the
 *    floor outside, which is open too (the building floats in the scene box).
 * 5. Rooms: air cells joined across every open face that is not an opening. The room holding
 *    the box cells is the outside (kOutsideRoom). A room whose volume is small for its largest
 *    opening (volume / area^1.5 < `passageThickness`: the tunnel a door makes through a thick
 *    wall, the hole through a slab) is a passage and joins the neighbour it shares the largest
 *    opening with; so does a room no polygon faces into (nothing to locate an eye in). Rooms
 *    one polygon faces into are joined: the portal graph locates an eye by the polygons around
 *    it, so each room must be closed by polygons of its own (and its portals).
 * 6. Portals: the open faces between different rooms, one convex polygon (the hull of the faces)
 *    per connected opening region and room pair.
 *
 * Conservativeness: every open face between air cells is either inside a room or part of a
 * portal's region, and a portal's polygon is the convex hull of that region, so any straight path
 * through air from one room to another crosses a chain of portals, and no portal is smaller than
 * the open faces it stands for. Merging cells into rooms only makes rooms larger. What it relies
 * on: polygons are opaque where they are (a crack thinner than the BSP tolerance is closed), and
 * see-through polygons (glass) are marked so that they do not close their opening.
 *
 * Leaks: cells joined to the outside through faces that are not openings (a missing wall, a gap
 * at a wall's edge), faced by polygons (more polygon area on their faces faces into them than
 * away) and enclosed by geometry in at least 5 of the 6 axis directions are reported
 * in `leakPoints`. A model that leaks gets no rooms (every polygon kOutsideRoom, no portals: a
 * portal culler then culls by the frustum alone) unless `keepRoomsWithLeaks` asks for them,
 * because no room labelling is conservative then: through the leak, places where eyes stand
 * join the outside, and (1) a polygon facing into a room and into such a place (a floor running
 * from a room into the leaking space) gets one of the two, so the other sees it without a
 * portal; (2) the back of a room's wall, whose front faces the room and whose back faces the
 * void behind it, is seen from such a place through the void, without a portal; an eye there
 * beyond the rooms' bounds starts from the outside node and enters rooms only through their
 * portals. Merging the rooms of (1) into the outside does not help (2), and merging by (2) would
 * merge every room: a converted level's surfaces are single polygons with the void behind them.
 * On hydronex2 and ps9ctf the kept rooms lose pixels in 5-10 views of 33-42 (BENCHMARKS.md).
 *
 * Polygons: each gets the room its fragments face into over the largest area (see-through ones:
 * the room just in front of their centroid); a part facing the outside with a room behind it
 * counts for that room (a polygon wound the wrong way). Polygons with no covered part
 * (see-through, coincident with one that took the cover, or hidden: facing solid space) get the
 * room just in front of their centroid, else the room just beyond one of their edges on their
 * back side (a box's bottom on the floor peeks out there), else the first room found stepping
 * from their centroid along their normal; polygons facing the outside with no room behind
 * (facades), those where no room is found (polygonsWithoutRoom) and dropped (invalid) ones get
 * kOutsideRoom. Limits: input polygons must face into the space they bound: a void pocket
 * closed by polygons wound the wrong way is taken for a room (Freedoom MAP12 converted before
 * the converter faced its back-side wall parts into their sectors lost pixels in 50 of 123
 * views); a zero-thickness exterior wall without a facade polygon of its own goes to its room,
 * so an eye outside sees it only through that room's windows.
 *
 * Cost: the BSP, then per round of opening splits the cells and faces again (a few rounds);
 * the demo building (2,250 polygons, 24 rooms) takes about 0.5 s, Freedoom MAP12 (67,170
 * polygons) 25 s, single-threaded.
 */

#include "scenevis/BspBuilder.h"
#include "scenevis/PolygonMesh.h"
#include "scenevis/PortalGraph.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace scenevis
{
namespace portals
{

struct GenerationConfig
{
  /// Share of a planar open region's outline that must lie against polygons of its plane for the
  /// region to be an opening. A door in a corner of a wall has 0.5, a table top 1/3 of a room's
  /// area about 0.25; the default sits between.
  double openingEnclosure = 0.45;
  /// Rooms with volume / (largest opening area)^1.5 below this are passages (see the file
  /// comment). A door through a 0.2 m wall: 0.15; a 1 m^2 closet with a door: about 1.
  double passageThickness = 0.5;
  /// Growth of the scene box around the input bounds, as a fraction of their diagonal.
  double margin = 0.1;
  /// Processor seconds the generation may take (0: no limit; the calling thread's processor time
  /// where POSIX has a thread clock, else std::clock: a loaded machine, or other threads of the
  /// process at work, stretch the wall time but not the answer). Checked between its steps (after
  /// the BSP, each round of opening splits, the openings) and every 256 cells of the leak search;
  /// past it, generation stops with GenerationStatus::OverBudget and no rooms (never a partial,
  /// unchecked answer). A caller that tries generation on speculation (`--cull auto`) bounds what
  /// a scene that turns out to leak costs it.
  double budgetSeconds = 0.0;
  /// Stop at the first leak cell found (status Ok, no rooms, statistics.leakCells 1, its point in
  /// leakPoints, a message saying so). The cells joined to the outside are flooded from the box
  /// first, each plane's openings classified only when the flood reaches it, so a leaking scene
  /// costs the cells and a few planes instead of every plane. For callers that use rooms only
  /// without leaks (`--cull auto`); off, every leak cell is counted (`scenevis portals`). The
  /// rooms and portals of a scene that does not leak are the same either way.
  bool stopAtFirstLeak = false;
  /// With leaks, still give the rooms found (the rooms behind a leak merged into the outside):
  /// not conservative (see the file comment), statistics.roomsWithheld 0. Off: a model that
  /// leaks gets no rooms and no portals (status Ok, a message saying why, the rooms and portals
  /// it would have had in statistics.roomsWithheld and portalsWithheld).
  bool keepRoomsWithLeaks = false;
  /// The BSP over the blocking polygons. allowFreePlanes is ignored (always off): every node's
  /// plane must hold all the polygons in it that its region contains. The plane tolerance is
  /// coarser than the sorter's (1e-6 of the diagonal, not 1e-10): converted levels store points
  /// in single precision and close T-junctions with fan triangles whose centres, rounded, leave
  /// a wall's triangles off its plane by about 1e-5 of the level's size; with a finer tolerance
  /// they become planes of their own with open slivers between them (on Freedoom MAP12 the
  /// outside then leaks into 614 of its 1,615 sectors at 1e-10, 159 at 1e-7, 12 at 1e-6).
  scenevis::bsp::BuildConfig bsp = []
  {
    scenevis::bsp::BuildConfig c;
    c.relativeTolerance = 1e-6;
    c.allowFreePlanes = false;
    return c;
  }();
};

struct GenerationInput
{
  const PolygonMesh* mesh = nullptr;
  /// Per polygon (or empty): non-zero for see-through polygons (glass panes) that must not close
  /// an opening. They get a room like any polygon but take no part in the cells.
  std::vector<std::uint8_t> seeThrough;
};

enum class GenerationStatus
{
  Ok,
  EmptyInput,      ///< No mesh or no polygons.
  NoValidPolygons, ///< Every polygon was degenerate or touched a NaN/Inf point.
  OverBudget       ///< Stopped after GenerationConfig::budgetSeconds; no rooms.
};

/// Numbers a test can assert on; times only for reports.
struct GenerationStatistics
{
  std::size_t inputPolygons = 0;
  std::size_t blockingPolygons = 0; ///< Polygons given to the BSP (not see-through).
  std::size_t droppedPolygons = 0;  ///< Degenerate or invalid (the BSP's counts).
  std::size_t bspNodes = 0;
  std::size_t openingSplits = 0; ///< Cells split because they straddled an opening.
  std::size_t cells = 0; ///< Empty child slots of the BSP.
  std::size_t airCells = 0;
  std::size_t faces = 0;               ///< Cell faces on node planes.
  std::size_t openFaces = 0;           ///< Open pieces of those faces (after subtracting polygons).
  std::size_t openingFaces = 0;        ///< Open pieces between air cells classified as openings.
  std::size_t roomsBeforePassages = 0; ///< Rooms (without the outside) before passages merged.
  std::size_t passagesMerged = 0;
  std::size_t roomsJoinedByPolygons = 0; ///< Rooms joined because one polygon faces into both.
  std::size_t rooms = 0; ///< Final rooms (without the outside).
  std::size_t portals = 0;
  std::size_t exteriorPortals = 0; ///< Portals to the outside.
  std::size_t leakCells = 0;
  /// Rooms and portals found but not given because the model leaks (keepRoomsWithLeaks off).
  std::size_t roomsWithheld = 0;
  std::size_t portalsWithheld = 0;
  std::size_t polygonsWithoutRoom = 0; ///< Valid polygons whose front is solid (inside-out).
  double bspSeconds = 0.0;
  double cellSeconds = 0.0;    ///< Cells, faces and the splits at openings.
  double openingSeconds = 0.0; ///< Classifying open regions.
  double totalSeconds = 0.0;
};

struct GeneratedPortals
{
  GenerationStatus status = GenerationStatus::Ok;
  std::string message; ///< Why the status is not Ok, or why an Ok result has no rooms (leaks).
  /// Per input polygon: room id 0 .. roomCount-1, or kOutsideRoom.
  std::vector<std::int32_t> roomOfPolygon;
  std::int32_t roomCount = 0;
  /// Planar convex polygons; roomB is kOutsideRoom for exterior portals, else roomA < roomB.
  std::vector<PortalDesc> portals;
  /// A point in each leaking cell (at most 64), world coordinates.
  std::vector<glm::dvec3> leakPoints;
  GenerationStatistics statistics;

  /// The portal graph's input for @p mesh (the mesh generate() was given).
  CellSceneInput cellScene(const PolygonMesh& mesh) const;
};

/// Find rooms and portals (see the file comment). Never throws for bad geometry.
GeneratedPortals generatePortals(const GenerationInput& input, const GenerationConfig& config = {});

} // namespace portals
} // namespace scenevis
