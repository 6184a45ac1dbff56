// Strict text-to-number parsing shared by XML attributes and command-line
// options, so that every reader refuses the same things: leading or trailing
// text or spaces, hexadecimal ("0x10"), NaN, infinities, values that overflow
// their type, and integers written with a fraction or exponent. DDS-free.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace structloc::config {

// A finite decimal number ("-1.5", "2e-3", ".5"); nullopt for anything else.
std::optional<double> ParseFiniteDouble(const std::string& text);

// A decimal integer ("-12", "0", "42") that fits in long long; nullopt for
// anything else, including "1e3", "1.0", "+5", " 5" and "0x10".
std::optional<long long> ParseInteger(const std::string& text);

// Exactly `count` finite decimal numbers separated by spaces or tabs ("1.5 2 0.3");
// nullopt when there are fewer, more, or any token is not such a number.
std::optional<std::vector<double>> ParseNumberList(const std::string& text, size_t count);

}  // namespace structloc::config
