// `aesim verify` as a team meets it: its own receiver through a description file, the bundled
// receiver through its own, mutants of both that must fail at the check they break, a testbench
// exported for another simulator, and bad descriptions.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <ostream>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>

#include "aesim/errors/input_error.hpp"
#include "description/receiver_description.hpp"
#include "description/rtl_folder_key.hpp"
#include "driver/case_driver.hpp"
#include "support/temp_dir_test.hpp"

namespace aesim {
namespace {
namespace fs = std::filesystem;

using testing::Outcome;
using testing::slurp;

const std::string kRtl = std::string(AESIM_SOURCE_DIR) + "/rtl";
const std::string kSecond = AESIM_SECOND_RECEIVER_DIR;
const std::string kThird = AESIM_THIRD_RECEIVER_DIR;

// The quick plan: 9 directed cases (6 without a ready port) and 6 scene runs of ~2000 firings.
void expect_pass(const Outcome& o, const nlohmann::json& r, std::size_t cases = 15) {
  ASSERT_EQ(o.status, 0) << o.out << o.err;
  EXPECT_EQ(r["passed"], true);
  EXPECT_EQ(r["failures"], 0);
  EXPECT_EQ(r["protocol_violations"], 0);
  EXPECT_TRUE(r["first_failure"].is_null()) << r["first_failure"].dump();
  EXPECT_GT(r["transactions"].get<double>(), 8000);
  EXPECT_GT(r["beats_checked"].get<double>(), 7000);
  EXPECT_GT(r["receiver_cycles"].get<double>(), 5e5);
  EXPECT_EQ(r["cases"].size(), cases);
  for (const char* key : {"wall_time_s", "receiver_cycles", "beats_checked", "transactions"}) EXPECT_TRUE(r.contains(key));
}

class VerifyTest : public testing::TempDirTest {
 protected:
  // aesim verify with the build tree's model cache (warmed by the verify.warm_cache test).
  Outcome verify(const std::string& args) { return aesim("verify " + args, "AESIM_CACHE_DIR='" AESIM_VERIFY_CACHE "' "); }
  // The bundled receiver's description with its sources named by absolute paths, so that an
  // edited copy may be written into the test's folder.
  static std::string bundled_description_elsewhere() {
    std::string rtl;
    for (const char* f : {"aer_receiver.v", "aer_req_sync.v", "aer_timestamp.v", "aer_fifo.v"}) rtl += ", \"" + kRtl + "/" + f + "\"";
    return edited(slurp(kRtl + "/aer_receiver.toml"),
                  "sources = [\"aer_receiver.v\", \"aer_req_sync.v\", \"aer_timestamp.v\", \"aer_fifo.v\"]",
                  "sources = [" + rtl.substr(2) + "]");
  }
  nlohmann::json report(const std::string& out = "out/verify") const {
    return nlohmann::json::parse(slurp(dir_ / out / "verify.json"));
  }
  // The level-valid receiver's RTL copied into the test's folder; its description's text.
  std::string level_valid_receiver() {
    const std::string dir = std::string(AESIM_SOURCE_DIR) + "/tests/rtl/level_valid_receiver";
    write("lvr.v", slurp(dir + "/lvr.v"));
    return slurp(dir + "/lvr.toml");
  }
  // The bundled receiver instantiated as `rx` (32-bit stamps, 1 us ticks at 50 MHz, collisions
  // discarded, its FIFO full at all its words), each port wired to what `wires` names for it, else
  // to the wire of its own name; the status outputs left open unless named.
  static std::string bundled_instance(const std::map<std::string, std::string>& wires, int addr_width = 16, int depth = 64) {
    std::map<std::string, std::string> to = {{"prescale_i", "24'd50"}, {"fifo_limit_i", std::to_string(depth)},
                                             {"discard_collisions_i", "1'b1"}, {"ts_external_i", "1'b0"}, {"ts_i", "32'd0"},
                                             {"fifo_count_o", ""}};
    for (const auto& [port, wire] : wires) to[port] = wire;
    std::string connections;
    for (const char* port : {"clk_i", "rst_ni", "req_i", "addr_i", "contention_i", "ack_o", "prescale_i", "fifo_limit_i",
                             "discard_collisions_i", "ts_external_i", "ts_i", "evt_valid_o", "evt_ready_i", "evt_ts_o",
                             "evt_addr_o", "evt_flags_o", "fifo_count_o"}) {
      connections += fmt::format("{}.{}({})", connections.empty() ? "" : ", ", port, to.count(port) ? to[port] : port);
    }
    return fmt::format("  aer_receiver #(.ADDR_WIDTH({}), .TS_WIDTH(32), .DEPTH({}), .PRESCALE_WIDTH(24)) rx (\n      {},\n"
                       "      .events_o(), .collisions_o(), .overflows_o(), .idle_o());\n",
                       addr_width, depth, connections);
  }
  // A description of a wrapper `top` (its own file `top`.v in the test's folder) around the bundled
  // receiver: their sources, 50 MHz, `reset`, each role on the port `ports` names for it, else on
  // the bundled receiver's own (with any other role `ports` names), and the bundled receiver's behaviour (discarded collisions, drops,
  // 1 us stamps of 32 bits, Ack on the 4th edge).
  static std::string around_bundled(const std::string& top, const std::string& reset,
                                    const std::map<std::string, std::string>& ports = {}) {
    std::string d = "top = \"" + top + "\"\nsources = [\"" + top + ".v\"";
    for (const char* f : {"aer_receiver.v", "aer_req_sync.v", "aer_timestamp.v", "aer_fifo.v"}) d += ", \"" + kRtl + "/" + f + "\"";
    d += "]\nclock = \"50MHz\"\nreset = " + reset + "\n[ports]\n";
    const std::map<std::string, std::string> own = {
        {"clk", "\"clk_i\""},           {"req", "\"req_i\""},           {"ack", "\"ack_o\""},
        {"addr", "\"addr_i\""},         {"contention", "\"contention_i\""}, {"valid", "\"evt_valid_o\""},
        {"ready", "\"evt_ready_i\""},   {"out_addr", "\"evt_addr_o\""},  {"timestamp", "\"evt_ts_o\""},
        {"flags", "\"evt_flags_o\""}};
    for (const auto& [role, port] : own) d += role + " = " + (ports.count(role) ? ports.at(role) : port) + "\n";
    for (const auto& [role, port] : ports) d += own.count(role) ? "" : role + " = " + port + "\n";
    return d + "[behaviour]\ncollisions = \"discard\"\nfull = \"drop\"\ntimestamp_tick = \"1us\"\ntimestamp_bits = 32\n"
               "ack_latency_cycles = [4, 4]\n";
  }
  // A top `top` giving each event in 16-bit words on `word` with valid/ready (word_valid,
  // word_ready) and its drop count on `overflows`: the bundled receiver (4 words deep) inside,
  // its event taken from it as `take` says, and `body` for the rest; its ports as
  // two_word_description() names them.
  static std::string two_word_top(const std::string& top, const std::string& regs, const std::string& take,
                                  const std::string& body) {
    return "module " + top + R"( (
    input  wire        clk_i, rst_ni, req_i, contention_i, word_ready,
    input  wire [15:0] addr_i,
    output wire        ack_o, word_valid,
    output wire [15:0] word,
    output wire [31:0] overflows);
  wire valid, flag;
  wire [31:0] ts;
  wire [15:0] addr;
)" + regs + "  wire take = " + take + ";\n" +
           edited(bundled_instance({{"evt_valid_o", "valid"}, {"evt_ready_i", "take"}, {"evt_ts_o", "ts"}, {"evt_addr_o", "addr"},
                                    {"evt_flags_o", "flag"}}, 16, 4),
                  ".overflows_o()", ".overflows_o(overflows)") +
           body + "endmodule\n";
  }
  // Its description: an event of two words, the flag and address in the first, the stamp's low 16
  // bits in the second, and `more` roles.
  static std::string two_word_description(const std::string& top, std::map<std::string, std::string> more = {}) {
    more.insert({{"valid", "\"word_valid\""},
                 {"ready", "\"word_ready\""},
                 {"out_addr", R"({ port = "word[9:0]", word = 0 })"},
                 {"flags", R"({ port = "word[15]", word = 0 })"},
                 {"timestamp", R"({ port = "word", word = 1 })"},
                 {"overflow_count", "\"overflows\""}});
    return edited(around_bundled(top, R"({ port = "rst_ni", active = "low" })", more), "timestamp_bits = 32\n",
                  "timestamp_bits = 16\nevent_words = 2\n");
  }
  // The description at `path` passes the quick plan (`cases` cases), proves every property, and
  // its exported testbench prints PASS in Icarus.
  void expect_proved_and_exported(const std::string& path, std::size_t cases) {
    const Outcome o = verify("'" + path + "' --formal --export-tb tb");
    const nlohmann::json r = report();
    expect_pass(o, r, cases);
    ASSERT_TRUE(r["formal"].is_array());
    for (const auto& v : r["formal"]) EXPECT_EQ(v["verdict"], "proved") << v.dump();
    EXPECT_EQ(last_line((dir_ / "tb").string(), "iverilog -g2005 -o sim -c tb_files.f && vvp -n sim").rfind("PASS", 0), 0u);
  }
  // `text`, written as `name`, is refused: exit 2, with `needle` in its one line.
  void expect_refused(const std::string& name, const std::string& text, const std::string& needle) {
    write(name, text);
    const Outcome o = verify(name + " --out refused");
    EXPECT_EQ(o.status, 2) << o.err;
    EXPECT_NE(o.err.find(needle), std::string::npos) << o.err;
  }
  // `text` with its first `from` replaced by `to`; a failure of the test when it has none.
  static std::string edited(std::string text, const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    if (at == std::string::npos) {
      ADD_FAILURE() << "no '" << from << "' in:\n" << text;
      return text;
    }
    return text.replace(at, from.size(), to);
  }
  // A run with --formal and --export-tb tb: no property failed, the stamp rule among them, and the
  // exported testbench prints PASS in Icarus.
  void expect_stamps_proved_and_exported(const nlohmann::json& r) const {
    ASSERT_TRUE(r["formal"].is_array());
    bool stamp_checked = false;
    for (const auto& v : r["formal"]) {
      EXPECT_NE(v["verdict"], "failed") << v.dump();
      stamp_checked = stamp_checked || v["property"] == "stamp_rule";
    }
    EXPECT_TRUE(stamp_checked);
    EXPECT_EQ(last_line((dir_ / "tb").string(), "iverilog -g2005 -o sim -c tb_files.f && vvp -n sim").rfind("PASS", 0), 0u);
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

// An input the description leaves alone is held at 0, and the run says which: the bundled
// receiver's external stamp input, unused while its own counter stamps, passes and is named.
TEST_F(VerifyTest, InputsTheDescriptionLeavesAloneAreNamedAsHeldAtZero) {
  std::string description = edited(slurp(kRtl + "/aer_receiver.toml"), "ts_i = 0\n", "");
  for (const char* f : {"aer_receiver.v", "aer_req_sync.v", "aer_timestamp.v", "aer_fifo.v"}) {
    description = edited(description, "\"" + std::string(f) + "\"", "\"" + kRtl + "/" + f + "\"");
  }
  write("no_ts.toml", description);
  const Outcome o = verify("no_ts.toml");
  expect_pass(o, report());
  EXPECT_NE(o.err.find("aesim verify: input ts_i held at 0 throughout (no role, not in [inputs])"), std::string::npos) << o.err;
  const nlohmann::json notes = report()["notes"];
  EXPECT_TRUE(std::any_of(notes.begin(), notes.end(), [](const nlohmann::json& n) {
    return n.get<std::string>().find("input ts_i held at 0") != std::string::npos;
  })) << notes.dump();
  // Named in [inputs], it is not.
  EXPECT_EQ(verify(kRtl + "/aer_receiver.toml --out named").err.find("held at 0"), std::string::npos);
}

// Verilator spells some legal Verilog names otherwise in C++ (a double underscore, a '$', a C++
// keyword, an escaped identifier): the description names the ports as the Verilog does, and an
// escaped name that no role takes is left alone.
TEST_F(VerifyTest, PortsVerilatorRenamesInCppAreNamedAsTheVerilogNamesThem) {
  write("odd_names.v", R"(module odd_names (
    input  wire        clk__i, rst_ni, req$i,
    input  wire [15:0] addr_i,
    input  wire        contention_i, evt_ready_i, \mode.select ,
    output wire        switch, evt_valid_o, evt_flags_o,
    output wire [31:0] evt_ts_o,
    output wire [15:0] evt_addr_o,
    output wire [6:0]  \fifo.count );
)" + bundled_instance({{"clk_i", "clk__i"}, {"req_i", "req$i"}, {"ack_o", "switch"}, {"ts_external_i", "\\mode.select "}, {"fifo_count_o", "\\fifo.count "}}) + R"(endmodule
)");
  const std::string description = around_bundled("odd_names", R"({ port = "rst_ni", active = "low" })",
      {{"clk", R"("clk__i")"}, {"req", R"("req$i")"}, {"ack", R"("switch")"}});
  write("odd_names.toml", description);
  const Outcome o = verify("odd_names.toml");
  expect_pass(o, report());
  EXPECT_NE(o.err.find("input mode.select held at 0"), std::string::npos) << o.err;
  // A name that starts with '$' is a system task's, not a port's.
  expect_refused("dollar.toml", edited(description, "req = \"req$i\"", "req = \"$req\""),
                 "ports.req: '$req' is not a plain Verilog identifier");
  // An inverted line written as an expression: the error says how a polarity is written.
  expect_refused("inverted.toml", edited(description, "req = \"req$i\"", "req = \"!req$i\""),
                 "ports.req: '!req$i' is not a plain Verilog identifier (a line active low is { port = \"req$i\", active = \"low\" })");
}

// Sources that hold what yosys cannot parse (a debug package's string function, which Verilator
// takes): `--formal` stops with yosys's line and names `[formal] sources`; given the sources
// without that file, the proof reads them instead, says so, and proves the bundled receiver.
TEST_F(VerifyTest, TheProofReadsFormalSourcesWhereYosysCannotReadTheSources) {
  write("rx_names_pkg.sv", "package rx_names_pkg;\n  function automatic string state_name(input int s);\n"
                           "    return (s != 0) ? \"busy\" : \"idle\";\n  endfunction\nendpackage\n");
  std::string rtl;
  for (const char* f : {"aer_receiver.v", "aer_req_sync.v", "aer_timestamp.v", "aer_fifo.v"}) rtl += ", \"" + kRtl + "/" + f + "\"";
  const std::string bundled = slurp(kRtl + "/aer_receiver.toml");
  const std::string listed = "sources = [\"aer_receiver.v\", \"aer_req_sync.v\", \"aer_timestamp.v\", \"aer_fifo.v\"]";
  const std::string with_package = edited(bundled, listed, "sources = [\"rx_names_pkg.sv\"" + rtl + "]");
  write("package.toml", with_package);
  const Outcome refused = verify("package.toml --formal --formal-seconds 1 --out refused");
  EXPECT_EQ(refused.status, 2) << refused.err;
  EXPECT_NE(refused.err.find("yosys: rx_names_pkg.sv:2"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("[formal] sources"), std::string::npos) << refused.err;

  write("formal_sources.toml", edited(with_package, "unsynchronised_outputs = [\"idle_o\"]\n",
                                      "unsynchronised_outputs = [\"idle_o\"]\nsources = [" + rtl.substr(2) + "]\n"));
  const Outcome proved = verify("formal_sources.toml --formal --formal-seconds 1 --out proved");
  EXPECT_EQ(proved.status, 0) << proved.err;
  const nlohmann::json r = report("proved");
  EXPECT_TRUE(r["passed"].get<bool>());
  ASSERT_EQ(r["formal"].size(), 12u) << r.dump();
  for (const auto& v : r["formal"]) EXPECT_NE(v["verdict"], "failed") << v.dump();
  EXPECT_NE(r["formal_run"]["notes"].dump().find("the proof read [formal] sources in place of sources"), std::string::npos)
      << r["formal_run"].dump();
  // A VHDL file is no source for yosys.
  write("x.vhd", "entity x is end x;\n");
  expect_refused("vhdl.toml", edited(with_package, "unsynchronised_outputs = [\"idle_o\"]\n",
                                     "unsynchronised_outputs = [\"idle_o\"]\nsources = [\"x.vhd\"]\n"),
                 "formal.sources[0]: yosys reads Verilog or SystemVerilog here");
}

// Req and Ack named active low (the third receiver's aer_req_n, aer_ack_n) but described at the
// default level: the run fails, rightly, and the hint names the key that says so.
TEST_F(VerifyTest, AHandshakeNamedActiveLowButDescribedHighIsHinted) {
  for (const char* f : {"pkt_rx.sv", "pkt_rx_pkg.sv"}) fs::copy_file(kThird + "/" + f, dir_ / f);
  const std::string own = slurp(kThird + "/pkt_rx.toml");
  write("high.toml", edited(edited(own, "req = { port = \"aer_req_n\", active = \"low\" }", "req = \"aer_req_n\""),
                            "ack = { port = \"aer_ack_n\", active = \"low\" }", "ack = \"aer_ack_n\""));
  const Outcome o = verify("high.toml --out high");
  EXPECT_EQ(o.status, 1) << o.err;
  const nlohmann::json first = report("high")["first_failure"];
  EXPECT_NE(first.value("hint", "").find("req port aer_req_n is named as active low but described active high: "
                                         "req = { port = \"aer_req_n\", active = \"low\" }"),
            std::string::npos)
      << first.dump();
  EXPECT_NE(o.out.find("hint: req port aer_req_n"), std::string::npos) << o.out;
}

// A clock as datasheets and timing constraints give it: a frequency with its unit, a plain number
// of hertz, or a period; a stamp's tick as a number of seconds. The same receiver at 50 MHz passes
// with the same cycles and transactions whichever way it is written; a period of no time is
// refused naming the key.
TEST_F(VerifyTest, AClockIsAFrequencyOrAPeriodAndPlainNumbersAreInTheKeysUnit) {
  const std::string bundled = bundled_description_elsewhere();
  write("hz.toml", bundled);
  ASSERT_EQ(verify("hz.toml --out hz").status, 0);
  const nlohmann::json reference = report("hz");
  for (const auto& [name, clock, tick] : {std::tuple<const char*, const char*, const char*>{"number", "50e6", "1e-6"},
                                         {"period", "\"20 ns\"", "\"1us\""}}) {
    const std::string text = edited(edited(bundled, "clock = \"50MHz\"", std::string("clock = ") + clock),
                                    "timestamp_tick = \"1us\"", std::string("timestamp_tick = ") + tick);
    write(std::string(name) + ".toml", text);
    const Outcome o = verify(std::string(name) + ".toml --out " + name);
    ASSERT_EQ(o.status, 0) << name << ": " << o.err;
    const nlohmann::json r = report(name);
    EXPECT_TRUE(r["passed"].get<bool>()) << name;
    EXPECT_EQ(r["receiver_cycles"], reference["receiver_cycles"]) << name;
    EXPECT_EQ(r["beats_checked"], reference["beats_checked"]) << name;
    EXPECT_EQ(r["transactions"], reference["transactions"]) << name;
  }
  expect_refused("zero.toml", edited(bundled, "clock = \"50MHz\"", "clock = \"0 s\""), "clock: a period of 0 s");
  expect_refused("word.toml", edited(bundled, "clock = \"50MHz\"", "clock = \"fast\""),
                 "receiver description 'word.toml': clock: not a number (got 'fast')");
}

// Parameters and defines as TOML users write them: a string that reads as a Verilog integer
// ("16", "16'd16", "'hFF", "8'b1010_1010", "-3") is that number, passed on in decimal (the string
// "16" passed as a string made a 16-bit port 12,598 bits wide); a float as it is; any other
// string stays a string. A run with ADDR_WIDTH = "16" passes as with 16.
TEST_F(VerifyTest, ParametersWrittenAsStringsOfNumbersAreNumbers) {
  const std::string bundled = bundled_description_elsewhere();
  write("strings.toml", edited(bundled, "ADDR_WIDTH = 16, TS_WIDTH = 32, DEPTH = 64",
                               "ADDR_WIDTH = \"16\", TS_WIDTH = \"32'd32\", DEPTH = \"'h40\""));
  const ReceiverDescription d = read_receiver_description((dir_ / "strings.toml").string());
  EXPECT_EQ(d.parameters.at("ADDR_WIDTH"), "16");
  EXPECT_EQ(d.parameters.at("TS_WIDTH"), "32");
  EXPECT_EQ(d.parameters.at("DEPTH"), "64");
  const Outcome o = verify("strings.toml --out strings");
  EXPECT_EQ(o.status, 0) << o.err;
  EXPECT_TRUE(report("strings")["passed"].get<bool>());
  write("kinds.toml", edited(bundled, "parameters = {",
                             "defines = { BITS = \"8'b1010_1010\", NEG = \"-3\", FILE = \"mem.hex\", GAIN = 2.5, "
                             "BIG = \"64'hFFFF_FFFF_FFFF_FFFF\", HUGE = \"65'h1_0000_0000_0000_0000\" }\nparameters = {"));
  const ReceiverDescription k = read_receiver_description((dir_ / "kinds.toml").string());
  EXPECT_EQ(k.defines.at("BITS"), "170");
  EXPECT_EQ(k.defines.at("NEG"), "-3");
  EXPECT_EQ(k.defines.at("FILE"), "\"mem.hex\"");
  EXPECT_EQ(k.defines.at("GAIN"), "2.5");
  EXPECT_EQ(k.defines.at("BIG"), "18446744073709551615");
  // Past 64 bits it is no number aesim works out: the string as written.
  EXPECT_EQ(k.defines.at("HUGE"), "\"65'h1_0000_0000_0000_0000\"");
  // An input held at a value takes the same literals; a negative one or a float is refused.
  write("held.toml", edited(bundled, "prescale_i = 50 ", "prescale_i = \"8'd50\" "));
  EXPECT_EQ(read_receiver_description((dir_ / "held.toml").string()).inputs.at("prescale_i"), 50u);
  expect_refused("negative.toml", edited(bundled, "prescale_i = 50 ", "prescale_i = \"-50\" "),
                 "inputs.prescale_i: expected a non-negative integer");
}

// A project's file list (files.f, as verilator -F reads it) among the sources stands for what it
// names, in its place: paths from the list's own folder, a nested -F list, +incdir+ and +define+,
// comments of all three kinds, $VAR from the environment. The receiver passes as with its files
// named one by one; a switch aesim cannot pass on, an unset variable and a list naming itself
// are refused naming the list and its line.
TEST_F(VerifyTest, AFileListStandsForTheFilesItNames) {
  fs::create_directories(dir_ / "proj/rtl");
  fs::create_directories(dir_ / "proj/inc");
  for (const char* f : {"aer_receiver.v", "aer_req_sync.v", "aer_timestamp.v", "aer_fifo.v"}) {
    fs::copy_file(kRtl + "/" + f, dir_ / "proj/rtl" / f);
  }
  write("proj/rtl/core.f", "// the receiver's parts\naer_req_sync.v  aer_timestamp.v  /* two on a line */\naer_fifo.v # the FIFO\n");
  write("proj/files.f", "+incdir+inc\n+define+AESIM_LISTED+WIDTH=16\n-F rtl/core.f\n${AESIM_TEST_RX}/rtl/aer_receiver.v\n");
  const std::string own = slurp(kRtl + "/aer_receiver.toml");
  const std::string listed = "sources = [\"aer_receiver.v\", \"aer_req_sync.v\", \"aer_timestamp.v\", \"aer_fifo.v\"]";
  write("proj/rx.toml", edited(own, listed, "sources = [\"files.f\"]"));
  ::setenv("AESIM_TEST_RX", (dir_ / "proj").c_str(), 1);
  const ReceiverDescription d = read_receiver_description((dir_ / "proj/rx.toml").string());
  const std::string rtl = (dir_ / "proj/rtl/").string();
  EXPECT_EQ(d.sources, (std::vector<std::string>{rtl + "aer_req_sync.v", rtl + "aer_timestamp.v", rtl + "aer_fifo.v",
                                                 rtl + "aer_receiver.v"}));
  EXPECT_EQ(d.include_dirs, std::vector<std::string>{(dir_ / "proj/inc").string()});
  EXPECT_EQ(d.defines.at("AESIM_LISTED"), "");
  EXPECT_EQ(d.defines.at("WIDTH"), "16");
  const Outcome o = verify("proj/rx.toml --out listed");
  expect_pass(o, report("listed"));
  write("proj/files.f", "+incdir+inc\n-F rtl/core.f\n-y lib\n");
  expect_refused("proj/switch.toml", edited(own, listed, "sources = [\"files.f\"]"),
                 "file list '" + (dir_ / "proj/files.f").string() + "' line 3: '-y' asks the simulator");
  write("proj/files.f", "$AESIM_NO_SUCH_VARIABLE/rtl/aer_receiver.v\n");
  expect_refused("proj/unset.toml", edited(own, listed, "sources = [\"files.f\"]"),
                 "line 1: environment variable AESIM_NO_SUCH_VARIABLE is not set");
  write("proj/files.f", "-f files.f\n");
  expect_refused("proj/loop.toml", edited(own, listed, "sources = [\"files.f\"]"), "a loop of lists");
  ::unsetenv("AESIM_TEST_RX");
}

// Sources as a Makefile lists them, a folder's files by a pattern: every match, in byte order,
// each file once where it first comes, so a package named ahead of the pattern stays ahead of the
// module that imports it (pkt_rx.sv sorts before pkt_rx_pkg.sv). A pattern that matches nothing,
// or has wildcards in its folder, is refused naming the entry.
TEST_F(VerifyTest, SourcesTakeAFoldersFilesByAPatternEachOnceInOrder) {
  fs::create_directories(dir_ / "rtl");
  for (const char* f : {"pkt_rx.sv", "pkt_rx_pkg.sv"}) fs::copy_file(kThird + "/" + f, dir_ / "rtl" / f);
  const std::string own = slurp(kThird + "/pkt_rx.toml");
  const std::string listed = "sources = [\"pkt_rx_pkg.sv\", \"pkt_rx.sv\"]";
  write("pattern.toml", edited(own, listed, "sources = [\"rtl/pkt_rx_pkg.sv\", \"rtl/*.sv\"]"));
  const Outcome o = verify("pattern.toml --out pattern");
  expect_pass(o, report("pattern"));
  expect_refused("none.toml", edited(own, listed, "sources = [\"rtl/pkt_rx_pkg.sv\", \"rtl/*.vhd\"]"),
                 "sources[1]: '" + (dir_ / "rtl/*.vhd").string() + "' matches no file");
  expect_refused("folders.toml", edited(own, listed, "sources = [\"*/pkt_rx*.sv\"]"),
                 "sources[0]: '*/pkt_rx*.sv': wildcards name files of one folder");
}

// An output to an FX2-style slave FIFO: a word written at an edge where the active-low strobe is
// low and the active-high full flag is not up, and a bus whose contention line is active low.
// Described with those polarities it passes, here and in the exported testbench; described as
// active high, each of the three fails.
TEST_F(VerifyTest, ValidReadyAndContentionTakeTheLevelTheyAreActiveAt) {
  write("fx2_top.v", R"(module fx2_top (
    input  wire        clk_i, rst_ni, req_i, contention_n, full,
    input  wire [15:0] addr_i,
    output wire        ack_o, slwr_n, evt_flags_o,
    output wire [31:0] evt_ts_o,
    output wire [15:0] evt_addr_o);
  wire valid;
)" + bundled_instance({{"contention_i", "!contention_n"}, {"evt_valid_o", "valid"}, {"evt_ready_i", "!full"}}, 16, 8) +
                             R"(  assign slwr_n = !valid;
endmodule
)");
  const std::string description = around_bundled("fx2_top", R"({ port = "rst_ni", active = "low" })",
                                                  {{"contention", R"({ port = "contention_n", active = "low" })"},
                                                   {"valid", R"({ port = "slwr_n", active = "low" })"},
                                                   {"ready", R"({ port = "full", active = "low" })"}});
  write("fx2.toml", description);
  const Outcome o = verify("fx2.toml --export-tb tb");
  expect_pass(o, report());
  EXPECT_EQ(last_line((dir_ / "tb").string(), "iverilog -g2005 -o sim -c tb_files.f && vvp -n sim").rfind("PASS", 0), 0u);
  const std::map<std::string, std::string> active_high = {
      {"valid", "valid = \"slwr_n\""}, {"ready", "ready = \"full\""}, {"contention", "contention = \"contention_n\""}};
  for (const auto& [role, plain] : active_high) {
    const std::string line = role == "valid"   ? "valid = { port = \"slwr_n\", active = \"low\" }"
                             : role == "ready" ? "ready = { port = \"full\", active = \"low\" }"
                                               : "contention = { port = \"contention_n\", active = \"low\" }";
    write(role + ".toml", edited(description, line, plain));
    const Outcome wrong = verify(role + ".toml --out " + role);
    EXPECT_EQ(wrong.status, 1) << role << ": " << wrong.err;
  }
  // A valid read at the wrong level gives beats where no transaction waited, and the run says
  // where to look.
  const nlohmann::json first = report("valid")["first_failure"];
  EXPECT_EQ(first["check"], "beat") << first.dump();
  EXPECT_NE(first.value("hint", "").find("a valid active low"), std::string::npos) << first.dump();
  // Only the one-bit roles have a level.
  expect_refused("addr.toml", edited(description, "addr = \"addr_i\"", "addr = { port = \"addr_i\", active = \"low\" }"),
                 "ports.addr: only req, ack, valid, ready, contention and special take { port, active }");
}

