// The kidnap watch's searches are held to their budget of work per scan: on
// a map that explains little of a building the watch doubts the tracking
// again and again, and each whole-map search it asks for costs 0.05-0.3 s.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "office_scene.hpp"
#include "structloc/localisation_core/global/kidnap_watch.hpp"

namespace structloc::localisation_core {
namespace {

KidnapOptions Budgeted() {
  KidnapOptions o;
  o.search_period_s = 0.0;  // only the budget holds the searches back
  o.max_search_period_s = 0.0;
  o.search_work_per_scan = 1e5;
  o.search_work_banked = 6e6;
  return o;
}

// Feeds `scans` lost scans at 10 Hz from `t0`; each search due costs `work`.
// Returns the stamps searched at.
std::vector<double> LostFor(KidnapWatch& watch, double t0, int scans, uint64_t work) {
  std::vector<double> searched;
  for (int i = 0; i < scans; ++i) {
    const double t = t0 + 0.1 * i;
    if (watch.Observe({}, t, {}, /*lost=*/true)) {
      watch.Searched(t);
      watch.Spent(work);
      searched.push_back(t);
    }
  }
  return searched;
}

TEST(KidnapWatch, ItsSearchesStayWithinTheirBudgetOfWorkPerScan) {
  const testing::OfficeScene office(geometry::kPi);
  const GlobalLocaliser localiser(office.world, GlobalLocaliserOptions{});
  const KidnapOptions o = Budgeted();
  KidnapWatch watch(localiser, office.options.sensor_mount, o);
  const int scans = 1000;
  const uint64_t work = 3'000'000;
  const auto searched = LostFor(watch, 0.0, scans, work);
  // All it may spend: what it had saved and what the scans brought; and it
  // does search whenever the budget holds a search, so it spends nearly all.
  const double allowed = o.search_work_banked + scans * o.search_work_per_scan;
  const double spent = static_cast<double>(searched.size() * work);
  EXPECT_LE(spent, allowed);
  EXPECT_GE(spent, allowed - 2.0 * work);
  // The first search comes once the doubt has lasted after_s.
  ASSERT_FALSE(searched.empty());
  EXPECT_NEAR(searched.front(), o.after_s, 0.1 + 1e-9);
}

TEST(KidnapWatch, AfterACalmSpellTheFirstSearchComesAtOnce) {
  const testing::OfficeScene office(geometry::kPi);
  const GlobalLocaliser localiser(office.world, GlobalLocaliserOptions{});
  KidnapWatch watch(localiser, office.options.sensor_mount, Budgeted());
  const uint64_t work = 3'000'000;
  LostFor(watch, 0.0, 300, work);  // spends all it had
  EXPECT_LT(watch.Budget(), static_cast<double>(work));
  // Tracked again, at the pose the scans are taken from, for 60 s.
  std::mt19937 rng(7);
  const auto scan = office.Scan(361, rng);
  const auto points = ScanPointsInLaserFrame(scan.ranges, scan.angle_min, scan.angle_increment, 0.0,
                                             scan.max_range_m - 1e-3);
  for (int i = 0; i < 600; ++i) {
    const double t = 30.0 + 0.1 * i;
    EXPECT_FALSE(watch.Observe(points, t, office.truth, /*lost=*/false));
  }
  ASSERT_TRUE(watch.LastShare());
  EXPECT_GT(*watch.LastShare(), 0.9);
  const auto searched = LostFor(watch, 90.0, 100, work);
  ASSERT_FALSE(searched.empty());
  EXPECT_NEAR(searched.front(), 90.0 + watch.Options().after_s, 0.1 + 1e-9);
  EXPECT_GE(searched.size(), 2u);  // the budget had saved up two searches
}

TEST(KidnapWatch, ToldToDoubtItSearchesUntilASearchFindsTheRobot) {
  const testing::OfficeScene office(geometry::kPi);
  const GlobalLocaliser localiser(office.world, GlobalLocaliserOptions{});
  KidnapWatch watch(localiser, office.options.sensor_mount, KidnapOptions{});
  std::mt19937 rng(7);
  const auto scan = office.Scan(361, rng);
  const auto points = ScanPointsInLaserFrame(scan.ranges, scan.angle_min, scan.angle_increment, 0.0,
                                             scan.max_range_m - 1e-3);
  // The scans fit where the robot is tracked: no doubt ...
  for (int i = 0; i < 20; ++i) EXPECT_FALSE(watch.Observe(points, 0.1 * i, office.truth, false));
  EXPECT_FALSE(watch.InDoubt());
  // ... until a search made for another reason found a place that fits
  // clearly better: a search is due at once, and the doubt stays although
  // the share does not fall.
  watch.Doubt(2.0);
  EXPECT_TRUE(watch.Observe(points, 2.0, office.truth, false));
  watch.Searched(2.0);
  for (int i = 1; i < 50; ++i) watch.Observe(points, 2.0 + 0.1 * i, office.truth, false);
  EXPECT_TRUE(watch.InDoubt());
  // A search that finds the robot where it is tracked ends it.
  EXPECT_FALSE(watch.Jumped(7.0, points, office.truth, office.truth));
  EXPECT_FALSE(watch.Observe(points, 7.1, office.truth, false));
  EXPECT_FALSE(watch.InDoubt());
}

TEST(KidnapWatch, ClearlyBetterMeansMinShareGainMoreOfTheScan) {
  const testing::OfficeScene office(geometry::kPi);
  const GlobalLocaliser localiser(office.world, GlobalLocaliserOptions{});
  const KidnapWatch watch(localiser, office.options.sensor_mount, KidnapOptions{});
  std::mt19937 rng(7);
  const auto scan = office.Scan(361, rng);
  const auto points = ScanPointsInLaserFrame(scan.ranges, scan.angle_min, scan.angle_increment, 0.0,
                                             scan.max_range_m - 1e-3);
  const geometry::Pose2D elsewhere{office.truth.x - 3.0, office.truth.y + 1.0, 1.0};
  EXPECT_TRUE(watch.ClearlyBetter(points, office.truth, elsewhere));
  EXPECT_FALSE(watch.ClearlyBetter(points, elsewhere, office.truth));
  EXPECT_FALSE(watch.ClearlyBetter(points, office.truth, office.truth));
}

TEST(KidnapWatch, RefusesABudgetThatCannotHoldAScansShare) {
  KidnapOptions o;
  o.search_work_banked = o.search_work_per_scan / 2;
  EXPECT_THROW(CheckKidnapOptions(o), std::invalid_argument);
  o = KidnapOptions{};
  o.search_work_per_scan = -1.0;
  EXPECT_THROW(CheckKidnapOptions(o), std::invalid_argument);
}

}  // namespace
}  // namespace structloc::localisation_core
