// The laser preset chosen from a scan's geometry (issue 39): the real
// recordings' SICK LMS 2xx scans, the 270 deg lasers the other presets are
// for, and scans no preset fits; every file it names exists and loads.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "structloc/localisation_core/localiser/localiser_options.hpp"
#include "structloc/localisation_core/scan/laser_preset.hpp"
#include "test_paths.hpp"

namespace structloc {
namespace {

using localisation_core::ChooseLaserPreset;

double Deg(double d) {
  return d * M_PI / 180.0;
}

TEST(LaserPreset, TheRealRecordingsScansAreASickLms2xx) {
  // Freiburg 079: 361 FLASER beams over 180 deg; Intel: 180 beams at 1 deg;
  // a log that gives no maximum range; a 100 deg scan at 0.25 deg.
  for (const localisation_core::ScanShape shape :
       {localisation_core::ScanShape{361, Deg(0.5), 80.0},
        localisation_core::ScanShape{180, Deg(1.0), 80.0},
        localisation_core::ScanShape{181, -Deg(1.0), 0.0},
        localisation_core::ScanShape{401, Deg(0.25), 8.0}}) {
    const auto choice = ChooseLaserPreset(shape);
    EXPECT_EQ(choice.file, "maps/params/sick_lms2xx.xml") << choice.reason;
    EXPECT_NE(choice.reason.find("SICK LMS 2xx"), std::string::npos) << choice.reason;
  }
}

TEST(LaserPreset, TwoHundredSeventyDegreeLasersBySpacing) {
  EXPECT_EQ(ChooseLaserPreset({1081, Deg(0.25), 30.0}).file, "maps/params/hokuyo_utm30lx.xml");
  EXPECT_EQ(ChooseLaserPreset({541, Deg(0.5), 30.0}).file, "maps/params/sick_s300_microscan3.xml");
}

TEST(LaserPreset, ScansNoPresetFitsKeepTheBuiltInDefaultsAndSaySo) {
  // The thesis' 300 readings over a turn; a short-range 180 deg laser (URG
  // cropped); 240 deg at 0.36 deg (Hokuyo URG-04LX); 180 deg at 0.7 deg.
  for (const localisation_core::ScanShape shape :
       {localisation_core::ScanShape{300, 2 * M_PI / 300, 4.0},
        localisation_core::ScanShape{361, Deg(0.5), 5.6},
        localisation_core::ScanShape{667, Deg(0.36), 5.6},
        localisation_core::ScanShape{258, Deg(0.7), 80.0}}) {
    const auto choice = ChooseLaserPreset(shape);
    EXPECT_TRUE(choice.file.empty()) << choice.file;
    EXPECT_NE(choice.reason.find("give --params"), std::string::npos) << choice.reason;
  }
}

TEST(LaserPreset, EveryFileItNamesIsShippedAndLoads) {
  for (const localisation_core::ScanShape shape :
       {localisation_core::ScanShape{361, Deg(0.5), 80.0},
        localisation_core::ScanShape{1081, Deg(0.25), 30.0},
        localisation_core::ScanShape{541, Deg(0.5), 30.0}}) {
    const std::string path = testing::SourcePath(ChooseLaserPreset(shape).file);
    ASSERT_TRUE(std::filesystem::exists(path)) << path;
    EXPECT_NO_THROW(localisation_core::LoadLocaliserOptions(path)) << path;
  }
}

}  // namespace
}  // namespace structloc
