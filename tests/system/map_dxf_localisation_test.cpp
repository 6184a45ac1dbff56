// Issue 11's acceptance for CAD drawings: the office floor drawn in
// millimetres (tests/data/maps/office_floor_mm.dxf), imported with
// `structloc map import --dxf ... --layers WALLS,PILLARS` (furniture and the
// free-standing cabinet-edge corner left out), serves the localisation of
// the office scenario as well as the original maps/office_floor.xml. The
// scenario keeps the original world as the simulated truth; only the replay's
// map changes.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "cli_runner.hpp"
#include "structloc/replay/replay.hpp"
#include "structloc/simulation_core/recorder.hpp"
#include "structloc/simulation_core/scenario.hpp"
#include "temp_dir.hpp"
#include "test_paths.hpp"

namespace structloc {
namespace {

replay::TrajectoryError Localise(const std::string& map, const std::string& dir,
                                 const geometry::Pose2D& initial_pose, const std::string& name) {
  replay::ReplayOptions o;
  o.map_path = map;
  o.log_path = dir + "/run.clf";
  o.params_path = testing::SourcePath("maps/params/office_sick.xml");
  o.truth_path = dir + "/truth.tum";
  o.out_tum = dir + "/" + name + ".tum";
  o.initial_pose = initial_pose;
  const auto report = replay::RunReplay(o);
  EXPECT_GT(report.scans_used, 590u) << name;
  EXPECT_EQ(report.scans_lost, 0u) << name;
  if (!report.estimate_error) {
    ADD_FAILURE() << name << ": no error against the truth";
    return {};
  }
  const auto& e = *report.estimate_error;
  std::printf("%s: %zu poses, position RMSE %.2f mm, max %.2f mm, heading RMSE %.4f deg\n",
              name.c_str(), e.matched, 1e3 * e.position_rmse_m, 1e3 * e.position_max_m,
              e.heading_rmse_rad * 180.0 / geometry::kPi);
  return e;
}

TEST(DxfImportLocalisation, TheOfficeLocalisesOnTheImportedDrawingAsOnTheOriginalWorld) {
  const testing::TempDir temp;
  const std::string imported = temp / "office_from_dxf.xml";
  const auto import = testing::RunCli({"map", "import", "--dxf",
                                       testing::SourcePath("tests/data/maps/office_floor_mm.dxf"),
                                       "--layers", "WALLS,PILLARS", "--out", imported});
  ASSERT_EQ(import.exit_code, 0) << import.output;

  const auto scenario =
      simulation_core::LoadScenario(testing::SourcePath("maps/scenarios/office_people.xml"));
  const std::string dir = temp / "office";
  simulation_core::RecordScenario(scenario, dir);

  const auto original = Localise(testing::SourcePath("maps/office_floor.xml"), dir,
                                 scenario.initial_pose, "original world");
  const auto from_dxf = Localise(imported, dir, scenario.initial_pose, "imported DXF");
  ASSERT_GT(original.matched, 590u);
  ASSERT_EQ(from_dxf.matched, original.matched);
  EXPECT_LE(from_dxf.position_rmse_m, original.position_rmse_m + 0.001);
  EXPECT_LE(from_dxf.position_max_m, original.position_max_m + 0.005);
  EXPECT_LE(from_dxf.heading_rmse_rad, original.heading_rmse_rad + 0.01 * geometry::kPi / 180.0);
}

}  // namespace
}  // namespace structloc
