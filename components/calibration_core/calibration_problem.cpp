// The calibration's batch least-squares problem (see header).
#include "structloc/calibration_core/calibration_problem.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <optional>

#include "structloc/kinematics/tricycle.hpp"

namespace structloc::calibration_core {

kinematics::RobotParameters WithValues(const kinematics::RobotParameters& base,
                                       const ParameterValues& values) {
  kinematics::RobotParameters p = base;
  p.wheel_radius = values[kWheelRadius];
  p.axle_distance = values[kAxleDistance];
  p.steering_offset = values[kSteeringOffset];
  p.steering_rad_per_tick = values[kSteeringGain];
  p.sensor = {values[kSensorX], values[kSensorY], values[kSensorTheta]};
  p.left_wheel_radius = values[kLeftWheelRadius];
  p.right_wheel_radius = values[kRightWheelRadius];
  p.wheel_separation = values[kWheelSeparation];
  return p;
}

ParameterValues ValuesOf(const kinematics::RobotParameters& p) {
  return {p.wheel_radius,       p.axle_distance,   p.steering_offset, p.steering_rad_per_tick,
          p.sensor.x,           p.sensor.y,        p.sensor.theta,    p.left_wheel_radius,
          p.right_wheel_radius, p.wheel_separation};
}

namespace {

// Central-difference steps of the parameter Jacobian, in each parameter's unit.
constexpr ParameterValues kParameterStep{1e-6, 1e-5, 1e-6, 1e-9, 1e-5,
                                         1e-5, 1e-6, 1e-6, 1e-6, 1e-5};

Eigen::Matrix3d UpperCholeskyOfInverse(const Eigen::Matrix3d& covariance) {
  return Eigen::LLT<Eigen::Matrix3d>(covariance.inverse()).matrixU();
}

// Measured (state) minus predicted relative motion from pose a to pose b, in a's frame.
Eigen::Vector3d MotionError(const geometry::Pose2D& a, const geometry::Pose2D& b,
                            const geometry::Pose2D& predicted) {
  const geometry::Pose2D rel = geometry::Between(a, b);
  return {rel.x - predicted.x, rel.y - predicted.y,
          geometry::WrapAngle(rel.theta - predicted.theta)};
}

// Fix minus the fix sensor's pose for the base pose `base`.
Eigen::Vector3d FixError(const Fix& fix, const geometry::Pose2D& base,
                         const geometry::Pose2D& sensor) {
  const geometry::Pose2D h = geometry::Compose(base, sensor);
  return {fix.pose.x - h.x, fix.pose.y - h.y, geometry::WrapAngle(fix.pose.theta - h.theta)};
}

void AddBlock(std::vector<Eigen::Triplet<double>>& triplets, Eigen::Index row, Eigen::Index col,
              const Eigen::Matrix3d& block) {
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) triplets.emplace_back(row + r, col + c, block(r, c));
  }
}

}  // namespace

