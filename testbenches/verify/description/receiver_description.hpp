#pragma once
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace aesim {

// Where a role lives in the RTL: a whole port, a slice of one (`pkt_data[23:8]`, `ctl[0]`), or,
// for a multi-bit role, ports and slices joined as Verilog joins them (`{evt_y, evt_x[4:0]}`: the
// first part the most significant).
struct PortRef {
  std::string port;        // empty for a joined role
  int msb = -1, lsb = -1;  // the slice in the port's own bit numbering; -1: the whole port
  std::vector<PortRef> parts{};  // a joined role's parts, most significant first
  bool sliced() const { return msb >= 0; }
  bool joined() const { return !parts.empty(); }
  // The single ports and slices it is made of: its parts, or itself.
  std::vector<PortRef> pieces() const { return joined() ? parts : std::vector<PortRef>{*this}; }
  bool uses(const std::string& name) const;
  std::string text() const;  // as the description wrote it
};

// The most edges a description may say its design stays in reset past the release.
inline constexpr int kMaxResetReleaseCycles = 64;

// A team's receiver RTL as its description file (docs/reference.md section 6) says: how to build it, which of
// its ports plays which role, and what it promises. Paths are absolute (relative ones in the file
// are taken from the file's folder).
struct ReceiverDescription {
  enum class Collisions { Discard, Flag, Pass };
  enum class Full { Drop, Hold };

  std::string file;  // the description itself, for messages
  std::string top;
  std::vector<std::string> sources, include_dirs;
  std::map<std::string, std::string> defines;     // NAME -> value ("" for a bare define)
  std::map<std::string, std::string> parameters;  // NAME -> Verilog literal (strings quoted)
  double clock_hz = 0;
  std::string reset_port;  // empty for a design without a reset (`reset = "none"`)
  bool reset_active_high = false;
  // Edges the design stays in reset after aesim releases it (`reset = { ..., release_cycles = N }`:
  // a reset synchroniser of N flops inside the top): latency bounds and stamps count from there.
  int reset_release_cycles = 0;
  bool has_reset() const { return !reset_port.empty(); }
  // The one-bit roles at their active level: high, unless the description says
  // `{ port = "...", active = "low" }` (req, ack, valid, ready, contention).
  std::set<std::string> active_low;
  bool active_high(const std::string& role) const { return active_low.count(role) == 0; }
  // Which edges are beats: where valid is high (with ready, where both are), the default; `valid =
  // { port, beat = "rise" }`, a level held for each word (a data-ready flag that stays up until
  // the handshake ends, say): where it is high and was low at the edge before; `beat = "change"`,
  // a flag that toggles for each word (a two-phase strobe): where it differs from the edge before.
  // The last two only without a ready port.
  enum class ValidBeat { High, Rise, Change };
  ValidBeat valid_beat = ValidBeat::High;
  // How long the sender holds the address and contention it raised Req with (`[bus]
  // address_held`): until Ack rises, as the imager's pixels do (they let go of the lines with Req
  // when Ack resets them); or until Ack falls, as a synchronous sender's output register does (a
  // receiver may then take the address after Req falls).
  enum class AddressHeld { UntilAckRises, UntilAckFalls };
  AddressHeld address_held = AddressHeld::UntilAckRises;
  // How Req and Ack signal (`[bus] handshake`): four-phase, the imager's own bus (Req rises, Ack
  // rises, Req falls, Ack falls: two edges of each a transaction); or two-phase (transition
  // signalling: each edge of Req, either way, is a transaction, answered by one edge of Ack, so a
  // transaction is open while the two lines differ). On a two-phase link the sender toggles Req when
  // the bus opens a transaction, with the address and contention bundled until Ack answers; both
  // lines start at their inactive level and return to it with the receiver's reset.
  enum class Handshake { FourPhase, TwoPhase };
  Handshake handshake = Handshake::FourPhase;
  bool two_phase() const { return handshake == Handshake::TwoPhase; }
  // Further clock inputs driven by the receiver's clock (`clk = ["clk_i", "usb_clk"]`): a top whose
  // output side has a clock port of its own runs both sides on the one clock.
  std::vector<std::string> clock_also;
  // The output side's own clock (`clk = ["clk_i", { port = "usb_clk", clock = "48MHz" }]`): the
  // output stream (valid, ready, out_addr, timestamp, flags, special, overflow_count) is taken at its
  // rising edges and the consumer's ready driven in its time, at a frequency and a phase of its own
  // (the phase drawn for each case), so that a crossing between the two sides meets every alignment
  // of their edges. `clock = ["24MHz", "100MHz"]`: a range, each case at a frequency drawn from it.
  // Ack latencies, stamps and the reset count the receiver's clock.
  std::string out_clock_port;
  double out_clock_hz = 0, out_clock_hz_max = 0;  // equal unless a range
  bool has_out_clock() const { return !out_clock_port.empty(); }
  // The output words an event takes (`[behaviour] event_words`, 1 to 8): an interface as narrow as
  // a USB chip's 16-bit FIFO gives the address in one word and the stamp in the next. Each of
  // out_addr, timestamp and flags is read from one of them (`{ port = "...", word = k }`, k from
  // 0, the first; default 0); words that say they are no event (`special`) are not counted.
  int event_words = 1;
  // `special = { port, word = k }`: the whole event whose word k carries the mark is no event (a
  // timestamp wrap sent in an event's shape); without `word`, each marked word is one on its own.
  std::optional<int> special_word;
  std::map<std::string, int> word_of;  // role -> its word, where not 0
  int word(const std::string& role) const {
    const auto at = word_of.find(role);
    return at == word_of.end() ? 0 : at->second;
  }
  std::map<std::string, PortRef> ports;            // role -> where it is
  std::map<std::string, std::uint64_t> inputs;     // RTL port -> constant value
  Collisions collisions = Collisions::Discard;
  Full full = Full::Drop;  // meaningful only with a ready port
  // The stamp (with a timestamp port only): ticks of timestamp_cycles clock cycles since reset,
  // modulo 2^timestamp_bits, at one fixed edge of every transaction.
  double timestamp_tick = 0;  // s
  std::uint64_t timestamp_cycles = 0;
  int timestamp_bits = 0;
  // That edge, when the description states it: counting the first rising edge after Req rose as 1.
  std::optional<int> timestamp_offset_cycles;
  int ack_latency_min = 0, ack_latency_max = 0;  // clock edges
  // The flops Req passes through before any logic reads it (the formal structural check).
  int synchroniser_flops = 2;
  // `aesim verify --formal`: parameter overrides for the proof only (a smaller FIFO, say), the
  // words the receiver can hold (for the depth of the bounded check), or that depth itself.
  // Outputs that may read Req before the synchroniser's last flop (a clock-gating hint, say): the
  // structural check accepts logic whose only sinks they are. The Verilog the proof reads instead
  // of `sources`, where those hold what yosys cannot parse (a package's string functions, say).
  struct Formal {
    std::map<std::string, std::string> parameters;
    std::map<std::string, std::uint64_t> inputs;  // [inputs] overrides for the proof
    int fifo_words = 2;
    std::optional<int> depth;
    std::vector<std::string> unsynchronised_outputs;
    std::vector<std::string> sources;
  } formal;

  bool has(const std::string& role) const { return ports.count(role) != 0; }
  const std::string& port(const std::string& role) const { return ports.at(role).port; }
  const PortRef& ref(const std::string& role) const { return ports.at(role); }
};

// The roles of docs/reference.md section 6, required ones first; `optional` says which may be left out.
struct PortRole {
  const char* name;
  bool input;  // driven by aesim
  bool optional;
};
const std::vector<PortRole>& port_roles();

// Reads and checks a description; every problem is an InputError naming the file and the key.
ReceiverDescription read_receiver_description(const std::string& path);

const char* to_string(ReceiverDescription::Collisions c);
const char* to_string(ReceiverDescription::Full f);
const char* to_string(ReceiverDescription::AddressHeld h);
const char* to_string(ReceiverDescription::Handshake h);

}  // namespace aesim
