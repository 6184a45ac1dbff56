// The calibration component's last result on disk (last_result_file.hpp):
// what is saved comes back identical, and a file that is truncated, too
// large, not CDR, or holds a NaN is refused with a reason instead of being
// published again after a restart.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "structloc/calibration/last_result_file.hpp"
#include "temp_dir.hpp"

namespace structloc {
namespace {

structloc_msgs::msg::CalibrationResult SomeResult() {
  structloc_msgs::msg::CalibrationResult r;
  r.success(true);
  r.parameters().wheel_radius_m(0.1012);
  r.parameters().axle_distance_m(0.62);
  r.standard_deviations().wheel_radius_m(1e-5);
  r.estimated({"wheel_radius", "axle_distance"});
  r.covariance({1e-10, 0.0, 0.0, 4e-8});
  r.warnings({"a warning"});
  r.window_end().sec(1234);
  return r;
}

std::string Bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(LastResultFile, WhatIsSavedComesBackIdentical) {
  const testing::TempDir dir;
  const std::string path = dir / calibration::kLastResultFileName;
  ASSERT_EQ(calibration::SaveLastResult(path, SomeResult()), "");
  std::string why;
  const auto back = calibration::LoadLastResult(path, why);
  ASSERT_TRUE(back.has_value()) << why;
  EXPECT_TRUE(*back == SomeResult());
  EXPECT_FALSE(std::filesystem::exists(path + ".partial"));
}

TEST(LastResultFile, DamagedFilesAreRefusedWithAReason) {
  const testing::TempDir dir;
  const std::string good = dir / "good.cdr";
  ASSERT_EQ(calibration::SaveLastResult(good, SomeResult()), "");
  const std::string bytes = Bytes(good);
  std::string why;
  EXPECT_FALSE(calibration::LoadLastResult(dir / "missing.cdr", why));
  EXPECT_NE(why.find("missing.cdr"), std::string::npos);

  const std::string truncated = dir.Write("truncated.cdr", bytes.substr(0, bytes.size() / 2));
  EXPECT_FALSE(calibration::LoadLastResult(truncated, why));
  EXPECT_NE(why.find("not a saved calibration result"), std::string::npos) << why;

  const std::string empty_file = dir.Write("empty.cdr", "");
  EXPECT_FALSE(calibration::LoadLastResult(empty_file, why));
  EXPECT_NE(why.find("0 bytes"), std::string::npos) << why;

  const std::string large =
      dir.Write("large.cdr", std::string(calibration::kMaxLastResultBytes + 1, '\0'));
  EXPECT_FALSE(calibration::LoadLastResult(large, why));
  EXPECT_NE(why.find(std::to_string(calibration::kMaxLastResultBytes)), std::string::npos) << why;

  auto nan = SomeResult();
  nan.parameters().wheel_radius_m(std::nan(""));
  const std::string nan_path = dir / "nan.cdr";
  ASSERT_EQ(calibration::SaveLastResult(nan_path, nan), "");
  EXPECT_FALSE(calibration::LoadLastResult(nan_path, why));
  EXPECT_NE(why.find("not a finite number"), std::string::npos) << why;

  const std::string text = dir.Write("text.cdr", "<robot wheel_radius_m=\"0.1\"/>");
  EXPECT_FALSE(calibration::LoadLastResult(text, why));
}

}  // namespace
}  // namespace structloc
