/**
 * @file GTestSupport.h
 * @brief GoogleTest glue for the SceneVis testing harness (header-only; include from tests only).
 */
#ifndef scenevis_testing_GTestSupport_h
#define scenevis_testing_GTestSupport_h

#include "scenevis/testing/StrictVtkOutput.h"

#include <gtest/gtest.h>

#include <string>

namespace scenevis
{
namespace testing
{

/**
 * Fixture base: every VTK error or warning during the test fails it, unless declared on
 * `VtkOutput` (VtkOutput.ExpectError("...") etc.) before it happens.
 */
class StrictVtkTest : public ::testing::Test
{
protected:
  void TearDown() override
  {
    const std::string report = this->VtkOutput.Check();
    EXPECT_TRUE(report.empty()) << report;
  }

  StrictVtkOutput VtkOutput;
};

} // namespace testing
} // namespace scenevis

/// Fail the current GoogleTest test if @p guard (a StrictVtkOutput) saw undeclared VTK output.
#define SCENEVIS_EXPECT_VTK_CLEAN(guard)                                                           \
  do                                                                                               \
  {                                                                                                \
    const std::string scenevisVtkReport = (guard).Check();                                         \
    EXPECT_TRUE(scenevisVtkReport.empty()) << scenevisVtkReport;                                   \
  } while (false)

#endif
