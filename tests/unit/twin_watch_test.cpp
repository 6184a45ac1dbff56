// The map's twins and the watch that tells a tracked pose from its twin: in
// the pillared hall (the same turned by 180 deg about its centre but for a
// niche in the east wall) a robot tracked at the twin of where it is fits
// every scan as well as at the truth until the niche is in view.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "structloc/localisation_core/global/map_twins.hpp"
#include "structloc/localisation_core/global/twin_watch.hpp"
#include "structloc/world_model/world_model_xml.hpp"
#include "synthetic_scans.hpp"

namespace structloc::localisation_core {
namespace {

world_model::WorldModel Map(const std::string& name) {
  return world_model::LoadWorldModel(std::string(STRUCTLOC_SOURCE_DIR) + "/maps/" + name);
}

TEST(MapTwins, ThePillaredHallHasOneTwinTurnedAboutItsCentre) {
  const auto hall = Map("pillar_hall.xml");
  const GlobalLocaliser localiser(hall, GlobalLocaliserOptions{});
  const auto twins = FindMapTwins(hall, localiser);
  ASSERT_EQ(twins.size(), 1u);
  // 180 deg about (12, 7): a place p goes to (24, 14) - p.
  EXPECT_NEAR(twins[0].x, 24.0, 0.01);
  EXPECT_NEAR(twins[0].y, 14.0, 0.01);
  EXPECT_NEAR(std::abs(twins[0].theta), geometry::kPi, 1e-6);
}

TEST(MapTwins, TheSymmetricOfficeHasItsTwinToo) {
  const auto office = Map("symmetric_office.xml");
  const GlobalLocaliser localiser(office, GlobalLocaliserOptions{});
  const auto twins = FindMapTwins(office, localiser);
  ASSERT_EQ(twins.size(), 1u);
  EXPECT_NEAR(std::abs(twins[0].theta), geometry::kPi, 1e-6);
}

TEST(MapTwins, MapsWithoutTwinsHaveNone) {
  for (const char* name : {"office_floor.xml", "room_corridor.xml", "corridor_hall.xml",
                           "real/freiburg_079.xml", "real/intel.xml"}) {
    const auto world = Map(name);
    const GlobalLocaliser localiser(world, GlobalLocaliserOptions{});
    EXPECT_TRUE(FindMapTwins(world, localiser).empty()) << name;
  }
}

TEST(MapTwins, OptionsOutOfRangeAreNamed) {
  MapTwinOptions o;
  o.min_overlap = 0.3;
  EXPECT_THROW(
      {
        try {
          CheckMapTwinOptions(o);
        } catch (const std::invalid_argument& e) {
          EXPECT_NE(std::string(e.what()).find("min_overlap"), std::string::npos);
          throw;
        }
      },
      std::invalid_argument);
}

// Drives the robot along the hall's south side towards the niche (x from 12
// to 21 at y = 2.5, heading east), the watch told the robot is at the twin
// of the truth (`tracked_at_twin`) or at the truth; returns the first
// decision.
std::optional<TwinDecision> DriveEast(bool tracked_at_twin) {
  const auto hall = Map("pillar_hall.xml");
  const auto scene = world_model::Scene::FromWorld(hall);
  const GlobalLocaliser localiser(hall, GlobalLocaliserOptions{});
  const auto twins = FindMapTwins(hall, localiser);
  const geometry::Pose2D mount{0.2, 0.0, 0.0};
  TwinWatch watch(localiser, mount, twins, HypothesisOptions{}, MapTwinOptions{}.allowance_points);
  std::mt19937 rng(7);
  for (int i = 0; i <= 90; ++i) {
    const geometry::Pose2D truth{12.0 + 0.1 * i, 2.5, 0.0};
    const auto scan = testing::CastScan(scene, geometry::Compose(truth, mount),
                                        {541, 1.5 * geometry::kPi, 30.0, 0.01}, rng);
    const auto points =
        ScanPointsInLaserFrame(scan.ranges, scan.angle_min, scan.angle_increment, 0.05, 30.0);
    const geometry::Pose2D tracked =
        tracked_at_twin ? geometry::Compose(twins.at(0), truth) : truth;
    if (auto decision = watch.Observe(points, 0.1 * i, tracked, 0.0)) return decision;
  }
  return std::nullopt;
}

TEST(TwinWatch, ARobotTrackedAtItsTwinIsFoundOnceTheDifferingDetailIsInView) {
  const auto decision = DriveEast(/*tracked_at_twin=*/true);
  ASSERT_TRUE(decision.has_value());
  // Where it is: on the south side, heading east.
  EXPECT_GT(decision->twin.x, 12.0);
  EXPECT_NEAR(decision->twin.y, 2.5, 0.05);
  EXPECT_NEAR(decision->twin.theta, 0.0, 0.02);
  EXPECT_LE(decision->since, decision->stamp);
}

TEST(TwinWatch, ARobotTrackedWhereItIsKeepsItsPose) {
  EXPECT_FALSE(DriveEast(/*tracked_at_twin=*/false).has_value());
}

TEST(TwinWatch, ARobotStandingStillWeighsOneScanOnly) {
  const auto hall = Map("pillar_hall.xml");
  const GlobalLocaliser localiser(hall, GlobalLocaliserOptions{});
  TwinWatch watch(localiser, {}, FindMapTwins(hall, localiser), HypothesisOptions{},
                  MapTwinOptions{}.allowance_points);
  const geometry::Pose2D still{20.0, 2.5, 0.0};
  EXPECT_TRUE(watch.Due(still));
  watch.Observe({}, 0.0, still, 0.0);
  EXPECT_FALSE(watch.Due(still));
  EXPECT_TRUE(watch.Due({20.3, 2.5, 0.0}));
}

}  // namespace
}  // namespace structloc::localisation_core
