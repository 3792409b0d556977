// vtkSceneVisModelReader on what it is for: the parts and colours of glTF and VRML scenes (the
// VRML `material USE` fix, as text and as colours), NaN/Inf clean-up, and real third-party models
// of the data cache (scripts/fetch-data.sh; those checks are skipped, exit 77, when the cache has
// none of them).
#include "vtkSceneVisModelReader.h"

#include "scenevis/testing/Expect.h"
#include "scenevis/testing/ImageCompare.h" // WriteTemporaryFile
#include "scenevis/testing/Models.h"

#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <string>

namespace
{
// Two triangles that USE a material DEF'd on an earlier shape, and one with an unknown name.
const char* const kUsedMaterial = R"(#VRML V2.0 utf8
Shape {
    appearance Appearance {material DEF LED-GREEN Material {
        diffuseColor 0.400 0.700 0.150
        transparency 0.10
        }
    }
}
Shape { geometry IndexedFaceSet
{ coordIndex [0,1,2,-1]
coord Coordinate { point [0 0 0,1 0 0,0 1 0]
}}
appearance Appearance{material USE LED-GREEN }}
Shape { geometry IndexedFaceSet
{ coordIndex [0,1,2,-1]
coord Coordinate { point [0 0 1,1 0 1,0 1 1]
}}
appearance Appearance{material USE UNKNOWN }}
)";

// Three triangles, the middle one using a NaN point (ASCII PLY: its reader parses "nan").
const char* const kNanTriangle = R"(ply
format ascii 1.0
element vertex 7
property float x
property float y
property float z
element face 3
property list uchar int vertex_indices
end_header
0 0 0
1 0 0
0 1 0
nan 0 0
2 0 0
3 0 0
2 1 0
3 0 1 2
3 1 3 2
3 4 5 6
)";

std::string WriteText(const std::string& name, const std::string& text)
{
  return scenevis::testing::WriteTemporaryFile(name, text);
}

/// Distinct RGBA values of the "Colors" cell scalars.
std::set<std::array<int, 4>> DistinctColors(vtkPolyData* pd)
{
  std::set<std::array<int, 4>> colors;
  auto* array = vtkUnsignedCharArray::SafeDownCast(pd->GetCellData()->GetArray("Colors"));
  for (vtkIdType i = 0; array && i < array->GetNumberOfTuples(); ++i)
  {
    colors.insert({ array->GetValue(4 * i), array->GetValue(4 * i + 1), array->GetValue(4 * i + 2),
      array->GetValue(4 * i + 3) });
  }
  return colors;
}

void TestInlineVrmlMaterialUses()
{
  const std::string fixed = vtkSceneVisModelReader::InlineVrmlMaterialUses(kUsedMaterial);
  SCENEVIS_EXPECT(fixed.find("material USE LED-GREEN") == std::string::npos);
  // The USE became the DEF'd node itself (without DEF, so the name is defined once).
  SCENEVIS_EXPECT(fixed.find("material Material {\n        diffuseColor 0.400 0.700 0.150\n"
                             "        transparency 0.10\n        }") != std::string::npos);
  // An unknown name stays as it was; text without USE is returned unchanged.
  SCENEVIS_EXPECT(fixed.find("material USE UNKNOWN") != std::string::npos);
  SCENEVIS_EXPECT(vtkSceneVisModelReader::InlineVrmlMaterialUses("Shape { }") == "Shape { }");
}

void TestVrmlPartsGetTheirUsedMaterial()
{
  const std::string path = WriteText("scenevis-test-model-reader.wrl", kUsedMaterial);
  vtkNew<vtkSceneVisModelReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  std::remove(path.c_str());
  vtkPolyData* pd = reader->GetOutput();
  SCENEVIS_EXPECT(std::string(reader->GetErrorMessage()).empty());
  SCENEVIS_EXPECT(pd->GetNumberOfCells() == 2);
  vtkDataArray* parts = pd->GetCellData()->GetArray("PartId");
  auto* colors = vtkUnsignedCharArray::SafeDownCast(pd->GetCellData()->GetScalars());
  SCENEVIS_EXPECT(parts && colors);
  if (!parts || !colors || pd->GetNumberOfCells() != 2)
  {
    return;
  }
  SCENEVIS_EXPECT(parts->GetComponent(0, 0) != parts->GetComponent(1, 0));
  SCENEVIS_EXPECT(std::string(colors->GetName()) == "Colors");
  // First shape: the USEd LED-GREEN (0.4 0.7 0.15, transparency 0.1 -> opacity 0.9).
  SCENEVIS_EXPECT(colors->GetValue(0) == 102 && colors->GetValue(1) == 178 &&
    colors->GetValue(2) == 38 && colors->GetValue(3) == 229);
  // Second shape: unknown material -> VTK's default, opaque.
  SCENEVIS_EXPECT(colors->GetValue(7) == 255);
}