// An event given in two output words, as a 16-bit USB FIFO takes it (the bundled receiver behind a
// serialiser: the flag and address, then the stamp's low 16 bits), is described with
// `event_words = 2` and the word each field comes from. It passes in simulation, in the proof and
// in Icarus; taken as one word an event, its stamp words are events no transaction gave.
TEST_F(VerifyTest, AnEventOfSeveralOutputWordsIsGatheredFromThem) {
  write("two_word_top.v", two_word_top("two_word_top", "  reg second;  // the event's stamp word is the one offered\n",
                                       "word_ready && second", R"(  assign word_valid = valid;
  assign word = second ? ts[15:0] : {flag, addr[14:0]};
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) second <= 1'b0;
    else if (valid && word_ready) second <= !second;
)"));
  const std::string description = two_word_description("two_word_top");
  write("words.toml", description);
  const Outcome o = verify("words.toml --formal --formal-seconds 1 --export-tb tb --out words");
  ASSERT_EQ(o.status, 0) << o.out << o.err;
  const nlohmann::json r = report("words");
  expect_pass(o, r);
  ASSERT_TRUE(r["formal"].is_array());
  for (const auto& v : r["formal"]) EXPECT_NE(v["verdict"], "failed") << v.dump();
  EXPECT_EQ(last_line((dir_ / "tb").string(), "iverilog -g2005 -o sim -c tb_files.f && vvp -n sim").rfind("PASS", 0), 0u);

  // Each word an event: the stamp words are beats no transaction gave.
  std::string one = edited(description, "event_words = 2\n", "");
  one = edited(edited(one, "timestamp = { port = \"word\", word = 1 }\n", ""), "timestamp_tick = \"1us\"\ntimestamp_bits = 16\n", "");
  write("one.toml", one);
  const Outcome single = verify("one.toml --out one");
  EXPECT_EQ(single.status, 1) << single.err;
  EXPECT_EQ(report("one")["first_failure"]["check"], "beat") << report("one")["first_failure"].dump();

  expect_refused("third.toml", edited(description, "word = 1 }", "word = 2 }"),
                 "ports.timestamp.word: word 2 of an event of 2 (behaviour.event_words; the first is 0)");
}

