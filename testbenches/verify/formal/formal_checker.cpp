#include "formal/formal_checker.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "driver/bound_ports.hpp"
#include "export/port_wiring.hpp"

namespace aesim {
namespace {

using Collisions = ReceiverDescription::Collisions;
using Full = ReceiverDescription::Full;

// The guard of property p's assertions: CHECK selects one (0: all); a property left out is off.
std::string on(int p) { return p < 0 ? "1'b0" : fmt::format("(CHECK == 0 || CHECK == {})", p); }

// Bits for a counter that reaches `n`.
int bits_for(std::uint64_t n) {
  int b = 1;
  while (b < 63 && (1ULL << b) <= n) ++b;
  return b;
}

}  // namespace

FormalChecker formal_checker(const ReceiverDescription& d, const std::vector<RtlPort>& ports,
                             const std::optional<StampRule::Candidate>& stamp) {
  FormalChecker c;
  const int lmin = d.ack_latency_min, lmax = d.ack_latency_max;
  const bool hold = d.full == Full::Hold && d.has("ready");
  const bool drops = d.full == Full::Drop && d.has("ready");
  // Data properties need to know which transactions give no beat: a discarded collision is
  // visible (contention), a drop only through overflow_count (a discarded collision the receiver
  // also counts as a drop is told by its contention).
  bool data = true;
  if (drops && !d.has("overflow_count")) {
    data = false;
    c.notes.push_back("the beats' order, values and stamps are simulated only: under \"drop\" without overflow_count "
                      "the proof cannot tell a dropped transaction");
  }
  const bool stamps = data && d.has("timestamp") && stamp.has_value();
  if (data && d.has("timestamp") && !stamp) {
    c.notes.push_back("the stamp rule is simulated only: the simulation inferred none (no stamped beat)");
  }

  // A counter of the ticks completed since the reset, `name` after each edge (with `name`_div the
  // edges into the current tick), `width` bits: the stamps' rule, and the time a design reads.
  const auto ticks_since_reset = [&d](const std::string& name, int width) {
    return fmt::format(R"(
  // Ticks since reset: {name} after each edge, {name}_div the edges into the current tick.
  reg [{msb}:0] {name} = 0;
  reg [{dw_msb}:0] {name}_div = 0;
  always @(posedge clk) begin
    if (settling) begin
      {name} <= 0;
      {name}_div <= 0;
    end else if ({name}_div == {dw}'d{tick_last}) begin
      {name} <= {name} + 1'b1;
      {name}_div <= 0;
    end else begin
      {name}_div <= {name}_div + 1'b1;
    end
  end
)",
                       fmt::arg("name", name), fmt::arg("msb", width - 1), fmt::arg("tick_last", d.timestamp_cycles - 1),
                       fmt::arg("dw", bits_for(d.timestamp_cycles)), fmt::arg("dw_msb", bits_for(d.timestamp_cycles) - 1));
  };
  auto add = [&](const std::string& name, const std::string& text) {
    c.properties.push_back({static_cast<int>(c.properties.size()) + 1, name, text});
    return c.properties.back().id;
  };
  // A design without a reset starts from its registers' initial values: no reset steps, and Ack
  // low in that first state.
  const int reset_steps = d.has_reset() ? kFormalResetSteps : 0;
  // A two-phase link: the checker's sender is the four-phase bus behind it (req_i), whose every rise
  // changes the Req line; its Ack is high from the change of the Ack line that answers to Req's fall.
  // The handshake's properties are then about the changes; a fall has none.
  const bool two = d.two_phase();
  const int p_reset = two ? add("ack_at_rest_after_reset", d.has_reset() ? "Ack is at its resting level after the reset"
                                                                         : "Ack is at its resting level at power-up (the design has no reset)")
                          : add("ack_low_after_reset", d.has_reset() ? "Ack is low after the reset"
                                                                     : "Ack is low at power-up (the design has no reset)");
  const int p_rise = two ? add("ack_changes_with_req", "Ack changes only while a change of Req waits for it")
                         : add("ack_rises_with_req", "Ack rises only while a Req waits for it");
  const int p_rise_min = two ? add("ack_change_min", fmt::format("Ack changes no sooner than {} edges after Req changed", lmin))
                             : add("ack_rise_min", fmt::format("Ack rises no sooner than {} edges after Req rose", lmin));
  const char* stall_excuse = hold ? " (or of the consumer's last stall)" : "";
  const int p_rise_max = two ? add("ack_change_max", fmt::format("Ack changes within {} edges of Req changing{}", lmax, stall_excuse))
                             : add("ack_rise_max", fmt::format("Ack rises within {} edges of Req rising{}", lmax, stall_excuse));
  const int p_fall = two ? -1 : add("ack_falls_after_req", "Ack falls only after Req fell");
  const int p_fall_min = two ? -1 : add("ack_fall_min", fmt::format("Ack falls no sooner than {} edges after Req fell", lmin));
  const int p_fall_max = two ? -1 : add("ack_fall_max", fmt::format("Ack falls within {} edges of Req falling", lmax));
  const int p_held = d.has("ready") ? add("held_beat_stable", "a beat offered and not taken stays, unchanged") : -1;
  const int p_invent = data ? add("no_invented_beat", "every beat is a transaction's") : -1;
  const int p_order =
      data ? add("beat_in_order", fmt::format("every transaction's beat comes in bus order with its address and flag "
                                              "(collisions {})",
                                              to_string(d.collisions)))
           : -1;
  const int p_stamp = stamps ? add("stamp_rule", "the stamp follows the run's stamp rule") : -1;

  // Deep enough for the FIFO to fill and drain, a tick to pass, and the handshakes around them.
  const int handshake = 2 * lmax + 2;
  const int tick = d.has("timestamp") ? static_cast<int>(std::min<std::uint64_t>(d.timestamp_cycles, 4000)) : 0;
  const int settle = reset_steps + d.reset_release_cycles;
  c.depth = settle + 2 + (d.formal.fifo_words + 2) * handshake + tick;
  c.depth_reason = fmt::format("{} reset steps{} + 2 + ({} FIFO words + 2) x {} edges a handshake{}", reset_steps,
                               d.reset_release_cycles ? fmt::format(" + {} release edges", d.reset_release_cycles) : "",
                               d.formal.fifo_words, handshake, tick ? fmt::format(" + a tick of {} edges", tick) : "");
  if (d.formal.depth) {
    c.depth = *d.formal.depth;
    c.depth_reason = "stated by [formal] depth";
  }

  PortWiring wiring(d, ports);
  wiring.drive("clk", "clk");
  for (const std::string& name : d.clock_also) wiring.drive(PortRef{name}, "clk");
  if (d.has_out_clock()) {
    // One step is one edge of one clock: the proof runs the output side on the receiver's clock.
    wiring.drive(PortRef{d.out_clock_port}, "clk");
    c.notes.push_back(fmt::format("the proof runs {} on the receiver's clock: the crossing at its own {} is "
                                  "simulated only",
                                  d.out_clock_port,
                                  d.out_clock_hz == d.out_clock_hz_max
                                      ? fmt::format("{:g} MHz", d.out_clock_hz / 1e6)
                                      : fmt::format("{:g} to {:g} MHz", d.out_clock_hz / 1e6, d.out_clock_hz_max / 1e6)));
  }
  if (d.has_reset()) {
    wiring.drive_raised(PortRef{d.reset_port}, d.reset_active_high, "in_reset");
  }
  wiring.drive_raised("req", two ? "req_line" : "req_i");
  // The addresses the receiver both takes and gives: of an input port wider than the output (a
  // 16-bit AER input whose low 10 bits come out in a packet's slice) the extra bits are held at
  // zero, as the narrower bus driving it holds them (the simulation drives bus-width addresses);
  // a solver's address there could never come out.
  const int addr_port_width = role_width(d, ports, "addr"), ow = role_width(d, ports, "out_addr");
  const int aw = std::min(addr_port_width, ow);
  wiring.drive("addr", aw < addr_port_width ? fmt::format("{{{}'d0, addr_i}}", addr_port_width - aw) : "addr_i");
  if (d.has("contention")) wiring.drive_raised("contention", "contention_i");
  if (d.has("ready")) wiring.drive_raised("ready", "ready_i");
  if (d.has("time_in")) wiring.drive("time_in", "time_tk");
  for (const auto& [name, value] : d.inputs) wiring.drive(PortRef{name}, fmt::format("{}'d{}", find_port(ports, name)->width, value));
  const std::string ack = wiring.read_raised("ack"), out_addr = wiring.read("out_addr");
  const std::string ts = d.has("timestamp") ? wiring.read("timestamp") : "";
  const std::string flag = d.has("flags") ? wiring.read("flags") : "";
  const std::string ov = d.has("overflow_count") ? wiring.read("overflow_count") : "";
  const int tw = d.has("timestamp") ? role_width(d, ports, "timestamp") : 1;
  const int vw = d.has("overflow_count") ? role_width(d, ports, "overflow_count") : 1;
  const std::string valid_wire = wiring.valid_beat("valid");
  const std::string special = d.has("special") ? wiring.read_raised("special") : "1'b0";

  std::map<std::string, std::string> parameters = d.parameters;
  for (const auto& [k, v] : d.formal.parameters) parameters[k] = v;
  std::string parameter_list;
  for (const auto& [k, v] : parameters) parameter_list += fmt::format("{}.{}({})", parameter_list.empty() ? "" : ", ", k, v);

  // The stamp's edge for the tagged transaction: ticks since reset (tk, with div the edges into
  // the current tick) at edge rise + k, or at the edge its Ack rose or fell + j; tk_hist keeps
  // earlier ticks.
  std::string stamp_logic;
  if (stamps) {
    const int hist = std::max(1, lmax + 1);
    std::string capture;
    const char* edge = stamp->anchor == StampRule::Anchor::AckFall ? "tag_ack_fall" : "tag_ack_rise";
    const char* edge_q = stamp->anchor == StampRule::Anchor::AckFall ? "tag_fell_q" : "tag_acked_q";
    if (stamp->anchor == StampRule::Anchor::ReqRise) {
      capture = fmt::format("      if ((choose || tagged) && !tag_ts_known && since_tag == {}) begin tag_ts <= tk; tag_ts_known <= 1'b1; end\n",
                            stamp->offset);
    } else if (stamp->offset == 1) {
      capture = fmt::format("      if ({}) begin tag_ts <= tk; tag_ts_known <= 1'b1; end\n", edge_q);
    } else if (stamp->offset == 0) {
      capture = fmt::format("      if ({}) begin tag_ts <= tk; tag_ts_known <= 1'b1; end\n", edge);
    } else {
      capture = fmt::format("      if ({}) begin tag_ts <= tk_hist[{}]; tag_ts_known <= 1'b1; end\n", edge, -stamp->offset - 1);
    }
    stamp_logic = fmt::format(R"(
{ticks}  reg [{tw_msb}:0] tk_hist [0:{hist_last}];
  integer h;
  always @(posedge clk) begin
    tk_hist[0] <= tk;
    for (h = 1; h <= {hist_last}; h = h + 1) tk_hist[h] <= tk_hist[h - 1];
  end
  reg [{tw_msb}:0] tag_ts = 0, tag_beat_ts = 0;
  reg tag_ts_known = 0, tag_beat_known = 0, tag_acked_q = 0, tag_ack_high = 0, tag_fell_q = 0;
  // The tagged transaction's Ack falling: the first fall after it rose.
  wire tag_ack_fall = tag_ack_high && !ack && ack_q;
  always @(posedge clk) begin
    tag_acked_q <= tag_ack_rise;
    tag_fell_q <= tag_ack_fall;
    if (tag_ack_rise) tag_ack_high <= 1'b1;
    else if (tag_ack_fall) tag_ack_high <= 1'b0;
{capture}    if (tag_beat) begin
      tag_beat_ts <= ev_ts;
      tag_beat_known <= 1'b1;
    end
  end
  always @* if ({p_stamp}) begin
    if (tag_ts_known && tag_beat_known) assert (tag_beat_ts == tag_ts);
  end
)",
                              fmt::arg("ticks", ticks_since_reset("tk", tw)), fmt::arg("tw_msb", tw - 1),
                              fmt::arg("hist_last", hist - 1), fmt::arg("capture", capture), fmt::arg("p_stamp", on(p_stamp)));
  }

