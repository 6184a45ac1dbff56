// HealthReport -> DiagnosticArray conversion.
#include "structloc/dds_common/diagnostics.hpp"

#include "structloc/dds_common/ros_conversions.hpp"

namespace structloc::dds_common {

const char* ToString(HealthLevel level) {
  switch (level) {
    case HealthLevel::kOk:
      return "OK";
    case HealthLevel::kWarn:
      return "WARN";
    case HealthLevel::kError:
      return "ERROR";
    case HealthLevel::kStale:
      return "STALE";
  }
  return "?";
}

diagnostic_msgs::msg::DiagnosticArray ToDiagnosticArray(const std::string& component,
                                                        const HealthReport& report,
                                                        double stamp_seconds) {
  diagnostic_msgs::msg::DiagnosticArray array;
  array.header().stamp(ToRosTime(stamp_seconds));
  diagnostic_msgs::msg::DiagnosticStatus status;
  status.level(static_cast<uint8_t>(report.level));
  status.name("structloc/" + component);
  status.message(report.message);
  status.hardware_id(component);
  for (const auto& [key, value] : report.values) {
    diagnostic_msgs::msg::KeyValue kv;
    kv.key(key);
    kv.value(value);
    status.values().push_back(kv);
  }
  array.status().push_back(status);
  return array;
}

}  // namespace structloc::dds_common