// Between events of two words the serialiser sends, every 256 cycles, a marker in an event's shape
// (bit 14 of its first word set, its count in the second), as USB AER monitors send a timestamp
// wrap: `special = { port = "word[14]", word = 0 }` makes each such event no event, counted as
// special beats, in the simulation, the proof and Icarus. A mark on words of their own (no `word`)
// would leave the marker's second word to start an event: the run fails.
TEST_F(VerifyTest, AnEventMarkedOnOneOfItsWordsIsNoEvent) {
  write("mark_top.v", two_word_top("mark_top", R"(  reg second, marking, pending;
  reg [7:0] cycles;
  reg [15:0] markers;
)",
                                   "word_ready && second && !marking", R"(  assign word_valid = marking || valid;
  assign word = marking ? (second ? markers : 16'h4000) : (second ? ts[15:0] : {flag, 1'b0, addr[13:0]});
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) begin
      {second, marking, pending} <= 3'b000;
      cycles <= 8'd0;
      markers <= 16'd0;
    end else begin
      cycles <= cycles + 1'b1;
      if (cycles == 8'hff) pending <= 1'b1;
      if (!marking && !second && pending && !valid) marking <= 1'b1;
      if (word_valid && word_ready) begin
        second <= !second;
        if (marking && second) begin
          marking <= 1'b0;
          pending <= 1'b0;
          markers <= markers + 1'b1;
        end
      end
    end
)"));
  const std::string description =
      two_word_description("mark_top", {{"special", R"({ port = "word[14]", word = 0 })"}});
  write("mark.toml", description);
  const Outcome o = verify("mark.toml --formal --formal-seconds 1 --export-tb tb --out mark");
  ASSERT_EQ(o.status, 0) << o.out << o.err;
  const nlohmann::json r = report("mark");
  expect_pass(o, r);
  EXPECT_GT(r["special_beats"].get<double>(), 100) << r.dump();
  ASSERT_TRUE(r["formal"].is_array());
  for (const auto& v : r["formal"]) EXPECT_NE(v["verdict"], "failed") << v.dump();
  EXPECT_EQ(last_line((dir_ / "tb").string(), "iverilog -g2005 -o sim -c tb_files.f && vvp -n sim").rfind("PASS", 0), 0u);

  write("own.toml", edited(description, R"(special = { port = "word[14]", word = 0 })", R"(special = "word[14]")"));
  EXPECT_EQ(verify("own.toml --out own").status, 1);
}

// A top whose output side has a clock port of its own (here a register stage on `out_clk` between
// the bundled receiver and the consumer) lists both clocks, `clk = ["clk_i", "out_clk"]`: both are
// driven by the receiver's clock, in the simulation, the proof and the exported testbench. With
// only `clk_i` named, `out_clk` is held at 0, as the run says, and no beat ever comes out.
TEST_F(VerifyTest, ASecondClockPortRunsOnTheReceiversClock) {
  write("two_clk_top.v", R"(module two_clk_top (
    input  wire        clk_i, out_clk, rst_ni, req_i, contention_i, evt_ready_i,
    input  wire [15:0] addr_i,
    output wire        ack_o,
    output reg         evt_valid_o, evt_flags_o,
    output reg  [31:0] evt_ts_o,
    output reg  [15:0] evt_addr_o);
  wire valid, flag;
  wire [31:0] ts;
  wire [15:0] addr;
  wire take = !evt_valid_o || evt_ready_i;
)" + bundled_instance({{"evt_valid_o", "valid"}, {"evt_ready_i", "take"}, {"evt_ts_o", "ts"}, {"evt_addr_o", "addr"},
                       {"evt_flags_o", "flag"}}) +
                                 R"(  always @(posedge out_clk or negedge rst_ni)
    if (!rst_ni) begin
      evt_valid_o <= 1'b0;
      evt_flags_o <= 1'b0;
      evt_ts_o    <= 32'd0;
      evt_addr_o  <= 16'd0;
    end else if (take) begin
      evt_valid_o <= valid;
      evt_flags_o <= flag;
      evt_ts_o    <= ts;
      evt_addr_o  <= addr;
    end
endmodule
)");
  const std::string description =
      around_bundled("two_clk_top", R"({ port = "rst_ni", active = "low" })", {{"clk", R"(["clk_i", "out_clk"])"}});
  write("two.toml", description);
  const Outcome o = verify("two.toml --formal --formal-seconds 5 --export-tb tb --out two");
  const nlohmann::json r = report("two");
  expect_pass(o, r);
  ASSERT_TRUE(r["formal"].is_array());
  for (const auto& v : r["formal"]) EXPECT_NE(v["verdict"], "failed") << v.dump();
  EXPECT_EQ(last_line((dir_ / "tb").string(), "iverilog -g2005 -o sim -c tb_files.f && vvp -n sim").rfind("PASS", 0), 0u);

  write("one.toml", edited(description, R"(clk = ["clk_i", "out_clk"])", R"(clk = "clk_i")"));
  const Outcome one = verify("one.toml --out one");
  EXPECT_EQ(one.status, 1) << one.err;
  EXPECT_NE((one.out + one.err).find("out_clk held at 0"), std::string::npos) << one.out << one.err;
  EXPECT_EQ(report("one")["beats_checked"], 0) << report("one")["first_failure"].dump();

  expect_refused("both.toml", edited(description, R"(clk = ["clk_i", "out_clk"])", R"(clk = ["clk_i", "req_i"])"),
                 "ports.clk: port req_i is also ports.req");
}

// A top with its own two-flop reset synchroniser comes out of reset two edges after aesim lets
// go: a Req held through the reset is answered two edges late. Described with release_cycles = 2
// it passes, with the stamps counted from its own release; with 1 or none it fails there.
TEST_F(VerifyTest, ADesignsOwnResetSynchroniserIsDescribedByItsReleaseCycles) {
  write("rs_top.v", R"(module rs_top (
    input  wire        clk_i, rst_ni, req_i, contention_i, evt_ready_i,
    input  wire [15:0] addr_i,
    output wire        ack_o, evt_valid_o, evt_flags_o,
    output wire [31:0] evt_ts_o,
    output wire [15:0] evt_addr_o);
  reg [1:0] rst_q;
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) rst_q <= 2'b00;
    else rst_q <= {rst_q[0], 1'b1};
)" + bundled_instance({{"rst_ni", "rst_q[1]"}}) + R"(endmodule
)");
  const std::string description = around_bundled("rs_top", R"({ port = "rst_ni", active = "low", release_cycles = 2 })");
  write("rs.toml", description);
  const Outcome o = verify("rs.toml");
  expect_pass(o, report());
  // The bundled receiver's rule, counted from the design's own release.
  EXPECT_NE((o.out + o.err).find("stamps: ticks since reset at edge 4 after Req rose or the edge Ack rose\n"), std::string::npos)
      << o.out << o.err;
  for (const char* release : {", release_cycles = 1", ""}) {
    write("short.toml", edited(description, ", release_cycles = 2", release));
    const Outcome early = verify("short.toml --out short");
    EXPECT_EQ(early.status, 1) << release << ": " << early.err;
    EXPECT_NE((early.out + early.err).find("hint: a design that passes its reset through flops of its own"), std::string::npos)
        << early.out << early.err;
    EXPECT_EQ(report("short")["first_failure"]["check"], "ack_rise_latency") << report("short")["first_failure"].dump();
    EXPECT_EQ(report("short")["first_failure"]["case"], "req_through_reset") << report("short")["first_failure"].dump();
  }
  expect_refused("absurd.toml", edited(description, "release_cycles = 2", "release_cycles = 65"),
                 "reset.release_cycles: expected an integer from 0 to 64");
}

// A design with the bus's row and column on inputs of their own and the event's column, row and
// stamp halves on outputs of their own (as DVS interfaces give them) is described by joining them
// as Verilog does: it passes, here and in the exported testbench, and with the column and row
// joined the other way round it fails at the first beat.
TEST_F(VerifyTest, RolesJoinPortsAsVerilogJoinsThem) {
  write("xy_top.v", R"(module xy_top (
    input  wire        clk_i, rst_ni, req_i, contention_i, evt_ready_i,
    input  wire [4:0]  row, col,
    output wire        ack_o, evt_valid_o, evt_flags_o,
    output wire [4:0]  evt_x, evt_y,
    output wire [15:0] ts_hi, ts_lo);
  wire [9:0] addr_out;
)" + bundled_instance({{"addr_i", "{row, col}"}, {"evt_ts_o", "{ts_hi, ts_lo}"}, {"evt_addr_o", "addr_out"}}, 10, 8) +
                            R"(  assign {evt_y, evt_x} = addr_out;
endmodule
)");
  const std::string description = around_bundled("xy_top", R"({ port = "rst_ni", active = "low" })",
                                                  {{"addr", R"("{row, col}")"},
                                                   {"out_addr", R"("{evt_y, evt_x}")"},
                                                   {"timestamp", R"("{ts_hi, ts_lo}")"}});
  write("xy.toml", description);
  const Outcome o = verify("xy.toml --export-tb tb");
  expect_pass(o, report());
  EXPECT_EQ(last_line((dir_ / "tb").string(), "iverilog -g2005 -o sim -c tb_files.f && vvp -n sim").rfind("PASS", 0), 0u);
  write("swapped.toml", edited(description, "out_addr = \"{evt_y, evt_x}\"", "out_addr = \"{evt_x, evt_y}\""));
  EXPECT_EQ(verify("swapped.toml --out swapped").status, 1);
  EXPECT_EQ(report("swapped")["first_failure"]["check"], "beat") << report("swapped")["first_failure"].dump();
  // Only the multi-bit roles join ports, each port once.
  const std::vector<std::pair<std::string, std::string>> bad = {
      {edited(description, "valid = \"evt_valid_o\"", "valid = \"{evt_valid_o, evt_flags_o}\""),
       "ports.valid: '{evt_valid_o, evt_flags_o}': only addr, out_addr, timestamp and time_in may join ports"},
      {edited(description, "out_addr = \"{evt_y, evt_x}\"", "out_addr = \"{evt_y, evt_y}\""), "port evt_y is also ports.out_addr"},
      {edited(description, "out_addr = \"{evt_y, evt_x}\"", "out_addr = \"{evt_y, }\""), "an empty part in the joined ports"}};
  for (std::size_t i = 0; i < bad.size(); ++i) expect_refused(fmt::format("bad{}.toml", i), bad[i].first, bad[i].second);
}

// An output stream with in-band markers (a word with bit 15 set every 256 cycles, where an event
// stream puts its time markers) passes with the marker bit described as `special`: such beats are
// no transaction's, and are counted; described without it, the first marker is a beat no
// transaction gave.
TEST_F(VerifyTest, BeatsThatSayTheyAreNoEventAreNotMatchedToTransactions) {
  write("mk_top.v", R"(module mk_top (
    input  wire        clk_i, rst_ni, req_i, contention_i,
    input  wire [15:0] addr_i,
    output wire        ack_o, valid, evt_flags_o,
    output wire [15:0] word,
    output wire [31:0] evt_ts_o);
  wire evt_valid;
  wire [15:0] evt_addr;
)" + bundled_instance({{"evt_valid_o", "evt_valid"}, {"evt_ready_i", "1'b1"}, {"evt_addr_o", "evt_addr"}}) +
                           R"(  reg [7:0] cycles;
  reg [6:0] markers;
  reg pending;
  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) begin
      cycles <= 0;
      markers <= 0;
      pending <= 1'b0;
    end else begin
      cycles <= cycles + 1'b1;
      if (cycles == 8'hff) pending <= 1'b1;
      else if (pending && !evt_valid) begin
        pending <= 1'b0;
        markers <= markers + 1'b1;
      end
    end
  assign valid = evt_valid || pending;
  assign word = evt_valid ? {1'b0, evt_addr[14:0]} : {1'b1, 8'd0, markers};
endmodule
)");
  std::string description =
      around_bundled("mk_top", R"({ port = "rst_ni", active = "low" })",
                     {{"valid", R"("valid")"}, {"out_addr", R"("word[9:0]")"}, {"special", R"("word[15]")"}});
  description = edited(description, "ready = \"evt_ready_i\"\n", "");
  write("mk.toml", description);
  const Outcome o = verify("mk.toml --export-tb tb");
  const nlohmann::json r = report();
  expect_pass(o, r, 12);
  EXPECT_GT(r["special_beats"].get<double>(), 1000) << r.dump();
  EXPECT_EQ(last_line((dir_ / "tb").string(), "iverilog -g2005 -o sim -c tb_files.f && vvp -n sim").rfind("PASS", 0), 0u);
  write("plain.toml", edited(description, "special = \"word[15]\"\n", ""));
  EXPECT_EQ(verify("plain.toml --out plain").status, 1);
  EXPECT_EQ(report("plain")["first_failure"]["check"], "beat") << report("plain")["first_failure"].dump();
}

// An output whose strobe toggles for each word (a two-phase strobe, the word held until the next)
// is described with beat = "change": it passes, here and in the exported testbench; taken as a
// level held for each word ("rise") every other word is missed, and the beat after one is not the
// transaction it should be.
TEST_F(VerifyTest, AStrobeThatTogglesForEachWordIsABeatAtEachChange) {
  write("tog_top.v", R"(module tog_top (
    input  wire        clk_i, rst_ni, req_i, contention_i,
    input  wire [15:0] addr_i,
    output wire        ack_o,
    output reg         toggle,
    output reg  [15:0] word,
    output reg  [31:0] stamp);
  wire evt_valid;
  wire [15:0] evt_addr;
  wire [31:0] evt_ts;
)" + bundled_instance({{"evt_valid_o", "evt_valid"}, {"evt_ready_i", "1'b1"}, {"evt_addr_o", "evt_addr"},
                       {"evt_ts_o", "evt_ts"}, {"evt_flags_o", ""}}) +
                            R"(  always @(posedge clk_i or negedge rst_ni)
    if (!rst_ni) begin
      toggle <= 1'b0;
      word <= 16'd0;
      stamp <= 32'd0;
    end else if (evt_valid) begin
      toggle <= !toggle;
      word <= evt_addr;
      stamp <= evt_ts;
    end
