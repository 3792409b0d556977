#include "vtkDemoSceneSource.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"

#include "scenevis/Scenes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <exception>
#include <vector>

vtkStandardNewMacro(vtkDemoSceneSource);

namespace
{
const char* const SceneNames[] = { "spheres", "cyclic-quads", "triangles", "cad", "building" };

unsigned char ToByte(double v)
{
  return static_cast<unsigned char>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0));
}

void ToPolyData(const scenevis::scenes::Scene& scene, vtkPolyData* output)
{
  const scenevis::PolygonMesh& mesh = scene.mesh;
  vtkNew<vtkDoubleArray> coordinates;
  coordinates->SetNumberOfComponents(3);
  coordinates->SetNumberOfTuples(static_cast<vtkIdType>(mesh.points.size()));
  std::copy_n(&mesh.points[0].x, 3 * mesh.points.size(), coordinates->GetPointer(0));
  vtkNew<vtkPoints> points;
  points->SetData(coordinates);

  vtkNew<vtkIdTypeArray> offsets;
  offsets->SetNumberOfTuples(static_cast<vtkIdType>(mesh.offsets.size()));
  std::copy(mesh.offsets.begin(), mesh.offsets.end(), offsets->GetPointer(0));
  vtkNew<vtkIdTypeArray> connectivity;
  connectivity->SetNumberOfTuples(static_cast<vtkIdType>(mesh.indices.size()));
  std::copy(mesh.indices.begin(), mesh.indices.end(), connectivity->GetPointer(0));
  vtkNew<vtkCellArray> polys;
  polys->SetData(offsets, connectivity);

  output->SetPoints(points);
  output->SetPolys(polys);

  const vtkIdType numPolys = static_cast<vtkIdType>(mesh.polygonCount());
  vtkNew<vtkIdTypeArray> partIds;
  partIds->SetName("PartId");
  partIds->SetNumberOfTuples(numPolys);
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetName("Colors");
  colors->SetNumberOfComponents(4);
  colors->SetNumberOfTuples(numPolys);
  for (vtkIdType c = 0; c < numPolys; ++c)
  {
    const std::uint32_t p = scene.part[static_cast<std::size_t>(c)];
    const scenevis::scenes::Part& part = scene.parts[p];
    partIds->SetValue(c, p);
    colors->SetTypedTuple(c, std::array<unsigned char, 4>{ ToByte(part.colour.r),
                               ToByte(part.colour.g), ToByte(part.colour.b), ToByte(part.opacity) }
                               .data());
  }
  output->GetCellData()->AddArray(partIds);
  output->GetCellData()->SetScalars(colors);

  vtkNew<vtkStringArray> names;
  names->SetName("PartNames");
  vtkNew<vtkUnsignedCharArray> partColors;
  partColors->SetName("PartColors");
  partColors->SetNumberOfComponents(4);
  for (const scenevis::scenes::Part& part : scene.parts)
  {
    names->InsertNextValue(part.name);
    const unsigned char rgba[4] = { ToByte(part.colour.r), ToByte(part.colour.g),
      ToByte(part.colour.b), ToByte(part.opacity) };
    partColors->InsertNextTypedTuple(rgba);
  }
  output->GetFieldData()->AddArray(names);
  output->GetFieldData()->AddArray(partColors);
}

/**
 * Keep only piece @p piece of @p pieces of a scene: whole parts, in contiguous runs of part ids
 * balanced by polygons (part p goes to the piece its first polygon falls in when the polygons are
 * counted in part order), with the points they use. Cell data follows the cells; the field data
 * (part names and colours, indexed by the global PartId) stays whole.
 */
