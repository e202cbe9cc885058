#include <algorithm>
#include <vector>

#include <fmt/format.h>

#include "commands.hpp"
#include "aesim/event_files/event_file.hpp"
#include "aesim/units/si_units.hpp"
#include "report_stream.hpp"

namespace aesim {

int info_command(const std::string& path, const std::string& layout) {
  const EventRecording rec = load_events(path, std::nullopt, layout);
  const std::size_t n = rec.events.size();
  const double span = n > 1 ? rec.events.back().t - rec.events.front().t : 0.0;
  std::vector<std::size_t> per_tile(static_cast<std::size_t>(std::max(rec.tiles, 1)), 0);
  std::size_t ghosts = 0, off = 0;
  for (const AddressEvent& e : rec.events) {
    if (e.tile < per_tile.size()) ++per_tile[e.tile];
    ghosts += (e.flags & kGhostEvent) ? 1 : 0;
    off += (e.flags & kOffEvent) ? 1 : 0;
  }
  fmt::print(report_stream(), "{}: {} events, array {}x{}{}, {} tile{}\n", path, n, rec.width, rec.height,
             rec.size_recorded ? "" : " (not recorded in the file: the span of its events)", rec.tiles,
             rec.tiles == 1 ? "" : "s");
  if (n > 0) {
    fmt::print(report_stream(), "  first {:.6f} s, last {:.6f} s, span {}\n", rec.events.front().t, rec.events.back().t,
               format_si(span, "s"));
  }
  if (span > 0) fmt::print(report_stream(), "  rate {}\n", format_si(static_cast<double>(n) / span, "events/s"));
  if (ghosts > 0) fmt::print(report_stream(), "  ghost events {}\n", ghosts);
  if (off > 0) fmt::print(report_stream(), "  OFF events {} (polarity as contrast: a recording of another tool's)\n", off);
  for (const std::string& s : rec.skipped) fmt::print(report_stream(), "  left out {}\n", s);
  for (const std::string& s : rec.read_as) fmt::print(report_stream(), "  read as {}\n", s);
  if (rec.reordered > 0) fmt::print(report_stream(), "  {} events stamped before the one ahead of them in the file, read in time order\n", rec.reordered);
  if (rec.stamp_wraps > 0) fmt::print(report_stream(), "  stamps wrapped past 2^32 us {} times, unwrapped\n", rec.stamp_wraps);
  for (std::size_t t = 0; t < per_tile.size() && n > 0; ++t) {
    fmt::print(report_stream(), "  tile {}: {} events ({:.1f} %){}\n", t, per_tile[t], 100.0 * per_tile[t] / n,
               span > 0 ? ", " + format_si(per_tile[t] / span, "events/s") : "");
  }
  return 0;
}

}  // namespace aesim