endmodule
)");
  std::string description = around_bundled("tog_top", R"({ port = "rst_ni", active = "low" })",
                                           {{"valid", R"({ port = "toggle", beat = "change" })"},
                                            {"out_addr", R"("word")"},
                                            {"timestamp", R"("stamp")"}});
  description = edited(edited(description, "ready = \"evt_ready_i\"\n", ""), "flags = \"evt_flags_o\"\n", "");
  write("tog.toml", description);
  const Outcome o = verify("tog.toml --export-tb tb");
  expect_pass(o, report(), 12);
  EXPECT_EQ(last_line((dir_ / "tb").string(), "iverilog -g2005 -o sim -c tb_files.f && vvp -n sim").rfind("PASS", 0), 0u);
  write("rise.toml", edited(description, "beat = \"change\"", "beat = \"rise\""));
  EXPECT_EQ(verify("rise.toml --out rise").status, 1);
  EXPECT_EQ(report("rise")["first_failure"]["check"], "beat") << report("rise")["first_failure"].dump();
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
  // Described as discarding collisions, it fails at the collision case, and the run says where
  // to look.
  write("ae_rx_alt.v", slurp(kSecond + "/ae_rx_alt.v"));
  write("discard.toml", edited(slurp(kSecond + "/ae_rx_alt.toml"), "collisions = \"flag\"", "collisions = \"discard\""));
  EXPECT_EQ(verify("discard.toml --out discard").status, 1);
  const nlohmann::json first = report("discard")["first_failure"];
  EXPECT_EQ(first["case"], "collision") << first.dump();
  EXPECT_NE(first.value("hint", "").find("behaviour.collisions (now \"discard\""), std::string::npos) << first.dump();
}

