#include "session/verify_session.hpp"

#include <chrono>
#include <cstdio>
#include <filesystem>

#include <fmt/format.h>

#include "driver/bound_ports.hpp"
#include "driver/rtl_working_folder.hpp"

namespace aesim {
void trace_failure(const DutLibrary& library, const std::vector<RtlPort>& ports, const ReceiverDescription& d,
                   const VerifyCase& c, std::uint64_t cycle, const std::string& path) {
  const std::string trace = std::filesystem::absolute(path).string();
  const RtlWorkingFolder folder(d.file);
  DutInstance dut(library, true);
  if (!dut.open_trace(trace)) return;
  const BoundPorts bound = bind_ports(dut, d, ports);
  CaseRunOptions o;
  o.trace = true;
  o.trace_from = cycle > 64 ? cycle - 64 : 0;
  o.trace_to = cycle + 16;
  VerifyCase limited = c;
  limited.max_edges = std::min(c.max_edges, cycle + 16);
  run_case(dut, bound, d, limited, nullptr, o);
}

VerifyResult verify_receiver(const DutLibrary& library, const std::vector<RtlPort>& ports, const ReceiverDescription& d,
                             const std::vector<VerifyCase>& cases, const VerifyOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const RtlWorkingFolder folder(d.file);
  TransactionScoreboard sb(d, d.has("overflow_count"),
                           d.has("overflow_count") ? find_port(ports, d.port("overflow_count"))->width : 0);
  if (options.stamp_rule) sb.hold_stamps_to(*options.stamp_rule);
  VerifyResult r;
  const VerifyCase* to_export = nullptr;
  for (const VerifyCase& c : cases) {
    if (c.kind != "scene" || !options.exported) continue;
    if (!to_export || (to_export->ready_probability >= 1 && c.ready_probability < 1)) to_export = &c;
  }
  auto shorten = [&](std::string text) {
    if (options.source_prefix.empty()) return text;
    for (std::size_t at; (at = text.find(options.source_prefix)) != std::string::npos;) text.erase(at, options.source_prefix.size());
    return text;
  };
  for (const VerifyCase& c : cases) {
    DutInstance dut(library, false);
    const BoundPorts bound = bind_ports(dut, d, ports);
    CaseRunOptions o;
    const bool export_this = &c == to_export;
    if (export_this) {
      o.waveform = &options.exported->waveform;
      o.beats = &options.exported->beats;
      options.exported->case_name = c.name;
      options.exported->out_clock = out_clock_of(d, c);
    }
    const std::uint64_t t0 = sb.transactions(), b0 = sb.beats_checked(), f0 = sb.failures();
    const CaseStats stats = run_case(dut, bound, d, c, &sb, o);
    CaseSummary s{c.name, c.kind, stats.edges, stats.firings, sb.transactions() - t0, sb.beats_checked() - b0,
                  sb.failures() - f0, "", sb.case_first_failure(), out_clock_of(d, c).hz};
    if (s.first_failure) {
      s.first_failure->observed = shorten(s.first_failure->observed);
      s.first_failure->expected = shorten(s.first_failure->expected);
    }
    if (stats.rtl.kind == RtlEvent::Kind::Finish) s.rtl_finish = shorten(stats.rtl.where);
    if (!stats.rtl_output.empty() && r.rtl_output.size() < (1u << 20)) {
      r.rtl_output += "== " + c.name + "\n" + shorten(stats.rtl_output);
      if (r.rtl_output.back() != '\n') r.rtl_output += '\n';
    }
    r.receiver_cycles += stats.edges;
    if (export_this) options.exported->end_ps = (stats.edges + 2) * clock_period_ps(d);
    if (options.progress) {
      const std::string verdict =
          s.first_failure ? fmt::format("FAIL ({} at cycle {})", s.first_failure->check, s.first_failure->cycle) : "ok";
      // Over a range of output clocks, the one this case ran at.
      const std::string at = d.out_clock_hz_max > d.out_clock_hz ? fmt::format(" ({} at {:.1f} MHz)", d.out_clock_port, s.out_clock_hz / 1e6) : "";
      std::fprintf(stderr, "  %-34s %9llu cycles %8llu transactions %8llu beats  %s%s%s\n", c.name.c_str(),
                   static_cast<unsigned long long>(s.edges), static_cast<unsigned long long>(s.transactions),
                   static_cast<unsigned long long>(s.beats), verdict.c_str(), at.c_str(),
                   s.rtl_finish.empty() ? "" : fmt::format(" (ended by the RTL's $finish at {})", s.rtl_finish).c_str());
    }
    r.cases.push_back(s);
  }
  r.transactions = sb.transactions();
  r.beats_checked = sb.beats_checked();
  r.special_beats = sb.special_beats();
  r.failures = sb.failures();
  r.protocol_violations = sb.protocol_violations();
  r.drops = sb.drops_accepted();
  r.first_failure = sb.first_failure();
  if (r.first_failure) {
    r.first_failure->observed = shorten(r.first_failure->observed);
    r.first_failure->expected = shorten(r.first_failure->expected);
  }
  r.stamp_rule = sb.stamp_rule();
  r.stamp_edge = sb.stamp_edge();
  r.ack_rise = sb.ack_rise_latency();
  r.ack_fall = sb.ack_fall_latency();
  r.run_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace aesim
