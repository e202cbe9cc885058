#include "report/verify_report.hpp"


namespace aesim {
namespace {

nlohmann::json failure_json(const VerifyFailure& f) {
  return {{"time_s", f.time_s}, {"cycle", f.cycle}, {"check", f.check}, {"expected", f.expected}, {"observed", f.observed}};
}

nlohmann::json span_json(const TransactionScoreboard::LatencySpan& s) {
  return s.count == 0 ? nlohmann::json(nullptr) : nlohmann::json::array({s.min, s.max});
}

}  // namespace

nlohmann::json verify_report(const ReceiverDescription& d, const std::string& plan, std::uint64_t seed,
                             const DutBuild& build, const VerifyResult& r, const std::vector<std::string>& notes,
                             double wall_time_s) {
  nlohmann::json j;
  j["passed"] = r.passed();
  j["transactions"] = r.transactions;
  j["beats_checked"] = r.beats_checked;
  if (d.has("special")) j["special_beats"] = r.special_beats;
  j["failures"] = r.failures;
  j["protocol_violations"] = r.protocol_violations;
  j["receiver_cycles"] = r.receiver_cycles;
  j["wall_time_s"] = wall_time_s;
  if (r.first_failure) {
    j["first_failure"] = failure_json(*r.first_failure);
    j["first_failure"]["case"] = r.first_failure->case_name;
    if (!r.first_failure->hint.empty()) j["first_failure"]["hint"] = r.first_failure->hint;
  } else {
    j["first_failure"] = nullptr;
  }
  j["drops_accounted"] = r.drops;
  j["stamp_rule"] = r.stamp_rule.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.stamp_rule);
  j["ack_latency_observed"] = {{"rise", span_json(r.ack_rise)}, {"fall", span_json(r.ack_fall)}};
  j["notes"] = notes;
  j["receiver"] = {{"description", d.file}, {"top", d.top},
                   {"collisions", to_string(d.collisions)}, {"full", to_string(d.full)},
                   {"handshake", to_string(d.handshake)}};
  if (d.has_out_clock()) {
    j["receiver"]["out_clock"] = {{"port", d.out_clock_port},
                                  {"hz", d.out_clock_hz == d.out_clock_hz_max ? nlohmann::json(d.out_clock_hz)
                                                                              : nlohmann::json({d.out_clock_hz, d.out_clock_hz_max})}};
  }
  j["plan"] = plan;
  j["seed"] = seed;
  j["build"] = {{"cached", build.cached}, {"seconds", build.seconds}};
  j["run_time_s"] = r.run_seconds;
  j["cycles_per_second"] = r.run_seconds > 0 ? static_cast<double>(r.receiver_cycles) / r.run_seconds : 0.0;
  nlohmann::json cases = nlohmann::json::array();
  for (const CaseSummary& c : r.cases) {
    cases.push_back({{"name", c.name}, {"kind", c.kind}, {"receiver_cycles", c.edges}, {"firings", c.firings},
                     {"transactions", c.transactions}, {"beats_checked", c.beats}, {"failures", c.failures},
                     {"rtl_finish", c.rtl_finish.empty() ? nlohmann::json(nullptr) : nlohmann::json(c.rtl_finish)},
                     {"first_failure", c.first_failure ? failure_json(*c.first_failure) : nlohmann::json(nullptr)}});
    if (d.has_out_clock()) cases.back()["out_clock_hz"] = c.out_clock_hz;
  }
  j["cases"] = cases;
  return j;
}

void add_formal_report(nlohmann::json& report, const FormalResult& formal, const std::string& counterexample_path,
                       const std::string& replay) {
  nlohmann::json list = nlohmann::json::array();
  for (const FormalVerdict& v : formal.verdicts) {
    nlohmann::json item = {{"property", v.property}, {"verdict", v.verdict}, {"depth", v.depth}, {"time_s", v.time_s},
                           {"asserts", v.text}};
    if (v.step) item["step"] = *v.step;
    if (!v.detail.empty()) item["detail"] = v.detail;
    list.push_back(item);
  }
  report["formal"] = list;
  report["formal_run"] = {{"depth", formal.depth},
                          {"depth_reason", formal.depth_reason},
                          {"solver", formal.solver},
                          {"property_seconds", formal.property_seconds},
                          {"cached", formal.cached},
                          {"seconds", formal.seconds},
                          {"notes", formal.notes},
                          {"failed_property", formal.failed_property.empty() ? nlohmann::json(nullptr) : nlohmann::json(formal.failed_property)},
                          {"counterexample", counterexample_path.empty() ? nlohmann::json(nullptr) : nlohmann::json(counterexample_path)},
                          {"replay", replay.empty() ? nlohmann::json(nullptr) : nlohmann::json(replay)}};
  if (formal.failed()) report["passed"] = false;
}

}  // namespace aesim
