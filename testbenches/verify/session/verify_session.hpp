#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "build/port_list.hpp"
#include "description/receiver_description.hpp"
#include "driver/case_driver.hpp"
#include "driver/dut_library.hpp"
#include "scoreboard/transaction_scoreboard.hpp"
#include "stimulus/verify_case.hpp"

namespace aesim {

struct CaseSummary {
  std::string name, kind;
  std::uint64_t edges = 0, firings = 0, transactions = 0, beats = 0, failures = 0;
  std::string rtl_finish;  // where the RTL's $finish ended the case, if it did
  std::optional<VerifyFailure> first_failure;  // the case's own first
  double out_clock_hz = 0;  // the output's own clock in this case, where it has one
};

struct VerifyResult {
  std::uint64_t transactions = 0, beats_checked = 0, failures = 0, protocol_violations = 0, receiver_cycles = 0;
  std::uint64_t drops = 0;
  std::uint64_t special_beats = 0;  // beats that said they were no event (the `special` role)
  double run_seconds = 0;  // the cases alone, not the build
  std::optional<VerifyFailure> first_failure;
  std::vector<CaseSummary> cases;
  std::string stamp_rule;  // the rule the stamps followed (StampRule::describe)
  std::optional<StampRule::Candidate> stamp_edge;
  TransactionScoreboard::LatencySpan ack_rise, ack_fall;  // the Ack latencies seen (see the scoreboard)
  std::string rtl_output;  // what the RTL printed, per case (bounded)
  bool passed() const { return failures == 0; }
};

// The exact inputs and the beats of one case, for a testbench outside aesim.
struct ExportedRun {
  std::string case_name;
  std::vector<WaveRecord> waveform;
  std::vector<TakenBeat> beats;
  std::uint64_t end_ps = 0;
  OutClock out_clock;  // the output's own clock in the exported case, where it has one
};

struct VerifyOptions {
  bool progress = true;
  // Filled when set, from the first scene case with back-pressure (a consumer not always ready),
  // or the first scene case when there is none.
  ExportedRun* exported = nullptr;
  // A prefix cut from file names in the RTL's messages (the description's folder).
  std::string source_prefix;
  // Stamps held to this rule from the first beat (a replay), instead of inferring one.
  std::optional<StampRule::Candidate> stamp_rule;
};

// Runs every case on a fresh model from the library, with the transaction scoreboard.
VerifyResult verify_receiver(const DutLibrary& library, const std::vector<RtlPort>& ports,
                             const ReceiverDescription& d, const std::vector<VerifyCase>& cases,
                             const VerifyOptions& options);

// The case again, from reset, with Verilator's trace of every signal into `path` over the 64
// cycles before `cycle` and 16 after it.
void trace_failure(const DutLibrary& library, const std::vector<RtlPort>& ports, const ReceiverDescription& d,
                   const VerifyCase& c, std::uint64_t cycle, const std::string& path);

}  // namespace aesim
