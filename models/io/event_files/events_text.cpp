#include "aesim/event_files/events_text.hpp"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"

namespace aesim {
namespace {

// The longest stamp an event may carry, s: far past any recording, and well inside int64
// microseconds.
constexpr double kLatestSeconds = 1e12;
constexpr int kMostSide = 65535;
constexpr std::size_t kMostShown = 40;

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

}  // namespace aesim
