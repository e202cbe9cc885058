#include "session/pixel_calibration.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <mutex>
#include <thread>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/files/scratch_folder.hpp"
#include "measure/firing_measure.hpp"
#include "aesim/output/temp_files.hpp"
#include "ngspice/ngspice_run.hpp"

namespace aesim {
namespace {

namespace fs = std::filesystem;

constexpr double kUnmeasured = std::numeric_limits<double>::quiet_NaN();
// ngspice's largest step is the period over this: the firing and reset edges are then placed to
// 1/500 of a period (Gear's error control refines the edges themselves), and the mean period over
// `firings` periods to 2/(500 * firings).
constexpr double kStepsPerPeriod = 500;
// ngspice seeds its statistical functions from the clock unless told; a deck that uses them is
// calibrated on this draw, so that the same deck gives the same preset.
constexpr unsigned kTableSeed = 1;
// The most a midpoint's log-log interpolation may be off, by the fit's prediction, before the
// midpoint is measured too; and the most points a table may grow to.
constexpr double kInterpolationTolerance = 0.002;
constexpr std::size_t kMaxTablePoints = 400;
// Transients one point may take to find its period: each unfired run looks 30x further, up to
// periods of kLongestPeriod (a pixel firing less than once in 1000 s is dark for any sensor, and
// ngspice's time steps collapse over simulated days: 59 s of ngspice for 2.5e7 s of a leaky node).
constexpr int kMaxRuns = 6;
constexpr double kLongestPeriod = 1000;

// What a silent run showed: the kind, for the calibration's bounds, and the words, for the user.
struct Silence {
  Stop stop = Stop::none;
  std::string text;
};

// A run in which the pixel never fired, looked at for the reason it never will: out held high
// (latched), or the probe node settled (it moved by under 1 % in the run's last 30 % of what it
// moved before: a leak or a clamp balances the photocurrent, not a ramp too slow for the run).
// Stop::none when neither: the next run waits longer.
Silence why_silent(const Waveform& w, double vdd, const std::string& probe) {
  if (w.t.size() < 10) return {};
  const std::size_t n = w.t.size();
  // Weighed by time, not samples: ngspice takes long steps over a latched node and short ones over
  // the ramp before it.
  double high = 0;
  for (std::size_t k = 1; k < n; ++k) high += w.out[k] > vdd / 2 ? w.t[k] - w.t[k - 1] : 0;
  if (high * 2 > w.t.back() - w.t.front() && w.out.back() > vdd / 2) {
    // Held mid-rail rather than at the supply, out is more likely an analog node than a spike.
    return {Stop::latched, w.out.back() > 0.75 * vdd
                               ? fmt::format("out latched high ({:.3g} V)", w.out.back())
                               : fmt::format("out held at {:.3g} V, between the logic levels", w.out.back())};
  }
  if (w.probe.size() != n) return {};
  const double cut = w.t.front() + 0.7 * (w.t.back() - w.t.front());
  std::size_t k = 0;
  while (k + 1 < n && w.t[k] < cut) ++k;
  const double early = std::fabs(w.probe[k] - w.probe.front()), late = std::fabs(w.probe.back() - w.probe[k]);
  if (late <= 0.01 * early + 1e-6) {
    return {Stop::settled, fmt::format("node '{}' settles at {:.3g} V without out rising", probe, w.probe.back())};
  }
  return {};
}

struct PointRun {
  CalibrationPoint point;
  Waveform wave;
  FiringMeasure measure;
  bool abandoned = false;  // stopped by `abandon` before it had an answer
};

PointRun measure_point(const PixelDeck& deck, const CalibrationOptions& o, double current, std::optional<unsigned> mc_seed,
                       double guess, const fs::path& scratch, const std::string& name,
                       const std::function<bool()>& abandon = {}) {
  PointRun r;
  r.point.current = current;
  r.point.period = r.point.pulse = r.point.comparator_delay = r.point.supply_charge = kUnmeasured;
  const auto wanted = static_cast<std::size_t>(o.firings + 2);
  // After ngspice gives up on a transient: the next solver settings, and past the last, the
  // largest step cut tenfold, twice at most; then the current is left out.
  double finer = 1;
  std::size_t settings = 0;
  const std::size_t last_settings = kSolverLevels - 1;
  // The first firing starts from ngspice's all-zero state, not from a reset, and may take longer
  // than a period: once a run has seen it, the next runs last that long plus the periods.
  double first_fire = 0;
  // The last run that measured a period, and the largest step it had: ngspice's answer at another
  // step, kept with the point's.
  double earlier_period = kUnmeasured, earlier_step = kUnmeasured;
  for (int run = 0; run < kMaxRuns; ++run) {
    if (abandon && abandon()) {
      r.abandoned = true;
      return r;
    }
    const double t_stop = first_fire > 0 ? first_fire + guess * (o.firings + 1.5) : guess * (o.firings + 2.5);
    TransientRequest request{current, t_stop, guess / kStepsPerPeriod / finer, mc_seed.value_or(kTableSeed),
                             mc_seed.has_value(), settings, o.failure_log, abandon};
    try {
      r.wave = run_transient(deck, o.vdd, request, scratch, name);
    } catch (const TransientAbandoned&) {
      r.abandoned = true;
      return r;
    } catch (const InputError&) {
      // A Ctrl-C reaches ngspice too, which then fails: the interruption, not the deck, is why.
      if (interrupt_requested()) throw Interrupted(interrupt_requested());
      throw;
    } catch (const TransientAborted& e) {
      if (interrupt_requested()) throw Interrupted(interrupt_requested());
      if (settings < last_settings) {
        // A level whose tolerances are those just tried (a current too small to scale them up)
        // would fail the same way: the next that differs.
        const std::string tried = solver_settings(settings, current, o.vdd).label();
        do {
          ++settings;
        } while (settings < last_settings && solver_settings(settings, current, o.vdd).label() == tried);
      } else if (finer < 100) {
        finer *= 10;
      } else {
        r.point.aborted = e.what();
        return r;
      }
      --run;
      continue;
    }
    r.point.settings = settings;
    r.measure = measure_firings(r.wave, o.vdd);
    ++r.point.runs;
    r.point.simulated += request.t_stop;
    const std::size_t fired = r.measure.fires.size();
    if (fired >= 1) first_fire = r.measure.fires.front();
    const bool resolved = r.measure.period > guess / 2 && r.measure.period < guess * 2;
    // The last run keeps what it measured if it saw at least two periods at the step it was sized for.
    if ((fired >= wanted || (run + 1 == kMaxRuns && fired >= 3)) && resolved) {
      r.point.period = r.measure.period;
      r.point.pulse = r.measure.pulse;
      r.point.supply_charge = r.measure.supply_charge;
      r.point.step = request.t_max;
      if (std::isfinite(earlier_period) && std::fabs(earlier_step / request.t_max - 1) > 0.05) {
        r.point.earlier_period = earlier_period;
        r.point.earlier_step = earlier_step;
      }
      return r;
    }
    if (fired >= 3) {
      earlier_period = r.measure.period;
      earlier_step = request.t_max;
    }
    if (fired < 3) {
      // It never will, or not periodically: no longer run is worth waiting for. A pixel that fired
      // and then held out high (a reset the light outruns) has latched as surely as one that never
      // rose; one whose node settled after its last firing (a start-up transient through the
      // feedback capacitor can give one) has stopped as surely as one that never fired.
      const Silence seen = why_silent(r.wave, o.vdd, deck.probe);
      const bool settled_after = fired > 0 && r.measure.fires.back() < r.wave.t.front() + 0.7 * (r.wave.t.back() - r.wave.t.front());
      if (seen.stop != Stop::none && (fired == 0 || seen.stop == Stop::latched || settled_after)) {
        r.point.stop = seen.stop;
        r.point.seen =
            fired == 0 ? seen.text : fmt::format("fired {} time{}, then {}", fired, fired > 1 ? "s" : "", seen.text);
        return r;
      }
    }
    if (fired >= 3) {
      guess = r.measure.period;
    } else if (fired >= 1) {
      guess = request.t_stop / static_cast<double>(fired);
    } else if (guess >= kLongestPeriod) {
      break;
    } else {
      guess = std::min(guess * 30, kLongestPeriod);
    }
  }
  return r;
}

// The period measured at `current` (NaN: not measured, or it never fired).
double period_at(const std::vector<PointRun>& runs, double current) {
  for (const PointRun& r : runs) {
    if (r.point.current == current) return r.point.period;
  }
  return kUnmeasured;
}

// An added point whose period fell outside its interval's ends (calibrate_pixel's refinement).
struct OutsideEnds {
  double beyond;  // |log| of how far outside
  double a, b;    // A, the interval's ends
};

// Where the table's periods scatter by more than it resolves, in words with the evidence: the
// point furthest outside its neighbours' periods and, where a point's runs at two largest steps
// gave periods further apart than the table's tolerance, the one furthest apart. Empty when
// every added point lay between its neighbours.
std::string scatter_note(const std::vector<PointRun>& runs, const std::map<double, OutsideEnds>& outside) {
  if (outside.empty()) return "";
  double low = std::numeric_limits<double>::infinity(), high = 0, worst_at = 0;
  OutsideEnds worst{0, 0, 0};
  for (const auto& [current, o] : outside) {
    low = std::min(low, o.a);
    high = std::max(high, o.b);
    if (o.beyond > worst.beyond) {
      worst = o;
      worst_at = current;
    }
  }
  std::string text = fmt::format(
      "the periods between {:.3g} and {:.3g} A scatter by more than the table resolves: {} added point{} fell "
      "outside the periods either side by up to {:.2g} % (at {:.3g} A, {:.4g} s between {:.4g} and {:.4g} s)",
      low, high, outside.size(), outside.size() == 1 ? "" : "s", 100 * std::expm1(worst.beyond), worst_at,
      period_at(runs, worst_at), period_at(runs, worst.a), period_at(runs, worst.b));
  const CalibrationPoint* steps = nullptr;
  double apart = kInterpolationTolerance;
  for (const PointRun& r : runs) {
    const CalibrationPoint& p = r.point;
    if (p.current < low || p.current > high || !std::isfinite(p.period) || !std::isfinite(p.earlier_period)) continue;
    const double d = std::fabs(std::log(p.period / p.earlier_period));
    if (d > apart) {
      apart = d;
      steps = &p;
    }
  }
  if (steps) {
    text += fmt::format("; ngspice's period there depends on its time step (at {:.3g} A, {:.4g} s with a largest step "
                        "of {:.3g} s, {:.4g} s with {:.3g} s)",
                        steps->current, steps->earlier_period, steps->earlier_step, steps->period, steps->step);
  }
  return text + "; the table was not refined further there and holds the periods measured";
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
        if (interrupt_requested()) throw Interrupted(interrupt_requested());
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
  // A signal stops the points politely: the scratch folder and its ngspice files are removed as
  // the stack unwinds, and the command exits with 128 + the signal.
  const Cooperative stop_politely;
  Calibration c;
  c.ngspice = ngspice_version();
  const ScratchFolder scratch(fs::absolute(fs::temp_directory_path()) / fmt::format("aesim-calibrate-{}", ::getpid()));
  std::vector<PointRun> runs;
  // Where the grid's runs showed the pixel stop: the brightest current at which its node settled
  // without firing periodically (a weaker light settles it lower still: a leak or a clamp that
  // balances one photocurrent balances a smaller one further from the threshold), and the weakest
  // at which out latched (a stronger light outruns the reset sooner). Currents beyond them are
  // not run, and a run under way there is stopped: a pixel that fires nowhere is told so after a
  // few transients, not after every current's.
  std::mutex bounds_lock;
  double settled_at = 0, latched_at = std::numeric_limits<double>::infinity();
  std::string settled_seen, latched_seen;
  auto beyond = [&](double current) {
    std::lock_guard<std::mutex> g(bounds_lock);
    return current < settled_at || current > latched_at;
  };
  auto learn = [&](const CalibrationPoint& p) {
    if (std::isfinite(p.period) || p.inferred) return;
    std::lock_guard<std::mutex> g(bounds_lock);
    if (p.stop == Stop::latched) {
      if (p.current < latched_at) {
        latched_at = p.current;
        latched_seen = p.seen;
      }
    } else if (p.stop == Stop::settled && p.current > settled_at) {
      settled_at = p.current;
      settled_seen = p.seen;
    }
  };
  // A current beyond the bounds: silent as the one that set them. Said the same way whether its own
  // run finished before the bound was known, was stopped, or never started, so that the preset is
  // the same whatever order the runs finished in.
  auto as_beyond = [&](CalibrationPoint& p) {
    p.period = p.pulse = p.comparator_delay = p.supply_charge = kUnmeasured;
    p.inferred = true;
    p.seen = p.current < settled_at ? fmt::format("as at {:.3g} A, a stronger light: {}", settled_at, settled_seen)
                                    : fmt::format("as at {:.3g} A, a weaker light: {}", latched_at, latched_seen);
  };
  auto measure_all = [&](const std::vector<double>& currents, const char* what) {
    const std::size_t first = runs.size();
    runs.resize(first + currents.size());
    run_parallel(
        static_cast<int>(currents.size()), o.jobs,
        [&](int k) {
          const std::size_t index = first + static_cast<std::size_t>(k);
          const double current = currents[static_cast<std::size_t>(k)];
          const auto abandon = [&beyond, current] { return beyond(current); };
          runs[index] = measure_point(deck, o, current, std::nullopt, o.charge_guess / current, scratch.path(),
                                      fmt::format("p{:03d}", index), abandon);
          if (!runs[index].abandoned) learn(runs[index].point);
        },
        progress_bar(o.progress, static_cast<int>(currents.size()), what));
    std::sort(runs.begin(), runs.end(), [](const PointRun& a, const PointRun& b) { return a.point.current < b.point.current; });
  };
  // The grid's currents from both ends inwards, halving (the brightest, the weakest, the middle,
  // the quarters, ...): where the pixel stops shows at the fewest runs.
  const auto grid_current = [&](int k) {
    return o.i_low * std::pow(o.i_high / o.i_low, static_cast<double>(k) / (o.points - 1));
  };
  std::vector<double> grid{grid_current(o.points - 1), grid_current(0)};
  std::vector<std::pair<int, int>> spans{{0, o.points - 1}};
  for (std::size_t next = 0; next < spans.size(); ++next) {
    const auto [a, b] = spans[next];
    if (b - a < 2) continue;
    const int m = (a + b) / 2;
    grid.push_back(grid_current(m));
    spans.emplace_back(a, m);
    spans.emplace_back(m, b);
  }
  measure_all(grid, "photocurrents");
  for (PointRun& r : runs) {
    const bool silent = !std::isfinite(r.point.period) && r.point.aborted.empty();
    if (r.abandoned || (silent && beyond(r.point.current))) as_beyond(r.point);
  }
  auto fired = [&] {
    std::vector<const PointRun*> out;
    for (const PointRun& r : runs) {
      if (std::isfinite(r.point.period)) out.push_back(&r);
    }
    return out;
  };
  // ngspice's reason for the currents it gave up on under every setting, once each.
  auto aborted = [&] {
    std::size_t n = 0;
    std::string why;
    for (const PointRun& r : runs) {
      if (r.point.aborted.empty()) continue;
      ++n;
      if (why.empty()) why = r.point.aborted;
    }
    return std::make_pair(n, why);
  };
  if (fired().size() < 3) {
    const auto [n_aborted, why] = aborted();
    const std::string gave_up =
        n_aborted == 0 ? std::string()
                       : fmt::format("; ngspice gave up at {} of them under every solver setting ({})", n_aborted, why);
    if (n_aborted == runs.size()) {
      throw InputError(fmt::format("deck '{}': ngspice gave up at every one of the {} photocurrents under every solver "
                                   "setting ({})",
                                   deck.given, runs.size(), why));
    }
    if (fired().empty()) {
      // What the runs showed, at the brightest current that showed something.
      std::string seen;
      std::size_t not_run = 0;  // beyond the current named
      for (auto it = runs.rbegin(); it != runs.rend(); ++it) {
        if (it->point.inferred) {
          ++not_run;
        } else if (seen.empty() && !it->point.seen.empty()) {
          seen = fmt::format("; at {:.3g} A {}", it->point.current, it->point.seen);
        }
      }
      if (not_run > 0) {
        seen += fmt::format(" ({} of the {} currents, beyond it, were not waited for)", not_run, runs.size());
      }
      throw InputError(fmt::format("deck '{}': the pixel never fires between {:.3g} A and {:.3g} A (no rising edge "
                                   "of out through vdd/2 = {:.3g} V){}{}",
                                   deck.given, o.i_low, o.i_high, o.vdd / 2, seen, gave_up));
    }
    // Where it fired, and what the nearest currents on either side showed: where to look next.
    std::vector<double> fired_at;
    for (const PointRun* r : fired()) fired_at.push_back(r->point.current);
    std::string where = fmt::format("{:.3g} A", fmt::join(fired_at, ", "));
    const auto nearest = [](auto from, auto to) {
      for (auto it = from; it != to; ++it) {
        if (!std::isfinite(it->point.period) && !it->point.inferred && !it->point.seen.empty()) {
          return fmt::format("at {:.3g} A {}", it->point.current, it->point.seen);
        }
      }
      return std::string();
    };
    const auto first_fired = std::find_if(runs.begin(), runs.end(), [](const PointRun& r) { return std::isfinite(r.point.period); });
    const auto last_fired = std::find_if(runs.rbegin(), runs.rend(), [](const PointRun& r) { return std::isfinite(r.point.period); });
    for (const std::string& side :
         {nearest(std::make_reverse_iterator(first_fired), runs.rend()), nearest(last_fired.base(), runs.end())}) {
      if (!side.empty()) where += "; " + side;
    }
    throw InputError(fmt::format("deck '{}': the pixel fires at only {} of the {} photocurrents ({}){}; a table "
                                 "needs 3: widen --currents, or add --points",
                                 deck.given, fired().size(), runs.size(), where, gave_up));
  }
  // The model interpolates the table log-log, which bends away from eq. 2 where the dark current
  // or the reset matter (3.6 % between points half a decade apart at the dark current's knee).
  // Where an interval's midpoint would be off by more than kInterpolationTolerance, the midpoint
  // is measured too, until none is (each pass halves the spacing, so the error falls fourfold),
  // within kMaxTablePoints. The miss is the fit's bend, known in closed form, or that with the bend
  // of the table's departure from the fit, from the points around the interval: a circuit far
  // from eq. 2 bends where the fit does not (on a SKY130 axon hillock 5 to 15 % off eq. 2, the
  // fit's bend alone leaves a 0.8 % miss at 2 pA, between the points at 1 and 3.16 pA). A bend
  // read from three measured points holds their scatter too, which halving does not shrink (a
  // scatter e reads as a miss of about e / 2 at every spacing: a deck whose periods scatter by
  // half a percent grew its table to the 400-point limit), so the halves of an interval whose
  // added midpoint missed by M are refined for the departure's bend only while M / 4, what
  // halving leaves of a true bend, is still over the tolerance.
  std::map<double, double> midpoint_miss;  // added current -> |log| of its interval's miss, measured
  // A smooth period falls with the light, or turns once to rise towards a latch: a midpoint lies
  // between its interval's ends, or beyond them where the period turns, and the points around turn
  // no more. An added point whose period lies outside its ends by more than the tolerance with the
  // periods turning again at a point beyond them shows that they scatter by more than the table
  // resolves there (ngspice's own accuracy: near a leak's knee its period moved by 5 % with its
  // largest step on a foundry deck), which more points would only sample again (that deck grew its
  // table to 289 points in 581 transients). Intervals it ends are not halved.
  std::map<double, OutsideEnds> outside;  // by the added current
  for (;;) {
    const std::vector<const PointRun*> f = fired();
    std::vector<double> current, period;
    for (const PointRun* r : f) {
      current.push_back(r->point.current);
      period.push_back(r->point.period);
    }
    const PixelFit fit = fit_pixel(current, period);
    std::vector<double> departure;  // log of the table over the fit, at each point
    for (std::size_t i = 0; i < f.size(); ++i) departure.push_back(std::log(period[i] / fit.period(current[i])));
    // The second derivative of the departure over log current at point i, from it and its two
    // neighbours: linear interpolation over an interval of log width h misses its midpoint by
    // h^2 / 8 of it.
    const auto bend = [&](std::size_t i) {
      const double x0 = std::log(current[i - 1]), x1 = std::log(current[i]), x2 = std::log(current[i + 1]);
      return 2 * ((departure[i + 1] - departure[i]) / (x2 - x1) - (departure[i] - departure[i - 1]) / (x1 - x0)) /
             (x2 - x0);
    };
    std::vector<double> midpoints;
    std::vector<std::pair<double, double>> halved;  // each midpoint's interval
    // The miss measured at an end of this interval, where it was added: its halves leave a quarter.
    const auto parent_miss = [&midpoint_miss](double a, double b) {
      double miss = std::numeric_limits<double>::infinity();
      for (double end : {a, b}) {
        if (const auto it = midpoint_miss.find(end); it != midpoint_miss.end()) miss = std::min(miss, it->second);
      }
      return miss;
    };
    for (std::size_t k = 0; k + 1 < f.size(); ++k) {
      const double a = current[k], b = current[k + 1], m = std::sqrt(a * b);
      // A current already measured between them (one that never fired) is not asked again.
      const bool measured_between = std::any_of(runs.begin(), runs.end(), [&](const PointRun& r) {
        return r.point.current > a && r.point.current < b;
      });
      if (measured_between || outside.count(a) || outside.count(b)) continue;
      // The table's departure from the fit at the ends carries over to the midpoint, as it stands
      // and bent as it bends at the nearer points (the larger of the two): either miss counts.
      const double ends = std::sqrt(period[k] / fit.period(a) * period[k + 1] / fit.period(b));
      const double interpolated = std::sqrt(period[k] * period[k + 1]);
      const double left = k > 0 ? bend(k) : 0.0, right = k + 2 < f.size() ? bend(k + 1) : 0.0;
      const double h = std::log(b / a);
      const double bent = h * h / 8 * (std::fabs(left) > std::fabs(right) ? left : right);
      const double miss = interpolated / (fit.period(m) * ends);
      const bool bends = std::fabs(std::log(miss) + bent) > kInterpolationTolerance &&
                         parent_miss(a, b) / 4 > kInterpolationTolerance;
      if (std::fabs(miss - 1) > kInterpolationTolerance || bends) {
        midpoints.push_back(m);
        halved.emplace_back(a, b);
      }
    }
    if (midpoints.empty() || runs.size() + midpoints.size() > kMaxTablePoints) break;
    c.refined += static_cast<int>(midpoints.size());
    measure_all(midpoints, "photocurrents added between points");
    const std::vector<const PointRun*> now = fired();
    // The period of the fired point `step` places from the one at `current` (NaN: none there).
    const auto beside = [&now](double current, int step) {
      for (std::size_t k = 0; k < now.size(); ++k) {
        if (now[k]->point.current != current) continue;
        const auto at = static_cast<std::ptrdiff_t>(k) + step;
        return at >= 0 && at < static_cast<std::ptrdiff_t>(now.size()) ? now[static_cast<std::size_t>(at)]->point.period
                                                                         : kUnmeasured;
      }
      return kUnmeasured;
    };
    for (std::size_t j = 0; j < midpoints.size(); ++j) {
      const double pm = period_at(runs, midpoints[j]), pa = period_at(runs, halved[j].first),
                   pb = period_at(runs, halved[j].second);
      if (std::isfinite(pm) && std::isfinite(pa) && std::isfinite(pb)) {
        midpoint_miss[midpoints[j]] = std::fabs(std::log(pm / std::sqrt(pa * pb)));
        // Outside its ends, and turning again at a point beyond them: a smooth period turns once
        // at most here (falling with the light, or rising again towards a latch).
        const double beyond = std::min(std::fabs(std::log(pm / pa)), std::fabs(std::log(pm / pb)));
        const double before = beside(halved[j].first, -1), after = beside(halved[j].second, 1);
        const bool turns_again = (std::isfinite(before) && (pa - before) * (pm - pa) < 0) ||
                                 (std::isfinite(after) && (after - pb) * (pb - pm) < 0);
        if ((pm - pa) * (pm - pb) > 0 && beyond > kInterpolationTolerance && turns_again) {
          outside[midpoints[j]] = {beyond, halved[j].first, halved[j].second};
        }
      }
    }
  }

  c.scatter_note = scatter_note(runs, outside);
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
  std::vector<double> silent, given_up;
  std::vector<std::vector<double>> per_settings(kSolverLevels);
  std::string why;
  for (const CalibrationPoint& p : c.points) {
    if (!p.aborted.empty()) {
      given_up.push_back(p.current);
      if (why.empty()) why = p.aborted;
      continue;
    }
    if (!std::isfinite(p.period)) silent.push_back(p.current);
    // A point beyond a settle or a latch may or may not have been run (the jobs' order decides), so
    // only the points that decide are counted, and the preset is the same whatever the order.
    if (std::isfinite(p.period) || (!p.inferred && p.runs > 0)) per_settings[p.settings].push_back(p.current);
  }
  c.currents_per_settings = per_settings;
  const auto listed = [](const std::vector<double>& currents) { return fmt::format("{:.3g}", fmt::join(currents, ", ")); };
  if (!given_up.empty()) {
    std::fprintf(stderr, "aesim calibrate: warning: ngspice gave up at %zu photocurrents (%s A) under every solver "
                         "setting (%s); the table leaves them out\n",
                 given_up.size(), listed(given_up).c_str(), why.c_str());
  }
  for (std::size_t k = 1; k < per_settings.size(); ++k) {
    if (!per_settings[k].empty()) {
      std::fprintf(stderr, "aesim calibrate: %zu photocurrent%s (%s A) run with fallback settings (%s) after ngspice "
                           "gave up under tighter ones; the preset says which\n",
                   per_settings[k].size(), per_settings[k].size() == 1 ? "" : "s", listed(per_settings[k]).c_str(),
                   solver_level_text(k));
    }
  }
  if (!silent.empty()) {
    const auto beyond_count = std::count_if(c.points.begin(), c.points.end(), [](const CalibrationPoint& p) { return p.inferred; });
    const std::string beyond_text =
        beyond_count == 0 ? std::string()
                          : fmt::format(" ({} of them beyond a current where it settled or latched, not waited for)", beyond_count);
    std::fprintf(stderr, "aesim calibrate: warning: the pixel never fired (or never settled to a period) at %zu of %zu "
                         "photocurrents (%s A)%s; the table holds the other %zu\n",
                 silent.size(), c.points.size(), listed(silent).c_str(), beyond_text.c_str(), c.current.size());
  }
  if (!c.scatter_note.empty()) std::fprintf(stderr, "aesim calibrate: warning: %s\n", c.scatter_note.c_str());
  c.fit = fit_pixel(c.current, c.period);
  std::vector<double> pulses;
  for (const CalibrationPoint& p : c.points) {
    if (std::isfinite(p.period)) pulses.push_back(p.pulse);
  }
  try {
    c.circuit = fit_circuit(c.current, c.period, pulses);
  } catch (const std::invalid_argument&) {
    // A pulse unmeasured or as long as its period: the circuit's form cannot be told apart.
  }
  // Where the circuit was seen not to fire beyond the table's ends: the pixel is silent there too.
  for (const CalibrationPoint& p : c.points) {
    if (std::isfinite(p.period) || !p.aborted.empty()) continue;
    if (p.current < c.current.front() && p.current > c.silent_below) {
      c.silent_below = p.current;
      c.silent_below_seen = p.seen;
    }
    if (p.current > c.current.back() && p.current < c.silent_above) {
      c.silent_above = p.current;
      c.silent_above_seen = p.seen;
    }
  }
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
            throw InputError(fmt::format("deck '{}': Monte Carlo run {} never fires at {:.3g} A{}", deck.given, k + 1,
                                         c.mc_current,
                                         r.point.aborted.empty() ? "" : " (ngspice gave up: " + r.point.aborted + ")"));
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
    // Identical runs differ only by the rounding of the mean: the deck has no statistics.
    if (*c.mismatch < 1e-9) {
      c.mismatch = 0.0;
      std::fprintf(stderr, "aesim calibrate: warning: --mc: every run fired with the same period; the deck has no "
                           "statistical functions (agauss, ...) or no `mc` parameter that switches them on\n");
    }
  }
  c.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return c;
}

}  // namespace aesim
