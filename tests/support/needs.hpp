// A test that needs something the machine may lack (gnuplot, MuJoCo built
// in, libEGL): skipped with the reason where it is missing, unless
// CONTACT2D_REQUIRE_DEPENDENCIES is set, where it fails. scripts/test sets
// it: scripts/setup installs all of them, so there a skip would hide a
// broken install (MuJoCo 3's own: mujoco3_test_util.hpp).
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>

#define CONTACT2D_NEEDS(present, what_is_missing)                                         \
  do {                                                                                    \
    if (!(present)) {                                                                     \
      if (std::getenv("CONTACT2D_REQUIRE_DEPENDENCIES") != nullptr)                       \
        FAIL() << (what_is_missing) << " (CONTACT2D_REQUIRE_DEPENDENCIES: scripts/setup " \
               << "installs it)";                                                         \
      GTEST_SKIP() << (what_is_missing);                                                  \
    }                                                                                     \
  } while (false)
