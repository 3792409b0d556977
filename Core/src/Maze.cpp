// The maze level of Scenes.h: box rooms on a jittered grid with many openings per wall, made to
// stress visibility precomputation (long sight lines through aligned openings, windows, holes).
#include "scenevis/Scenes.h"

#include <algorithm>
#include <array>
#include <stdexcept>

namespace scenevis
{
namespace scenes
{

namespace
{
/// splitmix64: the same sequence on every platform (std distributions are not portable).
class MazeRandom
{
public:
  explicit MazeRandom(std::uint64_t seed)
    : State(seed)
  {
  }
  double uniform()
  {
    std::uint64_t z = (this->State += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * (1.0 / 9007199254740992.0);
  }
  double uniform(double a, double b) { return a + (b - a) * this->uniform(); }
  bool chance(double p) { return this->uniform() < p; }

private:
  std::uint64_t State;
};

/// An opening in a face, in the face's (s, t) coordinates; openings of one face are disjoint in s.
struct Hole
{
  double s0, s1, t0, t1;
};

/// A face: the plane coordinate[axis] == at, s along sAxis, t along the remaining axis.
struct Face
{
  int axis = 0;
  int sAxis = 1;
  double at = 0.0;
  double s0 = 0.0, s1 = 0.0, t0 = 0.0, t1 = 0.0;
  std::vector<Hole> holes;

