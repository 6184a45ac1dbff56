// The laser's mounting from static transforms (see header).
#include "structloc/dds_common/static_transforms.hpp"

#include <cmath>

#include "structloc/dds_common/ros_conversions.hpp"

namespace structloc::dds_common {
namespace {

// A planar transform with finite values, or nullopt.
std::optional<geometry::Pose2D> Planar(const geometry_msgs::msg::TransformStamped& t) {
  const geometry::Pose2D pose{t.transform().translation().x(), t.transform().translation().y(),
                              YawFromQuaternion(t.transform().rotation())};
  if (!geometry::IsFinite(pose)) return std::nullopt;
  return pose;
}

}  // namespace

void StaticTransforms::Add(const tf2_msgs::msg::TFMessage& m) {
  for (const auto& t : m.transforms()) {
    const auto known = by_child_.find(t.child_frame_id());
    if (known != by_child_.end()) {
      known->second = t;
    } else if (by_child_.size() < kMaxFrames) {
      by_child_.emplace(t.child_frame_id(), t);
    } else {
      ++dropped_;
    }
  }
}

std::optional<geometry::Pose2D> StaticTransforms::Chain(const std::string& base_frame,
                                                        const std::string& child_frame,
                                                        std::string& path) const {
  constexpr int kMaxChainDepth = 16;  // a longer chain is a loop
  geometry::Pose2D pose{0.0, 0.0, 0.0};
  std::string frame = child_frame;
  path = child_frame;
  for (int depth = 0; depth < kMaxChainDepth && frame != base_frame; ++depth) {
    const auto t = by_child_.find(frame);
    if (t == by_child_.end()) return std::nullopt;
    const auto step = Planar(t->second);
    if (!step) return std::nullopt;
    pose = geometry::Compose(*step, pose);
    frame = t->second.header().frame_id();
    path = frame + " -> " + path;
  }
  if (frame != base_frame || frame == child_frame) return std::nullopt;
  return pose;
}

}  // namespace structloc::dds_common
