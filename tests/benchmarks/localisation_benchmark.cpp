// Speed of the position update, measured with Google Benchmark: one benchmark
// per pipeline step and for the whole update, on the office floor seen from
// the hall (walls, corners and pillars all active), with per-update median and
// p99 as counters and the beam-count complexity fitted. Prints figures; it
// asserts nothing (speed goals live here, not in timed unit tests).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>

#include "office_scene.hpp"
#include "structloc/localisation_core/expectation/scan_visibility.hpp"
#include "structloc/localisation_core/features/corners/corner_extractor.hpp"
#include "structloc/localisation_core/features/cylinders/cylinder_extractor.hpp"
#include "structloc/localisation_core/features/walls/wall_extractor.hpp"

namespace structloc {
namespace {

using localisation_core::Localiser;

double FieldOfView(int beams) {
  return beams == 300 ? 2 * geometry::kPi : 1.5 * geometry::kPi;
}

// The weighted solver's (the default's) clusters: no thesis means.
constexpr auto kMeans = localisation_core::ClusterMeans::kSkip;

// Every intermediate of one update, prepared with the step functions.
struct Prepared {
  testing::OfficeScene office;
  testing::SyntheticScan scan;
  localisation_core::BeamDirections directions;
  localisation_core::ScanPoints points;
  std::vector<localisation_core::WindowLine> windows;
  localisation_core::ExpectedWalls expected;
  std::vector<localisation_core::ExpectedPoint> corners, cylinders;
  geometry::Pose2D sensor_prior;
  std::vector<int> assignment;
  localisation_core::WallClusterWork wall_work;
  std::vector<localisation_core::WallCluster> walls;

