// SI values, presets, --set overrides and validation (docs/reference.md section 3).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "aesim/errors/input_error.hpp"
#include "aesim/config/sensor_config.hpp"
#include "aesim/units/si_units.hpp"
#include "support/temp_dir_test.hpp"

namespace aesim {
namespace {

TEST(SiUnits, PrefixesAndUnits) {
  EXPECT_DOUBLE_EQ(parse_si("100fF", "F", "k"), 100e-15);
  EXPECT_DOUBLE_EQ(parse_si("1 pA", "A", "k"), 1e-12);
  EXPECT_DOUBLE_EQ(parse_si("2us", "s", "k"), 2e-6);
  EXPECT_DOUBLE_EQ(parse_si("2\xC2\xB5s", "s", "k"), 2e-6);
  EXPECT_DOUBLE_EQ(parse_si("5ms", "s", "k"), 5e-3);
  EXPECT_DOUBLE_EQ(parse_si("50MHz", "Hz", "k"), 50e6);
  EXPECT_DOUBLE_EQ(parse_si("1e-13", "F", "k"), 1e-13);
  EXPECT_DOUBLE_EQ(parse_si("3k", "", "k"), 3000);
  EXPECT_DOUBLE_EQ(parse_si("0.5V", "V", "k"), 0.5);
}

TEST(SiUnits, RejectsWrongUnitsAndGarbageNamingTheKey) {
  for (const char* bad : {"100pA", "abc", "", "1 furlong", "1e999", "nan", "10 F F"}) {
    try {
      parse_si(bad, "F", "pixel.c_int");
      FAIL() << "accepted '" << bad << "'";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("pixel.c_int"), std::string::npos) << e.what();
    }
  }
}

// A unit in the wrong case is not guessed at ("mhz" could be milli or mega); the message says so.
TEST(SiUnits, AUnitInAnotherCaseIsRefusedSayingUnitsAreCaseSensitive) {
  for (const char* bad : {"100mhz", "100MHZ", "10 KHz", "5hz"}) {
    try {
      parse_si(bad, "Hz", "receiver.clock");
      FAIL() << "accepted '" << bad << "'";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("case-sensitive: Hz, with m milli, M mega"), std::string::npos) << e.what();
    }
  }
  try {
    parse_si("100 furlong", "Hz", "receiver.clock");
    FAIL() << "accepted '100 furlong'";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).find("case-sensitive"), std::string::npos) << e.what();
  }
}

TEST(SensorConfig, AlohaPresetHasTheSpecConstants) {
  const SensorConfig c = load_sensor("aloha");
  EXPECT_DOUBLE_EQ(c.pixel.c_int, 100e-15);
  EXPECT_DOUBLE_EQ(c.pixel.dv_int, 1.0);
  EXPECT_DOUBLE_EQ(c.pixel.i_max, 1e-12);
  EXPECT_EQ(c.array.rows, 64);
  EXPECT_EQ(c.array.cols, 64);
  EXPECT_EQ(c.array.tile_rows, 32);
  EXPECT_EQ(c.array.tile_cols, 32);
  // f_max = i_max / (c_int * dv_int) = 10 Hz
  EXPECT_NEAR(c.pixel.i_max / (c.pixel.c_int * c.pixel.dv_int), 10.0, 1e-9);
  EXPECT_NO_THROW(c.validate());
}

