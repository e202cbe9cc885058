// The aesim program as a user meets it: default run, outputs, bad input, reproducibility.
#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <cmath>
#include <map>
#include <set>
#include <tuple>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "aesim/config/sensor_config.hpp"
#include "aesim/scene/netpbm.hpp"
#include "aesim/version.hpp"
#include "support/csv_rows.hpp"
#include "support/temp_dir_test.hpp"

namespace aesim {
namespace {
namespace fs = std::filesystem;

using testing::Outcome;
using testing::slurp;

class CliTest : public testing::TempDirTest {
 protected:
  std::size_t files_in_dir() const {
    std::size_t n = 0;
    for (const auto& e : fs::recursive_directory_iterator(dir_)) n += e.is_regular_file() ? 1 : 0;
    return n;
  }
};

const std::string kScenes = std::string(AESIM_SOURCE_DIR) + "/scenes";

TEST_F(CliTest, DefaultRunWritesEveryOutputUnderOut) {
  const Outcome o = aesim("run");
  ASSERT_EQ(o.status, 0) << o.err;
  for (const char* f : {"events.aedat", "events.csv", "recon.png", "summary.json"}) {
    EXPECT_TRUE(fs::is_regular_file(dir_ / "out" / f)) << f;
  }
  EXPECT_NE(o.out.find("fired"), std::string::npos);
  EXPECT_NE(o.out.find("out/events.aedat"), std::string::npos);
  EXPECT_NE(o.out.find("sizing: power "), std::string::npos) << o.out;
  const auto summary = nlohmann::json::parse(slurp(dir_ / "out" / "summary.json"));
  for (const char* key : {"events_fired", "events_delivered", "events_collided", "events_ghost", "events_dropped",
                          "offered_load", "throughput", "tau_s", "sim_time_s", "wall_time_s", "fidelity", "sensor"}) {
    EXPECT_TRUE(summary.contains(key)) << key;
  }
  EXPECT_GT(summary["events_fired"].get<double>(), 0);
  // The aloha bus with contention detection: every fired event is delivered or lost.
  EXPECT_EQ(summary["events_fired"].get<double>(),
            summary["events_delivered"].get<double>() + summary["events_collided"].get<double>());
  EXPECT_EQ(summary["events_ghost"], 0);
  EXPECT_EQ(summary["fidelity"], "event");
  EXPECT_EQ(summary["sensor"]["pixel"]["c_int"].get<double>(), 100e-15);
  // CSV rows match the summary's count, and the header is the reference's (docs/reference.md).
  const std::string csv = slurp(dir_ / "out" / "events.csv");
  EXPECT_EQ(csv.rfind("t_us,x,y,tile,flags\n", 0), 0u);
  EXPECT_EQ(static_cast<double>(std::count(csv.begin(), csv.end(), '\n') - 1),
            summary["events_delivered"].get<double>());
}

// A calibrated preset is only the circuit within the currents it was measured at: a run whose
// light leaves them says how many pixels, which way and how far, counted here from the scene file
// itself; a run inside them says nothing.
TEST_F(CliTest, ARunOutsideTheCalibratedRangeSaysWhereOnce) {
  // scenes/gradient.pgm: 64x64, 16-bit big-endian values after "P5\n64 64\n65535\n".
  const std::string pgm = slurp(kScenes + "/gradient.pgm");
  const std::string header = "P5\n64 64\n65535\n";
  ASSERT_EQ(pgm.compare(0, header.size(), header), 0);
  // aesim_pixel's table runs from 1 fA to 1 nA; at i_max = 2 nA a value v gives v * 2 nA.
  std::size_t below = 0, above = 0;
  for (std::size_t i = header.size(); i + 1 < pgm.size(); i += 2) {
    const unsigned raw = (static_cast<unsigned char>(pgm[i]) << 8) | static_cast<unsigned char>(pgm[i + 1]);
    const double current = 2e-9 * raw / 65535.0;
    below += current < 1e-15;
    above += current > 1e-9;
  }
  ASSERT_GT(below, 0u);
  ASSERT_GT(above, 0u);
  const Outcome o = aesim("run --sensor aesim_pixel --scene " + kScenes +
                          "/gradient.pgm --duration 10ms --set pixel.i_max=2nA --summary s.json");
  ASSERT_EQ(o.status, 0) << o.err;
  const std::string want = fmt::format("of the scene's 4096 pixels, {} below it, down to 0 A; {} above it, up to 2 nA",
                                       below, above);
  EXPECT_NE(o.err.find(want), std::string::npos) << o.err;
  EXPECT_NE(o.err.find("calibrated from 1 fA to 1 nA"), std::string::npos) << o.err;
  EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << o.err;  // one line
  // The uniform scene at full light, 1 pA: inside the table, no word.
  const Outcome inside = aesim("run --sensor aesim_pixel --scene " + kScenes + "/uniform.pgm --duration 10ms");
  ASSERT_EQ(inside.status, 0) << inside.err;
  EXPECT_EQ(inside.err.find("calibrated from"), std::string::npos) << inside.err;
}

TEST_F(CliTest, SameSeedSameBytesOtherSeedOtherBytes) {
  const std::string common = "--scene " + kScenes +
                             "/moving_disc --duration 1s --set pixel.shot_noise=true "
                             "--set pixel.initial=random ";
  auto run = [&](const std::string& tag, int seed) {
    const Outcome o = aesim("run " + common + "--set sim.seed=" + std::to_string(seed) + " --out " + tag +
                            ".aedat --csv " + tag + ".csv --recon " + tag + ".pgm");
    EXPECT_EQ(o.status, 0) << o.err;
  };
  run("a", 3);
  run("b", 3);
  run("c", 4);
  for (const char* ext : {".aedat", ".csv", ".pgm"}) {
    EXPECT_EQ(slurp(dir_ / (std::string("a") + ext)), slurp(dir_ / (std::string("b") + ext))) << ext;
  }
  EXPECT_NE(slurp(dir_ / "a.aedat"), slurp(dir_ / "c.aedat"));
}

// A file's format is told by its extension in either case: a camera's IMG_0001.JPG is a JPEG,
// RUN.AEDAT4 an AEDAT 4.0 file, A.PNG a PNG image; the same bytes as the lower-case names give.
TEST_F(CliTest, ExtensionsInUpperCaseNameTheSameFormats) {
  write("A.PGM", slurp(kScenes + "/letters/A.pgm"));
  const Outcome upper = aesim("run --scene A.PGM --duration 200ms --out RUN.AEDAT4 --recon R.PNG");
  ASSERT_EQ(upper.status, 0) << upper.err;
  const Outcome lower = aesim("run --scene " + kScenes + "/letters/A.pgm --duration 200ms --out run.aedat4 --recon r.png");
  ASSERT_EQ(lower.status, 0) << lower.err;
  EXPECT_EQ(slurp(dir_ / "RUN.AEDAT4"), slurp(dir_ / "run.aedat4"));
  EXPECT_EQ(slurp(dir_ / "R.PNG"), slurp(dir_ / "r.png"));
  const Outcome info = aesim("info RUN.AEDAT4");
  EXPECT_EQ(info.status, 0) << info.err;
}

TEST_F(CliTest, BadInputIsOneLineExitTwoAndNoOutput) {
  const std::string truncated = write("truncated.pgm", std::string("P5\n8 8\n255\n") + std::string(20, '\x80'));
  const std::string malformed = write("malformed.pgm", "P7\nhello\n");
  const std::string outputs = " --out o.aedat --csv o.csv --summary o.json --recon o.png";
  const std::pair<std::string, std::string> cases[] = {
      {"run --scene " + truncated, "truncated"},
      {"run --scene " + malformed, "not a Netpbm image"},
      {"run --scene " + write("t.pfm", "Pf\n2 2\n-1.0\nabc"), "truncated"},
      {"run --set pixel.c_intt=1fF", "pixel.c_intt"},
      {"run --set pixel.c_int=abc", "pixel.c_int"},
      {"run --set pixel.c_int=100pA", "pixel.c_int"},
      {"run --set pixel.c_int=-100fF", "pixel.c_int"},
      {"run --set pixel.dv_int=0", "pixel.dv_int"},
      {"run --set array.rows=0", "array.rows"},
      {"run --set sim.duration=-1s", "sim.duration"},
      {"run --set novalue", "--set"},
      {"run --scene /no/such/scene.pgm", "not found"},
      {"run --sensor no_such_sensor", "unknown sensor"},
      {"run --set sim.fidelity=warp", "sim.fidelity"},
      {"run --set sim.fidelity=fixed_step --set sim.step=0", "sim.step"},
      {"run --set sim.fidelity=event --vcd w.vcd", "--vcd"},
      {"run --set sim.fidelity=cycle --set bus.access=arbitrated", "bus.access"},
      {"run --set sim.fidelity=cycle --vcd w.vcd --vcd-from 2s --vcd-to 1s", "--vcd-from"},
      {"run --frobnicate", "frobnicate"},
      {"run --recon o.jpg", "--recon"},
      {"run --sensor " + write("bad.toml", "[pixel\nc_int = "), "malformed TOML"},
      {"run --sensor " + write("unit.toml", "[pixel]\nc_int = \"1V\"\n"), "pixel.c_int"},
  };
  for (const auto& [args, needle] : cases) {
    const Outcome o = aesim(args + (args.find("--recon") == std::string::npos ? outputs : ""));
    EXPECT_EQ(o.status, 2) << args << ": " << o.err;
    EXPECT_NE(o.err.find(needle), std::string::npos) << args << ": " << o.err;
    EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << args << ": " << o.err;
    EXPECT_EQ(files_in_dir(), 5u) << args << " left files behind";  // only the inputs written above
    EXPECT_FALSE(fs::exists(dir_ / "out")) << args;
  }
}

TEST_F(CliTest, ReconReproducesTheCheckerboardAndInfoCountsEvents) {
  ASSERT_EQ(aesim("run --scene " + kScenes + "/checkerboard.pgm --duration 3s --out e.aedat --summary s.json").status, 0);
  const Outcome recon = aesim("recon e.aedat --mode histogram -o r.pgm");
  ASSERT_EQ(recon.status, 0) << recon.err;
  const Image img = read_pnm((dir_ / "r.pgm").string());
  ASSERT_EQ(img.width, 64);
  // Lit squares fire ~30 times in 3 s, dark ones (1 fA) essentially never.
  for (int y = 4; y < 64; y += 8) {
    for (int x = 4; x < 64; x += 8) {
      const bool lit = ((x / 8) + (y / 8)) % 2 == 0;
      if (lit) EXPECT_GT(img.at(x, y), 0.85) << x << "," << y;
      else EXPECT_LT(img.at(x, y), 0.1) << x << "," << y;
    }
  }
  const Outcome interval = aesim("recon e.aedat --mode interval --events 5000 -o i.png");
  EXPECT_EQ(interval.status, 0) << interval.err;
  EXPECT_NE(interval.out.find("5000 of"), std::string::npos);

  const auto summary = nlohmann::json::parse(slurp(dir_ / "s.json"));
  const Outcome info = aesim("info e.aedat");
  ASSERT_EQ(info.status, 0) << info.err;
  EXPECT_NE(info.out.find(std::to_string(summary["events_delivered"].get<long long>()) + " events"), std::string::npos)
      << info.out;
  EXPECT_NE(info.out.find("tile 3:"), std::string::npos);
}

TEST_F(CliTest, TruthHasEveryFiredEventAndVcdHoldsTheWindow) {
  const Outcome o = aesim("run --set sim.fidelity=cycle --set receiver.clock=200kHz --duration 1s --truth t.csv "
                          "--summary s.json --vcd w.vcd --vcd-from 10ms --vcd-to 20ms");
  ASSERT_EQ(o.status, 0) << o.err;
  const auto summary = nlohmann::json::parse(slurp(dir_ / "s.json"));
  const std::string truth = slurp(dir_ / "t.csv");
  EXPECT_EQ(truth.rfind("x,y,tile,t_fire_us,fate,t_deliver_us,latency_us\n", 0), 0u);
  std::istringstream lines(truth);
  std::string line;
  std::getline(lines, line);
  std::map<std::string, double> fates;
  double rows = 0;
  while (std::getline(lines, line)) {
    ++rows;
    const auto a = line.find(',', line.find(',', line.find(',', line.find(',') + 1) + 1) + 1);
    fates[line.substr(a + 1, line.find(',', a + 1) - a - 1)] += 1;
  }
  EXPECT_EQ(rows, summary["events_fired"].get<double>());
  EXPECT_EQ(fates["delivered"], summary["events_delivered"].get<double>());
  EXPECT_EQ(fates["collided"], summary["events_collided"].get<double>());
  EXPECT_GT(fates["collided"], 0);  // a 200 kHz receiver makes tau ~27 us: collisions happen

  const std::string vcd = slurp(dir_ / "w.vcd");
  EXPECT_NE(vcd.find("$timescale 1ps $end"), std::string::npos);
  EXPECT_NE(vcd.find("$var wire 10 $ addr $end"), std::string::npos);
  EXPECT_NE(vcd.find("$scope module tile3 $end"), std::string::npos);
  // Every timestamp lies in the window, and there is activity in it.
  std::istringstream v(vcd.substr(vcd.find("$enddefinitions")));
  std::size_t stamps = 0;
  while (std::getline(v, line)) {
    if (line.empty() || line[0] != '#') continue;
    const double t = std::stod(line.substr(1));
    EXPECT_GE(t, 10e9);
    EXPECT_LE(t, 20e9);
    ++stamps;
  }
  EXPECT_GT(stamps, 20u);
}

// The stamp convention (docs/modelling_choices.md): at the cycle fidelity an event's stamp is the ticks completed by its
// latch edge, floor(t_deliver / tick). Every delivered row of the truth file must appear in the
// events file with exactly that t_us (1 us tick, 50 clock cycles: 1 latch in 50 falls on a tick
// edge, the case an off-by-one stamp gets wrong).
TEST_F(CliTest, CycleStampsAreTheLatchEdgesTickInBothFiles) {
  const Outcome o = aesim("run --set sim.fidelity=cycle --duration 300ms --csv e.csv --truth t.csv");
  ASSERT_EQ(o.status, 0) << o.err;
  using Key = std::tuple<long long, int, int, int>;  // t_us, x, y, tile
  std::multiset<Key> from_truth, from_events;
  std::istringstream truth(slurp(dir_ / "t.csv"));
  std::string line;
  std::getline(truth, line);
  std::size_t on_edge = 0;
  while (std::getline(truth, line)) {
    std::istringstream row(line);
    std::string x, y, tile, fired, fate, delivered;
    std::getline(row, x, ',');
    std::getline(row, y, ',');
    std::getline(row, tile, ',');
    std::getline(row, fired, ',');
    std::getline(row, fate, ',');
    std::getline(row, delivered, ',');
    if (fate != "delivered") continue;
    const double t_us = std::stod(delivered);
    const double nearest = std::nearbyint(t_us);
    on_edge += std::fabs(t_us - nearest) < 1e-6 ? 1 : 0;
    const auto stamp = static_cast<long long>(std::fabs(t_us - nearest) < 1e-6 ? nearest : std::floor(t_us));
    from_truth.insert({stamp, std::stoi(x), std::stoi(y), std::stoi(tile)});
  }
  for (const std::vector<std::string>& row : testing::csv_rows(slurp(dir_ / "e.csv"))) {
    from_events.insert({std::stoll(row.at(0)), std::stoi(row.at(1)), std::stoi(row.at(2)), std::stoi(row.at(3))});
  }
  ASSERT_GT(from_events.size(), 1000u);
  EXPECT_GT(on_edge, 0u);  // the stimulus holds the case that matters
  EXPECT_TRUE(from_truth == from_events) << from_truth.size() << " delivered in the truth file, "
                                         << from_events.size() << " events";
}

TEST_F(CliTest, RtlReceiverInTheLoopTracesItsInternalsBesideTheBus) {
  const Outcome o = aesim("run --set receiver.model=rtl --duration 500ms --vcd w.vcd --vcd-from 50us --vcd-to 300us "
                          "--summary s.json --csv rtl.csv");
  ASSERT_EQ(o.status, 0) << o.err;
  EXPECT_NE(o.out.find("fidelity cycle (chosen by auto)"), std::string::npos) << o.out;
  const auto summary = nlohmann::json::parse(slurp(dir_ / "s.json"));
  EXPECT_EQ(summary["scoreboard_mismatches"], 0);
  EXPECT_EQ(summary["scoreboard_beats"], summary["events_delivered"]);
  for (int t = 0; t < 4; ++t) {
    const std::string rtl = slurp(dir_ / ("w.tile" + std::to_string(t) + ".rtl.vcd"));
    EXPECT_NE(rtl.find("$var wire  1 "), std::string::npos) << t;
    EXPECT_NE(rtl.find(" state_q "), std::string::npos) << t;  // an internal register
    EXPECT_NE(rtl.find(" req_s3 "), std::string::npos) << t;   // the synchronizer
    // Scope names without dots (GTKWave reads dots as another level of hierarchy).
    EXPECT_NE(rtl.find("$scope module imager_tile" + std::to_string(t) + "_receiver_rtl $end"), std::string::npos) << t;
    for (std::size_t at = rtl.find("$scope"); at != std::string::npos; at = rtl.find("$scope", at + 1)) {
      EXPECT_EQ(rtl.substr(at, rtl.find("$end", at) - at).find('.'), std::string::npos) << t;
    }
  }
  // The reference receiver gives the same events.
  ASSERT_EQ(aesim("run --set receiver.model=reference --set sim.fidelity=cycle --duration 500ms --csv ref.csv").status, 0);
  EXPECT_EQ(slurp(dir_ / "rtl.csv"), slurp(dir_ / "ref.csv"));
  // Nothing temporary is left behind.
  for (const auto& e : fs::directory_iterator(dir_)) EXPECT_EQ(e.path().string().find(".tmp."), std::string::npos);
}

TEST_F(CliTest, ReceiverLimitsAreInputErrors) {
  EXPECT_EQ(aesim("run --set sim.fidelity=cycle --set receiver.fifo_depth=100 --summary s.json").status, 2);
  EXPECT_EQ(aesim("run --set receiver.model=verilog --summary s.json").status, 2);
  EXPECT_EQ(aesim("run --set receiver.full_policy=spill --summary s.json").status, 2);
  EXPECT_EQ(aesim("run --set receiver.model=rtl --set sim.fidelity=event --summary s.json").status, 2);
  EXPECT_FALSE(fs::exists(dir_ / "s.json"));
}

TEST_F(CliTest, CompareMeasuresEveryRungAgainstTheEventRung) {
  const Outcome o = aesim("compare --duration 200ms --steps 1ms -o ladder.csv");
  ASSERT_EQ(o.status, 0) << o.err;
  std::istringstream csv(slurp(dir_ / "ladder.csv"));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line.rfind("scene,rung,step_s,wall_time_s,wall_per_sim_s,events_fired,count_error,rms_time_error_s", 0), 0u);
  std::map<std::string, std::vector<std::string>> rows;
  while (std::getline(csv, line)) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string c;
    while (std::getline(ss, c, ',')) cells.push_back(c);
    rows[cells[1]] = cells;
  }
  ASSERT_EQ(rows.size(), 6u);  // queue, event, pixel_processes, cycle, cycle_rtl, fixed_step
  for (const char* exact : {"event", "pixel_processes", "cycle", "cycle_rtl"}) {
    EXPECT_EQ(std::stod(rows[exact][6]), 0.0) << exact;  // count error
    EXPECT_EQ(std::stod(rows[exact][7]), 0.0) << exact;  // firing-time error
  }
  EXPECT_GT(std::stod(rows["fixed_step"][7]), 1e-4);  // a 1 ms step is off by a good part of it
  EXPECT_GT(std::stod(rows["queue"][6]), 0.0);

