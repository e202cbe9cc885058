#include <cmath>
#include <cstdio>
#include <string>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "aesim/classify/template_classifier.hpp"
#include "aesim/files/data_dir.hpp"
#include "aesim/errors/input_error.hpp"
#include "aesim/event_files/event_file.hpp"
#include "aesim/units/si_units.hpp"
#include "report_stream.hpp"

namespace aesim {

nlohmann::json classify_recording(ClassifyOptions opt, const EventRecording* given) {
  opt.templates = opt.templates.empty() ? data_dir() + "/scenes/templates/letters" : shipped_if_missing(opt.templates);
  if (!(opt.classifier.k > 0)) throw InputError("--k: must be positive");
  if (opt.classifier.max_events == 0) throw InputError("--max-events: must be at least 1");
  if (!(opt.classifier.overflow > 0)) throw InputError("--overflow: must be positive");
  if (!(opt.cycles_per_template > 0) || !std::isfinite(opt.cycles_per_template)) {
    throw InputError("--cycles-per-template: must be a positive, finite number");
  }
  const double clock = parse_si(opt.clock, "Hz", "--clock");
  if (!(clock > 0)) throw InputError("--clock: must be positive");
  opt.classifier.ranks = !opt.no_ranks;
  if (opt.classifier.center_events > 0) opt.classifier.center_templates = true;

  const std::vector<Template> templates = load_templates(opt.templates);
  std::vector<std::string> warnings;
  if (opt.classifier.ranks) {
    for (const Containment& c : contained_templates(templates, 0.95, opt.classifier.center_templates)) {
      warnings.push_back(fmt::format("template '{}' lies {:.0f} % inside '{}': under ranks '{}' ties it over every "
                                     "full pass of events and can win only by their order",
                                     templates[c.inner].name, 100 * c.fraction, templates[c.outer].name,
                                     templates[c.outer].name));
    }
  }
  const std::optional<ArraySize> size =
      opt.size.empty() ? std::nullopt : std::optional<ArraySize>(parse_array_size(opt.size, "--size"));
  const EventRecording rec = given ? *given : load_events(opt.events, size, opt.layout);
  // The size scales events onto the templates: guessed from the events it would change the
  // decision with the events that happened to fire (a CSV records no size).
  if (!rec.size_recorded) {
    throw InputError(fmt::format("event file '{}' records no array size: give it (--size WIDTHxHEIGHT; size='WIDTHxHEIGHT' "
                                 "in Python)",
                                 opt.events));
  }
  std::vector<std::pair<double, double>> events;
  for (const AddressEvent& e : rec.events) {
    if (e.flags & kGhostEvent) continue;
    events.push_back(template_position(e.x, e.y, rec.width, rec.height, templates.front().width, templates.front().height));
  }
  const ClassifyResult r = classify(templates, events, opt.classifier);
  const double seconds = static_cast<double>(r.events_used) * static_cast<double>(templates.size()) *
                         opt.cycles_per_template / clock;
  const std::string winner = r.winner >= 0 ? templates[static_cast<std::size_t>(r.winner)].name : "";
  nlohmann::json j = {{"winner", r.winner >= 0 ? nlohmann::json(winner) : nlohmann::json(nullptr)},
                      {"events_used", r.events_used},
                      {"events_available", events.size()},
                      {"restarts", r.restarts},
                      {"additions", r.additions},
                      {"comparisons", r.comparisons},
                      {"ranks", opt.classifier.ranks},
                      {"centred_templates", opt.classifier.center_templates},
                      {"shift", {r.shift_x, r.shift_y}},
                      {"estimated_time_s", seconds},
                      {"clock_hz", clock},
                      {"cycles_per_template", opt.cycles_per_template},
                      {"warnings", warnings},
                      {"scores", nlohmann::json::object()},
                      {"ranks_by_template", nlohmann::json::object()}};
  for (std::size_t i = 0; i < templates.size(); ++i) {
    j["scores"][templates[i].name] = r.scores[i];
    j["ranks_by_template"][templates[i].name] = templates[i].rank;
  }
  return j;
}

int classify_command(ClassifyOptions opt) {
  const nlohmann::json j = classify_recording(opt);
  for (const auto& w : j["warnings"]) {
    std::fprintf(stderr, "aesim classify: warning: %s\n", w.get<std::string>().c_str());
  }
  if (opt.json) {
    fmt::print(report_stream(), "{}\n", j.dump(2));
    return 0;
  }
  if (!j["winner"].is_null()) {
    fmt::print(report_stream(), "winner: {} after {} of {} events ({} restarts)\n", j["winner"].get<std::string>(),
               j["events_used"].get<std::uint64_t>(), j["events_available"].get<std::uint64_t>(),
               j["restarts"].get<std::uint64_t>());
  } else {
    fmt::print(report_stream(), "winner: none after {} events ({} restarts)\n", j["events_used"].get<std::uint64_t>(),
               j["restarts"].get<std::uint64_t>());
  }
  std::string scores;
  for (const auto& [name, score] : j["scores"].items()) {
    scores += fmt::format("{}{} {:.2f} (rank {:.2f})", scores.empty() ? "" : ", ", name, score.get<double>(),
                          j["ranks"].get<bool>() ? j["ranks_by_template"][name].get<double>() : 1.0);
  }
  fmt::print(report_stream(), "  scores: {}\n", scores);
  fmt::print(report_stream(), "  {} additions, {} comparisons\n", j["additions"].get<std::uint64_t>(), j["comparisons"].get<std::uint64_t>());
  fmt::print(report_stream(), "  estimated {} on a {} processor at {} cycles per template per event\n",
             format_si(j["estimated_time_s"].get<double>(), "s"), format_si(j["clock_hz"].get<double>(), "Hz"),
             j["cycles_per_template"].get<double>());
  return 0;
}

}  // namespace aesim
