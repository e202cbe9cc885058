// The outside audit's bad-input matrix, through the real program: every case ends with exit
// status 2 (or the documented outcome), one line on stderr that names the problem, nothing left
// behind in the folder, and no hang (each case runs under `timeout`; outside the sanitizer build
// also under a 4 GB address-space limit, so a runaway allocation fails the case).
#include <fcntl.h>
#include <signal.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/sanitized_build.hpp"
#include "support/temp_dir_test.hpp"

namespace aesim {
namespace {
namespace fs = std::filesystem;

using testing::Outcome;
using testing::slurp;

const std::string kScenes = std::string(AESIM_SOURCE_DIR) + "/scenes";

std::string be32(std::uint32_t v) {
  return {static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8), static_cast<char>(v)};
}

class HostileInputTest : public testing::TempDirTest {
 protected:
  // Runs aesim under a time limit (and a memory limit where the build allows one).
  Outcome bounded(const std::string& args, int seconds = 60) {
    // ASan reserves terabytes of address space up front.
    const std::string limit = testing::kUnderAddressSanitizer ? "" : "ulimit -v 4000000 && ";
    return aesim(args, limit + "timeout " + std::to_string(seconds) + " ");
  }

  std::set<std::string> listing() const {
    std::set<std::string> names;
    for (const auto& e : fs::recursive_directory_iterator(dir_)) names.insert(fs::relative(e.path(), dir_).string());
    return names;
  }

  // Exit 2, one line naming `needle`, and the folder exactly as before.
  void expect_refused(const std::string& args, const std::string& needle) {
    const std::set<std::string> before = listing();
    const Outcome o = bounded(args);
    EXPECT_EQ(o.status, 2) << args << "\n" << o.err;
    EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << args << "\n" << o.err;
    EXPECT_NE(o.err.find(needle), std::string::npos) << args << "\n" << o.err;
    EXPECT_EQ(o.err.find("internal error"), std::string::npos) << o.err;
    EXPECT_EQ(listing(), before) << args;
  }

  void copy_scene(const std::string& from, const std::string& to) { fs::copy_file(kScenes + "/" + from, dir_ / to); }

  // Starts aesim in the folder with its stderr in err.txt; returns its pid (to signal it).
  pid_t start(std::vector<std::string> args) {
    args.insert(args.begin(), AESIM_BINARY);
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    const std::string err = (dir_ / "err.txt").string();
    const pid_t pid = ::fork();
    if (pid == 0) {
      if (::chdir(dir_.c_str()) != 0 || !std::freopen("/dev/null", "w", stdout) ||
          !std::freopen(err.c_str(), "w", stderr)) {
        ::_exit(127);
      }
      ::execv(argv[0], argv.data());
      ::_exit(127);
    }
    return pid;
  }

  template <class Condition>
  bool wait_for(Condition done) {
    for (int i = 0; i < 2400; ++i) {  // 60 s
      if (done()) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(25));
    }
    return false;
  }

  std::size_t count_temporaries() const {
    std::size_t n = 0;
    for (const auto& e : fs::directory_iterator(dir_)) n += e.path().filename().string().find(".aesim-tmp.") != std::string::npos;
    return n;
  }
};

TEST_F(HostileInputTest, NoSpecValueOrPathReachesAShell) {
  copy_scene("uniform.pgm", "u.pgm");
  fs::copy_file(std::string(AESIM_SOURCE_DIR) + "/scripts/charts/collisions.gp", dir_ / "c.gp");
  // A chart value that closes a quote in a shell command: now it only names a file that is not there.
  write("inject.toml",
        "sensor = \"aloha\"\nduration = \"50ms\"\nchart = \"c.gp' ; touch PWNED ; echo '\"\n"
        "[[group]]\nscene = \"u.pgm\"\n\"bus.t_event\" = [\"100ns\", \"1us\"]\n");
  expect_refused("sweep inject.toml -o r.csv", "chart script");
  EXPECT_FALSE(fs::exists(dir_ / "PWNED"));

  // An output path with shell syntax is a file name like any other, and the chart is drawn from it.
  write("plain.toml",
        "sensor = \"aloha\"\nduration = \"50ms\"\nchart = \"c.gp\"\n"
        "[[group]]\nscene = \"u.pgm\"\n\"bus.t_event\" = [\"100ns\", \"1us\"]\n");
  const Outcome o = bounded("sweep plain.toml -o 'x$(touch PWNED).csv'");
  ASSERT_EQ(o.status, 0) << o.err;
  EXPECT_FALSE(fs::exists(dir_ / "PWNED"));
  EXPECT_TRUE(fs::is_regular_file(dir_ / "x$(touch PWNED).csv"));
  if (o.err.find("gnuplot not found") == std::string::npos) {
    EXPECT_GT(fs::file_size(dir_ / "x$(touch PWNED).png"), 1000u);
    EXPECT_GT(fs::file_size(dir_ / "x$(touch PWNED).svg"), 1000u);
  }
}