  const Outcome coarse = aesim("run --set sim.fidelity=fixed_step --set sim.step=50ms --set pixel.t_reset=0 "
                               "--set pixel.i_max=1nA --duration 1s --summary s.json");
  ASSERT_EQ(coarse.status, 0) << coarse.err;
  EXPECT_NE(coarse.err.find("coarser than some pixels' integration time"), std::string::npos) << coarse.err;
}

// -o names the event file of run and emulate as it names recon's and sweep's output: the same
// bytes as --out.
TEST_F(CliTest, DashOIsTheOutOfRunAndEmulate) {
  for (const std::string& command : {"emulate " + kScenes + "/letters/O.pgm", std::string("run --duration 50ms --summary s.json")}) {
    ASSERT_EQ(aesim(command + " --out long.aedat").status, 0) << command;
    const Outcome o = aesim(command + " -o short.aedat");
    ASSERT_EQ(o.status, 0) << command << ": " << o.err;
    const std::string long_form = slurp(dir_ / "long.aedat");
    EXPECT_GT(long_form.size(), 1000u) << command;
    EXPECT_EQ(slurp(dir_ / "short.aedat"), long_form) << command;
  }
}

TEST_F(CliTest, EmulateThenClassifyRecognisesTheLetter) {
  const Outcome e = aesim("emulate " + kScenes + "/letters/O.pgm --queue q.txt --out o.aedat --recon r.pgm --events 500");
  ASSERT_EQ(e.status, 0) << e.err;
  const std::string queue = slurp(dir_ / "q.txt");
  ASSERT_GT(std::count(queue.begin(), queue.end(), '\n'), 500);
  EXPECT_NE(queue.find(' '), std::string::npos);
  const Outcome c = aesim("classify o.aedat --json");
  ASSERT_EQ(c.status, 0) << c.err;
  const auto j = nlohmann::json::parse(c.out);
  EXPECT_EQ(j["winner"], "O");
  EXPECT_GT(j["additions"].get<double>(), 0);
  EXPECT_TRUE(j["scores"].contains("Q"));
  EXPECT_FALSE(j["centred_templates"].get<bool>());
  // --center N centres the subject on its first N events and every template on its own centroid;
  // the O is drawn centred, so the subject barely moves (less than a pixel).
  const Outcome centred = aesim("classify o.aedat --center 1000 --json");
  ASSERT_EQ(centred.status, 0) << centred.err;
  const auto jc = nlohmann::json::parse(centred.out);
  EXPECT_EQ(jc["winner"], "O");
  EXPECT_TRUE(jc["centred_templates"].get<bool>());
  EXPECT_LT(std::hypot(jc["shift"][0].get<double>(), jc["shift"][1].get<double>()), 1.0);
  EXPECT_TRUE(nlohmann::json::parse(aesim("classify o.aedat --center-templates --json").out)["centred_templates"].get<bool>());
  const Outcome human = aesim("classify o.aedat --templates " + kScenes + "/templates/letters --clock 20MHz");
  EXPECT_NE(human.out.find("winner: O"), std::string::npos) << human.out;
  EXPECT_NE(human.out.find("cycles per template per event"), std::string::npos);
  const Outcome report = aesim("report bandwidth --width 128 --height 96 --bits 8 --events 400");
  ASSERT_EQ(report.status, 0);
  EXPECT_NE(report.out.find("98304 bits"), std::string::npos) << report.out;
  EXPECT_NE(report.out.find("5600 bits"), std::string::npos) << report.out;
  // The paper's constants by default: 100 cycles per template at 57.6 MHz.
  EXPECT_NEAR(j["estimated_time_s"].get<double>(),
              j["events_used"].get<double>() * 4 * 100 / 57.6e6, 1e-12);
  EXPECT_NE(report.out.find("airtime"), std::string::npos) << report.out;
}

