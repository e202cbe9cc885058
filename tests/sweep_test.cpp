// aesim sweep: spec expansion, bad specs, and a small sweep end to end.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "aesim/errors/input_error.hpp"
#include "support/sanitized_build.hpp"
#include "support/temp_dir_test.hpp"
#include "aesim/spec/sweep_spec.hpp"

namespace aesim {
namespace {
namespace fs = std::filesystem;

class SweepTest : public testing::TempDirTest {
 protected:
  std::string spec(const std::string& text) { return write("spec.toml", text); }
  int aesim(const std::string& args, std::string* err = nullptr) {
    const testing::Outcome o = TempDirTest::aesim(args);
    if (err) *err = o.err.substr(0, o.err.find('\n'));
    return o.status;
  }
};

TEST_F(SweepTest, GroupsExpandToTheCartesianProductWithLogRanges) {
  const SweepSpec s = load_sweep_spec(spec(R"(
sensor = "aloha"
[set]
"pixel.mismatch" = 0
[[group]]
name = "a"
scene = ["scenes/letters/A.pgm", "scenes/letters/O.pgm"]
"bus.t_event" = { from = "1us", to = "100us", points = 3, scale = "log" }
"pixel.initial" = ["reset", "random"]
[[group]]
name = "b"
"receiver.clock" = { from = "1MHz", to = "3MHz", points = 3 }
)"));
  ASSERT_EQ(s.points.size(), 2u * 3 * 2 + 3);
  EXPECT_EQ(s.swept_keys, (std::vector<std::string>{"bus.t_event", "pixel.initial", "receiver.clock"}));
  // Last axis fastest; the fixed [set] comes first in every point.
  EXPECT_EQ(s.points[0].sets[0], (std::pair<std::string, std::string>{"pixel.mismatch", "0"}));
  EXPECT_EQ(s.points[0].sets[1].second, "1e-06s");
  EXPECT_EQ(s.points[1].sets[2].second, "random");
  EXPECT_EQ(s.points[2].sets[1].second, "1e-05s");  // the log midpoint of 1 us and 100 us
  EXPECT_NE(s.points[6].scene.find("O.pgm"), std::string::npos);
  EXPECT_EQ(s.points[13].sets[1].second, "2000000Hz");  // the linear midpoint
  EXPECT_EQ(s.points[13].group, "b");
}

TEST_F(SweepTest, BadSpecsAreOneLineErrorsWithExitTwo) {
  const std::pair<std::string, std::string> cases[] = {
      {"[[group]]\n\"pixel.c_intt\" = [\"1fF\"]\n", "pixel.c_intt"},
      {"[[group]]\n\"bus.t_event\" = []\n", "empty list"},
      {"sensor = \"aloha\"\n", "no [[group]]"},
      {"[[group]]\n\"pixel.c_int\" = [\"lots\"]\n", "pixel.c_int"},
      {"[[group]]\n\"pixel.c_int\" = [\"-1fF\"]\n", "pixel.c_int"},
      {"[[group]]\n\"bus.t_event\" = { from = \"1us\", to = \"2ms\", points = 1 }\n", "points"},
      {"[[group]]\n\"bus.t_event\" = { from = \"1us\", to = \"2V\", points = 3 }\n", "units"},
      {"[[group]]\nscene = \"no/such.pgm\"\n", "not found"},
      {"colour = 3\n[[group]]\nname = \"x\"\n", "colour"},
      {"[[group\n", "malformed TOML"},
      {"chart = \"no_such.gp\"\n[[group]]\nname = \"x\"\n", "chart script 'no_such.gp' is neither in the spec's folder"},
  };
  for (const auto& [text, needle] : cases) {
    std::string err;
    EXPECT_EQ(aesim("sweep " + spec(text) + " -o s.csv", &err), 2) << text;
    EXPECT_NE(err.find(needle), std::string::npos) << text << " -> " << err;
    EXPECT_FALSE(fs::exists(dir_ / "s.csv")) << text;
  }
}

std::vector<std::vector<std::string>> read_csv(const fs::path& p) {
  std::vector<std::vector<std::string>> rows;
  std::ifstream in(p);
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string c;
    while (std::getline(ss, c, ',')) cells.push_back(c);
    rows.push_back(cells);
  }
  return rows;
}

// Two sweep CSVs hold the same results: every cell equal but wall_time_s, which is measured.
void expect_same_results(const std::vector<std::vector<std::string>>& a,
                         const std::vector<std::vector<std::string>>& b) {
  ASSERT_EQ(a.size(), b.size());
  ASSERT_FALSE(a.empty());
  const auto wall = static_cast<std::size_t>(std::find(a[0].begin(), a[0].end(), "wall_time_s") - a[0].begin());
  ASSERT_LT(wall, a[0].size());
  for (std::size_t r = 0; r < a.size(); ++r) {
    ASSERT_EQ(a[r].size(), b[r].size()) << "row " << r;
    for (std::size_t c = 0; c < a[r].size(); ++c) {
      if (c != wall) {
        EXPECT_EQ(a[r][c], b[r][c]) << "row " << r << ", " << a[0][c];
      }
    }
  }
}

TEST_F(SweepTest, SmallSweepWritesOneRowPerPointWithTheoryAndMatchesAcrossJobCounts) {
  const std::string s = spec(R"(
sensor = "aloha"
duration = "500ms"
[set]
"bus.access" = "aloha"
[[group]]
name = "load"
scene = "scenes/uniform.pgm"
"bus.t_event" = { from = "10us", to = "100us", points = 3, scale = "log" }
)");
  ASSERT_EQ(aesim("sweep " + s + " -o one.csv --jobs 1 --no-chart"), 0);
  ASSERT_EQ(aesim("sweep " + s + " -o two.csv --jobs 2 --no-chart"), 0);
  const auto one = read_csv(dir_ / "one.csv");
  const auto two = read_csv(dir_ / "two.csv");
  ASSERT_EQ(one.size(), 4u);
  const auto& h = one[0];
  EXPECT_EQ(h[0], "group");
  EXPECT_EQ(h[1], "scene");
  EXPECT_EQ(h[2], "bus.t_event");
  EXPECT_EQ(h[3], "events_fired");
  EXPECT_EQ(h.back(), "theory_collision_fraction");
  auto col = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(h.begin(), h.end(), name) - h.begin());
  };
  ASSERT_LT(col("wall_time_s"), h.size());
  for (std::size_t r = 1; r < one.size(); ++r) {
    const double g = std::stod(one[r][col("offered_load")]);
    EXPECT_NEAR(std::stod(one[r][col("theory_throughput")]), g * std::exp(-2 * g), 1e-12);
    EXPECT_NEAR(std::stod(one[r][col("theory_collision_fraction")]), 1 - std::exp(-2 * g), 1e-12);
  }
  expect_same_results(one, two);  // whatever the number of parallel jobs
  // tau grows along the rows, and so does the offered load.
  EXPECT_LT(std::stod(one[1][col("offered_load")]), std::stod(one[3][col("offered_load")]));
}

