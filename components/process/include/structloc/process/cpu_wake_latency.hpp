// A limit on how long an idle CPU may take to wake, held while a
// latency-critical component runs. An idle CPU sleeps; waking it for the next
// scan costs tens of microseconds on bare metal's deeper sleep states and more
// in a virtual machine, whose idle CPUs the host takes back. Linux's PM QoS
// interface (/dev/cpu_dma_latency, the one cyclictest and real-time set-ups
// use) keeps every CPU out of the sleep states slower to leave than the limit
// (0: an idle CPU polls) for as long as the requesting process holds the file
// open. The price is power: the CPUs never sleep deeply.
#pragma once

#include <optional>
#include <string>

namespace structloc::process {

class CpuWakeLatencyLimit {
 public:
  static constexpr const char* kDevice = "/dev/cpu_dma_latency";
  // Holds the limit of `max_us` microseconds (>= 0) until destroyed; throws
  // std::runtime_error saying why it cannot (no such device, no permission).
  explicit CpuWakeLatencyLimit(int max_us, const std::string& device = kDevice);
  ~CpuWakeLatencyLimit();
  CpuWakeLatencyLimit(const CpuWakeLatencyLimit&) = delete;
  CpuWakeLatencyLimit& operator=(const CpuWakeLatencyLimit&) = delete;

  int MaxUs() const { return max_us_; }

  // The limit the kernel holds now: the smallest any process asks for, or
  // kNoLimitUs; none when the device cannot be read (it needs root).
  static constexpr int kNoLimitUs = 2000000000;
  static std::optional<int> InForceUs(const std::string& device = kDevice);

 private:
  int fd_ = -1;
  int max_us_ = 0;
};

}  // namespace structloc::process
