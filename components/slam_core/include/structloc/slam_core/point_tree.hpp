// The nearest of a fixed set of 2-D points to a query, within a distance: a
// k-d tree (Bentley 1975), built once per scan-matching reference. The ICP
// asks this for every scan point in every iteration, first within a metre:
// a grid of cells as wide as the normal radius made each query visit up to
// 81 cells and hundreds of points in a dense submap (a 0.25 deg laser puts
// ~30 points on each quarter metre of a wall at 2 m, per keyframe); the tree
// visits a few dozen. The answer is exact. DDS-free.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace structloc::slam_core {

class PointTree {
 public:
  PointTree() = default;  // of no points
  explicit PointTree(const std::vector<Eigen::Vector2d>& points);
  // The index (into the points given) of the point nearest to `p` within
  // `max_distance_m`, a point at exactly that distance included; of points
  // equally near, the one of the lowest index; -1 when there is none.
  int Nearest(const Eigen::Vector2d& p, double max_distance_m) const;

 private:
  struct Node {
    int begin = 0, end = 0;     // the node's points: [begin, end) of points_
    int left = -1, right = -1;  // children (-1: a leaf)
    int axis = 0;               // 0: x, 1: y
    double split = 0.0;         // left holds coordinates <= split, right >=
  };
  int Build(int begin, int end);
  void Search(int node, const Eigen::Vector2d& p, double* best_d2, int* best) const;

  std::vector<Eigen::Vector2d> points_;  // in the tree's order
  std::vector<int> ids_;                 // each one's index in the points given
  std::vector<Node> nodes_;
};

}  // namespace structloc::slam_core