TEST_F(HostileInputTest, InvalidUtf8InAnyTomlIsRefusedBeforeTheParser) {
  // toml11 3.7.1 reads past its buffer on these 3 bytes (a literal string with byte 0xFF).
  const std::string poison = "'\xff'";
  write("sensor.toml", "[pixel]\nc_int = " + poison + "\n");
  expect_refused("run --sensor sensor.toml --summary s.json", "line 2: invalid UTF-8 byte 0xFF");
  write("spec.toml", "sensor = \"aloha\"\nduration = " + poison + "\n");
  expect_refused("sweep spec.toml -o r.csv", "line 2: invalid UTF-8 byte 0xFF");
  fs::create_directory(dir_ / "frames");
  copy_scene("uniform.pgm", "frames/0.pgm");
  copy_scene("checkerboard.pgm", "frames/1.pgm");
  write("frames/scene.toml", "frame_rate = " + poison + "\n");
  expect_refused("run --scene frames --summary s.json", "scene.toml': line 1: invalid UTF-8 byte 0xFF");
  // Overlong forms, surrogates and control characters are refused too; real UTF-8 passes the guard.
  write("overlong.toml", "[pixel]\n# \xc0\xaf\nc_int = \"100fF\"\n");
  expect_refused("run --sensor overlong.toml --summary s.json", "line 2: invalid UTF-8 byte 0xC0");
  write("surrogate.toml", "[pixel]\n# \xed\xa0\x80\n");
  expect_refused("run --sensor surrogate.toml --summary s.json", "invalid UTF-8 byte 0xED");
  write("control.toml", "[pixel]\nc_int = \"100\x01" "fF\"\n");
  expect_refused("run --sensor control.toml --summary s.json", "line 2: control character 0x01");
  // toml11 recurses once per nesting level: deep nesting is refused before it overflows the stack
  // (found by the sensor_toml fuzzer), and brackets in comments and strings do not count.
  write("deep.toml", "[pixel]\nx = " + std::string(5000, '[') + "\n");
  expect_refused("run --sensor deep.toml --summary s.json", "line 2: arrays or tables nested deeper than 32");
  write("brackets.toml", "# " + std::string(100, '[') + "\n[pixel]\nc_int = \"100fF\" # " + std::string(100, '{') +
                             "\ndv_int = '''1V" + std::string(100, '[') + "'''\n");
  const Outcome brackets = bounded("run --sensor brackets.toml --duration 50ms --summary s.json");
  EXPECT_NE(brackets.err.find("dv_int"), std::string::npos) << brackets.err;  // parsed: the value itself is bad
  // toml11 doubles a signed place value per binary digit: more than 62 digits overflow, leading
  // zeros included (found by the sensor_toml fuzzer); 62 are read.
  write("binary.toml", "[array]\nrows = 0b" + std::string(70, '0') + "1\n");
  expect_refused("run --sensor binary.toml --summary s.json", "line 2: binary integer of 71 digits (at most 62)");
  write("binary_ok.toml", "[array]\nrows = 0b" + std::string(55, '0') + "1000000\n");
  const Outcome binary = bounded("run --sensor binary_ok.toml --set array.tile_rows=16 --duration 50ms --summary s.json");
  EXPECT_EQ(binary.status, 0) << binary.err;
  write("good.toml", "# Kapazit\xc3\xa4t \xe2\x80\x94 \xf0\x9f\x93\xb7\n[pixel]\nc_int = \"50fF\"\n");
  const Outcome ok = bounded("run --sensor good.toml --duration 50ms --summary s.json");
  EXPECT_EQ(ok.status, 0) << ok.err;
}

TEST_F(HostileInputTest, ASweepTooLargeToExpandIsRefusedBeforeExpanding) {
  std::string spec = "sensor = \"aloha\"\n[[group]]\n";
  for (const char* key : {"bus.t_event", "pixel.c_int", "pixel.dv_int", "pixel.i_max", "pixel.t_reset"}) {
    spec += std::string("\"") + key + "\" = { from = 1, to = 2, points = 8192 }\n";
  }
  write("huge.toml", spec);
  expect_refused("sweep huge.toml -o r.csv", "more than 100000 design points");
}

TEST_F(HostileInputTest, OutputsAreCheckedBeforeTheRunAndCommittedAllOrNone) {
  fs::create_directory(dir_ / "folder");
  expect_refused("run --duration 50ms --out o.aedat --csv folder", "--csv 'folder': is a folder");
  expect_refused("run --duration 50ms --out X --csv X", "--out and --csv both name 'X'");
  expect_refused("run --duration 50ms --out ./X --summary X", "both name");
  write("file.txt", "x");
  expect_refused("run --duration 50ms --summary file.txt/s.json", "is not a folder");
  copy_scene("uniform.pgm", "s.pgm");
  const std::string scene = slurp(dir_ / "s.pgm");
  expect_refused("run --scene s.pgm --duration 50ms --recon s.pgm", "would overwrite the input 's.pgm'");
  EXPECT_EQ(slurp(dir_ / "s.pgm"), scene);
  write("spec.csv", "sensor = \"aloha\"\n[[group]]\nscene = \"s.pgm\"\n");
  expect_refused("sweep spec.csv -o spec.csv", "would overwrite the input 'spec.csv'");
  const std::string events = "t_us,x,y,tile,flags\n1,1,1,0,0\n";
  write("e.csv", events);
  fs::create_symlink("e.csv", dir_ / "e.pgm");  // the same file under an image's name
  expect_refused("recon e.csv -o e.pgm", "would overwrite the input");
  EXPECT_EQ(slurp(dir_ / "e.csv"), events);
  if (::geteuid() != 0) {
    fs::create_directory(dir_ / "readonly");
    fs::permissions(dir_ / "readonly", fs::perms::owner_read | fs::perms::owner_exec);
    expect_refused("run --duration 50ms --summary readonly/s.json", "cannot write in 'readonly'");
  }
}

