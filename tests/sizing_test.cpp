// Sizing: the power model on hand-computed cases, the lux conversion, constraints, Pareto fronts,
// the recommendation, and the power of an ALOHA quadrant against the published chip.
#include <cmath>
#include <set>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "aesim/errors/input_error.hpp"
#include "aesim/summary/summary.hpp"
#include "aesim/scene/photocurrents.hpp"
#include "aesim/power/power_model.hpp"
#include "aesim/sizing/sizing_report.hpp"
#include "support/scenes.hpp"
#include "aesim/spec/sweep_spec.hpp"
#include "support/temp_dir_test.hpp"
#include "aesim/run/imager_simulation.hpp"

namespace aesim {
namespace {

TEST(PowerModel, HandComputedCase) {
  // 1000 firings of 100 fF over 1 V at 3.3 V: 1000 * (0.33 pJ + 1 pJ) = 1.33 nJ in the pixels.
  // 900 transactions carrying 4500 address ones: (4500 + 1800) * 0.5 pF * 3.3^2 = 34.3035 nJ on
  // the bus; 900 * 10 pJ = 9 nJ in the receiver. Over 2 s: 22.3168 nW dynamic; 1024 pixels at
  // 5.5 nW: 5.632 uW static.
  PowerParams p;
  PowerInputs in;
  in.c_int = 100e-15;
  in.dv_int = 1.0;
  in.firings = 1000;
  in.transactions = 900;
  in.address_ones = 4500;
  in.pixels = 1024;
  in.duration = 2.0;
  const PowerResult r = power(p, in);
  EXPECT_NEAR(r.pixel_energy, 1.33e-9, 1e-21);
  EXPECT_NEAR(r.bus_energy, 34.3035e-9, 1e-19);
  EXPECT_NEAR(r.receiver_energy, 9e-9, 1e-21);
  EXPECT_NEAR(r.static_power, 5.632e-6, 1e-18);
  EXPECT_NEAR(r.total_power, 5.632e-6 + (1.33e-9 + 34.3035e-9 + 9e-9) / 2, 1e-16);
  EXPECT_NEAR(r.energy_per_event, (1.33e-9 + 34.3035e-9 + 9e-9) / 1000, 1e-21);
}

TEST(PowerModel, LuxToPhotocurrent) {
  // 0.3 A/W x (683 lx / 683 lm/W = 1 W/m^2) x 900 um^2 x 0.3 = 81 pA.
  EXPECT_NEAR(photocurrent_from_lux(683, 0.3, 683, 900e-12, 0.3), 81e-12, 1e-24);
  SensorConfig c;
  c.light.lux = 10;
  EXPECT_NEAR(c.resolved().pixel.i_max, 0.3 * (10.0 / 683) * 900e-12 * 0.3, 1e-25);
  c.light.lux = 0;
  EXPECT_EQ(c.resolved().pixel.i_max, c.pixel.i_max);  // no illuminance: i_max as set
}

TEST(PowerModel, AnAlohaQuadrantDrawsAboutSixMicrowattsAtTheChipsEventRate) {
  // The ALOHA chip: 6 uW per 32x32 quadrant at about 7,700 events/s. One quadrant, uniform light
  // of 0.752 pA (7.52 Hz per pixel: 7,700 events/s), the aloha preset's power parameters.
  SensorConfig c = load_sensor("aloha");
  c.array.rows = c.array.cols = 32;
  c.pixel.i_max = 0.752e-12;
  c.sim.duration = 4.0;
  const Photocurrents photocurrents(testing::make_scene({testing::make_image(32, 32, [](int, int) { return 1.0; })}),
                                    c.pixel);
  const SimulationResult r = simulate(c.resolved(), photocurrents);
  const nlohmann::json s = make_summary(c, r.log, r.facts);
  EXPECT_NEAR(s["events_fired"].get<double>() / 4.0, 7700, 100);
  EXPECT_NEAR(s["power_per_tile_w"].get<double>(), 6e-6, 0.6e-6);
  EXPECT_GT(s["energy_per_event_j"].get<double>(), 0.0);
}

DesignPoint point(const char* label, double power, double psnr, double loss, double latency = 0) {
  return {label, {{"power_w", power}, {"psnr_db", psnr}, {"collision_fraction", loss}, {"latency_p99_s", latency}}};
}

TEST(SizingReport, ConstraintsFrontsAndRecommendationOnAHandMadeTable) {
  const std::vector<DesignPoint> points = {
      point("a", 10e-6, 30, 0.01, 1e-3),  // feasible, dominated by b on power and quality
      point("b", 8e-6, 32, 0.02, 2e-3),   // feasible, on both fronts
      point("c", 5e-6, 26, 0.04, 3e-3),   // feasible, cheapest but slowest, on both fronts
      point("d", 3e-6, 40, 0.20, 1e-4),   // violates the loss constraint
      point("e", 12e-6, 20, 0.00, 1e-4),  // violates PSNR and power
  };
  const std::vector<Constraint> constraints = {parse_constraint("collision_fraction", "<= 0.05"),
                                               parse_constraint("psnr_db", ">= 25"),
                                               parse_constraint("power_w", "<= 11uW")};
  EXPECT_DOUBLE_EQ(constraints[2].bound, 11e-6);
  const SizingAnalysis a = analyse_sizing(points, constraints);
  EXPECT_EQ(a.feasible, (std::vector<bool>{true, true, true, false, false}));
  EXPECT_EQ(a.front_power_quality, (std::vector<std::size_t>{2, 1}));
  EXPECT_EQ(a.front_power_latency, (std::vector<std::size_t>{2, 1, 0}));
  // Worst relative margins: a min(0.8, 0.2, 0.09) = 0.09; b min(0.6, 0.28, 0.27) = 0.27;
  // c min(0.2, 0.04, 0.55) = 0.04. The most robust is b.
  EXPECT_EQ(a.recommended, 1);
  ASSERT_EQ(a.margins.size(), 3u);
  EXPECT_NEAR(a.margins[1], 0.28, 1e-12);
  const std::string report = sizing_report(points, constraints, a);
  EXPECT_NE(report.find("**b**"), std::string::npos);
}

TEST(SizingReport, WithNothingFeasibleNamesTheBindingConstraintAndTheClosestDesign) {
  const std::vector<DesignPoint> points = {
      point("p", 30e-6, 30, 0.01),  // power 200 % over
      point("q", 20e-6, 24, 0.02),  // power 100 % over: the least negative worst margin
      point("r", 40e-6, 17, 0.06),  // over on everything
  };
  const std::vector<Constraint> constraints = {parse_constraint("collision_fraction", "<= 0.05"),
                                               parse_constraint("psnr_db", ">= 18"),
                                               parse_constraint("power_w", "<= 10uW")};
  const SizingAnalysis a = analyse_sizing(points, constraints);
  EXPECT_EQ(a.recommended, -1);
  EXPECT_EQ(a.closest, 1);
  EXPECT_EQ(a.meeting, (std::vector<std::size_t>{2, 2, 0}));
  ASSERT_EQ(a.closest_margins.size(), 3u);
  EXPECT_NEAR(a.closest_margins[2], -1.0, 1e-12);
  const std::string report = sizing_report(points, constraints, a);
  EXPECT_NE(report.find("No design point meets every constraint."), std::string::npos);
  EXPECT_NE(report.find("`power_w`: met by 0 of 3 designs"), std::string::npos);
  EXPECT_NE(report.find("Closest: **q**"), std::string::npos);
  EXPECT_NE(report.find("margin -100 % (violated)"), std::string::npos);
}

TEST(SizingReport, WorstCaseAcrossConditions) {
  const std::vector<DesignPoint> merged =
      worst_case_by_label({point("x", 5e-6, 30, 0.01), point("x", 7e-6, 22, 0.03), point("y", 1e-6, 40, 0.0)});
  ASSERT_EQ(merged.size(), 2u);
  EXPECT_DOUBLE_EQ(merged[0].values.at("power_w"), 7e-6);
  EXPECT_DOUBLE_EQ(merged[0].values.at("psnr_db"), 22);
  EXPECT_DOUBLE_EQ(merged[0].values.at("collision_fraction"), 0.03);
}

TEST(SizingReport, MalformedConstraintsNameTheColumn) {
  for (const char* bad : {"10uW", "<= lots", "=> 3", ""}) {
    try {
      parse_constraint("power_w", bad);
      FAIL() << bad;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("power_w"), std::string::npos) << e.what();
    }
  }
}

class SweepSamplingTest : public testing::TempDirTest {};

TEST_F(SweepSamplingTest, SeededSamplesAreReproducibleAndDrawnFromTheAxes) {
  const std::string spec = write("s.toml", R"(
[[group]]
samples = 12
seed = 5
"pixel.c_int" = ["25fF", "50fF", "100fF"]
"bus.t_event" = { from = "100ns", to = "10us", points = 5, scale = "log" }
)");
  const SweepSpec a = load_sweep_spec(spec);
  const SweepSpec b = load_sweep_spec(spec);
  ASSERT_EQ(a.points.size(), 12u);
  std::set<std::string> c_ints;
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    EXPECT_EQ(a.points[i].sets, b.points[i].sets);
    c_ints.insert(a.points[i].sets[1].second);
  }
  EXPECT_GT(c_ints.size(), 1u);  // really drawn, not one value
  for (const std::string& v : c_ints) EXPECT_TRUE(v == "25fF" || v == "50fF" || v == "100fF") << v;
  EXPECT_THROW(load_sweep_spec(write("bad.toml", "[[group]]\nsamples = 0\n\"pixel.c_int\" = [\"1fF\"]\n")), InputError);
  EXPECT_THROW(load_sweep_spec(write("bad2.toml", "[constraints]\npower_w = \"10uW\"\n[[group]]\nname = \"x\"\n")),
               InputError);
}

}  // namespace
}  // namespace aesim
