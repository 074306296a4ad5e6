#include <gtest/gtest.h>
#include "core/simulate.hpp"
TEST(Placeholder, Builds) { SUCCEED(); }
