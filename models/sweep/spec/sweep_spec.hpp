#pragma once
#include <string>
#include <utility>
#include <vector>

#include "aesim/sizing/sizing_report.hpp"

namespace aesim {

// One design point: a scene and the --set overrides that make it.
struct SweepPoint {
  std::string group;
  std::string scene;
  std::vector<std::pair<std::string, std::string>> sets;  // fixed [set] first, then the group's values
};

// A sweep spec (TOML), documented in docs/sweeps.md:
//   sensor = "aloha"   duration = "2s"   jobs = 0   chart = "../charts/collisions.gp"
//   [set]       "key" = value, ...                    overrides for every point
//   [[group]]   name = "...", scene = [...], "key" = value | [values] | {from, to, points, scale}
//               samples = N, seed = S   (optional: N seeded random draws instead of the full grid)
//   [constraints]  column = "<= 10uW" | ">= 25" ...
// Each group is the Cartesian product of its lists and ranges, scenes outermost and the other keys
// in alphabetical order, the last varying fastest; with `samples`, N points per scene each take
// every key's value at random (uniformly) from its list or range. The sweep is the groups in file
// order.
struct SweepSpec {
  std::string path;
  std::string sensor = "aloha";
  std::string duration;
  std::string chart;  // gnuplot script, resolved to a path; empty for none
  int jobs = 0;       // 0: all cores
  std::vector<std::string> swept_keys;  // every key any group varies or sets, in first-seen order
  std::vector<SweepPoint> points;
  std::vector<Constraint> constraints;  // [constraints]: column = "<= value" / ">= value"
};

// Parses, expands and validates every point (each resolves to a valid sensor configuration)
// before anything runs. Throws InputError naming the spec, the group and the key.
SweepSpec load_sweep_spec(const std::string& path);

}  // namespace aesim