TEST_F(HostileInputTest, LeftoversOfAKilledRunAreRemovedByTheNextAndLiveOnesAreKept) {
  char host[256] = {};
  ::gethostname(host, sizeof host - 1);
  std::string h = host;
  for (char& c : h) c = c == '.' ? '_' : c;
  // A pid that cannot be alive (above pid_max), and this test's own pid (alive).
  const std::string dead = ".summary.json.aesim-tmp." + h + ".999999999";
  const std::string alive = ".summary.json.aesim-tmp." + h + "." + std::to_string(::getpid());
  const std::string other_host = ".summary.json.aesim-tmp.otherhost.999999999";
  write(dead, "half");
  write(alive, "busy");
  write(other_host, "theirs");
  fs::create_directory(dir_ / (".r.csv.points0.aesim-tmp." + h + ".999999999"));
  const Outcome o = bounded("run --duration 50ms --summary summary.json");
  ASSERT_EQ(o.status, 0) << o.err;
  EXPECT_FALSE(fs::exists(dir_ / dead));
  EXPECT_FALSE(fs::exists(dir_ / (".r.csv.points0.aesim-tmp." + h + ".999999999")));
  EXPECT_TRUE(fs::exists(dir_ / alive));
  EXPECT_TRUE(fs::exists(dir_ / other_host));
}

TEST_F(HostileInputTest, ASignalWhileOutputsAreOpenLeavesNoTemporaries) {
  // With the RTL in the loop and --vcd, Verilator writes its traces to temporaries during the run:
  // a SIGTERM then must remove them. The run is long enough to be caught in the middle.
  const pid_t pid = start({"run", "--duration", "200s", "--set", "receiver.model=rtl", "--vcd", "w.vcd", "--vcd-to",
                           "1ms", "--summary", "s.json"});
  ASSERT_TRUE(wait_for([&] { return count_temporaries() > 0; })) << "no temporary appeared";
  ::kill(pid, SIGTERM);
  int status = 0;
  ::waitpid(pid, &status, 0);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM);
  EXPECT_EQ(listing(), (std::set<std::string>{"err.txt"}));
}

TEST_F(HostileInputTest, AnInterruptedSweepKeepsOnlyItsJournalAndTheResumeLeavesNothing) {
  copy_scene("uniform.pgm", "u.pgm");
  // Points long enough to be interrupted between: 10 s of the cycle fidelity each, 2 s under the
  // sanitizers, where the same code takes six times as long (the resume's three points of 10 s took
  // most of the test's 8.4 s there).
  const std::string duration = testing::kUnderAddressSanitizer ? "2s" : "10s";
  write("slow.toml",
        "sensor = \"aloha\"\nduration = \"" + duration + "\"\njobs = 1\n[[group]]\nscene = \"u.pgm\"\n"
        "\"sim.fidelity\" = \"cycle\"\n\"bus.t_event\" = [\"100ns\", \"200ns\", \"300ns\", \"400ns\"]\n");
  const pid_t pid = start({"sweep", "slow.toml", "-o", "r.csv"});
  // Interrupt once the journal holds its header and one finished point.
  ASSERT_TRUE(wait_for([&] {
    const std::string j = slurp(dir_ / "r.csv.partial");
    return std::count(j.begin(), j.end(), '\n') >= 2;
  }));
  ::kill(pid, SIGINT);
  int status = 0;
  ::waitpid(pid, &status, 0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 128 + SIGINT) << status;
  const std::string err = slurp(dir_ / "err.txt");
  fs::remove(dir_ / "err.txt");
  EXPECT_NE(err.find("interrupted"), std::string::npos) << err;
  EXPECT_EQ(listing(), (std::set<std::string>{"slow.toml", "u.pgm", "r.csv.partial"})) << err;
  // The limit only catches a hang.
  const Outcome o = bounded("sweep slow.toml -o r.csv", 240);
  ASSERT_EQ(o.status, 0) << o.err;
  EXPECT_NE(o.err.find("resuming"), std::string::npos) << o.err;
  EXPECT_EQ(listing(), (std::set<std::string>{"slow.toml", "u.pgm", "r.csv"}));
}