TEST(SensorConfig, SetAcceptsEveryKeyAndEchoesIt) {
  SensorConfig c;
  c.set("pixel.c_int", "50fF");
  c.set("bus.access", "ideal");
  c.set("pixel.shot_noise", "on");
  c.set("sim.seed", "12345");
  c.set("array.rows", "128");
  const nlohmann::json j = c.to_json();
  EXPECT_DOUBLE_EQ(j["pixel"]["c_int"].get<double>(), 50e-15);
  EXPECT_EQ(j["bus"]["access"], "ideal");
  EXPECT_EQ(j["pixel"]["shot_noise"], true);
  EXPECT_EQ(j["sim"]["seed"], 12345);
  EXPECT_EQ(j["array"]["rows"], 128);
  std::size_t keys = 0;
  for (const auto& section : j) keys += section.size();
  EXPECT_EQ(keys, SensorConfig::keys().size());
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SensorConfig, BadKeysValuesAndPhysicsNameTheKey) {
  SensorConfig c;
  EXPECT_NE(error_of([&] { c.set("pixel.c_intt", "1fF"); }).find("pixel.c_intt"), std::string::npos);
  EXPECT_NE(error_of([&] { c.set("array.rows", "12.5"); }).find("array.rows"), std::string::npos);
  EXPECT_NE(error_of([&] { c.set("bus.access", "token-ring"); }).find("bus.access"), std::string::npos);
  EXPECT_NE(error_of([&] { c.set("pixel.shot_noise", "maybe"); }).find("pixel.shot_noise"), std::string::npos);

  SensorConfig negative;
  negative.set("pixel.c_int", "-100fF");
  EXPECT_NE(error_of([&] { negative.validate(); }).find("pixel.c_int"), std::string::npos);
  SensorConfig zero_swing;
  zero_swing.set("pixel.dv_int", "0V");
  EXPECT_NE(error_of([&] { zero_swing.validate(); }).find("pixel.dv_int"), std::string::npos);
  SensorConfig big_tile;
  big_tile.set("array.tile_rows", "65");
  EXPECT_NE(error_of([&] { big_tile.validate(); }).find("array.tile_rows"), std::string::npos);
  // A smaller array alone keeps the preset's 32-pixel tiles: the message gives both sizes.
  SensorConfig small_array;
  small_array.set("array.rows", "16");
  EXPECT_NE(error_of([&] { small_array.validate(); }).find("32 rows a tile must be from 1 to array.rows (16): set array.tile_rows too"),
            std::string::npos);
  // A tile of no columns was set, not left over: no advice to set it.
  SensorConfig no_columns;
  no_columns.set("array.tile_cols", "0");
  const std::string no_columns_error = error_of([&] { no_columns.validate(); });
  EXPECT_NE(no_columns_error.find("0 columns a tile must be from 1 to array.cols (64)"), std::string::npos) << no_columns_error;
  EXPECT_EQ(no_columns_error.find("too"), std::string::npos) << no_columns_error;
  SensorConfig long_run;
  long_run.set("sim.duration", "1e7s");
  EXPECT_NE(error_of([&] { long_run.validate(); }).find("sim.duration"), std::string::npos);
}

// A file that names its base is read over that preset: what it leaves out is the base's (here
// aloha's mismatch, reset time and array), a base named by a relative path is found beside the
// file, and a loop of bases is refused. A file without one keeps SensorConfig's own values (an
// ideal pixel: no mismatch, no reset time), as the key reference's "built in" says.
using SensorPresetFiles = testing::TempDirTest;
TEST_F(SensorPresetFiles, AFileIsReadOverTheBaseItNames) {
  const SensorConfig aloha = load_sensor("aloha");
  ASSERT_EQ(aloha.pixel.mismatch, 0.02);
  write("mine.toml", "base = \"aloha\"\n[pixel]\nc_int = \"40fF\"\n");
  std::filesystem::create_directories(dir_ / "runs");
  write("runs/small.toml", "base = \"../mine.toml\"\n[array]\nrows = 32\ntile_rows = 16\n");
  const SensorConfig small = load_sensor((dir_ / "runs/small.toml").string());
  EXPECT_DOUBLE_EQ(small.pixel.c_int, 40e-15);
  EXPECT_EQ(small.array.rows, 32);
  EXPECT_EQ(small.array.tile_rows, 16);
  EXPECT_EQ(small.pixel.mismatch, aloha.pixel.mismatch);
  EXPECT_EQ(small.pixel.t_reset, aloha.pixel.t_reset);
  EXPECT_EQ(small.pixel.i_dark, aloha.pixel.i_dark);
  EXPECT_EQ(small.array.cols, aloha.array.cols);
  EXPECT_EQ(small.bus.t_event, aloha.bus.t_event);
  const SensorConfig bare = load_sensor(write("bare.toml", "[pixel]\nc_int = \"40fF\"\n"));
  EXPECT_EQ(bare.pixel.mismatch, SensorConfig{}.pixel.mismatch);
  EXPECT_EQ(bare.pixel.t_reset, SensorConfig{}.pixel.t_reset);
  write("a.toml", "base = \"b.toml\"\n");
  write("b.toml", "base = \"a.toml\"\n");
  EXPECT_NE(error_of([&] { load_sensor((dir_ / "a.toml").string()); }).find("a loop"), std::string::npos);
  EXPECT_NE(error_of([&] { load_sensor(write("c.toml", "base = \"no_such_preset\"\n")); }).find("unknown sensor 'no_such_preset'"),
            std::string::npos);
  // The key a user reaches for first is named in the refusal.
  EXPECT_NE(error_of([&] { load_sensor(write("p.toml", "preset = \"aloha\"\n")); }).find("base = \"NAME\""),
            std::string::npos);
}

TEST(SensorConfig, UnknownPresetIsAnInputError) {
  EXPECT_THROW(load_sensor("no_such_sensor"), InputError);
  EXPECT_THROW(load_sensor("/nonexistent/x.toml"), InputError);
}

}  // namespace
}  // namespace aesim
