// The seam for feature kinds: the parameter file's blocks decide which
// extractors run, each kind reports under its own name, and a kind written
// outside the library (here a test-only one) plugs in with nothing else changed.
#include <gtest/gtest.h>

#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "office_scene.hpp"
#include "structloc/localisation_core/features/corners/corner_extractor.hpp"
#include "structloc/localisation_core/features/cylinders/cylinder_extractor.hpp"
#include "structloc/localisation_core/features/feature_kinds.hpp"
#include "structloc/localisation_core/features/walls/wall_extractor.hpp"
#include "structloc/localisation_core/localiser/localiser.hpp"

namespace structloc::localisation_core {
namespace {

std::vector<std::string> Kinds(const std::vector<std::unique_ptr<FeatureExtractor>>& extractors) {
  std::vector<std::string> kinds;
  for (const auto& e : extractors) kinds.emplace_back(e->Kind());
  return kinds;
}

TEST(FeatureKinds, TheParameterFileDecidesWhichExtractorsRunAndInWhichOrder) {
  const testing::OfficeScene office(2 * geometry::kPi);
  LocaliserOptions o;
  EXPECT_EQ(Kinds(MakeFeatureExtractors(o, office.world, 300)),
            (std::vector<std::string>{"walls", "corners", "cylinders"}));
  o.kinds.Get<CornerKindOptions>().enabled = false;
  EXPECT_EQ(Kinds(MakeFeatureExtractors(o, office.world, 300)),
            (std::vector<std::string>{"walls", "cylinders"}));
  o.kinds.Get<CylinderKindOptions>().enabled = false;
  EXPECT_EQ(Kinds(MakeFeatureExtractors(o, office.world, 300)),
            (std::vector<std::string>{"walls"}));
}

TEST(FeatureKinds, EveryKindIsNamedLikeItsBlockInTheParameterFile) {
  const testing::OfficeScene office(2 * geometry::kPi);
  const auto file = LocaliserOptionFile();
  const auto kinds = FeatureKinds();
  const auto extractors = MakeFeatureExtractors(LocaliserOptions{}, office.world, 300);
  ASSERT_EQ(kinds.size(), extractors.size());
  for (size_t i = 0; i < kinds.size(); ++i) EXPECT_STREQ(kinds[i].name, extractors[i]->Kind());
  for (const auto& e : extractors) {
    bool found = false;
    for (const auto& section : file.Sections()) found = found || section.Section() == e->Kind();
    EXPECT_TRUE(found) << e->Kind() << " has no <" << e->Kind() << "> block";
  }
}

TEST(FeatureKinds, EachKindsOptionsAreItsOwnTypeAndItsBlockReadsThem) {
  LocaliserOptions o;
  EXPECT_DOUBLE_EQ(o.kinds.Get<CornerKindOptions>().extraction.gate_m, CornerOptions{}.gate_m);
  o.kinds.Get<CornerKindOptions>().extraction.gate_m = 0.35;
  o.kinds.Get<WallKindOptions>().clusters.gate_r_m = 0.15;
  const LocaliserOptions copy = o;
  EXPECT_DOUBLE_EQ(copy.kinds.Get<CornerKindOptions>().extraction.gate_m, 0.35);
  EXPECT_DOUBLE_EQ(copy.kinds.Get<WallKindOptions>().clusters.gate_r_m, 0.15);
  EXPECT_TRUE(copy.kinds.Get<CylinderKindOptions>().enabled) << "defaults for a kind never set";
  // The <corners> block shows and checks the corner kind's own options.
  const auto file = LocaliserOptionFile();
  int corner_blocks = 0;
  for (const auto& section : file.Sections()) {
    if (section.Section() != "corners") continue;
    ++corner_blocks;
    bool shown = false;
    for (const auto& [key, value] : section.Values(copy)) {
      shown = shown || (key == "gate_m" && value == "0.35");
    }
    EXPECT_TRUE(shown);
    o.kinds.Get<CornerKindOptions>().extraction.gate_m = -1.0;
    EXPECT_THROW(section.Validate(o), std::invalid_argument);
  }
  EXPECT_EQ(corner_blocks, 1);
}

TEST(FeatureKinds, ResultsListEachEnabledKindWithItsCountsMatchesAndTime) {
  testing::OfficeScene office(2 * geometry::kPi);
  office.options.kinds.Get<CornerKindOptions>().enabled = false;
  Localiser localiser(office.world, office.options);
  std::mt19937 rng(5);
  const auto scan = office.Scan(300, rng);
  const auto& r = localiser.Update(office.Input(scan));
  ASSERT_FALSE(r.lost) << ToString(r.lost_reason);
  ASSERT_EQ(r.features.size(), 2u);
  EXPECT_EQ(r.Kind("corners"), nullptr);
  const auto* walls = r.Kind("walls");
  const auto* cylinders = r.Kind("cylinders");
  ASSERT_NE(walls, nullptr);
  ASSERT_NE(cylinders, nullptr);
  EXPECT_EQ(walls->shape, FeatureShape::kLine);
  EXPECT_GT(walls->Matched(), 2);
  EXPECT_GE(walls->expected, walls->Matched());
  EXPECT_GT(cylinders->Matched(), 0);
  EXPECT_EQ(r.Matched(), walls->Matched() + cylinders->Matched());
  for (const auto& m : cylinders->matches) {
    EXPECT_GT(m.radius_m, 0.0) << "a cylinder match carries its radius";
    EXPECT_GT(std::hypot(m.x_m, m.y_m), 0.0);
  }
  EXPECT_GE(walls->extract_us, 0.0);
}

// A feature kind written for this test only, to show what a new kind provides:
// it places the map's visible corners itself and "finds" each exactly where the
// true pose puts it.
class OracleCorners : public FeatureExtractor {
 public:
  explicit OracleCorners(const geometry::Pose2D& true_sensor) : true_sensor_(true_sensor) {}
  const char* Kind() const override { return "oracle_corners"; }
  FeatureShape Shape() const override { return FeatureShape::kPoint; }
  int TakeSlots(const world_model::WorldModel& map, int first_slot) override {
    first_slot_ = first_slot;
    return static_cast<int>(map.Corners().size());
  }
  void Expect(const ExpectationInput& in) override {
    expected_.clear();
    for (int i : in.visibility->corners) {
      const auto& c = in.map->Corners()[static_cast<size_t>(i)];
      expected_.push_back(
          ExpectPoint(i, c.id, c.position, 0.0, first_slot_, in.sensor_prior, *in.map_errors));
    }
  }
  int Expected() const override { return static_cast<int>(expected_.size()); }
  void Extract(const ExtractionInput&, Measurements& all,
               std::vector<FeatureMatch>& matches) override {
    for (const auto& e : expected_) {
      PointMeasurement m;
      m.sensor = true_sensor_.ApplyInverse(e.world);
      m.covariance = 1e-6 * Eigen::Matrix2d::Identity();
      m.world = e.world;
      FeatureMatch match;
      match.model_id = e.model_id;
      match.slot = e.slot;
      match.members = 1;
      match.x_m = m.sensor.x();
      match.y_m = m.sensor.y();
      match.row = static_cast<int>(all.points.size());
      all.points.push_back(m);
      matches.push_back(match);
    }
  }

