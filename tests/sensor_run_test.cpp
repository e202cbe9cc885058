// run_sensor(): a whole run as one library call, the one `aesim run` and the Python module make.
// Its files are the program's own, byte for byte; it prints nothing and hands its warnings back.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/events/event_stream.hpp"
#include "aesim/sensor_run/sensor_run.hpp"
#include "support/csv_rows.hpp"
#include "support/temp_dir_test.hpp"

namespace aesim {
namespace {

using testing::csv_rows;
using testing::slurp;

const std::string kScenes = std::string(AESIM_SOURCE_DIR) + "/scenes";

class SensorRunTest : public testing::TempDirTest {};

// The same files as `aesim run` with the same spec, and the report's counts those of the files.
TEST_F(SensorRunTest, WritesTheProgramsFilesAndReportsTheirCounts) {
  RunSpec spec;
  spec.scene = kScenes + "/natural.pgm";
  spec.settings = {{"sim.duration", "300ms"}, {"pixel.c_int", "80fF"}};
  spec.csv = (dir_ / "lib.csv").string();
  spec.out = (dir_ / "lib.aedat").string();
  EventCollector collected;
  spec.stream = &collected;
  ::testing::internal::CaptureStdout();
  ::testing::internal::CaptureStderr();
  const RunReport report = run_sensor(spec);
  EXPECT_EQ(::testing::internal::GetCapturedStdout(), "");
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");

  const testing::Outcome o = aesim("run --scene " + spec.scene +
                                   " --duration 300ms --set pixel.c_int=80fF --csv cli.csv --out cli.aedat");
  ASSERT_EQ(o.status, 0) << o.err;
  EXPECT_EQ(slurp(dir_ / "lib.csv"), slurp(dir_ / "cli.csv"));
  EXPECT_EQ(slurp(dir_ / "lib.aedat"), slurp(dir_ / "cli.aedat"));
  const std::size_t rows = csv_rows(slurp(dir_ / "lib.csv")).size();
  EXPECT_GT(rows, 1000u);
  EXPECT_EQ(report.totals.delivered, rows);
  EXPECT_EQ(collected.events().size(), rows);
  EXPECT_EQ(report.summary["events_delivered"].get<double>(), static_cast<double>(rows));
  EXPECT_EQ(report.fidelity, Fidelity::Event);
  EXPECT_EQ(report.written, (std::vector<std::string>{spec.out, spec.csv}));
  EXPECT_EQ(report.scene_width, 64);
  EXPECT_TRUE(report.warnings.empty());
}

// A calibrated preset's range left by the scene's light: the warning comes back in the report, as
// the line the program prints after "aesim: warning: ", and nothing is printed.
TEST_F(SensorRunTest, WarningsComeBackInsteadOfBeingPrinted) {
  RunSpec spec;
  spec.sensor = "aesim_pixel";
  spec.scene = kScenes + "/gradient.pgm";
  spec.settings = {{"sim.duration", "10ms"}, {"pixel.i_max", "2nA"}};
  ::testing::internal::CaptureStderr();
  const RunReport report = run_sensor(spec);
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("calibrated from 1 fA to 1 nA"), std::string::npos) << report.warnings[0];
  EXPECT_TRUE(report.written.empty());

  const testing::Outcome o = aesim("run --sensor aesim_pixel --scene " + spec.scene +
                                   " --duration 10ms --set pixel.i_max=2nA --summary s.json");
  ASSERT_EQ(o.status, 0) << o.err;
  EXPECT_EQ(o.err, "aesim: warning: " + report.warnings[0] + "\n");
}

// Bad input throws before any file is made; the scene's frames may come from memory.
TEST_F(SensorRunTest, BadInputThrowsAndLeavesNothingAndFramesMayComeFromMemory) {
  RunSpec bad;
  bad.settings = {{"pixel.c_int", "-1fF"}};
  bad.csv = (dir_ / "never.csv").string();
  EXPECT_THROW(run_sensor(bad), InputError);
  EXPECT_FALSE(std::filesystem::exists(dir_ / "never.csv"));

  RunSpec memory;
  Image frame;
  frame.width = frame.height = 8;
  frame.pixels.assign(64, 0.5);
  memory.frames = {frame};
  memory.settings = {{"sim.duration", "100ms"}};
  const RunReport report = run_sensor(memory);
  EXPECT_EQ(report.scene_width, 8);
  EXPECT_FALSE(report.default_scene);
  // Uniform half light on the 64x64 aloha array: 4096 pixels at 5 Hz for 0.1 s fire 0 or 1 times
  // each with pixel.initial=random, so about half of them once.
  EXPECT_GT(report.totals.fired, 1500u);
  EXPECT_LT(report.totals.fired, 2600u);
}

}  // namespace
}  // namespace aesim
