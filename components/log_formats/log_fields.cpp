// Log field parsing (see header).
#include "structloc/log_formats/log_fields.hpp"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <string>

namespace structloc::log_formats {

std::vector<std::string_view> SplitFields(std::string_view line) {
  std::vector<std::string_view> fields;
  size_t i = 0;
  const auto blank = [](char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
  };
  while (i < line.size()) {
    while (i < line.size() && blank(line[i])) ++i;
    const size_t start = i;
    while (i < line.size() && !blank(line[i])) ++i;
    if (i > start) fields.push_back(line.substr(start, i - start));
  }
  return fields;
}

std::optional<double> ParseReal(std::string_view token) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty() || token.front() == '+') return std::nullopt;
  const char* first = token.data();
  const char* last = token.data() + token.size();
  double value = 0.0;
  const auto [end, error] = std::from_chars(first, last, value, std::chars_format::general);
  if (end != last) return std::nullopt;
  if (error == std::errc::result_out_of_range) {
    // Beyond the double range: strtod gives +-HUGE_VAL (inf) or the underflowed value.
    return std::strtod(std::string(token).c_str(), nullptr);
  }
  if (error != std::errc()) return std::nullopt;
  return value;
}

std::optional<double> ParseFinite(std::string_view token) {
  const auto value = ParseReal(token);
  if (!value || !std::isfinite(*value)) return std::nullopt;
  return value;
}

std::optional<uint64_t> ParseCount(std::string_view token) {
  uint64_t value = 0;
  if (token.empty() || token.front() == '-' || token.front() == '+') return std::nullopt;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (error != std::errc() || end != token.data() + token.size()) return std::nullopt;
  return value;
}

std::optional<int64_t> ParseInteger(std::string_view token) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  int64_t value = 0;
  if (token.empty() || token.front() == '+') return std::nullopt;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (error != std::errc() || end != token.data() + token.size()) return std::nullopt;
  return value;
}

}  // namespace structloc::log_formats
