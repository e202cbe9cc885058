#include "merge_probe.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <limits>

#include "aesim/array/address_map.hpp"
#include "aesim/run/imager_simulation.hpp"

namespace aesim {

RecordedWindows record_windows(const ResolvedConfig& config, const Photocurrents& photocurrents, std::size_t windows) {
  EventCollector collected;
  SimulationRequest request;
  request.keep_events = true;
  request.stream = &collected;
  simulate(config, photocurrents, request);
  const std::vector<AddressEvent>& events = collected.events();
  const auto tiles = static_cast<std::size_t>(AddressMap(config.array).tiles());
  RecordedWindows r;
  r.events = events.size();
  const std::size_t per_window = (events.size() + windows - 1) / windows;
  for (std::size_t at = 0; at < events.size(); at += per_window) {
    const std::size_t end = std::min(events.size(), at + per_window);
    TileRecords batch(tiles);
    for (std::size_t i = at; i < end; ++i) batch.events[events[i].tile].push_back(TileEvent::of(events[i]));
    // Each tile's records come out of the merged stream in order, and a run's tiles say so as they
    // record (EventLog::fired_and_delivered): the merge takes them as sorted runs, as in a run.
    std::fill(batch.events_in_order.begin(), batch.events_in_order.end(), 1);
    r.windows.push_back(std::move(batch));
    r.before.push_back(end < events.size() ? events[end].t : events.back().t + 1);
  }
  return r;
}

std::uint64_t merge_probe(const RecordedWindows& recorded) {
  // A tournament tree of losers over the tiles (Knuth's replacement selection): each record
  // climbs one path of log2(tiles) matches, the least comparisons a k-way merge can do.
  struct Head {
    double t;
    std::uint64_t rest;  // tile << 32 | bus address: the order of equal times
    bool before(const Head& o) const { return t < o.t || (t == o.t && rest < o.rest); }
  };
  constexpr double kDone = std::numeric_limits<double>::infinity();
  std::vector<std::uint64_t> out;
  out.reserve(1 << 14);
  std::uint64_t made = 0;
  for (const TileRecords& w : recorded.windows) {
    const std::size_t k = w.events.size();
    std::size_t leaves = 1;
    while (leaves < k) leaves *= 2;
    std::vector<std::size_t> at(leaves, 0);
    const auto head = [&](std::size_t tile) {
      if (tile >= k || at[tile] >= w.events[tile].size()) return Head{kDone, ~std::uint64_t(0)};
      const TileEvent& e = w.events[tile][at[tile]];
      return Head{e.t, (std::uint64_t(tile) << 32) | (e.address_ghost & ~TileEvent::kGhostBit)};
    };
    // loser[node] for the inner nodes 1..leaves-1; the winner of the whole tree apart.
    std::vector<std::size_t> loser(leaves);
    std::vector<std::size_t> winner(2 * leaves);
    for (std::size_t i = 0; i < leaves; ++i) winner[leaves + i] = i;
    for (std::size_t node = leaves - 1; node >= 1; --node) {
      const std::size_t a = winner[2 * node], b = winner[2 * node + 1];
      const bool a_first = head(a).before(head(b)) || head(b).t == kDone;
      winner[node] = a_first ? a : b;
      loser[node] = a_first ? b : a;
    }
    std::size_t top = leaves > 1 ? winner[1] : 0;
    for (;;) {
      const Head h = head(top);
      if (h.t == kDone) break;
      out.push_back((h.rest << 32) | static_cast<std::uint32_t>(h.t * 1e6));
      if (out.size() == out.capacity()) {
        benchmark::DoNotOptimize(out.data());
        out.clear();
      }
      ++made;
      ++at[top];
      Head current = head(top);
      for (std::size_t node = (leaves + top) / 2; node >= 1; node /= 2) {
        const Head other = head(loser[node]);
        if (other.before(current)) {
          std::swap(top, loser[node]);
          current = other;
        }
      }
    }
  }
  benchmark::DoNotOptimize(out.data());
  return made;
}

}  // namespace aesim
