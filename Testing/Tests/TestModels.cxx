// Tests of the model loader: the VRML `material USE` fix (pure text, always runs) and the parts and
// colours of imported scenes on real third-party models (skipped when scripts/fetch-data.sh has not
// fetched them).
#include "scenevis/testing/Models.h"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>

using scenevis::testing::DataFile;
using scenevis::testing::InlineVrmlMaterialUses;
using scenevis::testing::LoadModel;

namespace
{
const char* const kTwoShapes = R"(#VRML V2.0 utf8
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

std::string WriteText(const std::string& name, const std::string& text)
{
  const auto path = std::filesystem::temp_directory_path() / name;
  std::ofstream(path) << text;
  return path.string();
}

/// Distinct RGBA values of the "Colors" cell scalars.
std::set<std::array<int, 4>> DistinctColors(vtkPolyData* pd)
{
  std::set<std::array<int, 4>> colors;
  auto* array = vtkUnsignedCharArray::SafeDownCast(pd->GetCellData()->GetArray("Colors"));
  for (vtkIdType i = 0; array && i < array->GetNumberOfTuples(); ++i)
  {
    colors.insert({ array->GetValue(4 * i), array->GetValue(4 * i + 1),
      array->GetValue(4 * i + 2), array->GetValue(4 * i + 3) });
  }
  return colors;
}
} // namespace

TEST(Models, InlineVrmlMaterialUsesCopiesTheDefinedMaterial)
{
  const std::string fixed = InlineVrmlMaterialUses(kTwoShapes);
  EXPECT_EQ(fixed.find("material USE LED-GREEN"), std::string::npos);
  // The USE became the DEF'd node itself (without DEF, so the name is defined once).
  const std::string inlined = "material Material {\n        diffuseColor 0.400 0.700 0.150\n"
                              "        transparency 0.10\n        }";
  EXPECT_NE(fixed.find(inlined), std::string::npos) << fixed;
  // An unknown name stays as it was; text without USE is returned unchanged.
  EXPECT_NE(fixed.find("material USE UNKNOWN"), std::string::npos);
  EXPECT_EQ(InlineVrmlMaterialUses("Shape { }"), "Shape { }");
}

TEST(Models, VrmlPartsGetTheirUsedMaterial)
{
  const std::string path = WriteText("scenevis-test-models.wrl", kTwoShapes);
  std::string error;
  auto pd = LoadModel(path, &error);
  std::remove(path.c_str());
  ASSERT_TRUE(pd) << error;
  ASSERT_EQ(pd->GetNumberOfCells(), 2);
  auto* parts = pd->GetCellData()->GetArray("PartId");
  ASSERT_TRUE(parts);
  EXPECT_NE(parts->GetComponent(0, 0), parts->GetComponent(1, 0));
  auto* colors = vtkUnsignedCharArray::SafeDownCast(pd->GetCellData()->GetScalars());
  ASSERT_TRUE(colors);
  ASSERT_STREQ(colors->GetName(), "Colors");
  // First shape: the USEd LED-GREEN (0.4 0.7 0.15, transparency 0.1 -> opacity 0.9, 229).
  EXPECT_EQ(colors->GetValue(0), 102);
  EXPECT_EQ(colors->GetValue(1), 178); // 255 * 0.7f rounds down
  EXPECT_EQ(colors->GetValue(2), 38);
  EXPECT_EQ(colors->GetValue(3), 229); // 0.9 in the importer's float property
  // Second shape: unknown material -> VTK's default (opaque).
  EXPECT_EQ(colors->GetValue(7), 255);
}

TEST(Models, UnreadableFilesGiveOneLine)
{
  std::string error;
  EXPECT_FALSE(LoadModel("/nonexistent/model.wrl", &error));
  EXPECT_NE(error.find("cannot open"), std::string::npos) << error;
  const std::string path = WriteText("scenevis-test-models.xyz", "solid");
  EXPECT_FALSE(LoadModel(path, &error));
  std::remove(path.c_str());
  EXPECT_NE(error.find("unsupported model format"), std::string::npos) << error;
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;
}

TEST(Models, EngineAssemblyHasItsParts)
{
  const std::string path = DataFile("engine-glb");
  if (path.empty())
  {
    GTEST_SKIP() << "engine-glb not fetched (scripts/fetch-data.sh)";
  }
  std::string error;
  auto pd = LoadModel(path, &error);
  ASSERT_TRUE(pd) << error;
  // /work/shared/DATA.md: vtkGLTFImporter gives 115 parts, 121,496 triangles.
  double range[2];
  pd->GetCellData()->GetArray("PartId")->GetRange(range);
  EXPECT_EQ(range[0], 0);
  EXPECT_EQ(range[1], 114);
  EXPECT_EQ(pd->GetNumberOfPolys(), 121496);
  EXPECT_GE(DistinctColors(pd).size(), 3u);
}

TEST(Models, KiCadPartIsColouredAndTranslucentWhereItsMaterialIs)
{
  const std::string dir = DataFile("kicad-wrl-dir");
  if (dir.empty())
  {
    GTEST_SKIP() << "kicad-wrl-dir not fetched (scripts/fetch-data.sh --kicad)";
  }
  const std::string path =
    dir + "/LED_THT.3dshapes/LED_D1.8mm_W1.8mm_H2.4mm_Horizontal_O1.27mm_Z1.6mm.wrl";
  std::string error;
  auto pd = LoadModel(path, &error);
  ASSERT_TRUE(pd) << error;
  const auto colors = DistinctColors(pd);
  // Without the USE fix every shape is VTK's default white, opaque.
  EXPECT_EQ(colors.count({ 255, 255, 255, 255 }), 0u);
  EXPECT_EQ(colors.count({ 102, 178, 38, 229 }), 1u) << "the green LED body (transparency 0.1)";
  EXPECT_GE(colors.size(), 2u);
}

TEST(Models, WusonReadsAlikeInEveryFormat)
{
  for (const char* key : { "wuson-obj", "wuson-ply", "wuson-stl", "wuson-wrl" })
  {
    const std::string path = DataFile(key);
    if (path.empty())
    {
      GTEST_SKIP() << key << " not fetched (scripts/fetch-data.sh)";
    }
    std::string error;
    auto pd = LoadModel(path, &error);
    ASSERT_TRUE(pd) << key << ": " << error;
    EXPECT_GE(pd->GetNumberOfCells(), 3000) << key;
  }
}
