// CPU wake-up latency limit through PM QoS (see header).
#include "structloc/process/cpu_wake_latency.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <stdexcept>

namespace structloc::process {

CpuWakeLatencyLimit::CpuWakeLatencyLimit(int max_us, const std::string& device) : max_us_(max_us) {
  if (max_us < 0) {
    throw std::invalid_argument("a CPU wake-up latency limit must be >= 0 us, got " +
                                std::to_string(max_us));
  }
  fd_ = ::open(device.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd_ < 0) {
    const int error = errno;
    throw std::runtime_error(
        "cannot limit the CPUs' wake-up latency: " + device + ": " + std::strerror(error) +
        (error == EACCES || error == EPERM
             ? " (writing it needs root or write access to it; or set the limit for the whole "
               "machine, e.g. with tuned's latency-performance profile)"
             : ""));
  }
  // The kernel takes the limit as a binary 32-bit integer (a 4-byte write).
  const std::int32_t value = max_us;
  if (::write(fd_, &value, sizeof value) != static_cast<ssize_t>(sizeof value)) {
    const int error = errno;
    ::close(fd_);
    throw std::runtime_error("cannot limit the CPUs' wake-up latency: writing " + device + ": " +
                             std::strerror(error));
  }
}

std::optional<int> CpuWakeLatencyLimit::InForceUs(const std::string& device) {
  const int fd = ::open(device.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return std::nullopt;
  std::int32_t value = 0;
  const bool read_all = ::read(fd, &value, sizeof value) == static_cast<ssize_t>(sizeof value);
  ::close(fd);
  if (!read_all) return std::nullopt;
  return value;
}

CpuWakeLatencyLimit::~CpuWakeLatencyLimit() {
  ::close(fd_);  // the kernel drops the limit with its last open file
}

}  // namespace structloc::process
