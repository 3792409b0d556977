// Specification of the --cameras FILE.json reader (Tools/CameraFile.h) on its own, without VTK:
// what a valid file gives, how command-line defaults combine with each camera, and one clear
// line for every kind of bad file.
#include "../CameraFile.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>

using scenevis::tool::CameraSpec;
using scenevis::tool::ReadCameraFile;

namespace
{
/// Writes @p text to a scratch file and returns its path.
std::string Write(const std::string& name, const std::string& text)
{
  const std::string path = ::testing::TempDir() + "scenevis-cameras-" + name + ".json";
  std::ofstream(path) << text;
  return path;
}

/// The one-line error reading @p text gives ("" if it reads).
std::string ErrorOf(const std::string& name, const std::string& text)
{
  try
  {
    ReadCameraFile(Write(name, text), CameraSpec());
  }
  catch (const std::runtime_error& e)
  {
    const std::string what = e.what();
    EXPECT_EQ(what.find('\n'), std::string::npos) << "not one line: " << what;
    return what;
  }
  return "";
}
} // namespace

TEST(CameraFile, ReadsEveryMember)
{
  const std::vector<CameraSpec> cameras = ReadCameraFile(
    Write("valid", R"([ {"eye": [0, 0, 5], "focal": [0, 0, 0]},
      {"eye": [5, 0, 0], "focal": [0, 0, 0], "up": [0, 0, 1], "view_angle": 60,
       "clipping_range": [0.5, 50]},
      {"eye": [0, 5, 0], "focal": [0, 0, 0], "parallel_scale": 2} ])"),
    CameraSpec());
  ASSERT_EQ(cameras.size(), 3u);
  EXPECT_TRUE(cameras[0].hasEye && cameras[0].hasFocal);
  EXPECT_EQ(cameras[0].eye[2], 5.0);
  EXPECT_FALSE(cameras[0].FixedClippingRange());
  EXPECT_TRUE(cameras[1].hasUp);
  EXPECT_EQ(cameras[1].up[2], 1.0);
  EXPECT_EQ(cameras[1].viewAngle, 60.0);
  EXPECT_FALSE(cameras[1].parallel);
  EXPECT_TRUE(cameras[1].FixedClippingRange());
  EXPECT_EQ(cameras[1].clippingRange[1], 50.0);
  EXPECT_TRUE(cameras[2].parallel);
  EXPECT_EQ(cameras[2].parallelScale, 2.0);
}

TEST(CameraFile, CommandLineValuesAreEachCamerasDefaults)
{
  CameraSpec defaults;
  defaults.hasUp = true;
  defaults.up[0] = 1.0;
  defaults.up[1] = 0.0;
  defaults.clippingRange[0] = 1.0;
  defaults.clippingRange[1] = 100.0;
  const std::vector<CameraSpec> cameras =
    ReadCameraFile(Write("defaults", R"([{"eye": [0, 0, 5], "focal": [0, 0, 0]}])"), defaults);
  ASSERT_EQ(cameras.size(), 1u);
  EXPECT_EQ(cameras[0].up[0], 1.0);
  EXPECT_TRUE(cameras[0].FixedClippingRange());
}

TEST(CameraFile, BadFilesGiveOneClearLine)
{
  EXPECT_NE(ErrorOf("empty", ""), "");
  EXPECT_NE(ErrorOf("none", "[]"), "");
  EXPECT_NE(ErrorOf("object", R"({"eye": [0, 0, 5], "focal": [0, 0, 0]})"), "");
  EXPECT_NE(ErrorOf("trailing", R"([{"eye": [0, 0, 5], "focal": [0, 0, 0]},])"), "");
  EXPECT_NE(ErrorOf("truncated", R"([{"eye": [0, 0, 5], "focal": [0, 0)"), "");
  EXPECT_NE(ErrorOf("nan", R"([{"eye": [NaN, 0, 5], "focal": [0, 0, 0]}])"), "");
  EXPECT_NE(ErrorOf("no-eye", R"([{"focal": [0, 0, 0]}])"), "");
  EXPECT_NE(ErrorOf("short", R"([{"eye": [0, 5], "focal": [0, 0, 0]}])"), "");
  EXPECT_NE(ErrorOf("text", R"([{"eye": ["0", 0, 5], "focal": [0, 0, 0]}])"), "");
  EXPECT_NE(ErrorOf("same", R"([{"eye": [1, 2, 3], "focal": [1, 2, 3]}])"), "");
  EXPECT_NE(ErrorOf("unknown", R"([{"eye": [0, 0, 5], "focal": [0, 0, 0], "fov": 60}])"), "");
  EXPECT_NE(ErrorOf("both", R"([{"eye": [0, 0, 5], "focal": [0, 0, 0], "view_angle": 30,
    "parallel_scale": 2}])"),
    "");
  EXPECT_NE(ErrorOf("angle", R"([{"eye": [0, 0, 5], "focal": [0, 0, 0], "view_angle": 180}])"),
    "");
  EXPECT_NE(ErrorOf("range",
              R"([{"eye": [0, 0, 5], "focal": [0, 0, 0], "clipping_range": [5, 1]}])"),
    "");
  EXPECT_NE(ErrorOf("duplicate", R"([{"eye": [0, 0, 5], "eye": [0, 0, 6], "focal": [0, 0, 0]}])"),
    "");
  // Where: the line and column of a syntax error.
  const std::string error = ErrorOf("where", "[\n  {\"eye\": [0, 0, 5],, \"focal\": [0, 0, 0]}]");
  EXPECT_NE(error.find("2"), std::string::npos) << error;
  // A file that does not exist.
  try
  {
    ReadCameraFile("/nonexistent/cameras.json", CameraSpec());
    ADD_FAILURE() << "no error for a missing file";
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/cameras.json"), std::string::npos);
  }
}
