#include "fit/transfer_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace aesim {
namespace {

// Weighted least squares of y ~ a * x + b with weights w, b within [b_min, b_max]: the bounded
// optimum is then on the bound (the problem is convex in a and b).
struct Line {
  double a = 0, b = 0;
};

Line fit_line(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& w, double b_min,
              double b_max) {
  double sw = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    sw += w[k];
    sx += w[k] * x[k];
    sy += w[k] * y[k];
    sxx += w[k] * x[k] * x[k];
    sxy += w[k] * x[k] * y[k];
  }
  const double det = sw * sxx - sx * sx;
  Line l;
  if (det > 0) {
    l.a = (sw * sxy - sx * sy) / det;
    l.b = (sxx * sy - sx * sxy) / det;
  }
  if (!(det > 0) || l.b < b_min || l.b > b_max) {
    l.b = std::clamp(det > 0 ? l.b : 0.0, b_min, b_max);
    double num = 0, den = 0;
    for (std::size_t k = 0; k < x.size(); ++k) {
      num += w[k] * x[k] * (y[k] - l.b);
      den += w[k] * x[k] * x[k];
    }
    l.a = den > 0 ? num / den : 0;
  }
  return l;
}

struct Trial {
  double i_dark = 0, cost = 0;
  Line line;
};

Trial trial(const std::vector<double>& current, const std::vector<double>& period, double i_dark, double t_max) {
  std::vector<double> x(current.size()), w(current.size());
  for (std::size_t k = 0; k < current.size(); ++k) {
    x[k] = 1.0 / (current[k] + i_dark);
    w[k] = 1.0 / (period[k] * period[k]);
  }
  Trial t{i_dark, 0, fit_line(x, period, w, 0.0, t_max)};
  for (std::size_t k = 0; k < current.size(); ++k) {
    const double r = (t.line.a * x[k] + t.line.b - period[k]) / period[k];
    t.cost += r * r;
  }
  return t;
}

}  // namespace

PixelFit fit_pixel(const std::vector<double>& current, const std::vector<double>& period) {
  if (current.size() < 3 || current.size() != period.size()) {
    throw std::invalid_argument("fit_pixel: needs at least three (current, period) points");
  }
  const double t_max = 0.99 * *std::min_element(period.begin(), period.end());
  const double lo = current.front() * 1e-6, hi = current.back() * 10;
  // Scan i_dark over decades (and zero), then refine the best bracket in log(i_dark).
  Trial best = trial(current, period, 0.0, t_max);
  const int steps = 240;
  int best_step = -1;
  for (int s = 0; s <= steps; ++s) {
    const double i = lo * std::pow(hi / lo, static_cast<double>(s) / steps);
    const Trial t = trial(current, period, i, t_max);
    if (t.cost < best.cost) {
      best = t;
      best_step = s;
    }
  }
  if (best_step >= 0) {
    double a = std::log(lo) + std::log(hi / lo) * std::max(0, best_step - 1) / steps;
    double b = std::log(lo) + std::log(hi / lo) * std::min(steps, best_step + 1) / steps;
    const double g = 0.5 * (std::sqrt(5.0) - 1);
    for (int it = 0; it < 80; ++it) {
      const double c = b - g * (b - a), d = a + g * (b - a);
      if (trial(current, period, std::exp(c), t_max).cost < trial(current, period, std::exp(d), t_max).cost) {
        b = d;
      } else {
        a = c;
      }
    }
    const Trial refined = trial(current, period, std::exp(0.5 * (a + b)), t_max);
    if (refined.cost < best.cost) best = refined;
  }
  PixelFit fit;
  fit.charge = best.line.a;
  fit.t_reset = best.line.b;
  fit.i_dark = best.i_dark;
  double sum = 0;
  for (std::size_t k = 0; k < current.size(); ++k) {
    const double r = (fit.period(current[k]) - period[k]) / period[k];
    fit.residuals.push_back(r);
    sum += r * r;
    fit.max_residual = std::max(fit.max_residual, std::fabs(r));
  }
  fit.rms_residual = std::sqrt(sum / static_cast<double>(current.size()));
  return fit;
}

namespace {

// Q minimising the relative residuals of Q / (I + i_dark) against `t`, and their sum of squares.
struct Integration {
  double charge = 0, cost = std::numeric_limits<double>::infinity();
};

Integration fit_integration(const std::vector<double>& current, const std::vector<double>& t, double i_dark) {
  double num = 0, den = 0;
  for (std::size_t k = 0; k < current.size(); ++k) {
    const double x = 1.0 / (current[k] + i_dark);
    num += x / t[k];
    den += x * x / (t[k] * t[k]);
  }
  Integration fit;
  if (!(den > 0)) return fit;
  fit.charge = num / den;
  fit.cost = 0;
  for (std::size_t k = 0; k < current.size(); ++k) {
    const double r = fit.charge / ((current[k] + i_dark) * t[k]) - 1;
    fit.cost += r * r;
  }
  return fit;
}

// i_dark along one real axis: s in [-1, 0) a leak from just short of the lowest current (where the
// pixel would never fire) down to nothing, s in [0, 1] a dark current from a millionth of the
// lowest current up to ten times the highest.
double i_dark_at(double s, double lowest, double highest) {
  if (s < 0) return -lowest * (1 - std::pow(10.0, 12 * s));
  const double lo = lowest * 1e-6, hi = highest * 10;
  return lo * std::pow(hi / lo, s);
}

}  // namespace