TEST_F(HostileInputTest, WorkBeyondTheLimitIsEstimatedAndRefusedBeforeTheRun) {
  const std::string one_pixel =
      "--set array.rows=1 --set array.cols=1 --set array.tile_rows=1 --set array.tile_cols=1 --summary s.json";
  expect_refused("run --set pixel.i_max=1e300 --set pixel.t_reset=0 " + one_pixel, "sim.max_events");
  expect_refused("run --set light.lux=1e300 --set pixel.t_reset=0 " + one_pixel, "pixel.i_max");
  expect_refused("run --set pixel.c_int=1e-300 --set pixel.t_reset=0 " + one_pixel, "fire");
  expect_refused("run --set pixel.i_max=1uA --summary s.json", "about 2.17e+09 events");
  // A PFM whose one value is 1e6 of full scale.
  std::string pfm = "Pf\n1 1\n-1.0\n";
  const float big = 1e6f;
  pfm.append(reinterpret_cast<const char*>(&big), 4);
  write("bright.pfm", pfm);
  expect_refused("run --scene bright.pfm --summary s.json", "sim.max_events");
  // Two frames alternating at 1 GHz for a second.
  fs::create_directory(dir_ / "fast");
  copy_scene("uniform.pgm", "fast/0.pgm");
  copy_scene("checkerboard.pgm", "fast/1.pgm");
  write("fast/scene.toml", "frame_rate = \"1GHz\"\nloop = true\n");
  expect_refused("run --scene fast --summary s.json", "scene.frame_rate: the run would wake pixels");
  expect_refused("run --set sim.fidelity=fixed_step --set sim.step=1ps --summary s.json", "sim.step");
  // The queue rung scans every pixel in each of eq. 3's iterations: one lit pixel among a million at
  // 1e5 events/s fires little but costs 1e11 pixel visits.
  std::string one_lit = "P5\n1024 1024\n255\n";
  one_lit.append(1024 * 1024, '\0');
  one_lit[one_lit.size() - 1] = '\xff';
  write("one_lit.pgm", one_lit);
  expect_refused("run --scene one_lit.pgm --set array.rows=1024 --set array.cols=1024 --set sim.fidelity=queue "
                 "--set pixel.i_max=10nA --summary s.json",
                 "sim.fidelity: the queue rung would visit pixels");
  expect_refused("emulate " + kScenes + "/letters/A.pgm --size 4096x4096 --f-max 1e6", "--max-events");
  // A sweep point asking for too much is the sweep's bad input too (the spec's other points may have run).
  write("bright.toml", "sensor = \"aloha\"\nduration = \"2s\"\n[[group]]\n\"pixel.i_max\" = [\"1uA\"]\n");
  const Outcome sweep = bounded("sweep bright.toml -o r.csv");
  EXPECT_EQ(sweep.status, 2) << sweep.err;
  EXPECT_NE(sweep.err.find("point 1 failed: pixel.i_max: the run would fire"), std::string::npos) << sweep.err;
  EXPECT_FALSE(fs::exists(dir_ / "r.csv"));
  EXPECT_FALSE(fs::exists(dir_ / "r.csv.partial"));  // nothing finished, nothing to resume
  // The limit is the user's to raise, and it is what decides: a run refused at 10 events runs at 1e8.
  expect_refused("run --duration 50ms --max-events 10 --summary s.json", "limit 10");
  const Outcome o = bounded("run --duration 50ms --summary s.json");
  EXPECT_EQ(o.status, 0) << o.err;
}

TEST_F(HostileInputTest, ConversionsToIntegersAreRangeChecked) {
  expect_refused("run --set receiver.tick=1e-30 --summary s.json", "receiver.tick");
  expect_refused("run --set receiver.tick=1e30 --summary s.json", "receiver.tick");
  expect_refused("run --set receiver.clock=1e-30 --set sim.fidelity=cycle --summary s.json", "receiver.clock");
  expect_refused("run --set receiver.clock=1e30 --set sim.fidelity=cycle --summary s.json", "receiver.clock");
  expect_refused("run --set bus.t_event=1e30 --summary s.json", "bus.t_event");
  expect_refused("run --vcd w.vcd --vcd-from 1e30s", "--vcd-from");
}

TEST_F(HostileInputTest, TinyFilesCannotAskForHugeAllocations) {
  write("far.csv", "t_us,x,y,tile,flags\n1,65535,65535,0,0\n");
  expect_refused("recon far.csv -o r.pgm", "more than the 16777216");
  // An AEDAT header claiming a 65535 x 1024 array, with one event.
  write("big.aedat",
        "#!AER-DAT2.0\r\n# aesim.sensor.array.rows: 1024\r\n# aesim.sensor.array.cols: 65535\r\n"
        "# aesim.sensor.array.tile_rows: 1024\r\n# aesim.sensor.array.tile_cols: 65535\r\n" +
            be32(0) + be32(1));
  expect_refused("recon big.aedat -o r.pgm", "more than the 16777216");
  expect_refused("run --set array.rows=8192 --set array.cols=8192 --set array.tile_rows=1 --set array.tile_cols=1",
                 "array.rows");
  expect_refused("run --set array.rows=4096 --set array.cols=4096 --set array.tile_rows=1 --set array.tile_cols=1",
                 "more than the 65536");
  write("huge.pgm", "P5\n65536 1024\n255\nxx");
  expect_refused("run --scene huge.pgm --summary s.json", "more than the 16777216");
  write("tall.pgm", "P5\n4096 4096\n255\nxx");
  expect_refused("run --scene tall.pgm --summary s.json", "truncated pixel data");
  write("ascii.pgm", "P2\n4096 4096\n255\n1 2 3\n");
  expect_refused("run --scene ascii.pgm --summary s.json", "truncated pixel data");
}

