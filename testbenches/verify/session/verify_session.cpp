#include "session/verify_session.hpp"

#include <chrono>
#include <cstdio>

#include "driver/bound_ports.hpp"

namespace aesim {
void trace_failure(const DutLibrary& library, const std::vector<RtlPort>& ports, const ReceiverDescription& d,
                   const VerifyCase& c, std::uint64_t cycle, const std::string& path) {
  DutInstance dut(library, true);
  if (!dut.open_trace(path)) return;
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
  TransactionScoreboard sb(d, d.has("overflow_count"),
                           d.has("overflow_count") ? find_port(ports, d.port("overflow_count"))->width : 0,
                           clock_period_ps(d));
  VerifyResult r;
  bool exported = false;
  for (const VerifyCase& c : cases) {
    DutInstance dut(library, false);
    const BoundPorts bound = bind_ports(dut, d, ports);
    CaseRunOptions o;
    const bool export_this = !exported && c.kind == "scene" && options.exported;
    if (export_this) {
      o.waveform = &options.exported->waveform;
      o.beats = &options.exported->beats;
      options.exported->case_name = c.name;
      exported = true;
    }
    const std::uint64_t t0 = sb.transactions(), b0 = sb.beats_checked(), f0 = sb.failures();
    const CaseStats stats = run_case(dut, bound, d, c, &sb, o);
    CaseSummary s{c.name, c.kind, stats.edges, stats.firings, sb.transactions() - t0, sb.beats_checked() - b0,
                  sb.failures() - f0};
    r.receiver_cycles += stats.edges;
    if (export_this) options.exported->end_ps = (stats.edges + 2) * clock_period_ps(d);
    if (options.progress) {
      std::fprintf(stderr, "  %-34s %9llu cycles %8llu transactions %8llu beats  %s\n", c.name.c_str(),
                   static_cast<unsigned long long>(s.edges), static_cast<unsigned long long>(s.transactions),
                   static_cast<unsigned long long>(s.beats), s.failures ? "FAIL" : "ok");
    }
    r.cases.push_back(s);
  }
  r.transactions = sb.transactions();
  r.beats_checked = sb.beats_checked();
  r.failures = sb.failures();
  r.protocol_violations = sb.protocol_violations();
  r.drops = sb.drops_accepted();
  r.first_failure = sb.first_failure();
  r.run_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace aesim
