// structloc_soak_benchmark [--seconds S] [--check]: the localisation component
// soaked (issue 16). It starts the real component and feeds it, over DDS in
// real time, the office scenario driven in a loop with a 40 Hz, 1081-beam
// laser for S seconds (default 1800), sampling the process every second from
// /proc. After the warm-up (a quarter of the run, 30..300 s) it reports:
//   - resident memory growth, the least-squares slope of VmRSS, in MB/h (over
//     a steady span under 10 minutes judged as growth per 10 minutes: a few
//     pages of allocator noise in the 90 s of the short run would read as
//     MB/h);
//   - queues: the thread count and the scan-to-pose latency of the first and
//     last minute after warm-up (a queue that grows shows as latency that grows);
//   - accounting: scans sent against scans processed + dropped + rejected as the
//     component's own status counts them (every scan must be one of those).
// With --check it exits 1 unless memory grows under 1 MB/h, the thread count
// does not grow, the last minute's median latency is within twice the first's
// + 1 ms, and every scan is accounted for. ./setup.sh test runs 120 s with
// --check; the 30-minute run is documented in docs/guides/testing.md.
#include <algorithm>
#include <cstdio>
#include <map>
#include <mutex>

#include "benchmarks/process_cpu.hpp"
#include "benchmarks/realtime_feed.hpp"
#include "geometry_msgs/msg/PoseWithCovarianceStampedPubSubTypes.h"
#include "pose_argument.hpp"
#include "structloc/config/command_line.hpp"
#include "structloc/process/child_process.hpp"
#include "structloc_msgs/msg/LocalisationStatusPubSubTypes.h"
#include "test_domains.hpp"
#include "test_paths.hpp"

