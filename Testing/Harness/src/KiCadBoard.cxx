#include "scenevis/testing/KiCadBoard.h"

#include "scenevis/testing/Models.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkIdTypeArray.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkTriangleFilter.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <map>
#include <random>
#include <set>

namespace scenevis
{
namespace testing
{
namespace
{
namespace fs = std::filesystem;

// The libraries a board is populated from: what a real board carries, from 0402 resistors to
// QFP/BGA packages, pin headers and DC/DC modules; the LEDs bring translucent materials.
const char* const kLibraries[] = { "Package_SO", "Package_QFP", "Package_DFN_QFN", "Package_BGA",
  "Package_TO_SOT_SMD", "Package_DIP", "Capacitor_SMD", "Capacitor_Tantalum_SMD", "Capacitor_THT",
  "Resistor_SMD", "LED_SMD", "LED_THT", "Inductor_SMD", "Crystal", "Diode_SMD",
  "Connector_PinHeader_2.54mm", "Connector_USB", "Converter_DCDC", "Button_Switch_SMD" };

// Board size in KiCad units (1 unit = 2.54 mm): 40 x 26 = 102 x 66 mm, 1.6 mm thick.
constexpr double kBoardWidth = 40.0;
constexpr double kBoardDepth = 26.0;
constexpr double kBoardThickness = 1.6 / 2.54;
constexpr double kBoardGap = 3.0;
constexpr double kPartMargin = 0.4;
constexpr std::size_t kNoPart = std::numeric_limits<std::size_t>::max();

struct Part
{
  vtkSmartPointer<vtkPolyData> polys;
  std::string file;
  double bounds[6];
  double color[3];
  double opacity;
};

template <typename T>
bool Degenerate(const T* a, const T* b, const T* c)
{
  auto same = [](const T* p, const T* q) { return p[0] == q[0] && p[1] == q[1] && p[2] == q[2]; };
  return same(a, b) || same(b, c) || same(a, c);
}

/**
 * Triangles only, with "Colors" (RGBA) as the only cell array (the importer may deliver polygons
 * and strips), and without triangles that have two points at the same place. KiCad parts have
 * such triangles; they cover no pixel, and VTK 9.1's vtkOpenGLIndexBufferObject drops them from
 * the index buffer, so without them the board's triangle counts are those drawn (the
 * vtkChunkedPolyDataMapper culls either way: it leaves them out of its own triangle list).
 */
vtkSmartPointer<vtkPolyData> Triangulated(vtkPolyData* input)
{
  vtkNew<vtkTriangleFilter> triangles;
  triangles->PassVertsOff();
  triangles->PassLinesOff();
  triangles->SetInputData(input);
  triangles->Update();
  vtkPolyData* tri = triangles->GetOutput();
  auto* colors = vtkUnsignedCharArray::SafeDownCast(tri->GetCellData()->GetArray("Colors"));
  vtkNew<vtkCellArray> kept;
  vtkNew<vtkUnsignedCharArray> keptColors;
  keptColors->SetName("Colors");
  keptColors->SetNumberOfComponents(4);
  vtkCellArray* polys = tri->GetPolys();
  vtkPoints* points = tri->GetPoints();
  for (vtkIdType c = 0; points && c < polys->GetNumberOfCells(); ++c)
  {
    vtkIdType n;
    const vtkIdType* ids;
    polys->GetCellAtId(c, n, ids);
    double p[3][3];
    for (int k = 0; k < 3 && n == 3; ++k)
    {
      points->GetPoint(ids[k], p[k]);
    }
    if (n != 3 || Degenerate(p[0], p[1], p[2]))
    {
      continue;
    }
    kept->InsertNextCell(3, ids);
    const unsigned char white[4] = { 200, 200, 200, 255 };
    keptColors->InsertNextTypedTuple(
      colors && colors->GetNumberOfComponents() == 4 ? colors->GetPointer(4 * c) : white);
  }
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->SetPoints(points); // normals are not in every part; point data are dropped for all
  out->SetPolys(kept);
  out->GetCellData()->SetScalars(keptColors);
  return out;
}

/// Most frequent colour (by cells) and smallest opacity of a part's "Colors".
void RepresentativeColor(vtkPolyData* polys, double color[3], double& opacity)
{
  color[0] = color[1] = color[2] = 0.8;
  opacity = 1.0;
  auto* colors = vtkUnsignedCharArray::SafeDownCast(polys->GetCellData()->GetScalars());
  if (!colors || colors->GetNumberOfComponents() != 4)
  {
    return;
  }
  std::map<std::uint32_t, vtkIdType> counts;
  unsigned char minAlpha = 255;
  for (vtkIdType i = 0; i < colors->GetNumberOfTuples(); ++i)
  {
    const unsigned char* c = colors->GetPointer(4 * i);
    ++counts[(std::uint32_t(c[0]) << 16) | (std::uint32_t(c[1]) << 8) | c[2]];
    minAlpha = std::min(minAlpha, c[3]);
  }
  if (counts.empty())
  {
    return;
  }
  const auto best = std::max_element(
    counts.begin(), counts.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
  color[0] = ((best->first >> 16) & 255) / 255.0;
  color[1] = ((best->first >> 8) & 255) / 255.0;
  color[2] = (best->first & 255) / 255.0;
  opacity = minAlpha / 255.0;
}

/// A closed box [0,w] x [0,d] x [-t,0] of 12 triangles with a green RGBA "Colors" array.
vtkSmartPointer<vtkPolyData> Plate(double w, double d, double t)
{
  vtkNew<vtkPoints> points;
  for (int k = 0; k < 8; ++k)
  {
    points->InsertNextPoint((k & 1) ? w : 0.0, (k & 2) ? d : 0.0, (k & 4) ? 0.0 : -t);
  }
  // Outward-facing (counter-clockwise seen from outside) quads split into triangles.
  const int quads[6][4] = { { 0, 2, 3, 1 }, { 4, 5, 7, 6 }, { 0, 1, 5, 4 }, { 2, 6, 7, 3 },
    { 0, 4, 6, 2 }, { 1, 3, 7, 5 } };
  vtkNew<vtkCellArray> polys;
  for (const auto& q : quads)
  {
    const vtkIdType a[3] = { q[0], q[1], q[2] }, b[3] = { q[0], q[2], q[3] };
    polys->InsertNextCell(3, a);
    polys->InsertNextCell(3, b);
  }
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetName("Colors");
  colors->SetNumberOfComponents(4);
  colors->SetNumberOfTuples(12);
  const unsigned char green[4] = { 26, 110, 52, 255 };
  for (int c = 0; c < 4; ++c)
  {
    colors->FillComponent(c, green[c]);
  }
  auto plate = vtkSmartPointer<vtkPolyData>::New();
  plate->SetPoints(points);
  plate->SetPolys(polys);
  plate->GetCellData()->SetScalars(colors);
  return plate;
}

std::vector<std::string> SortedWrl(const fs::path& folder)
{
  std::vector<std::string> files;
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec))
  {
    if (it->path().extension() == ".wrl")
    {
      files.push_back(it->path().filename().string());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

/// Merge all instances into one polydata (points transformed, "PartId" = instance index).
vtkSmartPointer<vtkPolyData> Merge(const std::vector<KiCadInstance>& instances)
{
  vtkIdType pointCount = 0, cellCount = 0;
  for (const KiCadInstance& inst : instances)
  {
    pointCount += inst.polys->GetNumberOfPoints();
    cellCount += inst.polys->GetNumberOfPolys();
  }
  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  points->SetNumberOfPoints(pointCount);
  float* xyz = static_cast<float*>(points->GetVoidPointer(0));
  vtkNew<vtkIdTypeArray> offsets, connectivity;
  offsets->SetNumberOfValues(cellCount + 1);
  connectivity->SetNumberOfValues(3 * cellCount); // triangles only (see Triangulated())
  vtkNew<vtkIdTypeArray> partIds;
  partIds->SetName("PartId");
  partIds->SetNumberOfValues(cellCount);
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetName("Colors");
  colors->SetNumberOfComponents(4);
  colors->SetNumberOfTuples(cellCount);
  vtkIdType pointBase = 0, cellBase = 0, connBase = 0;
  for (std::size_t i = 0; i < instances.size(); ++i)
  {
    vtkPolyData* pd = instances[i].polys;
    const vtkMatrix4x4* m = instances[i].matrix;
    for (vtkIdType p = 0; p < pd->GetNumberOfPoints(); ++p)
    {
      double x[3];
      pd->GetPoint(p, x);
      for (int r = 0; r < 3; ++r)
      {
        xyz[3 * (pointBase + p) + r] = static_cast<float>(m->GetElement(r, 0) * x[0] +
          m->GetElement(r, 1) * x[1] + m->GetElement(r, 2) * x[2] + m->GetElement(r, 3));
      }
    }
    auto* partColors = vtkUnsignedCharArray::SafeDownCast(pd->GetCellData()->GetScalars());
    vtkCellArray* polys = pd->GetPolys();
    const vtkIdType cells = polys->GetNumberOfCells();
    for (vtkIdType c = 0; c < cells; ++c)
    {
      vtkIdType n;
      const vtkIdType* ids;
      polys->GetCellAtId(c, n, ids);
      // Distinct points of a part can meet once rounded to float here: drop what collapsed
      // (see Triangulated() for why).
      if (n != 3 ||
        Degenerate(xyz + 3 * (pointBase + ids[0]), xyz + 3 * (pointBase + ids[1]),
          xyz + 3 * (pointBase + ids[2])))
      {
        continue;
      }
      offsets->SetValue(cellBase, connBase);
      for (vtkIdType k = 0; k < n; ++k)
      {
        connectivity->SetValue(connBase + k, pointBase + ids[k]);
      }
      connBase += n;
      partIds->SetValue(cellBase, static_cast<vtkIdType>(i));
      unsigned char* rgba = colors->GetPointer(4 * cellBase);
      if (partColors && partColors->GetNumberOfComponents() == 4)
      {
        std::copy_n(partColors->GetPointer(4 * c), 4, rgba);
      }
      else
      {
        rgba[0] = rgba[1] = rgba[2] = 200;
        rgba[3] = 255;
      }
      ++cellBase;
    }
    pointBase += pd->GetNumberOfPoints();
  }
  offsets->SetValue(cellBase, connBase);
  offsets->Resize(cellBase + 1);
  offsets->SetNumberOfValues(cellBase + 1);
  connectivity->Resize(connBase);
  connectivity->SetNumberOfValues(connBase);
  partIds->Resize(cellBase);
  partIds->SetNumberOfValues(cellBase);
  colors->Resize(cellBase);
  colors->SetNumberOfTuples(cellBase);
  vtkNew<vtkCellArray> polys;
  polys->SetData(offsets, connectivity);
  auto merged = vtkSmartPointer<vtkPolyData>::New();
  merged->SetPoints(points);
  merged->SetPolys(polys);
  merged->GetCellData()->AddArray(partIds);
  merged->GetCellData()->SetScalars(colors);
  return merged;
}
} // namespace

KiCadBoard MakeKiCadBoard(const KiCadBoardOptions& options)
{
  KiCadBoard board;
  const std::string dir = options.directory.empty() ? DataFile("kicad-wrl-dir") : options.directory;
  std::error_code ec;
  if (dir.empty() || !fs::is_directory(dir, ec))
  {
    board.error = "data absent: KiCad parts (key kicad-wrl-dir) not fetched, see DATA.md";
    return board;
  }
  std::vector<std::pair<std::string, std::vector<std::string>>> libraries;
  for (const char* library : kLibraries)
  {
    std::vector<std::string> files =
      SortedWrl(fs::path(dir) / (std::string(library) + ".3dshapes"));
    if (!files.empty())
    {
      libraries.emplace_back(library, std::move(files));
    }
  }
  if (libraries.empty())
  {
    board.error = "data absent: no .wrl files under '" + dir + "'";
    return board;
  }

  // ---- Part types: round-robin over the libraries, a random file of each, read once. --------
  std::mt19937 gen(options.seed);
  std::vector<Part> parts;
  std::set<std::string> tried;
  const std::size_t attempts = 4 * options.partTypes + 16;
  for (std::size_t a = 0; a < attempts && parts.size() < options.partTypes; ++a)
  {
    const auto& library = libraries[a % libraries.size()];
    const std::string file =
      library.first + ".3dshapes/" + library.second[gen() % library.second.size()];
    if (!tried.insert(file).second)
    {
      continue;
    }
    vtkSmartPointer<vtkPolyData> model = LoadModel((fs::path(dir) / file).string());
    if (!model)
    {
      continue; // an unreadable part is skipped, the board is built from the others
    }
    Part part;
    part.polys = Triangulated(model);
    const vtkIdType triangles = part.polys->GetNumberOfPolys();
    part.polys->GetBounds(part.bounds);
    const double w = part.bounds[1] - part.bounds[0], d = part.bounds[3] - part.bounds[2];
    if (triangles == 0 || static_cast<std::size_t>(triangles) > options.maximumTrianglesPerPart ||
      !std::isfinite(w) || !std::isfinite(d) || std::max(w, d) > 0.5 * kBoardDepth)
    {
      continue;
    }
    part.file = file;
    RepresentativeColor(part.polys, part.color, part.opacity);
    parts.push_back(std::move(part));
  }
  if (parts.empty())
  {
    board.error = "no readable KiCad part under '" + dir + "'";
    return board;
  }
  for (const Part& part : parts)
  {
    board.partFiles.push_back(part.file);
  }

  // ---- Placement: random parts on shelves of boards until the target is reached. ------------
  struct Placement
  {
    std::size_t part;
    std::size_t board;
    double x, y;
    bool turned;
  };
  std::vector<Placement> placements;
  std::size_t boardIndex = 0;
  double shelfX = kPartMargin, shelfY = kPartMargin, shelfDepth = 0.0;
  std::size_t triangles = 0;
  while (triangles < options.targetTriangles &&
    (options.maximumParts == 0 || placements.size() < options.maximumParts))
  {
    const std::size_t p = gen() % parts.size();
    const bool turned = options.rotate && (gen() & 1u);
    const double* b = parts[p].bounds;
    const double w = turned ? b[3] - b[2] : b[1] - b[0];
    const double d = turned ? b[1] - b[0] : b[3] - b[2];
    if (shelfX + w > kBoardWidth - kPartMargin)
    {
      shelfX = kPartMargin;
      shelfY += shelfDepth + kPartMargin;
      shelfDepth = 0.0;
    }
    if (shelfY + d > kBoardDepth - kPartMargin)
    {
      ++boardIndex;
      shelfX = shelfY = kPartMargin;
      shelfDepth = 0.0;
    }
    placements.push_back({ p, boardIndex, shelfX, shelfY, turned });
    shelfX += w + kPartMargin;
    shelfDepth = std::max(shelfDepth, d);
    triangles += static_cast<std::size_t>(parts[p].polys->GetNumberOfPolys());
  }
  board.boards = boardIndex + 1;
  const std::size_t columns =
    static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(board.boards))));
  auto boardOrigin = [&](std::size_t i, double& ox, double& oy)
  {
    ox = static_cast<double>(i % columns) * (kBoardWidth + kBoardGap);
    oy = static_cast<double>(i / columns) * (kBoardDepth + kBoardGap);
  };

