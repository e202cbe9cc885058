#include "measure/firing_measure.hpp"

#include <cmath>
#include <limits>

namespace aesim {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double cross_time(const std::vector<double>& t, const std::vector<double>& v, std::size_t i, double level) {
  const double dv = v[i + 1] - v[i];
  return dv == 0 ? t[i] : t[i] + (level - v[i]) * (t[i + 1] - t[i]) / dv;
}

double value_at(const std::vector<double>& t, const std::vector<double>& v, std::size_t i, double when) {
  const double dt = t[i + 1] - t[i];
  return dt == 0 ? v[i] : v[i] + (when - t[i]) * (v[i + 1] - v[i]) / dt;
}

}  // namespace

FiringMeasure measure_firings(const Waveform& w, double vdd) {
  FiringMeasure m;
  m.period = m.pulse = m.supply_charge = m.onset_level = kNaN;
  const double half = vdd / 2, onset = vdd / 10;
  const std::size_t n = w.t.size();
  std::vector<double> falls, onset_levels;
  std::vector<std::size_t> fire_index;
  bool armed = true;  // a new onset only after out went back low
  for (std::size_t i = 0; i + 1 < n; ++i) {
    if (w.out[i] < half && w.out[i + 1] >= half) {
      m.fires.push_back(cross_time(w.t, w.out, i, half));
      fire_index.push_back(i);
    }
    if (w.out[i] >= half && w.out[i + 1] < half && !m.fires.empty()) falls.push_back(cross_time(w.t, w.out, i, half));
    if (!w.probe.empty() && armed && w.out[i] < onset && w.out[i + 1] >= onset) {
      onset_levels.push_back(w.probe[i]);
      armed = false;
    }
    if (w.out[i + 1] < onset) armed = true;
  }
  const std::size_t fires = m.fires.size();
  if (fires < 3) return m;
  m.period = (m.fires.back() - m.fires[1]) / static_cast<double>(fires - 2);
  double pulse = 0;
  std::size_t pulses = 0;
  for (std::size_t k = 1; k < fires; ++k) {
    for (double f : falls) {
      if (f > m.fires[k]) {
        if (k + 1 == fires || f < m.fires[k + 1]) {
          pulse += f - m.fires[k];
          ++pulses;
        }
        break;
      }
    }
  }
  if (pulses > 0) m.pulse = pulse / static_cast<double>(pulses);
  // Charge from the supply between the second and the last firing (trapezoids; ngspice counts a
  // delivering supply's current negative).
  double charge = 0;
  for (std::size_t i = fire_index[1]; i < fire_index.back(); ++i) {
    charge -= 0.5 * (w.supply[i] + w.supply[i + 1]) * (w.t[i + 1] - w.t[i]);
  }
  m.supply_charge = charge / static_cast<double>(fires - 2);
  if (onset_levels.size() >= 2) {
    double sum = 0;
    for (std::size_t k = 1; k < onset_levels.size(); ++k) sum += onset_levels[k];
    m.onset_level = sum / static_cast<double>(onset_levels.size() - 1);
    // Integrating upwards: the node is higher at the onset than halfway between two firings.
    const double mid_time = 0.5 * (m.fires[1] + m.fires[2]);
    for (std::size_t i = fire_index[1]; i + 1 < n; ++i) {
      if (w.t[i + 1] >= mid_time) {
        m.probe_rising = m.onset_level > value_at(w.t, w.probe, i, mid_time);
        break;
      }
    }
  }
  return m;
}

double comparator_delay(const Waveform& w, const FiringMeasure& m, double trip_level) {
  if (w.probe.empty() || m.fires.size() < 3 || !std::isfinite(trip_level)) return kNaN;
  const double sign = m.probe_rising ? 1.0 : -1.0;
  double sum = 0;
  std::size_t count = 0;
  std::size_t i = 0;
  for (std::size_t k = 1; k < m.fires.size(); ++k) {
    // The last crossing of the trip level, in the integrating direction, before this firing.
    double crossing = kNaN;
    for (; i + 1 < w.t.size() && w.t[i + 1] <= m.fires[k]; ++i) {
      if (sign * (w.probe[i] - trip_level) < 0 && sign * (w.probe[i + 1] - trip_level) >= 0) {
        crossing = cross_time(w.t, w.probe, i, trip_level);
      }
    }
    if (std::isfinite(crossing) && crossing > m.fires[k - 1]) {
      sum += m.fires[k] - crossing;
      ++count;
    }
  }
  return count > 0 ? sum / static_cast<double>(count) : kNaN;
}

}  // namespace aesim
