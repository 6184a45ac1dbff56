// The office tour with people, simulated offline (the log `structloc record`
// writes live when no scan is dropped), mapped by `structloc slam` and
// localised on the map it built. A self-built map has a frame of its own, so
// both are judged after one rigid alignment to the truth: the SLAM path by
// the real recordings' bars with odometry errors (RMSE <= 50 mm, max <= 200
// mm), the localisation on the self-built map by the demo's (10 mm, 30 mm).
// The people walking the corridor must not be built into the map.
#include <gtest/gtest.h>

#include <string>

#include "self_built_map.hpp"
#include "structloc/replay/replay.hpp"
#include "structloc/simulation_core/recorder.hpp"
#include "structloc/simulation_core/scenario.hpp"
#include "structloc/world_model/world_model_xml.hpp"
#include "temp_dir.hpp"
#include "test_paths.hpp"

namespace structloc {
namespace {

TEST(SelfBuiltMap, TheSimulatedOfficeTourMapsItselfAndLocalisesOnItsMap) {
  const testing::TempDir temp;
  const auto scenario =
      simulation_core::LoadScenario(testing::SourcePath("maps/scenarios/office_people.xml"));
  simulation_core::RecordScenario(scenario, temp.Path());
  replay::ReplayOptions o;
  o.log_path = temp / "run.clf";
  o.params_path = testing::SimulatedRobotParams();
  const auto built = testing::MapAndLocalise(o, temp / "truth.tum", temp.Path());
  ASSERT_EQ(built.slam.exit_code, 0) << built.slam.output;
  testing::ExpectMapExplainsItsScans(built);
  EXPECT_LE(built.slam_error.position_rmse_m, 0.05);
  EXPECT_LE(built.slam_error.position_max_m, 0.2);
  EXPECT_EQ(built.on_own_map.scans_lost, 0u);
  EXPECT_LE(built.on_own_map_error.position_rmse_m, 0.01);
  EXPECT_LE(built.on_own_map_error.position_max_m, 0.03);
  // The floor's three pillars and the scenario's cylinder, once each: not
  // rows of them where the people walked, nor one built twice where the
  // path's passes disagree by centimetres.
  const auto world = world_model::LoadWorldModel(temp / "slam_world.xml");
  EXPECT_EQ(world.Cylinders().size(), 4u);
}

}  // namespace
}  // namespace structloc