TEST_F(CliTest, ClassifyAndReconTakeTheArraySizeFromTheHeaderOrSize) {
  // One recording as AEDAT and CSV, on a 64x64 array whose outer rows and columns never fire.
  write("dot.pgm", [] {
    std::string pgm = "P5\n64 64\n255\n";
    for (int y = 0; y < 64; ++y) {
      for (int x = 0; x < 64; ++x) pgm += static_cast<char>(x > 8 && x < 40 && y > 8 && y < 40 ? 255 : 0);
    }
    return pgm;
  }());
  ASSERT_EQ(aesim("run --scene dot.pgm --set pixel.i_dark=0 --duration 1s --out d.aedat --csv d.csv").status, 0);
  const Outcome from_aedat = aesim("classify d.aedat --json");
  ASSERT_EQ(from_aedat.status, 0) << from_aedat.err;
  // A CSV records no size: classify refuses to guess it from the events, and agrees with the
  // AEDAT file event for event once it is given.
  const Outcome guessed = aesim("classify d.csv --json");
  EXPECT_EQ(guessed.status, 2);
  EXPECT_NE(guessed.err.find("records no array size: give it (--size WIDTHxHEIGHT; size='WIDTHxHEIGHT' in Python)"),
            std::string::npos)
      << guessed.err;
  const Outcome sized = aesim("classify d.csv --size 64x64 --json");
  ASSERT_EQ(sized.status, 0) << sized.err;
  EXPECT_EQ(nlohmann::json::parse(sized.out)["events_used"], nlohmann::json::parse(from_aedat.out)["events_used"]);
  EXPECT_EQ(aesim("classify d.aedat --size 32x32").status, 2);  // disagrees with the header
  EXPECT_EQ(aesim("classify d.csv --size 16x16").status, 2);    // events outside it
  // recon: the reference's form still works on a CSV, with a warning; --size gives the array's image.
  const Outcome spanned = aesim("recon d.csv -o spanned.pgm");
  ASSERT_EQ(spanned.status, 0) << spanned.err;
  EXPECT_NE(spanned.err.find("records no array size"), std::string::npos) << spanned.err;
  ASSERT_EQ(aesim("recon d.csv --size 64x64 -o sized.pgm").status, 0);
  EXPECT_EQ(slurp(dir_ / "sized.pgm").substr(0, 9), "P5\n64 64\n");
  EXPECT_NE(slurp(dir_ / "spanned.pgm").substr(0, 9), "P5\n64 64\n");
}

