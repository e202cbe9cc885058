#include "chart/calibration_chart.hpp"

#include <cmath>
#include <fstream>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/files/data_dir.hpp"
#include "aesim/process/child_process.hpp"

namespace aesim {
namespace {

// The period a pixel of these parameters fires with under constant photocurrent I.
double model_period(const PixelParams& p, double photocurrent) {
  const double current = p.integrating_current_at(photocurrent);
  return current > 0 ? p.threshold_charge() / current + p.t_reset : NAN;
}

}  // namespace

void draw_calibration_chart(const Calibration& c, const PixelParams& calibrated, const PixelParams& ideal,
                            const std::string& data_path, const std::string& png_path) {
  if (!program_available("gnuplot")) throw InputError("--chart: gnuplot is not installed (apt-get install gnuplot-nox)");
  {
    std::ofstream out(data_path);
    out << "current_A,ngspice_s,model_s,ideal_s,ideal_at_ngspice_s\n";
    const double lo = c.points.front().current / 10, hi = c.points.back().current * 10;
    const int steps = 200;
    for (int k = 0; k <= steps; ++k) {
      const double i = lo * std::pow(hi / lo, static_cast<double>(k) / steps);
      out << fmt::format("{:.6g},,{:.6g},{:.6g},\n", i, model_period(calibrated, i), model_period(ideal, i));
    }
    for (const CalibrationPoint& p : c.points) {
      if (std::isfinite(p.period)) {
        out << fmt::format("{:.6g},{:.6g},,,{:.6g}\n", p.current, p.period, model_period(ideal, p.current));
      }
    }
    if (!out) throw OutputError(fmt::format("cannot write '{}'", data_path));
  }
  // Outside the currents the circuit fired at (the table's ends) the chart shades the model's
  // extrapolation.
  const std::string script = data_dir() + "/scripts/charts/calibration.gp";
  if (run_child("gnuplot", {"-c", script, data_path, png_path, fmt::format("{:.6e}", c.current.front()),
                            fmt::format("{:.6e}", c.current.back())}) != 0) {
    throw OutputError(fmt::format("gnuplot failed on '{}' (its message above); no chart written", script));
  }
}

}  // namespace aesim