  explicit Prepared(int beams) : office(FieldOfView(beams)) {
    std::mt19937 rng(1);
    scan = office.Scan(beams, rng);
    const auto input = office.Input(scan);
    sensor_prior = geometry::Compose(input.odometry_pose, office.options.sensor_mount);
    directions.Update(scan.View());
    localisation_core::PrefilterStats stats;
    Prefilter(scan.View(), directions, office.options.prefilter, nullptr, points, stats);
    FitWindowLines(points, office.options.line_fit, windows);
    const auto lines = localisation_core::GroupCollinearWalls(office.world);
    std::vector<int> line_of(office.world.Walls().size());
    for (size_t l = 0; l < lines.size(); ++l) {
      for (int w : lines[l].walls) line_of[static_cast<size_t>(w)] = static_cast<int>(l);
    }
    const auto vo = localisation_core::ScanVisibility(office.options, scan.View());
    world_model::Visibility visibility;
    ComputeVisibility(office.world, office.scene, sensor_prior, vo, visibility);
    ComputeExpectedWalls(office.world, lines, line_of, visibility, sensor_prior, expected);
    const localisation_core::MapErrorMemory no_memory;  // every map error counted per scan
    for (int i : visibility.corners) {
      const auto& c = office.world.Corners()[static_cast<size_t>(i)];
      corners.push_back(ExpectPoint(i, c.id, c.position, 0.0, -1, sensor_prior, no_memory));
    }
    for (int i : visibility.cylinders) {
      const auto& c = office.world.Cylinders()[static_cast<size_t>(i)];
      cylinders.push_back(ExpectPoint(i, c.id, c.centre, c.radius, -1, sensor_prior, no_memory));
    }
    AssignWindowsByExpectation(windows, expected, sensor_prior, Eigen::Matrix3d::Identity(),
                               WallOptions().clusters, wall_work, assignment);
    BuildWallClusters(windows, assignment, points, office.options.line_fit.window_points, expected,
                      WallOptions().clusters, kMeans, wall_work, walls);
  }
  const localisation_core::WallKindOptions& WallOptions() const {
    return office.options.kinds.Get<localisation_core::WallKindOptions>();
  }
};

void BM_Prefilter(benchmark::State& state) {
  Prepared p(static_cast<int>(state.range(0)));
  localisation_core::ScanPoints points;
  points.Reserve(4096);
  for (auto _ : state) {
    localisation_core::PrefilterStats stats;
    Prefilter(p.scan.View(), p.directions, p.office.options.prefilter, nullptr, points, stats);
    benchmark::DoNotOptimize(points.x.data());
  }
}

void BM_LineFit(benchmark::State& state) {
  Prepared p(static_cast<int>(state.range(0)));
  std::vector<localisation_core::WindowLine> windows;
  windows.reserve(4096);
  for (auto _ : state) {
    FitWindowLines(p.points, p.office.options.line_fit, windows);
    benchmark::DoNotOptimize(windows.data());
  }
  // What the later stages work through: the points kept, their windows and
  // the windows that pass the rms check.
  state.counters["points"] = static_cast<double>(p.points.Size());
  state.counters["windows"] = static_cast<double>(windows.size());
  state.counters["valid"] = static_cast<double>(
      std::count_if(windows.begin(), windows.end(), [](const auto& w) { return w.valid; }));
}

void BM_WallClustering(benchmark::State& state) {
  Prepared p(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    AssignWindowsByExpectation(p.windows, p.expected, p.sensor_prior, Eigen::Matrix3d::Identity(),
                               p.WallOptions().clusters, p.wall_work, p.assignment);
    BuildWallClusters(p.windows, p.assignment, p.points, p.office.options.line_fit.window_points,
                      p.expected, p.WallOptions().clusters, kMeans, p.wall_work, p.walls);
    benchmark::DoNotOptimize(p.walls.data());
  }
}

// The thesis' rejected alternative, for comparison with BM_WallClustering.
void BM_WallClusteringKohonen(benchmark::State& state) {
  Prepared p(static_cast<int>(state.range(0)));
  std::mt19937 rng(1);
  for (auto _ : state) {
    AssignWindowsByKohonen(p.windows, p.expected, p.WallOptions().clusters, p.WallOptions().kohonen,
                           rng, p.assignment);
    BuildWallClusters(p.windows, p.assignment, p.points, p.office.options.line_fit.window_points,
                      p.expected, p.WallOptions().clusters, kMeans, p.wall_work, p.walls);
    benchmark::DoNotOptimize(p.walls.data());
  }
}

void BM_Corners(benchmark::State& state) {
  Prepared p(static_cast<int>(state.range(0)));
  localisation_core::CornerWork work;
  std::vector<localisation_core::PointCluster> out;
  work.Reserve(4096, 64);
  out.reserve(64);
  for (auto _ : state) {
    ExtractCorners(p.windows, p.points.wraps, p.corners,
                   p.office.options.kinds.Get<localisation_core::CornerKindOptions>().extraction,
                   p.office.options.line_fit.window_points, work, out);
    benchmark::DoNotOptimize(out.data());
  }
}

void BM_Cylinders(benchmark::State& state) {
  Prepared p(static_cast<int>(state.range(0)));
  localisation_core::CylinderWork work;
  work.Reserve(4096, 64);
  std::vector<localisation_core::PointCluster> out;
  out.reserve(64);
  for (auto _ : state) {
    ExtractCylinders(
        p.windows, p.points, p.cylinders,
        p.office.options.kinds.Get<localisation_core::CylinderKindOptions>().extraction,
        p.office.options.line_fit.window_points, work, out);
    benchmark::DoNotOptimize(out.data());
  }
}

// The whole update, each call timed on its own for median and p99.
void BM_Update(benchmark::State& state) {
  const int beams = static_cast<int>(state.range(0));
  testing::OfficeScene office(FieldOfView(beams));
  Localiser localiser(office.world, office.options);
  std::mt19937 rng(2);
  std::vector<testing::SyntheticScan> scans;
  for (int i = 0; i < 16; ++i) scans.push_back(office.Scan(beams, rng));
  std::vector<localisation_core::UpdateInput> inputs;
  for (const auto& s : scans) inputs.push_back(office.Input(s));
  std::vector<double> times;
  times.reserve(1 << 20);
  size_t i = 0;
  double solve_us = 0.0, expectation_us = 0.0, features_us = 0.0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto& r = localiser.Update(inputs[i++ % inputs.size()]);
    const auto t1 = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(r.pose);
    solve_us += r.times.solve_us;
    expectation_us += r.times.expectation_us;
    for (const auto& kind : r.features) features_us += kind.extract_us;
    if (times.size() < times.capacity()) {
      times.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
    }
  }
  std::sort(times.begin(), times.end());
  state.counters["median_us"] = times[times.size() / 2];
  state.counters["p99_us"] = times[std::min(times.size() - 1, times.size() * 99 / 100)];
  // Means of the update's own stage timings (the rest: prefilter and line fit).
  const double updates = static_cast<double>(state.iterations());
  state.counters["solve_us"] = solve_us / updates;
  state.counters["expectation_us"] = expectation_us / updates;
  state.counters["features_us"] = features_us / updates;
  state.SetComplexityN(beams);
}

BENCHMARK(BM_Prefilter)->Arg(300)->Arg(1081);
BENCHMARK(BM_LineFit)->Arg(300)->Arg(1081);
BENCHMARK(BM_WallClustering)->Arg(300)->Arg(1081);
BENCHMARK(BM_WallClusteringKohonen)->Arg(300)->Arg(1081);
BENCHMARK(BM_Corners)->Arg(300)->Arg(1081);
BENCHMARK(BM_Cylinders)->Arg(300)->Arg(1081);
BENCHMARK(BM_Update)->Arg(300)->Arg(1081);
// Time against beam count (270 deg scans): Google Benchmark fits the complexity.
void BM_UpdateScaling(benchmark::State& state) {
  BM_Update(state);
}
BENCHMARK(BM_UpdateScaling)->Arg(541)->Arg(1081)->Arg(2161)->Arg(4001)->Complexity();

}  // namespace
}  // namespace structloc

BENCHMARK_MAIN();