CircuitFit fit_circuit(const std::vector<double>& current, const std::vector<double>& period,
                       const std::vector<double>& pulse) {
  const std::size_t n = current.size();
  if (n < 3 || period.size() != n || pulse.size() != n) {
    throw std::invalid_argument("fit_circuit: needs at least three (current, period, pulse) points");
  }
  std::vector<double> integration(n);
  for (std::size_t k = 0; k < n; ++k) {
    if (!(pulse[k] > 0 && pulse[k] < period[k])) throw std::invalid_argument("fit_circuit: a pulse outside (0, period)");
    integration[k] = period[k] - pulse[k];
  }
  CircuitFit fit;
  // The reset: 1 / pulse = 1 / t_r - I / (t_r I_r), a line in I, fitted on relative residuals.
  {
    std::vector<double> y(n), w(n);
    for (std::size_t k = 0; k < n; ++k) {
      y[k] = 1.0 / pulse[k];
      w[k] = pulse[k] * pulse[k];
    }
    const Line l = fit_line(current, y, w, 0.0, std::numeric_limits<double>::infinity());
    // A latch more than ten times past the brightest point measured is a slope too slight to tell
    // from the pulses' own scatter, not a latch the table shows.
    if (l.a < 0 && l.b > 0 && -l.b / l.a < 10 * current.back()) {
      fit.t_r = 1.0 / l.b;
      fit.i_r = -l.b / l.a;
    } else {
      double sy = 0, syy = 0;
      for (std::size_t k = 0; k < n; ++k) {
        sy += y[k];
        syy += y[k] * y[k];
      }
      fit.t_r = sy / syy;  // the constant closest to every pulse in relative terms
    }
  }
  // The integration: scan i_dark over both signs, then refine around the best by golden section.
  const double lowest = current.front(), highest = current.back();
  const int steps = 480;
  int best_step = 0;
  Integration best = fit_integration(current, integration, 0.0);
  double best_i = 0;
  for (int k = 0; k <= steps; ++k) {
    const double s = -1 + 2.0 * k / steps;
    const double i = i_dark_at(s, lowest, highest);
    const Integration t = fit_integration(current, integration, i);
    if (t.cost < best.cost) {
      best = t;
      best_i = i;
      best_step = k;
    }
  }
  double a = -1 + 2.0 * std::max(0, best_step - 1) / steps, b = -1 + 2.0 * std::min(steps, best_step + 1) / steps;
  const double g = 0.5 * (std::sqrt(5.0) - 1);
  for (int it = 0; it < 80; ++it) {
    const double c = b - g * (b - a), d = a + g * (b - a);
    if (fit_integration(current, integration, i_dark_at(c, lowest, highest)).cost <
        fit_integration(current, integration, i_dark_at(d, lowest, highest)).cost) {
      b = d;
    } else {
      a = c;
    }
  }
  const double refined_i = i_dark_at(0.5 * (a + b), lowest, highest);
  const Integration refined = fit_integration(current, integration, refined_i);
  if (refined.cost < best.cost) {
    best = refined;
    best_i = refined_i;
  }
  fit.charge = best.charge;
  fit.i_dark = best_i;
  double sum = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double r = (fit.period(current[k]) - period[k]) / period[k];
    fit.residuals.push_back(r);
    sum += r * r;
    fit.max_residual = std::max(fit.max_residual, std::fabs(r));
  }
  fit.rms_residual = std::sqrt(sum / static_cast<double>(n));
  return fit;
}

SupplyFit fit_supply(const std::vector<double>& period, const std::vector<double>& charge) {
  // charge = static * period + dynamic: a line in period with intercept `dynamic` >= 0.
  std::vector<double> w(period.size());
  for (std::size_t k = 0; k < period.size(); ++k) w[k] = charge[k] != 0 ? 1.0 / (charge[k] * charge[k]) : 1.0;
  const double big = *std::max_element(charge.begin(), charge.end());
  const Line l = fit_line(period, charge, w, 0.0, std::max(0.0, big));
  const double inf = std::numeric_limits<double>::infinity();
  const Line free = fit_line(period, charge, w, -inf, inf);
  SupplyFit fit{l.b, std::max(0.0, l.a), 0, 0, free.b, free.a};
  double sum = 0;
  for (std::size_t k = 0; k < period.size(); ++k) {
    if (charge[k] == 0) continue;
    const double r = (fit.charge_per_firing + fit.static_current * period[k]) / charge[k] - 1;
    sum += r * r;
    fit.max_residual = std::max(fit.max_residual, std::fabs(r));
  }
  fit.rms_residual = period.empty() ? 0 : std::sqrt(sum / static_cast<double>(period.size()));
  return fit;
}

}  // namespace aesim