void KeepPiece(vtkPolyData* pd, int piece, int pieces)
{
  auto* partIds = vtkIdTypeArray::SafeDownCast(pd->GetCellData()->GetArray("PartId"));
  const vtkIdType cells = pd->GetNumberOfCells();
  if (!partIds || cells == 0)
  {
    return;
  }
  vtkIdType parts = 0;
  for (vtkIdType c = 0; c < cells; ++c)
  {
    parts = std::max(parts, partIds->GetValue(c) + 1);
  }
  std::vector<vtkIdType> before(static_cast<std::size_t>(parts) + 1, 0);
  for (vtkIdType c = 0; c < cells; ++c)
  {
    ++before[static_cast<std::size_t>(partIds->GetValue(c)) + 1];
  }
  for (std::size_t p = 1; p < before.size(); ++p)
  {
    before[p] += before[p - 1];
  }
  const auto pieceOf = [&](vtkIdType part)
  { return static_cast<int>(before[static_cast<std::size_t>(part)] * pieces / cells); };

  vtkNew<vtkPolyData> kept;
  kept->GetCellData()->CopyAllocate(pd->GetCellData());
  vtkNew<vtkCellArray> polys;
  vtkNew<vtkPoints> points;
  points->SetDataType(pd->GetPoints()->GetDataType());
  std::vector<vtkIdType> newId(static_cast<std::size_t>(pd->GetNumberOfPoints()), -1);
  vtkIdType npts = 0;
  const vtkIdType* ids = nullptr;
  std::vector<vtkIdType> cell;
  vtkCellArray* in = pd->GetPolys();
  for (vtkIdType c = 0; c < cells; ++c)
  {
    in->GetCellAtId(c, npts, ids);
    if (pieceOf(partIds->GetValue(c)) != piece)
    {
      continue;
    }
    cell.assign(ids, ids + npts);
    for (vtkIdType& id : cell)
    {
      vtkIdType& mapped = newId[static_cast<std::size_t>(id)];
      if (mapped < 0)
      {
        mapped = points->InsertNextPoint(pd->GetPoint(id));
      }
      id = mapped;
    }
    kept->GetCellData()->CopyData(pd->GetCellData(), c, polys->InsertNextCell(npts, cell.data()));
  }
  kept->SetPoints(points);
  kept->SetPolys(polys);
  kept->GetFieldData()->ShallowCopy(pd->GetFieldData());
  kept->GetCellData()->SetActiveScalars(
    pd->GetCellData()->GetScalars() ? pd->GetCellData()->GetScalars()->GetName() : nullptr);
  pd->ShallowCopy(kept);
}
} // namespace

//------------------------------------------------------------------------------
vtkDemoSceneSource::vtkDemoSceneSource()
{
  this->SetNumberOfInputPorts(0);
}

//------------------------------------------------------------------------------
bool vtkDemoSceneSource::SetSceneByName(const char* name)
{
  for (int s = SCENE_SPHERE_GRID; s <= SCENE_BUILDING; ++s)
  {
    if (name && std::strcmp(name, SceneNames[s]) == 0)
    {
      this->SetScene(s);
      return true;
    }
  }
  return false;
}

//------------------------------------------------------------------------------
const char* vtkDemoSceneSource::GetSceneName(int scene)
{
  return scene >= SCENE_SPHERE_GRID && scene <= SCENE_BUILDING ? SceneNames[scene] : "unknown";
}

//------------------------------------------------------------------------------
namespace
{
/// Fewest triangles a CAD part gets (a 100-part assembly asked for 100 triangles has 4,848).
constexpr vtkIdType kMinTrianglesPerPart = 40;
/// Triangles per room of the building, about (3 x 4 x 3 rooms: 5,252 triangles).
constexpr vtkIdType kTrianglesPerRoom = 150;

/// @p value clamped to [lo, hi]; @p clamped says whether it had to be.
template <typename T>
T Clamped(T value, T lo, T hi, bool& clamped)
{
  clamped = value < lo || value > hi;
  return value < lo ? lo : (value > hi ? hi : value);
}
} // namespace

#define SCENEVIS_CLAMPED_SETTER(Name, Type, Lo, Hi)                                              \
  void vtkDemoSceneSource::Set##Name(Type count)                                               \
  {                                                                                             \
    bool clamped = false;                                                                       \
    const Type value = Clamped<Type>(count, Lo, Hi, clamped);                                  \
    if (clamped)                                                                                \
    {                                                                                           \
      vtkWarningMacro(#Name " " << count << " is outside [" << (Lo) << ", " << (Hi)             \
                                << "]: using " << value << ".");                                \
    }                                                                                           \
    if (this->Name != value)                                                                    \
    {                                                                                           \
      this->Name = value;                                                                       \
      this->Modified();                                                                         \
    }                                                                                           \
  }

