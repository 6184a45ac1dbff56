// Repeated faults (issue 16): each component is killed with SIGKILL 20 times
// during a run of all three and started again; the three runs (one per
// victim, each on domains of its own) go side by side. Every time: the restarted
// component is matched and its data flows within 5 s of its start; the dead
// writer is unmatched within the lease (3 s in the shipped profile) + 1 s;
// the peers never crash and never stall (each one's diagnostics keep arriving
// with no gap over 2.5 s, their period being 0.5-1 s); /dev/shm holds no
// more Fast DDS segments afterwards than before; and, unless the robot itself
// was restarted, the localisation meets the demo's accuracy bar from 1 s after
// each of its starts on, judged against ground truth. Prints its figures.
#include <gtest/gtest.h>

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <thread>

#include "dds_test_support.hpp"
#include "diagnostic_msgs/msg/DiagnosticArrayPubSubTypes.h"
#include "sensor_msgs/msg/LaserScanPubSubTypes.h"
#include "shipped_copy.hpp"
#include "structloc/evaluation/live_evaluator.hpp"
#include "structloc/process/child_process.hpp"
#include "structloc_msgs/msg/CalibrationResultPubSubTypes.h"
#include "structloc_msgs/msg/LocalisationStatusPubSubTypes.h"
#include "stuck_process.hpp"
#include "temp_dir.hpp"
#include "test_domains.hpp"

namespace structloc {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;
constexpr int kKills = 20;
constexpr auto kRestartBar = 5s;
constexpr auto kUnmatchBar = 4s;  // the shipped profile's 3 s lease + 1 s
constexpr double kStallBarS = 2.5;
const std::vector<std::string> kComponents = {"simulator", "localisation", "calibration"};

// Fast DDS's shared-memory segments, ports and locks in /dev/shm.
size_t FastDdsShmEntries() {
  size_t count = 0;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator("/dev/shm", error)) {
    const std::string name = entry.path().filename().string();
    if (name.find("fastrtps") != std::string::npos ||
        name.find("fast_datasharing") != std::string::npos) {
      ++count;
    }
  }
  return count;
}

// Each component's run has a domain of its own, so the three run side by side.
int DomainOf(const std::string& victim) {
  if (victim == "localisation") return testing::domains::kRepeatedFaultsLocalisation;
  if (victim == "calibration") return testing::domains::kRepeatedFaultsCalibration;
  return testing::domains::kRepeatedFaults;
}

double Seconds(Clock::duration d) {
  return std::chrono::duration<double>(d).count();
}

// The poses that arrived at least `settle_s` after every start before them
// (`arrivals_s[i]` is when poses[i] arrived; both on the steady clock).
std::vector<log_formats::StampedPose> PosesSettledAfter(
    const std::vector<log_formats::StampedPose>& poses, const std::vector<double>& arrivals_s,
    const std::vector<double>& starts_s, double settle_s) {
  std::vector<log_formats::StampedPose> settled;
  for (size_t i = 0; i < std::min(poses.size(), arrivals_s.size()); ++i) {
    const bool settling = std::any_of(starts_s.begin(), starts_s.end(), [&](double start) {
      return arrivals_s[i] >= start && arrivals_s[i] < start + settle_s;
    });
    if (!settling) settled.push_back(poses[i]);
  }
  return settled;
}

// What the test hears: each component's main output (the simulator's scans,
// the localisation's status, the calibration's result topic, whose writer
// exists from its start) and every component's diagnostics.
class Observer {
 public:
  explicit Observer(int domain)
      : node_(testing::TestNodeOptions("fault_observer", domain)),
        scans_(node_.Subscribe<sensor_msgs::msg::LaserScanPubSubType>(
            dds_common::topics::kScan, [this](const auto&) { Heard("simulator"); })),
        status_(node_.Subscribe<structloc_msgs::msg::LocalisationStatusPubSubType>(
            dds_common::topics::kStatus, [this](const auto&) { Heard("localisation"); })),
        results_(node_.Subscribe<structloc_msgs::msg::CalibrationResultPubSubType>(
            dds_common::topics::kCalibration, [](const auto&) {})),
        diagnostics_(node_.Subscribe<diagnostic_msgs::msg::DiagnosticArrayPubSubType>(
            dds_common::topics::kDiagnostics, [this](const auto& array) {
              for (const auto& status : array.status()) Diagnostics(status.hardware_id());
            })) {}

  // Writers of `component`'s main output matched to the observer.
  size_t Matched(const std::string& component) const {
    if (component == "simulator") return scans_.MatchedWriters();
    if (component == "localisation") return status_.MatchedWriters();
    return results_.MatchedWriters();
  }
  // When `component`'s data last arrived: its main output, or for the
  // calibration (which publishes a result only at the end) its diagnostics.
  Clock::time_point LastData(const std::string& component) {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto& table = component == "calibration" ? last_diagnostics_ : last_data_;
    const auto it = table.find(component);
    return it == table.end() ? Clock::time_point{} : it->second;
  }
  // The longest silence of `component`'s diagnostics since ResetGaps, up to now.
  double LongestDiagnosticsGapS(const std::string& component) {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto it = last_diagnostics_.find(component);
    if (it == last_diagnostics_.end()) return 1e9;
    return std::max(longest_gap_s_[component], Seconds(Clock::now() - it->second));
  }
  void ResetGaps() {
    std::lock_guard<std::mutex> lock(mutex_);
    longest_gap_s_.clear();
  }

