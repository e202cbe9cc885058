// `aesim calibrate` and pixel.transfer: the table's arithmetic against hand-computed values, the
// fit and the measurements against constructed data, and, with ngspice, a deck whose answer is
// known by construction, the shipped deck against aesim runs at every exact rung, a light step
// against ngspice's own transient, Monte Carlo, and the decks a user gets wrong.
#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <cmath>
#include <limits>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "aesim/config/sensor_config.hpp"
#include "deck/pixel_deck.hpp"
#include "aesim/errors/input_error.hpp"
#include "fit/transfer_fit.hpp"
#include "measure/firing_measure.hpp"
#include "ngspice/ngspice_run.hpp"
#include "aesim/pixel/transfer_curve.hpp"
#include "preset/calibrated_preset.hpp"
#include "aesim/process/child_process.hpp"
#include "session/pixel_calibration.hpp"
#include "support/csv_rows.hpp"
#include "support/temp_dir_test.hpp"
#include "aesim/units/si_units.hpp"

namespace aesim {
namespace {

namespace fs = std::filesystem;
using testing::Outcome;
using testing::slurp;

const std::string kSource = AESIM_SOURCE_DIR;
const std::string kShippedDeck = kSource + "/models/circuits/aesim_pixel.cir";
const std::string kIdealDeck = kSource + "/tests/circuits/ideal_pixel.cir";
const std::string kBsimDeck = kSource + "/tests/circuits/bsim_axon_hillock.cir";
const std::string kBinnedDeck = kSource + "/tests/circuits/binned_pixel.cir";

// Text of a number with every digit (std::to_string would print 2.5e-14 as 0.000000).
std::string num(double v) {
  char text[64];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

// --- pixel.transfer -------------------------------------------------------------------------

TEST(TransferCurve, InterpolatesLogLogBetweenPoints) {
  const TransferCurve t{{1e-12, 1e-10}, {0.1, 1e-3}};
  EXPECT_DOUBLE_EQ(t.period_at(1e-12), 0.1);
  EXPECT_DOUBLE_EQ(t.period_at(1e-10), 1e-3);
  // A power law between the points: a decade up from 1 pA is a decade down in period.
  EXPECT_NEAR(t.period_at(1e-11), 1e-2, 1e-15);
  EXPECT_NEAR(t.period_at(std::sqrt(10.0) * 1e-12), 0.1 / std::sqrt(10.0), 1e-15);
}

TEST(TransferCurve, IntegratingCurrentFiresWithTheTablePeriod) {
  const TransferCurve t{{1e-13, 1e-12, 1e-11}, {2.0, 0.25, 0.02}};
  const double q = 1e-13, t_reset = 1e-3;
  for (double i : {1e-13, 3e-13, 1e-12, 4e-12, 1e-11}) {
    const double current = t.integrating_current(i, q, 0, t_reset);
    EXPECT_NEAR(q / current + t_reset, t.period_at(i), 1e-12) << i;
  }
}

TEST(TransferCurve, AResizedPixelScalesItsIntegrationFromTheMeasuredOne) {
  TransferCurve t{{1e-13, 1e-12}, {2.0, 0.25}};
  t.charge = 1e-13;
  t.t_reset = 1e-3;
  // Twice the threshold charge and its own 5 ms reset: the integration (period less the measured
  // reset) doubles, then the pixel's own reset follows.
  for (double i : {1e-13, 4e-13, 1e-12}) {
    const double current = t.integrating_current(i, 2e-13, 0, 5e-3);
    EXPECT_NEAR(2e-13 / current + 5e-3, 2 * (t.period_at(i) - 1e-3) + 5e-3, 1e-12) << i;
  }
}

TEST(TransferCurve, BeyondTheTableFollowsEq2CurrentFromTheEnds) {
  const TransferCurve t{{1e-13, 1e-11}, {1.0, 0.01}};
  const double q = 1e-13, i_dark = 1e-15, t_reset = 0;
  const double at_low = t.integrating_current(1e-13, q, i_dark, t_reset);  // 1e-13 A: q / 1 s
  EXPECT_NEAR(at_low, 1e-13, 1e-25);
  // Half the light (plus dark) below the table: the current scales with I + i_dark.
  EXPECT_NEAR(t.integrating_current(0.5e-13, q, i_dark, t_reset), at_low * (0.5e-13 + i_dark) / (1e-13 + i_dark), 1e-25);
  // No light: the dark current's share; no light and no dark current: never fires.
  EXPECT_NEAR(t.integrating_current(0, q, i_dark, t_reset), at_low * i_dark / (1e-13 + i_dark), 1e-27);
  EXPECT_EQ(t.integrating_current(0, q, 0, t_reset), 0.0);
  const double at_high = t.integrating_current(1e-11, q, i_dark, t_reset);
  EXPECT_NEAR(t.integrating_current(2e-11, q, i_dark, t_reset), at_high * (2e-11 + i_dark) / (1e-11 + i_dark), 1e-22);
}

// Where the circuit never fired beyond the table's ends (a leak at low light, a latch at high), the
// pixel integrates nothing there, and the fields travel with the table and are checked.
TEST(TransferCurve, BeyondTheSilentCurrentsThePixelNeverFires) {
  TransferCurve t{{1e-13, 1e-11}, {1.0, 0.01}};
  t.silent_below = 3e-14;
  t.silent_above = 1e-10;
  const double q = 1e-13, i_dark = 1e-15;
  EXPECT_GT(t.integrating_current(5e-14, q, i_dark, 0), 0.0);  // extrapolated, as before
  EXPECT_GT(t.integrating_current(5e-11, q, i_dark, 0), 0.0);
  for (double i : {0.0, 1e-14, 3e-14, 1e-10, 1e-9}) EXPECT_EQ(t.integrating_current(i, q, i_dark, 0), 0.0) << i;
  SensorConfig c;
  c.set("pixel.transfer", "{current=[1e-13,1e-11],period=[1.0,0.01],silent_below=\"30fA\",silent_above=1e-10}");
  EXPECT_NO_THROW(c.validate());
  EXPECT_DOUBLE_EQ(c.pixel.transfer.silent_below, 3e-14);
  EXPECT_EQ(c.to_json()["pixel"]["transfer"]["silent_above"].get<double>(), 1e-10);
  // A photocurrent of i_max x v: a pixel at full light above silent_above has no current at all.
  c.set("pixel.i_max", "200pA");
  EXPECT_EQ(c.pixel.integrating_current(1.0), 0.0);
  EXPECT_GT(c.pixel.integrating_current(0.25), 0.0);
  SensorConfig bad;
  bad.set("pixel.transfer", "{current=[1e-13,1e-11],period=[1.0,0.01],silent_above=1e-12}");
  try {
    bad.validate();
    ADD_FAILURE() << "a silent_above inside the table was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("silent_above (1e-12 A) must be above the highest current"), std::string::npos)
        << e.what();
  }
}

TEST(TransferCurve, ConfigReadsTheTableFromTomlAndSetAndRefusesBadOnes) {
  SensorConfig c;
  apply_toml_text(c, "[pixel]\ntransfer = { current = [1e-13, \"1pA\"], period = [1.0, \"100ms\"] }\n", "p.toml", "");
  ASSERT_EQ(c.pixel.transfer.current.size(), 2u);
  EXPECT_DOUBLE_EQ(c.pixel.transfer.current[1], 1e-12);
  EXPECT_DOUBLE_EQ(c.pixel.transfer.period[1], 0.1);
  c.set("pixel.transfer", "{current=[1e-12,1e-11],period=[0.1,0.01]}");
  EXPECT_DOUBLE_EQ(c.pixel.transfer.period[0], 0.1);
  EXPECT_NO_THROW(c.validate());
  // The summary echoes it; "none" removes it.
  EXPECT_EQ(c.to_json()["pixel"]["transfer"]["period"][1].get<double>(), 0.01);
  c.set("pixel.transfer", "none");
  EXPECT_TRUE(c.pixel.transfer.empty());
  EXPECT_TRUE(c.to_json()["pixel"]["transfer"].is_null());

  auto message = [](const std::string& value) {
    SensorConfig bad;
    try {
      bad.set("pixel.transfer", value);
      bad.validate();
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message("{current=[1e-12],period=[0.1,0.2]}").find("1 currents but 2 periods"), std::string::npos);
  EXPECT_NE(message("{current=[1e-11,1e-12],period=[0.1,0.2]}").find("currents must increase"), std::string::npos);
  EXPECT_NE(message("{current=[1e-12,1e-11],period=[0.1,0]}").find("not longer than pixel.t_reset"), std::string::npos);
  EXPECT_NE(message("{current=[1e-12,1e-11]}").find("needs both"), std::string::npos);
  EXPECT_NE(message("{current=[1e-12,1e-11],period=[0.1,0.01],extra=1}").find("unknown field"), std::string::npos);
  EXPECT_NE(message("{current=[1e-12,1e-11],period=[0.1,0.01],charge=0}").find("charge must be positive"),
            std::string::npos);
  EXPECT_NE(message("{current=[1e-12,1e-11],period=[0.1,0.01],t_reset=\"0.2s\"}").find("its t_reset"),
            std::string::npos);
  // The measured charge and reset travel with the table.
  SensorConfig with;
  with.set("pixel.transfer", "{current=[1e-12,1e-11],period=[0.1,0.01],charge=\"95fC\",t_reset=2e-6}");
  EXPECT_DOUBLE_EQ(with.pixel.transfer.charge, 95e-15);
  EXPECT_EQ(with.to_json()["pixel"]["transfer"]["t_reset"].get<double>(), 2e-6);
  EXPECT_NE(message("[1,2]").find("pixel.transfer"), std::string::npos);
}

// --- the fit and the measurements on constructed data ----------------------------------------

TEST(TransferFit, RecoversEq2FromExactPeriods) {
  const double q = 100e-15, t_reset = 2e-6, i_dark = 3e-15;
  std::vector<double> current, period;
  for (int k = 0; k <= 12; ++k) {
    current.push_back(1e-15 * std::pow(10.0, k / 2.0));
    period.push_back(q / (current.back() + i_dark) + t_reset);
  }
  const PixelFit fit = fit_pixel(current, period);
  EXPECT_NEAR(fit.charge / q, 1, 1e-6);
  EXPECT_NEAR(fit.t_reset / t_reset, 1, 1e-4);
  EXPECT_NEAR(fit.i_dark / i_dark, 1, 1e-4);
  EXPECT_LT(fit.max_residual, 1e-6);
}

// The circuit's own form recovered from exact periods and pulses: a leak (negative i_dark) and a
// reset lengthened by the light up to a latch (the axon hillock's figures), then a dark current
// and a constant reset.
TEST(TransferFit, RecoversALeakAndALatchingResetFromExactPeriodsAndPulses) {
  struct Case {
    double q, i_dark, t_r, i_r;
  };
  for (const Case& k : {Case{98.7e-15, -2.1e-15, 318e-6, 654e-12},
                        Case{100e-15, 3e-15, 2e-6, std::numeric_limits<double>::infinity()}}) {
    CircuitFit want;
    want.charge = k.q;
    want.i_dark = k.i_dark;
    want.t_r = k.t_r;
    want.i_r = k.i_r;
    std::vector<double> current, period, pulse;
    for (int n = 0; n <= 10; ++n) {
      current.push_back(3.16e-15 * std::pow(10.0, n / 2.0));  // 3.16 fA to 316 pA
      period.push_back(want.period(current.back()));
      pulse.push_back(want.reset(current.back()));
    }
    const CircuitFit fit = fit_circuit(current, period, pulse);
    EXPECT_NEAR(fit.charge / k.q, 1, 1e-6);
    EXPECT_NEAR(fit.i_dark / k.i_dark, 1, 1e-4);
    EXPECT_NEAR(fit.t_r / k.t_r, 1, 1e-9);
    if (std::isfinite(k.i_r)) {
      EXPECT_NEAR(fit.i_r / k.i_r, 1, 1e-9);
    } else {
      EXPECT_TRUE(std::isinf(fit.i_r));
    }
    EXPECT_LT(fit.max_residual, 1e-6);
    // eq. 2 cannot hold it where it bends: the leak and the latch leave residuals of percents.
    if (k.i_dark < 0) {
      EXPECT_GT(fit_pixel(current, period).max_residual, 0.05);
    }
  }
  EXPECT_THROW(fit_circuit({1e-12, 1e-11, 1e-10}, {1.0, 0.1, 0.01}, {1e-3, 1e-3, 0.02}), std::invalid_argument);
}

// A supply whose charge per period is a line with a negative intercept (crowbar current grows with
// the period faster than the charge per firing): the power model's parts stay non-negative, and
// the free fit's values are kept to be reported.
TEST(TransferFit, ANegativeChargePerFiringIsKeptAsTheFreeFitsValue) {
  const std::vector<double> period = {1e-3, 1e-2, 1e-1, 1.0};
  std::vector<double> charge;
  for (double p : period) charge.push_back(-1e-13 + 2.6e-6 * p);
  const SupplyFit s = fit_supply(period, charge);
  EXPECT_NEAR(s.free_charge_per_firing / -1e-13, 1, 1e-6);
  EXPECT_NEAR(s.free_static_current / 2.6e-6, 1, 1e-6);
  EXPECT_EQ(s.charge_per_firing, 0.0);
  EXPECT_GT(s.static_current, 0.0);
}

TEST(TransferFit, SupplySplitsIntoChargePerFiringAndStaticCurrent) {
  const std::vector<double> period = {1e-3, 1e-2, 1e-1, 1.0};
  std::vector<double> charge;
  for (double p : period) charge.push_back(5e-12 + 2e-9 * p);
  const SupplyFit s = fit_supply(period, charge);
  EXPECT_NEAR(s.charge_per_firing / 5e-12, 1, 1e-9);
  EXPECT_NEAR(s.static_current / 2e-9, 1, 1e-9);
}

// A hand-built waveform: out high for 1 us every 10 us (edges 10 ns), the supply delivering
// 1 uA while out is high and nothing else, the probe ramping 0 -> 1 V between pulses.
Waveform pulse_train(int pulses) {
  Waveform w;
  for (int k = 0; k < pulses; ++k) {
    const double t0 = 10e-6 * (k + 1);
    for (const auto& [dt, out, supply] : std::vector<std::tuple<double, double, double>>{
             {-5e-6, 0, 0}, {-10e-9, 0, 0}, {0, 3.3, -1e-6}, {1e-6, 3.3, -1e-6}, {1e-6 + 10e-9, 0, 0}}) {
      w.t.push_back(t0 + dt);
      w.out.push_back(out);
      w.supply.push_back(supply);
      w.probe.push_back(dt < 0 ? 1.0 + dt / 9e-6 : 0.0);
    }
  }
  return w;
}

// ngspice's progress reports judged as the calibration's watch judges them (t_stop 10 s, a 120 s
// limit, a 10 s window): a run whose pace would end it in time goes on, and so does one a few
// times too slow until its time left is a tenth of what it needs; one that crawls after a good start (its step collapsed at a
// stiff node) is given up as soon as its last 10 s show it, from 20 s on, with where it stalled; a
// slow start alone decides nothing.
TEST(StepCollapseWatch, GivesUpARunOnlyWhenItsPaceCannotFinishItInTime) {
  StepCollapseWatch steady(10, 120, 10);
  for (double wall = 0.5; wall <= 60; wall += 0.5) ASSERT_TRUE(steady.keep_waiting(wall, wall / 6)) << wall;

  StepCollapseWatch slow(10, 120, 10);  // 1 s simulated in 30 s: 300 s in all
  for (double wall = 0.5; wall <= 90; wall += 0.5) ASSERT_TRUE(slow.keep_waiting(wall, wall / 30)) << wall;

  StepCollapseWatch crawling(10, 120, 10);
  double gave_up = -1;
  for (double wall = 0.5; wall <= 120 && gave_up < 0; wall += 0.5) {
    const double t = wall <= 10 ? wall / 5 : 2 + (wall - 10) * 1e-4;  // 2 s simulated, then a crawl
    if (!crawling.keep_waiting(wall, t)) gave_up = wall;
  }
  EXPECT_GE(gave_up, 20);
  EXPECT_LE(gave_up, 20.5);  // the first judgement: the last 10 s were all crawl
  EXPECT_NEAR(crawling.stalled_at(), 2, 0.01);

  StepCollapseWatch slow_start(10, 120, 10);
  for (double wall = 0.5; wall <= 70; wall += 0.5) {
    const double t = wall <= 10 ? wall * 1e-3 : 0.01 + (wall - 10) / 6;  // slow first edges, then fast
    ASSERT_TRUE(slow_start.keep_waiting(wall, std::min(t, 10.0))) << wall;
  }
  EXPECT_TRUE(StepCollapseWatch(10, 120, 10).keep_waiting(50, -1));  // nothing reported yet
}

TEST(FiringMeasure, PeriodPulseAndSupplyChargeOfAHandBuiltWaveform) {
  const FiringMeasure m = measure_firings(pulse_train(6), 3.3);
  ASSERT_EQ(m.fires.size(), 6u);
  // Rising through 1.65 V halfway up a 10 ns edge.
  EXPECT_NEAR(m.fires[0], 10e-6 - 5e-9, 1e-15);
  EXPECT_NEAR(m.period, 10e-6, 1e-15);
  EXPECT_NEAR(m.pulse, 1e-6 + 10e-9, 1e-15);
  // 1 uA for 1 us plus two 10 ns half-ramps per period: 1.01 pC.
  EXPECT_NEAR(m.supply_charge, 1.01e-12, 1e-18);
  EXPECT_TRUE(m.probe_rising);
  EXPECT_FALSE(std::isfinite(measure_firings(pulse_train(2), 3.3).period));
}

// --- with ngspice --------------------------------------------------------------------------------

class NgspiceTest : public testing::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    if (!program_available("ngspice")) GTEST_SKIP() << "ngspice is not installed (scripts/setup installs it)";
  }
};

// Options for `points` photocurrents from `low` to `high`, two ngspice at once.
CalibrationOptions over(double low, double high, int points) {
  CalibrationOptions o;
  o.i_low = low;
  o.i_high = high;
  o.points = points;
  o.jobs = 2;
  return o;
}

// Without --subckt the deck's own subcircuit of three ports and iph is the pixel (an inverter
// beside it, with four ports, is not); two such, or none, is refused listing the deck's own.
TEST_F(NgspiceTest, WithoutSubcktTheDecksOnePixelIsTaken) {
  const std::string pixel = slurp(kIdealDeck);
  const std::string inverter = ".subckt inv in out vdd gnd\n.ends\n";
  EXPECT_EQ(read_pixel_deck(write("one.cir", inverter + pixel), "", "int").subckt, "ideal_pixel");
  std::string twin = pixel;
  twin.replace(twin.find(".subckt ideal_pixel"), 19, ".subckt second_pixel");
  twin.replace(twin.find(".ends"), 5, ".ends second_pixel");
  for (const auto& [name, text, needle] :
       {std::tuple<const char*, std::string, const char*>{"two.cir", pixel + "\n" + twin,
                                                         "several with three ports and iph: ideal_pixel, second_pixel"},
        {"none.cir", inverter, "none of the deck's own has three ports, vdd out gnd, and a parameter iph: inv"}}) {
    try {
      read_pixel_deck(write(name, text), "", "int");
      ADD_FAILURE() << name;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  }
}

// A deck as a designer runs it on its own: a title line (SPICE's first line), its models from a
// file beside it, and its own testbench (a supply named Vdd as the runs' is, an instance, .tran,
// a .control block that would run a shell command, and text past .end). The runs take its
// circuit alone, say what they left out, and give the bare pixel's table; the block never runs.
TEST_F(NgspiceTest, ADeckRunOnItsOwnIsCalibratedOnItsCircuitAlone) {
  std::string pixel = slurp(kIdealDeck);
  pixel.replace(pixel.find(".model hysteresis"), pixel.find(".ends") - pixel.find(".model hysteresis"), "");
  fs::create_directories(dir_ / "bench");
  write("bench/switch.lib", ".model hysteresis sw vt=1.0005 vh=0.4995 ron=1 roff=1e16\n");
  const std::string marker = (dir_ / "ran").string();
  const std::string own = "Ideal pixel, characterised on its own\n" + pixel + ".include switch.lib\n"
                          "Vdd vdd 0 3.3\nX1 vdd out 0 ideal_pixel\n+ iph=10p\n.tran 1u 1m\n"
                          ".control\nshell touch " + marker + "\nrun\n.endc\n.end\nnot SPICE after the end\n";
  const std::string path = write("bench/own.cir", own);
  std::istringstream lines(own);
  int control = 0, endc = 0, n = 0;
  for (std::string line; std::getline(lines, line);) {
    ++n;
    if (line == ".control") control = n;
    if (line == ".endc") endc = n;
  }
  const PixelDeck deck = read_pixel_deck(path, "ideal_pixel", "int");
  EXPECT_EQ(deck.left_out, (std::vector<std::string>{"its title line", fmt::format("its .control block (lines {} to {})", control, endc),
                                                      "its testbench's 2 element lines", "its .tran"}));
  EXPECT_NE(deck.circuit.find(".include \"" + (dir_ / "bench" / "switch.lib").string() + "\""), std::string::npos) << deck.circuit;
  const CalibrationOptions o = over(1e-12, 1e-10, 3);
  const Calibration on_its_own = calibrate_pixel(deck, o);
  const Calibration bare = calibrate_pixel(read_pixel_deck(kIdealDeck, "ideal_pixel", "int"), o);
  EXPECT_EQ(on_its_own.current, bare.current);
  EXPECT_EQ(on_its_own.period, bare.period);
  EXPECT_FALSE(fs::exists(marker));

  const Outcome cli = aesim("calibrate bench/own.cir --subckt ideal_pixel --currents 1pA:100pA --points 3 -o own.toml");
  EXPECT_EQ(cli.status, 0) << cli.err;
  EXPECT_NE(cli.err.find("the runs take the deck's circuit; left out: its title line, its .control block"), std::string::npos)
      << cli.err;
  EXPECT_FALSE(fs::exists(marker));
}

// The known deck with its reset's reference (0.5 V inside it) taken out as a port, vlo: held by
// --bias vlo=0.5V it gives the bare deck's table; held at 0.3 V the reset discharges towards a lower
// level, so it reaches its end (0.501 V) sooner and the periods shorten; left unheld, or a bias
// naming no port, is refused saying what to give.
TEST_F(NgspiceTest, APortBeyondTheThreeIsHeldAtTheVoltageGiven) {
  std::string biased = slurp(kIdealDeck);
  biased.replace(biased.find("vdd out gnd params"), 18, "vdd out gnd vlo params");
  biased.replace(biased.find("Vlo lo gnd 0.5\n"), 15, "");
  biased.replace(biased.find("Rdis dis lo"), 11, "Rdis dis vlo");
  const std::string path = write("biased.cir", biased);
  const CalibrationOptions o = over(1e-12, 1e-10, 3);
  const Calibration bare = calibrate_pixel(read_pixel_deck(kIdealDeck, "ideal_pixel", "int"), o);
  const PixelDeck held = read_pixel_deck(path, "ideal_pixel", "int", {}, {{"VLO", 0.5}});
  EXPECT_EQ(held.port_nets, (std::vector<std::string>{"vdd", "out", "0", "aesim_bias_vlo"}));
  EXPECT_EQ(calibrate_pixel(held, o).period, bare.period);
  const Calibration deeper = calibrate_pixel(read_pixel_deck(path, "ideal_pixel", "int", {}, {{"vlo", 0.3}}), o);
  ASSERT_EQ(deeper.period.size(), bare.period.size());
  EXPECT_LT(deeper.period.back(), bare.period.back() * (1 - 1e-4));

  const Outcome unheld = aesim("calibrate biased.cir --subckt ideal_pixel -o p.toml");
  EXPECT_EQ(unheld.status, 2);
  EXPECT_NE(unheld.err.find("has 4 ports (vdd out gnd vlo); aesim calibrate needs three, vdd out gnd, and holds each other "
                            "one at a voltage given as --bias NAME=VOLTS"),
            std::string::npos)
      << unheld.err;
  const Outcome nowhere = aesim("calibrate biased.cir --subckt ideal_pixel --bias vlo=0.5V --bias vb=1V -o p.toml");
  EXPECT_NE(nowhere.err.find("--bias vb: subcircuit 'ideal_pixel' has no port vb (its ports: vdd out gnd vlo)"), std::string::npos)
      << nowhere.err;
  EXPECT_NE(aesim("calibrate biased.cir --subckt ideal_pixel --bias vlo -o p.toml").err.find("expected PORT=VOLTS"),
            std::string::npos);
  // Without --subckt, the deck's one subcircuit of four ports (three and the one held) and iph.
  const Outcome cli = aesim("calibrate biased.cir --bias vlo=0.5V --currents 1pA:100pA --points 3 -o p.toml");
  ASSERT_EQ(cli.status, 0) << cli.err;
  EXPECT_NE(slurp(dir_ / "p.toml").find("# Ports held at a voltage in every run (--bias): vlo at 0.5 V."), std::string::npos);
}

// The known deck with its ports declared gnd vdd out: taken by their names, the same table.
TEST_F(NgspiceTest, APixelWithItsPortsInAnotherOrderGivesTheSameTable) {
  std::string swapped = slurp(kIdealDeck);
  swapped.replace(swapped.find("vdd out gnd params"), 11, "gnd vdd out");
  const CalibrationOptions o = over(1e-12, 1e-10, 3);
  const Calibration by_name = calibrate_pixel(read_pixel_deck(write("swapped.cir", swapped), "ideal_pixel", "int"), o);
  const Calibration bare = calibrate_pixel(read_pixel_deck(kIdealDeck, "ideal_pixel", "int"), o);
  ASSERT_EQ(by_name.period.size(), 3u);
  EXPECT_EQ(by_name.period, bare.period);
}

TEST_F(NgspiceTest, KnownDeckGivesItsThresholdChargeAndResetWithinOnePercent) {
  const PixelDeck deck = read_pixel_deck(kIdealDeck, "ideal_pixel", "int");
  const CalibrationOptions o = over(100e-15, 100e-9, 10);
  const Calibration c = calibrate_pixel(deck, o);
  ASSERT_GE(c.current.size(), 10u);  // and the points added where interpolation would miss
  // By construction (tests/circuits/ideal_pixel.cir): Q = 100 fF x 0.999 V, t_reset =
  // 1.59 Mohm x 100 fF x ln(0.999 / 0.001), no dark current.
  const double q = 100e-15 * 0.999, t_reset = 1.59e6 * 100e-15 * std::log(0.999 / 0.001);
  EXPECT_NEAR(c.fit.charge / q, 1, 0.01);
  EXPECT_NEAR(c.fit.t_reset / t_reset, 1, 0.01);
  EXPECT_LT(c.fit.i_dark, 0.01 * o.i_low);
  // The pulse on out is the reset, within the edges' time steps.
  EXPECT_NEAR(c.points.back().pulse / t_reset, 1, 0.02);
}

// A pixel whose integration current grows faster than its light, iph (1 + iph / 10 pA), so that
// its period bends in log-log where eq. 2 (or its fit) cannot: the table must hold points enough
// that the model's log-log interpolation follows the circuit between them.
TEST_F(NgspiceTest, ATableFarFromEq2IsMeasuredWhereItBendsSoThatInterpolationHoldsBetweenItsPoints) {
  std::string text = slurp(kIdealDeck);
  const std::string source = "I = v(out) < v(vdd) / 2 ? iph : 0";
  text.replace(text.find(source), source.size(), "I = v(out) < v(vdd) / 2 ? iph * (1 + iph / 1e-11) : 0");
  const PixelDeck deck = read_pixel_deck(write("bent.cir", text), "ideal_pixel", "int");
  const CalibrationOptions o = over(1e-12, 1e-10, 5);
  const Calibration c = calibrate_pixel(deck, o);
  // Against the same circuit measured densely (41 points, a twentieth of a decade apart, where
  // log-log interpolation cannot miss by more than a few hundredths of a percent), the refined
  // table's interpolation misses by no more than the 0.2 % it is refined to, with the scatter of
  // ngspice's measurements (counting eq. 2's bend alone left 5 points and a 3.7 % miss).
  const Calibration dense = calibrate_pixel(deck, over(o.i_low, o.i_high, 41));
  ASSERT_GE(dense.current.size(), 41u);
  const TransferCurve table{c.current, c.period};
  double worst = 0;
  for (std::size_t k = 0; k < dense.current.size(); ++k) {
    worst = std::max(worst, std::fabs(table.period_at(dense.current[k]) / dense.period[k] - 1));
  }
  EXPECT_LT(worst, 2.5e-3);
}

// Firing times of pixel (0, 0) from an `aesim run` truth file, in seconds.
std::vector<double> truth_fires(const std::string& csv) {
  std::vector<double> t;
  for (const std::vector<std::string>& row : testing::csv_rows(csv)) {
    if (row.size() >= 4 && row[0] == "0" && row[1] == "0") t.push_back(std::stod(row[3]) * 1e-6);
  }
  return t;
}

// A 2x2 scene lit at pixel (0, 0) only, at 8-bit value `value`, the others dark.
std::string lone_pixel_pgm(int value) {
  std::string pgm = "P5\n2 2\n255\n";
  pgm += static_cast<char>(value);
  pgm += std::string(3, '\0');
  return pgm;
}

class ShippedDeckTest : public NgspiceTest {
 protected:
  void SetUp() override {
    NgspiceTest::SetUp();
    if (IsSkipped()) return;
    preset_ = (dir_ / "pixel.toml").string();
    const Outcome o = aesim("calibrate '" + kShippedDeck + "' --subckt aesim_pixel -o pixel.toml");
    ASSERT_EQ(o.status, 0) << o.err;
    SensorConfig c;
    apply_toml_file(c, preset_, "");
    config_ = c;
  }

  // The circuit's own firings at a constant photocurrent, finely stepped (a reference, not a calibration).
  FiringMeasure circuit(double iph, double periods, const std::string& deck_path) const {
    const PixelDeck deck = read_pixel_deck(deck_path, "aesim_pixel", "int");
    const double p = config_.pixel.transfer.period_at(iph);
    return measure_firings(
        run_transient(deck, 3.3, {iph, p * periods, p / 2000}, dir_, "reference"), 3.3);
  }

  std::string common_sets(double i_max) const {
    return " --set pixel.mismatch=0 --set pixel.initial=reset --set array.rows=2 --set array.cols=2"
           " --set array.tile_rows=2 --set array.tile_cols=2 --set pixel.i_max=" +
           num(i_max);
  }

  std::string preset_;
  SensorConfig config_;
};

TEST_F(ShippedDeckTest, LandsNearTheAlohaPixelAndRunsWithNgspicesPeriodAtEveryExactRung) {
  // Near the aloha preset's 10 Hz at 1 pA (100 fC) with ~1 fA of dark current.
  EXPECT_NEAR(config_.pixel.threshold_charge() / 100e-15, 1, 0.1);
  EXPECT_GT(config_.pixel.i_dark, 0.3e-15);
  EXPECT_LT(config_.pixel.i_dark, 3e-15);
  const std::vector<double>& table = config_.pixel.transfer.current;
  ASSERT_GE(table.size(), 13u);
  write("lit.pgm", lone_pixel_pgm(255));
  // Between the table's points, where log-log interpolation is all the model has: a third of the
  // way into the first interval (the dark current's knee), one in the middle, the last.
  const std::size_t n = table.size();
  for (double iph : {table[0] * std::pow(table[1] / table[0], 1.0 / 3), std::sqrt(table[n / 2] * table[n / 2 + 1]),
                     table[n - 2] * std::pow(table[n - 1] / table[n - 2], 2.0 / 3)}) {
    const FiringMeasure ngspice = circuit(iph, 10, kShippedDeck);
    ASSERT_TRUE(std::isfinite(ngspice.period)) << iph;
    for (const char* fidelity : {"event", "cycle", "pixel_processes"}) {
      const Outcome o = aesim("run --sensor pixel.toml --scene lit.pgm --truth truth.csv --set sim.fidelity=" +
                              std::string(fidelity) + common_sets(iph) +
                              " --duration " + num(ngspice.period * 9));
      ASSERT_EQ(o.status, 0) << o.err;
      const std::vector<double> t = truth_fires(slurp(dir_ / "truth.csv"));
      ASSERT_GE(t.size(), 8u) << fidelity << " " << iph;
      const double period = (t.back() - t.front()) / static_cast<double>(t.size() - 1);
      EXPECT_NEAR(period / ngspice.period, 1, 0.01) << fidelity << " at " << iph << " A";
    }
  }
}

TEST_F(ShippedDeckTest, LightStepFiresWhenNgspiceFiresOverTenPeriods) {
  // ngspice: the shipped deck with its photocurrent stepping from 2 pA to 5 pA mid-integration.
  const double i1 = 2e-12, i2 = 5e-12;
  const double p1 = config_.pixel.transfer.period_at(i1), p2 = config_.pixel.transfer.period_at(i2);
  std::string deck = slurp(kShippedDeck);
  const double first_guess = p1 * 1.5;  // from 0 V the first firing takes longer than a period
  const double t_step = first_guess + 2.4 * p1;
  const std::string source = "Iph vdd int {iph}";
  ASSERT_NE(deck.find(source), std::string::npos);
  deck.replace(deck.find(source), source.size(),
               "Iph vdd int PWL(0 " + num(i1) + " " + num(t_step) + " " + num(i1) +
                   " " + num(t_step + 1e-9) + " " + num(i2) + ")");
  const std::string stepped = write("stepped.cir", deck);
  const PixelDeck pixel = read_pixel_deck(stepped, "aesim_pixel", "int");
  const FiringMeasure ngspice =
      measure_firings(run_transient(pixel, 3.3, {i1, t_step + 9 * p2, p2 / 2000}, dir_, "step"), 3.3);
  ASSERT_GE(ngspice.fires.size(), 12u);
  ASSERT_LT(ngspice.fires[1], t_step);

  // aesim: pixel (0, 0) reset at ngspice's first firing plus the reset, i.e. aesim's t = 0 is
  // ngspice's fires[0] + t_reset; two frames, 2 pA then 5 pA (i_max 5 pA, values 102/255 and 1).
  const double offset = ngspice.fires[0] + config_.pixel.t_reset;
  fs::create_directories(dir_ / "step");
  write("step/frame_000.pgm", lone_pixel_pgm(102));
  write("step/frame_001.pgm", lone_pixel_pgm(255));
  const Outcome o = aesim("run --sensor pixel.toml --scene step --truth truth.csv --set scene.frame_rate=" +
                          num(1.0 / (t_step - offset)) + common_sets(i2) + " --duration " + num(t_step + 9 * p2 - offset));
  ASSERT_EQ(o.status, 0) << o.err;
  const std::vector<double> model = truth_fires(slurp(dir_ / "truth.csv"));
  ASSERT_GE(model.size(), 10u);
  int after_step = 0;
  for (std::size_t k = 0; k < 10; ++k) {
    const double expected = ngspice.fires[k + 1], got = model[k] + offset;
    const double local_period = expected < t_step ? p1 : p2;
    after_step += expected > t_step ? 1 : 0;
    EXPECT_NEAR(got, expected, 0.01 * local_period) << "firing " << k + 1;
  }
  EXPECT_GE(after_step, 5);
}

TEST_F(NgspiceTest, MonteCarloMeasuresTheSpreadOfAStatisticalCapacitorAndTheTableStaysNominal) {
  // The known deck with its capacitor drawn by agauss when aesim sets mc=1: 5 % relative sigma of
  // the threshold charge in Monte Carlo runs, the nominal capacitor otherwise.
  std::string deck = slurp(kIdealDeck);
  const std::string cap = "Cint int gnd 100f", params = "params: iph=1p";
  ASSERT_NE(deck.find(cap), std::string::npos);
  deck.replace(deck.find(cap), cap.size(), "Cint int gnd {100f * (1 + mc * agauss(0, 0.05, 1))}");
  deck.replace(deck.find(params), params.size(), "params: iph=1p mc=0");
  const PixelDeck pixel = read_pixel_deck(write("mc.cir", deck), "ideal_pixel", "int");
  EXPECT_TRUE(pixel.mc_parameter);
  CalibrationOptions o = over(1e-12, 1e-10, 3);
  o.mc = 40;
  const Calibration c = calibrate_pixel(pixel, o);
  EXPECT_NEAR(c.fit.charge / (100e-15 * 0.999), 1, 0.005);
  ASSERT_TRUE(c.mismatch.has_value());
  // 40 draws estimate a 5 % sigma within about +-1.2 % (its standard error 5 % / sqrt(78)).
  EXPECT_NEAR(*c.mismatch, 0.05, 0.02);
  // Seeds 1..N: the same runs, the same spread.
  EXPECT_EQ(calibrate_pixel(pixel, o).mismatch, c.mismatch);
}

// A foundry PDK's statistical models, on by default: the known deck's capacitor drawn with a
// 20 % sigma when the PDK's switch (GF180's sw_stat_mismatch, set to 1 in a model file the deck
// includes) is on. The table is run with the switch at 0, so it is the nominal circuit; the Monte
// Carlo runs turn it on and measure the PDK's own spread; the preset says which switch it set.
TEST_F(NgspiceTest, APdksStatisticalSwitchIsOffForTheTableAndOnForMonteCarlo) {
  std::string deck = slurp(kIdealDeck);
  const std::string cap = "Cint int gnd 100f";
  ASSERT_NE(deck.find(cap), std::string::npos);
  deck.replace(deck.find(cap), cap.size(), "Cint int gnd {100f * (1 + sw_stat_mismatch * agauss(0, 0.2, 1))}");
  write("models.lib", "* the PDK's statistics, on\n.param sw_stat_global=1 sw_stat_mismatch = 1\n");
  write("pdk.cir", ".include models.lib\n" + deck);
  PixelDeck pixel = read_pixel_deck((dir_ / "pdk.cir").string(), "ideal_pixel", "int");
  EXPECT_EQ(pixel.statistical_switches, (std::vector<std::string>{"sw_stat_global", "sw_stat_mismatch"}));
  EXPECT_EQ(pixel.statistical_file, (dir_ / "pdk.cir").string());
  CalibrationOptions o = over(1e-12, 1e-10, 3);
  const Calibration nominal = calibrate_pixel(pixel, o);
  EXPECT_NEAR(nominal.fit.charge / (100e-15 * 0.999), 1, 0.005);
  // Left on, each point is a draw of seed 1: not the nominal capacitor.
  PixelDeck left_on = pixel;
  left_on.statistical_switches.clear();
  EXPECT_GT(std::abs(calibrate_pixel(left_on, o).fit.charge / (100e-15 * 0.999) - 1), 0.01);
  o.mc = 30;
  const Calibration mc = calibrate_pixel(pixel, o);
  ASSERT_TRUE(mc.mismatch.has_value());
  EXPECT_NEAR(*mc.mismatch, 0.2, 0.08);  // 30 draws of a 20 % sigma
  const Outcome run = aesim("calibrate pdk.cir --subckt ideal_pixel -o pdk.toml --currents 1pA:100pA --points 3");
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(slurp(dir_ / "pdk.toml").find("# Statistical models: the deck's switches sw_stat_global, sw_stat_mismatch "
                                           "were set to 0 for the table"),
            std::string::npos);
}

// A deck that draws at random with no switch and no `mc` parameter: the table is one draw, and the
// run says so rather than calling it nominal.
TEST_F(NgspiceTest, ADeckThatDrawsWithoutASwitchIsToldToBeADraw) {
  std::string deck = slurp(kIdealDeck);
  const std::string cap = "Cint int gnd 100f";
  deck.replace(deck.find(cap), cap.size(), "Cint int gnd {100f * (1 + agauss(0, 0.01, 1))}");
  write("draw.cir", deck);
  const Outcome o = aesim("calibrate draw.cir --subckt ideal_pixel -o draw.toml --currents 1pA:100pA --points 3");
  ASSERT_EQ(o.status, 0) << o.err;
  EXPECT_NE(o.err.find("warning: statistical models: 'draw.cir' draws at random"), std::string::npos) << o.err;
  EXPECT_NE(slurp(dir_ / "draw.toml").find("each point of the table is one draw of ngspice's seed 1"), std::string::npos);
}

using DeckReadingTest = testing::TempDirTest;

// A PDK's corner library (IHP SG13G2's cornerMOSlv_psp.lib: `.lib mos_tt` includes the nominal
// models, `.lib mos_tt_stat` the statistical ones beside them): `.lib FILE SECTION` reads that
// section only, as ngspice does, so another corner's statistics, devices and includes are not the
// deck's; `.include FILE` reads what lies outside the sections. The file's bytes are hashed once
// whichever sections are read.
TEST_F(DeckReadingTest, ALibrarysSectionIsReadAloneAsNgspiceReadsIt) {
  write("stat.inc", "* statistics\n.param dvth = agauss(0, 0.01, 1)\n.param sw_stat_mismatch = 1\n");
  write("corners.lib", "* corners\n.lib tt\n.param dvth = 0\n.endl tt\n.lib tt_stat\n.include stat.inc\n"
                       ".subckt sky130_fd_pr__nfet_01v8 d g s b\n.ends\n.endl\n");
  const std::string pixel = ".subckt p vdd out gnd params: iph=1p\nI1 vdd out {iph}\n"
                            "M1 out out gnd gnd sky130_fd_pr__nfet_01v8 w=1u l=1u\n.ends\n";
  const PixelDeck tt = read_pixel_deck(write("tt.cir", ".lib corners.lib tt\n" + pixel), "p", "int");
  EXPECT_TRUE(tt.statistical_switches.empty());
  EXPECT_EQ(tt.statistical_file, "");
  const PixelDeck stat = read_pixel_deck(write("stat.cir", ".lib corners.lib tt_stat\n" + pixel), "p", "int");
  EXPECT_EQ(stat.statistical_switches, std::vector<std::string>{"sw_stat_mismatch"});
  EXPECT_EQ(stat.statistical_file, (dir_ / "stat.inc").string());
  // Read whole, the file is its lines outside the sections: no statistics either.
  const PixelDeck whole = read_pixel_deck(write("whole.cir", ".include corners.lib\n" + pixel), "p", "int");
  EXPECT_TRUE(whole.statistical_switches.empty());
  EXPECT_EQ(whole.statistical_file, "");
  // Both sections: the library's bytes once in the hash, so naming a second section of it adds
  // only the file it includes.
  const PixelDeck both =
      read_pixel_deck(write("both.cir", ".lib corners.lib tt\n.lib corners.lib tt_stat\n" + pixel), "p", "int");
  EXPECT_EQ(both.statistical_switches, std::vector<std::string>{"sw_stat_mismatch"});
  write("stat.inc", "* statistics, changed\n.param dvth = agauss(0, 0.02, 1)\n.param sw_stat_mismatch = 1\n");
  EXPECT_EQ(read_pixel_deck(dir_ / "tt.cir", "p", "int").hash, tt.hash);
  EXPECT_NE(read_pixel_deck(dir_ / "both.cir", "p", "int").hash, both.hash);
}

// The supply the deck's MOS devices are made for, as SKY130 and GF180 spell it in their model
// names: the lowest of those its element lines use, never a capacitor's density or a model the
// PDK's own files define.
// The runs' nets on the pixel's ports: by the ports' names when each is plainly the supply, the
// output or the ground, one of each, in any order and case; else vdd out 0 in their order.
TEST_F(DeckReadingTest, APixelsPortsAreTakenByTheirNamesWhenTheySayWhichIsWhich) {
  using Nets = std::vector<std::string>;
  EXPECT_EQ(port_nets_by_name({"vdd", "out", "gnd"}), (Nets{"vdd", "out", "0"}));
  EXPECT_EQ(port_nets_by_name({"VSS", "VDD", "Spike"}), (Nets{"0", "vdd", "out"}));
  EXPECT_EQ(port_nets_by_name({"vpwr", "vgnd", "fire"}), (Nets{"vdd", "0", "out"}));
  for (const Nets& unclear : {Nets{"a", "b", "c"}, Nets{"vdd", "vcc", "out"}, Nets{"vdd", "out", "bias"}}) {
    EXPECT_EQ(port_nets_by_name(unclear), (Nets{"vdd", "out", "0"})) << unclear[0] << " " << unclear[1] << " " << unclear[2];
  }
  std::string swapped = slurp(kIdealDeck);
  swapped.replace(swapped.find("vdd out gnd params"), 11, "gnd vdd out");
  const PixelDeck deck = read_pixel_deck(write("swapped.cir", swapped), "ideal_pixel", "int");
  EXPECT_EQ(deck.port_nets, (Nets{"0", "vdd", "out"}));
  EXPECT_EQ(deck.ports_by_name, "gnd vdd out");
  EXPECT_EQ(read_pixel_deck(kIdealDeck, "ideal_pixel", "int").ports_by_name, "");
}

TEST_F(DeckReadingTest, TheDevicesRatedSupplyComesFromTheirModelNames) {
  write("pdk.lib", ".subckt sky130_fd_pr__nfet_g5v0d10v5 d g s b\nM1 d g s b sky130_fd_pr__nfet_01v8__model\n.ends\n"
                   ".model sky130_fd_pr__nfet_01v8__model nmos level=1\n");
  const std::string pixel = ".include pdk.lib\n.subckt p vdd out gnd params: iph=1p\nI1 vdd out {iph}\n";
  const std::map<std::string, std::pair<std::string, double>> cases = {
      {"sky130", {"XM1 out g gnd gnd sky130_fd_pr__nfet_01v8 W=1 L=0.15\n"
                  "XM2 out g vdd vdd sky130_fd_pr__pfet_g5v0d10v5 W=1 L=0.5\n", 1.8}},
      {"thick_gate", {"XM2 out g vdd vdd sky130_fd_pr__pfet_g5v0d10v5 W=1 L=0.5\n", 5.0}},
      {"gf180", {"M5 out n1 vdd vdd pmos_3p3 L=1.4u W=0.84u\nXC3 out n1 mim_2p0fF c_width=6e-6 c_length=5e-6\n", 3.3}},
      {"gf180_open_pdks", {"XM1 out n1 gnd gnd nfet_06v0_nvt W=1u L=1u\nXM2 out n1 gnd gnd nfet_03v3 W=1u L=1u\n", 3.3}},
      {"ihp", {"XM1 out n1 gnd gnd sg13_lv_nmos w=1u l=0.13u\n", 0}},
      {"capacitor_only", {"XC3 out gnd mim_2p0fF c_width=6e-6 c_length=5e-6\n", 0}},
  };
  for (const auto& [name, spec] : cases) {
    write(name + ".cir", pixel + spec.first + ".ends\n");
    const PixelDeck deck = read_pixel_deck((dir_ / (name + ".cir")).string(), "p", "");
    EXPECT_DOUBLE_EQ(deck.device_rating, spec.second) << name;
    EXPECT_EQ(deck.rated_device.empty(), spec.second == 0) << name;
    EXPECT_EQ(supply_rating_note(deck, 3.3).empty(), spec.second == 0 || spec.second >= 3.3) << name;
    // A tenth over the rating is still the device's own supply.
    EXPECT_TRUE(supply_rating_note(deck, 1.1 * spec.second).empty()) << name;
  }
  // The subcircuit in an included file: its devices are read there.
  write("own.sp", ".subckt p vdd out gnd params: iph=1p\nI1 vdd out {iph}\nM1 out out gnd gnd nmos_3p3 W=1u L=1u\n.ends\n");
  write("wrapper.cir", ".include pdk.lib\n.include own.sp\n");
  const PixelDeck wrapped = read_pixel_deck((dir_ / "wrapper.cir").string(), "p", "");
  EXPECT_DOUBLE_EQ(wrapped.device_rating, 3.3);
  EXPECT_EQ(wrapped.rated_device, "nmos_3p3");
}

// A 1.8 V pixel calibrated at the default 3.3 V supply is told so before its runs and in the
// preset; at its own supply it is not.
TEST_F(NgspiceTest, ASupplyAboveTheDevicesRatingIsSaidBeforeTheRunsAndInThePreset) {
  std::string deck = slurp(kIdealDeck);
  const std::string last = ".ends";
  deck.insert(deck.rfind(last), "Mspare gnd gnd gnd gnd sky130_fd_pr__nfet_01v8 W=1u L=1u\n"
                                 ".model sky130_fd_pr__nfet_01v8 nmos level=1\n");
  write("rated.cir", deck);
  const Outcome hot = aesim("calibrate rated.cir --subckt ideal_pixel -o hot.toml --currents 1pA:100pA --points 3 -j 2");
  ASSERT_EQ(hot.status, 0) << hot.err;
  const std::string said = "warning: the deck's sky130_fd_pr__nfet_01v8 is a 1.8 V device (so its name says) and the "
                           "runs' supply is 3.3 V";
  // Right after the banner, before the runs, so a user can stop them.
  EXPECT_NE(hot.err.find("vdd 3.3 V, 2 ngspice at once\naesim calibrate: " + said), std::string::npos) << hot.err;
  EXPECT_NE(slurp(dir_ / "hot.toml").find("# The deck's sky130_fd_pr__nfet_01v8 is a 1.8 V device"), std::string::npos);
  const Outcome own = aesim("calibrate rated.cir --subckt ideal_pixel -o own.toml --currents 1pA:100pA --points 3 --vdd 1.8V");
  ASSERT_EQ(own.status, 0) << own.err;
  EXPECT_EQ(own.err.find("1.8 V device"), std::string::npos) << own.err;
  EXPECT_NE(own.err.find("vdd 1.8 V"), std::string::npos) << own.err;
}

TEST_F(NgspiceTest, APixelThatFiresOnlyAboveItsLeakageIsTabledWhereItFires) {
  // The known deck with 100 Gohm from the node to ground: at 1.5 V it leaks 15 pA, so below that
  // the node never reaches the threshold. Nothing is asked twice, and the warning names the rest.
  std::string deck = slurp(kIdealDeck);
  const std::string cap = "Cint int gnd 100f";
  deck.replace(deck.find(cap), cap.size(), cap + "\nRleak int gnd 100g");
  write("leaky.cir", deck);
  const Outcome o = aesim("calibrate leaky.cir --subckt ideal_pixel -o leaky.toml --currents 1pA:1nA --points 7");
  ASSERT_EQ(o.status, 0) << o.err;
  EXPECT_NE(o.err.find("never fired (or never settled to a period) at 3 of"), std::string::npos) << o.err;
  EXPECT_NE(o.err.find("(1e-12, 3.16e-12, 1e-11 A)"), std::string::npos) << o.err;
  SensorConfig c;
  apply_toml_file(c, (dir_ / "leaky.toml").string(), "");
  EXPECT_GT(c.pixel.transfer.current.front(), 15e-12);
  // Fewer transients than the table's points and the silent ones could need were it re-asking.
  const std::string preset = slurp(dir_ / "leaky.toml");
  EXPECT_LT(std::count(preset.begin(), preset.end(), '\n'), 130) << preset;
  // The highest current that never fired bounds the table from below: the model's pixel is silent
  // there too. The circuit's form finds the leak as a negative i_dark between the silent current
  // and the lowest that fired (the resistor's current over the ramp from 0.5 V to 1.5 V, 5 to 15 pA).
  EXPECT_DOUBLE_EQ(c.pixel.transfer.silent_below, 1e-11);
  EXPECT_EQ(c.pixel.integrating_current_at(1e-11), 0.0);
  EXPECT_NE(preset.find("At 1e-11 A and below the circuit does not keep firing"), std::string::npos) << preset;
  const std::size_t leak = preset.find("(a leak: below ");
  ASSERT_NE(leak, std::string::npos) << preset;
  const double below = std::stod(preset.substr(leak + 15));
  EXPECT_GT(below, 5e-12);
  EXPECT_LT(below, 15e-12);

  // Where only one current of the grid fires, the error names it and what the nearest silent one showed.
  const Outcome narrow = aesim("calibrate leaky.cir --subckt ideal_pixel -o narrow.toml --currents 1pA:31.6pA --points 4");
  EXPECT_EQ(narrow.status, 2) << narrow.err;
  EXPECT_NE(narrow.err.find("the pixel fires at only 1 of the 4 photocurrents (3.16e-11 A; at 1e-11 A node 'int' settles "
                            "at "),
            std::string::npos)
      << narrow.err;
  EXPECT_FALSE(fs::exists(dir_ / "narrow.toml"));
}

// The known deck with an axon hillock's reset: the photocurrent stays on, and while out is high a
// constant 0.8 nA sink discharges the node against it, so the reset lengthens with the light,
// t_r / (1 - I / I_r) with t_r = 100 fF x 0.999 V / 0.8 nA = 124.9 us and I_r = 0.8 nA, and at and
// above 0.8 nA it never ends: out stays high. The table ends where the pixel fired, the first
// latched current bounds it from above, the circuit's form finds the latch, and a run on light
// past it fires none of those pixels.
TEST_F(NgspiceTest, AResetTheLightOutrunsLatchesAndThePresetSaysWhere) {
  std::string deck = slurp(kIdealDeck);
  const auto replace = [&deck](const std::string& from, const std::string& to) {
    ASSERT_NE(deck.find(from), std::string::npos) << from;
    deck.replace(deck.find(from), from.size(), to);
  };
  replace("Bph vdd int I = v(out) < v(vdd) / 2 ? iph : 0", "Iph vdd int {iph}");
  replace("Srst int dis int gnd hysteresis", "Bdis int gnd I = v(out) > v(vdd) / 2 ? 0.8n : 0");
  replace("Rdis dis lo 1.59meg", "");
  write("latching.cir", deck);
  const Outcome o = aesim("calibrate latching.cir --subckt ideal_pixel -o latching.toml --currents 1pA:1nA --points 7");
  ASSERT_EQ(o.status, 0) << o.err;
  SensorConfig c;
  apply_toml_file(c, (dir_ / "latching.toml").string(), "");
  EXPECT_NEAR(c.pixel.transfer.current.back() / std::pow(10.0, -9.5), 1, 1e-9);
  EXPECT_DOUBLE_EQ(c.pixel.transfer.silent_above, 1e-9);
  const std::string preset = slurp(dir_ / "latching.toml");
  EXPECT_NE(preset.find("At 1e-09 A and above the circuit does not keep firing (fired 1 time, then out latched high"),
            std::string::npos)
      << preset;
  // The periods' scatter near the latch reads as a bend at every spacing: refined by it without
  // the quartered miss of each added midpoint, the table grew to 396 currents; 20 with it.
  const std::size_t counted = preset.find(" photocurrents from ");
  ASSERT_NE(counted, std::string::npos);
  EXPECT_LE(std::stoi(preset.substr(preset.rfind(", ", counted) + 2)), 40) << preset.substr(0, 200);
  const std::size_t latch = preset.find("I_r = ");
  ASSERT_NE(latch, std::string::npos) << preset;
  // The pulses are measured to the time steps of runs sized for their periods, about 1 % at the
  // lowest currents, so the latch and the reset are known to a few percent.
  EXPECT_NEAR(std::stod(preset.substr(latch + 6)) / 0.8e-9, 1, 0.03);
  const std::size_t t_r = preset.find("t_r = ");
  ASSERT_NE(t_r, std::string::npos);
  EXPECT_NEAR(std::stod(preset.substr(t_r + 6)) / 124.9e-6, 1, 0.02);
  EXPECT_NE(preset.find("the pixel latches"), std::string::npos);
  // scenes/gradient.pgm at i_max = 2 nA: the pixels at or above 1 nA never fire.
  const Outcome run = aesim("run --sensor latching.toml --scene " + std::string(AESIM_SOURCE_DIR) +
                            "/scenes/gradient.pgm --set pixel.i_max=2nA --set pixel.initial=reset --set "
                            "bus.access=ideal --duration 5ms --truth truth.csv --summary s.json");
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.err.find("where the circuit does not keep firing, do not fire in the model either"), std::string::npos)
      << run.err;
  const std::string truth = slurp(dir_ / "truth.csv");
  const std::string pgm = slurp(std::string(AESIM_SOURCE_DIR) + "/scenes/gradient.pgm");
  const std::size_t header = std::string("P5\n64 64\n65535\n").size();
  std::size_t lines = 0, fired_past = 0;
  std::istringstream rows(truth);
  std::string line;
  std::getline(rows, line);
  while (std::getline(rows, line)) {
    ++lines;
    const int x = std::stoi(line), y = std::stoi(line.substr(line.find(',') + 1));
    const std::size_t at = header + 2 * static_cast<std::size_t>(y * 64 + x);
    const unsigned raw = (static_cast<unsigned char>(pgm[at]) << 8) | static_cast<unsigned char>(pgm[at + 1]);
    fired_past += 2e-9 * raw / 65535.0 >= 1e-9;
  }
  EXPECT_GT(lines, 100u);
  EXPECT_EQ(fired_past, 0u);
}

// A pixel that never fires is told so after one transient per current, with what the run showed,
// instead of ever longer runs that cannot end otherwise: the shipped deck with its photocurrent
// reversed (the node sits at the diode's clamp) and with its output stage replaced by a pull-up
// (out held high).
TEST_F(NgspiceTest, APixelThatNeverFiresIsToldSoWithWhatTheRunShowed) {
  const std::string shipped = slurp(kShippedDeck);
  std::string reversed = shipped, latched = shipped;
  reversed.replace(reversed.find("Iph vdd int {iph}"), 17, "Iph int vdd {iph}");
  latched.replace(latched.find("Mp2 out n1 vdd vdd pch w=1u l=2u"), 32, "");
  latched.replace(latched.find("Mn2 out n1 gnd gnd nch w=1u l=4u"), 32, "Rpu out vdd 1k");
  // The node that settles at the brightest current settles at every weaker one, and out that
  // latches at the weakest latches at every stronger one: the other twelve currents are not
  // waited for, and the error names the current that showed it.
  const std::pair<const char*, const char*> cases[] = {{"reversed", "at 1e-09 A node 'int' settles at"},
                                                       {"latched", "at 1e-15 A out latched high (3.3 V)"}};
  const std::map<std::string, std::string> decks = {{"reversed", reversed}, {"latched", latched}};
  for (const auto& [name, seen] : cases) {
    write(std::string(name) + ".cir", decks.at(name));
    const Outcome o = aesim(std::string("calibrate ") + name + ".cir --subckt aesim_pixel -o " + name + ".toml");
    EXPECT_EQ(o.status, 2) << o.err;
    EXPECT_NE(o.err.find("never fires between 1e-15 A and 1e-09 A"), std::string::npos) << o.err;
    EXPECT_NE(o.err.find(seen), std::string::npos) << o.err;
    EXPECT_NE(o.err.find("(12 of the 13 currents, beyond it, were not waited for)"), std::string::npos) << o.err;
    EXPECT_FALSE(fs::exists(dir_ / (std::string(name) + ".toml")));
  }
}

// ngspice's compatibility mode is the one the user's own runs have: a PDK's .spiceinit beside the
// deck sets it (open_pdks' `set ngbehavior=hsa`), aesim runs ngspice without reading that file
// (it runs commands), and takes the mode from it; --ngbehavior chooses one. Under `hs` a binned
// model is chosen by a finger's width, so the binned deck's table is the one its bin-1 card alone
// gives, and without it the one bin 2 alone gives (tests/circuits/binned_pixel.cir).
TEST_F(NgspiceTest, TheCompatibilityModeOfTheDecksSpiceinitIsTheRunsAndSaid) {
  const std::string binned = slurp(kBinnedDeck);
  const auto only_bin = [&binned](int keep) {
    std::string text;
    std::istringstream lines(binned);
    for (std::string line; std::getline(lines, line);) {
      if (line.rfind(".model nch.", 0) == 0) {
        if (line[11] - '0' != keep) continue;
        line = ".model nch nmos level=54 version=4.5" + line.substr(line.find(" vth0"));
      }
      text += line + "\n";
    }
    return text;
  };
  fs::create_directories(dir_ / "hsa");
  fs::create_directories(dir_ / "plain");
  fs::create_directories(dir_ / "spiceinit");
  write("hsa/binned.cir", binned);
  write("hsa/.spiceinit", "* the PDK's\nset num_threads=4\nset ngbehavior=hsa\nset ng_nomodcheck\n");
  write("plain/binned.cir", binned);
  write("one.cir", only_bin(1));
  write("two.cir", only_bin(2));
  const std::string range = " --subckt binned_pixel --currents 1nA:10nA --points 3 -o ";
  // The table and the reset pulses a preset holds.
  const auto table = [this](const std::string& preset) {
    SensorConfig c;
    apply_toml_file(c, (dir_ / preset).string(), "");
    return std::make_pair(c.pixel.transfer.current, c.pixel.transfer.period);
  };
  const Outcome hsa = aesim("calibrate hsa/binned.cir" + range + "hsa.toml");
  ASSERT_EQ(hsa.status, 0) << hsa.err;
  EXPECT_NE(hsa.err.find("ngspice runs in compatibility mode ngbehavior=hsa, as " + (dir_ / "hsa" / ".spiceinit").string() +
                         " sets it (nothing else of that file is run"),
            std::string::npos)
      << hsa.err;
  EXPECT_NE(slurp(dir_ / "hsa.toml").find("# ngspice's compatibility mode in every run: ngbehavior=hsa (as "),
            std::string::npos);
  ASSERT_EQ(aesim("calibrate plain/binned.cir" + range + "plain.toml").status, 0);
  ASSERT_EQ(aesim("calibrate one.cir" + range + "one.toml").status, 0);
  ASSERT_EQ(aesim("calibrate two.cir" + range + "two.toml").status, 0);
  const Outcome chosen = aesim("calibrate plain/binned.cir --ngbehavior hsa" + range + "chosen.toml");
  ASSERT_EQ(chosen.status, 0) << chosen.err;
  EXPECT_EQ(table("hsa.toml"), table("one.toml"));
  EXPECT_EQ(table("chosen.toml"), table("one.toml"));
  EXPECT_EQ(table("plain.toml"), table("two.toml"));
  EXPECT_NE(table("one.toml"), table("two.toml"));  // the bins differ in what the runs measure
  EXPECT_EQ(slurp(dir_ / "plain.toml").find("compatibility mode"), std::string::npos);

  // Its last setting, spelled as ngspice takes it; nothing else of the file, and none without one.
  write("spiceinit/.spiceinit", "set ngbehavior=hs\n  set   ngbehavior = \"ltpsa\"\nset ngbehaviour=ps\nshell touch x\n");
  EXPECT_EQ(spiceinit_ngbehavior((dir_ / "spiceinit").string()), "ltpsa");
  EXPECT_EQ(spiceinit_ngbehavior((dir_ / "plain").string()), "");
  for (const char* bad : {"'hs;x'", "HSA", "'hs a'"}) {
    const Outcome o = aesim("calibrate plain/binned.cir --ngbehavior " + std::string(bad) + range + "bad.toml");
    EXPECT_EQ(o.status, 2) << bad;
    EXPECT_NE(o.err.find("expected ngspice's compatibility letters"), std::string::npos) << o.err;
    EXPECT_FALSE(fs::exists(dir_ / "bad.toml"));
  }
}

// Periods that scatter by more than the table resolves (the ideal pixel's photocurrent wobbling by
// 3 % with the current, sin(iph x 1e15): at any spacing finer than the grid's, a point's period
// lies anywhere within its wobble of its neighbours', as ngspice's near a foundry pixel's leak
// knee do with its time step) are measured once and said, not chased: more points would only
// sample the scatter again, to the table's 400-point limit. The smooth deck is never said to.
TEST_F(NgspiceTest, PeriodsThatScatterBeyondTheTablesToleranceAreSaidNotChased) {
  std::string deck = slurp(kIdealDeck);
  const std::string photocurrent = "I = v(out) < v(vdd) / 2 ? iph : 0";
  ASSERT_NE(deck.find(photocurrent), std::string::npos);
  deck.replace(deck.find(photocurrent), photocurrent.size(), "I = v(out) < v(vdd) / 2 ? iph * (1 + 0.03 * sin(iph * 1e15)) : 0");
  write("wobble.cir", deck);
  const std::string range = " --subckt ideal_pixel --currents 10pA:100pA --points 3 -o ";
  const Outcome o = aesim("calibrate wobble.cir" + range + "wobble.toml");
  ASSERT_EQ(o.status, 0) << o.err;
  const std::size_t said = o.err.find("warning: the periods between ");
  ASSERT_NE(said, std::string::npos) << o.err;
  const std::string words = o.err.substr(said, o.err.find('\n', said) - said);
  EXPECT_NE(words.find("scatter by more than the table resolves"), std::string::npos) << words;
  EXPECT_NE(words.find("the table was not refined further there"), std::string::npos) << words;
  // How far a point fell outside its neighbours: beyond the table's 0.2 %, within two wobbles.
  const std::size_t up_to = words.find("by up to ");
  ASSERT_NE(up_to, std::string::npos) << words;
  const double outside = std::stod(words.substr(up_to + 9));
  EXPECT_GT(outside, 0.2) << words;
  EXPECT_LT(outside, 100 * (1.03 / 0.97 - 1)) << words;
  const std::string preset = slurp(dir_ / "wobble.toml");
  EXPECT_NE(preset.find("# The periods between "), std::string::npos) << preset;
  SensorConfig c;
  apply_toml_file(c, (dir_ / "wobble.toml").string(), "");
  EXPECT_LT(c.pixel.transfer.current.size(), 100u) << "the table chased the scatter";
  EXPECT_GT(c.pixel.transfer.current.size(), 3u);

  const Outcome smooth = aesim("calibrate " + kIdealDeck + range + "smooth.toml");
  ASSERT_EQ(smooth.status, 0) << smooth.err;
  EXPECT_EQ(smooth.err.find("scatter"), std::string::npos) << smooth.err;
}

// A deck written as foundry decks are (tests/circuits/bsim_axon_hillock.cir: BSIM4 transistors,
// a behavioural MIM capacitor with its leak, a photodiode with 2 fA of dark current, statistical
// switches on) calibrates with the default currents: the switches are found and set to 0; at 1 fA,
// below the dark current, the node settles a few tens of millivolts above ground, where ngspice
// itself gives up under the first solver settings (the capacitor's branch, as on the GF180 PDK's
// MIM capacitor), and the trapezoidal fallback runs it and is said; the dark current is fitted as a
// leak; the reset that the light lengthens and the latch past it are fitted, the currents past the
// latch are silent beyond it. An independent ngspice testbench (its own tolerances and step, the
// period from `meas` of the 2nd to the 6th rising edge) at 0.2 pA, between two table points, gives
// the period `aesim run` fires at with the preset.
TEST_F(NgspiceTest, ABsimDeckCalibratesWithTheDefaultCurrentsAndRunsAsTheCircuitDoes) {
  // ngspice alone, under the first settings at 1 fA: it gives up (no stand-in here).
  write("first_settings.cir", fmt::format(R"(* the BSIM deck at 1 fA under aesim's first solver settings
.options method=gear reltol=1e-4 abstol=1e-17 chgtol=1e-19 gmin=1e-18
.include "{}"
.param sw_stat_global=0 sw_stat_mismatch=0
Vdd vdd 0 3.3
X1 vdd out 0 bsim_axon_hillock iph=1e-15
.control
set num_threads=1
tran 0.2 1050 0 0.2 uic
quit 0
.endc
.end
)", kBsimDeck));
  run_child("ngspice", {"-b", "-n", "first_settings.cir"},
            {(dir_ / "first_settings.out").string(), (dir_ / "first_settings.err").string(), dir_.string()});
  EXPECT_NE((slurp(dir_ / "first_settings.out") + slurp(dir_ / "first_settings.err")).find("Timestep too small"),
            std::string::npos);

  const Outcome o = aesim("calibrate " + kBsimDeck + " --subckt bsim_axon_hillock --probe mem -o bsim.toml");
  ASSERT_EQ(o.status, 0) << o.err;
  EXPECT_NE(o.err.find("1 photocurrent (1e-15 A) run with fallback settings (trap, abstol and gmin x vdd at 1e-3 of "
                       "the photocurrent) after ngspice gave up under tighter ones"),
            std::string::npos)
      << o.err;
  // Its period turns once, rising again as the reset lengthens towards the latch: not scatter.
  EXPECT_EQ(o.err.find("scatter"), std::string::npos) << o.err;
  const std::string preset = slurp(dir_ / "bsim.toml");
  EXPECT_NE(preset.find("the deck's switches sw_stat_global, sw_stat_mismatch were set to 0 for the table"),
            std::string::npos)
      << preset;
  EXPECT_NE(preset.find("#   1 point: trap, abstol and gmin x vdd at 1e-3 of the photocurrent (1e-15 A)"),
            std::string::npos)
      << preset;
  EXPECT_NE(preset.find("At 1e-15 A and below the circuit does not keep firing (node 'mem' settles at 0.0"),
            std::string::npos)
      << preset;
  EXPECT_NE(preset.find("At 1e-11 A and above the circuit does not keep firing (fired 1 time, then out latched high"),
            std::string::npos)
      << preset;
  EXPECT_NE(preset.find("the pixel latches"), std::string::npos) << preset;
  // The circuit's own form: the photodiode's 2 fA (its reverse current is its saturation current a
  // few kT/q above ground) plus the capacitor's leak (0.06 fA at 1 V), as a negative dark current.
  const std::size_t leak_at = preset.find("i_dark = -", preset.find("# The circuit's own form"));
  ASSERT_NE(leak_at, std::string::npos) << preset;
  EXPECT_NEAR(std::stod(preset.substr(leak_at + 9)), -2.06e-15, 0.2e-15) << preset;
  std::size_t beyond = 0;
  for (std::size_t at = preset.find("silent beyond"); at != std::string::npos; at = preset.find("silent beyond", at + 1)) ++beyond;
  EXPECT_EQ(beyond, 4u) << preset;  // 31.6 pA to 1 nA, past the latch seen at 10 pA
  SensorConfig c;
  apply_toml_file(c, (dir_ / "bsim.toml").string(), "");
  ASSERT_GE(c.pixel.transfer.current.size(), 20u);
  EXPECT_NEAR(c.pixel.transfer.current.front(), 3.16227766e-15, 1e-23);
  EXPECT_DOUBLE_EQ(c.pixel.transfer.silent_below, 1e-15);
  EXPECT_DOUBLE_EQ(c.pixel.transfer.silent_above, 1e-11);

  write("independent.cir", fmt::format(R"(* the BSIM deck at 0.2 pA, nominal
.include "{}"
.param sw_stat_global=0 sw_stat_mismatch=0
.options method=gear reltol=1e-5 abstol=1e-17 chgtol=1e-19 gmin=1e-18
Vdd vdd 0 3.3
X1 vdd out 0 bsim_axon_hillock iph=2e-13
.control
set num_threads=1
tran 1e-4 4 0 2e-4 uic
meas tran first when v(out)=1.65 rise=2
meas tran last when v(out)=1.65 rise=6
quit 0
.endc
.end
)", kBsimDeck));
  ASSERT_EQ(run_child("ngspice", {"-b", "-n", "independent.cir"},
                      {(dir_ / "independent.out").string(), (dir_ / "independent.err").string(), dir_.string()}),
            0);
  const std::string measured = slurp(dir_ / "independent.out");
  const auto value = [&measured](const std::string& name) {
    const std::size_t at = measured.find("\n" + name + " ");
    EXPECT_NE(at, std::string::npos) << measured;
    return at == std::string::npos ? 0.0 : std::stod(measured.substr(measured.find('=', at) + 1));
  };
  const double circuit = (value("last") - value("first")) / 4;
  ASSERT_GT(circuit, 0.4);
  const Outcome run = aesim("run --sensor bsim.toml --scene " + std::string(AESIM_SOURCE_DIR) +
                            "/scenes/uniform.pgm --set pixel.i_max=2e-13A --set pixel.mismatch=0 --set "
                            "pixel.initial=reset --set bus.access=ideal --duration 3s --truth truth.csv");
  ASSERT_EQ(run.status, 0) << run.err;
  std::istringstream rows(slurp(dir_ / "truth.csv"));
  std::string line;
  std::vector<double> fires;
  std::getline(rows, line);
  while (std::getline(rows, line)) {
    if (line.rfind("0,0,", 0) == 0) fires.push_back(std::stod(line.substr(line.find(',', 4) + 1)) * 1e-6);
  }
  ASSERT_GE(fires.size(), 4u);
  const double model = (fires.back() - fires.front()) / static_cast<double>(fires.size() - 1);
  EXPECT_NEAR(model / circuit, 1, 0.003) << model << " s against the circuit's " << circuit << " s";
}

// The same deck with a short reset and a leakier capacitor: the leak is fitted as a negative dark
// current and the node settles at 3.16 fA (silent below the table: the photodiode's 2 fA and the
// capacitor's 1.5 fS at the node's 0.77 V), and the supply's charge per firing
// comes out negative (a crowbar current that grows with the period): said, with the figures, and
// the energy per firing held at 0 rather than clamped in silence.
TEST_F(NgspiceTest, ABsimDeckWithALeakAndAShortResetSaysBoth) {
  std::string deck = slurp(kBsimDeck);
  const std::string defaults = "params: iph=1p vbias=0.5 gleak=1.9e-6";
  ASSERT_NE(deck.find(defaults), std::string::npos);
  deck.replace(deck.find(defaults), defaults.size(), "params: iph=1p vbias=0.9 gleak=5e-5");
  write("leaky.cir", deck);
  const Outcome o = aesim("calibrate leaky.cir --subckt bsim_axon_hillock --probe mem -o leaky.toml");
  ASSERT_EQ(o.status, 0) << o.err;
  EXPECT_NE(o.err.find("warning: power.e_pixel_event is 0: the supply's charge per firing, 0 C (the line fitted without "
                       "bounds gives -"),
            std::string::npos)
      << o.err;
  const std::string preset = slurp(dir_ / "leaky.toml");
  EXPECT_NE(preset.find("(a leak: below "), std::string::npos) << preset;
  EXPECT_NE(preset.find("At 3.162e-15 A and below the circuit does not keep firing (node 'mem' settles at"),
            std::string::npos)
      << preset;
  EXPECT_NE(preset.find("I_r = none (the reset does not follow the light)"), std::string::npos) << preset;
  SensorConfig c;
  apply_toml_file(c, (dir_ / "leaky.toml").string(), "");
  EXPECT_NEAR(c.pixel.transfer.silent_below, 3.16227766e-15, 1e-23);
  EXPECT_EQ(c.power.e_pixel_event, 0.0);
  EXPECT_GT(c.power.p_static_pixel, 0.0);
}

// The same deck with its photocurrent reversed: the node settles at the brightest current, and no
// weaker one is waited for. The range ends at 100 nA rather than the default 1 nA: ngspice holds
// this settled node at 15 ns steps whatever the current, and the run at 1 nA, ten periods of a
// firing at that light, took it 17 s of the test's 19 (1.4 s in all at 100 nA).
TEST_F(NgspiceTest, ABsimDeckThatNeverFiresIsToldSoFromItsBrightestCurrent) {
  std::string deck = slurp(kBsimDeck);
  deck.replace(deck.find("Iph vdd mem {iph}"), 17, "Iph mem vdd {iph}");
  write("reversed.cir", deck);
  const Outcome o =
      aesim("calibrate reversed.cir --subckt bsim_axon_hillock --probe mem -o reversed.toml --currents 1fA:100nA");
  EXPECT_EQ(o.status, 2) << o.err;
  EXPECT_NE(o.err.find("never fires between 1e-15 A and 1e-07 A"), std::string::npos) << o.err;
  // The node settles below ground, where the photodiode, forward biased, holds it: 0.34 V at 1 nA
  // (the default range's brightest), and about 60 mV more a decade of current (n kT/q ln 10).
  EXPECT_NE(o.err.find("at 1e-07 A node 'mem' settles at -0.45"), std::string::npos) << o.err;
  EXPECT_NE(o.err.find("(12 of the 13 currents, beyond it, were not waited for)"), std::string::npos) << o.err;
  EXPECT_FALSE(fs::exists(dir_ / "reversed.toml"));
}

TEST_F(NgspiceTest, BadDecksEndWithOneLineExitTwoAndNoPreset) {
  const std::string ideal = slurp(kIdealDeck);
  std::map<std::string, std::pair<std::string, std::string>> cases;  // name -> deck text, expected words
  std::string syntax = ideal;
  syntax.replace(syntax.find("Cint int gnd 100f"), 17, "Cint int gnd {100f");
  cases["syntax"] = {syntax, "ngspice rejects it"};
  cases["missing_subckt"] = {"* nothing here\n.end\n", "no subcircuit 'ideal_pixel'"};
  cases["ports"] = {".subckt ideal_pixel vdd out gnd extra params: iph=1p\nR1 out gnd 1k\n.ends\n", "has 4 ports"};
  cases["never_fires"] = {".subckt ideal_pixel vdd out gnd params: iph=1p\nR1 out gnd 1k\nI1 vdd out {iph}\n.ends\n",
                          "never fires"};
  // An analog node given as out, resting mid-rail (1.2 k over 1 k from 3.3 V: 1.8 V), is not said to
  // have latched high.
  cases["out_mid_rail"] = {".subckt ideal_pixel vdd out gnd params: iph=1p\nR1 vdd out 1k\nR2 out gnd 1.2k\n.ends\n",
                           "out held at 1.8 V, between the logic levels"};
  for (const auto& [name, spec] : cases) {
    write(name + ".cir", spec.first);
    const Outcome o = aesim("calibrate " + name + ".cir --subckt ideal_pixel -o " + name +
                            ".toml --currents 1pA:100pA --points 3");
    EXPECT_EQ(o.status, 2) << name << ": " << o.err;
    EXPECT_NE(o.err.find(spec.second), std::string::npos) << name << ": " << o.err;
    // One line of error (after the banner, when the deck got as far as ngspice).
    const std::string last = o.err.substr(o.err.rfind('\n', o.err.size() - 2) + 1);
    EXPECT_EQ(last.rfind("aesim: ", 0), 0u) << name << ": " << o.err;
    EXPECT_NE(last.find(spec.second), std::string::npos) << name << ": " << o.err;
    EXPECT_FALSE(fs::exists(dir_ / (name + ".toml"))) << name;
    // Where ngspice itself rejected the deck, its whole log is kept beside the preset, named in
    // the error: the testbench aesim ran and ngspice's own words, which the one line abridges.
    const fs::path log = dir_ / (name + ".ngspice.log");
    EXPECT_EQ(fs::exists(log), name == "syntax") << name;
    if (name == "syntax") {
      EXPECT_NE(last.find("(ngspice's log: " + name + ".ngspice.log)"), std::string::npos) << o.err;
      // The cause ngspice gave (an unclosed brace), not only its closing "fatal error".
      EXPECT_NE(last.find("not found"), std::string::npos) << o.err;
      const std::string kept = slurp(log);
      EXPECT_NE(kept.find("Xpix vdd out 0 ideal_pixel"), std::string::npos) << kept;
      EXPECT_NE(kept.find("* ngspice's output"), std::string::npos) << kept;
    }
  }
  // ngspice missing: PATH without it.
  const Outcome o = aesim("calibrate '" + kIdealDeck + "' --subckt ideal_pixel -o x.toml", "PATH=/nonexistent ");
  EXPECT_EQ(o.status, 2) << o.err;
  EXPECT_NE(o.err.find("ngspice is not installed"), std::string::npos) << o.err;
  EXPECT_FALSE(fs::exists(dir_ / "x.toml"));
  // Absurd options are refused before any ngspice runs.
  for (const char* bad : {"--points 1", "--points 100000", "--currents 1nA:1fA", "--mc 1", "--vdd -1V"}) {
    const Outcome b = aesim("calibrate '" + kIdealDeck + "' --subckt ideal_pixel -o y.toml " + bad);
    EXPECT_EQ(b.status, 2) << bad << ": " << b.err;
  }
}

TEST_F(NgspiceTest, ShellSyntaxInTheDeckPathIsOnlyAName) {
  // The path reaches ngspice inside the generated testbench (its folder in the paths of the files
  // the deck includes, .include "FOLDER/FILE") and as an argument;
  // no shell sees it. What ngspice's .include line cannot carry (a quote, ';', ' $') is refused.
  write("deck$(touch pwned)|`touch pwned2`&x.cir", slurp(kIdealDeck));
  const Outcome o = aesim("calibrate 'deck$(touch pwned)|`touch pwned2`&x.cir' --subckt ideal_pixel -o p.toml "
                          "--currents 1pA:10pA --points 3");
  EXPECT_EQ(o.status, 0) << o.err;
  EXPECT_TRUE(fs::is_regular_file(dir_ / "p.toml"));
  for (const char* name : {"a\"b.cir", "a;touch pwned.cir", "a $ b.cir"}) {
    write(name, slurp(kIdealDeck));
    const Outcome refused = aesim(std::string("calibrate '") + name + "' --subckt ideal_pixel -o q.toml");
    EXPECT_EQ(refused.status, 2) << name;
    EXPECT_NE(refused.err.find("cannot carry"), std::string::npos) << refused.err;
    EXPECT_FALSE(fs::exists(dir_ / "q.toml"));
  }
  EXPECT_FALSE(fs::exists(dir_ / "pwned"));
  EXPECT_FALSE(fs::exists(dir_ / "pwned2"));
}

// A Verilog-A model compiled by OpenVAF (IHP SG13G2's PSP 103 MOS models) is an OSDI library,
// which ngspice loads with `pre_osdi` before it reads the circuit (its README_OSDI.md): --osdi puts
// one such line a library in each run's control block, with the library's bytes in the deck's
// hash. A deck whose devices need a library nobody gave is told to give one; a library given to an
// ngspice built without OSDI is told that. Either way its log is this calibration's, not an
// earlier one's.
TEST_F(NgspiceTest, AVerilogAModelIsGivenWithOsdiAndSaidWhenNgspiceCannotLoadIt) {
  const std::string library = write("psp.osdi", "not a library");
  const PixelDeck plain = read_pixel_deck(kIdealDeck, "ideal_pixel", "int");
  const PixelDeck with = read_pixel_deck(kIdealDeck, "ideal_pixel", "int", {library});
  ASSERT_EQ(with.osdi.size(), 1u);
  EXPECT_EQ(with.osdi[0], library);
  EXPECT_NE(with.hash, plain.hash);
  EXPECT_EQ(read_pixel_deck(kIdealDeck, "ideal_pixel", "int", {library}).hash, with.hash);
  TransientRequest request;
  request.iph = 1e-12;
  request.t_stop = 1e-3;
  request.t_max = 1e-6;
  const std::string bench = testbench_text(with, 3.3, request, "data.txt");
  const auto control = bench.find(".control\n"), load = bench.find("pre_osdi '" + library + "'\n");
  ASSERT_NE(load, std::string::npos) << bench;
  EXPECT_LT(control, load);
  EXPECT_LT(load, bench.find("\ntran "));
  EXPECT_EQ(testbench_text(plain, 3.3, request, "data.txt").find("osdi"), std::string::npos);

  // An N element (ngspice's letter for OSDI devices) of a model type nothing loaded.
  std::string deck = slurp(kIdealDeck);
  deck.replace(deck.find(".ends"), 5, "Nva out gnd gnd gnd vamos w=1u l=1u\n.model vamos psp103va type=1\n.ends");
  write("va.cir", deck);
  const std::string args = "calibrate va.cir --subckt ideal_pixel -o va.toml --currents 1pA:10pA --points 3";
  const Outcome missing = aesim(args);
  EXPECT_EQ(missing.status, 2) << missing.err;
  EXPECT_NE(missing.err.find("ngspice does not know the model type of the N element n.xpix.nva; a Verilog-A model "
                             "compiled by OpenVAF"),
            std::string::npos)
      << missing.err;
  EXPECT_NE(missing.err.find("loads with --osdi FILE.osdi"), std::string::npos) << missing.err;
  EXPECT_FALSE(fs::exists(dir_ / "va.toml"));
  EXPECT_EQ(slurp(dir_ / "va.ngspice.log").find("pre_osdi"), std::string::npos);

  // Whether this ngspice has the osdi command at all, asked of ngspice itself.
  write("probe.cir", "* osdi?\n.control\nosdi\nquit 0\n.endc\n.end\n");
  run_child("ngspice", {"-b", "-n", "probe.cir"},
            {(dir_ / "probe.out").string(), (dir_ / "probe.err").string(), dir_.string()});
  const bool has_osdi =
      (slurp(dir_ / "probe.out") + slurp(dir_ / "probe.err")).find("no such command") == std::string::npos;
  const Outcome given = aesim(args + " --osdi psp.osdi");
  EXPECT_EQ(given.status, 2) << given.err;
  // Without OSDI the command is missing; with it, this is no library.
  EXPECT_NE(given.err.find(has_osdi ? "--osdi: ngspice could not load a library: "
                                    : "--osdi: this ngspice cannot load OSDI libraries (it has no osdi command"),
            std::string::npos)
      << given.err;
  EXPECT_FALSE(fs::exists(dir_ / "va.toml"));
  // The log is this run's, whose testbench loads the library.
  EXPECT_NE(slurp(dir_ / "va.ngspice.log").find("pre_osdi '" + library + "'"), std::string::npos);

  // A deck that loads its library itself, as a PDK's examples do, is told to give it with --osdi.
  write("loads.cir", "* loads its library\n.control\npre_osdi psp.osdi\n.endc\n" + deck);
  const Outcome loads = aesim("calibrate loads.cir --subckt ideal_pixel -o loads.toml");
  EXPECT_EQ(loads.status, 2) << loads.err;
  EXPECT_NE(loads.err.find("'loads.cir' line 2: a .control block that loads an OSDI library (pre_osdi psp.osdi); aesim "
                           "calibrate runs the circuit of a deck only: remove the block and give the library with --osdi"),
            std::string::npos)
      << loads.err;
  EXPECT_FALSE(fs::exists(dir_ / "loads.toml"));

  for (const char* bad : {"absent.osdi", "a\"b.osdi", "a$HOME.osdi"}) {
    if (std::string(bad) != "absent.osdi") write(bad, "x");
    const Outcome refused = aesim(args + " --osdi '" + bad + "'");
    EXPECT_EQ(refused.status, 2) << refused.err;
    EXPECT_NE(refused.err.find(std::string("--osdi '") + bad + "'"), std::string::npos) << refused.err;
    EXPECT_FALSE(fs::exists(dir_ / "va.toml"));
  }
}

TEST_F(NgspiceTest, CtrlCStopsItWithNoPresetAndNoScratchLeft) {
  // Its own TMPDIR, where the command keeps its ngspice files: empty again after the signal.
  fs::create_directories(dir_ / "tmp");
  const Outcome o = aesim("calibrate '" + kIdealDeck + "' --subckt ideal_pixel -o p.toml --points 200 --mc 1000",
                          "TMPDIR='" + (dir_ / "tmp").string() + "' timeout --preserve-status -s INT 2 ");
  EXPECT_EQ(o.status, 128 + SIGINT) << o.err;
  EXPECT_FALSE(fs::exists(dir_ / "p.toml"));
  EXPECT_TRUE(fs::is_empty(dir_ / "tmp"));
}

TEST_F(NgspiceTest, AnNgspiceEndedByCtrlCIsAnInterruptionNotABadDeck) {
  // The group's Ctrl-C can end ngspice before the command sees its own: an ngspice that ends by
  // SIGINT (here a stand-in that sends it to itself) stops the command as the Ctrl-C would.
  fs::create_directories(dir_ / "bin");
  write("bin/ngspice", "#!/bin/sh\nkill -INT $$\n");
  fs::permissions(dir_ / "bin" / "ngspice", fs::perms::owner_all);
  const Outcome o = aesim("calibrate '" + kIdealDeck + "' --subckt ideal_pixel -o p.toml --points 3",
                          "PATH='" + (dir_ / "bin").string() + ":/usr/bin:/bin' ");
  EXPECT_EQ(o.status, 128 + SIGINT) << o.err;
  EXPECT_EQ(o.err.find("rejects"), std::string::npos) << o.err;
  EXPECT_FALSE(fs::exists(dir_ / "p.toml"));
}

TEST_F(NgspiceTest, SameDeckSameOptionsSameBytesAndTheChart) {
  const std::string args = "calibrate '" + kIdealDeck + "' --subckt ideal_pixel --currents 1pA:10nA --points 5 -o ";
  ASSERT_EQ(aesim(args + "a.toml --chart a.png -j 1").status, 0);
  ASSERT_EQ(aesim(args + "b.toml -j 2").status, 0);
  EXPECT_EQ(slurp(dir_ / "a.toml"), slurp(dir_ / "b.toml"));
  EXPECT_GT(fs::file_size(dir_ / "a.png"), 1000u);
  EXPECT_TRUE(fs::is_regular_file(dir_ / "a.csv"));
  EXPECT_EQ(slurp(dir_ / "a.png").substr(1, 3), "PNG");
}

// A circuit whose supply charge per firing is below its threshold charge (it draws the rest
// through paths that grow with the period) cannot have a negative e_pixel_event: it is 0, and the
// preset and the command say why and by how much each firing's energy is then overstated.
TEST(CalibratedPreset, ASupplyChargeBelowTheThresholdChargeIsSaidNotSilentlyClamped) {
  Calibration c;
  c.fit.charge = 100e-15;
  c.supply.charge_per_firing = 60e-15;
  c.supply.static_current = 1e-9;
  const SensorConfig config = calibrated_config(load_sensor("aloha"), c, 1.8);
  EXPECT_EQ(config.power.e_pixel_event, 0.0);
  const std::string note = per_firing_energy_note(c, 1.8);
  EXPECT_NE(note.find("4e-14 C below the threshold charge"), std::string::npos) << note;
  EXPECT_NE(note.find("7.2e-14 J high"), std::string::npos) << note;  // 1.8 V x 40 fC
  c.supply.charge_per_firing = 130e-15;
  EXPECT_EQ(per_firing_energy_note(c, 1.8), "");
  EXPECT_NEAR(calibrated_config(load_sensor("aloha"), c, 1.8).power.e_pixel_event, 1.8 * 30e-15, 1e-27);
}

// ngspice as a foundry deck makes it behave, standing first on PATH: after its progress lines, it
// gives up ("Timestep too small", as ngspice words it) on every transient below `below` amperes, under aesim's first
// solver settings only (abstol=1e-17) or under every setting, and otherwise hands the run to the
// real ngspice. What the calibration does then, and says, is tested on the shipped deck.
class FallbackTest : public NgspiceTest {
 protected:
  // The real ngspice, the first on PATH.
  static std::string real_ngspice() {
    std::istringstream dirs(std::getenv("PATH") ? std::getenv("PATH") : "/usr/bin");
    std::string dir;
    while (std::getline(dirs, dir, ':')) {
      const fs::path candidate = fs::path(dir) / "ngspice";
      if (!dir.empty() && fs::is_regular_file(candidate)) return candidate.string();
    }
    return "/usr/bin/ngspice";
  }
  std::string stand_in(double below, bool every_setting) {
    const fs::path bin = dir_ / "bin";
    fs::create_directories(bin);
    write("bin/ngspice", fmt::format(R"(#!/bin/sh
for deck; do :; done
iph=$(sed -n '1s/.* iph = \([^ ]*\) A$/\1/p' "$deck")
if {} awk -v i="$iph" 'BEGIN {{ exit !(i < {:g}) }}'; then
  echo 'Reference value :  1.00000e-05' >&2
  echo 'No. of Data Rows : 1234' >&2
  echo 'doAnalyses: TRAN:  Timestep too small; time = 1.2e-07, timestep = 1.25e-22: trouble with node "xpix.int"' >&2
  echo 'tran simulation(s) aborted' >&2
  exit 0
fi
exec '{}' "$@"
)", every_setting ? "" : "grep -q 'abstol=1e-17 ' \"$deck\" &&", below, real_ngspice()));
    fs::permissions(bin / "ngspice", fs::perms::owner_all);
    return "PATH=" + bin.string() + ":$PATH ";
  }
  // The preset's table: period by photocurrent, for the rows that fired.
  static std::map<double, double> table(const std::string& preset) {
    std::map<double, double> rows;
    std::istringstream in(preset);
    std::string line;
    while (std::getline(in, line)) {
      std::istringstream words(line);
      std::string hash, i_value, i_unit, p_value, p_unit;
      if (!(words >> hash >> i_value >> i_unit >> p_value >> p_unit) || hash != "#" || i_unit.back() != 'A' ||
          p_unit.back() != 's') {
        continue;
      }
      try {
        rows[parse_si(i_value + i_unit, "A", "current")] = parse_si(p_value + p_unit, "s", "period");
      } catch (const InputError&) {
      }
    }
    return rows;
  }
};

// Below 1 pA the first settings fail; above 10 fA the fallback's tolerances (a thousandth of the
// photocurrent) can be looser than them and still three decades below what is measured, so those
// currents are measured, and to the shipped preset's periods (all measured under the first
// settings) within 0.2 %; at and below 10 fA no looser setting is that tight: left out, and said.
TEST_F(FallbackTest, CurrentsTheFirstSettingsCannotRunAreMeasuredWithCheckedFallbacksAndSaidSo) {
  const Outcome o = aesim("calibrate " + kShippedDeck + " --subckt aesim_pixel -o pixel.toml", stand_in(1e-12, false));
  ASSERT_EQ(o.status, 0) << o.err;
  EXPECT_NE(o.err.find("4 photocurrents (3.16e-14, 5.62e-14, 1e-13, 3.16e-13 A) run with fallback settings (gear, "
                       "abstol and gmin x vdd at 1e-3 of the photocurrent)"),
            std::string::npos)
      << o.err;
  EXPECT_NE(o.err.find("warning: ngspice gave up at 3 photocurrents (1e-15, 3.16e-15, 1e-14 A)"), std::string::npos)
      << o.err;
  const std::string preset = slurp(dir_ / "pixel.toml");
  EXPECT_NE(preset.find("#   4 points: gear, abstol and gmin x vdd at 1e-3 of the photocurrent (3.162e-14, 5.623e-14, 1e-13, "
                        "3.162e-13 A)"), std::string::npos)
      << preset;
  EXPECT_NE(preset.find("# Left out: ngspice gave up at 1e-15, 3.162e-15, 1e-14 A under every setting"),
            std::string::npos)
      << preset;
  const std::map<double, double> got = table(preset), shipped = table(slurp(kSource + "/models/sensors/aesim_pixel.toml"));
  int compared = 0;
  for (const auto& [current, period] : got) {
    const auto it = shipped.find(current);
    if (it == shipped.end() || current >= 1e-12) continue;
    EXPECT_NEAR(period / it->second, 1, 0.002) << current << " A";
    ++compared;
  }
  EXPECT_EQ(compared, 4);
}

TEST_F(FallbackTest, ACurrentNoSettingRunsIsLeftOutWithAWarningAndTheRestCalibrate) {
  const Outcome o = aesim("calibrate " + kShippedDeck + " --subckt aesim_pixel -o pixel.toml", stand_in(1e-13, true));
  ASSERT_EQ(o.status, 0) << o.err;
  EXPECT_NE(o.err.find("warning: ngspice gave up at 4 photocurrents (1e-15, 3.16e-15, 1e-14, 3.16e-14 A) under every "
                       "solver setting (doAnalyses: TRAN:  Timestep too small"),
            std::string::npos)
      << o.err;
  const std::string preset = slurp(dir_ / "pixel.toml");
  EXPECT_NE(preset.find("# Left out: ngspice gave up at 1e-15, 3.162e-15, 1e-14, 3.162e-14 A"), std::string::npos)
      << preset;
  EXPECT_NE(preset.find("ngspice gave up "), std::string::npos);
  EXPECT_GE(table(preset).size(), 9u);
  EXPECT_EQ(o.err.find("Reference value"), std::string::npos) << o.err;  // ngspice's progress is no reason
}

TEST_F(FallbackTest, WhenNoCurrentRunsItIsOneLineExitTwoAndNoPreset) {
  const Outcome o = aesim("calibrate " + kShippedDeck + " --subckt aesim_pixel -o pixel.toml", stand_in(1, true));
  EXPECT_EQ(o.status, 2) << o.err;
  const auto error = o.err.find("aesim: ");
  ASSERT_NE(error, std::string::npos) << o.err;
  EXPECT_EQ(o.err.find('\n', error), o.err.size() - 1) << o.err;
  EXPECT_NE(o.err.find("ngspice gave up at every one of the 13 photocurrents under every solver setting "
                       "(doAnalyses: TRAN:  Timestep too small",
                       error),
            std::string::npos)
      << o.err;
  EXPECT_FALSE(fs::exists(dir_ / "pixel.toml"));
}

}  // namespace
}  // namespace aesim
