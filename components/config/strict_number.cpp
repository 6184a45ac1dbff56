// Strict number parsing (see header).
#include "structloc/config/strict_number.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace structloc::config {
namespace {

// Only the characters of a decimal number: strtod alone would also take
// leading spaces, "0x10", "inf" and "nan".
bool DecimalCharactersOnly(const std::string& text) {
  if (text.empty()) return false;
  for (const char c : text) {
    const bool allowed =
        (c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.' || c == 'e' || c == 'E';
    if (!allowed) return false;
  }
  return true;
}

}  // namespace

std::optional<double> ParseFiniteDouble(const std::string& text) {
  if (!DecimalCharactersOnly(text)) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(value)) {
    return std::nullopt;
  }
  return value;
}

std::optional<long long> ParseInteger(const std::string& text) {
  const size_t digits_from = !text.empty() && text[0] == '-' ? 1 : 0;
  if (text.size() == digits_from) return std::nullopt;
  for (size_t i = digits_from; i < text.size(); ++i) {
    if (text[i] < '0' || text[i] > '9') return std::nullopt;
  }
  errno = 0;
  const long long value = std::strtoll(text.c_str(), nullptr, 10);
  if (errno == ERANGE) return std::nullopt;
  return value;
}

std::optional<std::vector<double>> ParseNumberList(const std::string& text, size_t count) {
  std::istringstream in(text);
  std::vector<double> values;
  std::string token;
  while (in >> token) {
    const auto value = ParseFiniteDouble(token);
    if (!value || values.size() == count) return std::nullopt;
    values.push_back(*value);
  }
  if (values.size() != count) return std::nullopt;
  return values;
}

}  // namespace structloc::config
