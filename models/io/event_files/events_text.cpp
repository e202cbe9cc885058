#include "aesim/event_files/events_text.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/event_files/event_stamps.hpp"
#include "aesim/text/ascii_case.hpp"

namespace aesim {
namespace {

// The longest stamp an event may carry, s: far past any recording, and well inside int64
// microseconds.
constexpr double kLatestSeconds = 1e12;
constexpr int kMostSide = 65535;
constexpr std::size_t kMostShown = 40;
constexpr std::size_t kMostColumns = 64;

// Blanks, and jAER's commas (its text writer's CSV option).
bool blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f' || c == ','; }

// The line's fields (at most `most` + 1, so that a line of too many is seen).
std::size_t split(std::string_view line, std::string_view* fields, std::size_t most) {
  std::size_t n = 0, at = 0;
  while (n <= most) {
    while (at < line.size() && blank(line[at])) ++at;
    if (at == line.size()) break;
    const std::size_t start = at;
    while (at < line.size() && !blank(line[at])) ++at;
    fields[n++] = line.substr(start, at - start);
  }
  return n;
}

// A whole number from 0 to `most`, the whole field.
bool whole(std::string_view field, int most, int& out) {
  long long v = 0;
  const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), v);
  if (ec != std::errc() || end != field.data() + field.size() || v < 0 || v > most) return false;
  out = static_cast<int>(v);
  return true;
}

std::string shown(std::string_view line) {
  std::string s(line.substr(0, kMostShown));
  while (!s.empty() && blank(s.back())) s.pop_back();
  for (char& c : s) {
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7F) c = '?';
  }
  return line.size() > kMostShown ? s + "..." : s;
}

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '"' || s.front() == '\'')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r' || s.back() == '"' || s.back() == '\'')) {
    s.remove_suffix(1);
  }
  return s;
}

std::vector<std::string_view> split_at(std::string_view line, char delimiter) {
  std::vector<std::string_view> out;
  std::size_t at = 0;
  while (out.size() <= kMostColumns) {
    const std::size_t end = line.find(delimiter, at);
    out.push_back(trimmed(line.substr(at, end == std::string_view::npos ? std::string_view::npos : end - at)));
    if (end == std::string_view::npos) break;
    at = end + 1;
  }
  return out;
}

// The time column's unit from its name: seconds per unit, or none when the name gives no unit.
std::optional<double> unit_of(const std::string& name, bool& is_time) {
  // "t [us]", "time(s)", "timestamp_us": the name, then its unit.
  std::string base = name, unit;
  if (const std::size_t open = name.find_first_of("[("); open != std::string::npos) {
    base = std::string(trimmed(name.substr(0, open)));
    unit = name.substr(open + 1);
    unit.erase(std::remove_if(unit.begin(), unit.end(), [](char c) { return c == ']' || c == ')' || c == ' '; }), unit.end());
  } else if (const std::size_t under = name.rfind('_'); under != std::string::npos) {
    const std::string suffix = name.substr(under + 1);
    if (suffix == "s" || suffix == "ms" || suffix == "us" || suffix == "ns" || suffix == "sec" || suffix == "usec") {
      base = name.substr(0, under);
      unit = suffix;
    }
  }
  is_time = base == "t" || base == "ts" || base == "time" || base == "timestamp" || base == "event_timestamp" ||
            base == "timestamps";
  if (unit == "s" || unit == "sec") return 1.0;
  if (unit == "ms") return 1e-3;
  if (unit == "us" || unit == "usec" || unit == "µs") return 1e-6;
  if (unit == "ns") return 1e-9;
  return std::nullopt;
}

}  // namespace

