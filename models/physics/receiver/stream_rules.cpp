#include "receiver/stream_rules.hpp"

namespace aesim {

void StreamRules::edge(const StreamView& before) {
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

unsigned StreamRules::broken(const StreamView& now) const {
  if (!now.rst_n) return 0;
  unsigned n = 0;
  if (stalled_ && (!now.valid || now.ts != held_ts_ || now.addr != held_addr_ || now.flags != held_flags_)) ++n;
  if (now.events != taken_ + now.fifo_count) ++n;
  if (now.fifo_count > now.fifo_limit) ++n;
  return n;
}

}  // namespace aesim
