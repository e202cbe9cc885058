#include <cstdio>
#include <string>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "classify/template_classifier.hpp"
#include "files/data_dir.hpp"
#include "errors/input_error.hpp"
#include "event_files/event_file.hpp"
#include "units/si_units.hpp"

namespace aesim {

int classify_command(ClassifyOptions opt) {
  if (opt.templates.empty()) opt.templates = data_dir() + "/scenes/templates/letters";
  if (!(opt.classifier.k > 0)) throw InputError("--k: must be positive");
  if (opt.classifier.max_events == 0) throw InputError("--max-events: must be at least 1");
  if (!(opt.classifier.overflow > 0)) throw InputError("--overflow: must be positive");
  if (!(opt.cycles_per_template > 0)) throw InputError("--cycles-per-template: must be positive");
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
  for (const std::string& w : warnings) std::fprintf(stderr, "aesim classify: warning: %s\n", w.c_str());
  const std::optional<ArraySize> size =
      opt.size.empty() ? std::nullopt : std::optional<ArraySize>(parse_array_size(opt.size, "--size"));
  const EventRecording rec = load_events(opt.events, size);
  // The size scales events onto the templates: guessed from the events it would change the
  // decision with the events that happened to fire (a CSV records no size).
  if (!rec.size_recorded) {
    throw InputError(fmt::format("event file '{}' records no array size (a CSV does not): give --size WIDTHxHEIGHT",
                                 opt.events));
  }
  // Events in template coordinates: pixel centres scaled from the recording's array.
  const double sx = static_cast<double>(templates.front().width) / std::max(1, rec.width);
  const double sy = static_cast<double>(templates.front().height) / std::max(1, rec.height);
  std::vector<std::pair<double, double>> events;
  for (const AddressEvent& e : rec.events) {
    if (e.flags & kGhostEvent) continue;
    events.emplace_back((e.x + 0.5) * sx - 0.5, (e.y + 0.5) * sy - 0.5);
  }
  const ClassifyResult r = classify(templates, events, opt.classifier);
  const double seconds = static_cast<double>(r.events_used) * static_cast<double>(templates.size()) *
                         opt.cycles_per_template / clock;
  const std::string winner = r.winner >= 0 ? templates[static_cast<std::size_t>(r.winner)].name : "";
  if (opt.json) {
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
                        {"warnings", warnings},
                        {"scores", nlohmann::json::object()}};
    for (std::size_t i = 0; i < templates.size(); ++i) {
      j["scores"][templates[i].name] = r.scores[i];
      j["ranks_by_template"][templates[i].name] = templates[i].rank;
    }
    fmt::print("{}\n", j.dump(2));
    return 0;
  }
  if (r.winner >= 0) {
    fmt::print("winner: {} after {} of {} events ({} restarts)\n", winner, r.events_used, events.size(), r.restarts);
  } else {
    fmt::print("winner: none after {} events ({} restarts)\n", r.events_used, r.restarts);
  }
  std::string scores;
  for (std::size_t i = 0; i < templates.size(); ++i) {
    scores += fmt::format("{}{} {:.2f} (rank {:.2f})", i ? ", " : "", templates[i].name, r.scores[i],
                          opt.classifier.ranks ? templates[i].rank : 1.0);
  }
  fmt::print("  scores: {}\n", scores);
  fmt::print("  {} additions, {} comparisons\n", r.additions, r.comparisons);
  fmt::print("  estimated {} on a {} processor at {} cycles per template per event\n", format_si(seconds, "s"),
             format_si(clock, "Hz"), opt.cycles_per_template);
  return 0;
}

}  // namespace aesim
