#pragma once
#include <limits>
#include <vector>

namespace aesim {

// eq. 2 with a dark current and a reset, period = Q / (I + i_dark) + t_reset, fitted to measured
// periods by least squares on relative residuals (every decade of current counts alike).
// For a given i_dark the model is linear in Q and t_reset (solved exactly); i_dark >= 0 is found
// by a scan over decades refined by golden-section search. t_reset is kept within
// [0, 0.99 * the shortest period], so the table stays usable by the model.
struct PixelFit {
  double charge = 0;   // C
  double t_reset = 0;  // s
  double i_dark = 0;   // A
  std::vector<double> residuals;  // (model - measured) / measured, per point
  double rms_residual = 0, max_residual = 0;
  double period(double current) const { return charge / (current + i_dark) + t_reset; }
};

PixelFit fit_pixel(const std::vector<double>& current, const std::vector<double>& period);

// The circuit's own form where eq. 2 does not hold, fitted beside it for the provenance:
//   period = Q / (I + i_dark) + t_r / (1 - I / I_r)
// The integration runs on the net current I + i_dark, i_dark of either sign: a dark current (> 0),
// or a leak to ground (< 0) that the light must exceed before the pixel fires at all. The reset
// discharges the node with a net current that the light opposes, so it lengthens with the light
// and never ends at and above I_r: there the pixel latches (I_r infinite: a reset of t_r at any
// light). The reset part is fitted to the measured out-pulse widths (1 / pulse is a line in I),
// the integration part to period - pulse (Q by least squares for each i_dark, i_dark searched over
// both signs), both on relative residuals.
struct CircuitFit {
  double charge = 0;   // C
  double i_dark = 0;   // A, either sign
  double t_r = 0;      // s, the reset at no light
  double i_r = std::numeric_limits<double>::infinity();  // A, where the reset latches
  std::vector<double> residuals;  // (model - measured) / measured period, per point
  double rms_residual = 0, max_residual = 0;
  double reset(double current) const { return t_r / (1 - current / i_r); }
  double period(double current) const { return charge / (current + i_dark) + reset(current); }
};

// Throws std::invalid_argument for fewer than three points or a pulse not shorter than its period.
CircuitFit fit_circuit(const std::vector<double>& current, const std::vector<double>& period,
                       const std::vector<double>& pulse);

// Supply charge per period = dynamic charge per firing + static current x period, by linear least
// squares on relative residuals. The power model needs both parts non-negative: where the free fit
// gives a negative part, that part is held at 0 and the other refitted (the least-squares optimum
// on that bound), and the free fit's values are kept to be reported.
struct SupplyFit {
  double charge_per_firing = 0;  // C
  double static_current = 0;     // A
  double rms_residual = 0, max_residual = 0;  // relative, of the charge per period the line gives
  double free_charge_per_firing = 0, free_static_current = 0;  // the unbounded fit's
};

SupplyFit fit_supply(const std::vector<double>& period, const std::vector<double>& charge);

}  // namespace aesim
