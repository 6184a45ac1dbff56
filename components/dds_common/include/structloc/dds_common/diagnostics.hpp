// Builds diagnostic_msgs/DiagnosticArray samples from a component's health
// report, so every component reports OK/WARN/ERROR and why the same way.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "diagnostic_msgs/msg/DiagnosticArray.h"

namespace structloc::dds_common {

enum class HealthLevel : uint8_t { kOk = 0, kWarn = 1, kError = 2, kStale = 3 };

struct HealthReport {
  HealthLevel level = HealthLevel::kOk;
  std::string message;
  std::vector<std::pair<std::string, std::string>> values;
};

// "OK", "WARN", "ERROR", "STALE" for log lines.
const char* ToString(HealthLevel level);

diagnostic_msgs::msg::DiagnosticArray ToDiagnosticArray(const std::string& component,
                                                        const HealthReport& report,
                                                        double stamp_seconds);

}  // namespace structloc::dds_common
