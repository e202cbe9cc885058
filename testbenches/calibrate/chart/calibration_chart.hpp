#pragma once
#include <string>

#include "aesim/config/sensor_config.hpp"
#include "session/pixel_calibration.hpp"

namespace aesim {

// Period against photocurrent over the range (and a decade beyond): ngspice's points, the
// calibrated model (what aesim's pixel does with the preset: the table, eq. 2 beyond it) and the
// ideal eq. 2 pixel of the base preset. Data into `data_path` (CSV), drawn by gnuplot
// (scripts/charts/calibration.gp, paths as arguments) into `png_path`. Throws OutputError if
// gnuplot fails, InputError if it is missing.
void draw_calibration_chart(const Calibration& c, const PixelParams& calibrated, const PixelParams& ideal,
                            const std::string& data_path, const std::string& png_path);

}  // namespace aesim
