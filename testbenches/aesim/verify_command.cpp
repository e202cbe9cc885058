#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "build/dut_build.hpp"
#include "build/vhdl_conversion.hpp"
#include "commands.hpp"
#include "description/receiver_description.hpp"
#include "driver/bound_ports.hpp"
#include "aesim/errors/input_error.hpp"
#include "export/testbench_export.hpp"
#include "formal/formal_run.hpp"
#include "aesim/output/atomic_file.hpp"
#include "plan/verification_plan.hpp"
#include "report/failure_hint.hpp"
#include "report/verify_report.hpp"
#include "session/verify_session.hpp"
#include "report_stream.hpp"

namespace aesim {

int verify_command(const VerifyCommandOptions& opt) {
  const auto start = std::chrono::steady_clock::now();
  const ReceiverDescription written = read_receiver_description(opt.description);
  const std::string report_path = opt.out + "/verify.json", vcd_path = opt.out + "/failure.vcd";
  std::vector<OutputPath> outputs = {{"--out", report_path}};
  if (!opt.export_tb.empty()) outputs.push_back({"--export-tb", opt.export_tb + "/tb.v"});
  std::vector<std::string> inputs = written.sources;
  inputs.push_back(written.file);
  check_output_paths(outputs, inputs);
  // From here on a VHDL design is the Verilog GHDL makes of it.
  const ReceiverDescription d = with_vhdl_as_verilog(written, default_cache_dir());

  const VerificationPlan plan = make_plan(opt.plan);
  std::vector<std::string> notes;
  const std::vector<VerifyCase> cases = plan_cases(plan, d, opt.seed, &notes);
  const double cycles = plan_cycles(cases);
  if (cycles > kMaxPlanCycles) {
    throw InputError(fmt::format("--plan {}: asks for up to {:.3g} receiver clock cycles, more than the {:.0e} aesim "
                                 "runs in one command (hours); use fewer firings or seeds",
                                 opt.plan, cycles, kMaxPlanCycles));
  }
  if (!opt.export_tb.empty() && std::none_of(cases.begin(), cases.end(), [](const VerifyCase& c) { return c.kind == "scene"; })) {
    throw InputError("--export-tb: the plan has no scene run to export");
  }

  DutBuildOptions build_options;
  build_options.cache_dir = default_cache_dir();
  build_options.log_dir = opt.out;
  build_options.allow_system_tasks = opt.allow_system_tasks;
  const DutBuild build = build_dut(d, build_options);
  check_ports(d, build.ports, kVerifyBusBits);
  const DutLibrary library(build.library);
  if (d.sources != written.sources) notes.push_back("the VHDL as GHDL synthesised it: " + d.sources.back());
  const std::vector<std::string> held = inputs_held_at_zero(d, build.ports);
  if (!held.empty()) {
    std::string names;
    for (const std::string& h : held) names += (names.empty() ? "" : ", ") + h;
    notes.push_back(fmt::format("input{} {} held at 0 throughout (no role, not in [inputs])", held.size() > 1 ? "s" : "", names));
  }

  std::fprintf(stderr, "aesim verify: %s (%s), plan %s, %zu cases, seed %llu\n", d.top.c_str(),
               build.cached ? "cached model" : fmt::format("built in {:.1f} s", build.seconds).c_str(),
               plan.name.c_str(), cases.size(), static_cast<unsigned long long>(opt.seed));
  for (const std::string& note : notes) std::fprintf(stderr, "aesim verify: %s\n", note.c_str());
  VerifyOptions options;
  options.source_prefix = std::filesystem::absolute(d.file).parent_path().string() + "/";
  ExportedRun exported;
  if (!opt.export_tb.empty()) options.exported = &exported;
  VerifyResult result = verify_receiver(library, build.ports, d, cases, options);
  if (result.first_failure) result.first_failure->hint = failure_hint(*result.first_failure, d, held);

  // The formal check, after the simulation (whose stamp rule it asserts). RTL yosys cannot read is
  // bad input: the report still says what the simulation found, then the one-line error.
  std::optional<FormalResult> formal;
  std::string formal_error, replay_text;
  if (opt.formal || plan.formal) {
    FormalOptions fo;
    fo.cache_dir = build_options.cache_dir;
    fo.property_seconds = opt.formal_seconds;
    try {
      ReceiverDescription proof = vhdl_for_the_proof(written, d, default_cache_dir());
      const bool resynthesised = proof.sources != d.sources;
      if (!d.formal.sources.empty()) proof.sources = d.formal.sources;
      formal = run_formal(proof, result.stamp_edge, fo);
      if (!d.formal.sources.empty()) {
        std::string names;
        for (const std::string& s : d.formal.sources) names += (names.empty() ? "" : ", ") + std::filesystem::path(s).filename().string();
        formal->notes.push_back("the proof read [formal] sources in place of sources: " + names);
      } else if (resynthesised) {
        formal->notes.push_back("the VHDL the proof ran, synthesised with [formal] parameters: " + proof.sources.back());
      }
    } catch (const InputError& e) {
      formal_error = e.what();
    }
    if (formal && !formal->replay.empty()) {
      // The counterexample's inputs through the simulation driver and the scoreboard.
      VerifyCase replay;
      replay.name = "formal counterexample (" + formal->failed_property + ")";
      replay.kind = "replay";
      replay.replay = formal->replay;
      // The checker declares a consumer's ready input whatever the design; without a ready port
      // it reads none, so the solver's values for it are no stall.
      if (!d.has("ready")) {
        for (ReplayStep& step : replay.replay) step.ready = true;
      }
      replay.max_edges = formal->replay.size() + 2 * static_cast<std::uint64_t>(d.ack_latency_max) + 40;
      VerifyOptions ro;
      ro.progress = false;
      ro.source_prefix = options.source_prefix;
      ro.stamp_rule = result.stamp_edge;
      const VerifyResult again = verify_receiver(library, build.ports, d, {replay}, ro);
      if (again.first_failure) {
        const VerifyFailure& f = *again.first_failure;
        replay_text = fmt::format("the simulation driver, replaying the counterexample's inputs, reports {} at cycle {}: "
                                  "expected {}, observed {}",
                                  f.check, f.cycle, f.expected, f.observed);
      } else {
        replay_text = "the simulation driver, replaying the counterexample's inputs, finds no failure: the proof starts "
                      "flops without a reset at any value where Verilator starts them at 0, its checker follows one "
                      "transaction the solver picked where the scoreboard follows them all, and under \"hold\" the "
                      "scoreboard excuses an Ack's wait from the edge where the consumer stalls, the proof from the "
                      "edge after it";
      }
    }
  }

  OutputFiles files;
  if (result.first_failure) {
    // The failing case again on the traced build of the same RTL (built now, cached too).
    DutBuildOptions traced = build_options;
    traced.trace = true;
    const DutBuild traced_build = build_dut(d, traced);
    const DutLibrary traced_library(traced_build.library);
    const std::string temp = files.adopt(vcd_path);
    for (const VerifyCase& c : cases) {
      if (c.name == result.first_failure->case_name) {
        trace_failure(traced_library, traced_build.ports, d, c, result.first_failure->cycle, temp);
        break;
      }
    }
  }
  if (!opt.export_tb.empty()) write_testbench(opt.export_tb, d, build.ports, exported, files);
  const std::string rtl_log = opt.out + "/rtl_output.log";
  if (!result.rtl_output.empty()) files.open(rtl_log) << result.rtl_output;
  for (const CaseSummary& c : result.cases) {
    if (!c.rtl_finish.empty()) notes.push_back(fmt::format("the RTL's $finish at {} ended case '{}'", c.rtl_finish, c.name));
  }
  // Verilator's "%Warning: map.hex:0: $readmem file not found": the RTL ran without its table.
  if (result.rtl_output.find("$readmem file not found") != std::string::npos) {
    notes.push_back(fmt::format("the RTL's $readmem found no file ({}); the RTL reads relative names from the "
                                "description's folder, {}",
                                rtl_log, std::filesystem::absolute(d.file).parent_path().string()));
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::string formal_vcd = opt.out + "/formal_failure.vcd";
  if (formal && !formal->counterexample_vcd.empty()) files.open(formal_vcd) << formal->counterexample_vcd;
  nlohmann::json report = verify_report(d, opt.plan, opt.seed, build, result, notes, wall);
  if (formal) add_formal_report(report, *formal, formal->counterexample_vcd.empty() ? "" : formal_vcd, replay_text);
  if (!formal_error.empty()) report["formal_error"] = formal_error;
  files.open(report_path) << report.dump(2) << "\n";
  files.commit();
  // A stale trace or log of an earlier run would mislead.
  std::error_code ec;
  if (!result.first_failure) std::filesystem::remove(vcd_path, ec);
  if (result.rtl_output.empty()) std::filesystem::remove(rtl_log, ec);
  if (!formal || formal->counterexample_vcd.empty()) std::filesystem::remove(formal_vcd, ec);

  std::fprintf(report_stream(), "%s: %llu transactions, %llu beats checked, %llu receiver cycles in %.2f s (%.3g cycles/s)\n",
              result.passed() ? "PASS" : "FAIL", static_cast<unsigned long long>(result.transactions),
              static_cast<unsigned long long>(result.beats_checked),
              static_cast<unsigned long long>(result.receiver_cycles), result.run_seconds,
              result.run_seconds > 0 ? static_cast<double>(result.receiver_cycles) / result.run_seconds : 0.0);
  if (result.first_failure) {
    const VerifyFailure& f = *result.first_failure;
    std::fprintf(report_stream(), "first failure: %s in case '%s' at cycle %llu (%.9f s): expected %s, observed %s\n", f.check.c_str(),
                f.case_name.c_str(), static_cast<unsigned long long>(f.cycle), f.time_s, f.expected.c_str(),
                f.observed.c_str());
    std::fprintf(report_stream(), "%llu failed checks (%llu protocol violations); trace: %s\n",
                static_cast<unsigned long long>(result.failures),
                static_cast<unsigned long long>(result.protocol_violations), vcd_path.c_str());
    if (!f.hint.empty()) std::fprintf(report_stream(), "hint: %s\n", f.hint.c_str());
  }
  if (!result.stamp_rule.empty()) std::fprintf(report_stream(), "stamps: %s\n", result.stamp_rule.c_str());
  if (result.ack_rise.count > 0 || result.ack_fall.count > 0) {
    const auto span = [](const TransactionScoreboard::LatencySpan& s) {
      if (s.count == 0) return std::string("none seen");
      return s.min == s.max ? fmt::format("{} edges", s.min) : fmt::format("{} to {} edges", s.min, s.max);
    };
    if (d.two_phase()) {
      std::fprintf(report_stream(), "Ack latency seen: %s from a change of Req to Ack's (without a full output); described %d to %d\n",
                   span(result.ack_rise).c_str(), d.ack_latency_min, d.ack_latency_max);
    } else {
      std::fprintf(report_stream(), "Ack latency seen: rise %s (without a full output), fall %s; described %d to %d\n",
                   span(result.ack_rise).c_str(), span(result.ack_fall).c_str(), d.ack_latency_min,
                   d.ack_latency_max);
    }
  }
  for (const std::string& note : notes) {
    if (note.find("$finish") != std::string::npos || note.find("$readmem") != std::string::npos) {
      std::fprintf(report_stream(), "note: %s\n", note.c_str());
    }
  }
  if (!result.rtl_output.empty()) std::fprintf(report_stream(), "the RTL's own output: %s\n", rtl_log.c_str());
  if (formal) {
    std::map<std::string, int> count;
    // A bounded check its time limit stopped reaches fewer steps than the depth set.
    int shallowest = formal->depth, deepest = 0;
    for (const FormalVerdict& v : formal->verdicts) {
      ++count[v.verdict];
      if (v.verdict != "bounded") continue;
      shallowest = std::min(shallowest, v.depth);
      deepest = std::max(deepest, v.depth);
    }
    const std::string reach = shallowest == formal->depth ? fmt::format("to {} steps", formal->depth)
                              : shallowest == deepest    ? fmt::format("to {} of {} steps", shallowest, formal->depth)
                                                          : fmt::format("to {}-{} of {} steps", shallowest, deepest, formal->depth);
    std::fprintf(report_stream(), "formal: %zu properties: %d proved, %d bounded %s, %d failed (%.1f s%s)\n", formal->verdicts.size(),
                count["proved"], count["bounded"], reach.c_str(), count["failed"], formal->seconds, formal->cached ? ", cached" : "");
    for (const std::string& note : formal->notes) std::fprintf(report_stream(), "formal note: %s\n", note.c_str());
    for (const FormalVerdict& v : formal->verdicts) {
      if (v.verdict == "failed") {
        std::fprintf(report_stream(), "formal failure: %s (%s)%s%s\n", v.property.c_str(), v.text.c_str(), v.detail.empty() ? "" : ": ",
                    v.detail.c_str());
      }
    }
    if (!formal->counterexample_vcd.empty()) std::fprintf(report_stream(), "counterexample: %s; %s\n", formal_vcd.c_str(), replay_text.c_str());
  }
  std::fprintf(report_stream(), "wrote %s%s\n", report_path.c_str(), opt.export_tb.empty() ? "" : (", " + opt.export_tb + "/tb.v").c_str());
  if (!formal_error.empty()) throw InputError(formal_error);
  return result.passed() && !(formal && formal->failed()) ? 0 : 1;
}

}  // namespace aesim
