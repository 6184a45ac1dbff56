// The CPUs' wake-up latency limit: what it writes, that it names the device
// and the reason when it cannot hold the limit, and, where this machine lets
// the test write Linux's PM QoS device, that the kernel holds the limit while
// the object lives and drops it after.
#include "structloc/process/cpu_wake_latency.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <stdexcept>

#include "temp_dir.hpp"

namespace structloc::process {
namespace {

TEST(CpuWakeLatencyLimit, WritesTheLimitAsTheKernelTakesIt) {
  testing::TempDir dir;
  const std::string device = dir.Write("cpu_dma_latency", "");
  {
    CpuWakeLatencyLimit limit(25, device);
    EXPECT_EQ(limit.MaxUs(), 25);
  }
  std::ifstream in(device, std::ios::binary | std::ios::ate);
  EXPECT_EQ(in.tellg(), 4);  // one 32-bit integer, not text
  EXPECT_EQ(CpuWakeLatencyLimit::InForceUs(device), 25);
}

TEST(CpuWakeLatencyLimit, SaysWhichDeviceAndWhyWhenItCannotHoldTheLimit) {
  testing::TempDir dir;
  const std::string missing = dir / "no_such_device";
  try {
    CpuWakeLatencyLimit limit(0, missing);
    FAIL() << "held a limit through a missing device";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(missing + ": No such file or directory"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(CpuWakeLatencyLimit(-1, dir.Write("device", "")), std::invalid_argument);
  EXPECT_FALSE(CpuWakeLatencyLimit::InForceUs(missing).has_value());
}

TEST(CpuWakeLatencyLimit, TheKernelHoldsTheLimitWhileItLivesAndDropsItAfter) {
  const std::string device = CpuWakeLatencyLimit::kDevice;
  if (::access(device.c_str(), R_OK | W_OK) != 0) {
    GTEST_SKIP() << device << " is not readable and writable here";
  }
  // The kernel reads back the smallest limit any process holds; a test running
  // beside this one may hold another (never this one's 7 us).
  constexpr int kLimitUs = 7;
  {
    CpuWakeLatencyLimit limit(kLimitUs, device);
    const auto held = CpuWakeLatencyLimit::InForceUs(device);
    ASSERT_TRUE(held.has_value());
    EXPECT_LE(*held, kLimitUs);
  }
  EXPECT_NE(CpuWakeLatencyLimit::InForceUs(device), kLimitUs);
}

}  // namespace
}  // namespace structloc::process
