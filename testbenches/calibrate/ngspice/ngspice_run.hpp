#pragma once
#include <filesystem>
#include <functional>
#include <optional>
#include <stdexcept>
#include <deque>
#include <string>
#include <utility>
#include <vector>

#include "deck/pixel_deck.hpp"

namespace aesim {

// ngspice's integration method and tolerances for a transient. Level 0 is the one a pixel is
// measured with (sized for femtoamps and femtocoulombs). The others are the fallbacks tried, in
// order, when ngspice gives up on a transient ("timestep too small": a foundry deck's behavioural
// capacitors and BSIM models under tolerances that tight), each still three decades below what
// it measures: abstol and gmin x vdd at a thousandth of the photocurrent, so that neither the
// current error ngspice allows nor the leakage gmin adds moves a period by more than ~0.1 %.
// Level 1 is Gear with those tolerances, level 2 the trapezoidal rule with them.
struct SolverSettings {
  const char* method = "gear";
  double abstol = 1e-17, chgtol = 1e-19, gmin = 1e-18;
  std::string label() const;
};
inline constexpr std::size_t kSolverLevels = 3;
SolverSettings solver_settings(std::size_t level, double iph, double vdd);
// What each level is, for messages and the preset's provenance.
const char* solver_level_text(std::size_t level);

// One transient of the pixel at a constant photocurrent.
struct TransientRequest {
  double iph = 0;     // A
  double t_stop = 0;  // s
  double t_max = 0;   // s, ngspice's largest internal step
  unsigned seed = 1;             // ngspice's seed for agauss() and friends
  bool monte_carlo = false;      // sets the deck's `mc` parameter, when it has one
  std::size_t settings = 0;      // solver_settings() level
  // Where the testbench and ngspice's log of a run that rejects the deck are kept for the user
  // (the calibration's first such run's, replacing an earlier calibration's; empty: nowhere).
  // Anything there but a regular file is left alone.
  std::string failure_log{};
  // Asked about once a second while ngspice runs: true stops it (TransientAbandoned), for a run
  // whose answer another run has made known.
  std::function<bool()> abandon{};
};

// What a run records: the pixel's output, the supply's current (ngspice's sign: negative when the
// supply delivers), and the probe node's voltage when the deck has one.
struct Waveform {
  std::vector<double> t, out, supply, probe;
};

// The generated top level: the supply, one instance of the pixel, the simulator settings and the
// control block that writes the waveform to `data_path`.
std::string testbench_text(const PixelDeck& deck, double vdd, const TransientRequest& request,
                           const std::string& data_path);

// Runs ngspice (an argument vector, no shell; `-b -n`: batch, no user init file) on the testbench
// in `scratch` and reads the waveform. A deck ngspice rejects is an InputError with ngspice's
// first error line; ngspice missing is an InputError saying how to install it; a transient ngspice
// abandons is TransientAborted with its reason.
Waveform run_transient(const PixelDeck& deck, double vdd, const TransientRequest& request,
                       const std::filesystem::path& scratch, const std::string& name);

// ngspice gave up part-way ("timestep too small", or a time step that collapsed so far that the
// run would not end): other solver settings or a finer maximum step may get through.
// Whether a transient that ngspice reports progress on ("Reference value : t", about twice a
// second) will end within `run_seconds`: once it has run twice `window` seconds, the pace of its
// last `window` seconds, kept up, must reach `t_stop` within ten times the time left (its pace
// swings with the firings' edges: only a collapse is that far off). A run whose time step has collapsed
// (a stiff node under tight tolerances) is given up as soon as that shows, rather than at the
// limit; its first edges are slow in any run, so the pace is not judged before.
class StepCollapseWatch {
 public:
  StepCollapseWatch(double t_stop, double run_seconds, double window)
      : t_stop_(t_stop), run_seconds_(run_seconds), window_(window) {}
  // A progress sample: `wall` s since the start, `reported` s simulated (negative: none yet).
  bool keep_waiting(double wall, double reported);
  double stalled_at() const { return stalled_at_; }  // s simulated when it gave up (< 0: it did not)

 private:
  double t_stop_, run_seconds_, window_;
  std::deque<std::pair<double, double>> samples_;
  double stalled_at_ = -1;
};

class TransientAborted : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The run was stopped because TransientRequest::abandon said so.
class TransientAbandoned : public std::runtime_error {
 public:
  TransientAbandoned() : std::runtime_error("abandoned") {}
};

// "ngspice-39", from `ngspice -v`.
std::string ngspice_version();

}  // namespace aesim
