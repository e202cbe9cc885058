#pragma once
#include <cstdint>

namespace aesim {

// The 4-phase handshake's rules on one tile's wires: Req rises only while Ack is low, Ack rises
// only while Req is high, Req falls only while Ack is high, Ack falls only while Req is low (one
// transaction at a time). Counted by whoever sees every change of both wires: the cycle rung's
// bus, which drives Req and reacts to each change of Ack anyway, so that checking them costs no
// process activation of its own.
class HandshakeRules {
 public:
  // Req became `req` while Ack held `ack`.
  void req_changed(bool req, bool ack) { violations_ += req == ack ? 1 : 0; }
  // Ack became `ack` while Req held `req`.
  void ack_changed(bool ack, bool req) { violations_ += ack != req ? 1 : 0; }
  std::uint64_t violations() const { return violations_; }

 private:
  std::uint64_t violations_ = 0;
};

}  // namespace aesim
