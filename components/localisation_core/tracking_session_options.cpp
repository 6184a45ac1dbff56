// Tracking-session options: validation and XML loading (see header).
#include "tracking_session_options.hpp"

#include <stdexcept>

#include "strict_xml.hpp"

namespace structloc::localisation {

void SessionOptions::Validate() const {
  tracker.Validate();
  if (!(state_period_s > 0)) throw std::invalid_argument("tracking: state_period_s must be > 0");
  if (!(lost_error_after_s >= 0)) {
    throw std::invalid_argument("tracking: lost_error_after_s must be >= 0");
  }
  if (max_pending_scans < 1)
    throw std::invalid_argument("tracking: max_pending_scans must be >= 1");
}

SessionOptions LoadSessionOptions(const std::string& path) {
  const auto file = config::XmlFile::Load(path);
  const auto& root = file.Root("localisation_params");
  const auto* e = root.FirstChildElement("tracking");
  if (e == nullptr) {
    file.Fail(root,
              "missing section <tracking> (the pose tracker's and the session's options, see "
              "maps/params/office_sick.xml)");
  }
  if (const auto* second = e->NextSiblingElement("tracking")) {
    file.Fail(*second, "a second <tracking> section; write each section once");
  }
  config::AttributeReader a(file, *e);
  SessionOptions o;
  auto& t = o.tracker;
  t.odometry_wait_s = a.Double("odometry_wait_s");
  t.max_extrapolation_s = a.Double("max_extrapolation_s");
  t.max_future_s = a.Double("max_future_s");
  t.max_odometry_speed_m_s = a.Double("max_odometry_speed_m_s");
  t.max_odometry_turn_rate_rad_s = a.Double("max_odometry_turn_rate_rad_s");
  t.max_scan_duration_s = a.Double("max_scan_duration_s");
  t.odometry_sigma_xy_per_m = a.Double("odometry_sigma_xy_per_m");
  t.odometry_sigma_theta_per_m = a.Double("odometry_sigma_theta_per_m");
  t.odometry_sigma_theta_per_rad = a.Double("odometry_sigma_theta_per_rad");
  t.initial_sigma_xy_m = a.Double("initial_sigma_xy_m");
  t.initial_sigma_theta_rad = a.Double("initial_sigma_theta_rad");
  t.deskew = a.Bool("deskew");
  o.state_period_s = a.Double("state_period_s");
  o.lost_error_after_s = a.Double("lost_error_after_s");
  o.max_pending_scans = a.IntegerIn<size_t>("max_pending_scans", 1, 1000000);
  a.Finish();
  try {
    o.Validate();
  } catch (const std::invalid_argument& error) {
    file.Fail(*e, error.what());
  }
  return o;
}

}  // namespace structloc::localisation