SCENEVIS_CLAMPED_SETTER(TriangleCount, vtkIdType, 64, VTK_ID_MAX)
SCENEVIS_CLAMPED_SETTER(PartCount, vtkIdType, 1, 10000000)
SCENEVIS_CLAMPED_SETTER(Floors, int, 1, 1000)
SCENEVIS_CLAMPED_SETTER(RoomsX, int, 1, 1000)
SCENEVIS_CLAMPED_SETTER(RoomsY, int, 1, 1000)
#undef SCENEVIS_CLAMPED_SETTER

//------------------------------------------------------------------------------
vtkIdType vtkDemoSceneSource::EstimatedTriangleCount() const
{
  switch (this->Scene)
  {
    case SCENE_SPHERE_GRID:
      return this->TriangleCount;
    case SCENE_CAD_ASSEMBLY:
      // Every part has at least a few dozen triangles, whatever TriangleCount says.
      return std::max(this->TriangleCount, this->PartCount * kMinTrianglesPerPart);
    case SCENE_BUILDING:
      return static_cast<vtkIdType>(this->Floors) * this->RoomsX * this->RoomsY *
        kTrianglesPerRoom;
    default:
      return 0;
  }
}

//------------------------------------------------------------------------------
int vtkDemoSceneSource::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  outputVector->GetInformationObject(0)->Set(CAN_HANDLE_PIECE_REQUEST(), 1);
  return 1;
}

//------------------------------------------------------------------------------
int vtkDemoSceneSource::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const int piece = outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER())
    ? outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER())
    : 0;
  const int pieces = outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES())
    ? outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES())
    : 1;
  namespace scenes = scenevis::scenes;
  const vtkIdType estimate = this->EstimatedTriangleCount();
  if (estimate > this->MaximumTriangleCount)
  {
    vtkErrorMacro("Cannot generate the " << GetSceneName(this->Scene) << " scene: about "
                                         << estimate << " triangles, more than "
                                         << "MaximumTriangleCount (" << this->MaximumTriangleCount
                                         << "; about 100 bytes each at the peak).");
    output->Initialize();
    return 1;
  }
  try
  {
    switch (this->Scene)
    {
      case SCENE_SPHERE_GRID:
        ToPolyData(scenes::sphereGrid(4, 0.8, 1.0,
                     scenes::trianglesPerSphereFor(static_cast<std::size_t>(this->TriangleCount))),
          output);
        break;
      case SCENE_CYCLIC_QUADS:
        ToPolyData(scenes::cyclicQuads(), output);
        break;
      case SCENE_INTERPENETRATING_TRIANGLES:
        ToPolyData(scenes::interpenetratingTriangles(), output);
        break;
      case SCENE_CAD_ASSEMBLY:
      {
        const auto parts = static_cast<std::size_t>(this->PartCount);
        const std::size_t perPart =
          std::max<std::size_t>(1, static_cast<std::size_t>(this->TriangleCount) / parts);
        ToPolyData(scenes::cadAssembly(parts, perPart, this->Seed,
                     { this->Origin[0], this->Origin[1], this->Origin[2] }),
          output);
        break;
      }
      case SCENE_BUILDING:
      {
        const scenes::BuildingScene building =
          scenes::building(this->Floors, this->RoomsX, this->RoomsY, this->Seed);
        ToPolyData(building, output);
        vtkNew<vtkIntArray> rooms;
        rooms->SetName("RoomId");
        rooms->SetNumberOfTuples(static_cast<vtkIdType>(building.room.size()));
        std::copy(building.room.begin(), building.room.end(), rooms->GetPointer(0));
        output->GetCellData()->AddArray(rooms);
        break;
      }
      default:
        break;
    }
    if (pieces > 1)
    {
      KeepPiece(output, piece, pieces);
    }
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("Cannot generate the " << GetSceneName(this->Scene) << " scene: " << e.what());
    output->Initialize();
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkDemoSceneSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Scene: " << GetSceneName(this->Scene) << "\n";
  os << indent << "TriangleCount: " << this->TriangleCount << "\n";
  os << indent << "PartCount: " << this->PartCount << "\n";
  os << indent << "Floors: " << this->Floors << ", RoomsX: " << this->RoomsX
     << ", RoomsY: " << this->RoomsY << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "Origin: " << this->Origin[0] << " " << this->Origin[1] << " " << this->Origin[2]
     << "\n";
}