TEST_F(HostileInputTest, AbsurdRatesStampsAndChannelsAreRefused) {
  const std::string frame(4 * 4 * 3 / 2, '\x80');
  write("inf.y4m", "YUV4MPEG2 W4 H4 Finf:1 C420jpeg\nFRAME\n" + frame);
  expect_refused("emulate inf.y4m", "frame rate");
  write("huge.y4m", "YUV4MPEG2 W4 H4 F1e300:1e-300 C420jpeg\nFRAME\n" + frame);
  expect_refused("emulate huge.y4m", "frame rate");
  expect_refused("emulate " + kScenes + "/letters/A.pgm --frame-rate inf", "--frame-rate");
  write("negative.aedat", "#!AER-DAT2.0\r\n# aesim.sensor.array.rows: 4\r\n# aesim.sensor.array.cols: 4\r\n"
                          "# aesim.sensor.array.tile_rows: 4\r\n# aesim.sensor.array.tile_cols: 4\r\n" +
                              be32(0) + be32(0xFFFFFFF0u));
  expect_refused("info negative.aedat", "negative timestamp");
  std::string pfm = "PF\n1 1\n-1.0\n";
  for (float v : {0.5f, -0.25f, 0.5f}) pfm.append(reinterpret_cast<const char*>(&v), 4);
  write("colour.pfm", pfm);
  expect_refused("run --scene colour.pfm --summary s.json", "channel 1 is -0.25");
}

TEST_F(HostileInputTest, AFullDiskIsReportedWithItsReasonAndLeavesNothing) {
  fs::create_directory(dir_ / "small");
  if (::mount("tmpfs", (dir_ / "small").c_str(), "tmpfs", 0, "size=64k") != 0) {
    GTEST_SKIP() << "cannot mount a small tmpfs here (" << std::strerror(errno) << "): needs root";
  }
  // Every event file's writer, and the CSV: the system's reason, the file the user named, nothing left.
  for (const std::string out : {"--csv small/e.csv", "--out small/e.h5", "--out small/e.npy", "--out small/e.aedat4",
                                 "--out small/e.aedat", "--out small/e.raw", "--out small/e.dat"}) {
    const Outcome o = bounded("run --duration 2s " + out + " --summary small/s.json");
    const std::set<std::string> left = [&] {
      std::set<std::string> names;
      for (const auto& e : fs::directory_iterator(dir_ / "small")) names.insert(e.path().filename().string());
      return names;
    }();
    EXPECT_EQ(o.status, 1) << out << o.err;
    EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << o.err;
    EXPECT_NE(o.err.find("No space left on device"), std::string::npos) << o.err;
    EXPECT_EQ(o.err.find(".aesim-tmp."), std::string::npos) << "names the output, not its temporary: " << o.err;
    EXPECT_TRUE(left.empty()) << *left.begin();
  }
  ::umount((dir_ / "small").c_str());
}

// Event files reserve disk space ahead of their writes (SpaceAhead). On a disk with room for the
// run's outputs but not for the reservation, the run completes and leaves only its bytes; on one
// that fills after a reservation or where none could be made, the run fails as on any full disk.
TEST_F(HostileInputTest, SpaceReservedAheadNeitherFailsARunThatFitsNorHidesAFullDisk) {
  const fs::path small = dir_ / "small";
  fs::create_directory(small);
  const auto run = [&](const std::string& format, int seconds) {
    return bounded(fmt::format("run --scene {}/uniform.pgm --duration {}s --summary small/s.json --out small/e.{}", kScenes,
                               seconds, format));
  };
  // Uniform light writes 0.43 MB a second of .npy, 0.27 MB of AEDAT 2.0 or DAT.
  for (const auto& [format, filling] : {std::pair<std::string, int>{"npy", 60}, {"aedat", 100}, {"dat", 100}}) {
    // 20 s: a 5 to 9 MB file, which reserves 17 MiB past its first megabyte.
    if (::mount("tmpfs", small.c_str(), "tmpfs", 0, "size=24m") != 0) {
      GTEST_SKIP() << "cannot mount a small tmpfs here (" << std::strerror(errno) << "): needs root";
    }
    const Outcome fits = run(format, 20);
    EXPECT_EQ(fits.status, 0) << format << ": " << fits.err;
    struct stat st {};
    ASSERT_EQ(::stat((small / ("e." + format)).c_str(), &st), 0) << format;
    EXPECT_GT(st.st_size, 5000000) << format;
    EXPECT_LT(static_cast<std::uint64_t>(st.st_blocks) * 512, static_cast<std::uint64_t>(st.st_size) + 65536)
        << format << ": reserved space left past the end";
    ::umount(small.c_str());
    // 3 MiB: the file passes its first megabyte, cannot reserve, then fills the disk. 20 MiB: it
    // reserves once, then fills the disk with a file of over 25 MB.
    for (const auto& [size, seconds] : {std::pair<std::string, int>{"size=3m", 20}, {"size=20m", filling}}) {
      ASSERT_EQ(::mount("tmpfs", small.c_str(), "tmpfs", 0, size.c_str()), 0);
      const Outcome full = run(format, seconds);
      EXPECT_EQ(full.status, 1) << format << " " << size << ": " << full.err;
      EXPECT_NE(full.err.find("No space left on device"), std::string::npos) << full.err;
      EXPECT_TRUE(fs::is_empty(small)) << format << " " << size << ": left " << fs::directory_iterator(small)->path();
      ::umount(small.c_str());
    }
  }
}

