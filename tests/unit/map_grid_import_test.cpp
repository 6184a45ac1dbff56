// Walls, corners and pillars from occupancy grids: a world exported into a
// 5 cm map_server grid and imported back lies on the original's lines to
// within a centimetre (the sub-cell accuracy `structloc map import --grid`
// promises), pillars within 2 cm; furniture and noise are left out; thick
// walls give their faces, with door gaps kept.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "structloc/map_building/grid_vectoriser.hpp"
#include "structloc/map_building/world_rasteriser.hpp"
#include "structloc/map_formats/grid_map_file.hpp"
#include "structloc/world_model/world_model_xml.hpp"
#include "temp_dir.hpp"
#include "test_paths.hpp"

namespace structloc {
namespace {

using map_building::FittedWall;
using map_building::GridVectorisation;
using map_building::GridVectoriseOptions;
using map_building::OccupancyGrid;

constexpr double kDegree = 3.14159265358979 / 180.0;

struct Match {
  double offset_m = INFINITY;  // larger distance of the original's ends from the imported line
  double angle_rad = INFINITY;
};

double DistanceToLine(const FittedWall& wall, const Eigen::Vector2d& p) {
  return std::abs(std::cos(wall.line.alpha) * p.x() + std::sin(wall.line.alpha) * p.y() -
                  wall.line.r);
}

// The imported wall on the same line as the original wall a-b that overlaps it.
Match BestMatch(const std::vector<FittedWall>& walls, const Eigen::Vector2d& a,
                const Eigen::Vector2d& b) {
  Match best;
  const double alpha = std::atan2(b.y() - a.y(), b.x() - a.x()) + M_PI / 2.0;
  for (const auto& w : walls) {
    const double angle = std::abs(std::asin(std::sin(w.line.alpha - alpha)));
    if (angle > 2.0 * kDegree) continue;
    const double ta = map_building::AlongWall(w, a), tb = map_building::AlongWall(w, b);
    if (std::max(ta, tb) < 0.0 || std::min(ta, tb) > w.Length()) continue;
    const double offset = std::max(DistanceToLine(w, a), DistanceToLine(w, b));
    if (offset < best.offset_m) best = {offset, angle};
  }
  return best;
}

world_model::WorldModel OfficeFloor() {
  return world_model::LoadWorldModel(testing::SourcePath("maps/office_floor.xml"));
}

OccupancyGrid Exported(const world_model::WorldModel& world, double resolution = 0.05) {
  map_building::RasteriseOptions options;
  options.resolution_m = resolution;
  return map_building::RasteriseWorld(world, options);
}

// Whether imported wall `w` lies on the line of true wall a-b (within
// `tolerance_m` at both its ends and `angle_rad`) and within its extent
// (plus `end_m`).
bool OnWall(const FittedWall& w, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
            double tolerance_m, double angle_rad, double end_m) {
  const Eigen::Vector2d d = (b - a).normalized();
  const Eigen::Vector2d n(-d.y(), d.x());
  const double length = (b - a).norm();
  const double angle = std::abs(std::asin(std::clamp(
      d.x() * (w.b - w.a).normalized().y() - d.y() * (w.b - w.a).normalized().x(), -1.0, 1.0)));
  for (const Eigen::Vector2d& end : {w.a, w.b}) {
    const double along = d.dot(end - a);
    if (std::abs(n.dot(end - a)) > tolerance_m || along < -end_m || along > length + end_m)
      return false;
  }
  return angle <= angle_rad;
}

// Every wall of `world` has an imported wall on its line within `tolerance_m`,
// the imported walls on its line cover it but for `end_m` at each end (not
// truncated), and every imported wall lies on a wall of `world` (none
// spurious); prints the offsets and angles.
void ExpectWallsRecovered(const world_model::WorldModel& world, const GridVectorisation& result,
                          double tolerance_m, double angle_tolerance_rad, double end_m = 0.1) {
  double worst = 0.0;
  for (const auto& wall : world.Walls()) {
    const Match m = BestMatch(result.walls, wall.a, wall.b);
    std::cout << "  wall " << wall.id << ": offset " << m.offset_m * 1000.0 << " mm, angle "
              << m.angle_rad / kDegree << " deg\n";
    EXPECT_LE(m.offset_m, tolerance_m) << "wall " << wall.id;
    EXPECT_LE(m.angle_rad, angle_tolerance_rad) << "wall " << wall.id;
    if (std::isfinite(m.offset_m)) worst = std::max(worst, m.offset_m);
    // Not truncated: the pieces on its line cover it (a door in it is two walls).
    const Eigen::Vector2d d = (wall.b - wall.a).normalized();
    const double length = (wall.b - wall.a).norm();
    std::vector<std::pair<double, double>> pieces;
    for (const auto& w : result.walls) {
      if (!OnWall(w, wall.a, wall.b, tolerance_m, angle_tolerance_rad, end_m)) continue;
      const double ta = d.dot(w.a - wall.a), tb = d.dot(w.b - wall.a);
      pieces.emplace_back(std::min(ta, tb), std::max(ta, tb));
    }
    std::sort(pieces.begin(), pieces.end());
    double covered_to = end_m;  // the first end_m need not be covered
    for (const auto& [from, to] : pieces) {
      if (from > covered_to + 1e-9) break;
      covered_to = std::max(covered_to, to);
    }
    EXPECT_GE(covered_to, length - end_m)
        << "wall " << wall.id << " (" << length << " m) covered only to " << covered_to << " m";
  }
  // None spurious.
  for (const auto& w : result.walls) {
    bool on_a_wall = false;
    for (const auto& wall : world.Walls())
      on_a_wall = on_a_wall || OnWall(w, wall.a, wall.b, tolerance_m, angle_tolerance_rad, end_m);
    EXPECT_TRUE(on_a_wall) << "imported wall (" << w.a.transpose() << ") - (" << w.b.transpose()
                           << ") lies on no wall of the map";
  }
  std::cout << "  worst wall offset " << worst * 1000.0 << " mm over " << world.Walls().size()
            << " walls\n";
}

void ExpectPillarsRecovered(const world_model::WorldModel& world, const GridVectorisation& result,
                            double tolerance_m) {
  ASSERT_EQ(result.pillars.size(), world.Cylinders().size());
  for (const auto& cylinder : world.Cylinders()) {
    double best = INFINITY, radius_error = INFINITY;
    for (const auto& p : result.pillars) {
      const double d = (p.centre - cylinder.centre).norm();
      if (d < best) {
        best = d;
        radius_error = std::abs(p.radius - cylinder.radius);
      }
    }
    std::cout << "  pillar " << cylinder.id << ": centre off by " << best * 1000.0
              << " mm, radius by " << radius_error * 1000.0 << " mm\n";
    EXPECT_LE(best, tolerance_m);
    EXPECT_LE(radius_error, tolerance_m);
  }
}

TEST(GridImport, OfficeFloorExportedAndImportedBackLiesOnTheOriginalLines) {
  const auto world = OfficeFloor();
  testing::TempDir dir;
  map_formats::SaveGridMap(Exported(world), dir / "office.yaml");
  const OccupancyGrid grid = map_formats::LoadGridMap(dir / "office.yaml");
  EXPECT_DOUBLE_EQ(grid.resolution_m, 0.05);
  const auto result = map_building::VectoriseGrid(grid, {});
  std::cout << "office_floor, 5 cm grid: " << result.walls.size() << " walls imported\n";
  ExpectWallsRecovered(world, result, 0.01, 0.2 * kDegree);
  EXPECT_EQ(result.walls.size(), world.Walls().size());
  ExpectPillarsRecovered(world, result, 0.02);
  EXPECT_EQ(result.blobs_left_out, 0u);
  EXPECT_EQ(result.specks_left_out, 0u);
  // The corners where walls meet come back (the cabinet-edge corner is not in a grid).
  const auto imported = map_building::MakeWorld("office", result.walls, result.pillars);
  size_t derived = 0;
  for (const auto& c : world.Corners()) derived += c.derived;
  EXPECT_EQ(imported.Corners().size(), derived);
}

// Walls at odd angles and positions, not on cell borders: the sub-cell fit.
TEST(GridImport, ObliqueWallsAtArbitraryPositionsComeBackWithinACentimetre) {
  std::vector<world_model::Wall> walls;
  const Eigen::Vector2d centre(3.137, 2.071);
  const double turn = 17.3 * kDegree;
  const Eigen::Vector2d half[4] = {
      {-2.513, -1.871}, {2.513, -1.871}, {2.513, 1.871}, {-2.513, 1.871}};
  auto corner = [&](int i) {
    const Eigen::Vector2d& h = half[i % 4];
    return Eigen::Vector2d(centre.x() + std::cos(turn) * h.x() - std::sin(turn) * h.y(),
                           centre.y() + std::sin(turn) * h.x() + std::cos(turn) * h.y());
  };
  for (int i = 0; i < 4; ++i)
    walls.push_back(world_model::MakeWall(i + 1, corner(i), corner(i + 1)));
  // A wall at 61 degrees inside the room.
  walls.push_back(world_model::MakeWall(5, {2.21, 1.33}, {3.17, 3.06}));
  const world_model::WorldModel world("oblique", walls, {}, {});
  const auto result = map_building::VectoriseGrid(Exported(world), {});
  std::cout << "oblique room, 5 cm grid:\n";
  ExpectWallsRecovered(world, result, 0.01, 0.3 * kDegree);
}

// A grid whose origin is turned (map_server's yaw): the walls are oblique in
// the cells and still come back on their lines in the map frame.
TEST(GridImport, GridWithATurnedOriginGivesTheWallsInTheMapFrame) {
  const auto world = OfficeFloor();
  const double yaw = 0.3;
  const Eigen::Rotation2Dd turn(yaw);
  const Eigen::Vector4d bounds = world.Bounds();
  Eigen::Vector2d low(INFINITY, INFINITY), high(-INFINITY, -INFINITY);
  for (const auto& corner :
       {Eigen::Vector2d(bounds[0], bounds[1]), Eigen::Vector2d(bounds[2], bounds[1]),
        Eigen::Vector2d(bounds[0], bounds[3]), Eigen::Vector2d(bounds[2], bounds[3])}) {
    const Eigen::Vector2d in_grid = turn.inverse() * corner;
    low = low.cwiseMin(in_grid);
    high = high.cwiseMax(in_grid);
  }
  const Eigen::Vector2d origin = turn * (low - Eigen::Vector2d(0.5, 0.5));
  const Eigen::Vector2d size = (high - low + Eigen::Vector2d(1.0, 1.0)) / 0.05;
  OccupancyGrid grid(static_cast<int>(size.x()) + 1, static_cast<int>(size.y()) + 1, 0.05,
                     {origin.x(), origin.y(), yaw}, OccupancyGrid::kFree);
  for (const auto& wall : world.Walls()) map_building::MarkSegment(grid, wall.a, wall.b);
  for (const auto& c : world.Cylinders()) map_building::MarkCircle(grid, c.centre, c.radius);
  const auto result = map_building::VectoriseGrid(grid, {});
  std::cout << "office_floor in a grid turned by 0.3 rad:\n";
  ExpectWallsRecovered(world, result, 0.01, 0.3 * kDegree);
  ExpectPillarsRecovered(world, result, 0.02);
}

TEST(GridImport, FurnitureSizedBlobsAreLeftOutAndCounted) {
  const auto world = OfficeFloor();
  OccupancyGrid grid = Exported(world);
  const auto plain = map_building::VectoriseGrid(grid, {});
  // A 0.6 m x 0.4 m desk, filled, in an office.
  const Eigen::Vector2i low = grid.CellOf({2.0, 1.5});
  for (int r = 0; r < 8; ++r)
    for (int c = 0; c < 12; ++c) grid.At(low.x() + c, low.y() + r) = OccupancyGrid::kOccupied;
  const auto result = map_building::VectoriseGrid(grid, {});
  EXPECT_EQ(result.blobs_left_out, 1u);
  EXPECT_EQ(result.walls.size(), plain.walls.size());
  EXPECT_EQ(result.pillars.size(), plain.pillars.size());
}

// A wall seen by few scans, as a ray-cast grid has it: 2 m of cells in
// pieces of one to three cells with one- and two-cell gaps, no piece near the
// 1 m of a wall blob; then, after a three-cell gap (more than the default
// 0.1 m join), a piece of three cells. Judged with its neighbours the wall is
// one wall on its line, along a row, a column or a diagonal, and the piece
// beyond stays out; judged alone (max_join_gap_m 0) every piece is left out.
// An isolated pair of cells stays a speck either way.
enum class Heading { kAlongRow, kAlongColumn, kDiagonal };

OccupancyGrid DottedWall(Heading heading) {
  OccupancyGrid grid(70, 70, 0.05, {0, 0, 0}, OccupancyGrid::kFree);
  const int pieces[][2] = {{5, 7},   {9, 9},   {12, 14}, {16, 17}, {20, 22}, {24, 24},
                           {27, 29}, {31, 33}, {36, 37}, {39, 41}, {43, 44}, {48, 50}};
  for (const auto& piece : pieces) {
    for (int i = piece[0]; i <= piece[1]; ++i) {
      const int c = heading == Heading::kAlongColumn ? 12 : i;
      const int r = heading == Heading::kAlongRow ? 12 : i;
      grid.At(c, heading == Heading::kDiagonal ? i + 8 : r) = OccupancyGrid::kOccupied;
    }
  }
  grid.At(60, 3) = grid.At(61, 3) = OccupancyGrid::kOccupied;  // a speck, far from the wall
  return grid;
}

TEST(GridImport, DottedWallIsJoinedAcrossItsGaps) {
  for (const Heading heading : {Heading::kAlongRow, Heading::kAlongColumn, Heading::kDiagonal}) {
    SCOPED_TRACE(static_cast<int>(heading));
    const OccupancyGrid grid = DottedWall(heading);
    GridVectoriseOptions alone;
    alone.max_join_gap_m = 0.0;
    const auto pieces_alone = map_building::VectoriseGrid(grid, alone);
    EXPECT_TRUE(pieces_alone.walls.empty());
    EXPECT_EQ(pieces_alone.face_cells, 0u);
    EXPECT_EQ(pieces_alone.specks_left_out, 6u);  // the pieces of 1-2 cells, and the speck
    EXPECT_EQ(pieces_alone.blobs_left_out, 7u);   // the pieces of 3 cells

    const auto result = map_building::VectoriseGrid(grid, {});
    ASSERT_EQ(result.walls.size(), 1u);
    const FittedWall& wall = result.walls.front();
    const auto cell = [&](int i) {
      return heading == Heading::kAlongRow      ? grid.CellCentre(i, 12)
             : heading == Heading::kAlongColumn ? grid.CellCentre(12, i)
                                                : grid.CellCentre(i, i + 8);
    };
    EXPECT_NEAR(DistanceToLine(wall, cell(5)), 0.0, 1e-6);
    EXPECT_NEAR(DistanceToLine(wall, cell(44)), 0.0, 1e-6);
    EXPECT_NEAR(wall.Length(), (cell(44) - cell(5)).norm(), 1e-6);
    EXPECT_EQ(result.specks_left_out, 1u);
    EXPECT_EQ(result.blobs_left_out, 1u);  // the piece beyond the three-cell gap
  }
}

// A grid whose cells are far finer than the join gap (here a malformed
// resolution of a nanometre) is judged with a bounded join, not a kernel of
// petabytes.
TEST(GridImport, JoinIsBoundedOnAGridFarFinerThanTheGap) {
  OccupancyGrid grid = DottedWall(Heading::kAlongRow);
  grid.resolution_m = 1e-9;
  const auto result = map_building::VectoriseGrid(grid, {});
  EXPECT_TRUE(result.walls.empty());  // the group is nanometres long
  // All 13 blobs in one group (64 cells span the grid), judged furniture.
  EXPECT_EQ(result.specks_left_out, 0u);
  EXPECT_EQ(result.blobs_left_out, 13u);
}

// A 3-cell (15 cm) thick wall as SLAM draws them, with a 1 m door: its two
// faces become two walls, each through its face cells' centres, each split at
// the door and sharing one line on both sides of it.
TEST(GridImport, ThickWallGivesItsFacesWithTheDoorKept) {
  OccupancyGrid grid(140, 60, 0.05, {0, 0, 0}, OccupancyGrid::kFree);
  for (int c = 10; c < 130; ++c) {
    if (c >= 60 && c < 80) continue;  // the door: x 3.0 .. 4.0 m
    for (int r = 30; r < 33; ++r) grid.At(c, r) = OccupancyGrid::kOccupied;
  }
  const auto result = map_building::VectoriseGrid(grid, {});
  ASSERT_EQ(result.walls.size(), 4u);
  const double lower_face = grid.CellCentre(0, 30).y(), upper_face = grid.CellCentre(0, 32).y();
  int lower = 0, upper = 0;
  for (const auto& w : result.walls) {
    EXPECT_NEAR(std::abs(std::cos(w.line.alpha)), 0.0, 1e-9);
    const double y = w.a.y();
    EXPECT_NEAR(w.b.y(), y, 1e-9);
    lower += std::abs(y - lower_face) < 1e-6;
    upper += std::abs(y - upper_face) < 1e-6;
    const double left = std::min(w.a.x(), w.b.x()), right = std::max(w.a.x(), w.b.x());
    // Each piece ends at the door, not across it.
    EXPECT_TRUE(right <= 3.0 || left >= 4.0) << left << " .. " << right;
  }
  EXPECT_EQ(lower, 2);
  EXPECT_EQ(upper, 2);
}

TEST(GridImport, NoisyGridStillGivesTheWallsAndPillars) {
  const auto world = OfficeFloor();
  OccupancyGrid grid = Exported(world);
  std::mt19937 generator(20261123);
  std::bernoulli_distribution flip(0.003);
  size_t flipped = 0;
  for (auto& cell : grid.cells) {
    if (cell == OccupancyGrid::kUnknown || !flip(generator)) continue;
    cell = cell == OccupancyGrid::kOccupied ? OccupancyGrid::kFree : OccupancyGrid::kOccupied;
    ++flipped;
  }
  const auto result = map_building::VectoriseGrid(grid, {});
  std::cout << "office_floor with " << flipped << " flipped cells: " << result.walls.size()
            << " walls, " << result.specks_left_out << " specks, " << result.blobs_left_out
            << " blobs left out\n";
  EXPECT_GT(result.specks_left_out, 100u);
  ExpectWallsRecovered(world, result, 0.015, 0.3 * kDegree);
  ExpectPillarsRecovered(world, result, 0.02);
}

// Blobs a circle cannot be fitted to (a short diagonal stroke: its cells on
// one line) are left out, not an error.
TEST(GridImport, StraightStrokesAreNoPillars) {
  OccupancyGrid grid(40, 40, 0.05, {0, 0, 0}, OccupancyGrid::kFree);
  for (int i = 5; i < 17; ++i) grid.At(i, i) = OccupancyGrid::kOccupied;
  const auto result = map_building::VectoriseGrid(grid, {});
  EXPECT_TRUE(result.pillars.empty());
  EXPECT_TRUE(result.walls.empty());
  EXPECT_EQ(result.blobs_left_out, 1u);
}

TEST(GridImport, AGridWithoutOccupiedCellsIsNothingToImport) {
  const OccupancyGrid grid(10, 10, 0.05, {0, 0, 0}, OccupancyGrid::kFree);
  try {
    map_building::VectoriseGrid(grid, {});
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("nothing to import"), std::string::npos) << e.what();
  }
}

// A grid assembled by hand whose cells do not match its size is refused
// before any cell is read.
TEST(GridImport, AGridWhoseCellsDoNotMatchItsSizeIsRefused) {
  OccupancyGrid grid(10, 10, 0.05, {0, 0, 0}, OccupancyGrid::kOccupied);
  grid.cells.resize(50);
  try {
    map_building::VectoriseGrid(grid, {});
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("do not match its 10 x 10 cells"), std::string::npos)
        << e.what();
  }
}

