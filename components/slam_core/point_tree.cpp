// k-d tree for the scan matcher's nearest-point queries (see header).
#include "structloc/slam_core/point_tree.hpp"

#include <algorithm>
#include <numeric>

namespace structloc::slam_core {
namespace {

// Points a leaf holds: small enough that a leaf is scanned in a few
// comparisons, large enough that the tree stays shallow.
constexpr int kLeafPoints = 8;

}  // namespace

PointTree::PointTree(const std::vector<Eigen::Vector2d>& points) {
  ids_.resize(points.size());
  std::iota(ids_.begin(), ids_.end(), 0);
  points_ = points;
  if (!points.empty()) {
    nodes_.reserve(2 * points.size() / kLeafPoints + 1);
    Build(0, static_cast<int>(points.size()));
  }
  for (size_t k = 0; k < ids_.size(); ++k) points_[k] = points[ids_[k]];
}

int PointTree::Build(int begin, int end) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.push_back({begin, end});
  if (end - begin <= kLeafPoints) return index;
  Eigen::Vector2d low = points_[ids_[begin]], high = low;
  for (int k = begin + 1; k < end; ++k) {
    low = low.cwiseMin(points_[ids_[k]]);
    high = high.cwiseMax(points_[ids_[k]]);
  }
  // Split the wider extent at its median point.
  const int axis = (high.x() - low.x()) >= (high.y() - low.y()) ? 0 : 1;
  const int middle = begin + (end - begin) / 2;
  std::nth_element(ids_.begin() + begin, ids_.begin() + middle, ids_.begin() + end,
                   [&](int a, int b) { return points_[a](axis) < points_[b](axis); });
  const double split = points_[ids_[middle]](axis);
  const int left = Build(begin, middle);
  const int right = Build(middle, end);
  nodes_[index].axis = axis;
  nodes_[index].split = split;
  nodes_[index].left = left;
  nodes_[index].right = right;
  return index;
}

}  // namespace structloc::slam_core
