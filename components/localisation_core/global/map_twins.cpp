// The motions that carry a map onto itself (see header).
#include "structloc/localisation_core/global/map_twins.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "structloc/world_model/outline_points.hpp"

namespace structloc::localisation_core {
namespace {

// The map's outline as points every `step` metres, spread over the map so
// that a motion that misses shows it early.
std::vector<Eigen::Vector2d> Outline(const world_model::WorldModel& world, double step) {
  const auto samples = world_model::OutlinePoints(world, step, 4);
  std::vector<Eigen::Vector2d> spread(samples.size());
  size_t stride = 7919;
  while (!samples.empty() && std::gcd(stride, samples.size()) != 1) stride += 2;
  for (size_t i = 0; i < samples.size(); ++i) spread[i] = samples[(i * stride) % samples.size()];
  return spread;
}

// The share of the outline `motion` carries onto it; stops early (returning
// less than `needed`) once that share can no longer be reached.
double Overlap(const std::vector<Eigen::Vector2d>& outline, const geometry::Pose2D& motion,
               const GlobalLocaliser& localiser, const MapTwinOptions& options) {
  const double n = static_cast<double>(outline.size());
  const double misses_allowed = (1.0 - options.min_overlap) * n;
  double misses = 0.0;
  for (const auto& p : outline) {
    if (localiser.SurfaceGain(motion.Apply(p)) >= options.on_outline_gain) continue;
    if (++misses > misses_allowed) return 0.0;
  }
  return 1.0 - misses / n;
}

// The motions carrying wall `from` onto wall `to`, end to end either way round.
std::vector<geometry::Pose2D> Motions(const world_model::Wall& from, const world_model::Wall& to) {
  std::vector<geometry::Pose2D> motions;
  const Eigen::Vector2d d = from.b - from.a, mid = 0.5 * (from.a + from.b);
  const Eigen::Vector2d target_mid = 0.5 * (to.a + to.b);
  const double turn =
      std::atan2(to.b.y() - to.a.y(), to.b.x() - to.a.x()) - std::atan2(d.y(), d.x());
  for (const double theta : {turn, turn + geometry::kPi}) {
    geometry::Pose2D m{0.0, 0.0, geometry::WrapAngle(theta)};
    const Eigen::Vector2d shift = target_mid - m.Apply(mid);
    motions.push_back({shift.x(), shift.y(), m.theta});
  }
  return motions;
}

// Two motions found from different walls that are one.
constexpr double kSameMotionM = 0.2;
constexpr double kSameMotionRad = 2.0 * geometry::kPi / 180.0;

}  // namespace

void CheckMapTwinOptions(const MapTwinOptions& o) {
  auto require = [](bool ok, const char* name, const char* range) {
    if (!ok)
      throw std::invalid_argument(std::string("map twin options: ") + name + " must be " + range);
  };
  require(o.min_overlap > 0.5 && o.min_overlap <= 1.0, "min_overlap", "in (0.5, 1]");
  require(o.sample_step_m >= 0.01 && o.sample_step_m <= 10.0, "sample_step_m", "in [0.01, 10]");
  require(o.longest_walls >= 0 && o.longest_walls <= 1000, "longest_walls", "in [0, 1000]");
  require(o.min_wall_m >= 0.0, "min_wall_m", "at least 0");
  require(o.length_tolerance_m >= 0.0, "length_tolerance_m", "at least 0");
  require(o.on_outline_gain > 0.0 && o.on_outline_gain <= 1.0, "on_outline_gain", "in (0, 1]");
  require(o.allowance_points >= 0.0 && o.allowance_points <= 100.0, "allowance_points",
          "in [0, 100]");
}

std::vector<geometry::Pose2D> FindMapTwins(const world_model::WorldModel& world,
                                           const GlobalLocaliser& localiser,
                                           const MapTwinOptions& options) {
  CheckMapTwinOptions(options);
  std::vector<const world_model::Wall*> longest;
  for (const auto& wall : world.Walls())
    if (wall.Length() >= options.min_wall_m) longest.push_back(&wall);
  std::stable_sort(longest.begin(), longest.end(),
                   [](const auto* a, const auto* b) { return a->Length() > b->Length(); });
  if (longest.size() > static_cast<size_t>(options.longest_walls))
    longest.resize(static_cast<size_t>(options.longest_walls));
  const auto outline = Outline(world, options.sample_step_m);
  struct Twin {
    geometry::Pose2D motion;
    double overlap;
  };
  std::vector<Twin> twins;
  auto same = [](const geometry::Pose2D& a, const geometry::Pose2D& b) {
    return std::hypot(a.x - b.x, a.y - b.y) < kSameMotionM &&
           std::abs(geometry::WrapAngle(a.theta - b.theta)) < kSameMotionRad;
  };
  for (const auto* from : longest) {
    for (const auto* to : longest) {
      if (std::abs(from->Length() - to->Length()) > options.length_tolerance_m) continue;
      for (const auto& motion : Motions(*from, *to)) {
        if (!Distinct(geometry::Pose2D{}, motion, localiser.Options())) continue;  // the identity
        if (std::any_of(twins.begin(), twins.end(),
                        [&](const Twin& t) { return same(t.motion, motion); }))
          continue;
        const double overlap = Overlap(outline, motion, localiser, options);
        if (overlap >= options.min_overlap) twins.push_back({motion, overlap});
      }
    }
  }
  std::stable_sort(twins.begin(), twins.end(),
                   [](const Twin& a, const Twin& b) { return a.overlap > b.overlap; });
  std::vector<geometry::Pose2D> motions;
  for (const auto& t : twins) motions.push_back(t.motion);
  return motions;
}

}  // namespace structloc::localisation_core
