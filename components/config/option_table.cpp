// Number ranges of the option tables: membership and the wording used in
// messages and listings.
#include "structloc/config/option_table.hpp"

#include <cstdio>

namespace structloc::config {

std::string FormatNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.10g", value);
  return text;
}

bool Range::Contains(double value) const {
  if (!std::isfinite(value)) return false;
  if (magnitude) value = std::abs(value);
  if (min_open ? !(value > min) : !(value >= min)) return false;
  return max_open ? value < max : value <= max;
}

std::string Range::Describe() const {
  if (magnitude) return "magnitude " + Range{min, max, min_open, max_open, false}.Describe();
  const bool low = std::isfinite(min), high = std::isfinite(max);
  if (!low && !high) return "finite";
  if (!high) return std::string(min_open ? "> " : ">= ") + FormatNumber(min);
  if (!low) return std::string(max_open ? "< " : "<= ") + FormatNumber(max);
  return std::string("in ") + (min_open ? "(" : "[") + FormatNumber(min) + ", " +
         FormatNumber(max) + (max_open ? ")" : "]");
}

}  // namespace structloc::config
