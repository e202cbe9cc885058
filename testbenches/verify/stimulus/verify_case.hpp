#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace aesim {

// A pixel firing onto the bus: at t_ps it drives its address and Req.
struct Firing {
  std::uint64_t t_ps = 0;
  std::uint32_t addr = 0;
};

// Firings in time order.
class FiringSource {
 public:
  virtual ~FiringSource() = default;
  virtual bool next(Firing& f) = 0;
};

class ListedFirings : public FiringSource {
 public:
  explicit ListedFirings(std::vector<Firing> firings) : firings_(std::move(firings)) {}
  bool next(Firing& f) override {
    if (i_ == firings_.size()) return false;
    f = firings_[i_++];
    return true;
  }

 private:
  std::vector<Firing> firings_;
  std::size_t i_ = 0;
};

// Req driven high from from_ps to to_ps by no pixel at all: a glitch on the wire.
struct ReqGlitch {
  std::uint64_t from_ps = 0, to_ps = 0;
  std::uint32_t addr = 0;
};

// The bus and consumer as a formal counterexample drove them before one clock edge (replayed by
// the simulation driver instead of pixels).
struct ReplayStep {
  bool req = false, contention = false, ready = true;
  std::uint64_t addr = 0;
};

// One run of the receiver from reset: the firings, how the consumer of the output behaves, and
// any reset in the middle. Replayable: make_firings gives the same firings every time, so a
// failing case can be run again with a trace.
struct VerifyCase {
  std::string name;
  std::string kind;  // "directed" or "scene"
  std::function<std::unique_ptr<FiringSource>()> make_firings;
  // ALOHA pixels (false): a firing while Ack is high is absorbed, firings before the latch
  // collide. A queue of senders (true): a firing waits for an idle bus (Req and Ack low) and
  // drives alone, so transactions follow each other back to back.
  bool queued_senders = false;
  std::vector<ReqGlitch> glitches;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> stalls;  // ready low on edges [first, second)
  double ready_probability = 1;  // else ready at each edge with this probability
  std::uint64_t seed = 1;
  // Reset asserted reset_delay edges after the reset_after_ack-th Ack rise (0: never), for
  // reset_edges edges.
  int reset_after_ack = 0, reset_delay = 0, reset_edges = 0;
  std::vector<ReplayStep> replay;  // when set, the inputs before edge k+1 are replay[k] (no pixels)
  std::uint64_t max_edges = 0;  // the run's bound (the drain included)
  double expected_firings = 0;  // for the work estimate
};

}  // namespace aesim