TEST_F(CliTest, EmulateClassifyAndReportRejectBadInput) {
  const std::string bad_pgm = write("bad.pgm", "P5\n4 4\n255\nxx");
  const std::string bad_y4m = write("bad.y4m", "YUV4MPEG2 W4 H4 Cmono\nFRAME\nab");
  const std::pair<std::string, std::string> cases[] = {
      {"emulate " + bad_pgm + " --out e.aedat", "truncated"},
      {"emulate " + bad_y4m + " --out e.aedat", "truncated"},
      {"emulate " + kScenes + "/letters/A.pgm --behaviour sparkle --out e.aedat", "--behaviour"},
      {"emulate " + kScenes + "/letters/A.pgm --chaos-in 1.5 --out e.aedat", "--chaos-in"},
      {"emulate " + kScenes + "/letters/A.pgm --clip 200,100 --out e.aedat", "--clip"},
      {"emulate " + kScenes + "/letters/A.pgm --size 0x3 --out e.aedat", "--size"},
      {"emulate " + kScenes + "/letters/A.pgm --threshold 300 --out e.aedat", "--threshold"},
      {"classify missing.aedat", "not found"},
      {"classify " + bad_pgm + " --templates " + kScenes + "/templates/letters", "unsupported format"},
      {"classify x.aedat --templates /no/such/folder", "template folder"},
      {"report bandwidth --bits 0", "--bits"},
  };
  for (const auto& [args, needle] : cases) {
    const Outcome o = aesim(args);
    EXPECT_EQ(o.status, 2) << args << ": " << o.err;
    EXPECT_NE(o.err.find(needle), std::string::npos) << args << ": " << o.err;
    EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << args << ": " << o.err;
    EXPECT_FALSE(fs::exists(dir_ / "e.aedat")) << args;
  }
}