// An output that is a device or a FIFO is written through, never replaced: /dev/null stays the
// machine's /dev/null, a FIFO's reader gets the events, a FIFO with no reader is refused.
TEST_F(HostileInputTest, OutputsThatAreDevicesOrFifosAreWrittenThroughNeverReplaced) {
  const Outcome o = bounded("run --duration 50ms --summary /dev/null --csv /dev/null --out /dev/null.aedat");
  (void)o;
  struct stat st {};
  ASSERT_EQ(::stat("/dev/null", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode)) << "/dev/null was replaced";
  const Outcome to_null = bounded("run --duration 50ms --summary /dev/null --csv /dev/null");
  EXPECT_EQ(to_null.status, 0) << to_null.err;
  // A folder below /dev is an ordinary folder (the tmpfs /dev/shm): its file is made and committed.
  const fs::path shm = fs::path("/dev/shm") / ("aesim-test-" + std::to_string(::getpid()));
  std::error_code ec;
  if (fs::create_directory(shm, ec)) {
    const Outcome in_shm = bounded("run --duration 50ms --summary " + (shm / "s.json").string() + " --out " + (shm / "e.aedat").string());
    EXPECT_EQ(in_shm.status, 0) << in_shm.err;
    EXPECT_TRUE(fs::is_regular_file(shm / "e.aedat"));
    EXPECT_EQ(std::distance(fs::directory_iterator(shm), fs::directory_iterator()), 2) << "a temporary left";
    fs::remove_all(shm, ec);
  }

  ASSERT_EQ(::mkfifo((dir_ / "events.csv").c_str(), 0644), 0);
  std::string received;
  std::thread reader([&] {
    std::ifstream in(dir_ / "events.csv", std::ios::binary);
    received.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  const Outcome fifo = bounded("run --duration 50ms --csv events.csv --summary s.json");
  // A run that never opened the FIFO would leave the reader waiting in open() for ever: a writer
  // of our own lets it through to an empty read (and finds no reader if the run had one).
  if (const int fd = ::open((dir_ / "events.csv").c_str(), O_WRONLY | O_NONBLOCK); fd >= 0) ::close(fd);
  reader.join();
  EXPECT_EQ(fifo.status, 0) << fifo.err;
  EXPECT_EQ(received.rfind("t_us,x,y,tile,flags\n", 0), 0u);
  const nlohmann::json summary = nlohmann::json::parse(slurp(dir_ / "s.json"));
  EXPECT_EQ(std::count(received.begin(), received.end(), '\n') - 1, summary["events_delivered"].get<long>());
  ASSERT_EQ(::stat((dir_ / "events.csv").c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode));
  fs::remove(dir_ / "s.json");

  const Outcome lonely = bounded("run --duration 50ms --csv events.csv");
  EXPECT_EQ(lonely.status, 2) << lonely.err;
  EXPECT_NE(lonely.err.find("a FIFO with no reader"), std::string::npos) << lonely.err;
  ASSERT_EQ(::stat((dir_ / "events.csv").c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode));
  expect_refused("run --duration 50ms --summary newdir/", "ends in /");
  // A sweep's resume journal is read back: a FIFO there is refused at once, and kept.
  copy_scene("uniform.pgm", "u.pgm");
  write("spec.toml", "sensor = \"aloha\"\nduration = \"10ms\"\n[[group]]\nscene = \"u.pgm\"\n");
  ASSERT_EQ(::mkfifo((dir_ / "r.csv.partial").c_str(), 0644), 0);
  expect_refused("sweep spec.toml -o r.csv", "resume journal 'r.csv.partial': is a FIFO");
}

// Standard output as an output, whatever stands behind it (here a shell's `> stdout.txt`, a regular
// file): the data go to the redirection at its own offset, byte for byte what a file gets, and the
// report goes to stderr; through a pipe (a shell's `| cat`), the same. Under its other names too.
TEST_F(HostileInputTest, StandardOutputAsAnOutputHoldsOnlyTheData) {
  const Outcome to_file = bounded("run --duration 50ms --csv events.csv --summary s.json");
  ASSERT_EQ(to_file.status, 0) << to_file.err;
  const std::string expected = slurp(dir_ / "events.csv");
  ASSERT_GT(std::count(expected.begin(), expected.end(), '\n'), 100);
  for (const char* name : {"/dev/stdout", "/dev/fd/1", "/proc/self/fd/1"}) {
    const Outcome o = bounded(fmt::format("run --duration 50ms --csv={}", name));
    EXPECT_EQ(o.status, 0) << name << ": " << o.err;
    EXPECT_EQ(o.out, expected) << name;
    EXPECT_NE(o.err.find("aesim run: sensor aloha"), std::string::npos) << name << ": " << o.err;
    EXPECT_NE(o.err.find(std::string("wrote ") + name), std::string::npos) << o.err;
  }
  // '-', as Unix tools take it, alone or after '=': standard output under its own name.
  for (const char* option : {"--csv -", "--csv=-"}) {
    const Outcome o = bounded(fmt::format("run --duration 50ms {}", option));
    EXPECT_EQ(o.status, 0) << option << ": " << o.err;
    EXPECT_EQ(o.out, expected) << option;
    EXPECT_NE(o.err.find("aesim run: sensor aloha"), std::string::npos) << option << ": " << o.err;
    EXPECT_FALSE(fs::exists(dir_ / "-")) << option;
  }
  // An event file with no extension is AEDAT 2.0, on standard output as in a file.
  ASSERT_EQ(bounded("run --duration 50ms --out events").status, 0);
  const Outcome aedat = bounded("run --duration 50ms --out -");
  EXPECT_EQ(aedat.status, 0) << aedat.err;
  EXPECT_EQ(aedat.out, slurp(dir_ / "events"));
  EXPECT_EQ(aedat.out.rfind("#!AER-DAT2.0\r\n", 0), 0u);
  const Outcome piped = bounded("run --duration 50ms --csv /dev/stdout 2>report.txt | cat");
  EXPECT_EQ(piped.out, expected);
  // A file the command writes by name still gets its report on stdout.
  const Outcome named = bounded("run --duration 50ms --csv again.csv");
  EXPECT_NE(named.out.find("aesim run: sensor aloha"), std::string::npos) << named.out;
  EXPECT_EQ(slurp(dir_ / "again.csv"), expected);
}

// Two outputs into one stream would interleave into neither format: refused before the run,
// under any of the stream's names; /dev/null, which keeps nothing, takes any number.
TEST_F(HostileInputTest, TwoOutputsIntoOneStreamAreRefused) {
  expect_refused("run --duration 50ms --out - --summary -", "--out and --summary both write into '/dev/stdout'");
  expect_refused("run --duration 50ms --csv /dev/stdout --truth /dev/fd/1", "--csv and --truth both write into");
  ASSERT_EQ(::mkfifo((dir_ / "pipe").c_str(), 0644), 0);
  expect_refused("run --duration 50ms --csv pipe --truth pipe", "--csv and --truth both write into 'pipe'");
  const Outcome to_null = bounded("run --duration 50ms --out /dev/null --csv /dev/null --summary /dev/null");
  EXPECT_EQ(to_null.status, 0) << to_null.err;
}

// Inputs that are not files say what they are; a name with a newline stays on one line.
TEST_F(HostileInputTest, InputsThatAreNotFilesSayWhatTheyAre) {
  ASSERT_EQ(::mkfifo((dir_ / "scene.pgm").c_str(), 0644), 0);
  expect_refused("run --scene scene.pgm --summary s.json", "is a FIFO, not a file");
  fs::remove(dir_ / "scene.pgm");
  expect_refused("info /dev/zero.h5", "not found");
  fs::create_directory(dir_ / "frames");
  copy_scene("uniform.pgm", "frames/0001.pgm");
  fs::create_symlink("nowhere.pgm", dir_ / "frames/0002.pgm");
  expect_refused("run --scene frames --summary s.json", "'0002.pgm' is a link to nothing");
  fs::remove(dir_ / "frames/0002.pgm");
  copy_scene("uniform.pgm", "frames/frame_20261124123456789.pgm");
  expect_refused("run --scene frames --summary s.json", "over 15 digits");
  fs::remove(dir_ / "frames/frame_20261124123456789.pgm");
  const Outcome newline = bounded("run --scene 'bad\nname.pgm' --summary s.json");
  EXPECT_EQ(newline.status, 2);
  EXPECT_EQ(std::count(newline.err.begin(), newline.err.end(), '\n'), 1) << newline.err;
  EXPECT_NE(newline.err.find("bad\\nname.pgm"), std::string::npos) << newline.err;
}

// Readers bounded by the bytes they are given: an HDF5 file whose datasets claim 3e8 entries it
// does not store, or that links to another file; a MATLAB 7.3 file's vectors claiming 2e8; a scene whose frames at the array's size would
// not fit; a truncated JPEG (libjpeg would invent its missing rows).
TEST_F(HostileInputTest, ReadersAreBoundedByTheBytesTheyAreGiven) {
  write("make.py",
        "import h5py, numpy as np\n"
        "with h5py.File('huge.h5', 'w') as f:\n"
        "    g = f.create_group('events')\n"
        "    for n, t in [('x', 'u2'), ('y', 'u2'), ('t', 'u4'), ('p', 'u1')]:\n"
        "        g.create_dataset(n, shape=(300000000,), dtype=t, chunks=(65536,))\n"
        "with h5py.File('target.h5', 'w') as f:\n"
        "    g = f.create_group('events')\n"
        "    for n, t in [('x', 'u2'), ('y', 'u2'), ('t', 'u4'), ('p', 'u1')]:\n"
        "        g.create_dataset(n, data=np.zeros(4, dtype=t))\n"
        "with h5py.File('linked.h5', 'w') as f:\n"
        "    f['events'] = h5py.ExternalLink('target.h5', '/events')\n"
        "with h5py.File('table.h5', 'w') as f:\n"
        "    f.create_dataset('events', shape=(300000000, 4), dtype='u4', chunks=(65536, 4))\n"
        // MATLAB 7.3 is HDF5 after a 128-byte header in a 512-byte user block (version 0x0200, 'IM').
        "import struct\n"
        "with h5py.File('claims.mat', 'w', userblock_size=512) as f:\n"
        "    for n in ['x', 'y', 'ts', 'pol']:\n"
        "        f.create_dataset(n, shape=(1, 200000000), dtype='f8', chunks=(1, 65536))"
        ".attrs['MATLAB_class'] = np.bytes_('double')\n"
        "head = b'MATLAB 7.3 MAT-file, Platform: GLNXA64'.ljust(116, b' ') + bytes(8) + struct.pack('<H', 0x0200) + b'IM'\n"
        "with open('claims.mat', 'r+b') as f:\n"
        "    f.write(head)\n");
  ASSERT_EQ(std::system(("cd '" + dir_.string() + "' && /usr/bin/python3 make.py").c_str()), 0);
  expect_refused("info huge.h5", "claims 300000000 entries");
  expect_refused("info linked.h5", "/events is an external link");
  expect_refused("info table.h5", "/events claims 1200000000 entries");
  expect_refused("info claims.mat", "claims 200000000 numbers, more than its");

  fs::create_directory(dir_ / "many");
  for (int i = 0; i < 9; ++i) write(fmt::format("many/{:02d}.pgm", i), "P2\n1 1\n255\n7\n");
  expect_refused("run --scene many --set array.rows=4096 --set array.cols=4096 --duration 10s --summary s.json",
                 "would take");

  write("make_jpeg.py",
        "from PIL import Image\nimport numpy as np\n"
        "Image.fromarray((np.arange(4096).reshape(64, 64) % 256).astype('uint8')).save('g.jpg', quality=95)\n"
        "d = open('g.jpg', 'rb').read()\nopen('cut.jpg', 'wb').write(d[:len(d) // 2])\n");
  ASSERT_EQ(std::system(("cd '" + dir_.string() + "' && /usr/bin/python3 make_jpeg.py").c_str()), 0);
  expect_refused("run --scene cut.jpg --summary s.json", "Premature end of JPEG file");
}

// Decks and RTL describe circuits: a deck's .control block (and one in a file it includes) would
// run commands, and is refused before ngspice starts; an include that is a FIFO is named, not
// waited on; the output may not be the base preset it is made from.
TEST_F(HostileInputTest, NoCommandFromADeckAndNoWaitOnItsIncludes) {
  const std::string deck = slurp(std::string(AESIM_SOURCE_DIR) + "/models/circuits/aesim_pixel.cir");
  const std::string marker = (dir_ / "ran").string();
  write("inc.lib", ".control\nshell touch " + marker + "\n.endc\n");
  write("deck.cir", deck + ".include inc.lib\n");
  expect_refused("calibrate deck.cir --subckt aesim_pixel -o p.toml", "inc.lib' line 1: a .control block");
  EXPECT_FALSE(fs::exists(marker));
  fs::remove(dir_ / "inc.lib");
  ASSERT_EQ(::mkfifo((dir_ / "inc.lib").c_str(), 0644), 0);
  expect_refused("calibrate deck.cir --subckt aesim_pixel -o p.toml", "is a FIFO, not a file");
  fs::remove(dir_ / "inc.lib");
  fs::remove(dir_ / "deck.cir");
  fs::copy_file(std::string(AESIM_SOURCE_DIR) + "/models/sensors/aloha.toml", dir_ / "base.toml");
  expect_refused("calibrate " + std::string(AESIM_SOURCE_DIR) + "/models/circuits/aesim_pixel.cir --subckt aesim_pixel "
                 "-o base.toml --base base.toml",
                 "would overwrite the input");
}

// Work no estimate counted before: set-up of the cycle rung's tiles and of pixel_processes.
TEST_F(HostileInputTest, SetUpThatGrowsFasterThanItsSizeIsRefusedBeforeTheRun) {
  expect_refused("run --duration 1ms --set sim.fidelity=cycle --set array.rows=4096 --set array.cols=4096 --summary s.json",
                 "16384 tiles is more than its 4096");
  expect_refused("run --duration 1ms --set sim.fidelity=pixel_processes --set array.rows=256 --set array.cols=256 "
                 "--summary s.json",
                 "65536 pixels is more than its 32768");
}

TEST_F(HostileInputTest, NumbersOnTheCommandLineAreChecked) {
  copy_scene("uniform.pgm", "u.pgm");
  write("spec.toml", "sensor = \"aloha\"\nduration = \"10ms\"\n[[group]]\nscene = \"u.pgm\"\n");
  expect_refused("sweep spec.toml -o r.csv -j -3", "--jobs");
  expect_refused("compare --scene u.pgm --steps 0s -o c.csv", "--steps");
  expect_refused("classify u.pgm --cycles-per-template inf", "--cycles-per-template");
  expect_refused("emulate u.pgm --size 4294967297x1 --out e.aedat", "--size");
  write("far.csv", "t_us,x,y,tile,flags\n1e20,1,1,0,0\n");
  expect_refused("info far.csv", "past 1e15");
  write("far.csv", "t_us,x,y,tile,flags\n1,1,1,70000,0\n");
  expect_refused("info far.csv", "tile 70000");
}

TEST_F(HostileInputTest, PathsTheSystemCannotLookUpAreInputErrors) {
  // A name component longer than the system allows (found by the sweep_spec fuzzer): the lookup
  // fails, and that is the user's input, not an internal error.
  const std::string too_long(300, 'x');
  expect_refused("run --scene " + too_long + ".pgm --summary s.json", "File name too long");
  expect_refused("run --sensor " + too_long + ".toml --summary s.json", "File name too long");
  write("spec.toml", "sensor = \"aloha\"\n[[group]]\nscene = \"" + too_long + ".pgm\"\n");
  expect_refused("sweep spec.toml -o r.csv", "File name too long");
  write("file.pgm", "P2\n1 1\n255\n0\n");
  expect_refused("run --scene file.pgm/inside.pgm --summary s.json", "not found");  // ENOTDIR is "not found"
  expect_refused("classify " + kScenes + "/letters/A.pgm --templates " + too_long, "File name too long");
}

}  // namespace
}  // namespace aesim
