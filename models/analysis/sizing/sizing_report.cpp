#include "aesim/sizing/sizing_report.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "aesim/pareto/pareto_front.hpp"
#include "aesim/errors/input_error.hpp"
#include "aesim/units/si_units.hpp"

namespace aesim {
namespace {

std::string unit_of(const std::string& column) {
  auto ends = [&](const char* tail) {
    const std::string t(tail);
    return column.size() >= t.size() && column.compare(column.size() - t.size(), t.size(), t) == 0;
  };
  if (ends("_w")) return "W";
  if (ends("_s")) return "s";
  if (ends("_j")) return "J";
  if (ends("_hz")) return "Hz";
  if (ends("_db")) return "dB";
  return "";
}

// A number for the report: engineering prefixes for physical units, plain for dB and fractions.
std::string shown(double v, const std::string& unit) {
  if (unit.empty()) return fmt::format("{:.4g}", v);
  if (unit == "dB") return fmt::format("{:.1f} dB", v);
  return format_si(v, unit);
}

double value(const DesignPoint& p, const std::string& column) {
  const auto it = p.values.find(column);
  return it == p.values.end() ? std::numeric_limits<double>::quiet_NaN() : it->second;
}

// Relative margin: how far inside the bound, as a fraction of it (negative: violated).
double margin(const DesignPoint& p, const Constraint& c) {
  const double v = value(p, c.column);
  const double scale = std::max(std::fabs(c.bound), 1e-300);
  return (c.at_most ? c.bound - v : v - c.bound) / scale;
}

// The candidates on the Pareto front of (a, b), `low` saying for each whether lower is better;
// ordered by a.
std::vector<std::size_t> front(const std::vector<DesignPoint>& points, const std::vector<std::size_t>& candidates,
                               const std::string& a, bool a_low, const std::string& b, bool b_low) {
  std::vector<std::pair<double, double>> scores;
  for (std::size_t i : candidates) {
    scores.emplace_back(a_low ? value(points[i], a) : -value(points[i], a), b_low ? value(points[i], b) : -value(points[i], b));
  }
  std::vector<std::size_t> out;
  for (std::size_t k : pareto_front(scores)) out.push_back(candidates[k]);
  std::sort(out.begin(), out.end(), [&](std::size_t i, std::size_t j) { return value(points[i], a) < value(points[j], a); });
  return out;
}

}  // namespace

std::vector<DesignPoint> worst_case_by_label(const std::vector<DesignPoint>& points) {
  std::vector<DesignPoint> out;
  std::map<std::string, std::size_t> index;
  for (const DesignPoint& p : points) {
    const auto [it, fresh] = index.emplace(p.label, out.size());
    if (fresh) {
      out.push_back(p);
      continue;
    }
    DesignPoint& d = out[it->second];
    for (const auto& [column, v] : p.values) {
      const bool higher_is_better = column == "psnr_db" || column == "dynamic_range_covered";
      auto found = d.values.find(column);
      if (found == d.values.end()) d.values[column] = v;
      else found->second = higher_is_better ? std::min(found->second, v) : std::max(found->second, v);
    }
  }
  return out;
}

Constraint parse_constraint(const std::string& column, const std::string& text) {
  Constraint c;
  c.column = column;
  std::string rest = text;
  rest.erase(0, rest.find_first_not_of(' '));
  if (rest.rfind("<=", 0) == 0 || rest.rfind(">=", 0) == 0) {
    c.at_most = rest[0] == '<';
    rest = rest.substr(2);
  } else if (!rest.empty() && (rest[0] == '<' || rest[0] == '>')) {
    c.at_most = rest[0] == '<';
    rest = rest.substr(1);
  } else {
    throw InputError(fmt::format("constraint {}: expected <= or >= then a value (got '{}')", column, text));
  }
  c.bound = parse_si(rest, unit_of(column), "constraint " + column);
  return c;
}

SizingAnalysis analyse_sizing(const std::vector<DesignPoint>& points, const std::vector<Constraint>& constraints) {
  SizingAnalysis a;
  std::vector<std::size_t> feasible;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const bool ok = std::all_of(constraints.begin(), constraints.end(),
                                [&](const Constraint& c) { return margin(points[i], c) >= 0; });
    a.feasible.push_back(ok);
    if (ok) feasible.push_back(i);
  }
  a.front_power_quality = front(points, feasible, "power_w", true, "psnr_db", false);
  a.front_power_latency = front(points, feasible, "power_w", true, "latency_p99_s", true);
  double best = -std::numeric_limits<double>::infinity();
  for (std::size_t i : feasible) {
    double worst = std::numeric_limits<double>::infinity();
    for (const Constraint& c : constraints) worst = std::min(worst, margin(points[i], c));
    if (constraints.empty()) worst = -value(points[i], "power_w");
    if (worst > best) {
      best = worst;
      a.recommended = static_cast<int>(i);
    }
  }
  if (a.recommended >= 0) {
    for (const Constraint& c : constraints) a.margins.push_back(margin(points[static_cast<std::size_t>(a.recommended)], c));
    return a;
  }
  double closest = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < points.size() && !constraints.empty(); ++i) {
    double worst = std::numeric_limits<double>::infinity();
    for (const Constraint& c : constraints) worst = std::min(worst, margin(points[i], c));
    if (worst > closest) {
      closest = worst;
      a.closest = static_cast<int>(i);
    }
  }
  for (const Constraint& c : constraints) {
    a.meeting.push_back(static_cast<std::size_t>(
        std::count_if(points.begin(), points.end(), [&](const DesignPoint& p) { return margin(p, c) >= 0; })));
    if (a.closest >= 0) a.closest_margins.push_back(margin(points[static_cast<std::size_t>(a.closest)], c));
  }
  return a;
}