TEST_F(SweepTest, ASweepKilledMidwayResumesToTheSameCsv) {
  // Eight points of ~0.1 s each (a fine fixed step, ten times coarser under the sanitizers, whose
  // code takes about ten times as long), one job at a time; kill -9 after two have finished (the
  // six left take 0.6 s, the watcher looks every 20 ms), run again: the rest are done and the CSV
  // equals an uninterrupted run's.
  const std::string step = testing::kUnderAddressSanitizer ? "20us" : "2us";
  const std::string s = spec(R"(
sensor = "aloha"
duration = "200ms"
[set]
"array.rows" = 32
"array.cols" = 32
"sim.fidelity" = "fixed_step"
"sim.step" = ")" + step + R"("
[[group]]
name = "slow"
"pixel.c_int" = ["50fF", "60fF", "70fF", "80fF", "90fF", "100fF", "110fF", "120fF"]
)");
  ASSERT_EQ(aesim("sweep " + s + " -o whole.csv --jobs 1"), 0);
  const std::string cmd = "cd '" + dir_.string() + "' && ('" AESIM_BINARY "' sweep " + s +
                          " -o cut.csv --jobs 1 >/dev/null 2>&1 & pid=$!; "
                          "while [ ! -f cut.csv.partial ] || [ $(wc -l < cut.csv.partial) -lt 3 ]; do sleep 0.02; done; "
                          "kill -9 $pid; wait $pid 2>/dev/null; true)";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  ASSERT_FALSE(fs::exists(dir_ / "cut.csv"));  // nothing half-written
  ASSERT_TRUE(fs::exists(dir_ / "cut.csv.partial"));
  std::string err;
  ASSERT_EQ(aesim("sweep " + s + " -o cut.csv --jobs 2", &err), 0) << err;
  EXPECT_NE(err.find("resuming:"), std::string::npos) << err;
  EXPECT_EQ(err.find("resuming: 0 of"), std::string::npos) << err;
  EXPECT_EQ(err.find("resuming: 1 of"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(dir_ / "cut.csv.partial"));
  const auto whole = read_csv(dir_ / "whole.csv");
  const auto cut = read_csv(dir_ / "cut.csv");
  ASSERT_EQ(whole.size(), 9u);
  expect_same_results(whole, cut);
}

// Points run in forked children: one that fails (here, more work than sim.max_events allows)
// stops the sweep with its own one-line reason and exit status, the points before it stay in the
// journal, and no CSV is written.
TEST_F(SweepTest, AFailingPointStopsTheSweepAndKeepsTheFinishedOnes) {
  const std::string s = spec(R"(
sensor = "aloha"
duration = "1s"
[set]
"sim.fidelity" = "event"
"sim.max_events" = 100000
[[group]]
name = "brightening"
"pixel.i_max" = ["1pA", "2pA", "1nA"]
)");
  const testing::Outcome o = TempDirTest::aesim("sweep " + s + " -o out.csv --jobs 1");
  const std::string& err = o.err;
  EXPECT_EQ(o.status, 2) << err;
  EXPECT_NE(err.find("point 3 failed: pixel.i_max: "), std::string::npos) << err;
  EXPECT_NE(err.find("max_events"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(dir_ / "out.csv"));
  std::ifstream journal(dir_ / "out.csv.partial");
  std::string line;
  int finished = 0;
  while (std::getline(journal, line)) finished += line.rfind("{\"index\"", 0) == 0 ? 1 : 0;
  EXPECT_EQ(finished, 2);
}

TEST_F(SweepTest, UnderMpirunTheRanksShareTheSweepAndRankZeroWritesTheSameCsv) {
  if (std::system("command -v mpirun >/dev/null 2>&1") != 0) GTEST_SKIP() << "no mpirun (openmpi-bin)";
  const std::string s = spec(R"(
sensor = "aloha"
duration = "500ms"
[set]
"bus.access" = "aloha"
[[group]]
name = "load"
scene = ["scenes/letters/A.pgm", "scenes/natural.pgm"]
"bus.t_event" = { from = "10us", to = "1ms", points = 4, scale = "log" }
)");
  ASSERT_EQ(aesim("sweep " + s + " -o local.csv --no-chart"), 0);
  // Under LeakSanitizer (scripts/test), OpenMPI's leaks are matched to their suppressions
  // (tests/sanitizers/lsan.supp) only on full stacks, its plug-ins being unloaded by then: the
  // ranks unwind every allocation the slow way. Only they: it made other tests up to 4x slower.
  if (const char* lsan = std::getenv("LSAN_OPTIONS")) {
    ::setenv("LSAN_OPTIONS", (std::string(lsan) + ":fast_unwind_on_malloc=0").c_str(), 1);
  }
  // Root in a container: OpenMPI wants explicit consent. Two ranks on this machine.
  const std::string cmd = "cd '" + dir_.string() +
                          "' && OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 timeout 120 mpirun -np 2 "
                          "--oversubscribe '" AESIM_BINARY "' sweep " + s + " -o mpi.csv --no-chart --jobs 1 "
                          ">mpi.log 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << testing::slurp(dir_ / "mpi.log");
  const auto local = read_csv(dir_ / "local.csv");
  const auto mpi = read_csv(dir_ / "mpi.csv");
  ASSERT_EQ(local.size(), 9u);
  expect_same_results(local, mpi);
  for (const auto& e : fs::directory_iterator(dir_)) {
    EXPECT_EQ(e.path().filename().string().rfind(".mpi.points", 0), std::string::npos) << "work folder left";
  }
}

TEST_F(SweepTest, AJournalOfAnotherSweepIsNotResumed) {
  const std::string a = spec("[[group]]\n\"pixel.c_int\" = [\"50fF\"]\n");
  write("x.csv.partial", "aesim-sweep 0000000000000000\n");
  std::string err;
  EXPECT_EQ(aesim("sweep " + a + " -o x.csv --no-chart", &err), 2);
  EXPECT_NE(err.find("different sweep"), std::string::npos) << err;
}

// A shipped spec copied next to the user's own files still finds its scenes and its chart (they
// are named from the aesim tree), and draws the chart beside its CSV.
TEST_F(SweepTest, AShippedSpecCopiedElsewhereFindsItsScenesAndChart) {
  fs::create_directories(dir_ / "mine");
  std::string spec = testing::slurp(std::string(AESIM_SOURCE_DIR) + "/scripts/sweeps/collisions.toml");
  // A tenth of the duration under the sanitizers (17 s there against 3 s in Release): the paths
  // this test is about are found the same.
  const std::string duration = "duration = \"2s\"";
  ASSERT_NE(spec.find(duration), std::string::npos);
  if (testing::kUnderAddressSanitizer) spec.replace(spec.find(duration), duration.size(), "duration = \"200ms\"");
  write("mine/collisions.toml", spec);
  std::string err;
  ASSERT_EQ(aesim("sweep mine/collisions.toml -o mine/c.csv", &err), 0) << err;
  EXPECT_GT(read_csv(dir_ / "mine" / "c.csv").size(), 80u);
  if (std::system("command -v gnuplot >/dev/null 2>&1") == 0) {
    EXPECT_TRUE(fs::is_regular_file(dir_ / "mine" / "c.png"));
    EXPECT_TRUE(fs::is_regular_file(dir_ / "mine" / "c.svg"));
  }
}

// With constraints, the CSV marks the recommended design's rows: one design (the same swept values)
// in every condition (2 scenes x 3 illuminances), every one of its rows feasible, and it is the
// design the report recommends.
TEST_F(SweepTest, TheRecommendedDesignIsMarkedOnEveryRowOfIt) {
  std::string err;
  ASSERT_EQ(aesim("sweep " + std::string(AESIM_SOURCE_DIR) + "/scripts/sweeps/sizing.toml -o s.csv --no-chart", &err), 0)
      << err;
  const auto rows = read_csv(dir_ / "s.csv");
  ASSERT_GT(rows.size(), 1u);
  const auto col = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(rows[0].begin(), rows[0].end(), name) - rows[0].begin());
  };
  const std::size_t rec = col("recommended"), feas = col("feasible"), c_int = col("pixel.c_int"),
                    dv = col("pixel.dv_int"), tau = col("bus.t_event");
  ASSERT_LT(rec, rows[0].size());
  std::set<std::string> designs;
  std::size_t marked = 0;
  for (std::size_t r = 1; r < rows.size(); ++r) {
    if (rows[r][rec] != "1") continue;
    ++marked;
    EXPECT_EQ(rows[r][feas], "1") << "row " << r;
    designs.insert(rows[r][c_int] + " " + rows[r][dv] + " " + rows[r][tau]);
  }
  EXPECT_EQ(marked, 6u);
  ASSERT_EQ(designs.size(), 1u);
  const std::string report = testing::slurp(dir_ / "s.report.md");
  const std::string recommendation = report.substr(report.find("## Recommendation"));
  std::istringstream design(*designs.begin());
  double c = 0, v = 0, t = 0;
  design >> c >> v >> t;
  EXPECT_NE(recommendation.find(fmt::format("pixel.c_int={}fF", std::lround(c * 1e15))), std::string::npos)
      << recommendation.substr(0, 200);
  EXPECT_NE(recommendation.find(fmt::format("bus.t_event={}ns", std::lround(t * 1e9))), std::string::npos)
      << recommendation.substr(0, 200);
}

}  // namespace
}  // namespace aesim
