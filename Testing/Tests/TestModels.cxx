// Tests of the harness's model loading: LoadModel() forwards to vtkSceneVisModelReader (whose own
// tests, IO/Models/Testing/Cxx, cover formats, parts, colours and bad files) and adds what the
// tool and tests rely on: nullptr and one line instead of an empty output, no output-window text,
// NaN/Inf cells kept (the tool removes and counts them itself).
#include "scenevis/testing/GTestSupport.h"
#include "scenevis/testing/ImageCompare.h" // WriteTemporaryFile
#include "scenevis/testing/Models.h"

#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

using scenevis::testing::LoadModel;

namespace
{
std::string WriteText(const std::string& name, const std::string& text)
{
  return scenevis::testing::WriteTemporaryFile(name, text);
}
} // namespace

/// Every VTK error or warning fails the test: LoadModel() keeps the reader quiet.
class Models : public scenevis::testing::StrictVtkTest
{
};

TEST_F(Models, UnreadableFilesGiveOneLine)
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

TEST_F(Models, NonFiniteCellsAreKept)
{
  const std::string path = WriteText("scenevis-test-models-nan.ply",
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
    "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0\n1 0 0\n0 1 0\nnan 0 0\n3 0 1 2\n3 1 3 2\n");
  std::string error;
  auto pd = LoadModel(path, &error);
  std::remove(path.c_str());
  ASSERT_TRUE(pd) << error;
  EXPECT_EQ(pd->GetNumberOfCells(), 2);
}