void TestNonFiniteCellsAreRemoved()
{
  const std::string path = WriteText("scenevis-test-model-reader-nan.ply", kNanTriangle);
  vtkNew<vtkSceneVisModelReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  SCENEVIS_EXPECT(reader->GetNumberOfRemovedCells() == 1);
  SCENEVIS_EXPECT(reader->GetOutput()->GetNumberOfCells() == 2);
  double bounds[6];
  reader->GetOutput()->GetBounds(bounds);
  SCENEVIS_EXPECT(bounds[0] == 0 && bounds[1] == 3); // the NaN point is parked on a finite one
  // Off: the file as it is.
  reader->RemoveNonFiniteCellsOff();
  reader->Update();
  SCENEVIS_EXPECT(reader->GetNumberOfRemovedCells() == 0);
  SCENEVIS_EXPECT(reader->GetOutput()->GetNumberOfCells() == 3);
  std::remove(path.c_str());
}

/// Real models: returns how many of them the data cache had.
int TestRealModels()
{
  int found = 0;
  const std::string engine = scenevis::testing::DataFile("engine-glb");
  if (!engine.empty())
  {
    ++found;
    vtkNew<vtkSceneVisModelReader> reader;
    reader->SetFileName(engine.c_str());
    reader->Update();
    vtkPolyData* pd = reader->GetOutput();
    // /work/shared/DATA.md: vtkGLTFImporter gives 115 parts, 121,496 triangles.
    SCENEVIS_EXPECT(pd->GetNumberOfPolys() == 121496);
    double range[2] = { -1, -1 };
    if (vtkDataArray* parts = pd->GetCellData()->GetArray("PartId"))
    {
      parts->GetRange(range);
    }
    SCENEVIS_EXPECT(range[0] == 0 && range[1] == 114);
    SCENEVIS_EXPECT(DistinctColors(pd).size() >= 3);
  }
  for (const char* key : { "wuson-obj", "wuson-ply", "wuson-stl", "wuson-wrl", "bunny-stl" })
  {
    const std::string path = scenevis::testing::DataFile(key);
    if (path.empty())
    {
      continue;
    }
    ++found;
    vtkNew<vtkSceneVisModelReader> reader;
    reader->SetFileName(path.c_str());
    reader->Update();
    if (reader->GetOutput()->GetNumberOfCells() < 3000)
    {
      std::cerr << key << ": " << reader->GetOutput()->GetNumberOfCells() << " cells; "
                << reader->GetErrorMessage() << std::endl;
      ++scenevis::testing::ExpectFailures();
    }
  }
  const std::string kicad = scenevis::testing::DataFile("kicad-wrl-dir");
  if (!kicad.empty())
  {
    ++found;
    const std::string path =
      kicad + "/LED_THT.3dshapes/LED_D1.8mm_W1.8mm_H2.4mm_Horizontal_O1.27mm_Z1.6mm.wrl";
    vtkNew<vtkSceneVisModelReader> reader;
    reader->SetFileName(path.c_str());
    reader->Update();
    const auto colors = DistinctColors(reader->GetOutput());
    // Without the USE fix every shape is VTK's default white, opaque.
    SCENEVIS_EXPECT(colors.count({ 255, 255, 255, 255 }) == 0);
    SCENEVIS_EXPECT(colors.count({ 102, 178, 38, 229 }) == 1);
  }
  return found;
}
} // namespace

int TestSceneVisModelReader(int, char*[])
{
  TestInlineVrmlMaterialUses();
  TestVrmlPartsGetTheirUsedMaterial();
  TestNonFiniteCellsAreRemoved();
  const int real = TestRealModels();
  if (const int failures = scenevis::testing::ExpectFailures())
  {
    std::cerr << failures << " failure(s)" << std::endl;
    return EXIT_FAILURE;
  }
  if (real == 0)
  {
    std::cout << "real models skipped: none in " << scenevis::testing::DataDirectory()
              << " (scripts/fetch-data.sh)" << std::endl;
    return 77;
  }
  return EXIT_SUCCESS;
}