CalibrationProblem::CalibrationProblem(const std::vector<EncoderSample>& encoders,
                                       const std::vector<Fix>& fixes,
                                       const kinematics::RobotParameters& nominal,
                                       const CalibrationOptions& options, ProblemScope scope)
    : nominal_(nominal), options_(options) {
  // Unwrapped cumulative ticks at every sample: of the traction wheel, or of
  // the left (first) and right (second) wheels.
  const bool differential = nominal.kind == kinematics::DriveKind::kDifferential;
  std::vector<double> cumulative(encoders.size(), 0.0), right(encoders.size(), 0.0);
  for (size_t k = 1; k < encoders.size(); ++k) {
    const EncoderSample &a = encoders[k - 1], &b = encoders[k];
    cumulative[k] =
        cumulative[k - 1] +
        static_cast<double>(differential ? nominal.TickDelta(a.left_ticks, b.left_ticks)
                                         : nominal.TickDelta(a.traction_ticks, b.traction_ticks));
    if (differential) {
      right[k] =
          right[k - 1] + static_cast<double>(nominal.TickDelta(a.right_ticks, b.right_ticks));
    }
    if (encoders[k].t - encoders[k - 1].t > options.max_encoder_gap_s) ++encoder_gaps_;
  }
  auto locate = [&](double t) -> std::optional<size_t> {  // index k with t_k <= t < t_{k+1}
    if (t < encoders.front().t || t >= encoders.back().t) return std::nullopt;
    const auto it = std::upper_bound(encoders.begin(), encoders.end(), t,
                                     [](double v, const EncoderSample& s) { return v < s.t; });
    return static_cast<size_t>(it - encoders.begin()) - 1;
  };
  auto at = [&](const std::vector<double>& ticks, size_t k, double t) {
    const double f = (t - encoders[k].t) / (encoders[k + 1].t - encoders[k].t);
    return ticks[k] + f * (ticks[k + 1] - ticks[k]);
  };
  // The second value of a step: the steering reading, or the right wheel's ticks.
  auto second = [&](size_t k, double previous_right) {
    return differential ? right[k] - previous_right : encoders[k].steering_ticks;
  };
  std::vector<size_t> index;
  const bool relative = scope == ProblemScope::kRelativeMotion;
  for (const Fix& fix : fixes) {
    const auto k = locate(fix.t);
    if (!k) continue;
    if (relative && !fixes_.empty()) {
      const geometry::Pose2D step = geometry::Between(fixes_.back().pose, fix.pose);
      if (step.Translation().norm() < options.min_fix_travel_m &&
          std::abs(step.theta) < options.min_fix_turn_rad)
        continue;
    }
    fixes_.push_back(fix);
    fix_whitening_.push_back(FixVariance(fix).cwiseInverse().cwiseSqrt().asDiagonal());
    index.push_back(*k);
  }
  for (size_t i = 0; i + 1 < fixes_.size(); ++i) {
    const size_t ki = index[i], kj = index[i + 1];
    bool ok = true;
    for (size_t k = ki; ok && k <= kj; ++k) {
      ok = encoders[k + 1].t - encoders[k].t <= options.max_encoder_gap_s;
    }
    if (!ok) {
      ++intervals_skipped_;
      continue;
    }
    Link link;
    link.from = i;
    double previous = at(cumulative, ki, fixes_[i].t);
    double previous_right = at(right, ki, fixes_[i].t);
    for (size_t k = ki + 1; k <= kj; ++k) {
      link.steps.emplace_back(cumulative[k] - previous, second(k, previous_right));
      previous = cumulative[k];
      previous_right = right[k];
    }
    const double end_right = at(right, kj, fixes_[i + 1].t);
    link.steps.emplace_back(
        at(cumulative, kj, fixes_[i + 1].t) - previous,
        differential ? end_right - previous_right : encoders[kj + 1].steering_ticks);
    Eigen::Matrix3d covariance;
    Predict(link, nominal_, &covariance);
    if (relative) {  // both fixes' noise, in the first fix's frame
      const Eigen::Vector3d v = FixVariance(fixes_[i]) + FixVariance(fixes_[i + 1]);
      const double c = std::cos(fixes_[i].pose.theta), s = std::sin(fixes_[i].pose.theta);
      Eigen::Matrix2d rotation;
      rotation << c, s, -s, c;
      covariance.topLeftCorner<2, 2>() +=
          rotation * v.head<2>().asDiagonal() * rotation.transpose();
      covariance(2, 2) += v.z();
    }
    link.whitening = UpperCholeskyOfInverse(covariance);
    links_.push_back(std::move(link));
  }
}

Eigen::Vector3d CalibrationProblem::FixVariance(const Fix& fix) const {
  const double sxy2 = options_.default_sigma_xy_m * options_.default_sigma_xy_m;
  const double st2 = options_.default_sigma_theta_rad * options_.default_sigma_theta_rad;
  const Eigen::Vector3d v = fix.has_variance ? fix.variance : Eigen::Vector3d(sxy2, sxy2, st2);
  return v.array() + 1e-18;
}

