#include "vtkAutoRooms.h"

#include "vtkGenerateRooms.h"

#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkType.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <vector>

namespace
{
double MillisecondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
    .count();
}

/// Newell's normal of polygon @p pts in @p n (twice its area, along its normal); returns its
/// length.
double NewellNormal(vtkPoints* points, vtkIdType npts, const vtkIdType* pts, double n[3])
{
  n[0] = n[1] = n[2] = 0.0;
  for (vtkIdType k = 0; k < npts; ++k)
  {
    double a[3], b[3];
    points->GetPoint(pts[k], a);
    points->GetPoint(pts[(k + 1) % npts], b);
    n[0] += (a[1] - b[1]) * (a[2] + b[2]);
    n[1] += (a[2] - b[2]) * (a[0] + b[0]);
    n[2] += (a[0] - b[0]) * (a[1] + b[1]);
  }
  return std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

/// Calls @p visit(npts, pts, n, area) for each polygon of @p model with a finite, non-zero
/// Newell normal @p n (see NewellNormal).
template <typename Visit>
void ForEachPolygonNormal(vtkPolyData* model, Visit&& visit)
{
  vtkPoints* points = model->GetPoints();
  vtkCellArray* polys = model->GetPolys();
  vtkIdType npts = 0;
  const vtkIdType* pts = nullptr;
  for (polys->InitTraversal(); points && polys->GetNextCell(npts, pts);)
  {
    double n[3];
    const double area = NewellNormal(points, npts, pts, n);
    if (area > 0.0 && std::isfinite(area))
      visit(npts, pts, n, area);
  }
}

/**
 * Of the area of the polygons facing along an axis (within 1 degree), the share that faces a
 * polygon turned towards it further along that axis: a floor under a ceiling, a wall across a
 * room from another. On a 64 x 64 grid over the other two axes, each polygon's box marks the
 * farthest (nearest) facing-back polygon of every grid cell; a polygon's centre cell is then
 * looked up. Linear in the polygons (and their boxes' grid cells).
 */
/// Also the least of the per-axis shares in @p leastAxis (axes facing at least a tenth of the
/// area), and that axis in @p leastAxisIndex (-1 without facing area).
double EnclosedAreaOf(vtkPolyData* model, double alongCos, double& leastAxis, int& leastAxisIndex)
{
  constexpr int kGrid = 64;
  double bounds[6];
  model->GetBounds(bounds);
  struct Facing
  {
    int axis;
    bool positive;
    double coordinate;
    double area;
    double box[6];
  };
  std::vector<Facing> facing;
  vtkPoints* points = model->GetPoints();
  ForEachPolygonNormal(model,
    [&](vtkIdType npts, const vtkIdType* pts, const double n[3], double area)
    {
      Facing f{};
      for (int k = 0; k < 3; ++k)
      {
        f.box[2 * k] = VTK_DOUBLE_MAX;
        f.box[2 * k + 1] = -VTK_DOUBLE_MAX;
      }
      for (vtkIdType k = 0; k < npts; ++k)
      {
        double a[3];
        points->GetPoint(pts[k], a);
        for (int c = 0; c < 3; ++c)
        {
          f.box[2 * c] = std::min(f.box[2 * c], a[c]);
          f.box[2 * c + 1] = std::max(f.box[2 * c + 1], a[c]);
        }
      }
      for (int axis = 0; axis < 3; ++axis)
      {
        if (std::abs(n[axis]) / area >= alongCos)
        {
          f.axis = axis;
          f.positive = n[axis] > 0.0;
          f.coordinate = 0.5 * (f.box[2 * axis] + f.box[2 * axis + 1]);
          f.area = area;
          facing.push_back(f);
        }
      }
    });
  // Per axis: the largest coordinate of a polygon facing -axis and the smallest of one facing
  // +axis over each grid cell.
  std::vector<double> farthestBack(3 * kGrid * kGrid, -VTK_DOUBLE_MAX);
  std::vector<double> nearestFront(3 * kGrid * kGrid, VTK_DOUBLE_MAX);
  auto cellRange = [&](int axis, int which, double lo, double hi, int& first, int& last)
  {
    const int d = (axis + 1 + which) % 3;
    const double size = bounds[2 * d + 1] - bounds[2 * d];
    auto index = [&](double x)
    {
      const double t = size > 0.0 ? (x - bounds[2 * d]) / size : 0.0;
      return std::clamp(static_cast<int>(t * kGrid), 0, kGrid - 1);
    };
    first = index(lo);
    last = index(hi);
  };
  for (const Facing& f : facing)
  {
    int u0, u1, v0, v1;
    const int du = (f.axis + 1) % 3, dv = (f.axis + 2) % 3;
    cellRange(f.axis, 0, f.box[2 * du], f.box[2 * du + 1], u0, u1);
    cellRange(f.axis, 1, f.box[2 * dv], f.box[2 * dv + 1], v0, v1);
    for (int u = u0; u <= u1; ++u)
      for (int v = v0; v <= v1; ++v)
      {
        const std::size_t cell = static_cast<std::size_t>((f.axis * kGrid + u) * kGrid + v);
        if (f.positive)
          nearestFront[cell] = std::min(nearestFront[cell], f.coordinate);
        else
          farthestBack[cell] = std::max(farthestBack[cell], f.coordinate);
      }
  }
  double total = 0.0;
  double enclosed = 0.0;
  std::array<double, 3> axisTotal{ 0.0, 0.0, 0.0 };
  std::array<double, 3> axisEnclosed{ 0.0, 0.0, 0.0 };
  for (const Facing& f : facing)
  {
    int u, v, unused;
    const int du = (f.axis + 1) % 3, dv = (f.axis + 2) % 3;
    cellRange(f.axis, 0, 0.5 * (f.box[2 * du] + f.box[2 * du + 1]), 0.0, u, unused);
    cellRange(f.axis, 1, 0.5 * (f.box[2 * dv] + f.box[2 * dv + 1]), 0.0, v, unused);
    const std::size_t cell = static_cast<std::size_t>((f.axis * kGrid + u) * kGrid + v);
    total += f.area;
    axisTotal[static_cast<std::size_t>(f.axis)] += f.area;
    if (f.positive ? farthestBack[cell] > f.coordinate : nearestFront[cell] < f.coordinate)
    {
      enclosed += f.area;
      axisEnclosed[static_cast<std::size_t>(f.axis)] += f.area;
    }
  }
  leastAxis = 0.0;
  leastAxisIndex = -1;
  for (std::size_t axis = 0; axis < 3; ++axis)
  {
    if (axisTotal[axis] >= 0.1 * total && axisTotal[axis] > 0.0)
    {
      const double share = axisEnclosed[axis] / axisTotal[axis];
      if (leastAxisIndex < 0 || share < leastAxis)
      {
        leastAxis = share;
        leastAxisIndex = static_cast<int>(axis);
      }
    }
  }
  return total > 0.0 ? enclosed / total : 0.0;
}
} // namespace

