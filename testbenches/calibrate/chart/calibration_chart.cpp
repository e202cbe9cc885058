#include "chart/calibration_chart.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>

#include <fmt/format.h>

#include "errors/input_error.hpp"
#include "files/data_dir.hpp"
#include "process/child_process.hpp"

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
  // The range the circuit fired over (the table's ends): outside it the chart shades the model's
  // extrapolation.
  double fired_lo = 0, fired_hi = 0;
  for (const CalibrationPoint& p : c.points) {
    if (!std::isfinite(p.period)) continue;
    fired_lo = fired_lo == 0 ? p.current : std::min(fired_lo, p.current);
    fired_hi = std::max(fired_hi, p.current);
  }
  const std::string script = data_dir() + "/scripts/charts/calibration.gp";
  if (run_child("gnuplot", {"-c", script, data_path, png_path, fmt::format("{:.6e}", fired_lo),
                            fmt::format("{:.6e}", fired_hi)}) != 0) {
    throw OutputError(fmt::format("gnuplot failed on '{}' (its message above); no chart written", script));
  }
}

}  // namespace aesim
