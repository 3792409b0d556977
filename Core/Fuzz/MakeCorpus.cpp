// Writes the seed corpus of FuzzBsp (Core/Fuzz/corpus/): encodings of the hard cases (cyclic quads,
// interpenetrating triangles, coplanar and near-coplanar polygons, a scene at 1e7, an eye inside a
// closed box or on a polygon's plane, degenerate and non-finite input). Usage:
//   scenevis_fuzz_make_corpus <dir>
// The files are committed; rerun only when the format (FuzzBspInput.h) changes.
#include "FuzzBspInput.h"

#include "scenevis/Scenes.h"

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

using namespace scenevis::fuzz;

namespace
{

struct Case
{
  std::string name;
  Writer w;
};

// config byte: see FuzzBspInput.h.
int config(bool firstInList, bool offset1e7 = false, int tolerance = 0, int samples = 0,
  bool noFree = false)
{
  return (firstInList ? 1 : 0) | (noFree ? 2 : 0) | (tolerance << 2) | (samples << 4) |
    (offset1e7 ? 0x40 : 0);
}

int view(bool parallel, int mode, bool frontToBack, int moves)
{
  return (parallel ? 1 : 0) | (mode << 1) | (frontToBack ? 8 : 0) | (moves << 4);
}

/// Points and general polygons of a mesh (<= 32 points, <= 24 polygons).
void writeMesh(Writer& w, const scenevis::PolygonMesh& mesh)
{
  w.byte(static_cast<int>(mesh.points.size()));
  for (const auto& p : mesh.points)
  {
    w.coord(p.x);
    w.coord(p.y);
    w.coord(p.z);
  }
  w.byte(static_cast<int>(mesh.polygonCount()) - 1);
  for (std::size_t i = 0; i < mesh.polygonCount(); ++i)
  {
    w.byte(kGeneral);
    w.byte(static_cast<int>(mesh.polygonSize(i)) - 1);
    for (std::uint32_t k = 0; k < mesh.polygonSize(i); ++k)
    {
      w.byte(static_cast<int>(mesh.polygon(i)[k]));
    }
  }
}

void rectangle(Writer& w, int axis, double at, double u0, double u1, double v0, double v1)
{
  w.byte(kRectangle);
  w.byte(axis);
  w.coord(at);
  w.coord(u0);
  w.coord(u1);
  w.coord(v0);
  w.coord(v1);
}

void eyePoint(Writer& w, double x, double y, double z)
{
  w.coord(x);
  w.coord(y);
  w.coord(z);
}

void someMoves(Writer& w)
{
  // small step, onto a tree point, onto a node plane, parallel, back to the first eye
  w.byte(kSmallStep);
  w.byte(17);
  w.byte(18);
  w.byte(15);
  w.byte(20);
  w.byte(kOntoTreePoint);
  w.byte(5);
  w.byte(0);
  w.byte(kOntoNodePlane);
  w.byte(1);
  w.byte(0);
  w.byte(kParallel);
  eyePoint(w, 0.25, -0.5, -1);
  w.byte(kBackToFirst);
  w.byte(kNewPoint);
  eyePoint(w, -1.5, 2, 0.125);
}

} // namespace