vtkArchitecturalLook vtkArchitecturalLook::Of(vtkPolyData* model)
{
  const auto start = std::chrono::steady_clock::now();
  vtkArchitecturalLook look;
  look.Polygons = static_cast<std::size_t>(
    model->GetPolys()->GetNumberOfCells() + model->GetStrips()->GetNumberOfCells());
  std::ostringstream why;
  why << std::fixed << std::setprecision(2);
  if (look.Polygons > MaximumPolygons)
  {
    look.Milliseconds = MillisecondsSince(start);
    why << look.Polygons << " polygons (> " << MaximumPolygons
        << ", too many to generate rooms and portals for)";
    look.Reason = why.str();
    return look;
  }
  // Within 1 degree of an axis plane: facing along the axis, or perpendicular to it.
  const double alongCos = std::cos(std::acos(-1.0) / 180.0);
  const double acrossSin = std::sin(std::acos(-1.0) / 180.0);
  std::array<double, 3> aligned{ 0.0, 0.0, 0.0 };
  double total = 0.0;
  ForEachPolygonNormal(model,
    [&](vtkIdType, const vtkIdType*, const double n[3], double area)
    {
      total += area;
      for (int axis = 0; axis < 3; ++axis)
      {
        const double c = std::abs(n[axis]) / area;
        if (c >= alongCos || c <= acrossSin)
          aligned[axis] += area;
      }
    });
  int leastAxisIndex = -1;
  look.EnclosedArea = EnclosedAreaOf(model, alongCos, look.LeastEnclosedAxis, leastAxisIndex);
  const double best = std::max({ aligned[0], aligned[1], aligned[2] });
  look.AlignedArea = total > 0.0 ? best / total : 0.0;
  look.LooksArchitectural = look.AlignedArea >= MinimumAlignedArea &&
    look.EnclosedArea >= MinimumEnclosedArea && look.LeastEnclosedAxis >= MinimumLeastEnclosedAxis;
  look.Milliseconds = MillisecondsSince(start);
  why << look.Polygons << " polygons, " << 100.0 * look.AlignedArea
      << " % of their area in axis-aligned planes ("
      << (look.AlignedArea >= MinimumAlignedArea ? ">=" : "<") << " " << 100.0 * MinimumAlignedArea
      << " %), " << 100.0 * look.EnclosedArea
      << " % of that area faces another polygon across open space ("
      << (look.EnclosedArea >= MinimumEnclosedArea ? ">=" : "<") << " "
      << 100.0 * MinimumEnclosedArea << " %), " << 100.0 * look.LeastEnclosedAxis
      << " % along the least enclosed axis, "
      << "xyz?"[leastAxisIndex < 0 ? 3 : leastAxisIndex] << " ("
      << (look.LeastEnclosedAxis >= MinimumLeastEnclosedAxis ? ">=" : "<") << " "
      << 100.0 * MinimumLeastEnclosedAxis << " %), tested in " << look.Milliseconds << " ms";
  look.Reason = why.str();
  return look;
}

