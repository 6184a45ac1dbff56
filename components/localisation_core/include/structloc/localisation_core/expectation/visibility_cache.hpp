// Which map features the sensor can see (thesis 3.5.3), computed ahead and
// kept for the places the robot passes, so that the position update looks it
// up instead of ray casting against the map: on a real building a visibility
// takes 1-2 ms, the rest of an update some tens of microseconds. A
// visibility holds for a sensor within refresh_distance_m of where it was
// computed (and, short of a full-circle view, within refresh_angle_rad of its
// heading), as a visibility refreshed after that much travel always did. The
// localiser computes one between scans (Localiser::Anticipate) where the
// next scan is due and none holds, and an update without one uses the newest. Entries keep only
// what is seen (their lists grow to the most seen from one place, then stay) and are replaced least
// recently used first; a lookup allocates nothing. DDS-free.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "structloc/geometry/pose2d.hpp"
#include "structloc/world_model/visibility.hpp"
#include "structloc/world_model/world_model.hpp"

namespace structloc::localisation_core {

class VisibilityCache {
 public:
  // `reach_m` and `reach_rad` positive; `capacity` at least 2 entries.
  // Throws std::invalid_argument otherwise.
  VisibilityCache(const world_model::WorldModel& world, const world_model::Scene& scene,
                  double reach_m, double reach_rad, size_t capacity);

  // The view (range limits, field of view) the entries are for; another view
  // empties the cache (then true).
  bool SetView(const world_model::VisibilityOptions& view);
  const std::optional<world_model::VisibilityOptions>& View() const { return view_; }

  // Whether the visibility of `entry` holds for a sensor at `sensor`.
  bool Holds(int entry, const geometry::Pose2D& sensor) const;
  // The entry computed nearest to `sensor` of those that hold there, or -1.
  int Find(const geometry::Pose2D& sensor);
  // Computes the visibility at `sensor` (a view must be set), replacing the
  // least recently used entry other than `keep`; returns its index.
  int Compute(const geometry::Pose2D& sensor, int keep = -1);
  // The entry computed last, or -1.
  int Newest() const { return newest_; }
  const world_model::Visibility& At(int entry) const {
    return entries_[static_cast<size_t>(entry)].visibility;
  }
  uint64_t Computations() const { return computations_; }

 private:
  struct Entry {
    geometry::Pose2D pose;  // where it was computed
    bool valid = false;
    uint64_t used = 0;  // the last use's tick
    world_model::Visibility visibility;
  };
  bool FullCircle() const;

  const world_model::WorldModel& world_;
  const world_model::Scene& scene_;
  double reach_m_;
  double reach_rad_;
  std::optional<world_model::VisibilityOptions> view_;
  std::vector<Entry> entries_;
  world_model::Visibility workspace_;  // ComputeVisibility's, sized for the whole map
  uint64_t tick_ = 0;
  uint64_t computations_ = 0;
  int newest_ = -1;
};

}  // namespace structloc::localisation_core
