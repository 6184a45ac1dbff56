// Tracking-session options declared once (key, range, unit, description; the
// struct members hold the defaults) for the <tracking> block of a
// <localisation_params> file (see header).
#include "structloc/localisation_core/tracking/tracking_session_options.hpp"

#include <stdexcept>

#include "structloc/config/option_table.hpp"
#include "structloc/localisation_core/localiser/localiser_options.hpp"

namespace structloc::localisation_core {
namespace {

using config::Range;
using S = SessionOptions;
using T = TrackerOptions;

config::OptionFile<SessionOptions> SessionOptionFile() {
  config::OptionTable<S> t(
      "tracking", "the pose tracker (odometry prior, thesis 3.6) and the session's timing");
  t.Number("odometry_wait_s", &S::tracker, &T::odometry_wait_s, Range::NonNegative(), "s",
           "how long a scan may wait for odometry to cover it");
  t.Number("max_extrapolation_s", &S::tracker, &T::max_extrapolation_s, Range::Closed(0, 0.2), "s",
           "beams this far past the newest odometry are de-skewed by extrapolating it");
  t.Number("max_future_s", &S::tracker, &T::max_future_s, Range::Positive(), "s",
           "scans stamped further ahead of the odometry are refused");
  t.Number("max_odometry_speed_m_s", &S::tracker, &T::max_odometry_speed_m_s, Range::Positive(),
           "m/s", "faster odometry steps are jumps and refused");
  t.Number("max_odometry_turn_rate_rad_s", &S::tracker, &T::max_odometry_turn_rate_rad_s,
           Range::Positive(), "rad/s", "faster heading changes are jumps and refused");
  t.Number("max_scan_duration_s", &S::tracker, &T::max_scan_duration_s, Range::Positive(), "s",
           "a scan whose beams span longer than this is refused");
  t.Number("odometry_sigma_xy_per_m", &S::tracker, &T::odometry_sigma_xy_per_m,
           Range::NonNegative(), "m/m", "prior growth per metre driven (1 sigma)");
  t.Number("odometry_sigma_theta_per_m", &S::tracker, &T::odometry_sigma_theta_per_m,
           Range::NonNegative(), "rad/m", "heading prior growth per metre driven");
  t.Number("odometry_sigma_theta_per_rad", &S::tracker, &T::odometry_sigma_theta_per_rad,
           Range::NonNegative(), "rad/rad", "heading prior growth per radian turned");
  t.Number("initial_sigma_xy_m", &S::tracker, &T::initial_sigma_xy_m, Range::Positive(), "m",
           "uncertainty of a given initial pose (x and y)");
  t.Number("initial_sigma_theta_rad", &S::tracker, &T::initial_sigma_theta_rad, Range::Positive(),
           "rad", "uncertainty of a given initial heading");
  t.Flag("deskew", &S::tracker, &T::deskew, "de-skew scans from the odometry history");
  t.Number("odometry_scale_sigma", &S::tracker, &T::odometry_scale_sigma, Range::Closed(0, 0.5), "",
           "initial sigma of the odometry's distance and turn scale factors (0: not learnt)");
  t.Number("odometry_drift_sigma_rad_per_m", &S::tracker, &T::odometry_drift_sigma_rad_per_m,
           Range::Closed(0, 0.5), "rad/m",
           "initial sigma of the odometry's heading drift per metre (0: not learnt)");
  t.Number("calibration_walk_per_m", &S::tracker, &T::calibration_walk_per_m, Range::Closed(0, 0.1),
           "1/sqrt(m)", "how fast those factors may change while driving");
  t.Number("weak_std_m", &S::tracker, &T::weak_std_m, Range::Positive(), "m",
           "directions a scan's features pin worse than this stay with odometry");
  t.Number("weak_std_rad", &S::tracker, &T::weak_std_rad, Range::Positive(), "rad",
           "headings a scan's features pin worse than this stay with odometry");
  t.Number("min_update_travel_m", &S::tracker, &T::min_update_travel_m, Range::NonNegative(), "m",
           "no update until the robot moved this far (or turned min_update_turn_rad) since the "
           "last one");
  t.Number("min_update_turn_rad", &S::tracker, &T::min_update_turn_rad, Range::NonNegative(), "rad",
           "see min_update_travel_m");
  t.Number("lost_sigma_m", &S::tracker, &T::lost_sigma_m, Range::Positive(), "m",
           "without a usable scan, lost once the position sigma exceeds this");
  t.Number("min_explained_share", &S::tracker, &T::min_explained_share, Range::Closed(0, 1), "",
           "whole-scan check: below this share of the scan explained by the map the tracker "
           "re-acquires (0: no check)");
  t.Number("min_share_drop", &S::tracker, &T::min_share_drop, Range::Closed(0, 1), "",
           "a correction lowering the explained share by more than this is refused");
  t.Number("reacquire_after_s", &S::tracker, &T::reacquire_after_s, Range::NonNegative(), "s",
           "how long the share may stay low before a local search");
  t.Number("reacquire_max_radius_m", &S::tracker, &T::reacquire_max_radius_m, Range::Positive(),
           "m", "the local search's largest radius around the tracked pose");
  t.Number("search_work_per_scan", &S::tracker, &T::search_work_per_scan, Range::Closed(1000, 1e9),
           "",
           "the local search's slice between scans, in points looked up (about 10 ns each): "
           "searching never stalls the tracking");
  t.Number("state_period_s", &S::state_period_s, Range::Positive(), "s",
           "how often the pose is due to be saved");
  t.Number("lost_error_after_s", &S::lost_error_after_s, Range::NonNegative(), "s",
           "lost (dead reckoning) this long is an error, not a warning");
  t.Number("scan_timeout_s", &S::scan_timeout_s, Range::Positive(), "s",
           "health is WARN without scans (or odometry) this long");
  t.Number("silent_error_after_s", &S::silent_error_after_s, Range::Positive(), "s",
           "health is ERROR when an input stays silent this long");
  t.Number("problem_hold_s", &S::problem_hold_s, Range::NonNegative(), "s",
           "a rejected input stays in the health report this long");
  t.Number("max_pending_scans", &S::max_pending_scans, Range::Closed(1, 1000000), "",
           "scans waiting for odometry in in-order scheduling (replay)");
  t.Number("scan_latency_s", &S::scan_latency_s, Range::Closed(-1, 1), "s",
           "each scan was taken this long before its stamp (a laser stamped when its readings "
           "arrived, as structloc slam estimates): tracked, and its pose stamped, that much "
           "earlier");
  std::set<std::string> localiser_sections;
  const auto localiser_file = LocaliserOptionFile();
  for (const auto& section : localiser_file.Sections()) {
    localiser_sections.insert(section.Section());
  }
  return config::OptionFile<SessionOptions>("localisation_params", {t}, localiser_sections);
}

}  // namespace

// Declared with the tracker (pose_tracker.hpp); its ranges are the <tracking>
// block's, so they are written once, above.
void TrackerOptions::Validate() const {
  SessionOptions s;
  s.tracker = *this;
  SessionOptionFile().Validate(s);
}

void SessionOptions::Validate() const {
  SessionOptionFile().Validate(*this);
}

void PrintSessionOptions(std::ostream& out) {
  SessionOptionFile().Print(out, SessionOptions{});
}

void WriteExpandedLocalisationParams(const std::string& path, std::ostream& out) {
  const auto localiser = LoadLocaliserOptions(path);
  const auto session = LoadSessionOptions(path);
  out << "<localisation_params>\n";
  LocaliserOptionFile().WriteSections(out, localiser);
  SessionOptionFile().WriteSections(out, session);
  out << "</localisation_params>\n";
}

SessionOptions LoadSessionOptions(const std::string& path) {
  const auto file = config::XmlFile::Load(path);
  return SessionOptionFile().Load(file);
}

}  // namespace structloc::localisation_core