  // The time the design reads (time_in): ticks since reset, by the rule the stamps follow.
  const std::string time_logic = d.has("time_in") ? ticks_since_reset("time_tk", d.timestamp_bits) : "";

  const std::string gives = d.collisions == Collisions::Discard ? "!contention_i" : "1'b1";
  const std::string flag_ok = d.collisions == Collisions::Flag ? "ev_flag == tag_flag" : "!ev_flag";
  // An event of several output words (event_words): the words taken of the one under way, each
  // field kept from its word, and the event complete at its last word. With one word, the beat.
  std::string event_logic = fmt::format("  wire event_beat = beat;\n  wire [{}:0] ev_addr = out_addr;\n"
                                        "  wire [{}:0] ev_ts = out_ts;\n  wire ev_flag = out_flag;\n",
                                        ow - 1, tw - 1);
  // A mark on one word of an event (special = { port, word = k }) makes the whole event no event:
  // its words are counted as words, and the event is none.
  const bool marked_events = d.special_word.has_value();
  if (d.event_words > 1 || marked_events) {
    const int last = d.event_words - 1;
    const auto field = [last](int word, const char* now, const char* kept) {
      return word == last ? std::string(now) : std::string(kept);
    };
    event_logic = fmt::format(R"(  reg [3:0] word_q = 0;
  always @(posedge clk) begin
    if (settling) word_q <= 4'd0;
    else if (beat) word_q <= word_q == 4'd{last} ? 4'd0 : word_q + 1'b1;
  end
  reg [{ow_msb}:0] ev_addr_q = 0;
  reg [{tw_msb}:0] ev_ts_q = 0;
  reg ev_flag_q = 0, ev_special_q = 0;
  always @(posedge clk) if (beat) begin
    if (word_q == 4'd{addr_word}) ev_addr_q <= out_addr;
    if (word_q == 4'd{ts_word}) ev_ts_q <= out_ts;
    if (word_q == 4'd{flag_word}) ev_flag_q <= out_flag;
    if (word_q == 4'd{mark_word}) ev_special_q <= special;
  end
  wire [{ow_msb}:0] ev_addr = {addr};
  wire [{tw_msb}:0] ev_ts = {ts};
  wire ev_flag = {flag};
  wire ev_special = {marked};
  wire event_beat = beat && word_q == 4'd{last} && !ev_special;
)",
                              fmt::arg("last", last), fmt::arg("ow_msb", ow - 1), fmt::arg("tw_msb", tw - 1),
                              fmt::arg("addr_word", d.word("out_addr")), fmt::arg("ts_word", d.word("timestamp")),
                              fmt::arg("flag_word", d.word("flags")), fmt::arg("mark_word", d.special_word.value_or(0)),
                              fmt::arg("addr", field(d.word("out_addr"), "out_addr", "ev_addr_q")),
                              fmt::arg("ts", field(d.word("timestamp"), "out_ts", "ev_ts_q")),
                              fmt::arg("flag", field(d.word("flags"), "out_flag", "ev_flag_q")),
                              fmt::arg("marked", !marked_events ? "1'b0" : field(*d.special_word, "special", "ev_special_q")));
  }
  // The two-phase link between the checker's four-phase sender and the design: the Req line changes
  // at the step req_i rises; the checker's Ack is high from a change of the Ack line until req_i falls.
  const std::string link = two ? fmt::format(R"(
  // The two-phase link: its Req line, and the checker's four-phase view of its Ack line.
  reg link_req_q = 0, req_line_q = 0, ack_line_q = 0, ack_held_q = 0;
  wire req_line = req_line_q ^ (!settling && req_i && !link_req_q);
  wire ack_line = {ack};
  wire ack_change = ack_line != ack_line_q;
  // Held while req_i stays up: a sender that lets go as Ack changes may change Req again the step after.
  wire ack = ack_change || (ack_held_q && req_i && link_req_q);
  always @(posedge clk) begin
    link_req_q <= req_i;
    req_line_q <= req_line;
    ack_line_q <= ack_line;
    ack_held_q <= ack;
  end
)", fmt::arg("ack", ack))
                               : "";
  const int cw = bits_for(static_cast<std::uint64_t>(lmax) + 1);
  const int qw = bits_for(static_cast<std::uint64_t>(d.formal.fifo_words) + 8);
  const int sw = bits_for(static_cast<std::uint64_t>(lmax) + 3);
  c.source = fmt::format(R"(// Generated by aesim verify --formal from {description}: the checker around {top}.
// One step is one clock edge. Properties are selected by CHECK (0: all of them).
module aesim_formal_top #(
    parameter integer CHECK = 0
) (
    input wire clk,
    input wire req_i,
    input wire [{aw_msb}:0] addr_i,
    input wire contention_i,
    input wire ready_i,
    input wire pick_i
);
  reg [7:0] rst_cnt = 0;
  wire in_reset = rst_cnt < 8'd{reset_steps};
  // The design's own reset synchroniser holds it {release} edges past the release: the checker
  // sends nothing and counts nothing until then.
  wire settling = rst_cnt < 8'd{settled_step};
  always @(posedge clk) if (settling) rst_cnt <= rst_cnt + 1'b1;
{time_logic}
{declarations}{link}
  {top} {parameter_list}dut (
{connections}
  );

{ack_wire}{valid_wire}  wire [{ow_msb}:0] out_addr = {out_addr};
  wire [{tw_msb}:0] out_ts = {ts_expr};
  // Bit 0 of the flags, whether they are a port or a slice of one.
  wire [63:0] flag_bits = {flag_expr};
  wire out_flag = flag_bits[0];
  wire [{vw_msb}:0] ov = {ov_expr};
  wire ready = {ready_expr};

  // The sender and the handshake as the checker follows them: a transaction is open from the step
  // Req rises to the step Ack is seen high; closing from the step Req falls to the step Ack is low.
  reg past_valid = 0, free_q = 0, req_q = 0, ack_q = 0, open_q = 0, closing_q = 0, col_q = 0, txn_q = 0;
  reg [{aw_msb}:0] addr_q = 0;
  wire rise = !settling && req_i && !req_q;
  wire open = rise || open_q;
  wire fall = req_q && !req_i;
  wire closing = fall || closing_q;
  wire stall = !settling && !ready && (valid || ({hold} && open && !ack));
  // A beat that says it is no event (an in-band time marker) is no transaction's.
  wire special = {special};
  wire beat = !settling && valid && ready{not_special};
{event_logic}  // Edges since Req rose (lat), since it rose or the consumer last stalled (exc), since it fell
  // (flat); saturating just past the upper bound, where the properties have already decided.
  reg [{cw_msb}:0] lat_cnt = 0, exc_cnt = 0, fall_cnt = 0;
  wire [{cw_msb}:0] lat = rise ? {cw}'d0 : lat_cnt;
  wire [{cw_msb}:0] exc = rise ? {cw}'d0 : exc_cnt;
  wire [{cw_msb}:0] flat = fall ? {cw}'d0 : fall_cnt;
  always @(posedge clk) begin
    past_valid <= 1'b1;
    free_q <= !settling;
    req_q <= req_i;
    ack_q <= ack;
    addr_q <= addr_i;
    col_q <= contention_i;
    open_q <= open && !ack;
    closing_q <= closing && ack;
    txn_q <= (rise || txn_q) && (req_i || ack);
    lat_cnt <= open && !ack ? (lat == {cw}'d{sat} ? lat : lat + 1'b1) : {cw}'d0;
    exc_cnt <= open && !ack ? ({hold} && stall ? {cw}'d0 : exc == {cw}'d{sat} ? exc : exc + 1'b1) : {cw}'d0;
    fall_cnt <= closing && ack ? (flat == {cw}'d{sat} ? flat : flat + 1'b1) : {cw}'d0;
  end

  always @* begin
    if (settling) assume (!req_i);
    if (rise) assume (!ack);
    if (open_q && !ack) assume (req_i);
    if (open_q && req_i) assume (addr_i == addr_q && contention_i == col_q);
    // A sender that holds its lines until Ack falls ([bus] address_held).
    if ({held_to_fall} && txn_q && (req_i || ack)) assume (addr_i == addr_q && contention_i == col_q);
  end

  always @* begin
    if ({p_reset}) if ({reset_done}) assert (!{ack_at_rest});
    if ({p_rise}) if ({rise_guard}) assert ({rise_check});
    if ({p_rise_min}) if (free_q && ack && !ack_q && open) assert (lat >= {cw}'d{lmin});
    if ({p_rise_max}) if (!settling && open && !ack) assert (exc < {cw}'d{lmax});
    if ({p_fall}) if (free_q && !ack && ack_q) assert (!req_q);
    if ({p_fall_min}) if (closing && !ack && ack_q) assert (flat >= {cw}'d{lmin});
    if ({p_fall_max}) if (closing && ack) assert (flat < {cw}'d{lmax});
  end

  // A beat offered and not taken.
  reg held = 0, held_flag = 0;
  reg [{ow_msb}:0] held_addr = 0;
  reg [{tw_msb}:0] held_ts = 0;
  always @(posedge clk) begin
    held <= !settling && valid && !ready;
    held_addr <= out_addr;
    held_ts <= out_ts;
    held_flag <= out_flag;
  end
  always @* if ({p_held}) begin
    if (held && !settling) assert (valid && out_addr == held_addr && out_ts == held_ts && out_flag == held_flag);
  end

  // Transactions whose beat (or drop) is still to come, and the symbolic tag: one transaction the
  // solver picks (pick_i at its Req rise), with the beats due before its own. Small saturating
  // counters, not running totals, so that an inductive proof can relate them to the FIFO.
  reg [{qw_msb}:0] outstanding = 0, ahead = 0;
  reg [{vw_msb}:0] ov_q = 0;
  reg tagged = 0, tag_open = 0, tag_dropped = 0, tag_done = 0, tag_flag = 0;
  reg [{aw_msb}:0] tag_addr = 0;
  reg [{sw_msb}:0] since_tag_q = 0;
  wire gives = rise && {gives};
  // A drop counted now is the last transaction's (counted by its Ack edge); it takes a beat off
  // only if that transaction was to give one.
  reg last_gives = 0;
  wire dropped = {drops} && free_q && ov != ov_q && (rise ? {gives} : last_gives);
  wire choose = gives && pick_i && !tagged;
  wire tag_open_any = choose || tag_open;
  wire [{sw_msb}:0] since_tag = choose ? {sw}'d0 : since_tag_q;
  wire tag_ack_rise = tag_open_any && ack && !ack_q;
  wire tag_beat = tagged && !tag_dropped && !tag_done && event_beat && ahead == {qw}'d0;
  wire [{qw_msb}:0] taken = (event_beat ? {qw}'d1 : {qw}'d0) + (dropped ? {qw}'d1 : {qw}'d0);
  always @(posedge clk) begin
    ov_q <= ov;
    if (rise) last_gives <= {gives};
    if (settling) outstanding <= 0;
    else if (outstanding != {qw}'d{qw_sat}) outstanding <= outstanding + (gives ? {qw}'d1 : {qw}'d0) - taken;
    if ((choose || tagged) && since_tag != {sw}'d{sw_sat}) since_tag_q <= since_tag + 1'b1;
    if (choose) begin
      tagged <= 1'b1;
      tag_open <= 1'b1;
      tag_addr <= addr_i;
      tag_flag <= contention_i;
      ahead <= outstanding - taken;
    end
    if (tagged && !tag_done && event_beat && ahead != {qw}'d0) ahead <= ahead - 1'b1;
    if (tag_beat) tag_done <= 1'b1;
    if (tag_open && dropped) tag_dropped <= 1'b1;
    if (tag_ack_rise) tag_open <= 1'b0;
  end
  always @* begin
    if ({p_invent}) if (event_beat && outstanding != {qw}'d{qw_sat}) assert (outstanding > (dropped ? {qw}'d1 : {qw}'d0));
    if ({p_order}) if (tag_beat) assert (ev_addr == tag_addr && {flag_ok});
  end
{stamp_logic}endmodule
)",
                         fmt::arg("description", d.file), fmt::arg("top", d.top), fmt::arg("aw_msb", aw - 1),
                         fmt::arg("reset_steps", reset_steps), fmt::arg("settled_step", reset_steps + d.reset_release_cycles),
                         fmt::arg("release", d.reset_release_cycles),
                         fmt::arg("reset_done", d.has_reset() ? "past_valid && !settling && !free_q" : "!past_valid"), fmt::arg("declarations", wiring.declarations()),
                         fmt::arg("parameter_list", parameter_list.empty() ? "" : "#(" + parameter_list + ") "),
                         fmt::arg("connections", wiring.connections()), fmt::arg("link", link),
                         fmt::arg("ack_wire", two ? "" : fmt::format("  wire ack = {};\n", ack)),
                         fmt::arg("ack_at_rest", two ? "ack_line" : "ack"),
                         // A change of the Ack line answers only a change of the Req line (this step's
                         // included) it has not answered.
                         fmt::arg("rise_guard", two ? "free_q && ack_change" : "free_q && ack && !ack_q"),
                         fmt::arg("rise_check", two ? "req_line != ack_line_q" : "open"),
                         fmt::arg("valid_wire", valid_wire),
                         fmt::arg("ow_msb", ow - 1), fmt::arg("out_addr", out_addr), fmt::arg("tw_msb", tw - 1),
                         fmt::arg("ts_expr", ts.empty() ? "1'b0" : ts), fmt::arg("flag_expr", flag.empty() ? "64'd0" : flag),
                         fmt::arg("vw_msb", vw - 1), fmt::arg("ov_expr", ov.empty() ? "1'b0" : ov),
                         fmt::arg("ready_expr", d.has("ready") ? "ready_i" : "1'b1"), fmt::arg("special", special), fmt::arg("hold", hold ? "1'b1" : "1'b0"),
                         fmt::arg("held_to_fall", d.address_held == ReceiverDescription::AddressHeld::UntilAckFalls ? "1'b1" : "1'b0"),
                         fmt::arg("p_reset", on(p_reset)), fmt::arg("p_rise", on(p_rise)), fmt::arg("p_rise_min", on(p_rise_min)),
                         fmt::arg("p_rise_max", on(p_rise_max)), fmt::arg("p_fall", on(p_fall)), fmt::arg("p_fall_min", on(p_fall_min)),
                         fmt::arg("p_fall_max", on(p_fall_max)), fmt::arg("p_held", on(p_held)), fmt::arg("p_invent", on(p_invent)),
                         fmt::arg("p_order", on(p_order)), fmt::arg("lmin", lmin), fmt::arg("lmax", lmax), fmt::arg("gives", gives),
                         fmt::arg("flag_ok", flag_ok), fmt::arg("drops", drops && data ? "1'b1" : "1'b0"),
                         fmt::arg("cw", cw), fmt::arg("cw_msb", cw - 1), fmt::arg("sat", lmax + 1), fmt::arg("qw", qw),
                         fmt::arg("qw_msb", qw - 1), fmt::arg("qw_sat", (1 << qw) - 1), fmt::arg("sw", sw),
                         fmt::arg("sw_msb", sw - 1), fmt::arg("sw_sat", (1 << sw) - 1),
                         fmt::arg("time_logic", time_logic), fmt::arg("stamp_logic", stamp_logic),
                         fmt::arg("not_special", marked_events ? "" : " && !special"),
                         fmt::arg("event_logic", event_logic));
  return c;
}

}  // namespace aesim