// A receiver whose synchronizer has no glitch filter takes the directed case's glitch (half a
// period across an edge) for a request: it answers with an Ack after Req fell and outputs the
// glitch's address. That is allowed (a glitch breaks the bus protocol, not the receiver's); the
// filtered receiver ignores it. Both then deliver the next event.
TEST_F(VerifyTest, AReceiverWithoutAGlitchFilterMayAnswerTheGlitch) {
  const std::string unheld = edited(slurp(kSecond + "/ae_rx_alt.v"), "wire seen_high = sync[2] & held;",
                                    "wire seen_high = sync[2];");
  write("ae_rx_alt.v", edited(unheld, "wire seen_low = ~sync[2] & ~held;", "wire seen_low = ~sync[2];"));
  write("rx.toml", edited(slurp(kSecond + "/ae_rx_alt.toml"), "ack_latency_cycles = [5, 5]",
                          "ack_latency_cycles = [4, 4]"));
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

// The styles of the receivers met in the wild, all in the third receiver: a first synchroniser flop
// without reset (a Req held through reset is seen at once after it, fewer edges after the release
// than the lower latency bound), a valid that follows the synchronised Req (the beat taken on the
// edge Ack rises), active-low Req and Ack, the address and stamp as fields of a 72-bit packet,
// SystemVerilog with a package and an enum. No false failure on any seed, for it and the other two.
TEST_F(VerifyTest, EveryReceiverPassesOnEverySeed) {
  const char* scale = std::getenv("AESIM_COSIM_SCALE");  // scripts/test --full: the full plan too
  std::vector<std::string> plans = {"quick"};
  if (scale && *scale) plans.push_back("full");
  for (const std::string& receiver : {kThird + "/pkt_rx.toml", kRtl + "/aer_receiver.toml", kSecond + "/ae_rx_alt.toml"}) {
    for (const std::string& plan : plans) {
      for (int seed = 1; seed <= 5; ++seed) {
        const std::string out = "seed" + std::to_string(seed);
        const Outcome o = verify(receiver + " --plan " + plan + " --seed " + std::to_string(seed) + " --out " + out);
        ASSERT_EQ(o.status, 0) << receiver << " " << plan << " seed " << seed << ": " << o.out;
        EXPECT_EQ(report(out)["passed"], true);
      }
    }
  }
  ASSERT_EQ(verify(kThird + "/pkt_rx.toml --out third").status, 0);
  const nlohmann::json third = report("third");
  expect_pass(Outcome{0, "", ""}, third);
  ASSERT_EQ(third["cases"][4]["name"], "req_through_reset");
  EXPECT_EQ(third["cases"][4]["beats_checked"], 1);
  EXPECT_EQ(third["stamp_rule"], "ticks since reset at edge 1 after Req rose");
}

TEST_F(VerifyTest, AReceiverWithoutReadyOrStampIsVerifiedWithoutThem) {
  const Outcome o = verify(kThird + "/pkt_rx_free.toml");
  expect_pass(o, report(), 12);
  const nlohmann::json r = report();
  EXPECT_TRUE(r["stamp_rule"].is_null());
  ASSERT_EQ(r["notes"].size(), 1u);
  EXPECT_NE(r["notes"][0].get<std::string>().find("no ready port"), std::string::npos);
  EXPECT_NE(o.err.find("long_backpressure, full_output, full_at_pointer_offsets are left out"), std::string::npos)
      << o.err;
  for (const auto& c : r["cases"]) {
    if (c["kind"] == "scene") {
      EXPECT_NE(c["name"].get<std::string>().find("ready=1 "), std::string::npos) << c["name"];
    }
  }
}

// The fourth receiver (tests/rtl/fourth_receiver/arx.sv): an active-low asynchronous reset, a
// 4-word FIFO that drops when full and counts the drops in 8 bits. The quick plan drops over 255
// transactions, so its counter passes whether it wraps or saturates. Its FIFO's fullness told
// from the pointers' difference taken at 32 bits, a classic width slip, is full only before the
// pointers first wrap: a fill from reset passes it, the case that fills after the pointers moved
// on catches it in simulation, as the proof does.
TEST_F(VerifyTest, AFifoFullOnlyBeforeItsPointersWrapIsCaughtAndANarrowDropCounterMayWrapOrSaturate) {
  const std::string dir = std::string(AESIM_SOURCE_DIR) + "/tests/rtl/fourth_receiver";
  const Outcome wraps = verify("'" + dir + "/arx.toml' --out wraps");
  ASSERT_EQ(wraps.status, 0) << wraps.out << wraps.err;
  expect_pass(wraps, report("wraps"));
  EXPECT_GT(report("wraps")["drops_accounted"].get<double>(), 255);

  const std::string description = slurp(dir + "/arx.toml");
  write("arx.sv", slurp(dir + "/arx.sv"));
  ASSERT_NE(description.find("[ports]"), std::string::npos);
  std::string saturating = description;
  saturating.insert(saturating.find("[ports]"), "parameters = { SATURATE = 1 }\n\n");
  write("saturating.toml", saturating);
  const Outcome saturates = verify("saturating.toml --out saturating");
  ASSERT_EQ(saturates.status, 0) << saturates.out << saturates.err;
  expect_pass(saturates, report("saturating"));

  // A counter that stops one short of its largest value neither wraps nor saturates.
  write("arx.sv", edited(slurp(dir + "/arx.sv"), "dropped_o == 8'hFF", "dropped_o == 8'hFE"));
  const Outcome short_counter = verify("saturating.toml --out short");
  EXPECT_EQ(short_counter.status, 1) << short_counter.err;
  EXPECT_EQ(report("short")["first_failure"]["check"], "overflow_count");
  EXPECT_NE((short_counter.out + short_counter.err).find("(modulo 2^8 as the port is wide, or 255 held at its largest)"),
            std::string::npos)
      << short_counter.out << short_counter.err;

  write("arx.sv", edited(slurp(dir + "/arx.sv"),
                         "wire full = wr[DEPTH_LOG] != rd[DEPTH_LOG] && wr[DEPTH_LOG-1:0] == rd[DEPTH_LOG-1:0];",
                         "wire full = (wr - rd) == (1 << DEPTH_LOG);"));
  write("arx.toml", description);
  const Outcome slip = verify("arx.toml --out slip");
  EXPECT_EQ(slip.status, 1) << slip.err;
  const nlohmann::json r = report("slip");
  for (const auto& c : r["cases"]) {
    if (c["name"] != "full_at_pointer_offsets") {
      EXPECT_EQ(c["failures"], 0) << c.dump();
      EXPECT_TRUE(c["first_failure"].is_null()) << c.dump();
    } else {
      // The case's own first failure is the run's, and its line says which check at which cycle.
      EXPECT_EQ(c["first_failure"]["check"], "stalled_output") << c.dump();
      EXPECT_EQ(c["first_failure"]["cycle"], r["first_failure"]["cycle"]) << c.dump();
      const std::string line = "FAIL (stalled_output at cycle " + c["first_failure"]["cycle"].dump() + ")";
      EXPECT_NE(slip.err.find(line), std::string::npos) << line << "\n" << slip.err;
    }
  }
  EXPECT_EQ(r["first_failure"]["check"], "stalled_output") << r["first_failure"].dump();
  EXPECT_NE((slip.out + slip.err).find("in case 'full_at_pointer_offsets'"), std::string::npos) << slip.out << slip.err;
}

// A receiver whose valid is a data-ready flag held for the whole handshake (tests/rtl/
// level_valid_receiver): described with `beat = "rise"` it passes in simulation, in the proof and
// in its exported testbench under Icarus; described as a one-cycle valid, each word is counted
// once an edge it is held (beats no transaction gave); a copy whose flag never falls gives only
// its first word, and fails for the words it lost. With a ready port "rise" is refused.
TEST_F(VerifyTest, AValidHeldForEachWordGivesOneBeatOnItsRise) {
  const std::string dir = std::string(AESIM_SOURCE_DIR) + "/tests/rtl/level_valid_receiver";
  expect_proved_and_exported(dir + "/lvr.toml", 12);

  const std::string description = slurp(dir + "/lvr.toml");
  write("lvr.v", slurp(dir + "/lvr.v"));
  write("level.toml",
        edited(description, "valid = { port = \"word_ready\", beat = \"rise\" }", "valid = \"word_ready\""));
  const Outcome high = verify("level.toml --formal --out high");
  EXPECT_EQ(high.status, 1) << high.err;
  const nlohmann::json h = report("high");
  EXPECT_EQ(h["first_failure"]["check"], "beat") << h["first_failure"].dump();
  EXPECT_NE((high.out + high.err).find("expected no beat (no transaction is waiting)"), std::string::npos) << high.out;
  // Three edges a word (from its capture to Ack's fall) against one transaction each.
  EXPECT_GT(h["beats_checked"].get<double>(), 2.5 * h["transactions"].get<double>());
  int invented = 0;
  for (const auto& v : h["formal"]) {
    if (v["property"] != "no_invented_beat") continue;
    EXPECT_EQ(v["verdict"], "failed") << v.dump();
    ++invented;
  }
  EXPECT_EQ(invented, 1);

  write("lvr.v", edited(slurp(dir + "/lvr.v"), "        ack        <= 1'b0;\n        word_ready <= 1'b0;\n",
                        "        ack        <= 1'b0;\n"));
  write("lvr.toml", description);
  const Outcome held = verify("lvr.toml --out held");
  EXPECT_EQ(held.status, 1) << held.err;
  EXPECT_EQ(report("held")["first_failure"]["check"], "lost") << report("held")["first_failure"].dump();
  EXPECT_LT(report("held")["beats_checked"].get<double>(), 100);

  std::string with_ready = description;
  with_ready.replace(with_ready.find("out_addr = "), 0, "ready = \"rdy\"\n");
  write("ready.toml", with_ready);
  const Outcome refused = verify("ready.toml --out ready");
  EXPECT_EQ(refused.status, 2);
  EXPECT_NE(refused.err.find("ports.valid.beat: \"rise\" and \"change\" are for an output without back-pressure"), std::string::npos)
      << refused.err;
  EXPECT_FALSE(fs::exists(dir_ / "ready"));
}

// A receiver that takes the address after Req falls (tests/rtl/late_sampling_receiver) is right
// behind a sender that holds it until Ack falls, wrong behind the imager's pixels, which let go of
// it with Req. Described with `[bus] address_held = "until_ack_falls"` it passes in simulation, in
// the proof and in its exported testbench under Icarus; without it the first beat carries the
// released lines (0), a hint names the key, the proof's beat_in_order fails and the replay of its
// counterexample reports the same beat. The bundled receiver, which takes the address while Req is
// high, passes behind either sender.
TEST_F(VerifyTest, ASenderThatHoldsTheAddressUntilAckFallsIsDescribedByAddressHeld) {
  const std::string dir = std::string(AESIM_SOURCE_DIR) + "/tests/rtl/late_sampling_receiver";
  expect_proved_and_exported(dir + "/lsr.toml", 12);

  const std::string description = slurp(dir + "/lsr.toml");
  write("lsr.v", slurp(dir + "/lsr.v"));
  write("early.toml", edited(description, "[bus]\naddress_held = \"until_ack_falls\"\n", ""));
  const Outcome early = verify("early.toml --formal --out early");
  EXPECT_EQ(early.status, 1) << early.err;
  const nlohmann::json early_report = report("early");
  const nlohmann::json first = early_report["first_failure"];
  EXPECT_EQ(first["check"], "beat") << first.dump();
  EXPECT_NE(first.value("observed", "").find("address 0x0,"), std::string::npos) << first.dump();
  EXPECT_NE(first.value("hint", "").find("address_held = \"until_ack_falls\""), std::string::npos) << first.dump();
  int order = 0;
  for (const auto& v : early_report["formal"]) {
    if (v["property"] != "beat_in_order") {
      EXPECT_EQ(v["verdict"], "proved") << v.dump();
      continue;
    }
    EXPECT_EQ(v["verdict"], "failed") << v.dump();
    ++order;
  }
  EXPECT_EQ(order, 1);
  EXPECT_NE(early.out.find("replaying the counterexample's inputs, reports beat at cycle"), std::string::npos) << early.out;

  write("bundled.toml", slurp(kRtl + "/aer_receiver.toml") + "\n[bus]\naddress_held = \"until_ack_falls\"\n");
  for (const char* f : {"aer_receiver.v", "aer_req_sync.v", "aer_timestamp.v", "aer_fifo.v"}) write(f, slurp(kRtl + "/" + f));
  const Outcome bundled = verify("bundled.toml --out bundled");
  expect_pass(bundled, report("bundled"));

  expect_refused("later.toml", edited(description, "\"until_ack_falls\"", "\"later\""),
                 "bus.address_held: must be \"until_ack_rises\" (the imager's pixels) or \"until_ack_falls\"");
  expect_refused("unknown.toml", edited(description, "address_held", "address_hold"), "bus.address_hold: unknown key (address_held, handshake)");
}

// A design that stamps from a time it is given (the bundled receiver with ts_external_i set takes
// ts_i) has that port described as `time_in`: aesim drives it, after each edge, with the ticks
// completed since the reset by the stamps' own rule. Read at an edge, ts_i carries the ticks up to
// the edge before, where the receiver's own counter gives those up to that edge: the stamps pass
// with the rule one edge earlier. So they do in the proof (to the depth 2 s allow) and in Icarus.
// Held at 0 instead, every stamp is 0 and the first one past a tick fails.
TEST_F(VerifyTest, ATimeTheDesignReadsIsDrivenWithTheTicksSinceReset) {
  for (const char* f : {"aer_receiver.v", "aer_req_sync.v", "aer_timestamp.v", "aer_fifo.v"}) write(f, slurp(kRtl + "/" + f));
  // 8-bit stamps of two cycles, so that the proof sees several ticks and wraps within its depth.
  std::string own = edited(slurp(kRtl + "/aer_receiver.toml"), "TS_WIDTH = 32,", "TS_WIDTH = 8,");
  own = edited(edited(own, "prescale_i = 50 ", "prescale_i = 2 "), "timestamp_bits = 32", "timestamp_bits = 8");
  own = edited(own, "timestamp_tick = \"1us\"", "timestamp_tick = \"40ns\"");
  write("own.toml", own);
  ASSERT_EQ(verify("own.toml --out own").status, 0);
  EXPECT_EQ(report("own")["stamp_rule"], "ticks since reset at edge 4 after Req rose or the edge Ack rose");

  const std::string given = edited(edited(own, "ts_external_i = 0 ", "ts_external_i = 1 "), "ts_i = 0\n", "");
  write("given.toml", edited(given, "overflow_count = \"overflows_o\"\n", "overflow_count = \"overflows_o\"\ntime_in = \"ts_i\"\n"));
  const Outcome o = verify("given.toml --formal --formal-seconds 2 --export-tb tb --out given");
  const nlohmann::json r = report("given");
  expect_pass(o, r);
  EXPECT_EQ(r["stamp_rule"], "ticks since reset at edge 3 after Req rose or the edge Ack rose - 1");
  expect_stamps_proved_and_exported(r);

  write("held.toml", edited(given, "ts_external_i = 1 ", "ts_external_i = 1\nts_i = 0\n"));
  const Outcome held = verify("held.toml --out held");
  EXPECT_EQ(held.status, 1) << held.err;
  EXPECT_EQ(report("held")["first_failure"]["check"], "timestamp") << report("held")["first_failure"].dump();
  // Left out of the description, ts_i is held at 0 all the same, and the hint names it.
  write("absent.toml", given);
  EXPECT_EQ(verify("absent.toml --out absent").status, 1);
  const nlohmann::json absent = report("absent")["first_failure"];
  EXPECT_EQ(absent["check"], "timestamp") << absent.dump();
  EXPECT_NE(absent.value("hint", "").find("input ts_i is held at 0: a time the design stamps from is named time_in"),
            std::string::npos)
      << absent.dump();

  // The time's tick is the stamps' (timestamp_tick), needed without a timestamp port too.
  expect_refused("untimed.toml", edited(level_valid_receiver(), "out_addr = \"word\"\n", "out_addr = \"word\"\ntime_in = \"now\"\n"),
                 "behaviour.timestamp_tick");
}

// A receiver that stamps as it ends the handshake (EventReceiver-style: the address word first,
// the stamp when Ack falls, as an FPGA event receiver writes a FIFO) follows one rule all the same:
// ticks at the edge Ack fell. Its beats come after that edge, so the rule is found there, checked
// by the proof too and by the exported testbench; a stamp a tick late for odd addresses fails.
TEST_F(VerifyTest, AStampTakenAsAckFallsIsHeldToThatEdge) {
  const std::string rtl = R"(`default_nettype none
module fall_stamp (
    input  wire        clk,
    input  wire        rst,
    input  wire        req,
    input  wire [9:0]  addr,
    output reg         ack,
    output reg  [9:0]  word_addr,
    output reg  [15:0] word_ts,
    output reg         word_valid
);
  reg r1, r2;
  reg [9:0] taken;
  reg [15:0] now;
  always @(posedge clk) begin
    if (rst) begin
      {r1, r2, ack, word_valid} <= 4'd0;
      {taken, word_addr} <= 20'd0;
      {now, word_ts} <= 32'd0;
    end else begin
      {r2, r1} <= {r1, req};
      now <= now + 16'd1;
      word_valid <= 1'b0;
      if (r2 && !ack) begin
        taken <= addr;
        ack <= 1'b1;
      end else if (!r2 && ack) begin
        ack <= 1'b0;
        word_addr <= taken;
        word_ts <= now LATE;
        word_valid <= 1'b1;
      end
    end
  end
endmodule
`default_nettype wire
)";
  write("fall_stamp.v", edited(rtl, " LATE", ""));
  const std::string toml =
      "top = \"fall_stamp\"\nsources = [\"fall_stamp.v\"]\nclock = \"50MHz\"\nreset = { port = \"rst\", active = \"high\" }\n"
      "[ports]\nclk = \"clk\"\nreq = \"req\"\nack = \"ack\"\naddr = \"addr\"\nvalid = \"word_valid\"\n"
      "out_addr = \"word_addr\"\ntimestamp = \"word_ts\"\n"
      "[behaviour]\ncollisions = \"pass\"\nack_latency_cycles = [3, 3]\ntimestamp_tick = \"20ns\"\ntimestamp_bits = 16\n";
  write("fall.toml", toml);
  const Outcome o = verify("fall.toml --formal --formal-seconds 2 --export-tb tb --out fall");
  const nlohmann::json r = report("fall");
  expect_pass(o, r, 12);  // no ready port: the three back-pressure cases are left out
  EXPECT_EQ(r["stamp_rule"], "ticks since reset at the edge Ack fell - 1") << r.dump();
  // Two synchroniser flops, then Ack at the next edge: 3 edges each way, as the RTL reads.
  EXPECT_EQ(r["ack_latency_observed"], nlohmann::json::parse(R"({"rise": [3, 3], "fall": [3, 3]})")) << r.dump();
  EXPECT_NE(o.out.find("Ack latency seen: rise 3 edges (without a full output), fall 3 edges; described 3 to 3"),
            std::string::npos) << o.out;
  expect_stamps_proved_and_exported(r);

  write("fall_stamp.v", edited(rtl, " LATE", " + {15'd0, taken[0]}"));
  const Outcome late = verify("fall.toml --out late");
  EXPECT_EQ(late.status, 1) << late.err;
  EXPECT_EQ(report("late")["first_failure"]["check"], "timestamp") << report("late")["first_failure"].dump();
}

// A SystemVerilog receiver whose bus is an interface port: Verilator takes no interface on the top,
// so the error says to put the design under a top of plain ports, as does a role naming an
// interface's member; under such a top (the one docs/verify.md shows) it passes.
TEST_F(VerifyTest, AnInterfacePortOnTheTopIsToldToBeWrappedAndPassesWrapped) {
  write("ifrx.sv", R"(interface aer_if;
  logic req, ack;
  logic [9:0] addr;
  modport rx (input req, input addr, output ack);
endinterface
module ifrx (input logic clk, input logic rst_n, aer_if.rx bus, output logic [9:0] word, output logic valid);
  logic r1, r2;
  always_ff @(posedge clk) begin
    if (!rst_n) begin
      {r1, r2, bus.ack, valid} <= '0;
      word <= '0;
    end else begin
      {r2, r1} <= {r1, bus.req};
      valid <= 1'b0;
      if (r2 && !bus.ack) begin
        bus.ack <= 1'b1;
        word <= bus.addr;
        valid <= 1'b1;
      end else if (!r2 && bus.ack) begin
        bus.ack <= 1'b0;
      end
    end
  end
endmodule
)");
  write("ifrx_top.sv", R"(module ifrx_top (input logic clk, input logic rst_n, input logic req, input logic [9:0] addr,
                 output logic ack, output logic [9:0] word, output logic valid);
  aer_if bus ();
  assign bus.req = req;
  assign bus.addr = addr;
  assign ack = bus.ack;
  ifrx dut (.clk(clk), .rst_n(rst_n), .bus(bus.rx), .word(word), .valid(valid));
endmodule
)");
  const std::string toml = "top = \"ifrx\"\nsources = [\"ifrx.sv\"]\nclock = \"50MHz\"\nreset = { port = \"rst_n\", active = \"low\" }\n"
                           "[ports]\nclk = \"clk\"\nreq = \"req\"\nack = \"ack\"\naddr = \"addr\"\nvalid = \"valid\"\n"
                           "out_addr = \"word\"\n[behaviour]\ncollisions = \"pass\"\nack_latency_cycles = [3, 3]\n";
  write("ifrx.toml", toml);
  const Outcome bare = verify("ifrx.toml --out bare");
  EXPECT_EQ(bare.status, 2) << bare.err;
  EXPECT_NE(bare.err.find("Interfaced port on top level module; aesim drives a top's plain ports"), std::string::npos) << bare.err;
  expect_refused("member.toml", edited(toml, "req = \"req\"", "req = \"bus.req\""), "a member of an interface port?");

  write("top.toml", edited(edited(toml, "top = \"ifrx\"", "top = \"ifrx_top\""), "[\"ifrx.sv\"]", "[\"ifrx.sv\", \"ifrx_top.sv\"]"));
  const Outcome wrapped = verify("top.toml --out wrapped");
  expect_pass(wrapped, report("wrapped"), 12);  // no ready port: the three back-pressure cases are left out
}

// A receiver that reads a table by a relative name ($readmemh("map.hex"), beside its sources) finds
// it when aesim verify is run from another folder: the RTL runs in the description's folder, where
// the description's own paths start. Without the table it fails, and a note names the folder.
TEST_F(VerifyTest, AFileTheRtlReadsByARelativeNameIsTheOneBesideTheDescription) {
  std::filesystem::create_directories(dir_ / "rx");
  write("rx/lutrx.v", R"(module lutrx (input wire clk, input wire rst_n, input wire req, input wire [9:0] addr,
              output reg ack, output reg [9:0] word, output reg valid);
  reg [9:0] map [0:1023];
  initial $readmemh("map.hex", map);
  reg r1, r2;
  always @(posedge clk) begin
    if (!rst_n) begin
      {r1, r2, ack, valid} <= 4'd0;
      word <= 10'd0;
    end else begin
      {r2, r1} <= {r1, req};
      valid <= 1'b0;
      if (r2 && !ack) begin
        ack <= 1'b1;
        word <= map[addr];
        valid <= 1'b1;
      end else if (!r2 && ack) begin
        ack <= 1'b0;
      end
    end
  end
endmodule
)");
  std::string table;
  for (int a = 0; a < 1024; ++a) table += fmt::format("{:03x}\n", a);
  write("rx/map.hex", table);
  write("rx/lutrx.toml", "top = \"lutrx\"\nsources = [\"lutrx.v\"]\nclock = \"50MHz\"\nreset = { port = \"rst_n\", active = \"low\" }\n"
                         "[ports]\nclk = \"clk\"\nreq = \"req\"\nack = \"ack\"\naddr = \"addr\"\nvalid = \"valid\"\n"
                         "out_addr = \"word\"\n[behaviour]\ncollisions = \"pass\"\nack_latency_cycles = [3, 3]\n");
  const Outcome o = verify("rx/lutrx.toml --out found");
  expect_pass(o, report("found"), 12);

  std::filesystem::remove(dir_ / "rx" / "map.hex");
  const Outcome lost = verify("rx/lutrx.toml --out lost");
  EXPECT_EQ(lost.status, 1) << lost.err;
  EXPECT_NE(lost.out.find("note: the RTL's $readmem found no file (lost/rtl_output.log); the RTL reads relative names from "
                          "the description's folder, " + (dir_ / "rx").string()),
            std::string::npos)
      << lost.out;
}

// A two-phase receiver (each edge of Req an event, Ack toggled once) described with the default,
// four-phase handshake gives a second beat, of the released lines, as Req falls: it fails there,
// and the hint names the handshake key rather than valid's level. A level-held valid described as a
// plain one repeats its word instead, and keeps the hint about valid.
TEST_F(VerifyTest, ATwoPhaseReceiverIsToldItMeetsAFourPhaseBus) {
  write("tpr.v", R"(`default_nettype none
module tpr (
    input  wire       clk,
    input  wire       rst,
    input  wire       req,
    input  wire [9:0] addr,
    output reg        ack,
    output reg  [9:0] word,
    output reg        word_valid
);
  reg r1, r2, r3;
  always @(posedge clk) begin
    if (rst) begin
      {r1, r2, r3, ack, word_valid} <= 5'd0;
      word <= 10'd0;
    end else begin
      {r3, r2, r1} <= {r2, r1, req};
      word_valid <= r2 != r3;
      if (r2 != r3) begin
        word <= addr;
        ack  <= !ack;
      end
    end
  end
endmodule
`default_nettype wire
)");
  write("tpr.toml", "top = \"tpr\"\nsources = [\"tpr.v\"]\nclock = \"50MHz\"\nreset = { port = \"rst\", active = \"high\" }\n"
                    "[ports]\nclk = \"clk\"\nreq = \"req\"\nack = \"ack\"\naddr = \"addr\"\nvalid = \"word_valid\"\n"
                    "out_addr = \"word\"\n[behaviour]\ncollisions = \"pass\"\nack_latency_cycles = [3, 3]\n");
  const Outcome o = verify("tpr.toml --out two");
  EXPECT_EQ(o.status, 1) << o.err;
  const nlohmann::json first = report("two")["first_failure"];
  EXPECT_EQ(first["check"], "beat") << first.dump();
  EXPECT_EQ(first["observed"], "address 0x0, stamp 0, flag 0") << first.dump();
  EXPECT_NE(first.value("hint", "").find("[bus] handshake = \"two_phase\""), std::string::npos) << first.dump();

  write("level.toml", edited(level_valid_receiver(), "valid = { port = \"word_ready\", beat = \"rise\" }", "valid = \"word_ready\""));
  EXPECT_EQ(verify("level.toml --out level").status, 1);
  const nlohmann::json level = report("level")["first_failure"];
  EXPECT_EQ(level["check"], "beat") << level.dump();
  EXPECT_NE(level.value("hint", "").find("one held for each word (beat = \"rise\")"), std::string::npos) << level.dump();
}

// A two-phase receiver (tests/rtl/two_phase_receiver: each change of Req an event, answered by one
// change of Ack, back-pressure holding Ack) described with `[bus] handshake = "two_phase"` passes
// in simulation (the glitch case left out: no change of Req is withdrawn), in the proof and in its
// exported testbench under Icarus, with its stamps at the edge before Ack changes and its latency
// seen from change to change. Its lines resting high (IDLE = 1) pass described active low, and
// fail as reset ends described active high (the hint names the resting level); a copy that changes
// Ack again once its beat is taken fails at that change in simulation, in the proof, whose
// counterexample the driver replays to the same check, and in its exported testbench; the bundled four-phase receiver described
// as two-phase fails its second transaction of a burst (it answers the Req that fell with its Ack's
// fall, and gives no beat for it).
TEST_F(VerifyTest, ATwoPhaseLinkIsVerifiedChangeByChange) {
  const std::string dir = std::string(AESIM_SOURCE_DIR) + "/tests/rtl/two_phase_receiver";
  expect_proved_and_exported(dir + "/tpr.toml", 14);
  const nlohmann::json r = report();
  EXPECT_EQ(r["receiver"]["handshake"], "two_phase");
  EXPECT_EQ(r["stamp_rule"], "ticks since reset at the edge Ack changed - 1");
  EXPECT_EQ(r["ack_latency_observed"]["rise"], nlohmann::json::parse("[3, 3]"));
  EXPECT_TRUE(r["ack_latency_observed"]["fall"].is_null());
  bool glitch_note = false;
  for (const auto& n : r["notes"]) glitch_note = glitch_note || n.get<std::string>().find("two-phase") != std::string::npos;
  EXPECT_TRUE(glitch_note) << r["notes"].dump();
  for (const auto& c : r["cases"]) EXPECT_NE(c["name"], "req_glitch");

  const std::string description = slurp(dir + "/tpr.toml");
  write("tpr.v", slurp(dir + "/tpr.v"));
  const std::string low = edited(edited(description, "req = \"req\"", "req = { port = \"req\", active = \"low\" }"),
                                 "ack = \"ack\"", "ack = { port = \"ack\", active = \"low\" }");
  write("high_rest.toml", edited(low, "sources = [\"tpr.v\"]\n", "sources = [\"tpr.v\"]\nparameters = { IDLE = 1 }\n"));
  const Outcome high_rest = verify("high_rest.toml --out high_rest");
  expect_pass(high_rest, report("high_rest"), 14);
  write("low_rest.toml", low);
  EXPECT_EQ(verify("low_rest.toml --out low_rest").status, 1);
  const nlohmann::json rest = report("low_rest")["first_failure"];
  EXPECT_EQ(rest["check"], "reset") << rest.dump();
  EXPECT_NE(rest.value("hint", "").find("rest at their inactive level after reset"), std::string::npos) << rest.dump();

  write("twice.v", edited(slurp(dir + "/tpr.v"), "if (take) ack <= req_sync;",
                          "if (take) ack <= req_sync;\n      else if (out_valid && out_ready) ack <= !ack;"));
  write("twice.toml", edited(description, "sources = [\"tpr.v\"]", "sources = [\"twice.v\"]"));
  const Outcome twice = verify("twice.toml --formal --formal-seconds 5 --export-tb twice_tb --out twice");
  EXPECT_EQ(twice.status, 1) << twice.err;
  const nlohmann::json t = report("twice");
  EXPECT_EQ(t["first_failure"]["check"], "ack_without_req") << t["first_failure"].dump();
  EXPECT_EQ(t["first_failure"]["case"], "single_event") << t["first_failure"].dump();
  bool changes_failed = false;
  for (const auto& v : t["formal"]) changes_failed = changes_failed || (v["property"] == "ack_changes_with_req" && v["verdict"] == "failed");
  EXPECT_TRUE(changes_failed) << t["formal"].dump();
  EXPECT_NE(twice.out.find("replaying the counterexample's inputs, reports ack_without_req"), std::string::npos) << twice.out;
  EXPECT_EQ(last_line((dir_ / "twice_tb").string(), "iverilog -g2005 -o sim -c tb_files.f && vvp -n sim").rfind("FAIL", 0), 0u);
  EXPECT_NE(slurp(dir_ / "twice_tb" / "run.txt").find("Ack changed with no change of Req waiting"), std::string::npos);

  write("bundled.toml", slurp(kRtl + "/aer_receiver.toml") + "\n[bus]\nhandshake = \"two_phase\"\n");
  for (const char* f : {"aer_receiver.v", "aer_req_sync.v", "aer_timestamp.v", "aer_fifo.v"}) write(f, slurp(kRtl + "/" + f));
  EXPECT_EQ(verify("bundled.toml --out bundled").status, 1);
  const nlohmann::json four = report("bundled")["first_failure"];
  EXPECT_EQ(four["check"], "beat") << four.dump();
  EXPECT_EQ(four["case"], "back_to_back") << four.dump();

  expect_refused("three.toml", edited(description, "\"two_phase\"", "\"three_phase\""),
                 "bus.handshake: must be \"four_phase\" (the imager's bus) or \"two_phase\"");
  expect_refused("falls.toml", edited(description, "[bus]\n", "[bus]\naddress_held = \"until_ack_falls\"\n"),
                 "bus.address_held: a two-phase Ack does not fall");
}

// An output on a clock of its own (`clk = ["clk", { port = "out_clk", clock = "30MHz" }]`): its
// beats are taken at that clock's edges and its consumer driven in its time. The two-clock
// receiver of the tests (tests/rtl/two_clock_receiver: a toggle-handshake mailbox between a 50 MHz
// input and a 30 MHz output) passes in simulation, in the proof (which runs both sides on one
// clock, and says so) and in its exported testbench, whose second clock Icarus runs at the run's
// phase. A crossing that passes a one-cycle strobe from the 50 MHz side without a handshake passes
// with both sides on one clock and at 50 MHz of its own, and loses events at 30 MHz, where the
// slower clock can miss the strobe; over a range of output clocks each case runs at its own.
TEST_F(VerifyTest, AnOutputOnAClockOfItsOwnIsTakenAtItsEdges) {
  const std::string dir = std::string(AESIM_SOURCE_DIR) + "/tests/rtl/two_clock_receiver";
  const Outcome own = verify("'" + dir + "/tcr.toml' --formal --export-tb tb");
  const nlohmann::json r = report();
  expect_pass(own, r, 15);
  EXPECT_EQ(r["receiver"]["out_clock"], nlohmann::json::parse(R"({"port": "out_clk", "hz": 30000000.0})"));
  for (const auto& v : r["formal"]) EXPECT_EQ(v["verdict"], "proved") << v.dump();
  EXPECT_NE(r["formal_run"]["notes"].dump().find("the crossing at its own 30 MHz is simulated only"), std::string::npos)
      << r["formal_run"].dump();
  EXPECT_EQ(last_line((dir_ / "tb").string(), "iverilog -g2005 -o sim -c tb_files.f && vvp -n sim").rfind("PASS", 0), 0u);
  EXPECT_NE(slurp(dir_ / "tb" / "tb.v").find("always @(posedge out_clk)"), std::string::npos);

  write("pcr.v", R"(`default_nettype none
module pcr (
    input  wire       clk,
    input  wire       rst_n,
    input  wire       req,
    input  wire [9:0] addr,
    output reg        ack,
    input  wire       out_clk,
    output reg        out_valid,
    output reg  [9:0] out_addr
);
  reg       req_meta, req_sync, strobe, s1, s2, s3;
  reg [9:0] word;
  always @(posedge clk or negedge rst_n) begin
    if (!rst_n) begin
      {req_meta, req_sync, strobe, ack} <= 4'd0;
      word <= 10'd0;
    end else begin
      req_meta <= req;
      req_sync <= req_meta;
      strobe   <= 1'b0;
      if (req_sync && !ack) begin
        word   <= addr;
        strobe <= 1'b1;
        ack    <= 1'b1;
      end else if (!req_sync && ack) begin
        ack <= 1'b0;
      end
    end
  end
  always @(posedge out_clk or negedge rst_n) begin
    if (!rst_n) begin
      {s1, s2, s3, out_valid} <= 4'd0;
      out_addr <= 10'd0;
    end else begin
      {s3, s2, s1} <= {s2, s1, strobe};
      out_valid <= s2 && !s3;
      if (s2 && !s3) out_addr <= word;
    end
  end
endmodule
`default_nettype wire
)");
  const std::string strobe = "top = \"pcr\"\nsources = [\"pcr.v\"]\nclock = \"50MHz\"\nreset = { port = \"rst_n\", active = \"low\" }\n"
                             "[ports]\nclk = [\"clk\", \"out_clk\"]\nreq = \"req\"\nack = \"ack\"\naddr = \"addr\"\n"
                             "valid = \"out_valid\"\nout_addr = \"out_addr\"\n[behaviour]\ncollisions = \"pass\"\n"
                             "ack_latency_cycles = [3, 3]\n";
  write("one.toml", strobe);
  const Outcome one = verify("one.toml --out one");
  expect_pass(one, report("one"), 12);
  write("same.toml", edited(strobe, "\"out_clk\"]", "{ port = \"out_clk\", clock = \"50MHz\" }]"));
  const Outcome same = verify("same.toml --out same");
  expect_pass(same, report("same"), 12);
  write("slow.toml", edited(strobe, "\"out_clk\"]", "{ port = \"out_clk\", clock = \"30MHz\" }]"));
  const Outcome slow = verify("slow.toml --out slow");
  EXPECT_EQ(slow.status, 1) << slow.err;
  // An event missed is a transaction with no beat: found as such ("lost"), or as the next beat
  // standing where the missed one should ("beat"), whichever comes first.
  const nlohmann::json lost = report("slow");
  const std::string check = lost["first_failure"]["check"];
  EXPECT_TRUE(check == "lost" || check == "beat") << lost["first_failure"].dump();
  EXPECT_LT(lost["beats_checked"].get<double>(), 0.9 * lost["transactions"].get<double>());
  // Over a range of output clocks, each case at its own: every case from 50 MHz up catches the
  // 20 ns strobe, and a range reaching below 50 MHz loses events in its slow cases alone.
  write("fast.toml", edited(strobe, "\"out_clk\"]", "{ port = \"out_clk\", clock = [\"50MHz\", \"200MHz\"] }]"));
  const Outcome fast = verify("fast.toml --out fast");
  expect_pass(fast, report("fast"), 12);
  write("wide.toml", edited(strobe, "\"out_clk\"]", "{ port = \"out_clk\", clock = [\"20MHz\", \"200MHz\"] }]"));
  const Outcome wide_run = verify("wide.toml --out wide");
  EXPECT_EQ(wide_run.status, 1);
  const nlohmann::json wide = report("wide");
  EXPECT_EQ(wide["receiver"]["out_clock"]["hz"], nlohmann::json::parse("[20000000.0, 200000000.0]"));
  int slow_cases = 0;
  for (const auto& c : wide["cases"]) {
    const double hz = c["out_clock_hz"];
    EXPECT_TRUE(hz >= 20e6 && hz <= 200e6) << c.dump();
    if (hz >= 50e6) EXPECT_EQ(c["failures"], 0) << c.dump();
    slow_cases += hz < 50e6;
    // Each case's line says the frequency it ran at.
    EXPECT_NE(wide_run.err.find(fmt::format("(out_clk at {:.1f} MHz)", hz / 1e6)), std::string::npos) << wide_run.err;
  }
  EXPECT_GT(slow_cases, 0);

  const std::string description = slurp(dir + "/tcr.toml");
  write("tcr.v", slurp(dir + "/tcr.v"));
  expect_refused("no_clock.toml", edited(description, ", clock = \"30MHz\" }", " }"), "ports.clk[1].clock: missing");
  expect_refused("two_clocks.toml", edited(description, "clock = \"30MHz\" }]", "clock = \"30MHz\" }, { port = \"x\", clock = \"1MHz\" }]"),
                 "ports.clk[2]: a second clock of its own: the output side has one clock");
  expect_refused("phase.toml", edited(description, "clock = \"30MHz\" }", "clock = \"30MHz\", phase = 1 }"),
                 "ports.clk[1].phase: unknown key (port, clock)");
  expect_refused("own_first.toml", edited(description, "[\"clk\", { port = \"out_clk\", clock = \"30MHz\" }]",
                                          "[{ port = \"out_clk\", clock = \"30MHz\" }, \"clk\"]"),
                 "ports.clk: the first is the receiver's own clock, as its port name (its frequency is `clock`)");
  expect_refused("backwards.toml", edited(description, "clock = \"30MHz\" }", "clock = [\"30MHz\", \"20MHz\"] }"),
                 "ports.clk[1].clock: a range from its lower frequency to its higher");
}

// An output clock's rising and falling edges, and its consumer's changes a quarter period after
// each rise, never fall on an edge of the receiver's clock: at one instant the run takes the
// receiver's edge first and a simulator both at once, so an exported testbench would part from the
// run. Checked by brute force over every alignment the two periods make (the residues repeat after
// half / gcd periods), for receiver clocks whose half period is odd (48 MHz) or even, over ranges
// of output clocks, for many cases; the frequency stays within the range and 0.1 % of the draw.
TEST(OutClockTiming, ItsEdgesAndConsumerNeverMeetTheReceiversEdges) {
  for (const double receiver_hz : {50e6, 48e6, 33.3e6, 100e6}) {
    ReceiverDescription d;
    d.clock_hz = receiver_hz;
    d.out_clock_port = "out_clk";
    d.out_clock_hz = 20e6;
    d.out_clock_hz_max = 200e6;
    const std::uint64_t half = clock_period_ps(d) / 2;
    for (int i = 0; i < 200; ++i) {
      VerifyCase c;
      c.name = "case " + std::to_string(i);
      c.seed = static_cast<std::uint64_t>(1 + i % 7);
      const OutClock o = out_clock_of(d, c);
      ASSERT_EQ(o.period_ps % 4, 0u);
      ASSERT_GE(o.hz, 20e6 * 0.999);
      ASSERT_LE(o.hz, 200e6 * 1.001);
      ASSERT_GT(o.first_rise_ps, 0u);
      ASSERT_LT(o.first_rise_ps, o.period_ps);
      for (std::uint64_t j = 0; j < half; ++j) {
        const std::uint64_t rise = o.first_rise_ps + j * o.period_ps;
        for (const std::uint64_t t : {rise, rise + o.period_ps / 4, rise + o.period_ps / 2}) {
          ASSERT_NE(t % half, 0u) << receiver_hz << " Hz, " << c.name << ": period " << o.period_ps << ", first rise "
                                  << o.first_rise_ps << ", meets at " << t;
        }
        if (j * o.period_ps % half == 0 && j > 0) break;  // every alignment seen
      }
    }
  }
}

// An address port wider than the output's address (spio's AER-to-SpiNNaker mapper takes 16 bits
// and its packet's slice gives 10): the proof drives the addresses both carry, as the bus and the
// simulation do, so a solver's address in the extra bits is no counterexample; a wrong slice
// still fails in both.
TEST_F(VerifyTest, AnAddressPortWiderThanTheOutputIsCheckedOnTheAddressesBothCarry) {
  const std::string wide = edited(level_valid_receiver(), "sources = [\"lvr.v\"]\n",
                                  "sources = [\"lvr.v\"]\nparameters = { AW = 16 }\n");
  write("wide.toml", edited(wide, "out_addr = \"word\"\n", "out_addr = \"word[9:0]\"\n"));
  write("wrong.toml", edited(wide, "out_addr = \"word\"\n", "out_addr = \"word[10:1]\"\n"));
  const Outcome o = verify("wide.toml --plan quick --formal --out wide");
  ASSERT_EQ(o.status, 0) << o.out << o.err;
  const nlohmann::json r = report("wide");
  int order = 0;
  for (const auto& v : r["formal"]) {
    EXPECT_EQ(v["verdict"], "proved") << v.dump();
    order += v["property"] == "beat_in_order";
  }
  EXPECT_EQ(order, 1);
  const Outcome bad = verify("wrong.toml --plan quick --formal --out wrong");
  EXPECT_EQ(bad.status, 1) << bad.err;
  const nlohmann::json w = report("wrong");
  EXPECT_EQ(w["first_failure"]["check"], "beat") << w["first_failure"].dump();
  bool order_failed = false;
  for (const auto& v : w["formal"]) order_failed |= v["property"] == "beat_in_order" && v["verdict"] == "failed";
  EXPECT_TRUE(order_failed) << w["formal"].dump();
}

// A block whose Req its top synchronises (spio's mapper behind its top's spio_spinnaker_link_sync)
// is described with synchroniser_flops = 0: the proof checks no synchroniser and says so.
TEST_F(VerifyTest, ASynchroniserOutsideTheDesignIsSaidAndNotChecked) {
  write("outside.toml", edited(level_valid_receiver(), "ack_latency_cycles = [3, 3]\n",
                               "ack_latency_cycles = [3, 3]\nsynchroniser_flops = 0\n"));
  const Outcome o = verify("outside.toml --plan quick --formal --out outside");
  ASSERT_EQ(o.status, 0) << o.out << o.err;
  const nlohmann::json r = report("outside");
  for (const auto& v : r["formal"]) EXPECT_NE(v["property"], "req_synchronised") << v.dump();
  EXPECT_EQ(r["formal"].size(), 9u);
  EXPECT_NE(o.out.find("formal: 9 properties: 9 proved"), std::string::npos) << o.out;
  EXPECT_NE(o.out.find("formal note: Req is synchronised outside the design (behaviour.synchroniser_flops = 0)"),
            std::string::npos)
      << o.out;
}

// A design without a reset (`reset = "none"`): its registers' initial values are its reset
// state. Every case starts from them, the case that resets mid-run is left out and said so, and
// Ack must be low before the first edge, in simulation and in the proof; a copy that starts with
// Ack high fails both there.
TEST_F(VerifyTest, AReceiverWithoutAResetStartsFromItsInitialValues) {
  const std::string dir = std::string(AESIM_SOURCE_DIR) + "/tests/rtl/no_reset_receiver";
  const Outcome o = verify("'" + dir + "/noreset_rx.toml' --formal");
  const nlohmann::json good = report();
  expect_pass(o, good, 14);
  EXPECT_NE(o.err.find("the receiver has no reset: every case starts from the design's initial values, and the "
                       "cases reset_mid_handshake are left out"),
            std::string::npos)
      << o.err;
  ASSERT_TRUE(good["formal"].is_array());
  for (const auto& v : good["formal"]) EXPECT_EQ(v["verdict"], "proved") << v.dump();

  write("noreset_rx.v",
        edited(slurp(dir + "/noreset_rx.v"), "output reg        ack = 1'b0,", "output reg        ack = 1'b1,"));
  write("noreset_rx.toml", slurp(dir + "/noreset_rx.toml"));
  const Outcome bad = verify("noreset_rx.toml --formal --out high");
  EXPECT_EQ(bad.status, 1) << bad.err;
  const nlohmann::json r = report("high");
  EXPECT_EQ(r["first_failure"]["check"], "reset");
  EXPECT_EQ(r["first_failure"]["cycle"], 0);
  EXPECT_NE((bad.out + bad.err).find("formal failure: ack_low_after_reset (Ack is low at power-up (the design has no reset)): fails at step 0"),
            std::string::npos)
      << bad.out;
}

// A receiver written in VHDL (tests/rtl/vhdl_receiver: the fourth receiver's logic, upper-case
// names, generics, a package in a file of its own, signals named as Verilog's reserved words) is
// synthesised to Verilog by GHDL and verified like any other: it passes, with its generics applied (DEPTH_LOG = 3: the full-output case takes
// the 8 words such a FIFO holds), its description's names matched whatever their case, and its
// exported testbench passes under Icarus on the Verilog GHDL made. A copy with Ack one edge early
// fails; VHDL GHDL cannot read, [formal] parameters, and no GHDL on PATH are one-line errors. Under
// a Verilog top, the VHDL entity it instantiates is converted and the pair passes; a VHDL top with
// Verilog beside it is refused.
TEST_F(VerifyTest, AReceiverInVhdlIsSynthesisedByGhdlAndVerified) {
  const std::string src = std::string(AESIM_SOURCE_DIR) + "/tests/rtl/vhdl_receiver";
  for (const char* f : {"arx_pkg.vhd", "req_sync.vhd", "varx.vhd"}) write(f, slurp(src + "/" + f));
  const std::string description = slurp(src + "/varx.toml");
  write("varx.toml", description);
  const Outcome o = verify("varx.toml --export-tb tb");
  const nlohmann::json r = report();
  expect_pass(o, r, 15);
  EXPECT_NE(o.err.find("aesim verify: the VHDL as GHDL synthesised it: "), std::string::npos) << o.err;
  for (const auto& c : r["cases"]) {
    if (c["name"] == "full_output") {
      EXPECT_EQ(c["beats_checked"], 8) << c.dump();
    }
  }
  const std::string tb = (dir_ / "tb").string();
  EXPECT_EQ(last_line(tb, "iverilog -g2005 -o sim -c tb_files.f && vvp -n sim").rfind("PASS", 0), 0u);
  // The VHDL's signals `config` and `table`, reserved words in Verilog, as escaped identifiers.
  std::istringstream files(slurp(fs::path(tb) / "tb_files.f"));
  std::string converted;
  for (std::string line; std::getline(files, line);) {
    if (line.size() > 2 && line.compare(line.size() - 2, 2, ".v") == 0 && line.find("receiver.v") != std::string::npos) converted = line;
  }
  const std::string verilog = slurp(converted);
  EXPECT_NE(verilog.find("\\config "), std::string::npos) << converted;
  EXPECT_NE(verilog.find("\\table "), std::string::npos) << converted;

  std::string lower_case = description;
  for (const char* name : {"VARX", "RST_N", "CLK", "AER_REQ", "AER_ACK", "AER_ADDR", "AER_COLL", "M_VALID", "M_READY",
                           "M_DATA", "DROPPED"}) {
    std::string l = name;
    for (char& ch : l) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    for (auto at = lower_case.find("\"" + std::string(name)); at != std::string::npos; at = lower_case.find("\"" + std::string(name))) {
      lower_case.replace(at + 1, l.size(), l);
    }
  }
  write("lower.toml", lower_case);
  const Outcome lower = verify("lower.toml --out lower");
  expect_pass(lower, report("lower"), 15);

  // A copy of the receiver in `folder` with one line of its VHDL changed, verified.
  const auto variant = [&](const std::string& folder, const std::string& from, const std::string& to) {
    fs::create_directories(dir_ / folder);
    for (const char* f : {"arx_pkg.vhd", "req_sync.vhd"}) write(folder + "/" + f, slurp(src + "/" + f));
    write(folder + "/varx.vhd", edited(slurp(src + "/varx.vhd"), from, to));
    write(folder + "/varx.toml", description);
    return verify(folder + "/varx.toml --out " + folder + "_out");
  };
  const Outcome early = variant("early", "  AER_ACK <= ack_q;", "  AER_ACK <= s2;");
  EXPECT_EQ(early.status, 1) << early.err;
  EXPECT_EQ(report("early_out")["first_failure"]["check"], "ack_rise_latency");

  const Outcome broken = variant("broken", "      now   <= now + 1;", "      now   <= now + ;");
  EXPECT_EQ(broken.status, 2) << broken.err;
  EXPECT_NE(broken.err.find("aesim: receiver VHDL does not synthesise: "), std::string::npos) << broken.err;
  EXPECT_NE(broken.err.find("varx.vhd:"), std::string::npos) << broken.err;
  EXPECT_EQ(std::count(broken.err.begin(), broken.err.end(), '\n'), 1) << broken.err;

  // Under a Verilog top: the entity it instantiates converted at its generics' defaults (a
  // 4-word FIFO: the full-output case takes 4 words), the Verilog built beside it.
  for (const char* f : {"mixed_top.v", "mixed_top.toml"}) write(f, slurp(src + "/" + f));
  const Outcome mixed = verify("mixed_top.toml --out mixed --export-tb mixed_tb");
  const nlohmann::json m = report("mixed");
  expect_pass(mixed, m, 15);
  for (const auto& c : m["cases"]) {
    if (c["name"] == "full_output") {
      EXPECT_EQ(c["beats_checked"], 4) << c.dump();
    }
  }
  EXPECT_EQ(last_line((dir_ / "mixed_tb").string(), "iverilog -g2005 -o sim -c tb_files.f && vvp -n sim").rfind("PASS", 0), 0u);
  // The Verilog setting the entity's generics: GHDL builds it with them (an 8-word FIFO, a
  // saturating counter), and the module takes the parameters. An expression or a list by position
  // is refused: GHDL needs the values.
  fs::create_directories(dir_ / "overrides");
  for (const char* f : {"arx_pkg.vhd", "req_sync.vhd", "varx.vhd", "mixed_top.toml"}) write(std::string("overrides/") + f, slurp(src + "/" + f));
  const std::string top = slurp(src + "/mixed_top.v");
  write("overrides/mixed_top.v", edited(top, "  VARX rx (", "  VARX #(.DEPTH_LOG(3), .SATURATE(\"true\")) rx ("));
  const Outcome overrides = verify("overrides/mixed_top.toml --out overrides_out");
  const nlohmann::json overridden = report("overrides_out");
  expect_pass(overrides, overridden, 15);
  for (const auto& c : overridden["cases"]) {
    if (c["name"] == "full_output") {
      EXPECT_EQ(c["beats_checked"], 8) << c.dump();
    }
  }
  write("overrides/mixed_top.v", edited(top, "  VARX rx (", "  VARX #(.DEPTH_LOG(1 + 2)) rx ("));
  expect_refused("overrides/mixed_top.toml", slurp((dir_ / "overrides/mixed_top.toml").string()),
                 "the Verilog sets the VHDL entity VARX's generic DEPTH_LOG to '1 + 2'");
  write("overrides/mixed_top.v", edited(top, "  VARX rx (", "  VARX #(3) rx ("));
  expect_refused("overrides/mixed_top.toml", slurp((dir_ / "overrides/mixed_top.toml").string()),
                 "the Verilog sets the VHDL entity VARX's generics by position");
  // A VHDL top with Verilog beside it: GHDL cannot take the Verilog.
  write("vhdl_top.toml", edited(slurp(src + "/mixed_top.toml"), "top = \"mixed_top\"", "top = \"VARX\""));
  const Outcome vhdl_top = verify("vhdl_top.toml --out vhdl_top");
  EXPECT_EQ(vhdl_top.status, 2) << vhdl_top.err;
  EXPECT_NE(vhdl_top.err.find("the top 'VARX' is a VHDL entity and other sources are Verilog"), std::string::npos) << vhdl_top.err;

  // Without GHDL on PATH: said so, with the package that brings it.
  const Outcome no_ghdl = aesim("verify varx.toml --out no_ghdl", "PATH=/nonexistent AESIM_CACHE_DIR='" AESIM_VERIFY_CACHE "' ");
  EXPECT_EQ(no_ghdl.status, 2) << no_ghdl.err;
  EXPECT_NE(no_ghdl.err.find("GHDL is not installed (apt-get install ghdl)"), std::string::npos) << no_ghdl.err;

  // [formal] parameters are generics for the proof's own conversion (a 2-word FIFO), as they are a
  // Verilog design's parameters for its proof; bounded shallow here, to keep the suite short.
  write("formal.toml", description + "\n[formal]\nparameters = { DEPTH_LOG = 1 }\ndepth = 12\n");
  const Outcome formal = verify("formal.toml --out formal_out --formal --formal-seconds 3");
  EXPECT_EQ(formal.status, 0) << formal.out << formal.err;
  // The rest of the line after `prefix` in `text`; empty without one.
  const auto after = [](const std::string& text, const std::string& prefix) {
    const auto at = text.find(prefix);
    return at == std::string::npos ? std::string() : text.substr(at + prefix.size(), text.find('\n', at) - at - prefix.size());
  };
  const std::string proof_vhdl =
      after(formal.out + formal.err, "formal note: the VHDL the proof ran, synthesised with [formal] parameters: ");
  EXPECT_TRUE(fs::is_regular_file(proof_vhdl)) << formal.out << formal.err;
  EXPECT_NE(proof_vhdl, after(o.err, "the VHDL as GHDL synthesised it: "));
  EXPECT_EQ(report("formal_out")["formal"].size(), 12u) << report("formal_out").dump();
}

// The design's own verdicts: a $fatal fails the run with the RTL's message, file and line; a
// $finish ends the case and is reported; $system and DPI imports are refused before anything runs.
TEST_F(VerifyTest, TheRtlsOwnVerdictsCountAndItRunsNoCommand) {
  const Outcome fatal = verify(std::string(AESIM_THIRD_MUTANT_DIR) + "/own_fatal/pkt_rx.toml");
  ASSERT_EQ(fatal.status, 1) << fatal.err;
  const nlohmann::json r = report();
  EXPECT_EQ(r["first_failure"]["check"], "rtl_assertion");
  const std::string observed = r["first_failure"]["observed"];
  EXPECT_EQ(observed.rfind("pkt_rx.sv:", 0), 0u) << observed;
  EXPECT_NE(observed.find("boom"), std::string::npos) << observed;
  EXPECT_LT(r["failures"].get<double>(), 20);  // each case ends at its first verdict
  EXPECT_EQ(fatal.out.find("%Error"), fatal.out.rfind("%Error")) << "the RTL's output stays out of aesim's";

  auto variant = [&](const std::string& folder, const std::string& from, const std::string& to) {
    fs::create_directories(dir_ / folder);
    for (const char* f : {"pkt_rx_pkg.sv", "pkt_rx.toml"}) fs::copy_file(kThird + "/" + f, dir_ / folder / f);
    write(folder + "/pkt_rx.sv", edited(slurp(kThird + "/pkt_rx.sv"), from, to));
    return (dir_ / folder / "pkt_rx.toml").string();
  };
  const std::string anchor = "  assign pkt_valid = offer && !col_q;";
  const Outcome finish = verify(variant("finish", anchor, "  always_ff @(posedge clk) if (rst_n && offer) $finish;\n" + anchor) +
                                " --out finished");
  ASSERT_EQ(finish.status, 0) << finish.out << finish.err;
  const nlohmann::json f = report("finished");
  EXPECT_FALSE(f["cases"][0]["rtl_finish"].is_null());
  EXPECT_NE(f["cases"][0]["rtl_finish"].get<std::string>().find("pkt_rx.sv:"), std::string::npos);
  EXPECT_NE(finish.out.find("$finish"), std::string::npos) << finish.out;

  const std::string marker = (dir_ / "ran").string();
  const std::string system =
      variant("system", anchor, "  always_ff @(posedge clk) if (rst_n && offer) $system(\"touch " + marker + "\");\n" + anchor);
  const Outcome refused = verify(system + " --out refused");
  EXPECT_EQ(refused.status, 2);
  EXPECT_NE(refused.err.find("$system"), std::string::npos) << refused.err;
  EXPECT_FALSE(fs::exists(marker));
  EXPECT_FALSE(fs::exists(dir_ / "refused/verify.json"));
  ASSERT_EQ(verify(system + " --out allowed --allow-system-tasks --plan " + write("one.toml", "directed = [\"single_event\"]\n")).status, 0);
  EXPECT_TRUE(fs::exists(marker));

  const Outcome dpi = verify(variant("dpi", "  state_t state;", "  import \"DPI-C\" function int host_call();\n  state_t state;") +
                             " --out dpi");
  EXPECT_EQ(dpi.status, 2);
  EXPECT_NE(dpi.err.find("DPI import at"), std::string::npos) << dpi.err;
}

// `--formal` on the three receivers: every handshake property proved (ABC's pdr); the structural
// check follows Req through the synchronisers (the bundled receiver's idle_o, a clock-gating hint
// that reads the first flop, is declared unsynchronised in its description).
TEST_F(VerifyTest, FormalProvesTheHandshakeOfEveryReceiver) {
  const char* handshake[] = {"req_synchronised", "ack_low_after_reset", "ack_rises_with_req", "ack_rise_min",
                             "ack_rise_max", "ack_falls_after_req", "ack_fall_min", "ack_fall_max"};
  int n = 0;
  // The bundled receiver with five seconds a property instead of the default 20: ABC proves each
  // handshake property in under one, and its stamp_rule, bounded, would take its whole budget twice.
  for (const auto& [receiver, seconds] : {std::pair{kThird + "/pkt_rx.toml", 20}, std::pair{kRtl + "/aer_receiver.toml", 5}}) {
    const std::string out = "formal" + std::to_string(n++);
    const Outcome o = verify(receiver + " --formal --formal-seconds " + std::to_string(seconds) + " --out " + out);
    ASSERT_EQ(o.status, 0) << o.out << o.err;
    const nlohmann::json r = report(out);
    EXPECT_EQ(r["formal_run"]["property_seconds"], seconds);
    EXPECT_EQ(r["passed"], true);
    ASSERT_TRUE(r["formal"].is_array());
    std::map<std::string, std::string> verdict;
    for (const auto& v : r["formal"]) {
      verdict[v["property"]] = v["verdict"];
      EXPECT_TRUE(v.contains("depth") && v.contains("time_s")) << v.dump();
      EXPECT_NE(v["verdict"], "failed") << v.dump();
    }
    for (const char* p : handshake) EXPECT_EQ(verdict[p], "proved") << receiver << " " << p;
    EXPECT_GT(r["formal_run"]["depth"].get<int>(), 20);
    EXPECT_NE(o.out.find("formal: 12 properties"), std::string::npos) << o.out;
  }
  // The third receiver, with no FIFO, has every property proved, its stamps and beats included.
  const nlohmann::json third = report("formal0");
  for (const auto& v : third["formal"]) EXPECT_EQ(v["verdict"], "proved") << v.dump();
  // A second run is the cache's, and so is a copy of the receiver's folder elsewhere: the proofs
  // follow the files, not where they lie.
  ASSERT_EQ(verify(kThird + "/pkt_rx.toml --formal --out formal_again").status, 0);
  EXPECT_EQ(report("formal_again")["formal_run"]["cached"], true);
  fs::copy(kThird, dir_ / "copied");
  ASSERT_EQ(verify("copied/pkt_rx.toml --formal --plan quick --out formal_copied").status, 0);
  EXPECT_EQ(report("formal_copied")["formal_run"]["cached"], true);
}

// The stale-stamp and first-flop mutants fail the proof as they fail the simulation: the property,
// the step, the counterexample's VCD, and the counterexample replayed through the simulation
// driver to the scoreboard's own failure.
TEST_F(VerifyTest, FormalCatchesTheStaleStampAndTheFirstFlopDecision) {
  struct Case {
    const char* mutant;
    const char* property;
    const char* replayed;
  };
  for (const Case& c : {Case{"stale_tick", "stamp_rule", "reports timestamp"},
                        Case{"first_flop_decision", "ack_rise_min", "reports ack_rise_latency"}}) {
    const std::string out = std::string("formal_") + c.mutant;
    // Five seconds a property: each failure is found in two, and the properties left undecided
    // would otherwise take the default budget twice.
    const Outcome o =
        verify(std::string(AESIM_THIRD_MUTANT_DIR) + "/" + c.mutant + "/pkt_rx.toml --formal --formal-seconds 5 --out " + out);
    ASSERT_EQ(o.status, 1) << o.err;
    const nlohmann::json r = report(out);
    EXPECT_EQ(r["passed"], false);
    bool failed = false;
    for (const auto& v : r["formal"]) {
      if (v["property"] == c.property) {
        EXPECT_EQ(v["verdict"], "failed");
        EXPECT_GT(v["step"].get<int>(), 4);
        failed = true;
      }
    }
    EXPECT_TRUE(failed) << c.mutant;
    EXPECT_EQ(r["formal_run"]["failed_property"], c.property);
    const std::string vcd = slurp(dir_ / out / "formal_failure.vcd");
    EXPECT_NE(vcd.find("$enddefinitions"), std::string::npos);
    EXPECT_NE(r["formal_run"]["replay"].get<std::string>().find(c.replayed), std::string::npos) << r["formal_run"].dump();
  }
  // The structural check names the path of the decision read from the first flop.
  const nlohmann::json first = report("formal_first_flop_decision");
  for (const auto& v : first["formal"]) {
    if (v["property"] != "req_synchronised") continue;
    EXPECT_EQ(v["verdict"], "failed");
    EXPECT_NE(v["detail"].get<std::string>().find("aer_req_n -> req_meta -> "), std::string::npos) << v.dump();
    EXPECT_NE(v["detail"].get<std::string>().find("pkt_rx.sv:"), std::string::npos) << v.dump();
  }
}

// RTL yosys cannot read: one line naming yosys's first error, exit 2, and the simulation's report
// written all the same. `formal = true` in a plan file asks for the proof as --formal does.
TEST_F(VerifyTest, FormalOnRtlYosysCannotReadIsOneLineAndThePlanMayAskForIt) {
  fs::create_directories(dir_ / "imported");
  for (const char* f : {"pkt_rx_pkg.sv", "pkt_rx.toml"}) fs::copy_file(kThird + "/" + f, dir_ / "imported" / f);
  write("imported/pkt_rx.sv",
        edited(slurp(kThird + "/pkt_rx.sv"), "module pkt_rx #(", "import pkt_rx_pkg::*;\nmodule pkt_rx #("));
  write("formal_plan.toml", "formal = true\ndirected = [\"single_event\"]\n");
  const Outcome o = verify((dir_ / "imported/pkt_rx.toml").string() + " --plan formal_plan.toml --out imported_out");
  EXPECT_EQ(o.status, 2) << o.err;
  const auto error = o.err.find("aesim: ");
  ASSERT_NE(error, std::string::npos) << o.err;
  EXPECT_EQ(o.err.find('\n', error), o.err.size() - 1) << o.err;
  EXPECT_NE(o.err.find("pkt_rx.sv:", error), std::string::npos) << o.err;
  EXPECT_NE(o.err.find("import", error), std::string::npos) << o.err;
  const nlohmann::json r = report("imported_out");
  EXPECT_EQ(r["passed"], true);
  EXPECT_NE(r["formal_error"].get<std::string>().find("yosys"), std::string::npos);
}

struct Mutant {
  const char* receiver;  // folder of mutants
  const char* name;
  const char* description;
  const char* check;  // the first check it must fail
};

// CTest lists a case by its parameter's printout: the mutant's name, not its bytes.
void PrintTo(const Mutant& m, std::ostream* os) { *os << m.name << " (" << m.check << ")"; }

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
                      Mutant{AESIM_SECOND_MUTANT_DIR, "moves_while_stalled", "ae_rx_alt.toml", "stalled_output"},
                      Mutant{AESIM_THIRD_MUTANT_DIR, "first_flop_decision", "pkt_rx.toml", "ack_rise_latency"},
                      Mutant{AESIM_THIRD_MUTANT_DIR, "stale_tick", "pkt_rx.toml", "timestamp"},
                      Mutant{AESIM_THIRD_MUTANT_DIR, "divider_off_by_one", "pkt_rx.toml", "timestamp"},
                      Mutant{AESIM_THIRD_MUTANT_DIR, "skipped_tick", "pkt_rx.toml", "timestamp"},
                      Mutant{AESIM_THIRD_MUTANT_DIR, "own_fatal", "pkt_rx.toml", "rtl_assertion"}),
    [](const ::testing::TestParamInfo<Mutant>& i) {
      return std::string(i.param.description).substr(0, 3) + "_" + i.param.name;
    });

// The exported testbench replays a scene run with back-pressure, with the description's polarity,
// slices and constants, and runs warning-free in Icarus: Verilog-2005 for Verilog sources, -g2012
// for SystemVerilog ones, the sources listed in tb_files.f.
TEST_F(VerifyTest, ExportedTestbenchPassesInIcarusOnTheGoodDesignsAndFailsOnAMutant) {
  struct Design {
    std::string description, mutant_folder, standard;
  };
  const Design designs[] = {
      {kRtl + "/aer_receiver.toml", std::string(AESIM_MUTANT_DIR) + "/ack_early", "2005"},
      {kSecond + "/ae_rx_alt.toml", std::string(AESIM_SECOND_MUTANT_DIR) + "/stale_timestamp", "2005"},
      {kThird + "/pkt_rx.toml", std::string(AESIM_THIRD_MUTANT_DIR) + "/stale_tick", "2012"}};
  int i = 0;
  for (const Design& d : designs) {
    const std::string tb = (dir_ / ("tb" + std::to_string(i++))).string();
    const Outcome o = verify(d.description + " --export-tb " + tb);
    ASSERT_EQ(o.status, 0) << o.err;
    const std::string bench = slurp(fs::path(tb) / "tb.v");
    EXPECT_NE(bench.find("module tb;"), std::string::npos);
    EXPECT_NE(bench.find("ready=0.9"), std::string::npos) << "a run with back-pressure";
    EXPECT_NE(bench.find("iverilog -g" + d.standard), std::string::npos);
    const std::string compile = "iverilog -g" + d.standard + " -o sim -c tb_files.f && vvp -n sim";
    EXPECT_EQ(last_line(tb, compile).rfind("PASS", 0), 0u) << d.description;
    const std::string output = slurp(fs::path(tb) / "run.txt");
    EXPECT_EQ(output.find("arning"), std::string::npos) << output;
    // The same testbench on the mutant's sources.
    std::string files = slurp(fs::path(tb) / "tb_files.f");
    const std::string source_dir = fs::path(d.description).parent_path().string();
    for (std::size_t at; (at = files.find(source_dir)) != std::string::npos;) files.replace(at, source_dir.size(), d.mutant_folder);
    write(fs::path(tb).filename().string() + "/tb_files.f", files);
    EXPECT_EQ(last_line(tb, compile).rfind("FAIL", 0), 0u) << d.description;
  }
}

// A design without a reset whose next state is an `always @*` block: Verilator's two-state run
// passes, and so does the exported testbench in Icarus as Verilog-2005; as SystemVerilog, Icarus
// runs no process at time 0, so the state and Ack go unknown (x) at the first edge. The testbench
// says so, not that Ack rose (an edge from 0 to x is no rise).
TEST_F(VerifyTest, ExportedTestbenchTellsAnUnknownAckFromARise) {
  write("xrx.v", R"(module xrx (input clk, input req, input [9:0] addr, output ack, output valid, output [9:0] out_addr);
  reg m = 1'b0, s = 1'b0;
  reg [1:0] state = 2'd0;
  reg [1:0] next;
  reg [9:0] word = 10'd0;
  always @* begin
    next = state;
    case (state)
      2'd0: if (s) next = 2'd1;
      2'd1: next = 2'd2;
      2'd2: if (!s) next = 2'd0;
      default: next = 2'd0;
    endcase
  end
  always @(posedge clk) begin
    m <= req;
    s <= m;
    if (state == 2'd0 && s) word <= addr;
    state <= next;
  end
  assign ack = state[1];
  assign valid = state == 2'd1;
  assign out_addr = word;
endmodule
)");
  write("xrx.toml", R"(top = "xrx"
sources = ["xrx.v"]
clock = "50MHz"
reset = "none"
[ports]
clk = "clk"
req = "req"
ack = "ack"
addr = "addr"
valid = "valid"
out_addr = "out_addr"
[behaviour]
collisions = "pass"
ack_latency_cycles = [3, 4]
)");
  const Outcome o = verify("xrx.toml --plan quick --export-tb tb");
  ASSERT_EQ(o.status, 0) << o.out << o.err;
  const std::string tb = (dir_ / "tb").string();
  EXPECT_EQ(last_line(tb, "iverilog -g2005 -o sim -c tb_files.f && vvp -n sim").rfind("PASS", 0), 0u);
  EXPECT_EQ(last_line(tb, "iverilog -g2012 -o sim -c tb_files.f && vvp -n sim").rfind("FAIL", 0), 0u);
  const std::string output = slurp(fs::path(tb) / "run.txt");
  EXPECT_NE(output.find("Ack is unknown (x) at 20000 ps"), std::string::npos) << output;
  EXPECT_EQ(output.find("Ack rose"), std::string::npos) << output;
}

TEST_F(VerifyTest, BadDescriptionsAreOneLineExitTwoAndWriteNothing) {
  const std::string good = slurp(kSecond + "/ae_rx_alt.toml");
  auto variant = [&](const std::string& name, const std::string& from, const std::string& to) {
    fs::copy_file(kSecond + "/ae_rx_alt.v", dir_ / "ae_rx_alt.v", fs::copy_options::overwrite_existing);
    return write(name, edited(good, from, to));
  };
  struct Bad {
    std::string file, needle;
  };
  // An include folder holding more than a build may read: a sparse file, so nothing is written.
  fs::create_directories(dir_ / "huge");
  std::ofstream(dir_ / "huge" / "dump.bin").close();
  fs::resize_file(dir_ / "huge" / "dump.bin", std::uintmax_t(300) << 20);
  const Bad bad[] = {
      {variant("no_port.toml", "req = \"bus_req\"", "req = \"bus_request\""), "bus_request"},
      {variant("narrow.toml", "AW = 12", "AW = 8"), "bus_addr"},
      {variant("wrong_way.toml", "ack = \"bus_ack\"", "ack = \"bus_collide\""), "bus_collide"},
      {variant("no_role.toml", "valid = \"out_valid\"\n", ""), "ports.valid"},
      {variant("bad_policy.toml", "full = \"drop\"", "full = \"spill\""), "behaviour.full"},
      {variant("bad_beat.toml", "valid = \"out_valid\"", "valid = { port = \"out_valid\", beat = \"edge\" }"),
       "ports.valid.beat: must be \"high\""},
      {variant("valid_edge.toml", "valid = \"out_valid\"", "valid = { port = \"out_valid\", edge = \"rise\" }"),
       "ports.valid.edge: unknown key (port, active, beat)"},
      {variant("no_source.toml", "sources = [\"ae_rx_alt.v\"]", "sources = [\"missing.v\"]"), "missing.v"},
      {variant("flops.toml", "ack_latency_cycles = [5, 5]", "ack_latency_cycles = [5, 5]\nsynchroniser_flops = 9"),
       "behaviour.synchroniser_flops: expected the flops Req passes before any logic reads it, 0"},
      {(write("rx.vhd", "entity rx is end rx;\n"),
        variant("vhdl.toml", "sources = [\"ae_rx_alt.v\"]", "sources = [\"ae_rx_alt.v\", \"rx.vhd\"]")),
       "no Verilog source instantiates any of the VHDL entities (1 declared)"},
      {variant("huge.toml", "sources = [\"ae_rx_alt.v\"]", "sources = [\"ae_rx_alt.v\"]\ninclude_dirs = [\"huge\"]"),
       "include_dirs: '" + (dir_ / "huge").string() + "' holds over 256 MiB"},
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
  for (const char* seconds : {"0", "3601", "ten"}) {
    const Outcome budget = verify(kSecond + "/ae_rx_alt.toml --formal --formal-seconds " + seconds);
    EXPECT_EQ(budget.status, 2) << seconds;
    EXPECT_NE(budget.err.find("--formal-seconds"), std::string::npos) << budget.err;
  }
}

// A folder the RTL's build may read goes into the caches' keys whole: each file by its place and its
// text, only the Verilog ones from a source's folder, and nothing past 256 MiB.
TEST_F(VerifyTest, AFoldersFilesChangeTheKeyAndAHugeFolderIsRefusedUnread) {
  const auto key = [this](RtlFolderFiles which) {
    std::string k;
    add_rtl_folder_to_key(k, dir_ / "rtl", which, [this](const fs::path& f) { return f.lexically_relative(dir_).string(); },
                          "sources");
    return k;
  };
  fs::create_directories(dir_ / "rtl");
  write("rtl/a.vh", "`define W 4\n");
  write("rtl/notes.txt", "x");
  const std::string verilog = key(RtlFolderFiles::VerilogOnly), all = key(RtlFolderFiles::All);
  EXPECT_EQ(verilog, "folder rtl\nrtl/a.vh\n`define W 4\n\n");
  EXPECT_EQ(all, "folder rtl\nrtl/a.vh\n`define W 4\n\nrtl/notes.txt\nx\n");
  write("rtl/notes.txt", "y");
  EXPECT_EQ(key(RtlFolderFiles::VerilogOnly), verilog);
  EXPECT_NE(key(RtlFolderFiles::All), all);
  write("rtl/a.vh", "`define W 5\n");
  EXPECT_NE(key(RtlFolderFiles::VerilogOnly), verilog);
  std::ofstream(dir_ / "rtl" / "z.sv").close();
  fs::resize_file(dir_ / "rtl" / "z.sv", std::uintmax_t(257) << 20);
  try {
    key(RtlFolderFiles::VerilogOnly);
    ADD_FAILURE() << "a 257 MiB folder was hashed";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("sources: '" + (dir_ / "rtl").string() + "' holds over 256 MiB"), std::string::npos)
        << e.what();
  }
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