PolarityRecording decode_events_text(const std::string& data, const std::string& label) {
  PolarityRecording rec;
  // A UTF-8 byte order mark, as Windows editors begin a text file.
  std::size_t at = data.rfind("\xEF\xBB\xBF", 0) == 0 ? 3 : 0;
  std::size_t line_number = 0;
  // jAER's text writer says in its header when its stamps are whole microseconds.
  bool microseconds = false;
  std::string_view fields[6];
  const auto fail = [&](std::string_view line, const std::string& what) {
    throw InputError(fmt::format("event file '{}': line {} ('{}'): {}", label, line_number, shown(line), what));
  };
  while (at < data.size()) {
    std::size_t end = data.find('\n', at);
    if (end == std::string::npos) end = data.size();
    const std::string_view line(data.data() + at, end - at);
    at = end + 1;
    ++line_number;
    const std::size_t n = split(line, fields, 5);
    if (n == 0) continue;
    if (fields[0].front() == '#') {
      microseconds = microseconds || line.find("timestamp(int32 us)") != std::string_view::npos;
      continue;
    }
    // rpg_e2vid's size line comes before any event.
    if (n == 2 && rec.events.empty() && rec.width == 0) {
      if (!whole(fields[0], kMostSide, rec.width) || !whole(fields[1], kMostSide, rec.height) || rec.width == 0 ||
          rec.height == 0) {
        fail(line, "a line of two fields is rpg_e2vid's 'width height', two whole numbers from 1 to 65535");
      }
      continue;
    }
    if (n < 4 || n > 5) fail(line, "expected 't x y p': time in s, x, y, polarity (1 ON, 0 or -1 OFF)");
    PolarityEvent e;
    const char* const t_last = fields[0].data() + fields[0].size();
    if (microseconds) {
      const auto [t_end, t_ec] = std::from_chars(fields[0].data(), t_last, e.t_us);
      if (t_ec != std::errc() || t_end != t_last) fail(line, "the time is not a whole number of microseconds");
      if (e.t_us < 0) fail(line, "the time is negative");
    } else {
      double t = 0;
      const auto [t_end, t_ec] = std::from_chars(fields[0].data(), t_last, t);
      if (t_ec != std::errc() || t_end != t_last || !std::isfinite(t)) {
        fail(line, "the time is not a number of seconds");
      }
      if (t < 0 || t > kLatestSeconds) fail(line, fmt::format("the time is outside 0 to {:g} s", kLatestSeconds));
      e.t_us = std::llround(t * 1e6);
    }
    if (!whole(fields[1], kMostSide, e.x) || !whole(fields[2], kMostSide, e.y)) {
      fail(line, "x and y must be whole numbers from 0 to 65535");
    }
    if (fields[3] == "1") {
      e.on = true;
    } else if (fields[3] == "0" || fields[3] == "-1") {
      e.on = false;
    } else {
      fail(line, "the polarity must be 1 (ON), 0 or -1 (OFF)");
    }
    rec.events.push_back(e);
  }
  put_in_time_order(rec);
  return rec;
}

