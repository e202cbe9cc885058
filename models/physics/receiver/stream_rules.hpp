#pragma once
#include <cstdint>

namespace aesim {

// What a receiver's stream and status outputs show at one moment.
struct StreamView {
  bool rst_n = true;
  bool valid = false, ready = false, flags = false;
  std::uint32_t ts = 0, addr = 0;
  std::uint32_t events = 0, fifo_count = 0, fifo_limit = 0;
  bool counters = true;  // events and fifo_count are driven
};

// The rules of a receiver's event stream, checked at every rising clock edge:
//  - while valid is high and ready low, the beat (timestamp, address, flags) must not change and
//    valid must not fall;
//  - nothing vanishes: events written equal beats taken plus words still in the FIFO, and the
//    FIFO never holds more than its limit (where the receiver drives those counters).
// The outputs are registered, so what they hold after an edge they still hold at the next rising
// edge (or when the run ends, the clock stopped): each edge checks the last edge's outputs, then
// latches this edge's inputs. Shared by the SystemC monitor (receiver/stream_monitor) and the
// reference receiver's clock domain (receiver/reference_clock_domain).
class StreamRules {
 public:
  // A rising edge; `before` is what the outputs held before it. Inline, as are the rules: run
  // at every edge of every tile.
  void edge(const StreamView& before) {
    if (pending_) violations_ += broken(before);
    pending_ = false;
    if (!before.rst_n) {
      taken_ = 0;
      stalled_ = false;
      return;
    }
    pending_ = true;
    // A beat offered and not taken must be offered again, unchanged.
    if (before.valid && before.ready) ++taken_;
    stalled_ = before.valid && !before.ready;
    held_ts_ = before.ts;
    held_addr_ = before.addr;
    held_flags_ = before.flags;
  }
  // Rule breaks so far, the last edge's outputs (`now`) included.
  std::uint64_t violations(const StreamView& now) const { return violations_ + (pending_ ? broken(now) : 0); }

 private:
  // Rules the outputs break now, after the last edge.
  unsigned broken(const StreamView& now) const {
    if (!now.rst_n) return 0;
    unsigned n = 0;
    if (stalled_ && (!now.valid || now.ts != held_ts_ || now.addr != held_addr_ || now.flags != held_flags_)) ++n;
    if (now.counters && now.events != taken_ + now.fifo_count) ++n;
    if (now.counters && now.fifo_count > now.fifo_limit) ++n;
    return n;
  }

  bool stalled_ = false;
  bool pending_ = false;  // an edge's outputs not yet checked
  std::uint32_t held_ts_ = 0, held_addr_ = 0;
  bool held_flags_ = false;
  std::uint64_t taken_ = 0, violations_ = 0;
};

}  // namespace aesim