  vtkSmartPointer<vtkPolyData> plate = Plate(kBoardWidth, kBoardDepth, kBoardThickness);
  for (std::size_t i = 0; i < board.boards; ++i)
  {
    KiCadInstance inst;
    inst.polys = plate;
    inst.matrix = vtkSmartPointer<vtkMatrix4x4>::New();
    double ox, oy;
    boardOrigin(i, ox, oy);
    inst.matrix->SetElement(0, 3, ox);
    inst.matrix->SetElement(1, 3, oy);
    inst.color[0] = 26 / 255.0;
    inst.color[1] = 110 / 255.0;
    inst.color[2] = 52 / 255.0;
    inst.partType = kNoPart;
    inst.triangles = plate->GetNumberOfPolys();
    board.instances.push_back(inst);
  }
  for (const Placement& pl : placements)
  {
    const Part& part = parts[pl.part];
    const double* b = part.bounds;
    double ox, oy;
    boardOrigin(pl.board, ox, oy);
    KiCadInstance inst;
    inst.polys = part.polys;
    inst.matrix = vtkSmartPointer<vtkMatrix4x4>::New();
    // Footprint's lower-left corner (after the turn) to the shelf position; z stays (KiCad's
    // z = 0 is the board surface, through-hole pins go below it).
    if (pl.turned)
    {
      // (x, y) -> (-y, x): the turned footprint starts at (-ymax, xmin).
      inst.matrix->SetElement(0, 0, 0.0);
      inst.matrix->SetElement(0, 1, -1.0);
      inst.matrix->SetElement(1, 0, 1.0);
      inst.matrix->SetElement(1, 1, 0.0);
      inst.matrix->SetElement(0, 3, ox + pl.x + b[3]);
      inst.matrix->SetElement(1, 3, oy + pl.y - b[0]);
    }
    else
    {
      inst.matrix->SetElement(0, 3, ox + pl.x - b[0]);
      inst.matrix->SetElement(1, 3, oy + pl.y - b[2]);
    }
    std::copy_n(part.color, 3, inst.color);
    inst.opacity = part.opacity;
    inst.partType = pl.part;
    inst.triangles = part.polys->GetNumberOfPolys();
    board.instances.push_back(inst);
  }
  board.triangles = 0;
  for (const KiCadInstance& inst : board.instances)
  {
    board.triangles += inst.triangles;
  }
  double ox, oy;
  boardOrigin(board.boards - 1, ox, oy);
  const std::size_t rows = (board.boards + columns - 1) / columns;
  board.bounds[0] = 0.0;
  board.bounds[1] =
    static_cast<double>(std::min(columns, board.boards)) * (kBoardWidth + kBoardGap) - kBoardGap;
  board.bounds[2] = 0.0;
  board.bounds[3] = static_cast<double>(rows) * (kBoardDepth + kBoardGap) - kBoardGap;
  board.bounds[4] = std::numeric_limits<double>::max();
  board.bounds[5] = std::numeric_limits<double>::lowest();
  for (const Part& part : parts)
  {
    board.bounds[4] = std::min(board.bounds[4], part.bounds[4]);
    board.bounds[5] = std::max(board.bounds[5], part.bounds[5]);
  }
  board.bounds[4] = std::min(board.bounds[4], -kBoardThickness);
  if (options.merged)
  {
    board.merged = Merge(board.instances);
    board.merged->GetBounds(board.bounds);
    board.triangles = board.merged->GetNumberOfPolys();
  }
  return board;
}

} // namespace testing
} // namespace scenevis