PolarityRecording decode_foreign_csv(const std::string& data, const std::string& label) {
  PolarityRecording rec;
  std::size_t at = data.rfind("\xEF\xBB\xBF", 0) == 0 ? 3 : 0;
  std::size_t line_number = 0;
  const auto fail = [&](std::string_view line, const std::string& what) {
    throw InputError(fmt::format("event file '{}': line {} ('{}'): {}", label, line_number, shown(line), what));
  };
  // Where each role's column is (x, y, polarity, time), and the time's unit when its name says.
  std::array<int, 4> column{-1, -1, -1, -1};
  std::optional<double> seconds_per_unit;
  char delimiter = ',';
  bool known_layout = false, headerless = false;
  std::string time_name;
  // The stamps as written, until the whole column says its unit.
  std::vector<double> stamps;
  UnnamedStampUnit unnamed;
  while (at < data.size()) {
    std::size_t end = data.find('\n', at);
    if (end == std::string::npos) end = data.size();
    const std::string_view line = trimmed(std::string_view(data).substr(at, end - at));
    at = end + 1;
    ++line_number;
    if (line.empty() || line.front() == '#') continue;
    if (line.front() == '%') {
      // Metavision's header lines: its geometry is the array's size.
      unsigned w = 0, h = 0;
      if (std::sscanf(std::string(line).c_str(), "%%geometry:%u,%u", &w, &h) == 2 && w >= 1 && h >= 1 && w <= kMostSide &&
          h <= kMostSide) {
        rec.width = static_cast<int>(w);
        rec.height = static_cast<int>(h);
      }
      continue;
    }
    if (!known_layout) {
      known_layout = true;
      const bool named = std::any_of(line.begin(), line.end(), [](char c) { return std::isalpha(static_cast<unsigned char>(c)); });
      if (named) {
        for (char d : {',', ';', '\t'}) {
          if (line.find(d) != std::string_view::npos) {
            delimiter = d;
            break;
          }
        }
        const std::vector<std::string_view> names = split_at(line, delimiter);
        if (names.size() > kMostColumns) fail(line, fmt::format("more than {} columns", kMostColumns));
        for (std::size_t i = 0; i < names.size(); ++i) {
          const std::string name = ascii_lower(std::string(names[i]));
          bool is_time = false;
          const std::optional<double> unit = unit_of(name, is_time);
          const int role = name == "x" ? 0 : name == "y" ? 1
                           : (name == "p" || name == "pol" || name == "polarity" || name == "on") ? 2
                           : is_time ? 3 : -1;
          if (role < 0) continue;
          if (column[role] >= 0) fail(line, fmt::format("two columns give the {}", role == 3 ? "time" : name));
          column[role] = static_cast<int>(i);
          if (role == 3) {
            seconds_per_unit = unit;
            time_name = std::string(names[i]);
          }
        }
        if (column[0] < 0 || column[1] < 0 || column[3] < 0) {
          fail(line, "a header naming the columns needs x, y and the time (t, ts, time or timestamp; its unit as t_us or "
                     "t [s]); the polarity (p, pol, polarity or on) is optional");
        }
        continue;
      }
      // No header: Metavision's rows, x, y, p and t in microseconds.
      column = {0, 1, 2, 3};
      seconds_per_unit = 1e-6;
      headerless = true;
    }
    const std::vector<std::string_view> fields = split_at(line, delimiter);
    const int needed = *std::max_element(column.begin(), column.end());
    if (static_cast<int>(fields.size()) <= needed) {
      fail(line, fmt::format("{} fields where the {} has {} or more", fields.size(),
                             headerless ? "x,y,p,t layout" : "header", needed + 1));
    }
    PolarityEvent e;
    for (int role = 0; role < 2; ++role) {
      const std::string_view f = fields[static_cast<std::size_t>(column[role])];
      int& v = role == 0 ? e.x : e.y;
      long long n = -1;
      const auto [end_x, ec] = std::from_chars(f.data(), f.data() + f.size(), n);
      if (ec != std::errc() || end_x != f.data() + f.size() || n < 0 || n > kMostSide) {
        fail(line, "x and y must be whole numbers from 0 to 65535");
      }
      v = static_cast<int>(n);
    }
    if (column[2] >= 0) {
      const std::string p = ascii_lower(std::string(fields[static_cast<std::size_t>(column[2])]));
      if (p == "1" || p == "true" || p == "on") {
        e.on = true;
      } else if (p == "0" || p == "-1" || p == "false" || p == "off") {
        e.on = false;
      } else {
        fail(line, headerless ? "the polarity (the third field of Metavision's x,y,p,t rows; a file of another order "
                                "needs a header naming its columns) must be 1 or 0"
                              : "the polarity must be 1, true or ON, or 0, -1, false or OFF");
      }
    }
    const std::string_view tf = fields[static_cast<std::size_t>(column[3])];
    double t = 0;
    const auto [t_end, t_ec] = std::from_chars(tf.data(), tf.data() + tf.size(), t);
    if (t_ec != std::errc() || t_end != tf.data() + tf.size() || !std::isfinite(t) || t < 0) {
      fail(line, "the time is not a number, 0 or more");
    }
    unnamed.see(t);
    stamps.push_back(t);
    rec.events.push_back(e);
  }
  for (std::size_t i = 0; i < stamps.size(); ++i) {
    const double seconds = seconds_per_unit ? stamps[i] * *seconds_per_unit : unnamed.seconds ? stamps[i] : stamps[i] * 1e-6;
    if (!(seconds <= kLatestSeconds)) {
      throw InputError(fmt::format("event file '{}': event {} is stamped {:g} s, past {:g} s", label, i, seconds, kLatestSeconds));
    }
    rec.events[i].t_us = seconds_per_unit ? std::llround(seconds * 1e6) : unnamed.microseconds(stamps[i]);
  }
  if (known_layout && !rec.events.empty()) {
    if (headerless) {
      rec.read_as.push_back("Metavision's CSV rows x,y,p,t, t in microseconds");
    } else if (seconds_per_unit) {
      const double u = *seconds_per_unit;
      rec.read_as.push_back(fmt::format("CSV columns by its header, time '{}' in {}", time_name,
                                        u == 1.0 ? "s" : u == 1e-3 ? "ms" : u == 1e-6 ? "us" : "ns"));
    } else {
      rec.read_as.push_back(fmt::format("CSV columns by its header, time '{}' in {} ({})", time_name,
                                        unnamed.seconds ? "s" : "us", unnamed.words()));
    }
  }
  put_in_time_order(rec);
  return rec;
}

}  // namespace aesim
