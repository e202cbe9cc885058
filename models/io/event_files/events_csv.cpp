#include "aesim/event_files/events_csv.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <sstream>

#include <fmt/compile.h>
#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/limits/limits.hpp"
#include "aesim/files/input_path.hpp"
#include "aesim/events/timestamps.hpp"

namespace aesim {

void write_events_csv(std::ostream& out, const std::vector<AddressEvent>& events, double tick) {
  EventsCsvWriter writer(out, tick);
  writer.events(events.data(), events.size());
}

EventsCsvWriter::EventsCsvWriter(std::ostream& out, double tick)
    : out_(out), tick_(tick), decimals_(std::max(0, static_cast<int>(std::ceil(-std::log10(tick / 1e-6) - 1e-9)))) {
  for (int i = 0; i < decimals_; ++i) scale_ *= 10;
  const double units = tick / 1e-6 * static_cast<double>(scale_);
  const double whole = std::nearbyint(units);
  if (decimals_ <= 12 && whole >= 1 && std::fabs(units - whole) < 1e-9 * whole) step_ = static_cast<std::uint64_t>(whole);
  buffer_ = "t_us,x,y,tile,flags\n";
}

EventsCsvWriter::~EventsCsvWriter() { flush(); }

void EventsCsvWriter::events(const AddressEvent* first, std::size_t count) {
  auto out = std::back_inserter(buffer_);
  for (const AddressEvent* e = first; e != first + count; ++e) {
    const std::uint64_t ticks = timestamp_ticks(e->t, tick_);
    if (step_ == 0) {
      const double t_us = static_cast<double>(ticks) * (tick_ / 1e-6);
      fmt::format_to(out, FMT_COMPILE("{:.{}f}"), t_us, decimals_);
    } else if (decimals_ == 0) {
      fmt::format_to(out, FMT_COMPILE("{}"), ticks * step_);
    } else {
      const std::uint64_t v = ticks * step_;
      fmt::format_to(out, FMT_COMPILE("{}.{:0{}}"), v / scale_, v % scale_, decimals_);
    }
    fmt::format_to(out, FMT_COMPILE(",{},{},{},{}\n"), e->x, e->y, e->tile, static_cast<unsigned>(e->flags));
    if (buffer_.size() > (1u << 16)) flush();
  }
}

void EventsCsvWriter::flush() {
  out_ << buffer_;
  buffer_.clear();
}

std::vector<AddressEvent> read_events_csv(const std::string& path) {
  require_input_file(path, "event file");
  std::ifstream in(path);
  return parse_events_csv(in, path);
}

std::vector<AddressEvent> parse_events_csv(std::istream& in, const std::string& path) {
  std::string line;
  if (!std::getline(in, line) || (line != "t_us,x,y,tile,flags" && line != "t_us,x,y,tile,flags\r")) {
    throw InputError(fmt::format("event file '{}': first line must be t_us,x,y,tile,flags", path));
  }
  std::vector<AddressEvent> events;
  std::size_t number = 1;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty() || line == "\r") continue;
    std::istringstream fields(line);
    AddressEvent e;
    double t_us = 0;
    long long x = -1, y = -1, tile = -1, flags = -1;
    char c1 = 0, c2 = 0, c3 = 0, c4 = 0;
    if (!(fields >> t_us >> c1 >> x >> c2 >> y >> c3 >> tile >> c4 >> flags) || c1 != ',' || c2 != ',' ||
        c3 != ',' || c4 != ',' || !std::isfinite(t_us) || t_us < 0 || x < 0 || y < 0 || tile < 0 ||
        flags < 0 || flags > 1 || x > 0xFFFF || y > 0xFFFF || tile > 0xFFFFFF) {
      throw InputError(fmt::format("event file '{}': malformed line {}", path, number));
    }
    if (t_us > 1e15) throw InputError(fmt::format("event file '{}': line {}: t_us {} is past 1e15 (31 years)", path, number, t_us));
    if (tile >= kMaxTiles) {
      throw InputError(fmt::format("event file '{}': line {}: tile {} is past the {} tiles aesim handles", path, number, tile, kMaxTiles));
    }
    e.t = t_us * 1e-6;
    e.x = static_cast<std::uint32_t>(x);
    e.y = static_cast<std::uint32_t>(y);
    e.tile = static_cast<std::uint32_t>(tile);
    e.flags = static_cast<std::uint8_t>(flags);
    if (!events.empty() && e.t < events.back().t) {
      throw InputError(fmt::format("event file '{}': timestamps decrease at line {}", path, number));
    }
    events.push_back(e);
  }
  return events;
}

}  // namespace aesim