geometry::Pose2D CalibrationProblem::Predict(const Link& link, const kinematics::RobotParameters& p,
                                             Eigen::Matrix3d* covariance) const {
  geometry::Pose2D pose;
  const double rad_per_tick = 2.0 * geometry::kPi / p.traction_ticks_per_rev;
  const bool differential = p.kind == kinematics::DriveKind::kDifferential;
  Eigen::Matrix3d sigma = Eigen::Matrix3d::Zero();
  for (const auto& [first, second] : link.steps) {
    // Tricycle: traction ticks and steering reading; differential: left and right ticks.
    const double left = first * rad_per_tick * p.left_wheel_radius;
    const double right = second * rad_per_tick * p.right_wheel_radius;
    const geometry::Pose2D next =
        differential ? kinematics::AdvanceDifferential(pose, left, right, p.wheel_separation)
                     : kinematics::Advance(pose, first * rad_per_tick, p.SteeringAngle(second),
                                           p.wheel_radius, p.axle_distance);
    if (covariance != nullptr) {
      // Step noise in the step's own frame: slip scales the whole arc, heading
      // noise turns it; both variances grow with the wheels' path length.
      const double path = differential ? 0.5 * (std::abs(left) + std::abs(right))
                                       : std::abs(first * rad_per_tick * p.wheel_radius);
      const geometry::Pose2D u = geometry::Between(pose, next);
      const Eigen::Vector3d arc(u.x, u.y, u.theta);
      Eigen::Matrix3d step = Eigen::Matrix3d::Zero();
      if (path > 1e-12) step += (options_.slip_variance_m2_per_m / path) * arc * arc.transpose();
      step(2, 2) += options_.heading_variance_rad2_per_m * path;
      const double c = std::cos(pose.theta), s = std::sin(pose.theta);
      Eigen::Matrix3d f = Eigen::Matrix3d::Identity();
      f(0, 2) = -s * u.x - c * u.y;
      f(1, 2) = c * u.x - s * u.y;
      Eigen::Matrix3d g = Eigen::Matrix3d::Identity();
      g.topLeftCorner<2, 2>() << c, -s, s, c;
      sigma = f * sigma * f.transpose() + g * step * g.transpose();
    }
    pose = next;
  }
  if (covariance != nullptr) {
    // The tick quantisation at the link's ends is left out: it does not
    // accumulate (each end's error is shared with the neighbouring link with
    // the opposite sign), so as white noise per link it would overstate the
    // long-baseline uncertainty. A floor keeps a standing robot's constraint finite.
    sigma.diagonal().array() += 1e-12;
    *covariance = 0.5 * (sigma + sigma.transpose());
  }
  return pose;
}

CalibrationState CalibrationProblem::Initial() const {
  return AtFixes(ValuesOf(nominal_));
}

CalibrationState CalibrationProblem::AtFixes(const ParameterValues& values) const {
  CalibrationState state;
  state.values = values;
  const geometry::Pose2D to_base = geometry::Inverse(WithValues(nominal_, values).sensor);
  for (const Fix& fix : fixes_) state.poses.push_back(geometry::Compose(fix.pose, to_base));
  return state;
}

Eigen::VectorXd CalibrationProblem::Whitened(const CalibrationState& state) const {
  const auto p = WithValues(nominal_, state.values);
  Eigen::VectorXd r(static_cast<Eigen::Index>(3 * (fixes_.size() + links_.size())));
  for (size_t i = 0; i < fixes_.size(); ++i) {
    r.segment<3>(static_cast<Eigen::Index>(3 * i)) =
        fix_whitening_[i] * FixError(fixes_[i], state.poses[i], p.sensor);
  }
  const Eigen::Index base = static_cast<Eigen::Index>(3 * fixes_.size());
  for (size_t k = 0; k < links_.size(); ++k) {
    const Link& link = links_[k];
    const geometry::Pose2D predicted = Predict(link, p, nullptr);
    r.segment<3>(base + static_cast<Eigen::Index>(3 * k)) =
        link.whitening * MotionError(state.poses[link.from], state.poses[link.from + 1], predicted);
  }
  return r;
}

