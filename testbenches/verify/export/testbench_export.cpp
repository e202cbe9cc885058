#include "export/testbench_export.hpp"

#include <algorithm>
#include <map>

#include <fmt/format.h>

#include "driver/bound_ports.hpp"
#include "driver/case_driver.hpp"

namespace aesim {
namespace {

std::string range(int msb, int lsb) { return msb == 0 && lsb == 0 ? "" : fmt::format("[{}:{}] ", msb, lsb); }

bool any_systemverilog(const ReceiverDescription& d) {
  return std::any_of(d.sources.begin(), d.sources.end(), [](const std::string& s) {
    return s.size() > 3 && (s.compare(s.size() - 3, 3, ".sv") == 0 || s.compare(s.size() - 4, 4, ".svh") == 0);
  });
}

// Every port the testbench touches, once, as a wire named p_PORT of the port's own width: an
// output read by roles (whole or sliced), or an input assembled from the roles and constants that
// drive its bits (continuous assignments, so the levels hold from time 0).
class PortWiring {
 public:
  PortWiring(const ReceiverDescription& d, const std::vector<RtlPort>& ports) : d_(d), ports_(ports) {}
  // An output role's bits.
  std::string read(const std::string& r) {
    const PortRef& ref = d_.ref(r);
    used_[ref.port];
    if (!ref.sliced()) return "p_" + ref.port;
    return ref.msb == ref.lsb ? fmt::format("p_{}[{}]", ref.port, ref.msb) : fmt::format("p_{}[{}:{}]", ref.port, ref.msb, ref.lsb);
  }
  // An input role's bits (or a whole input port) driven by `expr`.
  void drive(const std::string& r, const std::string& expr) { drive(d_.ref(r), expr); }
  void drive(const PortRef& ref, const std::string& expr) {
    const RtlPort& p = *find_port(ports_, ref.port);
    const int lo = std::min(p.msb, p.lsb);
    used_[ref.port].push_back({ref.sliced() ? ref.msb : lo + p.width - 1, ref.sliced() ? ref.lsb : lo, expr});
  }
  std::string declarations() const {
    std::string out;
    for (const auto& [name, pieces] : used_) {
      const RtlPort& p = *find_port(ports_, name);
      const int lo = std::min(p.msb, p.lsb), hi = lo + p.width - 1;
      if (!p.input) {
        out += fmt::format("  wire {}p_{};\n", range(hi, lo), name);
        continue;
      }
      // Highest bits first; bits no role drives are 0.
      std::vector<Piece> sorted = pieces;
      std::sort(sorted.begin(), sorted.end(), [](const Piece& a, const Piece& b) { return a.msb > b.msb; });
      std::string concat;
      int next = hi;
      for (const Piece& piece : sorted) {
        if (piece.msb < next) concat += fmt::format("{}{}'d0", concat.empty() ? "" : ", ", next - piece.msb);
        concat += fmt::format("{}{}", concat.empty() ? "" : ", ", piece.expr);
        next = piece.lsb - 1;
      }
      if (next >= lo) concat += fmt::format("{}{}'d0", concat.empty() ? "" : ", ", next - lo + 1);
      out += fmt::format("  wire {}p_{} = {{{}}};\n", range(hi, lo), name, concat);
    }
    return out;
  }
  std::string connections() const {
    std::string out;
    for (const auto& [name, pieces] : used_) out += fmt::format("{}      .{}(p_{})", out.empty() ? "" : ",\n", name, name);
    return out;
  }

