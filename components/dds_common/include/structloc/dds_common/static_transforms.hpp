// The robot's static transforms as heard on rt/tf_static, and the laser's
// mounting from them: a robot description may place the laser through frames
// between (base_link -> laser_mount -> laser), so the mounting is the
// composition of the chain from the base frame down to the laser's frame, in
// the plane. The localisation component and `structloc record` read the
// mounting this one way.
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <string>

#include "geometry_msgs/msg/TransformStamped.h"
#include "structloc/geometry/pose2d.hpp"
#include "tf2_msgs/msg/TFMessage.h"

namespace structloc::dds_common {

class StaticTransforms {
 public:
  // A robot description has tens of frames, a large one hundreds; a peer
  // sending ever new frames must not grow this without bound.
  static constexpr size_t kMaxFrames = 4096;

  // Keeps every transform of `m`, the newest per child frame; transforms to
  // frames beyond the first kMaxFrames are dropped (and counted).
  void Add(const tf2_msgs::msg::TFMessage& m);
  size_t Frames() const { return by_child_.size(); }
  size_t Dropped() const { return dropped_; }
  // The pose of `child_frame` in `base_frame` (x, y, yaw), composed from the
  // transforms heard; `path` receives "base_link -> laser_mount -> laser".
  // nullopt while the chain is incomplete, loops or holds a non-finite
  // transform, and when the two frames are the same.
  std::optional<geometry::Pose2D> Chain(const std::string& base_frame,
                                        const std::string& child_frame, std::string& path) const;

 private:
  std::map<std::string, geometry_msgs::msg::TransformStamped> by_child_;
  size_t dropped_ = 0;
};

}  // namespace structloc::dds_common
