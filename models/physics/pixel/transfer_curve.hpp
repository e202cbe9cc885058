#pragma once
#include <limits>
#include <string>
#include <vector>

namespace aesim {

class TomlValue;

// pixel.transfer: a pixel's measured firing period at each photocurrent (from `aesim calibrate`,
// i.e. from the pixel's circuit in ngspice), for where the circuit bends away from eq. 2.
//
// The table is indexed by photocurrent, i_max * v: the circuit's own leakage is inside the
// measured periods, so pixel.i_dark is not added to the look-up. Between points the period is
// interpolated log-log (a power law per segment, which eq. 2 is at both ends of its range).
//
// A pixel integrates an effective current chosen so that, under constant light, it fires with the
// table's period: I_eff = Q / (period(I) - t_reset), Q the threshold charge and t_reset the reset
// the table was measured with (its `charge` and `t_reset` fields, which `aesim calibrate` writes;
// without them, the pixel's own). Charge then carries over exactly when the light changes, as
// without the table, and mismatch and shot noise act on the pixel's charge as before. A pixel
// resized from the calibrated one (pixel.c_int or dv_int in a sweep) integrates the same current
// to its own threshold, and resets for its own pixel.t_reset: the circuit's departures from eq. 2
// stay in the current. Outside the table the effective current follows eq. 2's current,
// I + i_dark, scaled to meet the table at its end point, so zero light fires at the dark current's
// rate (or never).
//
// Where the circuit was seen not to fire at all (it latched, or a leak held its node below the
// threshold), the table says so: at photocurrents at or below `silent_below`, and at or above
// `silent_above`, the pixel integrates nothing and never fires, as the circuit did. Between such a
// current and the table's end the model extrapolates as above.
struct TransferCurve {
  std::vector<double> current;  // A, strictly increasing, positive
  std::vector<double> period;   // s, each longer than the reset
  double charge = 0;            // C, threshold charge the table was measured with (0: the pixel's)
  double t_reset = -1;          // s, reset the table was measured with (< 0: the pixel's)
  double silent_below = 0;      // A, the circuit never fired at or below it (0: not seen)
  double silent_above = std::numeric_limits<double>::infinity();  // A, nor at or above it

  bool empty() const { return current.empty(); }
  // Whether the circuit was seen not to fire at this photocurrent (at or past a silent bound).
  bool silent_at(double photocurrent) const {
    return photocurrent >= silent_above || (silent_below > 0 && photocurrent <= silent_below);
  }
  // The table's period at a photocurrent within [current.front(), current.back()].
  double period_at(double photocurrent) const;
  // The current the pixel integrates at this photocurrent (see above).
  double integrating_current(double photocurrent, double threshold_charge, double i_dark, double t_reset) const;
  // Sizes, order and signs; throws InputError naming `key`. Every period must exceed the table's
  // reset (or, without one, `pixel_t_reset`).
  void validate(const std::string& key, double pixel_t_reset) const;
};

// From TOML ({ current = [...], period = [...], charge = Q, t_reset = T, silent_below = I,
// silent_above = I }, all but the first two optional;
// numbers in A, s and C or strings with units) or
// from --set text in the same form; "none" or "" is no table. Throws InputError naming `key`.
TransferCurve transfer_from_toml(const TomlValue& value, const std::string& key);
TransferCurve transfer_from_text(const std::string& text, const std::string& key);

}  // namespace aesim