TEST_F(CliTest, ReconAndInfoRejectBadInput) {
  EXPECT_EQ(aesim("recon missing.aedat -o r.png").status, 2);
  EXPECT_EQ(aesim("info missing.aedat").status, 2);
  write("bad.aedat", "#!AER-DAT2.0\r\nxyz");
  EXPECT_EQ(aesim("info bad.aedat").status, 2);
  EXPECT_EQ(aesim("recon bad.aedat --mode sideways -o r.png").status, 2);
  EXPECT_FALSE(fs::exists(dir_ / "r.png"));
}

// docs/configuration_keys.md's table is what `aesim config keys --markdown` prints: every key the
// program accepts, with unit, the aloha preset's value and meaning; no key missing, none invented.
TEST_F(CliTest, KeyReferenceIsTheProgramsOwn) {
  const Outcome o = aesim("config keys --markdown");
  ASSERT_EQ(o.status, 0) << o.err;
  const std::string doc = slurp(std::string(AESIM_SOURCE_DIR) + "/docs/configuration_keys.md");
  const auto table = doc.find("| key |");
  ASSERT_NE(table, std::string::npos);
  EXPECT_EQ(doc.substr(table), o.out) << "regenerate the table with `aesim config keys --markdown`";
  std::size_t rows = 0;
  for (const std::string& key : SensorConfig::keys()) {
    EXPECT_NE(o.out.find("| `" + key + "` |"), std::string::npos) << key;
    ++rows;
  }
  EXPECT_EQ(static_cast<std::size_t>(std::count(o.out.begin(), o.out.end(), '\n')), rows + 2);
  // The plain listing carries each key once too, and another preset's values.
  const Outcome plain = aesim("config keys --sensor aesim_pixel");
  ASSERT_EQ(plain.status, 0) << plain.err;
  EXPECT_NE(plain.out.find("pixel.transfer"), std::string::npos);
  EXPECT_NE(plain.out.find("table of"), std::string::npos) << plain.out;
}