std::string sizing_report(const std::vector<DesignPoint>& points, const std::vector<Constraint>& constraints,
                          const SizingAnalysis& a) {
  std::string r = "# Sizing report\n\n";
  const std::size_t n_feasible = static_cast<std::size_t>(std::count(a.feasible.begin(), a.feasible.end(), true));
  r += fmt::format("{} designs, {} feasible in every condition (each judged on its worst case across the scenes "
                   "and the light levels swept).\n\n"
                   "Constraints:\n\n", points.size(), n_feasible);
  for (const Constraint& c : constraints) {
    r += fmt::format("- `{}` {} {}\n", c.column, c.at_most ? "<=" : ">=", shown(c.bound, unit_of(c.column)));
  }
  auto table = [&](const char* title, const std::vector<std::size_t>& rows, const char* second, const char* unit) {
    r += fmt::format("\n## {}\n\n| design point | power | {} | collision loss |\n|---|---|---|---|\n", title, second);
    for (std::size_t i : rows) {
      r += fmt::format("| {} | {} | {} | {:.2f} % |\n", points[i].label, format_si(value(points[i], "power_w"), "W"),
                       shown(value(points[i], second), unit), 100 * value(points[i], "collision_fraction"));
    }
    if (rows.empty()) r += "| (no feasible point) | | | |\n";
  };
  table("Feasible Pareto front: power against reconstruction quality", a.front_power_quality, "psnr_db", "dB");
  table("Feasible Pareto front: power against latency (p99)", a.front_power_latency, "latency_p99_s", "s");
  r += "\n## Recommendation\n\n";
  if (a.recommended < 0) {
    r += "No design point meets every constraint.\n";
    if (a.closest < 0) return r;
    r += "\nEach constraint alone:\n\n";
    for (std::size_t k = 0; k < constraints.size(); ++k) {
      r += fmt::format("- `{}`: met by {} of {} designs\n", constraints[k].column, a.meeting[k], points.size());
    }
    const DesignPoint& near = points[static_cast<std::size_t>(a.closest)];
    r += fmt::format("\nClosest: **{}** (the least negative worst margin):\n\n", near.label);
    for (std::size_t k = 0; k < constraints.size(); ++k) {
      r += fmt::format("- `{}` = {}: margin {:.0f} %{}\n", constraints[k].column,
                       shown(value(near, constraints[k].column), unit_of(constraints[k].column)),
                       100 * a.closest_margins[k], a.closest_margins[k] < 0 ? " (violated)" : "");
    }
    return r;
  }
  const DesignPoint& best = points[static_cast<std::size_t>(a.recommended)];
  r += fmt::format("**{}**: {} with PSNR {:.1f} dB and {:.2f} % collision loss. It is the feasible point whose "
                   "smallest margin to a constraint is largest:\n\n",
                   best.label, format_si(value(best, "power_w"), "W"), value(best, "psnr_db"),
                   100 * value(best, "collision_fraction"));
  for (std::size_t k = 0; k < constraints.size(); ++k) {
    r += fmt::format("- `{}` = {}: margin {:.0f} %\n", constraints[k].column,
                     shown(value(best, constraints[k].column), unit_of(constraints[k].column)), 100 * a.margins[k]);
  }
  return r;
}

}  // namespace aesim
