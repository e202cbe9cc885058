#pragma once
#include <optional>
#include <string>
#include <vector>

#include "build/port_list.hpp"
#include "description/receiver_description.hpp"
#include "formal/formal_checker.hpp"
#include "scoreboard/stamp_rule.hpp"
#include "stimulus/verify_case.hpp"

namespace aesim {

struct FormalVerdict {
  std::string property, text;
  std::string verdict;  // "proved", "bounded" or "failed"
  int depth = 0;        // steps of the bounded check (0 for the structural check)
  double time_s = 0;
  std::optional<int> step;  // a failure's step (clock edges from the start)
  std::string detail;       // a failure's path or message
};

struct FormalResult {
  std::vector<FormalVerdict> verdicts;
  int depth = 0;
  std::string depth_reason, solver;
  std::vector<std::string> notes;
  bool cached = false;
  double seconds = 0;
  double property_seconds = 0;  // each property's budget (FormalOptions)
  // The first failed property's counterexample: its VCD (yosys-smtbmc's), and its inputs per step
  // for the simulation driver.
  std::string counterexample_vcd;
  std::string failed_property;
  std::vector<ReplayStep> replay;
  bool failed() const;
};

struct FormalOptions {
  std::string cache_dir;
  bool progress = true;
  double property_seconds = 20;  // a proof or bounded check past this is stopped
};

// The formal check of docs/reference.md section 6: the checker (formal_checker) and the team's RTL read by yosys
// (read_verilog -formal, -sv for .sv files), one AIGER model per property, each checked by ABC:
// a bounded check to the checker's depth (bmc3), then an unbounded proof (pdr); a counterexample
// simulated by yosys (sim) into a VCD; and a
// structural check on yosys's netlist that Req reaches the logic only through
// synchroniser_flops flops (an inverter or buffer before the first allowed). Two solver runs at a
// time; the result is cached under the hash of the checker, the sources and the tools. RTL yosys
// cannot read is an InputError naming yosys's first error.
FormalResult run_formal(const ReceiverDescription& d, const std::optional<StampRule::Candidate>& stamp,
                        const FormalOptions& options);

// The structural check alone, on a yosys JSON netlist of the flattened top: empty when Req passes
// `flops` flops before any logic reads it (an inverter, a buffer, or a multiplexer passing it as
// data may stand before a flop; logic whose only sinks are `unsynchronised_outputs` may read it),
// else the path that breaks the rule.
std::string synchroniser_path_violation(const std::string& netlist_json, const std::string& top, const PortRef& req,
                                        int flops, const std::vector<std::string>& unsynchronised_outputs = {});

// The inputs of a counterexample per step: ABC's AIGER witness (`write_cex -a`: the initial
// latches, then one line of inputs a frame) read through yosys's map of the AIGER inputs.
std::vector<ReplayStep> counterexample_inputs(const std::string& aim_text, const std::string& aiw_text);

}  // namespace aesim
