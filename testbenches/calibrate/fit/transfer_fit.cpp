#include "fit/transfer_fit.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace aesim {
namespace {

// Weighted least squares of y ~ a * x + b with weights w; `b_max` bounds b to [0, b_max], the
// bounded optimum then being on the bound (the problem is convex in a and b).
struct Line {
  double a = 0, b = 0;
};

Line fit_line(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& w, double b_max) {
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
  if (!(det > 0) || l.b < 0 || l.b > b_max) {
    l.b = std::clamp(det > 0 ? l.b : 0.0, 0.0, b_max);
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
  Trial t{i_dark, 0, fit_line(x, period, w, t_max)};
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

SupplyFit fit_supply(const std::vector<double>& period, const std::vector<double>& charge) {
  // charge = static * period + dynamic: a line in period with intercept `dynamic` >= 0.
  std::vector<double> w(period.size());
  for (std::size_t k = 0; k < period.size(); ++k) w[k] = charge[k] != 0 ? 1.0 / (charge[k] * charge[k]) : 1.0;
  const double big = *std::max_element(charge.begin(), charge.end());
  const Line l = fit_line(period, charge, w, std::max(0.0, big));
  SupplyFit fit{l.b, std::max(0.0, l.a), 0, 0};
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
