#pragma once
#include <string>

#include "aesim/config/sensor_config.hpp"
#include "deck/pixel_deck.hpp"
#include "session/pixel_calibration.hpp"

namespace aesim {

// The base preset with the pixel fitted (docs/reference.md section 7): pixel.c_int (the threshold charge at the
// base's dv_int), t_reset, i_dark and transfer; power.vdd, e_pixel_event (supply energy per firing
// beyond c_int * dv_int * vdd) and p_static_pixel (the supply's current between firings); and
// pixel.mismatch when Monte Carlo runs measured it.
SensorConfig calibrated_config(SensorConfig base, const Calibration& c, double vdd);

// When the supply's charge per firing is below the threshold charge the power model already counts
// as recharging c_int (so e_pixel_event, which cannot be negative, is set to 0): why, and by how
// much each firing's energy is overstated; "" otherwise.
std::string per_firing_energy_note(const Calibration& c, double vdd);

// The preset as TOML: every key, with the provenance (deck, hash, ngspice, options) and the
// measured table with the fit's residuals in comments. Same inputs, same bytes.
std::string calibrated_preset_text(const SensorConfig& config, const Calibration& c, const PixelDeck& deck,
                                   const std::string& base, const CalibrationOptions& options);

}  // namespace aesim