// A slip names what was meant; no command at all lists the commands. One line, exit 2.
TEST_F(CliTest, MistypedNamesGetTheNearestAndNoCommandListsThem) {
  struct Case {
    const char* args;
    const char* says;
  } cases[] = {{"run --set pixel.cint=50fF", "unknown key 'pixel.cint', did you mean 'pixel.c_int'?"},
               {"run --set c_int=50fF", "did you mean 'pixel.c_int'?"},
               {"rnu", "unknown command 'rnu', did you mean 'run'?"},
               {"frobnicate", "unknown command 'frobnicate' (commands: run, recon,"},
               {"run --outt x.aedat", "aesim run: unknown option '--outt', did you mean '--out'?"},
               {"run --sumary=s.json", "aesim run: unknown option '--sumary', did you mean '--summary'?"},
               {"info --sizee 4x4 x.aedat", "aesim info: unknown option '--sizee'"},
               {"run --duration 10ms stray", "not expected: stray"},
               {"", "a command is required (run, recon,"}};
  for (const Case& c : cases) {
    const Outcome o = aesim(c.args);
    EXPECT_EQ(o.status, 2) << c.args;
    EXPECT_NE(o.err.find(c.says), std::string::npos) << c.args << ": " << o.err;
    EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << o.err;
    EXPECT_FALSE(fs::exists(dir_ / "out")) << c.args;
  }
}

