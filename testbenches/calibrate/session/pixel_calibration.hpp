#pragma once
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "deck/pixel_deck.hpp"
#include "ngspice/ngspice_run.hpp"
#include "fit/transfer_fit.hpp"

namespace aesim {

struct CalibrationOptions {
  double vdd = 3.3;                        // V
  double i_low = 1e-15, i_high = 1e-9;     // A, the photocurrents' range
  int points = 13;                         // spaced logarithmically over the range
  int firings = 8;                         // periods each transient measures (after its first firing)
  int mc = 0;                              // Monte Carlo runs for the mismatch
  int jobs = 1;                            // ngspice processes at once
  double charge_guess = 100e-15;           // C, sizes the first transient of each point
  bool progress = false;                   // a progress bar on stderr
  std::string failure_log;                 // where ngspice's log of a run rejecting the deck is kept
};

// One photocurrent's measurement.
// Why a run showed a pixel will not fire at its current.
enum class Stop { none, latched, settled };

struct CalibrationPoint {
  double current = 0;          // A
  double period = 0;           // s, mean firing period (NaN: never fired)
  double pulse = 0;            // s, out's pulse width
  double comparator_delay = 0; // s, NaN without a probe node
  double supply_charge = 0;    // C per firing
  double step = 0;             // s, ngspice's largest step in the run measured
  // An earlier run's period at another largest step (NaN: none measured one): how far ngspice's
  // answer moves with its step.
  double earlier_period = std::numeric_limits<double>::quiet_NaN(), earlier_step = 0;
  int runs = 0;                // transients it took to size the run
  double simulated = 0;        // s of circuit time simulated
  std::size_t settings = 0;    // the solver settings level it was measured with (solver_settings())
  std::string aborted;         // why ngspice gave up on it under every setting ("" when it did not)
  std::string seen;            // when it never fired and was not waited for longer: what the run showed
  Stop stop = Stop::none;      // and which of the two it was
  // Not run (or stopped): a weaker light than one whose node settled, or a stronger one than one that
  // latched, does the same; `seen` says which current showed it.
  bool inferred = false;
};

struct Calibration {
  std::vector<CalibrationPoint> points;  // every current measured, in increasing order
  int refined = 0;                       // of them added between the grid's points (see the .cpp)
  // Where added points' periods fell outside their neighbours' (the periods scatter by more than the
  // table resolves, which more points would not mend), in words; empty when nowhere.
  std::string scatter_note;
  std::vector<double> current, period;   // the points that fired: the transfer table
  PixelFit fit;
  std::optional<CircuitFit> circuit;     // the circuit's own form (where every fired point has a pulse)
  SupplyFit supply;
  // The nearest currents beyond the table's ends at which the circuit never fired, and what the run
  // showed there (0 and infinity: none seen).
  double silent_below = 0, silent_above = std::numeric_limits<double>::infinity();
  std::string silent_below_seen, silent_above_seen;
  double trip_level = 0;                 // V of the probe node where the comparator trips (NaN: none)
  std::optional<double> mismatch;        // relative std of the threshold charge (--mc)
  std::vector<double> mc_periods;        // s, one per Monte Carlo run
  double mc_current = 0;                 // A
  std::string ngspice;                   // version
  // At each solver_settings() level, the currents run to an answer with it (fired, or seen to settle
  // or latch): a fallback is said even where it showed the pixel silent.
  std::vector<std::vector<double>> currents_per_settings;
  double wall = 0;                       // s
};

// Runs the deck at every photocurrent (in parallel, `jobs` at a time), each transient sized from a
// guess of its period and rerun until it holds `firings` periods resolved by ~500 time steps each;
// adds points where log-log interpolation between neighbours would miss; fits eq. 2. A transient
// ngspice gives up on is run again under the next solver settings, then with finer steps; a
// current that still fails is left out with a warning. Throws InputError when ngspice rejects the
// deck or fewer than three currents fire.
Calibration calibrate_pixel(const PixelDeck& deck, const CalibrationOptions& options);

}  // namespace aesim
