#include "aesim/units/si_units.hpp"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"

namespace aesim {
namespace {

struct Prefix {
  std::string_view symbol;
  double scale;
};

// Longest symbols first so that "da" is never needed and "u"/"µ" both mean micro.
constexpr Prefix kPrefixes[] = {
    {"\xC2\xB5", 1e-6}, {"y", 1e-24}, {"z", 1e-21}, {"a", 1e-18}, {"f", 1e-15},
    {"p", 1e-12},       {"n", 1e-9},  {"u", 1e-6},  {"m", 1e-3},  {"k", 1e3},
    {"M", 1e6},         {"G", 1e9},   {"T", 1e12},
};

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

bool ends_with(std::string_view s, std::string_view tail) {
  return s.size() >= tail.size() && s.substr(s.size() - tail.size()) == tail;
}

}  // namespace

double parse_si(std::string_view text, std::string_view unit, std::string_view what) {
  const std::string_view body = trim(text);
  auto fail = [&](const std::string& why) -> double {
    throw InputError(fmt::format("{}: {} (got '{}')", what, why, text));
  };
  if (body.empty()) return fail("empty value");
  const std::string buffer(body);
  errno = 0;
  char* end = nullptr;
  const double number = std::strtod(buffer.c_str(), &end);
  if (end == buffer.c_str()) return fail("not a number");
  if (errno == ERANGE || !std::isfinite(number)) return fail("number out of range");
  std::string_view rest = trim(std::string_view(buffer).substr(static_cast<size_t>(end - buffer.c_str())));

  const std::string_view with_unit = rest;
  // The unit is optional; strip it first so that e.g. "m" in "ms" is read as the prefix.
  if (!unit.empty() && ends_with(rest, unit)) rest.remove_suffix(unit.size());
  double scale = 1.0;
  if (!rest.empty()) {
    bool matched = false;
    for (const Prefix& p : kPrefixes) {
      if (rest == p.symbol) {
        scale = p.scale;
        matched = true;
        break;
      }
    }
    if (!matched) {
      if (unit.empty()) return fail("unexpected unit or suffix");
      // "100mhz", "10 KHz": the unit or its prefix in another case. Not taken as meant: m is milli,
      // M mega.
      const auto lower = [](std::string_view v) {
        std::string out(v);
        for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        return out;
      };
      const std::string r = lower(with_unit), u = lower(unit);
      if (r.size() >= u.size() && r.compare(r.size() - u.size(), u.size(), u) == 0) {
        return fail(fmt::format("expected a value in {} (units and their prefixes are case-sensitive: {}, with m milli, "
                                "M mega, k kilo, u micro)",
                                unit, unit));
      }
      return fail(fmt::format("expected a value in {}", unit));
    }
  }
  const double value = number * scale;
  if (!std::isfinite(value)) return fail("number out of range");
  return value;
}

std::string format_si(double value, std::string_view unit) {
  if (value == 0.0 || !std::isfinite(value)) return fmt::format("{:g} {}", value, unit);
  static constexpr Prefix kOut[] = {{"f", 1e-15}, {"p", 1e-12}, {"n", 1e-9}, {"u", 1e-6},
                                    {"m", 1e-3},  {"", 1.0},    {"k", 1e3},  {"M", 1e6},
                                    {"G", 1e9}};
  const double magnitude = std::fabs(value);
  const Prefix* chosen = &kOut[0];
  for (const Prefix& p : kOut) {
    if (magnitude >= p.scale * 0.9995) chosen = &p;
  }
  return fmt::format("{:.4g} {}{}", value / chosen->scale, chosen->symbol, unit);
}

}  // namespace aesim