namespace structloc {
namespace {

using Clock = std::chrono::steady_clock;
constexpr double kMaxGrowthMbPerHour = 1.0;
constexpr double kShortestGrowthSpanS = 600.0;

struct Sample {
  double t_s;
  double rss_mb;
  long long threads;
};

// Least-squares slope of rss_mb over t_s, per hour.
double GrowthMbPerHour(const std::vector<Sample>& samples) {
  double n = 0, st = 0, sr = 0, stt = 0, str = 0;
  for (const auto& s : samples) {
    n += 1;
    st += s.t_s;
    sr += s.rss_mb;
    stt += s.t_s * s.t_s;
    str += s.t_s * s.rss_mb;
  }
  const double denominator = n * stt - st * st;
  return denominator > 0 ? 3600.0 * (n * str - st * sr) / denominator : 0.0;
}

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

int Run(int argc, char** argv) {
  const std::vector<config::OptionSpec> specs = {
      {"seconds", true, "length of the soak, 60..86400 s (default 1800)"},
      {"check", false, "exit 1 when a bar is missed"},
      {"help", false, "print the options and exit"}};
  const config::CommandLine cli(argc, argv, 1, specs);
  const double seconds = cli.NumberIn("seconds", 1800, 60, 86400);
  const double warm_up_s = std::clamp(0.25 * seconds, 30.0, 300.0);
  const std::string source = STRUCTLOC_SOURCE_DIR;
  const int domain = testing::domains::kSoakBenchmark;
  auto scenario = simulation_core::LoadScenario(source + "/maps/scenarios/office_people.xml");
  scenario.laser.rate_hz = 40.0;
  scenario.duration_s = seconds;
  scenario.path.loop = true;
  dds_common::Node node(
      {"soak_feeder", domain, source + "/qos/structloc_qos.xml", "structloc_localhost", "", {}});
  testing::RealtimeWriters writers{
      node.CreateWriter<sensor_msgs::msg::LaserScanPubSubType>(dds_common::topics::kScan),
      node.CreateWriter<nav_msgs::msg::OdometryPubSubType>(dds_common::topics::kOdom)};
  std::mutex mutex;
  std::map<double, Clock::time_point> sent;             // by scan stamp
  std::vector<std::pair<double, double>> latency_ms;    // (seconds into the run, latency)
  structloc_msgs::msg::LocalisationStatus last_status;  // the newest one
  Clock::time_point start;
  const auto poses = node.Subscribe<geometry_msgs::msg::PoseWithCovarianceStampedPubSubType>(
      dds_common::topics::kPose, [&](const geometry_msgs::msg::PoseWithCovarianceStamped& m) {
        const auto now = Clock::now();
        std::lock_guard<std::mutex> lock(mutex);
        const auto it = sent.find(dds_common::FromRosTime(m.header().stamp()));
        if (it == sent.end()) return;
        latency_ms.emplace_back(
            std::chrono::duration<double>(now - start).count(),
            std::chrono::duration<double, std::milli>(now - it->second).count());
        sent.erase(sent.begin(), it);  // older scans got no pose; keep the map small
      });
  const auto statuses = node.Subscribe<structloc_msgs::msg::LocalisationStatusPubSubType>(
      dds_common::topics::kStatus, [&](const structloc_msgs::msg::LocalisationStatus& m) {
        std::lock_guard<std::mutex> lock(mutex);
        if (m.scans_processed() + m.scans_dropped() + m.scans_rejected() >=
            last_status.scans_processed() + last_status.scans_dropped() +
                last_status.scans_rejected()) {
          last_status = m;
        }
      });
  const auto& p = scenario.initial_pose;
  process::ChildProcess loc(
      std::string(STRUCTLOC_BIN_DIR) + "/structloc_localisation",
      {"--domain", std::to_string(domain), "--qos", source + "/qos/structloc_qos.xml", "--params",
       structloc::testing::SimulatedRobotParams(), "--initial-pose",
       structloc::testing::PoseArgument(p)});
  const auto give_up = Clock::now() + std::chrono::seconds(30);
  while (writers.scans.MatchedReaders() == 0 || writers.odom.MatchedReaders() == 0) {
    if (const auto code = loc.Poll()) {
      std::printf("FAILED: the localisation ended with exit %d before it subscribed:\n%s\n", *code,
                  loc.CapturedOutput().c_str());
      return 1;
    }
    if (Clock::now() > give_up) {
      std::printf("FAILED: the localisation did not subscribe within 30 s:\n%s\n",
                  loc.CapturedOutput().c_str());
      return 1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  std::printf("soak: %.0f s of 40 Hz, 1081-beam scans (the office loop), warm-up %.0f s\n", seconds,
              warm_up_s);
  std::fflush(stdout);

  simulation_core::Simulation sim(scenario);
  std::vector<Sample> samples;
  size_t scans_sent = 0;
  double next_sample_s = 0.0;
  start = Clock::now();
  testing::FeedInRealTime(
      sim, writers, 1.0e9,
      [&](double stamp) {
        ++scans_sent;
        std::lock_guard<std::mutex> lock(mutex);
        sent[stamp] = Clock::now();
      },
      [&] {
        const double t = std::chrono::duration<double>(Clock::now() - start).count();
        if (t >= next_sample_s) {
          samples.push_back({t, testing::ProcStatusField(loc.Pid(), "VmRSS") / 1024.0,
                             testing::ProcStatusField(loc.Pid(), "Threads")});
          if (next_sample_s > 0 && static_cast<long>(next_sample_s) % 300 == 0) {
            std::printf("  t = %4.0f s  RSS %.1f MB, %lld threads, %zu scans sent\n", t,
                        samples.back().rss_mb, samples.back().threads, scans_sent);
            std::fflush(stdout);
          }
          next_sample_s += 1.0;
        }
        return loc.Poll() == std::nullopt;
      });
  std::this_thread::sleep_for(std::chrono::seconds(1));  // the last status
  if (const auto code = loc.Poll()) {
    std::printf("FAILED: the localisation ended with exit %d:\n%s\n", *code,
                loc.CapturedOutput().c_str());
    return 1;
  }
  loc.Stop(std::chrono::seconds(5));

  std::vector<Sample> steady;
  for (const auto& s : samples) {
    if (s.t_s >= warm_up_s) steady.push_back(s);
  }
  std::vector<double> first_minute, last_minute;
  const double end_s = samples.empty() ? 0.0 : samples.back().t_s;
  std::lock_guard<std::mutex> lock(mutex);
  for (const auto& [t, ms] : latency_ms) {
    if (t >= warm_up_s && t < warm_up_s + 60) first_minute.push_back(ms);
    if (t >= end_s - 60) last_minute.push_back(ms);
  }
  if (steady.size() < 10 || first_minute.empty() || last_minute.empty()) {
    std::printf("FAILED: too little steady state (%zu samples, %zu and %zu latencies)\n",
                steady.size(), first_minute.size(), last_minute.size());
    return 1;
  }
  const double growth = GrowthMbPerHour(steady);
  const double span_s = steady.back().t_s - steady.front().t_s;
  const double judged_growth = growth * span_s / std::max(span_s, kShortestGrowthSpanS);
  const uint64_t processed = last_status.scans_processed(), dropped = last_status.scans_dropped(),
                 rejected = last_status.scans_rejected();
  const long long unaccounted =
      static_cast<long long>(scans_sent) - static_cast<long long>(processed + dropped + rejected);
  const double first_ms = Median(first_minute), last_ms = Median(last_minute);
  std::printf(
      "resident memory: %.1f MB after warm-up, %.1f MB at the end, growth %.2f MB/h over "
      "%.0f s, judged %.2f MB/h (bar %.1f)\n",
      steady.front().rss_mb, steady.back().rss_mb, growth, span_s, judged_growth,
      kMaxGrowthMbPerHour);
  std::printf("threads: %lld after warm-up, %lld at the end\n", steady.front().threads,
              steady.back().threads);
  std::printf(
      "scan-to-pose latency median: %.3f ms in the first minute after warm-up, %.3f ms in "
      "the last\n",
      first_ms, last_ms);
  std::printf("scans: %zu sent, %llu processed, %llu dropped, %llu rejected, %lld unaccounted\n",
              scans_sent, static_cast<unsigned long long>(processed),
              static_cast<unsigned long long>(dropped), static_cast<unsigned long long>(rejected),
              unaccounted);
  if (!cli.Has("check")) return 0;
  bool ok = true;
  auto bar = [&ok](bool met, const char* what) {
    if (!met) std::printf("FAILED: %s\n", what);
    ok = ok && met;
  };
  bar(judged_growth < kMaxGrowthMbPerHour, "resident memory grows by 1 MB/h or more");
  bar(steady.back().threads <= steady.front().threads, "the thread count grew");
  bar(last_ms <= 2.0 * first_ms + 1.0, "latency grew: a queue is filling");
  bar(unaccounted == 0, "scans neither processed nor counted as dropped or rejected");
  if (ok) std::printf("PASSED: every soak bar met\n");
  return ok ? 0 : 1;
}

}  // namespace
}  // namespace structloc

int main(int argc, char** argv) {
  try {
    return structloc::Run(argc, argv);
  } catch (const structloc::config::HelpRequested& help) {
    std::printf("%s", help.usage.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "structloc_soak_benchmark: %s\n", e.what());
    return 2;
  }
}
