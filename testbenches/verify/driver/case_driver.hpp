#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "description/receiver_description.hpp"
#include "driver/bound_ports.hpp"
#include "driver/dut_library.hpp"
#include "scoreboard/transaction_scoreboard.hpp"
#include "stimulus/verify_case.hpp"

namespace aesim {

// Every input of the receiver after a change at t_ps: the exact waveform of a run.
struct WaveRecord {
  std::uint64_t t_ps = 0;
  bool req = false, contention = false, ready = true, reset = false;
  std::uint64_t addr = 0;
};

// A beat the receiver gave (taken at a rising edge with valid and ready).
struct TakenBeat {
  std::uint64_t addr = 0, timestamp = 0, flags = 0;
  bool special = false;  // said it is no event: its fields mean nothing to aesim
};

struct CaseRunOptions {
  std::vector<WaveRecord>* waveform = nullptr;  // filled when set
  std::vector<TakenBeat>* beats = nullptr;
  bool trace = false;  // dump Verilator's trace (opened by the caller) on edges [trace_from, trace_to]
  std::uint64_t trace_from = 0, trace_to = 0;
};

struct CaseStats {
  std::uint64_t edges = 0, firings = 0, absorbed = 0;
  RtlEvent rtl;  // what the RTL itself did to end the case early, if anything
  std::string rtl_output;  // what it printed (bounded)
};

// The receiver's clock period in whole picoseconds, rounded to an even number.
std::uint64_t clock_period_ps(const ReceiverDescription& d);
// The output side's own clock in a case (ReceiverDescription::has_out_clock; zeros without one):
// its frequency (drawn from the description's range, if it gives one), its period in whole
// picoseconds, a multiple of 4 (its consumer changes a quarter period after each rising edge), and
// its first rising edge.
struct OutClock {
  double hz = 0;
  std::uint64_t period_ps = 0, first_rise_ps = 0;
};
OutClock out_clock_of(const ReceiverDescription& d, const VerifyCase& c);
// Rising edges the receiver spends in reset at the start of every case.
inline constexpr std::uint64_t kResetEdges = 4;

// Runs one case on a model from reset, in plain C++: the clock toggled and the model evaluated
// directly, rising edges at k * period, falling edges half a period later, inputs changing
// between edges (a bus change due exactly on an edge moves 1 ps later, as on the cycle rung's
// bus). The clock runs on every cycle: the receiver's own timestamp counter is state aesim
// cannot see, so no cycle may be skipped. The scoreboard (if any) sees every wire change and
// every edge. The case ends early when the RTL calls $finish, or judges itself ($stop, $error,
// $fatal, a failing assertion) or Verilator stops it: the scoreboard records the verdict.
CaseStats run_case(DutInstance& dut, const BoundPorts& ports, const ReceiverDescription& d, const VerifyCase& c,
                   TransactionScoreboard* scoreboard, const CaseRunOptions& options = {});

}  // namespace aesim
