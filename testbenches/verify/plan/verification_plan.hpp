#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "description/receiver_description.hpp"
#include "stimulus/scene_cases.hpp"
#include "stimulus/verify_case.hpp"

namespace aesim {

// What `aesim verify` runs: the directed protocol cases and scene runs at several loads and seeds.
//   quick: directed, and light (G 0.05), medium (0.3) and heavy (1.0, the consumer ready 60 % of
//          the time) load on scenes/letters/A.pgm, two seeds each, 2000 firings a run: seconds.
//   full:  the same loads with four seeds and 300,000 firings a run: millions of transactions.
// A plan file (TOML) names its own:
//   directed = true                 # or a list of the directed cases to run, e.g.
//                                   # ["single_event", "back_to_back", "collision"]
//   [[scene]]
//   file = "scenes/letters/A.pgm"   # relative to the plan file; default the letter A
//   load = 0.3                      # offered load G
//   seeds = [1, 2, 3]               # or seeds = 3 (seeds 1..3)
//   firings = 100000                # per run
//   ready = 0.9                     # probability the consumer is ready at an edge
//   formal = true                   # (top level) the formal check too, as --formal
struct VerificationPlan {
  std::string name;
  bool directed = true;
  std::vector<std::string> directed_cases;  // empty: all of them
  std::vector<SceneLoad> scenes;  // one per run (seed expanded)
  bool formal = false;            // formal = true: the formal check too (as --formal)
};

// "quick", "full", or a plan file; InputError naming the key otherwise.
VerificationPlan make_plan(const std::string& plan);

// The plan's cases for this receiver; `seed` offsets every scene run's seed, so --seed N gives
// other firings and other back-pressure. A receiver without a ready port takes no back-pressure:
// the directed back-pressure cases are left out and the scene runs' consumer is always ready, and
// `notes` says so.
std::vector<VerifyCase> plan_cases(const VerificationPlan& plan, const ReceiverDescription& d, std::uint64_t seed,
                                   std::vector<std::string>* notes = nullptr);

// The work a plan asks for, in receiver clock cycles (estimated before anything runs).
double plan_cycles(const std::vector<VerifyCase>& cases);
inline constexpr double kMaxPlanCycles = 2e10;

}  // namespace aesim
