#include "events/event_merger.hpp"

#include <algorithm>
#include <limits>


namespace aesim {
namespace {

// (time, tile, address) as a pair of numbers, so comparisons inline.
struct OrderKey {
  double t;
  std::uint64_t rest;  // tile << 32 | bus address
  bool operator<(const OrderKey& o) const { return (t < o.t) | ((t == o.t) & (rest < o.rest)); }
};
OrderKey key_of(const AddressEvent& e) { return {e.t, (std::uint64_t(e.tile) << 32) | e.bus_address}; }
OrderKey key_of(const TruthRecord& r) { return key_of(r.firing); }
double time_of(const AddressEvent& e) { return e.t; }
double time_of(const TruthRecord& r) { return r.firing.t; }

constexpr double kNoLimit = std::numeric_limits<double>::infinity();
constexpr std::size_t kChunk = 4096;  // records per call of the stream: a few pages, cache-resident

// Appends each tile's new records to those it holds, sorts them if needed (simultaneous SystemC
// processes may have run in any order; a stable sort keeps production order among equal keys, as a
// sort of the whole run would), and merges every tile's records earlier than `before` through a
// winner tree of the tiles' heads into `chunk`, passing full chunks to `emit`.
template <typename T, typename Emit>
void merge_window(std::vector<std::vector<T>>& incoming, std::vector<std::vector<T>>& held, double before,
                  std::vector<T>& chunk, Emit emit) {
  auto less = [](const T& a, const T& b) { return key_of(a) < key_of(b); };
  const std::size_t tiles = held.size();
  std::vector<std::size_t> pos(tiles, 0), end(tiles, 0);
  // A winner tree over the tiles' heads: a pop replays only the winner's path, one comparison a
  // level, with no records moved (a heap compares twice a level and moves its entries).
  std::size_t leaves = 1;
  while (leaves < tiles) leaves *= 2;
  std::vector<OrderKey> head(leaves, OrderKey{kNoLimit, ~std::uint64_t(0)});
  std::size_t live = 0;
  for (std::size_t i = 0; i < tiles; ++i) {
    std::vector<T>& h = held[i];
    std::vector<T>& in = incoming[i];
    if (h.empty()) {
      h.swap(in);
    } else {
      h.insert(h.end(), in.begin(), in.end());
      in.clear();
    }
    if (!std::is_sorted(h.begin(), h.end(), less)) std::stable_sort(h.begin(), h.end(), less);
    const auto cut = std::partition_point(h.begin(), h.end(), [before](const T& r) { return time_of(r) < before; });
    end[i] = static_cast<std::size_t>(cut - h.begin());
    if (end[i] > 0) {
      head[i] = key_of(h[0]);
      live += end[i];
    }
  }
  std::vector<std::uint32_t> tree(2 * leaves);
  for (std::size_t i = 0; i < leaves; ++i) tree[leaves + i] = static_cast<std::uint32_t>(i);
  auto better = [&](std::uint32_t a, std::uint32_t b) { return head[b] < head[a] ? b : a; };
  for (std::size_t n = leaves - 1; n >= 1; --n) tree[n] = better(tree[2 * n], tree[2 * n + 1]);
  for (; live > 0; --live) {
    const std::uint32_t w = tree[1];
    const std::vector<T>& part = held[w];
    chunk.push_back(part[pos[w]]);
    if (chunk.size() == kChunk) {
      emit(chunk);
      chunk.clear();
    }
    head[w] = ++pos[w] < end[w] ? key_of(part[pos[w]]) : OrderKey{kNoLimit, ~std::uint64_t(0)};
    for (std::size_t n = (leaves + w) / 2; n >= 1; n /= 2) tree[n] = better(tree[2 * n], tree[2 * n + 1]);
  }
  if (!chunk.empty()) {
    emit(chunk);
    chunk.clear();
  }
  for (std::size_t i = 0; i < tiles; ++i) held[i].erase(held[i].begin(), held[i].begin() + static_cast<std::ptrdiff_t>(end[i]));
}

}  // namespace

EventMerger::EventMerger(std::size_t tiles, EventStream& out) : events_(tiles), truth_(tiles), out_(out) {
  event_chunk_.reserve(kChunk);
  truth_chunk_.reserve(kChunk);
}

void EventMerger::merge(TileRecords& batch, double before) {
  merge_window(batch.events, events_, before, event_chunk_,
               [this](const std::vector<AddressEvent>& c) { out_.events(c.data(), c.size()); });
  merge_window(batch.truth, truth_, before, truth_chunk_,
               [this](const std::vector<TruthRecord>& c) { out_.truth(c.data(), c.size()); });
}

}  // namespace aesim
