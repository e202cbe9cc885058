#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

namespace aesim {

// The receiver's registers, one clock edge at a time: the cycle-exact reference for
// rtl/aer_receiver.v. Every decision at an edge uses the values held before it, as the RTL's
// nonblocking assignments do; outputs() are the register outputs after the last edge.
class ReceiverCycleModel {
 public:
  struct Config {
    int addr_width = 16;
    int ts_width = 32;
    unsigned capacity = 64;  // DEPTH of the RTL build
    bool hold_when_full = false;
    unsigned prescale = 1;     // clock cycles per timestamp tick (0 acts as 1)
    unsigned fifo_limit = 16;  // words that make the FIFO full (receiver.fifo_depth)
    bool discard_collisions = true;
    bool ts_external = false;
  };
  struct Inputs {
    bool req = false;
    std::uint32_t addr = 0;
    bool contention = false;
    bool ready = true;
    std::uint64_t ts = 0;  // used when ts_external
  };
  struct Beat {
    std::uint64_t ts = 0;
    std::uint32_t addr = 0;
    bool flags = false;
    bool operator==(const Beat& o) const { return ts == o.ts && addr == o.addr && flags == o.flags; }
  };
  struct Outputs {
    bool ack = false;
    bool valid = false;
    Beat beat;  // meaningful when valid
    std::uint64_t events = 0, collisions = 0, overflows = 0;
    unsigned fifo_count = 0;
    bool idle = true;
  };

  explicit ReceiverCycleModel(const Config& config);

  void reset();
  void clock(const Inputs& in);
  // The register outputs after the last edge (kept up to date by clock() and reset(), so that a
  // caller reading them after every edge copies nothing).
  const Outputs& outputs() const { return out_; }

 private:
  Config config_;
  std::uint64_t ts_mask_;
  std::uint32_t addr_mask_;
  unsigned prescale_;  // at least 1
  unsigned limit_;     // words that make the FIFO full: fifo_limit or capacity, the smaller
  bool s1_ = false, s2_ = false, s3_ = false;  // the Req synchronizer's three flops
  bool acking_ = false;
  std::uint64_t divider_ = 0, ts_ = 0;
  std::uint64_t events_ = 0, collisions_ = 0, overflows_ = 0;
  // The FIFO as a ring: it never holds more than limit_ words (a write needs room below it), so
  // that is its size.
  std::vector<Beat> ring_;
  unsigned head_ = 0, count_ = 0;
  Outputs out_;  // what the registers above show
  // In the header, so that clock() passes the counters it just wrote in registers: read back from
  // memory as a pair, they stalled on store forwarding.
  void update_outputs() {
    out_.ack = acking_;
    out_.valid = count_ != 0;
    const Beat none;
    const Beat& beat = out_.valid ? ring_[head_] : none;
    out_.beat.ts = beat.ts;
    out_.beat.addr = beat.addr;
    out_.beat.flags = beat.flags;
    out_.events = events_;
    out_.collisions = collisions_;
    out_.overflows = overflows_;
    out_.fifo_count = count_;
    out_.idle = !acking_ && !s1_ && !s2_ && !s3_ && count_ == 0;
  }
};

}  // namespace aesim