TEST(GridImport, CircleFitIsExactOnACircle) {
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i < 12; ++i)
    points.emplace_back(1.5 + 0.4 * std::cos(i * 0.5), -2.0 + 0.4 * std::sin(i * 0.5));
  const auto circle = map_building::FitCircle(points);
  EXPECT_NEAR(circle.centre.x(), 1.5, 1e-9);
  EXPECT_NEAR(circle.centre.y(), -2.0, 1e-9);
  EXPECT_NEAR(circle.radius, 0.4, 1e-9);
  EXPECT_NEAR(circle.rms_m, 0.0, 1e-9);
}

TEST(GridExport, WallsOnCellBordersMarkBothSidesAndPillarInsidesAreUnknown) {
  const world_model::WorldModel world("box", {world_model::MakeWall(1, {0, 0}, {1, 0})}, {},
                                      {{1, {0.5, 0.6}, 0.2}});
  const OccupancyGrid grid = Exported(world);
  EXPECT_DOUBLE_EQ(grid.origin.x(), -0.5);
  EXPECT_DOUBLE_EQ(grid.origin.y(), -0.5);
  EXPECT_EQ(grid.At(grid.CellOf({0.5, 0.01}).x(), grid.CellOf({0.5, 0.01}).y()),
            OccupancyGrid::kOccupied);
  EXPECT_EQ(grid.At(grid.CellOf({0.5, -0.01}).x(), grid.CellOf({0.5, -0.01}).y()),
            OccupancyGrid::kOccupied);
  EXPECT_EQ(grid.At(grid.CellOf({0.5, 0.06}).x(), grid.CellOf({0.5, 0.06}).y()),
            OccupancyGrid::kFree);
  EXPECT_EQ(grid.At(grid.CellOf({0.5, 0.6}).x(), grid.CellOf({0.5, 0.6}).y()),
            OccupancyGrid::kUnknown);
  EXPECT_EQ(grid.At(grid.CellOf({0.5, 0.81}).x(), grid.CellOf({0.5, 0.81}).y()),
            OccupancyGrid::kOccupied);
  map_building::RasteriseOptions tiny;
  tiny.resolution_m = 1e-5;
  EXPECT_THROW(map_building::RasteriseWorld(world, tiny), std::invalid_argument);
}

}  // namespace
}  // namespace structloc
