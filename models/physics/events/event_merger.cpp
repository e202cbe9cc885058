#include "events/event_merger.hpp"

#include <algorithm>
#include <limits>

#include "containers/min_heap.hpp"

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
// heap of the tiles' heads into `chunk`, passing full chunks to `emit`.
template <typename T, typename Emit>
void merge_window(std::vector<std::vector<T>>& incoming, std::vector<std::vector<T>>& held, double before,
                  std::vector<T>& chunk, Emit emit) {
  auto less = [](const T& a, const T& b) { return key_of(a) < key_of(b); };
  struct Head {
    OrderKey key;
    std::size_t tile, pos, end;
  };
  struct Before {
    bool operator()(const Head& a, const Head& b) const { return a.key < b.key; }
  };
  std::vector<Head> heads;
  for (std::size_t i = 0; i < held.size(); ++i) {
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
    const std::size_t end = static_cast<std::size_t>(cut - h.begin());
    if (end > 0) heads.push_back({key_of(h[0]), i, 0, end});
  }
  MinHeap<Head, Before, 2> heap;
  heap.assign(std::move(heads));
  while (!heap.empty()) {
    Head h = heap.top();
    const std::vector<T>& part = held[h.tile];
    // Runs of one tile between the other tiles' heads are copied without going back to the heap.
    const OrderKey limit = heap.size() > 1 ? heap.runner_up().key : OrderKey{kNoLimit, 0};
    do {
      chunk.push_back(part[h.pos]);
      if (chunk.size() == kChunk) {
        emit(chunk);
        chunk.clear();
      }
      ++h.pos;
    } while (h.pos < h.end && key_of(part[h.pos]) < limit);
    if (h.pos < h.end) {
      h.key = key_of(part[h.pos]);
      heap.replace_top(h);
    } else {
      heap.pop();
    }
  }
  if (!chunk.empty()) {
    emit(chunk);
    chunk.clear();
  }
  for (std::size_t i = 0; i < held.size(); ++i) {
    std::vector<T>& h = held[i];
    const auto cut = std::partition_point(h.begin(), h.end(), [before](const T& r) { return time_of(r) < before; });
    h.erase(h.begin(), cut);
  }
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
