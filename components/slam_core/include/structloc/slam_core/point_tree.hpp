// The nearest of a fixed set of 2-D points to a query, within a distance: a
// k-d tree (Bentley 1975), built once per scan-matching reference. The ICP
// asks this for every scan point in every iteration, first within a metre:
// a grid of cells as wide as the normal radius made each query visit up to
// 81 cells and hundreds of points in a dense submap (a 0.25 deg laser puts
// ~30 points on each quarter metre of a wall at 2 m, per keyframe); the tree
// visits a few dozen. The answer is exact. DDS-free.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <vector>

namespace structloc::slam_core {

class PointTree {
 public:
  PointTree() = default;  // of no points
  explicit PointTree(const std::vector<Eigen::Vector2d>& points);
  // The index (into the points given) of the point nearest to `p` within
  // `max_distance_m`, a point at exactly that distance included; of points
  // equally near, the one of the lowest index; -1 when there is none.
  int Nearest(const Eigen::Vector2d& p, double max_distance_m) const {
    return Nearest(p, max_distance_m, [](int) { return true; });
  }
  // The same among the points `accept(index)` takes; it is asked only of a
  // point that would be the nearest so far, so an expensive test (whether a
  // point lies on a surface) runs for few points. Of points equally near,
  // the one `prefer(a, b)` puts first (true: a before b).
  template <class Accept, class Prefer = std::less<int>>
  int Nearest(const Eigen::Vector2d& p, double max_distance_m, Accept accept,
              Prefer prefer = {}) const {
    Query<Accept, Prefer> query{p, accept, prefer, max_distance_m * max_distance_m, -1};
    if (!nodes_.empty()) Search(0, query);
    return query.best;
  }

 private:
  struct Node {
    int begin = 0, end = 0;     // the node's points: [begin, end) of points_
    int left = -1, right = -1;  // children (-1: a leaf)
    int axis = 0;               // 0: x, 1: y
    double split = 0.0;         // left holds coordinates <= split, right >=
  };
  int Build(int begin, int end);
  // One search's question and its best answer so far, passed down as one
  // reference (the recursion stays light).
  template <class Accept, class Prefer>
  struct Query {
    const Eigen::Vector2d& p;
    Accept& accept;
    Prefer& prefer;
    double best_d2;
    int best;
  };
  template <class Q>
  void Search(int index, Q& q) const {
    const Node& node = nodes_[index];
    if (node.left < 0) {
      for (int k = node.begin; k < node.end; ++k) {
        const double d2 = (points_[k] - q.p).squaredNorm();
        const bool nearer =
            d2 < q.best_d2 || (d2 == q.best_d2 && (q.best < 0 || q.prefer(ids_[k], q.best)));
        if (nearer && q.accept(ids_[k])) {
          q.best_d2 = d2;
          q.best = ids_[k];
        }
      }
      return;
    }
    // The side of the split holding `p` first; the other only if a point
    // there can be as near as the best so far (ties kept for `prefer`).
    const double across = q.p(node.axis) - node.split;
    Search(across < 0 ? node.left : node.right, q);
    if (across * across <= q.best_d2) Search(across < 0 ? node.right : node.left, q);
  }

  std::vector<Eigen::Vector2d> points_;  // in the tree's order
  std::vector<int> ids_;                 // each one's index in the points given
  std::vector<Node> nodes_;
};

}  // namespace structloc::slam_core
