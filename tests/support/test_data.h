// Test data from Debian packages (assimp-testmodels' real and malformed meshes). scripts/setup
// installs it and the configure fails without it (cmake/required_tools.cmake), so a missing file
// fails the test; only a configure with -DSHADESIM_ALLOW_MISSING_TOOLS=ON turns it into a skip.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>

// Use as the first statement of a test body.
#if SHADESIM_TEST_DATA_OPTIONAL
#define SHADESIM_NEEDS_TEST_FILE(path)                                                     \
  if (!std::filesystem::exists(path))                                                      \
  GTEST_SKIP() << (path) << " is absent (Debian package assimp-testmodels not installed; " \
               << "allowed by SHADESIM_ALLOW_MISSING_TOOLS)"
#else
#define SHADESIM_NEEDS_TEST_FILE(path) \
  if (!std::filesystem::exists(path))  \
  FAIL() << (path) << " is absent: install Debian's assimp-testmodels (scripts/setup does)"
#endif
