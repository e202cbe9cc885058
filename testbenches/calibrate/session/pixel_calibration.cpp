#include "session/pixel_calibration.hpp"

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <functional>
#include <limits>
#include <mutex>
#include <thread>

#include <fmt/format.h>

#include "errors/input_error.hpp"
#include "files/scratch_folder.hpp"
#include "measure/firing_measure.hpp"
#include "ngspice/ngspice_run.hpp"

namespace aesim {
namespace {

namespace fs = std::filesystem;

constexpr double kUnmeasured = std::numeric_limits<double>::quiet_NaN();
// ngspice's largest step is the period over this: the firing and reset edges are then placed to
// 1/500 of a period (Gear's error control refines the edges themselves), and the mean period over
// `firings` periods to 2/(500 * firings).
constexpr double kStepsPerPeriod = 500;
// Transients one point may take to find its period: each unfired run looks 30x further.
constexpr int kMaxRuns = 6;

struct PointRun {
  CalibrationPoint point;
  Waveform wave;
  FiringMeasure measure;
};

PointRun measure_point(const PixelDeck& deck, const CalibrationOptions& o, double current, std::optional<unsigned> seed,
                       double guess, const fs::path& scratch, const std::string& name) {
  PointRun r;
  r.point.current = current;
  r.point.period = r.point.pulse = r.point.comparator_delay = r.point.supply_charge = kUnmeasured;
  const auto wanted = static_cast<std::size_t>(o.firings + 2);
  double finer = 1;  // after ngspice gave up on a step, the largest step is cut tenfold, twice at most
  for (int run = 0; run < kMaxRuns; ++run) {
    TransientRequest request{current, guess * (o.firings + 2.5), guess / kStepsPerPeriod / finer, seed};
    try {
      r.wave = run_transient(deck, o.vdd, request, scratch, name);
    } catch (const TransientAborted& e) {
      if (finer >= 100) throw InputError(e.what());
      finer *= 10;
      --run;
      continue;
    }
    r.measure = measure_firings(r.wave, o.vdd);
    ++r.point.runs;
    r.point.simulated += request.t_stop;
    const std::size_t fired = r.measure.fires.size();
    if (fired >= wanted && r.measure.period > guess / 2 && r.measure.period < guess * 2) {
      r.point.period = r.measure.period;
      r.point.pulse = r.measure.pulse;
      r.point.supply_charge = r.measure.supply_charge;
      return r;
    }
    if (fired >= 3) {
      guess = r.measure.period;
    } else if (fired >= 1) {
      guess = request.t_stop / static_cast<double>(fired);
    } else {
      guess *= 30;
    }
  }
  return r;
}

// Runs `count` jobs on `jobs` threads; the first exception stops the rest and is rethrown.
void run_parallel(int count, int jobs, const std::function<void(int)>& job, const std::function<void(int)>& done) {
  std::atomic<int> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr error;
  std::mutex lock;
  int finished = 0;
  auto worker = [&] {
    for (int i = next++; i < count && !failed; i = next++) {
      try {
        job(i);
        std::lock_guard<std::mutex> g(lock);
        done(++finished);
      } catch (...) {
        std::lock_guard<std::mutex> g(lock);
        if (!error) error = std::current_exception();
        failed = true;
      }
    }
  };
  std::vector<std::thread> threads;
  for (int t = 1; t < std::min(jobs, count); ++t) threads.emplace_back(worker);
  worker();
  for (std::thread& t : threads) t.join();
  if (error) std::rethrow_exception(error);
}

std::function<void(int)> progress_bar(bool show, int total, const char* what) {
  if (!show) return [](int) {};
  return [total, what](int done) {
    const int width = 30, filled = width * done / total;
    std::fprintf(stderr, "\raesim calibrate: [%s%s] %d/%d %s", std::string(filled, '#').c_str(),
                 std::string(width - filled, ' ').c_str(), done, total, what);
    if (done == total) std::fputc('\n', stderr);
    std::fflush(stderr);
  };
}

}  // namespace

Calibration calibrate_pixel(const PixelDeck& deck, const CalibrationOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  Calibration c;
  c.ngspice = ngspice_version();
  const ScratchFolder scratch(fs::temp_directory_path() / fmt::format("aesim-calibrate-{}", ::getpid()));
  std::vector<PointRun> runs(static_cast<std::size_t>(o.points));
  run_parallel(
      o.points, o.jobs,
      [&](int k) {
        const double u = o.points > 1 ? static_cast<double>(k) / (o.points - 1) : 0.0;
        const double current = o.i_low * std::pow(o.i_high / o.i_low, u);
        runs[static_cast<std::size_t>(k)] =
            measure_point(deck, o, current, std::nullopt, o.charge_guess / current, scratch.path(), fmt::format("p{:03d}", k));
      },
      progress_bar(o.progress, o.points, "photocurrents"));

  // The comparator trips where the probe node stands when out starts to rise under the weakest
  // light: its ramp is then so slow that it moves nothing during the comparator's delay.
  c.trip_level = kUnmeasured;
  for (const PointRun& r : runs) {
    if (std::isfinite(r.point.period)) {
      c.trip_level = r.measure.onset_level;
      break;
    }
  }
  for (PointRun& r : runs) {
    if (std::isfinite(r.point.period)) {
      r.point.comparator_delay = comparator_delay(r.wave, r.measure, c.trip_level);
      c.current.push_back(r.point.current);
      c.period.push_back(r.point.period);
    }
    c.points.push_back(r.point);
  }
  if (c.current.empty()) {
    throw InputError(fmt::format("deck '{}': the pixel never fires between {:.3g} A and {:.3g} A (out never rises "
                                 "through vdd/2 = {:.3g} V)",
                                 deck.path, o.i_low, o.i_high, o.vdd / 2));
  }
  if (c.current.size() < 3) {
    throw InputError(fmt::format("deck '{}': the pixel fires at only {} of the {} photocurrents; widen --currents",
                                 deck.path, c.current.size(), o.points));
  }
  c.fit = fit_pixel(c.current, c.period);
  std::vector<double> charge_periods, charges;
  for (const CalibrationPoint& p : c.points) {
    if (std::isfinite(p.period) && std::isfinite(p.supply_charge)) {
      charge_periods.push_back(p.period);
      charges.push_back(p.supply_charge);
    }
  }
  c.supply = fit_supply(charge_periods, charges);

  if (o.mc > 0) {
    c.mc_current = std::sqrt(o.i_low * o.i_high);
    const double guess = c.fit.period(c.mc_current);
    c.mc_periods.assign(static_cast<std::size_t>(o.mc), kUnmeasured);
    run_parallel(
        o.mc, o.jobs,
        [&](int k) {
          const PointRun r = measure_point(deck, o, c.mc_current, static_cast<unsigned>(k + 1), guess, scratch.path(),
                                           fmt::format("mc{:04d}", k));
          if (!std::isfinite(r.point.period)) {
            throw InputError(fmt::format("deck '{}': Monte Carlo run {} never fires at {:.3g} A", deck.path, k + 1,
                                         c.mc_current));
          }
          c.mc_periods[static_cast<std::size_t>(k)] = r.point.period;
        },
        progress_bar(o.progress, o.mc, "Monte Carlo runs"));
    // The spread of the integration time (period less reset) is the threshold charge's spread.
    double mean = 0, var = 0;
    for (double p : c.mc_periods) mean += p - c.fit.t_reset;
    mean /= o.mc;
    for (double p : c.mc_periods) var += (p - c.fit.t_reset - mean) * (p - c.fit.t_reset - mean);
    c.mismatch = o.mc > 1 ? std::sqrt(var / (o.mc - 1)) / mean : 0.0;
  }
  c.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return c;
}

}  // namespace aesim