 private:
  struct Piece {
    int msb, lsb;
    std::string expr;
  };
  const ReceiverDescription& d_;
  const std::vector<RtlPort>& ports_;
  std::map<std::string, std::vector<Piece>> used_;
};

}  // namespace

void write_testbench(const std::string& dir, const ReceiverDescription& d, const std::vector<RtlPort>& ports,
                     const ExportedRun& run, OutputFiles& files) {
  const std::uint64_t period = clock_period_ps(d);
  std::ostream& inputs = files.open(dir + "/tb_inputs.hex");
  for (const WaveRecord& w : run.waveform) {
    inputs << fmt::format("{:016x}{:08x}{:08x}\n", w.t_ps,
                          (w.req ? 8u : 0u) | (w.contention ? 4u : 0u) | (w.ready ? 2u : 0u) | (w.reset ? 1u : 0u),
                          static_cast<std::uint32_t>(w.addr));
  }
  if (!run.beats.empty()) {
    std::ostream& expected = files.open(dir + "/tb_expected.hex");
    for (const TakenBeat& b : run.beats) {
      expected << fmt::format("{:016x}{:08x}{:08x}\n", b.timestamp, static_cast<unsigned>(b.flags & 1),
                              static_cast<std::uint32_t>(b.addr));
    }
  }
  // Which sources to hand to Icarus, with the description's include folders: `iverilog -c`.
  std::ostream& list = files.open(dir + "/tb_files.f");
  for (const std::string& i : d.include_dirs) list << "+incdir+" << i << "\n";
  list << "tb.v\n";
  for (const std::string& s : d.sources) list << s << "\n";

  const auto level = [](bool active_high) { return active_high ? "1'b1" : "1'b0"; };
  const auto inverse = [](bool active_high) { return active_high ? "1'b0" : "1'b1"; };
  PortWiring wiring(d, ports);
  wiring.drive("clk", "clk");
  wiring.drive(PortRef{d.reset_port}, fmt::format("(rst ? {} : {})", level(d.reset_active_high), inverse(d.reset_active_high)));
  wiring.drive("req", fmt::format("(req ? {} : {})", level(d.req_active_high), inverse(d.req_active_high)));
  wiring.drive("addr", "addr");
  if (d.has("contention")) wiring.drive("contention", "contention");
  if (d.has("ready")) wiring.drive("ready", "ready");
  for (const auto& [name, value] : d.inputs) wiring.drive(PortRef{name}, fmt::format("{}'d{}", find_port(ports, name)->width, value));
  const std::string ack = wiring.read("ack"), valid = wiring.read("valid"), out_addr = wiring.read("out_addr");
  const std::string stamp = d.has("timestamp") ? wiring.read("timestamp") : "";
  const std::string flag = d.has("flags") ? wiring.read("flags") : "";
  if (d.has("overflow_count")) wiring.read("overflow_count");
  const int aw = role_width(d, ports, "addr");
  const std::string flag_bit = flag.empty() ? "1'b0" : "flag_bits[0]";
  std::string defines, parameters;
  for (const auto& [k, v] : d.defines) defines += fmt::format("`define {} {}\n", k, v);
  for (const auto& [k, v] : d.parameters) parameters += fmt::format("{}.{}({})", parameters.empty() ? "" : ", ", k, v);
  const bool sv = any_systemverilog(d);
  const std::string beats_read =
      run.beats.empty() ? "" : "    $readmemh(\"tb_expected.hex\", expected, 0, N_BEATS - 1);\n";
  const std::string stamp_check =
      stamp.empty() ? "" : " || out_stamp !== expected[taken][127:64]";
  const std::string stamp_text = stamp.empty() ? "0" : "out_stamp";

  std::ostream& tb = files.open(dir + "/tb.v");
  tb << fmt::format(R"(// Generated by aesim verify from {description}: the run "{case_name}".
// Replays its exact inputs (tb_inputs.hex) into {top} and checks every beat taken against the
// {beats} beats of the run (tb_expected.hex). Run in this folder:
//   iverilog -g{standard} -o sim -c tb_files.f  &&  vvp sim
// (tb_files.f lists tb.v, the RTL sources and their include folders.) The last line printed starts
// with PASS or FAIL.
`timescale 1ps/1ps
{defines}
module tb;
  localparam [63:0] HALF = 64'd{half};
  localparam [63:0] END_PS = 64'd{end_ps};
  localparam integer N_INPUTS = {n_inputs};
  localparam integer N_BEATS = {beats};

  reg [127:0] inputs [0:N_INPUTS-1];
  reg [127:0] expected [0:{expected_last}];
  // The run's signals as aesim reasons about them: Req and Ack raised or not, whatever their
  // levels on the RTL's ports.
  reg clk = 1'b0;
  reg rst = 1'b1;
  reg req = 1'b0;
  reg contention = 1'b0;
  reg ready = 1'b1;
  reg [{aw_msb}:0] addr = {aw}'d0;
{declarations}
  wire ack = {ack} == {ack_on};
  wire out_valid = {valid};
  wire [63:0] out_addr = {out_addr};
  wire [63:0] out_stamp = {stamp_wire};
  wire out_flag = {flag_bit};
{flag_wire}
  {top} {parameter_list}dut (
{connections}
  );

  // Rising edges at k * {period} ps, as in aesim's run.
  initial begin
    #(HALF);
    forever begin
      #(HALF) clk = 1'b1;
      #(HALF) clk = 1'b0;
    end
  end

  integer i;
  initial begin
    $readmemh("tb_inputs.hex", inputs, 0, N_INPUTS - 1);
{beats_read}    for (i = 0; i < N_INPUTS; i = i + 1) begin
      #(inputs[i][127:64] - $time);
      req = inputs[i][35];
      contention = inputs[i][34];
      ready = inputs[i][33];
      rst = inputs[i][32];
      addr = inputs[i][{aw_msb}:0];
    end
  end

  integer taken = 0;
  integer errors = 0;
  always @(posedge clk) begin
    if (out_valid && ready && !rst) begin
      if (taken >= N_BEATS) begin
        if (errors == 0) $display("beat %0d at %0t ps: address %0h stamp %0d, beyond the %0d expected", taken, $time, out_addr, {stamp_text}, N_BEATS);
        errors = errors + 1;
      end else if (out_addr !== {{32'd0, expected[taken][31:0]}}{stamp_check} || out_flag !== expected[taken][32]) begin
        if (errors == 0) $display("beat %0d at %0t ps: expected address %0h stamp %0d flag %0d, got address %0h stamp %0d flag %0d",
                                  taken, $time, expected[taken][31:0], expected[taken][127:64], expected[taken][32],
                                  out_addr, {stamp_text}, out_flag);
        errors = errors + 1;
      end
      taken = taken + 1;
    end
  end
  always @(posedge ack) begin
    if (!req) begin
      if (errors == 0) $display("Ack rose with Req low at %0t ps", $time);
      errors = errors + 1;
    end
  end

  initial begin
    #(END_PS);
    if (errors == 0 && taken == N_BEATS) $display("PASS: %0d beats as expected", taken);
    else $display("FAIL: %0d errors, %0d of %0d beats taken", errors, taken, N_BEATS);
    $finish;
  end
endmodule
)",
                    fmt::arg("description", d.file), fmt::arg("case_name", run.case_name), fmt::arg("top", d.top),
                    fmt::arg("standard", sv ? "2012" : "2005"), fmt::arg("beats", run.beats.size()),
                    fmt::arg("expected_last", std::max<std::size_t>(run.beats.size(), 1) - 1),
                    fmt::arg("defines", defines), fmt::arg("half", period / 2), fmt::arg("end_ps", run.end_ps),
                    fmt::arg("n_inputs", run.waveform.size()), fmt::arg("aw_msb", aw - 1), fmt::arg("aw", aw),
                    fmt::arg("declarations", wiring.declarations()), fmt::arg("ack", ack),
                    fmt::arg("ack_on", level(d.ack_active_high)), fmt::arg("valid", valid),
                    fmt::arg("out_addr", out_addr), fmt::arg("stamp_wire", stamp.empty() ? "64'd0" : stamp),
                    fmt::arg("flag_bit", flag_bit),
                    fmt::arg("flag_wire", flag.empty() ? "" : fmt::format("  wire [63:0] flag_bits = {};\n", flag)),
                    fmt::arg("parameter_list", parameters.empty() ? "" : "#(" + parameters + ") "),
                    fmt::arg("connections", wiring.connections()), fmt::arg("period", period),
                    fmt::arg("beats_read", beats_read),
                    fmt::arg("stamp_check", stamp_check), fmt::arg("stamp_text", stamp_text));
}

}  // namespace aesim