vtkAutoRooms vtkAutoRooms::Generate(
  vtkPolyData* model, const char* roomArrayName, double budgetSeconds)
{
  const auto start = std::chrono::steady_clock::now();
  vtkAutoRooms autoRooms;
  const vtkArchitecturalLook look = vtkArchitecturalLook::Of(model);
  if (!look.LooksArchitectural)
  {
    autoRooms.Milliseconds = MillisecondsSince(start);
    autoRooms.Reason = "rooms and portals not generated: " + look.Reason;
    return autoRooms;
  }
  autoRooms.Tried = true;
  vtkNew<vtkGenerateRooms> generate;
  generate->SetInputData(model);
  generate->SetRoomArrayName(roomArrayName);
  generate->SetBudgetSeconds(budgetSeconds);
  generate->StopAtFirstLeakOn();
  // The reason says what was found; a leak or a budget is an answer here, not a warning.
  vtkNew<vtkCallbackCommand> quiet;
  generate->AddObserver(vtkCommand::WarningEvent, quiet);
  generate->Update();
  autoRooms.Milliseconds = MillisecondsSince(start);
  autoRooms.RoomCount = generate->GetNumberOfRooms();
  autoRooms.PortalCount = static_cast<std::size_t>(generate->GetNumberOfPortals());
  autoRooms.ExteriorPortals = static_cast<std::size_t>(generate->GetNumberOfExteriorPortals());
  autoRooms.LeakCells = static_cast<std::size_t>(generate->GetNumberOfLeakCells());
  std::ostringstream why;
  why << std::fixed << std::setprecision(0);
  if (generate->GetStatus() != vtkGenerateRooms::STATUS_OK)
  {
    why << "generating rooms and portals failed (" << generate->GetStatusMessage() << ") in "
        << autoRooms.Milliseconds << " ms, so not used";
  }
  else if (autoRooms.RoomCount < 2 || autoRooms.PortalCount == 0 || autoRooms.LeakCells > 0)
  {
    why << "rooms and portals generated (" << look.Reason << "): " << autoRooms.RoomCount
        << " rooms, " << autoRooms.PortalCount << " portals, " << autoRooms.LeakCells
        << " leak cells in " << autoRooms.Milliseconds
        << " ms, not used (needs >= 2 rooms, >= 1 portal, no leak)";
  }
  else
  {
    autoRooms.Used = true;
    autoRooms.Rooms = vtkIntArray::SafeDownCast(
      generate->GetOutput()->GetCellData()->GetArray(generate->GetRoomArrayName()));
    autoRooms.Portals = generate->GetPortalsOutput();
    why << "generated " << autoRooms.RoomCount << " rooms, " << autoRooms.PortalCount
        << " portals (" << autoRooms.ExteriorPortals << " to the outside, 0 leak cells) in "
        << autoRooms.Milliseconds << " ms because " << look.Reason;
  }
  autoRooms.Reason = why.str();
  return autoRooms;
}