  int tAxis() const { return 3 - this->axis - this->sAxis; }
  glm::dvec3 point(double s, double t) const
  {
    glm::dvec3 p(0.0);
    p[this->axis] = this->at;
    p[this->sAxis] = s;
    p[this->tAxis()] = t;
    return p;
  }
};

void addQuad(PolygonMesh& mesh, std::vector<std::int32_t>& rooms, std::int32_t room,
  const Face& f, double s0, double s1, double t0, double t1)
{
  if (!(s1 > s0) || !(t1 > t0))
  {
    return;
  }
  const std::uint32_t ids[4] = { mesh.addPoint(f.point(s0, t0)), mesh.addPoint(f.point(s1, t0)),
    mesh.addPoint(f.point(s1, t1)), mesh.addPoint(f.point(s0, t1)) };
  mesh.addPolygon(ids, 4);
  rooms.push_back(room);
}

/// The face minus its holes, as quads: full-height strips between holes, pieces above and below.
void emitFace(PolygonMesh& mesh, std::vector<std::int32_t>& rooms, std::int32_t room, Face f)
{
  std::sort(f.holes.begin(), f.holes.end(),
    [](const Hole& a, const Hole& b) { return a.s0 < b.s0; });
  double s = f.s0;
  for (const Hole& h : f.holes)
  {
    addQuad(mesh, rooms, room, f, s, h.s0, f.t0, f.t1);
    addQuad(mesh, rooms, room, f, h.s0, h.s1, f.t0, h.t0);
    addQuad(mesh, rooms, room, f, h.s0, h.s1, h.t1, f.t1);
    s = h.s1;
  }
  addQuad(mesh, rooms, room, f, s, f.s1, f.t0, f.t1);
}
} // namespace

BuildingScene maze(const MazeConfig& c)
{
  if (c.floors < 1 || c.roomsX < 1 || c.roomsY < 1)
  {
    throw std::invalid_argument("scenevis::scenes::maze: floors, roomsX, roomsY must be >= 1");
  }
  if (static_cast<double>(c.floors) * c.roomsX * c.roomsY > 1e6)
  {
    throw std::length_error("scenevis::scenes::maze: too many rooms");
  }
  MazeRandom rng(c.seed);
  std::array<std::vector<double>, 3> lines; // grid lines per axis
  const int counts[3] = { c.roomsX, c.roomsY, c.floors };
  for (int a = 0; a < 3; ++a)
  {
    lines[a].push_back(0.0);
    for (int i = 0; i < counts[a]; ++i)
    {
      lines[a].push_back(lines[a].back() + (a < 2 ? rng.uniform(3.0, 8.0) : rng.uniform(2.6, 4.5)));
    }
  }
  const int perFloor = c.roomsX * c.roomsY;
  auto roomId = [&](int ix, int iy, int f) { return f * perFloor + iy * c.roomsX + ix; };

  BuildingScene scene;
  scene.rooms.resize(static_cast<std::size_t>(perFloor * c.floors));
  // Per room, its six faces: 2 * axis (low side) and 2 * axis + 1 (high side).
  std::vector<std::array<Face, 6>> faces(scene.rooms.size());
  for (int f = 0; f < c.floors; ++f)
  {
    for (int iy = 0; iy < c.roomsY; ++iy)
    {
      for (int ix = 0; ix < c.roomsX; ++ix)
      {
        const int id = roomId(ix, iy, f);
        Room& r = scene.rooms[static_cast<std::size_t>(id)];
        r.id = id;
        r.floor = f;
        r.ix = ix;
        r.iy = iy;
        const int cell[3] = { ix, iy, f };
        glm::dvec3 lo, hi;
        for (int a = 0; a < 3; ++a)
        {
          lo[a] = lines[a][static_cast<std::size_t>(cell[a])];
          hi[a] = lines[a][static_cast<std::size_t>(cell[a] + 1)];
        }
        r.bounds.extend(lo);
        r.bounds.extend(hi);
        for (int a = 0; a < 3; ++a)
        {
          for (int side = 0; side < 2; ++side)
          {
            Face& face = faces[static_cast<std::size_t>(id)][static_cast<std::size_t>(2 * a + side)];
            face.axis = a;
            face.sAxis = a == 2 ? 0 : (a == 0 ? 1 : 0); // walls: s horizontal, t = z
            face.at = side ? hi[a] : lo[a];
            face.s0 = lo[face.sAxis];
            face.s1 = hi[face.sAxis];
            face.t0 = lo[face.tAxis()];
            face.t1 = hi[face.tAxis()];
          }
        }
      }
    }
  }

  // One opening in face slot [s0, s1] x [t0, t1] (t = z for walls): a door, window or arch.
  auto wallOpening = [&](double s0, double s1, double t0, double t1)
  {
    const double w = s1 - s0, storey = t1 - t0;
    const double kind = rng.uniform();
    double width, bottom, top;
    if (kind < 0.5) // door
    {
      width = std::min(rng.uniform(0.8, 1.6), 0.8 * w);
      bottom = t0 + 0.05;
      top = std::min(t0 + rng.uniform(2.0, 2.4), t1 - 0.2);
    }
    else if (kind < 0.8) // window
    {
      width = std::min(rng.uniform(0.5, 2.5), 0.8 * w);
      bottom = t0 + rng.uniform(0.6, 1.2);
      top = std::min(bottom + rng.uniform(0.5, 1.4), t1 - 0.1);
    }
    else // arch
    {
      width = rng.uniform(0.5, 0.8) * w;
      bottom = t0 + 0.05;
      top = t1 - std::min(0.2, rng.uniform(0.1, 0.6) * storey);
    }
    const double margin = 0.05 * w;
    const double centre = rng.chance(c.aligned)
      ? 0.5 * (s0 + s1)
      : rng.uniform(s0 + margin + 0.5 * width, s1 - margin - 0.5 * width);
    return Hole{ centre - 0.5 * width, centre + 0.5 * width, bottom, top };
  };
  auto addPortal = [&](PortalKind kind, std::int32_t a, std::int32_t b, const Face& face,
                     const Hole& h, double normalSign)
  {
    Portal p;
    p.kind = kind;
    p.roomA = a;
    p.roomB = b;
    p.normal = glm::dvec3(0.0);
    p.normal[face.axis] = normalSign;
    // (s, t) is counter-clockwise around +axis when (sAxis, tAxis, axis) is right-handed.
    const bool ccw = (face.sAxis + 1) % 3 == face.tAxis();
    p.polygon = { face.point(h.s0, h.t0), face.point(h.s1, h.t0), face.point(h.s1, h.t1),
      face.point(h.s0, h.t1) };
    if (ccw != (normalSign > 0))
    {
      std::reverse(p.polygon.begin(), p.polygon.end());
    }
    scene.portals.push_back(std::move(p));
  };
  const double odds = c.openings[0] + c.openings[1] + c.openings[2] + c.openings[3];
  std::vector<int> hall(scene.rooms.size(), -1);
  for (int f = 0; f < c.floors; ++f)
  {
    for (int h = 0; h < c.hallsPerFloor; ++h)
    {
      const int top = std::max(2, c.hallSize);
      const int sx = std::min(c.roomsX, 2 + static_cast<int>(rng.uniform() * (top - 1)));
      const int sy = std::min(c.roomsY, 2 + static_cast<int>(rng.uniform() * (top - 1)));
      const int x0 = static_cast<int>(rng.uniform() * (c.roomsX - sx + 1));
      const int y0 = static_cast<int>(rng.uniform() * (c.roomsY - sy + 1));
      for (int iy = y0; iy < y0 + sy; ++iy)
      {
        for (int ix = x0; ix < x0 + sx; ++ix)
        {
          hall[static_cast<std::size_t>(roomId(ix, iy, f))] = f * c.hallsPerFloor + h;
        }
      }
    }
  }
  for (int f = 0; f < c.floors; ++f)
  {
    for (int iy = 0; iy < c.roomsY; ++iy)
    {
      for (int ix = 0; ix < c.roomsX; ++ix)
      {
        const int id = roomId(ix, iy, f);
        auto& mine = faces[static_cast<std::size_t>(id)];
        // Interior walls towards +x and +y, and the slab towards the floor above.
        for (int a = 0; a < 3; ++a)
        {
          const int cell[3] = { ix, iy, f };
          if (cell[a] + 1 >= counts[a])
          {
            continue;
          }
          const int other = a == 0 ? roomId(ix + 1, iy, f)
                                   : (a == 1 ? roomId(ix, iy + 1, f) : roomId(ix, iy, f + 1));
          Face& face = mine[static_cast<std::size_t>(2 * a + 1)];
          int n = 0;
          const bool open = a < 2 && hall[static_cast<std::size_t>(id)] >= 0 &&
            hall[static_cast<std::size_t>(id)] == hall[static_cast<std::size_t>(other)];
          if (a == 2)
          {
            n = rng.chance(c.stairHole) ? 1 : 0;
          }
          else if (open)
          {
            n = 1;
          }
          else
          {
            double pick = rng.uniform() * odds;
            while (n < 3 && pick >= c.openings[n])
            {
              pick -= c.openings[n++];
            }
          }
          for (int k = 0; k < n; ++k)
          {
            const double w = (face.s1 - face.s0) / n;
            const double s0 = face.s0 + k * w;
            Hole h;
            if (a == 2)
            {
              const double hw = rng.uniform(0.25, 0.45) * (face.s1 - face.s0);
              const double hd = rng.uniform(0.25, 0.45) * (face.t1 - face.t0);
              const double cs = rng.uniform(face.s0 + hw + 0.1, face.s1 - hw - 0.1);
              const double ct = rng.uniform(face.t0 + hd + 0.1, face.t1 - hd - 0.1);
              h = Hole{ cs - hw, cs + hw, ct - hd, ct + hd };
            }
            else if (open)
            {
              const double ms = 0.02 * (face.s1 - face.s0), mt = 0.02 * (face.t1 - face.t0);
              h = Hole{ face.s0 + ms, face.s1 - ms, face.t0 + mt, face.t1 - mt };
            }
            else
            {
              h = wallOpening(s0, s0 + w, face.t0, face.t1);
            }
            face.holes.push_back(h);
            faces[static_cast<std::size_t>(other)][static_cast<std::size_t>(2 * a)].holes.push_back(h);
            addPortal(a == 2 ? PortalKind::Stair : PortalKind::Door, id, other, face, h, 1.0);
          }
        }
        // Exterior walls: a window to the outside.
        for (int side = 0; side < 4; ++side)
        {
          const int a = side / 2;
          const int cell = a == 0 ? ix : iy;
          const bool exterior = (side % 2 == 0) ? cell == 0 : cell + 1 == counts[a];
          if (!exterior || !rng.chance(c.exteriorWindow))
          {
            continue;
          }
          Face& face = mine[static_cast<std::size_t>(side)];
          Hole h = wallOpening(face.s0, face.s1, face.t0, face.t1);
          const double below = face.t0 + 0.6;
          if (h.t0 < below) // a window, not a door to the street
          {
            h.t0 = std::min(below, h.t1 - 0.3);
          }
          face.holes.push_back(h);
          addPortal(PortalKind::Window, id, kOutside, face, h, side % 2 == 0 ? -1.0 : 1.0);
        }
      }
    }
  }

  // Geometry: every room's faces (its own), then the facade (the outside's).
  PolygonMesh walls, facade;
  std::vector<std::int32_t> wallRooms, facadeRooms;
  for (std::size_t r = 0; r < faces.size(); ++r)
  {
    for (std::size_t k = 0; k < 6; ++k)
    {
      const Face& face = faces[r][k];
      emitFace(walls, wallRooms, static_cast<std::int32_t>(r), face);
      const int a = static_cast<int>(k / 2);
      const Room& room = scene.rooms[r];
      const int cell[3] = { room.ix, room.iy, room.floor };
      const bool exterior = (k % 2 == 0) ? cell[a] == 0 : cell[a] + 1 == counts[a];
      if (exterior)
      {
        emitFace(facade, facadeRooms, kOutside, face);
      }
    }
  }
  const char* names[2] = { "walls", "facade" };
  const glm::dvec3 colours[2] = { { 0.8, 0.78, 0.72 }, { 0.6, 0.55, 0.5 } };
  const PolygonMesh* meshes[2] = { &walls, &facade };
  const std::vector<std::int32_t>* rooms[2] = { &wallRooms, &facadeRooms };
  for (std::size_t l = 0; l < 2; ++l)
  {
    Part part;
    part.name = names[l];
    part.colour = colours[l];
    part.firstPolygon = scene.mesh.append(*meshes[l]);
    part.polygonCount = static_cast<std::uint32_t>(meshes[l]->polygonCount());
    part.bounds = meshes[l]->bounds();
    scene.part.insert(scene.part.end(), part.polygonCount, static_cast<std::uint32_t>(l));
    scene.room.insert(scene.room.end(), rooms[l]->begin(), rooms[l]->end());
    scene.parts.push_back(std::move(part));
  }
  return scene;
}

} // namespace scenes
} // namespace scenevis
