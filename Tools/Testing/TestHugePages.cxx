// When the tool runs itself again in huge pages (Tools/HugePages.h): big scenes only, unless the
// environment says always or never.
#include "../HugePages.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <unistd.h>

using scenevis::tool::WantsHugePages;

namespace
{
/// A command line as main() gets it.
bool Wants(std::vector<std::string> words)
{
  words.insert(words.begin(), "scenevis");
  std::vector<char*> argv;
  for (std::string& word : words)
    argv.push_back(word.data());
  argv.push_back(nullptr);
  return WantsHugePages(static_cast<int>(words.size()), argv.data());
}

/// A sparse file of @p bytes (no disk space used), removed with the object.
struct SparseFile
{
  std::string path;
  explicit SparseFile(off_t bytes)
  {
    const char* tmp = std::getenv("TMPDIR");
    std::string name = std::string(tmp && *tmp ? tmp : "/tmp") + "/scenevis-huge-pages-XXXXXX";
    const int fd = mkstemp(&name[0]);
    EXPECT_GE(fd, 0);
    EXPECT_EQ(ftruncate(fd, bytes), 0);
    close(fd);
    path = name;
  }
  ~SparseFile() { std::remove(path.c_str()); }
};

/// Sets SCENEVIS_HUGE_PAGES for its lifetime (unset with nullptr).
struct Choice
{
  explicit Choice(const char* value)
  {
    if (value)
      setenv("SCENEVIS_HUGE_PAGES", value, 1);
    else
      unsetenv("SCENEVIS_HUGE_PAGES");
  }
  ~Choice() { unsetenv("SCENEVIS_HUGE_PAGES"); }
};
} // namespace

TEST(HugePages, OnlyBigScenesAreWorthASecondStart)
{
  Choice automatic(nullptr);
  const SparseFile big(static_cast<off_t>(scenevis::tool::kBigSceneBytes));
  const SparseFile small(static_cast<off_t>(scenevis::tool::kBigSceneBytes - 1));
  EXPECT_TRUE(Wants({ "render", "--scene", big.path, "--cull", "occlusion" }));
  EXPECT_FALSE(Wants({ "render", "--scene", small.path }));
  EXPECT_FALSE(Wants({ "render", "--scene", "/nonexistent/model.vtp" }));
  EXPECT_FALSE(Wants({ "render", "--scene", "spheres" }));
  EXPECT_TRUE(Wants({ "render", "--scene", "spheres", "--triangles", "4000000" }));
  EXPECT_FALSE(Wants({ "render", "--scene", "spheres", "--triangles", "3999999" }));
  EXPECT_FALSE(Wants({ "render", "--scene" })) << "a missing value is the parser's to report";
  EXPECT_FALSE(Wants({ "render", "--triangles", "many" }));
}

TEST(HugePages, TheEnvironmentSaysAlwaysOrNever)
{
  const SparseFile big(static_cast<off_t>(scenevis::tool::kBigSceneBytes));
  {
    Choice never("0");
    EXPECT_FALSE(Wants({ "render", "--scene", big.path }));
  }
  {
    Choice always("1");
    EXPECT_TRUE(Wants({ "render", "--scene", "triangles" }));
  }
}
