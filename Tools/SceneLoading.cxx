// The scene a command works on: loading, checking, colours, portals, normals.
#include "SceneLoading.h"

#include "Memory.h"
#include "Progress.h"
#include "SplitParts.h"
#include "UntrustedFiles.h"
#include "vtkDemoSceneSource.h"
#include "vtkSceneVisModelReader.h"

#include "scenevis/Scenes.h"
#include <vtkDemoScenePortals.h>
#include <vtkSceneVisDataCache.h>

#include <vtkAbstractArray.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyDataNormals.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <stdexcept>
#include <unordered_set>

namespace scenevis
{
namespace tool
{
namespace
{
/// Stores the cells of @p pd with 32-bit offsets and ids when they fit, as VTK can: readers give
/// 64-bit ids, 32 bytes per triangle where 16 do (0.78 GB of the 48.6M-triangle engine grid, on
/// top of which every path builds its own buffers). The copy is made one cell array at a time.
/// Returns the bytes saved.
std::uint64_t CompactCellStorage(vtkPolyData* pd)
{
  std::uint64_t saved = 0;
  for (vtkCellArray* cells : { pd->GetVerts(), pd->GetLines(), pd->GetPolys(), pd->GetStrips() })
  {
    if (cells && cells->IsStorage64Bit() && cells->CanConvertTo32BitStorage())
    {
      const unsigned long before = cells->GetActualMemorySize();
      if (cells->ConvertTo32BitStorage())
        saved += 1024u * (before - std::min(before, cells->GetActualMemorySize()));
    }
  }
  return saved;
}

/// Reads --portals; a missing file or one without RoomA/RoomB arrays is an error (exit 1). A file
/// without cells is no portals (what `scenevis portals` writes for a model without openings, or
/// for one that leaks: every cell in the outside).
vtkSmartPointer<vtkPolyData> LoadPortals(const std::string& path)
{
  std::string error;
  vtkSmartPointer<vtkPolyData> portals;
  {
    QuietVtkOutput quiet;
    portals = LoadModelKeepingNonFinite(path, &error);
  }
  const std::string noCells = "no cells";
  if (!portals && error.size() >= noCells.size() &&
    error.compare(error.size() - noCells.size(), noCells.size(), noCells) == 0)
  {
    portals = vtkSmartPointer<vtkPolyData>::New();
    portals->SetPoints(vtkNew<vtkPoints>());
    portals->SetPolys(vtkNew<vtkCellArray>());
    for (const char* name : { "RoomA", "RoomB" })
    {
      vtkNew<vtkIntArray> rooms;
      rooms->SetName(name);
      portals->GetCellData()->AddArray(rooms);
    }
  }
  if (!portals)
  {
    throw std::runtime_error("--portals: " + error);
  }
  for (const char* name : { "RoomA", "RoomB" })
  {
    vtkDataArray* array = portals->GetCellData()->GetArray(name);
    if (!array || array->GetNumberOfComponents() != 1)
    {
      throw std::runtime_error("--portals: '" + path + "' has no one-component cell array '" +
        name + "' (see vtkPortalCuller.h for the format)");
    }
  }
  return portals;
}

/// Above this many distinct part (or room) values, one actor each would take minutes to set up
/// and gigabytes to hold: such an array is almost certainly not one of parts (e.g. a cell id).
constexpr std::size_t kMaxDistinctKeys = 1000000;

bool IsIntegerType(int type)
{
  switch (type)
  {
    case VTK_CHAR:
    case VTK_SIGNED_CHAR:
    case VTK_UNSIGNED_CHAR:
    case VTK_SHORT:
    case VTK_UNSIGNED_SHORT:
    case VTK_INT:
    case VTK_UNSIGNED_INT:
    case VTK_LONG:
    case VTK_UNSIGNED_LONG:
    case VTK_LONG_LONG:
    case VTK_UNSIGNED_LONG_LONG:
    case VTK_ID_TYPE:
      return true;
    default:
      return false;
  }
}

/**
 * The part and room arrays render, cull and bench split the scene by: one integer per cell and
 * at most kMaxDistinctKeys values. One named with --part-array / --room-array must exist; the
 * default names may be absent (a scene without parts or rooms). Checked before anything costly
 * is built or anything is written. Errors name the arrays the scene has.
 */
void CheckKeyArrays(vtkPolyData* pd, const Options& options)
{
  struct Key
  {
    const char* flag;
    const std::string& name;
    bool named;
  };
  for (const Key& key : { Key{ "--part-array", options.partArray, options.partArraySet },
         Key{ "--room-array", options.roomArray, options.roomArraySet } })
  {
    vtkAbstractArray* array = pd->GetCellData()->GetAbstractArray(key.name.c_str());
    const std::string what = std::string("cell array '") + key.name + "' (" + key.flag + ")";
    if (!array)
    {
      if (!key.named)
        continue;
      std::string names;
      for (int i = 0; i < pd->GetCellData()->GetNumberOfArrays(); ++i)
      {
        const char* name = pd->GetCellData()->GetArrayName(i);
        names += (i ? ", " : "") + std::string(name ? name : "(unnamed)");
      }
      throw std::runtime_error("the scene has no " + what +
        (pd->GetPointData()->GetAbstractArray(key.name.c_str()) ? " (it is a point array)" : "") +
        "; its cell arrays: " + (names.empty() ? "none" : names));
    }
    auto* values = vtkDataArray::SafeDownCast(array);
    if (!values || !IsIntegerType(array->GetDataType()) || array->GetNumberOfComponents() != 1)
    {
      throw std::runtime_error("the " + what + " holds " +
        std::to_string(array->GetNumberOfComponents()) + "-component " +
        array->GetDataTypeAsString() + " values, not one integer per cell");
    }
    std::unordered_set<long long> distinct;
    for (vtkIdType c = 0; c < values->GetNumberOfTuples(); ++c)
    {
      distinct.insert(static_cast<long long>(values->GetTuple1(c)));
      if (distinct.size() > kMaxDistinctKeys)
      {
        throw std::runtime_error("the " + what + " has more than " +
          std::to_string(kMaxDistinctKeys) +
          " distinct values: refusing to make an actor of each (is it an array of parts?)");
      }
    }
  }
}

/// Above this many triangles, computed normals keep the polygons' orientation as the file has it.
constexpr vtkIdType kMaxTrianglesToReorient = 2000000;
} // namespace

LoadedScene LoadScene(const Options& options)
{
  LoadedScene loaded;
  const auto start = std::chrono::steady_clock::now();
  vtkNew<vtkDemoSceneSource> demo;
  if (demo->SetSceneByName(options.scene.c_str()))
  {
    demo->SetTriangleCount(options.triangles);
    demo->SetPartCount(options.parts);
    demo->Update();
    loaded.polydata = demo->GetOutput();
    loaded.description = "embedded demo '" + options.scene + "'";
    if (options.opacitySet)
    {
      // The demos mix translucent and opaque parts on purpose (and the figures in BENCHMARKS.md
      // are measured on them as made): --opacity does not flatten them, and says so.
      loaded.description += " (its own opacities: --opacity ignored)";
      std::cerr << "scenevis: warning: --opacity is ignored for the embedded demo '"
                << options.scene << "', which keeps its own opacities\n";
    }
    loaded.zUp = demo->GetScene() == vtkDemoSceneSource::SCENE_CAD_ASSEMBLY ||
      demo->GetScene() == vtkDemoSceneSource::SCENE_BUILDING;
    if (demo->GetScene() == vtkDemoSceneSource::SCENE_BUILDING)
    {
      // The same generator call as the source's, for the portals it does not output.
      loaded.portals = scenevis::MakePortalPolyData(scenevis::scenes::building(
        demo->GetFloors(), demo->GetRoomsX(), demo->GetRoomsY(), demo->GetSeed()));
    }
    if (!options.portals.empty())
    {
      loaded.portals = LoadPortals(options.portals);
    }
    loaded.loadMs = Milliseconds(start);
    return loaded;
  }
  std::string name = options.scene;
  std::string description = "file '" + name + "'";
  if (name.find('.') == std::string::npos)
  {
    const std::string cached = scenevis::DataFile(name);
    if (cached.empty())
    {
      throw UsageError("--scene '" + name +
        "' is neither a demo scene (spheres, cyclic-quads, triangles, cad, building), nor a "
        "fetched data key (scripts/fetch-data.sh), nor a model file (.vtp .vtk .ply .stl .obj "
        ".glb .gltf .wrl)");
    }
    description = "data '" + name + "' (" + cached + ")";
    name = cached;
  }
  CheckFitsInMemory(name);
  if (options.instances && !IsInstanceable(name))
    throw UsageError("--instances reads glTF and VRML files (.glb .gltf .wrl), not '" + name + "'");
  std::string error;
  {
    QuietVtkOutput quiet;
    loaded.polydata = options.instances ? LoadModelIsolated(name, error, LoadMeshLibrary)
                                        : LoadModelIsolated(name, error);
  }
  if (!loaded.polydata)
  {
    throw std::runtime_error(error);
  }
  CheckPointIds(loaded.polydata, name);
  // No renderer can draw cells with a NaN or infinite point, and VTK's point bounds skip NaN
  // points but not infinite ones: one such point would leave every method an empty image.
  if (const vtkIdType removed =
        vtkSceneVisModelReader::RemoveCellsWithNonFinitePoints(loaded.polydata))
  {
    description += ", " + std::to_string(removed) + " cell(s) with NaN/Inf points removed";
    if (loaded.polydata->GetNumberOfCells() == 0)
      throw std::runtime_error("cannot use '" + name + "': every cell has a NaN/Inf point");
  }
  // RGBA cell scalars like the demo scenes: the parts' own colours and opacities of imported
  // scenes (glTF, VRML, or a .vtp written by --export-scene: a "Colors" array), else one uniform
  // opaque colour. --opacity replaces every cell's alpha: a file says how translucent it is
  // unless the user asks for translucency.
  const vtkIdType cells = loaded.polydata->GetNumberOfCells();
  auto* own =
    vtkUnsignedCharArray::SafeDownCast(loaded.polydata->GetCellData()->GetArray("Colors"));
  if (own && (own->GetNumberOfComponents() < 3 || own->GetNumberOfTuples() != cells))
  {
    own = nullptr;
  }
  const bool ownAlpha = own && own->GetNumberOfComponents() >= 4 && !options.opacitySet;
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetName("Colors");
  colors->SetNumberOfComponents(4);
  colors->SetNumberOfTuples(cells);
  const auto alpha =
    static_cast<unsigned char>(options.opacitySet ? std::lround(options.opacity * 255.0) : 255);
  unsigned char rgba[4] = { 200, 170, 120, alpha };
  for (vtkIdType c = 0; c < cells; ++c)
  {
    if (own)
    {
      for (int k = 0; k < (ownAlpha ? 4 : 3); ++k)
        rgba[k] = own->GetTypedComponent(c, k);
    }
    colors->SetTypedTuple(c, rgba);
  }
  loaded.polydata->GetCellData()->RemoveArray("Colors");
  loaded.polydata->GetCellData()->SetScalars(colors);
  loaded.description = description;
  if (!options.portals.empty())
  {
    loaded.portals = LoadPortals(options.portals);
  }
  loaded.loadMs = Milliseconds(start);
  return loaded;
}

LoadedScene LoadSceneWithNormals(const Options& options)
{
  LoadedScene scene = LoadScene(options);
  const auto checkStart = std::chrono::steady_clock::now();
  CheckKeyArrays(scene.polydata, options);
  scene.checkMs = Milliseconds(checkStart);
  const auto normalsStart = std::chrono::steady_clock::now();
  // A mesh library's placements, which filters need not pass on (kept alive, not copied).
  const vtkSmartPointer<vtkFieldData> placements = scene.polydata->GetFieldData();
  if (!scene.polydata->GetPointData()->GetNormals())
  {
    // Smooth shading; sharp edges (CAD, buildings) stay sharp. The sorters carry normals along.
    vtkNew<vtkPolyDataNormals> normals;
    normals->SetInputData(scene.polydata);
    normals->SetFeatureAngle(50.0);
    // Re-orienting polygons consistently walks the whole mesh cell by cell: 60 % of the normals'
    // time on the 12M-triangle engine grid (16.6 s -> 6.3 s without). Big models come from
    // exporters that orient them; small ones (hand-made, scanned) keep the repair.
    if (CountTriangles(scene.polydata) > kMaxTrianglesToReorient)
      normals->ConsistencyOff();
    normals->Update();
    scene.polydata = normals->GetOutput();
  }
  scene.normalsMs = Milliseconds(normalsStart);
  const auto compactStart = std::chrono::steady_clock::now();
  scene.compactedBytes = CompactCellStorage(scene.polydata);
  scene.checkMs += Milliseconds(compactStart);
  if (options.instances)
  {
    scene.polydata->SetFieldData(placements);
    scene.instanced = std::make_shared<InstancedScene>(UnpackMeshLibrary(scene.polydata));
    // The placements now live in the scene's instances (6 MB of matrices for 46,000 of them).
    scene.polydata->SetFieldData(vtkSmartPointer<vtkFieldData>::New());
    scene.description += ", " + std::to_string(scene.instanced->meshes.size()) + " meshes placed " +
      std::to_string(scene.instanced->instances.size()) + " times";
  }
  scene.rssAfterLoad = ReadResidentMemory().current;
  return scene;
}

void SceneBounds(const LoadedScene& scene, double bounds[6])
{
  if (scene.instanced)
    InstancedBounds(*scene.instanced, bounds);
  else
    scene.polydata->GetBounds(bounds);
}

std::vector<vtkSmartPointer<vtkPolyData>> SplitByPart(
  vtkPolyData* pd, const std::string& partArray, bool releaseInputPolygons)
{
  return SplitByKeys(pd, { partArray }, releaseInputPolygons);
}

vtkIdType CountTriangles(vtkPolyData* pd)
{
  vtkIdType triangles = 0;
  vtkIdType npts = 0;
  const vtkIdType* pts = nullptr;
  vtkCellArray* polys = pd->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(npts, pts);)
  {
    triangles += std::max<vtkIdType>(npts - 2, 0);
  }
  vtkCellArray* strips = pd->GetStrips();
  for (strips->InitTraversal(); strips->GetNextCell(npts, pts);)
  {
    triangles += std::max<vtkIdType>(npts - 2, 0);
  }
  return triangles;
}

} // namespace tool
} // namespace scenevis
