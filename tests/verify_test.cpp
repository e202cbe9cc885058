// `aesim verify` as a team meets it: its own receiver through a description file, the bundled
// receiver through its own, mutants of both that must fail at the check they break, a testbench
// exported for another simulator, and bad descriptions.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <utility>

#include "support/temp_dir_test.hpp"

namespace aesim {
namespace {
namespace fs = std::filesystem;

using testing::Outcome;
using testing::slurp;

const std::string kRtl = std::string(AESIM_SOURCE_DIR) + "/rtl";
const std::string kSecond = AESIM_SECOND_RECEIVER_DIR;

class VerifyTest : public testing::TempDirTest {
 protected:
  // aesim verify with the build tree's model cache (warmed by the verify.warm_cache test).
  Outcome verify(const std::string& args) { return aesim("verify " + args, "AESIM_CACHE_DIR='" AESIM_VERIFY_CACHE "' "); }
  nlohmann::json report(const std::string& out = "out/verify") const {
    return nlohmann::json::parse(slurp(dir_ / out / "verify.json"));
  }
  // Runs a program with its arguments in `folder` (a shell only for the redirection; every
  // argument is a path the test made) and returns its last output line.
  std::string last_line(const std::string& folder, const std::string& command) const {
    const std::string cmd = "cd '" + folder + "' && " + command + " > run.txt 2>&1";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << command;
    std::istringstream lines(slurp(fs::path(folder) / "run.txt"));
    std::string line, last;
    while (std::getline(lines, line)) {
      if (!line.empty()) last = line;
    }
    return last;
  }
};

void expect_pass(const Outcome& o, const nlohmann::json& r) {
  ASSERT_EQ(o.status, 0) << o.out << o.err;
  EXPECT_EQ(r["passed"], true);
  EXPECT_EQ(r["failures"], 0);
  EXPECT_EQ(r["protocol_violations"], 0);
  EXPECT_TRUE(r["first_failure"].is_null());
  // The quick plan: 7 directed cases and 6 scene runs of ~2000 firings.
  EXPECT_GT(r["transactions"].get<double>(), 8000);
  EXPECT_GT(r["beats_checked"].get<double>(), 7000);
  EXPECT_GT(r["receiver_cycles"].get<double>(), 5e5);
  EXPECT_EQ(r["cases"].size(), 13u);
  for (const char* key : {"wall_time_s", "receiver_cycles", "beats_checked", "transactions"}) EXPECT_TRUE(r.contains(key));
}

TEST_F(VerifyTest, BundledReceiverPassesThroughItsOwnDescriptionInBothPolicies) {
  const Outcome drop = verify(kRtl + "/aer_receiver.toml");
  expect_pass(drop, report());
  EXPECT_FALSE(fs::exists(dir_ / "out/verify/failure.vcd"));
  const Outcome hold = verify(kRtl + "/aer_receiver_hold.toml --out hold");
  expect_pass(hold, report("hold"));
  // Only the drop build loses beats (the full_output case holds 200 transactions against 64 words).
  EXPECT_GT(report()["transactions"].get<double>() - report()["beats_checked"].get<double>(),
            report("hold")["transactions"].get<double>() - report("hold")["beats_checked"].get<double>());
}

TEST_F(VerifyTest, SecondReceiverPassesWithNoChangeToAesim) {
  const Outcome o = verify(kSecond + "/ae_rx_alt.toml");
  expect_pass(o, report());
  EXPECT_EQ(report()["receiver"]["collisions"], "flag");
  // A collision gives a flagged beat here, so only drops separate transactions from beats, but
  // for the transaction whose beat a reset cleared.
  double missing = 0;
  const nlohmann::json r = report();
  for (const auto& c : r["cases"]) {
    if (c["name"] != "reset_mid_handshake") missing += c["transactions"].get<double>() - c["beats_checked"].get<double>();
  }
  EXPECT_EQ(missing, report()["drops_accounted"].get<double>());
  EXPECT_GT(missing, 0);
}

// A receiver whose synchronizer has no glitch filter takes the directed case's glitch (half a
// period across an edge) for a request: it answers with an Ack after Req fell and outputs the
// glitch's address. That is allowed (a glitch breaks the bus protocol, not the receiver's); the
// filtered receiver ignores it. Both then deliver the next event.
TEST_F(VerifyTest, AReceiverWithoutAGlitchFilterMayAnswerTheGlitch) {
  std::string rtl = slurp(kSecond + "/ae_rx_alt.v");
  for (const auto& [from, to] :
       {std::pair<std::string, std::string>{"wire seen_high = sync[2] & held;", "wire seen_high = sync[2];"},
        {"wire seen_low = ~sync[2] & ~held;", "wire seen_low = ~sync[2];"}}) {
    const auto at = rtl.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    rtl.replace(at, from.size(), to);
  }
  write("ae_rx_alt.v", rtl);
  std::string description = slurp(kSecond + "/ae_rx_alt.toml");
  const auto at = description.find("ack_latency_cycles = [5, 5]");
  ASSERT_NE(at, std::string::npos);
  description.replace(at, 27, "ack_latency_cycles = [4, 4]");
  write("rx.toml", description);
  const Outcome o = verify("rx.toml --out unfiltered");
  ASSERT_EQ(o.status, 0) << o.out << o.err;
  ASSERT_EQ(verify(kSecond + "/ae_rx_alt.toml --out filtered").status, 0);
  const nlohmann::json unfiltered = report("unfiltered"), filtered = report("filtered");
  ASSERT_EQ(unfiltered["cases"][2]["name"], "req_glitch");
  EXPECT_EQ(unfiltered["cases"][2]["beats_checked"], 2);  // the glitch's address, then the event
  EXPECT_EQ(filtered["cases"][2]["beats_checked"], 1);
  EXPECT_EQ(unfiltered["cases"][2]["transactions"], 1);
}

TEST_F(VerifyTest, SecondRunStartsFromTheCache) {
  ASSERT_EQ(verify(kSecond + "/ae_rx_alt.toml").status, 0);
  const Outcome again = verify(kSecond + "/ae_rx_alt.toml --out again");
  ASSERT_EQ(again.status, 0);
  EXPECT_NE(again.err.find("cached model"), std::string::npos) << again.err;
  EXPECT_EQ(report("again")["build"]["cached"], true);
}

TEST_F(VerifyTest, SameSeedSameChecksOtherSeedOtherRuns) {
  ASSERT_EQ(verify(kRtl + "/aer_receiver.toml --out a").status, 0);
  ASSERT_EQ(verify(kRtl + "/aer_receiver.toml --out b").status, 0);
  ASSERT_EQ(verify(kRtl + "/aer_receiver.toml --out c --seed 7").status, 0);
  EXPECT_EQ(report("a")["cases"], report("b")["cases"]);
  EXPECT_NE(report("a")["cases"], report("c")["cases"]);
}

struct Mutant {
  const char* receiver;  // folder of mutants
  const char* name;
  const char* description;
  const char* check;  // the first check it must fail
};

class MutantTest : public VerifyTest, public ::testing::WithParamInterface<Mutant> {};

TEST_P(MutantTest, FailsAtTheCheckItBreaks) {
  const Mutant m = GetParam();
  const std::string folder = std::string(m.receiver) + "/" + m.name;
  const Outcome o = verify(folder + "/" + m.description);
  ASSERT_EQ(o.status, 1) << o.out << o.err;
  const nlohmann::json r = report();
  EXPECT_EQ(r["passed"], false);
  EXPECT_GT(r["failures"].get<double>(), 0);
  ASSERT_FALSE(r["first_failure"].is_null());
  EXPECT_EQ(r["first_failure"]["check"], m.check) << r["first_failure"].dump();
  for (const char* key : {"time_s", "cycle", "expected", "observed"}) EXPECT_TRUE(r["first_failure"].contains(key));
  // The trace of the cycles around it, Verilator's own, with the RTL's insides.
  const std::string vcd = slurp(dir_ / "out/verify/failure.vcd");
  EXPECT_NE(vcd.find("$timescale 1ps $end"), std::string::npos);
  EXPECT_NE(vcd.find("$scope module"), std::string::npos);
  EXPECT_NE(o.out.find("first failure: " + std::string(m.check)), std::string::npos) << o.out;
}

INSTANTIATE_TEST_SUITE_P(
    Receivers, MutantTest,
    ::testing::Values(Mutant{AESIM_MUTANT_DIR, "no_sync", "aer_receiver.toml", "ack_rise_latency"},
                      Mutant{AESIM_MUTANT_DIR, "ack_early", "aer_receiver.toml", "ack_rise_latency"},
                      Mutant{AESIM_MUTANT_DIR, "fifo_off_by_one", "aer_receiver.toml", "stalled_output"},
                      Mutant{AESIM_SECOND_MUTANT_DIR, "unsynchronised_decision", "ae_rx_alt.toml", "ack_rise_latency"},
                      Mutant{AESIM_SECOND_MUTANT_DIR, "uncounted_drop", "ae_rx_alt.toml", "overflow_count"},
                      Mutant{AESIM_SECOND_MUTANT_DIR, "fifo_off_by_one", "ae_rx_alt.toml", "stalled_output"},
                      Mutant{AESIM_SECOND_MUTANT_DIR, "lost_collision_flag", "ae_rx_alt.toml", "beat"},
                      Mutant{AESIM_SECOND_MUTANT_DIR, "stale_timestamp", "ae_rx_alt.toml", "timestamp"},
                      Mutant{AESIM_SECOND_MUTANT_DIR, "moves_while_stalled", "ae_rx_alt.toml", "stalled_output"}),
    [](const ::testing::TestParamInfo<Mutant>& i) {
      return std::string(i.param.description).substr(0, 3) + "_" + i.param.name;
    });

TEST_F(VerifyTest, ExportedTestbenchPassesInIcarusOnTheGoodDesignsAndFailsOnAMutant) {
  struct Design {
    std::string description, sources, mutant_sources;
  };
  const std::string m1 = std::string(AESIM_MUTANT_DIR) + "/ack_early/";
  const std::string m2 = std::string(AESIM_SECOND_MUTANT_DIR) + "/stale_timestamp/";
  const Design designs[] = {
      {kRtl + "/aer_receiver.toml",
       kRtl + "/aer_receiver.v " + kRtl + "/aer_req_sync.v " + kRtl + "/aer_timestamp.v " + kRtl + "/aer_fifo.v",
       m1 + "aer_receiver.v " + m1 + "aer_req_sync.v " + m1 + "aer_timestamp.v " + m1 + "aer_fifo.v"},
      {kSecond + "/ae_rx_alt.toml", kSecond + "/ae_rx_alt.v", m2 + "ae_rx_alt.v"}};
  int i = 0;
  for (const Design& d : designs) {
    const std::string tb = (dir_ / ("tb" + std::to_string(i++))).string();
    const Outcome o = verify(d.description + " --export-tb " + tb);
    ASSERT_EQ(o.status, 0) << o.err;
    const std::string bench = slurp(fs::path(tb) / "tb.v");
    EXPECT_NE(bench.find("module tb;"), std::string::npos);
    EXPECT_GT(std::count(bench.begin(), bench.end(), '\n'), 50);
    EXPECT_EQ(last_line(tb, "iverilog -g2005 -o sim tb.v " + d.sources + " && vvp sim").rfind("PASS", 0), 0u);
    EXPECT_EQ(last_line(tb, "iverilog -g2005 -o sim tb.v " + d.mutant_sources + " && vvp sim").rfind("FAIL", 0), 0u);
  }
}

TEST_F(VerifyTest, BadDescriptionsAreOneLineExitTwoAndWriteNothing) {
  const std::string good = slurp(kSecond + "/ae_rx_alt.toml");
  auto variant = [&](const std::string& name, const std::string& from, const std::string& to) {
    std::string text = good;
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
    fs::copy_file(kSecond + "/ae_rx_alt.v", dir_ / "ae_rx_alt.v", fs::copy_options::overwrite_existing);
    return write(name, text);
  };
  struct Bad {
    std::string file, needle;
  };
  const Bad bad[] = {
      {variant("no_port.toml", "req = \"bus_req\"", "req = \"bus_request\""), "bus_request"},
      {variant("narrow.toml", "AW = 12", "AW = 8"), "bus_addr"},
      {variant("wrong_way.toml", "ack = \"bus_ack\"", "ack = \"bus_collide\""), "bus_collide"},
      {variant("no_role.toml", "valid = \"out_valid\"\n", ""), "ports.valid"},
      {variant("bad_policy.toml", "full = \"drop\"", "full = \"spill\""), "behaviour.full"},
      {variant("no_source.toml", "sources = [\"ae_rx_alt.v\"]", "sources = [\"missing.v\"]"), "missing.v"},
      {variant("shell.toml", "top = \"ae_rx_alt\"", "top = \"x; rm -rf /\""), "top"},
      {write("empty.toml", ""), "top"},
      {(dir_ / "absent.toml").string(), "absent.toml"},
  };
  for (const Bad& b : bad) {
    const Outcome o = verify("'" + b.file + "'");
    EXPECT_EQ(o.status, 2) << b.file << ": " << o.err;
    // Any progress lines of a build, then one error line naming the problem.
    const auto error = o.err.find("aesim: ");
    ASSERT_NE(error, std::string::npos) << o.err;
    EXPECT_EQ(o.err.find('\n', error), o.err.size() - 1) << o.err;
    EXPECT_NE(o.err.find(b.needle, error), std::string::npos) << o.err;
    EXPECT_FALSE(fs::exists(dir_ / "out/verify/verify.json")) << b.file;
  }
  const Outcome plan = verify(kSecond + "/ae_rx_alt.toml --plan nonsense");
  EXPECT_EQ(plan.status, 2);
  EXPECT_NE(plan.err.find("--plan"), std::string::npos) << plan.err;
}

TEST_F(VerifyTest, RtlThatDoesNotCompileNamesTheFileAndLineAndKeepsTheLog) {
  std::string rtl = slurp(kSecond + "/ae_rx_alt.v");
  const auto at = rtl.find("  wire seen_high");
  ASSERT_NE(at, std::string::npos);
  const auto line = std::count(rtl.begin(), rtl.begin() + static_cast<long>(at), '\n') + 1;
  rtl.insert(at, "  this is not verilog;\n");
  write("ae_rx_alt.v", rtl);
  write("rx.toml", slurp(kSecond + "/ae_rx_alt.toml"));
  const Outcome o = verify("rx.toml");
  EXPECT_EQ(o.status, 2);
  // Progress lines of the build, then one error line naming the file and the line.
  const auto error = o.err.find("aesim: ");
  ASSERT_NE(error, std::string::npos) << o.err;
  EXPECT_EQ(o.err.find('\n', error), o.err.size() - 1) << o.err;
  EXPECT_NE(o.err.find("ae_rx_alt.v:" + std::to_string(line) + ":", error), std::string::npos) << o.err;
  EXPECT_TRUE(fs::exists(dir_ / "out/verify/verilator.log"));
  EXPECT_FALSE(fs::exists(dir_ / "out/verify/verify.json"));
}

TEST_F(VerifyTest, PlanFileRunsTheTeamsOwnCases) {
  write("plan.toml", "directed = false\n[[scene]]\nload = 0.5\nseeds = [3, 4]\nfirings = 500\nready = 0.8\n");
  const Outcome o = verify(kSecond + "/ae_rx_alt.toml --plan plan.toml");
  ASSERT_EQ(o.status, 0) << o.err;
  const nlohmann::json r = report();
  ASSERT_EQ(r["cases"].size(), 2u);
  EXPECT_EQ(r["cases"][0]["kind"], "scene");
  EXPECT_GT(r["transactions"].get<double>(), 600);
  write("some.toml", "directed = [\"single_event\", \"collision\"]\n");
  ASSERT_EQ(verify(kSecond + "/ae_rx_alt.toml --plan some.toml --out some").status, 0);
  const nlohmann::json some = report("some");
  ASSERT_EQ(some["cases"].size(), 2u);
  EXPECT_EQ(some["cases"][1]["name"], "collision");
  write("bad.toml", "directed = [\"no_such_case\"]\n");
  EXPECT_EQ(verify(kSecond + "/ae_rx_alt.toml --plan bad.toml --out bad").status, 2);
  write("huge.toml", "[[scene]]\nfirings = 1e8\nseeds = 1000\nload = 0.0001\n");
  const Outcome huge = verify(kSecond + "/ae_rx_alt.toml --plan huge.toml --out h");
  EXPECT_EQ(huge.status, 2);
  EXPECT_NE(huge.err.find("clock cycles"), std::string::npos) << huge.err;
}

}  // namespace
}  // namespace aesim
