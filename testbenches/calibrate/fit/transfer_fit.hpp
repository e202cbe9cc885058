#pragma once
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

// Supply charge per period = dynamic charge per firing + static current x period, by linear least
// squares on relative residuals; both kept non-negative.
struct SupplyFit {
  double charge_per_firing = 0;  // C
  double static_current = 0;     // A
  double rms_residual = 0, max_residual = 0;  // relative, of the charge per period the line gives
};

SupplyFit fit_supply(const std::vector<double>& period, const std::vector<double>& charge);

}  // namespace aesim
