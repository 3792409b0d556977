/**
 * @file Expect.h
 * @brief SCENEVIS_EXPECT(cond) for VTK-style tests (`int TestX(int, char*[])`), header-only.
 *
 * A failed condition is printed with its file and line and counted in ExpectFailures(); the test
 * returns EXIT_FAILURE when the count is not zero. (Older VTK-level tests define the same macro
 * locally as EXPECT.)
 */
#ifndef scenevis_testing_Expect_h
#define scenevis_testing_Expect_h

#include <iostream>

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
} // namespace testing
} // namespace scenevis

#define SCENEVIS_EXPECT(cond)                                                                      \
  do                                                                                               \
  {                                                                                                \
    if (!(cond))                                                                                   \
    {                                                                                              \
      std::cerr << __FILE__ << ":" << __LINE__ << ": expected " #cond << std::endl;                \
      ++scenevis::testing::ExpectFailures();                                                       \
    }                                                                                              \
  } while (false)

#endif
