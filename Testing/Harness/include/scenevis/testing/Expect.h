/**
 * @file Expect.h
 * @brief SCENEVIS_EXPECT(cond) for VTK-style tests (`int TestX(int, char*[])`), header-only.
 *
 * A failed condition is printed with its file and line (and, when a test has set one, the case
 * it is checking: ExpectContext()) and counted in ExpectFailures(); the test returns EXIT_FAILURE
 * when the count is not zero.
 */
#ifndef scenevis_testing_Expect_h
#define scenevis_testing_Expect_h

#include <iostream>
#include <string>

namespace scenevis
{
namespace testing
{
/// The failures counted so far by SCENEVIS_EXPECT (and by tests that add their own).
inline int& ExpectFailures()
{
  static int failures = 0;
  return failures;
}

/// The case a test is checking now (e.g. "vtkBSPSortFilter: no camera"), printed in brackets
/// before every failed SCENEVIS_EXPECT while it is not empty.
inline std::string& ExpectContext()
{
  static std::string context;
  return context;
}

/// What SCENEVIS_EXPECT does when @p condition (its text) is false at @p file: @p line.
inline void ExpectFailed(const char* file, int line, const char* condition)
{
  std::cerr << file << ":" << line << ": ";
  if (!ExpectContext().empty())
  {
    std::cerr << "[" << ExpectContext() << "] ";
  }
  std::cerr << "expected " << condition << std::endl;
  ++ExpectFailures();
}
} // namespace testing
} // namespace scenevis

#define SCENEVIS_EXPECT(cond)                                                                      \
  do                                                                                               \
  {                                                                                                \
    if (!(cond))                                                                                   \
    {                                                                                              \
      scenevis::testing::ExpectFailed(__FILE__, __LINE__, #cond);                                  \
    }                                                                                              \
  } while (false)

#endif
