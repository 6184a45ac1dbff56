// Global localisation (issue 12) on simulated scans: on the office floor a
// scan from a random pose in the corridor or the hall gives that pose (the
// offices themselves are identical rooms with the door at the same place, so
// there "ambiguous" is the right answer and only a confident wrong pose is an
// error); in a rectangular room, whose scans
// fit the room turned by half a turn as well, the answer is "ambiguous", never
// a confident pose; a scan of clutter the map does not hold is "not found".
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <random>

#include "office_scene.hpp"
#include "structloc/localisation_core/global/global_localiser.hpp"
#include "synthetic_scans.hpp"

namespace structloc {
namespace {

using localisation_core::GlobalDecision;
using localisation_core::GlobalLocaliser;
using localisation_core::GlobalLocaliserOptions;

std::vector<Eigen::Vector2d> Points(const testing::SyntheticScan& scan) {
  return localisation_core::ScanPointsInLaserFrame(
      scan.ranges, scan.angle_min, scan.angle_increment, 0.0, scan.max_range_m - 1e-3);
}

bool Close(const geometry::Pose2D& a, const geometry::Pose2D& b) {
  return std::hypot(a.x - b.x, a.y - b.y) <= 0.2 &&
         std::abs(geometry::WrapAngle(a.theta - b.theta)) <= 5.0 * geometry::kPi / 180.0;
}

// A pose within `b` (min x, min y, max x, max y) at least `clearance` from
// every wall and pillar.
geometry::Pose2D RandomPose(const world_model::WorldModel& world, const Eigen::Vector4d& b,
                            double clearance, std::mt19937& rng) {
  std::uniform_real_distribution<double> x(b[0], b[2]), y(b[1], b[3]),
      theta(-geometry::kPi, geometry::kPi);
  for (;;) {
    const Eigen::Vector2d p(x(rng), y(rng));
    bool clear = true;
    for (const auto& wall : world.Walls()) {
      const Eigen::Vector2d d = wall.b - wall.a;
      const double t = std::clamp((p - wall.a).dot(d) / d.squaredNorm(), 0.0, 1.0);
      clear = clear && (p - (wall.a + t * d)).norm() > clearance;
    }
    for (const auto& c : world.Cylinders())
      clear = clear && (p - c.centre).norm() > c.radius + clearance;
    if (clear) return {p.x(), p.y(), theta(rng)};
  }
}

struct Tally {
  int right = 0, ambiguous = 0, not_found = 0, wrong = 0;
  double seconds = 0.0;
};

// Scans from `scans` random poses within `area` of the office (SICK's 270 deg).
Tally LocateInOffice(const Eigen::Vector4d& area, int scans, unsigned seed, const char* name) {
  const testing::OfficeScene office(4.71238898038469);
  const GlobalLocaliser localiser(office.world, GlobalLocaliserOptions{});
  std::mt19937 rng(seed);
  Tally t;
  for (int n = 0; n < scans; ++n) {
    const geometry::Pose2D truth = RandomPose(office.world, area, 0.4, rng);
    const auto scan =
        testing::CastScan(office.scene, truth, {541, 4.71238898038469, 30.0, 0.01}, rng);
    const auto t0 = std::chrono::steady_clock::now();
    const auto result = localiser.Locate(Points(scan));
    t.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    switch (result.decision) {
      case GlobalDecision::kFound:
        ++(Close(result.best->pose, truth) ? t.right : t.wrong);
        EXPECT_TRUE(Close(result.best->pose, truth))
            << "placed at " << result.best->pose.x << " " << result.best->pose.y << " "
            << result.best->pose.theta << ", truth " << truth.x << " " << truth.y << " "
            << truth.theta;
        break;
      case GlobalDecision::kAmbiguous:
        ++t.ambiguous;
        break;
      case GlobalDecision::kNotFound:
        ++t.not_found;
        break;
    }
  }
  std::printf(
      "office %s: %d scans: %d right, %d ambiguous, %d not found, %d wrong; %.0f ms per "
      "scan\n",
      name, scans, t.right, t.ambiguous, t.not_found, t.wrong, 1e3 * t.seconds / scans);
  return t;
}

TEST(GlobalLocalisation, FindsRandomPosesInTheOfficeCorridorAndHall) {
  const Tally corridor = LocateInOffice({0, 5, 18, 8}, 20, 7, "corridor");
  const Tally hall = LocateInOffice({18, 0, 24, 14}, 20, 8, "hall");
  EXPECT_EQ(corridor.wrong + hall.wrong, 0);
  EXPECT_GE(corridor.right + hall.right, 36);
}

TEST(GlobalLocalisation, IsNeverConfidentlyWrongInTheOfficesIdenticalRooms) {
  const Tally rooms = LocateInOffice({0, 0, 18, 5}, 20, 9, "south rooms");
  EXPECT_EQ(rooms.wrong, 0);
}

world_model::WorldModel RectangularRoom() {
  return world_model::WorldModel(
      "room",
      {world_model::MakeWall(1, {0, 0}, {10, 0}), world_model::MakeWall(2, {10, 0}, {10, 6}),
       world_model::MakeWall(3, {10, 6}, {0, 6}), world_model::MakeWall(4, {0, 6}, {0, 0})},
      {}, {});
}

// A scan of the room from a random pose gives that pose and its twin (the
// room turned by half a turn), as best and runner-up, and "ambiguous".
void ExpectTwinsInTheRoom(const GlobalLocaliserOptions& options) {
  const world_model::WorldModel room = RectangularRoom();
  const auto scene = world_model::Scene::FromWorld(room);
  const GlobalLocaliser localiser(room, options);
  std::mt19937 rng(3);
  for (int n = 0; n < 10; ++n) {
    const geometry::Pose2D truth = RandomPose(room, room.Bounds(), 0.5, rng);
    const auto scan = testing::CastScan(scene, truth, {360, 2 * geometry::kPi, 30.0, 0.01}, rng);
    const auto result = localiser.Locate(Points(scan));
    ASSERT_TRUE(result.best && result.runner_up);
    EXPECT_EQ(result.decision, GlobalDecision::kAmbiguous)
        << "truth " << truth.x << " " << truth.y << " " << truth.theta << ", best "
        << result.best->pose.x << " " << result.best->pose.y << " " << result.best->pose.theta;
    // The two answers are the pose and its twin turned by half a turn about the centre.
    const geometry::Pose2D twin{10 - truth.x, 6 - truth.y,
                                geometry::WrapAngle(truth.theta + geometry::kPi)};
    EXPECT_TRUE((Close(result.best->pose, truth) && Close(result.runner_up->pose, twin)) ||
                (Close(result.best->pose, twin) && Close(result.runner_up->pose, truth)));
  }
}

TEST(GlobalLocalisation, ARectangularRoomIsAmbiguousNeverConfidentlyWrong) {
  ExpectTwinsInTheRoom(GlobalLocaliserOptions{});
}

// With no margin around the map, the walls on its far edges (x = 10 m, y = 6
// m lie exactly on a cell border) are drawn and the lattice stays on the grid.
TEST(GlobalLocalisation, WithoutAMarginTheWallsOnTheMapsEdgeCountToo) {
  GlobalLocaliserOptions options;
  options.grid_margin_m = 0.0;
  ExpectTwinsInTheRoom(options);
}

TEST(GlobalLocalisation, AScanOfClutterOnlyIsNotFound) {
  const testing::OfficeScene office(2 * geometry::kPi);
  const GlobalLocaliser localiser(office.world, GlobalLocaliserOptions{});
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int n = 0; n < 5; ++n) {
    // Boxes of 0.2-0.6 m strewn 1-4 m around a sensor in open space, no walls.
    world_model::Scene clutter;
    for (int i = 0; i < 12; ++i) {
      const double a = 2 * geometry::kPi * u(rng), r = 1.0 + 3.0 * u(rng);
      clutter.Add(testing::Box({r * std::cos(a), r * std::sin(a)}, 0.2 + 0.4 * u(rng),
                               0.2 + 0.4 * u(rng), geometry::kPi * u(rng)));
    }
    const auto scan =
        testing::CastScan(clutter, {0, 0, 0}, {360, 2 * geometry::kPi, 30.0, 0.01}, rng);
    const auto result = localiser.Locate(Points(scan));
    EXPECT_EQ(result.decision, GlobalDecision::kNotFound)
        << "best explains " << (result.best ? result.best->score : 0.0);
  }
}

// A search done a slice at a time (as a lost tracker does between scans)
// gives exactly what one done at once gives, whatever the slices: over the
// whole map and in a window, found or not.
// The same decision and the same best pose, to the last bit.
void ExpectTheSameAnswer(const localisation_core::GlobalResult& a,
                         const localisation_core::GlobalResult& b) {
  EXPECT_EQ(a.decision, b.decision);
  ASSERT_EQ(a.best.has_value(), b.best.has_value());
  if (!a.best) return;
  EXPECT_EQ(a.best->pose.x, b.best->pose.x);
  EXPECT_EQ(a.best->pose.y, b.best->pose.y);
  EXPECT_EQ(a.best->pose.theta, b.best->pose.theta);
  EXPECT_EQ(a.best->score, b.best->score);
}

TEST(GlobalLocalisation, ASearchInSlicesGivesWhatOneAtOnceGives) {
  const testing::OfficeScene office(4.71238898038469);
  const GlobalLocaliser localiser(office.world, GlobalLocaliserOptions{});
  std::mt19937 rng(11);
  for (int n = 0; n < 2; ++n) {
    const geometry::Pose2D truth = RandomPose(office.world, {1.0, 1.0, 19.0, 11.0}, 0.4, rng);
    const auto points =
        Points(testing::CastScan(office.scene, truth, {541, 4.71238898038469, 30.0, 0.01}, rng));
    const localisation_core::SearchWindow window{truth, 1.5, 0.5};
    for (const auto* w : {static_cast<const localisation_core::SearchWindow*>(nullptr), &window}) {
      const auto whole = localiser.Locate(points, w);
      localisation_core::GlobalSearch search(
          localiser, localisation_core::OneScan(points),
          w != nullptr ? std::optional<localisation_core::SearchWindow>(*w) : std::nullopt);
      int slices = 1;
      for (uint64_t budget = 5000; !search.Advance(budget); budget = budget * 3 / 2) ++slices;
      EXPECT_GT(slices, 3);
      const auto& sliced = search.Result();
      ExpectTheSameAnswer(sliced, whole);
      EXPECT_EQ(sliced.reason, whole.reason);
    }
  }
}

// Over the whole map the coarse phase is a branch and bound; a window as
// large as the map scores every position. Both must keep the same candidates
// and so give the same answer (a bound that dropped a good block would lose
// or move the best pose), also in the corridor of identical rooms, where the
// same coarse score comes back at every room: which of those tied hits were
// kept once depended on the order they were found in.
TEST(GlobalLocalisation, TheBranchAndBoundFindsWhatScoringEveryPositionFinds) {
  struct Floor {
    const char* map;
    Eigen::Vector4d area;  // where the random poses lie
  };
  for (const Floor& floor : {Floor{"office_floor.xml", {1.0, 1.0, 19.0, 11.0}},
                             Floor{"room_corridor.xml", {1.5, 6.9, 58.5, 7.1}}}) {
    SCOPED_TRACE(floor.map);
    const auto world =
        world_model::LoadWorldModel(std::string(STRUCTLOC_SOURCE_DIR) + "/maps/" + floor.map);
    const auto scene = world_model::Scene::FromWorld(world);
    const GlobalLocaliser localiser(world, GlobalLocaliserOptions{});
    std::mt19937 rng(12);
    const localisation_core::SearchWindow everywhere{{30.0, 6.0, 0.0}, 100.0, geometry::kPi};
    for (int n = 0; n < 4; ++n) {
      const geometry::Pose2D truth = RandomPose(world, floor.area, 0.4, rng);
      const auto points =
          Points(testing::CastScan(scene, truth, {541, 4.71238898038469, 30.0, 0.01}, rng));
      const auto bounded = localiser.Locate(points);
      const auto exhaustive = localiser.Locate(points, &everywhere);
      // The same hits kept (all those tied with the last one too, in whatever
      // order they were found) and refined in the same order: the same poses.
      ExpectTheSameAnswer(bounded, exhaustive);
      ASSERT_EQ(bounded.candidates.size(), exhaustive.candidates.size());
      for (size_t i = 0; i < bounded.candidates.size(); ++i) {
        EXPECT_EQ(bounded.candidates[i].pose.x, exhaustive.candidates[i].pose.x);
        EXPECT_EQ(bounded.candidates[i].pose.y, exhaustive.candidates[i].pose.y);
        EXPECT_EQ(bounded.candidates[i].score, exhaustive.candidates[i].score);
      }
    }
  }
}

// In the corridor of twelve identical rooms a scan from inside one room fits
// each of them as well. The hits of each room are many (neighbouring lattice
// positions and headings) and only the best of each neighbourhood is refined:
// every room must still be among the ranked poses, or the search would look
// surer than it is.
TEST(GlobalLocalisation, EachOfTheIdenticalRoomsIsRanked) {
  const auto world =
      world_model::LoadWorldModel(std::string(STRUCTLOC_SOURCE_DIR) + "/maps/room_corridor.xml");
  const auto scene = world_model::Scene::FromWorld(world);
  const GlobalLocaliser localiser(world, GlobalLocaliserOptions{});
  std::mt19937 rng(13);
  const geometry::Pose2D truth{27.3, 10.9, 1.4};  // in the sixth room, facing its back wall
  const auto result = localiser.Locate(
      Points(testing::CastScan(scene, truth, {541, 4.71238898038469, 30.0, 0.01}, rng)));
  EXPECT_EQ(result.decision, GlobalDecision::kAmbiguous);
  int rooms = 0;
  for (int room = 0; room < 12; ++room) {
    const geometry::Pose2D same{truth.x + 5.0 * (room - 5), truth.y, truth.theta};
    const bool ranked = std::any_of(
        result.candidates.begin(), result.candidates.end(),
        [&](const localisation_core::GlobalCandidate& c) { return Close(c.pose, same); });
    rooms += ranked ? 1 : 0;
    std::printf("room %d: %s\n", room, ranked ? "ranked" : "not ranked");
  }
  EXPECT_EQ(rooms, 12);
}

TEST(GlobalLocalisation, RefusesOptionsOutOfRange) {
  const testing::OfficeScene office(2 * geometry::kPi);
  GlobalLocaliserOptions options;
  options.coarse_step_m = 0.0;
  EXPECT_THROW(GlobalLocaliser(office.world, options), std::invalid_argument);
  options = {};
  options.min_score = 1.5;
  EXPECT_THROW(GlobalLocaliser(office.world, options), std::invalid_argument);
  options = {};
  options.grid_resolution_m = 1e-4;  // billions of cells
  EXPECT_THROW(GlobalLocaliser(office.world, options), std::invalid_argument);
  options = {};
  options.coarse_step_m = 1e-17;  // a lattice that never ends
  EXPECT_THROW(GlobalLocaliser(office.world, options), std::invalid_argument);
  options = {};
  options.coarse_step_m = 0.27;  // not a whole number of 5 cm cells
  EXPECT_THROW(GlobalLocaliser(office.world, options), std::invalid_argument);
  options = {};
  options.coarse_heading_step_rad = 1e-10;  // billions of headings
  EXPECT_THROW(GlobalLocaliser(office.world, options), std::invalid_argument);
  options = {};
  options.min_range_m = 40.0;  // beyond max_range_m: no reading could ever count
  EXPECT_THROW(GlobalLocaliser(office.world, options), std::invalid_argument);
  options = {};
  options.min_score = 0.0;  // every scan found, where the map explains none of it too
  EXPECT_THROW(GlobalLocaliser(office.world, options), std::invalid_argument);
  options = {};
  options.ambiguity_margin = 0.0;  // never "ambiguous", two equal poses or not
  EXPECT_THROW(GlobalLocaliser(office.world, options), std::invalid_argument);
  options = {};
  options.coarse_points = options.max_points + 1;
  EXPECT_THROW(GlobalLocaliser(office.world, options), std::invalid_argument);
  options = {};
  options.max_points = 400;
  options.coarse_points = 300;  // its 16-bit gains no longer sum exactly in a float
  EXPECT_THROW(GlobalLocaliser(office.world, options), std::invalid_argument);
  options = {};
  options.refine_precision_m = 0.0;  // climbs that go on until the step underflows
  EXPECT_THROW(GlobalLocaliser(office.world, options), std::invalid_argument);
}

TEST(GlobalLocalisation, TooFewReadingsAreNotFound) {
  const testing::OfficeScene office(2 * geometry::kPi);
  const GlobalLocaliser localiser(office.world, GlobalLocaliserOptions{});
  const auto result = localiser.Locate({{1.0, 0.0}, {0.0, 1.0}});
  EXPECT_EQ(result.decision, GlobalDecision::kNotFound);
  EXPECT_FALSE(result.best);
  EXPECT_NE(result.reason.find("readings"), std::string::npos);
}

}  // namespace
}  // namespace structloc
