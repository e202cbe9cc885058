#pragma once
#include <map>
#include <string>
#include <vector>

namespace aesim {

// A constraint on a summary column: column <= bound, or column >= bound.
struct Constraint {
  std::string column;
  bool at_most = true;
  double bound = 0;
};

// Parses "<= 10uW", ">= 25", "< 0.05" for `column`; the unit follows the column's suffix
// (_w: W, _s: s, _j: J, _hz: Hz, _db: dB). Throws InputError naming the column.
Constraint parse_constraint(const std::string& column, const std::string& text);

struct DesignPoint {
  std::string label;                      // e.g. the swept values
  std::map<std::string, double> values;   // summary columns
};

struct SizingAnalysis {
  std::vector<bool> feasible;
  // Indices of the feasible points on each front, in increasing power.
  std::vector<std::size_t> front_power_quality;  // lower power_w, higher psnr_db
  std::vector<std::size_t> front_power_latency;  // lower power_w, lower latency_p99_s
  int recommended = -1;                          // feasible point with the largest worst margin
  std::vector<double> margins;                   // of the recommended point, per constraint (relative)
  // With no feasible point: the one whose worst margin is least negative, and its margins; and
  // per constraint, how many designs meet it alone (which constraint binds).
  int closest = -1;
  std::vector<double> closest_margins;
  std::vector<std::size_t> meeting;
};

// Merges points with the same label (one design on several scenes) into their worst case: the
// largest value of columns where lower is better, the smallest of psnr_db and dynamic_range_covered.
std::vector<DesignPoint> worst_case_by_label(const std::vector<DesignPoint>& points);

// Marks feasibility, finds the feasible Pareto fronts and recommends the feasible point whose
// smallest relative margin to any constraint is largest (the most robust sizing); with no
// constraint, the one with the lowest power.
SizingAnalysis analyse_sizing(const std::vector<DesignPoint>& points, const std::vector<Constraint>& constraints);

// The report as Markdown: constraints, the fronts, the recommendation with its margins.
std::string sizing_report(const std::vector<DesignPoint>& points, const std::vector<Constraint>& constraints,
                          const SizingAnalysis& analysis);

}  // namespace aesim