 private:
  geometry::Pose2D true_sensor_;
  int first_slot_ = 0;
  std::vector<ExpectedPoint> expected_;
};

TEST(FeatureKinds, ANewKindPlugsInWithoutChangingTheLocaliser) {
  testing::OfficeScene office(2 * geometry::kPi);
  const geometry::Pose2D sensor = geometry::Compose(office.truth, office.options.sensor_mount);
  std::vector<std::unique_ptr<FeatureExtractor>> extractors;
  extractors.push_back(std::make_unique<OracleCorners>(sensor));
  Localiser localiser(office.world, office.options, std::move(extractors));
  std::mt19937 rng(5);
  const auto scan = office.Scan(300, rng);
  const auto& r = localiser.Update(office.Input(scan));
  ASSERT_FALSE(r.lost) << ToString(r.lost_reason);
  ASSERT_EQ(r.features.size(), 1u);
  const auto* oracle = r.Kind("oracle_corners");
  ASSERT_NE(oracle, nullptr);
  EXPECT_GE(oracle->Matched(), 2);
  EXPECT_EQ(oracle->expected, oracle->Matched());
  for (const auto& m : oracle->matches) EXPECT_TRUE(m.used);
  EXPECT_NEAR(r.pose.x, office.truth.x, 1e-3);
  EXPECT_NEAR(r.pose.y, office.truth.y, 1e-3);
  EXPECT_NEAR(r.pose.theta, office.truth.theta, 1e-3);
}

}  // namespace
}  // namespace structloc::localisation_core
