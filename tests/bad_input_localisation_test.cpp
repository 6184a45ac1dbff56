// Regression tests for the bad-input review of 12de806 (localisation defects): each
// test is named after the defect it keeps fixed (H = high, M = medium, L = low).
#include <gtest/gtest.h>

#include "cli_runner.hpp"
#include "temp_dir.hpp"
#include "test_paths.hpp"

namespace structloc {
namespace {

TEST(BadInputLocalisation, ScaffoldBuilds) { SUCCEED(); }

}  // namespace
}  // namespace structloc
