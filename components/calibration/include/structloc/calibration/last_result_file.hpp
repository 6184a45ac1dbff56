// The last published calibration result, kept in --out-dir as the CDR bytes
// it went out with (last_result.cdr), so that a restarted calibration
// component publishes it again: a TRANSIENT_LOCAL subscriber that joins after
// a restart still gets the newest result, as it would have before.
#pragma once

#include <optional>
#include <string>

#include "structloc_msgs/msg/CalibrationResultPubSubTypes.h"

namespace structloc::calibration {

inline constexpr const char* kLastResultFileName = "last_result.cdr";
// A result is a few kB; a larger file is refused naming this limit.
inline constexpr long long kMaxLastResultBytes = 1 << 20;

// Writes `result` to `path` atomically (config::OutputFile: a temporary file
// renamed over it);
// returns what went wrong, or "" when it was written.
std::string SaveLastResult(const std::string& path,
                           const structloc_msgs::msg::CalibrationResult& result);

// Reads a file SaveLastResult wrote. nullopt with `why` set when it is
// missing, larger than kMaxLastResultBytes, not a CalibrationResult in CDR,
// or holds a parameter, deviation or covariance that is not finite.
std::optional<structloc_msgs::msg::CalibrationResult> LoadLastResult(const std::string& path,
                                                                     std::string& why);

}  // namespace structloc::calibration