int main(int argc, char** argv)
{
  if (argc != 2)
  {
    std::fprintf(stderr, "usage: %s <corpus dir>\n", argv[0]);
    return 2;
  }
  std::vector<Case> cases;
  auto add = [&cases](const std::string& name) -> Writer&
  {
    cases.push_back(Case{ name, Writer{} });
    return cases.back().w;
  };

  const auto cyclic = scenevis::scenes::cyclicQuads().mesh;
  const auto piercing = scenevis::scenes::interpenetratingTriangles().mesh;
  for (int firstInList = 0; firstInList < 2; ++firstInList)
  {
    for (int offset = 0; offset < 2; ++offset)
    {
      const std::string suffix = std::string(firstInList ? "-first" : "-scored") +
        (offset ? "-1e7" : "");
      Writer& a = add("cyclic-quads" + suffix);
      a.byte(config(firstInList != 0, offset != 0));
      a.byte(15);
      a.byte(1);
      writeMesh(a, cyclic);
      a.byte(view(false, 0, false, 5));
      eyePoint(a, 0.125, 0.25, 2);
      someMoves(a);

      Writer& b = add("interpenetrating-triangles" + suffix);
      b.byte(config(firstInList != 0, offset != 0));
      b.byte(15);
      b.byte(7);
      writeMesh(b, piercing);
      b.byte(view(false, 0, true, 5));
      eyePoint(b, -0.375, 0.25, 1.5);
      someMoves(b);
    }
  }

  {
    // Coplanar: overlapping rectangles on z = 0, an exact duplicate with reversed winding, a
    // crossing rectangle; the eye on z = 0.
    Writer& w = add("coplanar-eye-on-plane");
    w.byte(config(false));
    w.byte(3);
    w.byte(2);
    w.byte(0); // no free points
    w.byte(5 - 1);
    rectangle(w, 2, 0, -1, 1, -1, 1);
    rectangle(w, 2, 0, -0.5, 1.5, -0.5, 1.5);
    w.byte(kCopy);
    w.byte(0);
    w.byte(8); // scale 0, reversed
    w.byte(16);
    w.byte(16);
    w.byte(24);
    rectangle(w, 0, 0.25, -1, 1, -1, 1);
    rectangle(w, 1, -0.25, -1, 1, -1, 1);
    w.byte(view(false, 1, false, 4));
    w.byte(0);  // polygon 0's plane
    w.byte(40); // s = 1.5 (off the polygon)
    w.byte(20); // t = 0.5
    someMoves(w);
  }
  for (int tolerance = 0; tolerance < 3; ++tolerance)
  {
    // Near-coplanar copies along z at 2^-40 .. 2^-30 (around both tolerances) and 2^-20.
    Writer& w = add("near-coplanar-tol" + std::to_string(tolerance));
    w.byte(config(tolerance == 1, false, tolerance));
    w.byte(7);
    w.byte(3);
    w.byte(0);
    w.byte(6 - 1);
    rectangle(w, 2, 0, -1, 1, -1, 1);
    for (int scale = 1; scale <= 5; ++scale)
    {
      w.byte(kCopy);
      w.byte(0);
      w.byte(scale | (scale & 1 ? 8 : 0));
      w.byte(16 + scale % 3 - 1); // a slight tilt of the shift, mostly +z
      w.byte(16);
      w.byte(24);
    }
    w.byte(view(false, 0, false, 3));
    eyePoint(w, 0.25, 0.375, 1);
    w.byte(kSmallStep);
    w.byte(16);
    w.byte(16);
    w.byte(0);
    w.byte(30);
    w.byte(kOntoNodePlane);
    w.byte(2);
    w.byte(0);
    w.byte(kNewPoint);
    eyePoint(w, 0.25, 0.375, -1);
  }
  {
    // A triangle grid placed at 1e7, viewed in parallel and then from inside.
    Writer& w = add("grid-at-1e7-parallel");
    w.byte(config(false, true));
    w.byte(15);
    w.byte(9);
    w.byte(9);
    for (int j = 0; j < 3; ++j)
    {
      for (int i = 0; i < 3; ++i)
      {
        eyePoint(w, i - 1.0, j - 1.0, 0.125 * ((i * 7 + j * 3) % 5) - 0.25);
      }
    }
    w.byte(8 - 1);
    for (int j = 0; j < 2; ++j)
    {
      for (int i = 0; i < 2; ++i)
      {
        const int a = j * 3 + i;
        w.byte(kTriangle);
        w.byte(a);
        w.byte(a + 1);
        w.byte(a + 4);
        w.byte(kTriangle);
        w.byte(a);
        w.byte(a + 4);
        w.byte(a + 3);
      }
    }
    w.byte(view(true, 0, false, 3));
    eyePoint(w, 0.125, -0.25, -1);
    w.byte(kNewPoint);
    eyePoint(w, 0, 0, 0);
    w.byte(kOntoTreePoint);
    w.byte(4);
    w.byte(0);
    w.byte(kSmallStep);
    w.byte(1);
    w.byte(2);
    w.byte(3);
    w.byte(36);
  }
  {
    // A closed box with the eye inside; crossing parallelograms and a fan.
    Writer& w = add("box-eye-inside");
    w.byte(config(false, false, 0, 2));
    w.byte(4);
    w.byte(11);
    w.byte(4);
    eyePoint(w, -1, -1, -0.5);
    eyePoint(w, 1, -0.5, 0.5);
    eyePoint(w, 0.5, 1, 0.25);
    eyePoint(w, -0.75, 0.5, 1);
    w.byte(10 - 1);
    for (int axis = 0; axis < 3; ++axis)
    {
      rectangle(w, axis, -1.5, -1.5, 1.5, -1.5, 1.5);
      rectangle(w, axis, 1.5, -1.5, 1.5, 1.5, -1.5); // wound the other way
    }
    w.byte(kParallelogram);
    w.byte(0);
    w.byte(1);
    w.byte(2);
    w.byte(kParallelogram);
    w.byte(3);
    w.byte(0);
    w.byte(2);
    w.byte(kFan);
    w.byte(1);
    w.byte(kFan);
    w.byte(3);
    w.byte(view(false, 0, true, 6));
    eyePoint(w, 0.125, 0.25, -0.125);
    someMoves(w);
  }
  {
    // Degenerate and non-finite input: repeated points, collinear triangles, NaN, Inf, huge and
    // tiny values, out-of-range ids, polygons of 1 and 2 points, a self-intersecting bow tie.
    Writer& w = add("degenerate-and-nonfinite");
    w.byte(config(true));
    w.byte(1);
    w.byte(0);
    w.byte(10);
    eyePoint(w, 0, 0, 0);
    eyePoint(w, 1, 0, 0);
    eyePoint(w, 2, 0, 0); // collinear
    eyePoint(w, 1, 1, 0);
    eyePoint(w, 0, 1, 0);
    w.byte(kNaN);
    w.byte(16);
    w.byte(16);
    w.byte(kInfPos);
    w.byte(kInfNeg);
    w.byte(16);
    w.byte(kHugePos);
    w.byte(16);
    w.byte(16);
    w.byte(kTinyPos);
    w.byte(kDenormal);
    w.byte(kTinyNeg);
    w.byte(kOverflowNeg);
    w.byte(kFar1e15);
    w.byte(3);
    w.byte(kFar1e7);
    w.byte(5);
    w.byte(12 - 1);
    w.byte(kTriangle); w.byte(0); w.byte(1); w.byte(2); // collinear
    w.byte(kTriangle); w.byte(0); w.byte(0); w.byte(3); // repeated point
    w.byte(kTriangle); w.byte(0); w.byte(5); w.byte(3); // NaN
    w.byte(kTriangle); w.byte(0); w.byte(6); w.byte(3); // Inf
    w.byte(kTriangle); w.byte(0); w.byte(7); w.byte(3); // 1e30
    w.byte(kTriangle); w.byte(0); w.byte(255); w.byte(3); // out of range
    w.byte(kGeneral); w.byte(0); w.byte(1); // one point
    w.byte(kGeneral); w.byte(1); w.byte(1); w.byte(2); // two points
    w.byte(kGeneral); w.byte(3); w.byte(0); w.byte(3); w.byte(1); w.byte(4); // bow tie
    w.byte(kGeneral); w.byte(5); w.byte(0); w.byte(0); w.byte(1); w.byte(3); w.byte(3); w.byte(0);
    w.byte(kTriangle); w.byte(8); w.byte(1); w.byte(3); // tiny values
    w.byte(kTriangle); w.byte(9); w.byte(1); w.byte(3); // 1e300 and 1e15
    w.byte(view(false, 0, false, 4));
    eyePoint(w, 0.5, 0.5, 2);
    someMoves(w);
  }
  {
    // Scored with one candidate, one sample and no free planes: the weakest heuristic.
    Writer& w = add("concave-and-nonplanar");
    w.byte(config(false, false, 0, 1, true));
    w.byte(0);
    w.byte(5);
    w.byte(8);
    eyePoint(w, -1, -1, 0);
    eyePoint(w, 1, -1, 0.25);
    eyePoint(w, 1, 1, 0);
    eyePoint(w, 0, 0, 0.5); // makes the quad concave
    eyePoint(w, -1, 1, -0.25);
    eyePoint(w, 0, -2, -1);
    eyePoint(w, 0, 2, 1);
    eyePoint(w, 0.5, 0, -1.5);
    w.byte(4 - 1);
    w.byte(kGeneral); w.byte(4); w.byte(0); w.byte(1); w.byte(2); w.byte(3); w.byte(4);
    w.byte(kGeneral); w.byte(3); w.byte(5); w.byte(6); w.byte(7); w.byte(2);
    w.byte(kParallelogram); w.byte(5); w.byte(7); w.byte(6);
    w.byte(kFan); w.byte(0);
    w.byte(view(false, 3, false, 3));
    w.byte(18); w.byte(13); w.byte(20); w.byte(2); // far eye
    w.byte(kSmallStep); w.byte(17); w.byte(16); w.byte(16); w.byte(2);
    w.byte(kOntoTreePoint); w.byte(9); w.byte(0);
    w.byte(kOntoNodePlane); w.byte(0); w.byte(0);
  }

  for (const Case& c : cases)
  {
    const std::string path = std::string(argv[1]) + "/" + c.name;
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(c.w.bytes.data()),
      static_cast<std::streamsize>(c.w.bytes.size()));
    if (!out)
    {
      std::fprintf(stderr, "cannot write %s\n", path.c_str());
      return 1;
    }
  }
  std::printf("wrote %zu corpus files to %s\n", cases.size(), argv[1]);
  return 0;
}