 private:
  void Heard(const std::string& component) {
    std::lock_guard<std::mutex> lock(mutex_);
    last_data_[component] = Clock::now();
  }
  void Diagnostics(const std::string& component) {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto now = Clock::now();
    const auto it = last_diagnostics_.find(component);
    if (it != last_diagnostics_.end()) {
      longest_gap_s_[component] = std::max(longest_gap_s_[component], Seconds(now - it->second));
    }
    last_diagnostics_[component] = now;
  }

  std::mutex mutex_;
  std::map<std::string, Clock::time_point> last_data_, last_diagnostics_;
  std::map<std::string, double> longest_gap_s_;
  dds_common::Node node_;
  dds_common::Subscription scans_, status_, results_, diagnostics_;
};

// One victim's run: its three components, observer and judge on a domain
// of its own.
class FaultRun {
 public:
  explicit FaultRun(std::string victim) : victim_(std::move(victim)) {}
  // Kills and restarts the victim; gtest failures name it.
  void Run();

 private:
  // Starts `component` as its own process with the shipped QoS file. The
  // simulator drives the office scenario in a loop for 10 minutes, however
  // long the twenty kills take; the localisation resumes from the pose it
  // saves.
  std::unique_ptr<process::ChildProcess> Start(const std::string& component, bool first) {
    std::vector<std::string> args = {"--domain", std::to_string(domain_), "--qos",
                                     testing::ShippedQos()};
    if (component == "simulator") {
      args.insert(args.end(), {"--scenario", looped_scenario_, "--wait-for-subscribers", "2"});
    } else if (component == "calibration") {
      // It records through the whole test, so that SIGTERM ends its recording
      // early and its estimate is not judged here: fixes from a localisation
      // killed every few seconds are sparse and weak, and the calibration
      // rightly refuses an estimate from them (exit 1 once its window is over).
      args.insert(args.end(), {"--record-s", "3600"});
    } else if (component == "localisation") {
      args.insert(args.end(),
                  {"--state-file", state_file_, "--params", testing::SimulatedRobotParams()});
      if (first) args.insert(args.end(), {"--initial-pose", "2.0 6.5 0"});
    }
    return std::make_unique<process::ChildProcess>(
        std::string(STRUCTLOC_BIN_DIR) + "/structloc_" + component, args);
  }

  // The office scenario, 600 s long, the robot driving from its start along
  // the corridor and then round and round the east room's pillar (a closed
  // circuit: the demo's own path ends facing away from its start, and a path
  // looped back from there U-turns in a wide arc out of the building).
  std::string LoopedScenario() const {
    std::string xml = testing::ShippedTextForCopy("maps/scenarios/office_people.xml");
    const std::string duration = "duration_s=\"60\"", path = "<path ", path_end = "</path>";
    const auto duration_at = xml.find(duration);
    if (duration_at == std::string::npos)
      throw std::runtime_error("office_people.xml lacks " + duration);
    xml.replace(duration_at, duration.size(), "duration_s=\"600\"");
    const auto path_at = xml.find(path), path_end_at = xml.find(path_end);
    if (path_at == std::string::npos || path_end_at == std::string::npos)
      throw std::runtime_error("office_people.xml lacks its <path>");
    xml.replace(path_at, path_end_at + path_end.size() - path_at,
                "<path mode=\"waypoints\" speed_m_s=\"0.8\" dwell_s=\"0\" lookahead_m=\"0.8\" "
                "loop=\"true\"><waypoint x=\"19.5\" y=\"6.5\"/><waypoint x=\"22.5\" "
                "y=\"6.5\"/><waypoint x=\"22.5\" y=\"3.0\"/><waypoint x=\"19.5\" "
                "y=\"3.0\"/></path>");
    return temp_.Write("office_looped.xml", xml);
  }

  const std::string victim_;
  const int domain_ = DomainOf(victim_);
  testing::TempDir temp_;
  std::string state_file_ = temp_ / "pose_state";
  std::string looped_scenario_ = LoopedScenario();  // written once, for every start
};

