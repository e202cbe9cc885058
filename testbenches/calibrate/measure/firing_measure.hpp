#pragma once
#include <vector>

#include "ngspice/ngspice_run.hpp"

namespace aesim {

// What one transient says about the pixel, all from crossings interpolated linearly between
// ngspice's time points. A firing is a rising crossing of `out` through vdd/2 (docs/reference.md section 7).
struct FiringMeasure {
  std::vector<double> fires;  // s, every firing
  // Means over the firings after the first (the first starts from ngspice's all-zero state, not
  // from a reset), NaN when there are fewer than two such firings.
  double period = 0;         // s, (last - second) / (count - 2)
  double pulse = 0;          // s, out above vdd/2 after each firing
  double supply_charge = 0;  // C drawn from the supply per period
  // V of the probe node at the last time point before out starts to rise (crosses vdd/10), mean
  // over the firings after the first; NaN without a probe.
  double onset_level = 0;
  bool probe_rising = true;  // the probe node integrates upwards
};

FiringMeasure measure_firings(const Waveform& w, double vdd);

// The comparator's delay: from the probe node crossing `trip_level` (in its integrating direction)
// to out crossing vdd/2, mean over the firings after the first; NaN when not measurable.
double comparator_delay(const Waveform& w, const FiringMeasure& m, double trip_level);

}  // namespace aesim
