// Tests of StrictVtkOutput: VTK errors/warnings are recorded and judged.
#include "scenevis/testing/GTestSupport.h"
#include "scenevis/testing/StrictVtkOutput.h"

#include <vtkNew.h>
#include <vtkObject.h>
#include <vtkOutputWindow.h>

#include <gtest/gtest.h>

using scenevis::testing::StrictVtkOutput;

namespace
{
void EmitError(const char* text)
{
  vtkNew<vtkObject> object;
  vtkErrorWithObjectMacro(object, << text);
}

void EmitWarning(const char* text)
{
  vtkNew<vtkObject> object;
  vtkWarningWithObjectMacro(object, << text);
}
} // namespace

TEST(StrictVtkOutput, CleanRunPasses)
{
  StrictVtkOutput strict;
  vtkOutputWindow::GetInstance()->DisplayText("plain text is not judged\n");
  EXPECT_EQ(strict.Check(), "");
}

TEST(StrictVtkOutput, UnexpectedErrorIsReported)
{
  StrictVtkOutput strict;
  EmitError("something broke");
  const std::string report = strict.Check();
  EXPECT_NE(report.find("Unexpected VTK error"), std::string::npos) << report;
  EXPECT_NE(report.find("something broke"), std::string::npos) << report;
}

TEST(StrictVtkOutput, UnexpectedWarningIsReported)
{
  StrictVtkOutput strict;
  EmitWarning("careful");
  vtkGenericWarningMacro(<< "generic careful");
  const std::string report = strict.Check();
  EXPECT_NE(report.find("Unexpected VTK warning"), std::string::npos) << report;
  EXPECT_NE(report.find("Unexpected VTK generic warning"), std::string::npos) << report;
}

TEST(StrictVtkOutput, ExpectedErrorIsAcceptedAndRequired)
{
  StrictVtkOutput strict;
  strict.ExpectError("No input data");
  EmitError("No input data on port 0");
  EXPECT_EQ(strict.Check(), "");

  StrictVtkOutput missing;
  missing.ExpectError("never happens");
  const std::string report = missing.Check();
  EXPECT_NE(report.find("did not occur"), std::string::npos) << report;
}

TEST(StrictVtkOutput, AllowedWarningMayOrMayNotOccur)
{
  {
    StrictVtkOutput strict;
    strict.AllowWarning("maybe");
    EXPECT_EQ(strict.Check(), "");
  }
  StrictVtkOutput strict;
  strict.AllowWarning("maybe");
  EmitWarning("maybe this");
  EXPECT_EQ(strict.Check(), "");
  // An allowed warning does not allow an error with the same text.
  EmitError("maybe this");
  EXPECT_NE(strict.Check(), "");
}

TEST(StrictVtkOutput, NestedGuardsSeeUndeclaredMessagesOnly)
{
  StrictVtkOutput outer;
  {
    StrictVtkOutput inner;
    inner.ExpectError("inner expected");
    EmitError("inner expected");
    EmitError("nobody expected this");
    const std::string report = inner.Check();
    EXPECT_NE(report.find("nobody expected this"), std::string::npos) << report;
  }
  // The declared error stayed inside; the undeclared one reached the outer guard too.
  const std::string report = outer.Check();
  EXPECT_EQ(report.find("inner expected"), std::string::npos) << report;
  EXPECT_NE(report.find("nobody expected this"), std::string::npos) << report;
}

TEST(StrictVtkOutput, ExitCodeForVtkStyleTests)
{
  StrictVtkOutput clean;
  EXPECT_EQ(clean.ExitCode(EXIT_SUCCESS), EXIT_SUCCESS);
  StrictVtkOutput dirty;
  EmitError("fails the test");
  EXPECT_EQ(dirty.ExitCode(EXIT_SUCCESS), EXIT_FAILURE);
}

TEST(StrictVtkOutput, UncheckedGuardTerminatesTheProcess)
{
  EXPECT_EXIT(
    {
      StrictVtkOutput strict;
      EmitError("forgotten");
    },
    ::testing::ExitedWithCode(EXIT_FAILURE),
    "unexpected VTK output");
}

TEST(StrictVtkOutput, RestoresThePreviousOutputWindow)
{
  vtkOutputWindow* before = vtkOutputWindow::GetInstance();
  {
    StrictVtkOutput strict;
    EXPECT_NE(vtkOutputWindow::GetInstance(), before);
    EXPECT_EQ(strict.Check(), "");
  }
  EXPECT_EQ(vtkOutputWindow::GetInstance(), before);
}

class StrictFixture : public scenevis::testing::StrictVtkTest
{
};

TEST_F(StrictFixture, DeclaredErrorPassesTheFixture)
{
  VtkOutput.ExpectError("fixture error");
  EmitError("fixture error");
}