void FaultRun::Run() {
  const std::string& victim = victim_;
  SCOPED_TRACE("victim: " + victim);
  Observer observer(domain_);
  dds_common::Node judge_node(testing::TestNodeOptions("fault_judge", domain_));
  evaluation::LiveEvaluator judge(judge_node, geometry::Pose2D{2.0, 6.5, 0.0});
  std::map<std::string, std::unique_ptr<process::ChildProcess>> running;
  for (const auto& c : kComponents) running[c] = Start(c, true);
  for (const auto& c : kComponents) {
    ASSERT_TRUE(testing::WaitUntil([&] { return observer.Matched(c) > 0; }))
        << c << " never matched: " << testing::WhyUnresponsive(*running[c]) << "\nits output:\n"
        << running[c]->CapturedOutput();
  }
  ASSERT_TRUE(testing::WaitUntil([&] { return observer.LastData(victim) != Clock::time_point{}; }))
      << victim << " sent nothing:\n"
      << running[victim]->CapturedOutput();
  observer.ResetGaps();

  std::vector<double> restart_s, unmatch_s;
  std::vector<double> localisation_starts_s;  // steady clock, as the judge's pose arrivals
  for (int kill = 0; kill < kKills; ++kill) {
    std::this_thread::sleep_for(2s);
    running[victim]->Signal(SIGKILL);
    const auto killed = Clock::now();
    ASSERT_TRUE(running[victim]->WaitExit(10s).has_value());
    ASSERT_TRUE(testing::WaitUntil([&] { return observer.Matched(victim) == 0; }, 30s))
        << "the dead " << victim << "'s writer was never unmatched";
    unmatch_s.push_back(Seconds(Clock::now() - killed));

    const auto started = Clock::now();
    if (victim == "localisation")
      localisation_starts_s.push_back(Seconds(started.time_since_epoch()));
    running[victim] = Start(victim, false);
    const bool back = testing::WaitUntil(
        [&] { return observer.Matched(victim) > 0 && observer.LastData(victim) > started; }, 30s);
    ASSERT_TRUE(back) << victim << " did not come back after kill " << kill + 1 << ": "
                      << testing::WhyUnresponsive(*running[victim]) << "\nits output:\n"
                      << running[victim]->CapturedOutput();
    restart_s.push_back(Seconds(Clock::now() - started));
    for (const auto& c : kComponents) {
      if (c == victim) continue;
      ASSERT_FALSE(running[c]->Poll().has_value())
          << c << " died after " << victim << " was killed " << kill + 1 << " times:\n"
          << running[c]->CapturedOutput();
    }
  }

  auto max_of = [](const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); };
  auto median_of = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  std::printf(
      "%s killed %d times: back (matched, data flowing) after median %.2f s, max %.2f s; "
      "dead writer unmatched after median %.2f s, max %.2f s\n",
      victim.c_str(), kKills, median_of(restart_s), max_of(restart_s), median_of(unmatch_s),
      max_of(unmatch_s));
  for (const auto& c : kComponents) {
    if (c == victim) continue;
    const double gap = observer.LongestDiagnosticsGapS(c);
    std::printf("%s run: peer %s alive, longest diagnostics gap %.2f s\n", victim.c_str(),
                c.c_str(), gap);
    EXPECT_LE(gap, kStallBarS) << c << " stalled while " << victim << " was killed";
  }
  EXPECT_LE(max_of(restart_s), Seconds(kRestartBar));
  EXPECT_LE(max_of(unmatch_s), Seconds(kUnmatchBar));
  // Unless the robot itself was restarted (the simulator starts its path
  // again), the localisation must meet the demo's bar (RMSE <= 10 mm, max <=
  // 30 mm, never lost) from 1 s after each of its starts on, as after one
  // restart: a restarted one confirms its saved correction with a local search
  // before it publishes, however far the odometry drifted while it was down.
  if (victim != "simulator") {
    std::this_thread::sleep_for(2s);
    const auto e = replay::CompareTrajectories(
        PosesSettledAfter(judge.Estimate(), judge.PoseArrivals(), localisation_starts_s, 1.0),
        judge.Truth(), 0.011);
    std::printf(
        "%s run: localisation against ground truth from 1 s after each start: RMSE %.1f mm, "
        "max %.1f mm over %zu poses, lost %llu times\n",
        victim.c_str(), 1e3 * e.position_rmse_m, 1e3 * e.position_max_m, e.matched,
        static_cast<unsigned long long>(judge.LostCount()));
    EXPECT_GT(e.matched, 100u);
    EXPECT_LE(e.position_rmse_m, 0.010) << running["localisation"]->CapturedOutput();
    EXPECT_LE(e.position_max_m, 0.030);
    EXPECT_EQ(judge.LostCount(), 0u);
  }
  for (auto& [c, process] : running) {
    process->Signal(SIGTERM);
    EXPECT_EQ(process->WaitExit(testing::kGenerousTimeout), 0) << c << ":\n"
                                                               << process->CapturedOutput();
  }
  running.clear();
}

// The three runs side by side (gtest's assertions are thread-safe; a fatal
// one ends only its own run).
TEST(RepeatedFaults, EachComponentKilledTwentyTimesPeersSurviveAndItIsBackWithinFiveSeconds) {
  const size_t shm_before = FastDdsShmEntries();
  std::vector<std::thread> runs;
  for (const auto& victim : kComponents) {
    runs.emplace_back([victim] { FaultRun(victim).Run(); });
  }
  for (auto& run : runs) run.join();
  const size_t shm_after = FastDdsShmEntries();
  std::printf("/dev/shm Fast DDS entries: %zu before, %zu after\n", shm_before, shm_after);
  EXPECT_LE(shm_after, shm_before);
}

}  // namespace
}  // namespace structloc
