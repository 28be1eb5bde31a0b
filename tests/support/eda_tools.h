// The EDA tools a test runs (Yosys, OpenSTA, the osu018 library): scripts/setup installs them, so
// a missing one fails the test; only a build configured with -DSHADESIM_ALLOW_MISSING_TOOLS=ON
// turns it into a skip, which ctest reports as skipped (gtest_discover_tests' SKIP_REGULAR_
// EXPRESSION on GoogleTest's "[  SKIPPED ]"), never a pass (tests/support/test_data.h's rule).
#pragma once

#include <gtest/gtest.h>

// Use as the first statement of a test body: `present` says whether the tools are there, `what`
// names them and their Debian packages, as a stream fragment ("sta or " << path), so it takes no
// parentheses.
// NOLINTBEGIN(bugprone-macro-parentheses): see above
#if SHADESIM_TEST_DATA_OPTIONAL
#define SHADESIM_NEEDS_TOOLS(present, what) \
  if (!(present)) GTEST_SKIP() << what << " absent (allowed by SHADESIM_ALLOW_MISSING_TOOLS)"
#else
#define SHADESIM_NEEDS_TOOLS(present, what) \
  if (!(present)) FAIL() << what << " absent: scripts/setup installs it"
#endif
// NOLINTEND(bugprone-macro-parentheses)
