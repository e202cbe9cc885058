#pragma once
#include <string>
#include <string_view>

namespace aesim {

// Parses a number with an optional SI prefix and an optional unit, e.g. "100fF", "1 pA",
// "2us", "50MHz", "1e-13". When `unit` is not empty, a unit written in the text must be that
// unit ("100pA" for a capacitance is rejected). Throws InputError naming `what`.
double parse_si(std::string_view text, std::string_view unit, std::string_view what);

// Formats a value with an engineering prefix for human summaries: 1e-13, "F" -> "100 fF".
std::string format_si(double value, std::string_view unit);

}  // namespace aesim
