// Strict reading of the whitespace-separated fields of one log line: a number
// is the whole token in decimal (no hex, no trailing text), and a count is an
// unsigned integer token, so that "0.000000" is never read as a count of 0
// followed by a stray ".000000". DDS-free.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

namespace structloc::log_formats {

// The fields of `line`, split at spaces, tabs and carriage returns.
std::vector<std::string_view> SplitFields(std::string_view line);

// A decimal floating-point token, including nan and inf; values beyond the
// double range (1e400) become +-inf. nullopt when the token is not a number.
std::optional<double> ParseReal(std::string_view token);

// ParseReal, and finite.
std::optional<double> ParseFinite(std::string_view token);

// An unsigned decimal integer token (digits only) that fits in uint64_t.
std::optional<uint64_t> ParseCount(std::string_view token);

// A signed decimal integer token that fits in int64_t.
std::optional<int64_t> ParseInteger(std::string_view token);

}  // namespace structloc::log_formats