Eigen::SparseMatrix<double> CalibrationProblem::Jacobian(const CalibrationState& state,
                                                         const std::vector<size_t>& active) const {
  const auto p = WithValues(nominal_, state.values);
  const Eigen::Index rows = static_cast<Eigen::Index>(3 * (fixes_.size() + links_.size()));
  const Eigen::Index pose_columns = static_cast<Eigen::Index>(3 * fixes_.size());
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<size_t>(rows) * (6 + active.size()));
  for (size_t i = 0; i < fixes_.size(); ++i) {
    const geometry::Pose2D& x = state.poses[i];
    const double c = std::cos(x.theta), s = std::sin(x.theta);
    Eigen::Matrix3d d = -Eigen::Matrix3d::Identity();  // d FixError / d base pose
    d(0, 2) = s * p.sensor.x + c * p.sensor.y;
    d(1, 2) = -c * p.sensor.x + s * p.sensor.y;
    const Eigen::Index row = static_cast<Eigen::Index>(3 * i);
    AddBlock(triplets, row, row, fix_whitening_[i] * d);
  }
  for (size_t k = 0; k < links_.size(); ++k) {
    const Link& link = links_[k];
    const geometry::Pose2D& a = state.poses[link.from];
    const geometry::Pose2D& b = state.poses[link.from + 1];
    const double c = std::cos(a.theta), s = std::sin(a.theta);
    const double dx = b.x - a.x, dy = b.y - a.y;
    Eigen::Matrix3d da = Eigen::Matrix3d::Zero(), db = Eigen::Matrix3d::Zero();
    da << -c, -s, -s * dx + c * dy,  //
        s, -c, -c * dx - s * dy,     //
        0, 0, -1;
    db << c, s, 0,  //
        -s, c, 0,   //
        0, 0, 1;
    const Eigen::Index row = pose_columns + static_cast<Eigen::Index>(3 * k);
    AddBlock(triplets, row, static_cast<Eigen::Index>(3 * link.from), link.whitening * da);
    AddBlock(triplets, row, static_cast<Eigen::Index>(3 * (link.from + 1)), link.whitening * db);
  }
  // Parameter columns by central differences (the poses held).
  for (size_t c = 0; c < active.size(); ++c) {
    CalibrationState plus = state, minus = state;
    const double h = kParameterStep[active[c]];
    plus.values[active[c]] += h;
    minus.values[active[c]] -= h;
    const Eigen::VectorXd column = (Whitened(plus) - Whitened(minus)) / (2 * h);
    // The fixes depend on the sensor mounting only; every entry that can be
    // non-zero is stored, even when it is 0 here, so the pattern never changes.
    const bool mounting =
        active[c] == kSensorX || active[c] == kSensorY || active[c] == kSensorTheta;
    for (Eigen::Index r = mounting ? 0 : pose_columns; r < rows; ++r) {
      triplets.emplace_back(r, pose_columns + static_cast<Eigen::Index>(c), column(r));
    }
  }
  Eigen::SparseMatrix<double> j(rows, pose_columns + static_cast<Eigen::Index>(active.size()));
  j.setFromTriplets(triplets.begin(), triplets.end());
  return j;
}

CalibrationState CalibrationProblem::Moved(const CalibrationState& state,
                                           const Eigen::VectorXd& delta,
                                           const std::vector<size_t>& active) const {
  CalibrationState moved = state;
  for (size_t i = 0; i < moved.poses.size(); ++i) {
    const Eigen::Index k = static_cast<Eigen::Index>(3 * i);
    moved.poses[i] = {moved.poses[i].x + delta(k), moved.poses[i].y + delta(k + 1),
                      geometry::WrapAngle(moved.poses[i].theta + delta(k + 2))};
  }
  const Eigen::Index base = static_cast<Eigen::Index>(3 * moved.poses.size());
  for (size_t c = 0; c < active.size(); ++c) {
    moved.values[active[c]] += delta(base + static_cast<Eigen::Index>(c));
  }
  return moved;
}

}  // namespace structloc::calibration_core