// --version names the project's version (CMakeLists.txt), the one the Python module and the
// installed package carry.
TEST_F(CliTest, VersionIsTheProjectsAndExitsZero) {
  const Outcome o = aesim("--version");
  EXPECT_EQ(o.status, 0) << o.err;
  EXPECT_EQ(o.out, std::string("aesim ") + kVersion + "\n");
  EXPECT_EQ(std::count(kVersion, kVersion + std::strlen(kVersion), '.'), 2) << kVersion;
}

// The documentation's commands name shipped files by paths from aesim's tree (`--scene
// scenes/natural.pgm`); from any other folder, where they name nothing, they are the shipped files
// (the program here finds its tree as an installed one finds PREFIX/share/aesim), and a file of
// the same path in the folder itself is taken before them.
TEST_F(CliTest, TheDocumentationsPathsNameTheShippedFilesFromAnyFolderUnlessItHasThem) {
  const Outcome shipped = aesim("run --scene scenes/natural.pgm --duration 20ms -o shipped.aedat");
  ASSERT_EQ(shipped.status, 0) << shipped.err;
  EXPECT_NE(shipped.out.find("scene " + kScenes + "/natural.pgm (64x64)"), std::string::npos) << shipped.out;
  ASSERT_EQ(aesim("run --scene " + kScenes + "/natural.pgm --duration 20ms -o given.aedat").status, 0);
  EXPECT_EQ(slurp(dir_ / "shipped.aedat"), slurp(dir_ / "given.aedat"));

  fs::create_directories(dir_ / "scenes");
  {
    std::ofstream own(dir_ / "scenes" / "natural.pgm", std::ios::binary);
    own << "P5 8 8 255\n" << std::string(64, '\xff');
  }
  const Outcome own = aesim("run --scene scenes/natural.pgm --duration 20ms -o own.aedat");
  ASSERT_EQ(own.status, 0) << own.err;
  EXPECT_NE(own.out.find("scene scenes/natural.pgm (8x8)"), std::string::npos) << own.out;

  // A sweep spec and a pixel deck the same way: each named file read (the spec's -o refused after
  // it, the deck's subcircuits listed), a name shipped nowhere not found.
  EXPECT_NE(aesim("sweep scripts/sweeps/collisions.toml -o c.txt").err.find("-o 'c.txt': use a .csv file name"), std::string::npos);
  EXPECT_NE(aesim("sweep scripts/sweeps/nothing.toml").err.find("sweep spec 'scripts/sweeps/nothing.toml': not found"),
            std::string::npos);
  const Outcome deck = aesim("calibrate models/circuits/aesim_pixel.cir --subckt nothing -o p.toml");
  EXPECT_EQ(deck.status, 2);
  EXPECT_NE(deck.err.find("aesim_pixel"), std::string::npos) << deck.err;
  EXPECT_EQ(deck.err.find("not found"), std::string::npos) << deck.err;
  EXPECT_FALSE(fs::exists(dir_ / "p.toml"));
}

}  // namespace
}  // namespace aesim
