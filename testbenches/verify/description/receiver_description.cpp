#include "description/receiver_description.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <optional>

#include <glob.h>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "description/file_list.hpp"
#include "aesim/text/nearest_name.hpp"
#include "aesim/files/input_path.hpp"
#include "build/vhdl_conversion.hpp"
#include "aesim/files/toml_file.hpp"
#include "aesim/units/si_units.hpp"

namespace aesim {
namespace {

namespace fs = std::filesystem;

// Sources are read whole to hash them for the cache.
constexpr std::uintmax_t kMaxSourceBytes = 64ull << 20;

// A string that reads as a Verilog integer, "16", "-3", "16'd16", "'hFF" or "8'b1010_1010": its
// value in decimal. TOML users write numbers as strings often enough that "16" passed on as the
// string it is made a 16-bit port 12,598 bits wide (the string's two bytes, read as a number).
std::optional<std::string> verilog_integer(const std::string& text) {
  std::string s;
  for (char c : text) {
    if (c != '_' && !std::isspace(static_cast<unsigned char>(c))) s += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  const bool negative = !s.empty() && s[0] == '-';
  if (negative) s.erase(0, 1);
  const std::size_t tick = s.find('\'');
  std::string digits = tick == std::string::npos ? s : s.substr(tick + 1);
  if (tick != std::string::npos) {
    const std::string size = s.substr(0, tick);
    if (!std::all_of(size.begin(), size.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); })) return std::nullopt;
    if (!digits.empty() && digits[0] == 's') digits.erase(0, 1);
  }
  int base = 10;
  if (tick != std::string::npos) {
    if (digits.empty()) return std::nullopt;
    const char b = digits[0];
    base = b == 'b' ? 2 : b == 'o' ? 8 : b == 'd' ? 10 : b == 'h' ? 16 : 0;
    if (base == 0) return std::nullopt;
    digits.erase(0, 1);
  }
  if (digits.empty() || digits.size() > 64) return std::nullopt;
  std::uint64_t value = 0;
  for (char c : digits) {
    const int d = std::isdigit(static_cast<unsigned char>(c)) ? c - '0' : (c >= 'a' && c <= 'f') ? c - 'a' + 10 : 99;
    if (d >= base) return std::nullopt;
    if (value > (~std::uint64_t(0) - static_cast<std::uint64_t>(d)) / static_cast<std::uint64_t>(base)) return std::nullopt;
    value = value * static_cast<std::uint64_t>(base) + static_cast<std::uint64_t>(d);
  }
  return (negative ? "-" : "") + std::to_string(value);
}

class Reader {
 public:
  Reader(const std::string& path, const TomlValue& root) : path_(path), root_(root) {
    std::error_code ec;
    dir_ = fs::absolute(fs::path(path), ec).parent_path();
    if (ec || dir_.empty()) dir_ = fs::path(path).parent_path();
    if (dir_.empty()) dir_ = ".";
  }

  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw InputError(fmt::format("receiver description '{}': {}: {}", path_, key, what));
  }

  const TomlValue* find(const TomlValue& table, const std::string& key) const {
    const auto& t = table.as_table();
    const auto it = t.find(key);
    return it == t.end() ? nullptr : &it->second;
  }
  const TomlValue& need(const TomlValue& table, const std::string& key, const std::string& label) const {
    const TomlValue* v = find(table, key);
    if (!v) fail(label, "missing");
    return *v;
  }
  std::string string_of(const TomlValue& v, const std::string& label) const {
    if (!v.is_string()) fail(label, "expected a string");
    if (v.as_string().empty()) fail(label, "empty");
    return v.as_string();
  }
  std::string path_of(const TomlValue& v, const std::string& label, bool folder) const {
    return checked_path(full_path(string_of(v, label)), label, folder);
  }
  // A quantity in `unit`: a string with SI prefix and unit ("1us"), or a plain TOML number in it.
  double quantity_of(const TomlValue& v, const std::string& label, const char* unit) const {
    if (v.is_integer()) return static_cast<double>(v.as_integer());
    if (v.is_floating()) return v.as_floating();
    return si(string_of(v, label), unit, label);
  }
  // A number with SI prefix and unit; a malformed one fails as every key does, naming the file.
  double si(const std::string& text, const char* unit, const std::string& label) const {
    return parse_si(text, unit, fmt::format("receiver description '{}': {}", path_, label));
  }
  // A clock as its frequency ("50MHz", or 50e6 in Hz) or as its period ("20ns"), as datasheets and
  // timing constraints give it.
  double frequency_of(const TomlValue& v, const std::string& label) const {
    if (!v.is_string()) return quantity_of(v, label, "Hz");
    std::string text = v.as_string();
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.pop_back();
    if (!text.empty() && text.back() == 's') {
      const double period = si(text, "s", label);
      if (!(period > 0)) fail(label, fmt::format("a period of {} s", period));
      return 1 / period;
    }
    return si(string_of(v, label), "Hz", label);
  }
  std::string full_path(const std::string& text) const {
    const fs::path p = fs::path(text);
    return (p.is_absolute() ? p : dir_ / p).lexically_normal().string();
  }
  // A file name with *, ? or [...] in it (rtl/*.sv, as a Makefile lists a folder's sources) is
  // every file it matches, in byte order, so that the same description always compiles the same
  // list; matching none is an error. Expanded by glob(3) in one folder, no shell.
  // A file list (`files.f`, verilator -F's) is the sources it names, checked as these are; its
  // include folders and defines are kept for the description (listed()).
  std::vector<std::string> files_of(const TomlValue& v, const std::string& label) const {
    const std::string text = string_of(v, label);
    const std::string ext = fs::path(text).extension().string();
    if (ext == ".f" || ext == ".F") {
      const FileList list = read_file_list(path_of(v, label, false), fmt::format("receiver description '{}': {}", path_, label));
      std::vector<std::string> files;
      for (const std::string& f : list.sources) files.push_back(checked_path(f, label, false));
      for (const std::string& dir : list.include_dirs) listed_.include_dirs.push_back(checked_path(dir, label, true));
      listed_.defines.insert(list.defines.begin(), list.defines.end());
      return files;
    }
    if (text.find_first_of("*?[") == std::string::npos) return {path_of(v, label, false)};
    // One folder read, whatever the pattern: wildcards in the file's name only.
    if (fs::path(text).parent_path().string().find_first_of("*?[") != std::string::npos) {
      fail(label, fmt::format("'{}': wildcards name files of one folder, in the file name only", text));
    }
    glob_t found{};
    const int status = ::glob(full_path(text).c_str(), GLOB_ERR, nullptr, &found);
    std::vector<std::string> matches(found.gl_pathv, found.gl_pathv + (status == 0 ? found.gl_pathc : 0));
    globfree(&found);
    if (matches.empty()) fail(label, fmt::format("'{}' matches no file", full_path(text)));
    std::sort(matches.begin(), matches.end());
    std::vector<std::string> out;
    for (const std::string& m : matches) {
      if (!fs::is_directory(m)) out.push_back(checked_path(m, label, false));
    }
    if (out.empty()) fail(label, fmt::format("'{}' matches only folders", full_path(text)));
    return out;
  }
  std::string checked_path(const std::string& full, const std::string& label, bool folder) const {
    const bool ok = folder ? is_input_folder(full, label) : is_input_file(full, label);
    if (!ok) fail(label, fmt::format("'{}' is not {}", full, folder ? "a folder" : "a readable file"));
    std::error_code ec;
    if (!folder && fs::file_size(full, ec) > kMaxSourceBytes) {
      fail(label, fmt::format("'{}' is over {} MiB; aesim reads at most that per RTL file", full, kMaxSourceBytes >> 20));
    }
    return full;
  }
  std::vector<std::string> paths(const std::string& key, bool folder, bool required) const {
    return paths_in(find(root_, key), key, folder, required);
  }
  // A path or a list of them, `v` (null when the key is absent), named `key` in errors.
  std::vector<std::string> paths_in(const TomlValue* v, const std::string& key, bool folder, bool required) const {
    std::vector<std::string> out;
    if (!v) {
      if (required) fail(key, "missing");
      return out;
    }
    // Each file once, where it first comes: a package named first stays first when a pattern
    // after it matches it again.
    const auto add = [&](const TomlValue& entry, const std::string& label) {
      for (std::string& p : folder ? std::vector<std::string>{path_of(entry, label, true)} : files_of(entry, label)) {
        if (std::find(out.begin(), out.end(), p) == out.end()) out.push_back(std::move(p));
      }
      if (out.size() > 1000) fail(key, "more than 1000 entries");
    };
    if (v->is_string()) {
      add(*v, key);
      return out;
    }
    if (!v->is_array()) fail(key, "expected a list of paths");
    for (std::size_t i = 0; i < v->as_array().size(); ++i) add(v->as_array()[i], fmt::format("{}[{}]", key, i));
    if (required && out.empty()) fail(key, "empty");
    if (out.size() > 1000) fail(key, "more than 1000 entries");
    return out;
  }
  // Verilog's simple identifiers only (a letter or '_', then letters, digits, '_' and '$'): these
  // names reach Verilator's command line, yosys's scripts and the exported testbench, so nothing
  // else may pass.
  std::string identifier(const std::string& text, const std::string& label) const {
    const bool ok = !text.empty() && text.size() <= 128 && !std::isdigit(static_cast<unsigned char>(text[0])) &&
                    text[0] != '$' && std::all_of(text.begin(), text.end(), [](char c) {
                      return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '$';
                    });
    if (!ok && text.size() > 1 && (text[0] == '!' || text[0] == '~')) {
      fail(label, fmt::format("'{}' is not a plain Verilog identifier (a line active low is {{ port = \"{}\", active = \"low\" }})",
                              text, text.substr(1)));
    }
    if (!ok && text.find('.') != std::string::npos) {
      fail(label, fmt::format("'{}' is not a plain Verilog identifier (a member of an interface port? the ports aesim drives "
                              "are plain ones: name as top a module of plain ports that makes the interface, "
                              "docs/verify.md)",
                              text));
    }
    if (!ok) fail(label, fmt::format("'{}' is not a plain Verilog identifier", text));
    return text;
  }
  // "{a, b[3:0], ...}": the parts joined, the first the most significant.
  PortRef joined_ref(const std::string& text, const std::string& label) const {
    PortRef ref;
    std::string inner = text.substr(1, text.size() - 2);
    std::size_t from = 0;
    for (;;) {
      const std::size_t comma = inner.find(',', from);
      std::string part = inner.substr(from, comma == std::string::npos ? std::string::npos : comma - from);
      const auto first = part.find_first_not_of(" \t"), last = part.find_last_not_of(" \t");
      part = first == std::string::npos ? "" : part.substr(first, last - first + 1);
      if (part.empty()) fail(label, fmt::format("'{}': an empty part in the joined ports", text));
      ref.parts.push_back(port_ref(part, label));
      if (comma == std::string::npos) break;
      from = comma + 1;
    }
    if (ref.parts.size() > 64) fail(label, fmt::format("'{}': more than 64 parts", text));
    return ref;
  }
  // "name", "name[msb:lsb]" or "name[bit]", descending.
  PortRef port_ref(const std::string& text, const std::string& label) const {
    PortRef ref;
    const auto open = text.find('[');
    ref.port = identifier(text.substr(0, open), label);
    if (open == std::string::npos) return ref;
    const std::string range = text.substr(open);
    long msb = -1, lsb = -1;
    char close = 0;
    int used = 0;
    const bool one = std::sscanf(range.c_str(), "[%ld]%n", &msb, &used) == 1 && used == static_cast<int>(range.size());
    const bool two = !one && std::sscanf(range.c_str(), "[%ld:%ld%c%n", &msb, &lsb, &close, &used) == 3 &&
                     close == ']' && used == static_cast<int>(range.size());
    if (one) lsb = msb;
    if (!(one || two) || msb < 0 || lsb < 0 || msb > 65535) {
      fail(label, fmt::format("'{}' is not a port or a slice of one (name[msb:lsb] or name[bit])", text));
    }
    if (msb < lsb) fail(label, fmt::format("'{}': a slice is [msb:lsb] with msb >= lsb", text));
    if (msb - lsb >= 64) fail(label, fmt::format("'{}': aesim connects slices of up to 64 bits", text));
    ref.msb = static_cast<int>(msb);
    ref.lsb = static_cast<int>(lsb);
    return ref;
  }
  std::string literal(const TomlValue& v, const std::string& label) const {
    if (v.is_integer()) return std::to_string(v.as_integer());
    if (v.is_boolean()) return v.as_boolean() ? "1" : "0";
    if (v.is_floating()) {
      if (!std::isfinite(v.as_floating())) fail(label, "a number must be finite");
      return fmt::format("{}", v.as_floating());
    }
    if (v.is_string()) {
      const std::string& s = v.as_string();
      if (const std::optional<std::string> number = verilog_integer(s)) return *number;
      const bool printable = std::all_of(s.begin(), s.end(), [](char c) { return c >= 0x20 && c < 0x7f && c != '"' && c != '\\'; });
      if (!printable) fail(label, "a string value may hold printable characters other than \" and \\ only");
      return "\"" + s + "\"";
    }
    fail(label, "expected a number, a boolean or a string");
  }
  const TomlValue& root() const { return root_; }

 private:
  std::string path_;
  fs::path dir_;
  const TomlValue& root_;
  mutable FileList listed_;  // what file lists among the paths read added beside their sources

 public:
  const FileList& listed() const { return listed_; }
};

}  // namespace

bool PortRef::uses(const std::string& name) const {
  const std::vector<PortRef> all = pieces();
  return std::any_of(all.begin(), all.end(), [&name](const PortRef& p) { return p.port == name; });
}

std::string PortRef::text() const {
  if (joined()) {
    std::string inner;
    for (const PortRef& p : parts) inner += (inner.empty() ? "" : ", ") + p.text();
    return "{" + inner + "}";
  }
  if (!sliced()) return port;
  return msb == lsb ? fmt::format("{}[{}]", port, msb) : fmt::format("{}[{}:{}]", port, msb, lsb);
}

const std::vector<PortRole>& port_roles() {
  static const std::vector<PortRole> roles = {
      {"clk", true, false},         {"req", true, false},        {"ack", false, false},
      {"addr", true, false},        {"valid", false, false},     {"out_addr", false, false},
      {"ready", true, true},        {"timestamp", false, true},  {"contention", true, true},
      {"flags", false, true},       {"overflow_count", false, true}, {"special", false, true},
      {"time_in", true, true}};
  return roles;
}

const char* to_string(ReceiverDescription::Collisions c) {
  switch (c) {
    case ReceiverDescription::Collisions::Discard: return "discard";
    case ReceiverDescription::Collisions::Flag: return "flag";
    case ReceiverDescription::Collisions::Pass: return "pass";
  }
  return "?";
}

const char* to_string(ReceiverDescription::Full f) { return f == ReceiverDescription::Full::Drop ? "drop" : "hold"; }
const char* to_string(ReceiverDescription::AddressHeld h) {
  return h == ReceiverDescription::AddressHeld::UntilAckRises ? "until_ack_rises" : "until_ack_falls";
}

const char* to_string(ReceiverDescription::Handshake h) {
  return h == ReceiverDescription::Handshake::FourPhase ? "four_phase" : "two_phase";
}

ReceiverDescription read_receiver_description(const std::string& path) {
  if (!is_input_file(path, "receiver description")) {
    throw InputError(fmt::format("receiver description '{}': no such file", path));
  }
  const TomlValue root = parse_toml_file(path, fmt::format("receiver description '{}'", path));
  const Reader r(path, root);
  ReceiverDescription d;
  d.file = path;
  for (const auto& [key, value] : root.as_table()) {
    static const char* known[] = {"top", "sources", "include_dirs", "defines", "parameters", "clock",
                                  "reset", "ports", "inputs", "bus", "behaviour", "formal"};
    if (std::find(std::begin(known), std::end(known), key) == std::end(known)) {
      r.fail(key, "unknown key" + did_you_mean(key, {std::begin(known), std::end(known)}));
    }
    (void)value;
  }
  d.top = r.identifier(r.string_of(r.need(root, "top", "top"), "top"), "top");
  d.sources = r.paths("sources", false, true);
  d.include_dirs = r.paths("include_dirs", true, false);
  // File lists among the sources stood for what they name (Reader::files_of); the description's
  // own include folders come first and its own defines win over the lists'.
  for (const std::string& dir : r.listed().include_dirs) {
    if (std::find(d.include_dirs.begin(), d.include_dirs.end(), dir) == d.include_dirs.end()) d.include_dirs.push_back(dir);
  }
  for (const auto& [name, value] : r.listed().defines) {
    r.identifier(name, "sources: a file list's +define+");
    // Its value reaches Verilator's arguments, yosys's script and the exported testbench as the
    // TOML's do: printable, a string only as a whole in quotes.
    const std::string inner = value.size() >= 2 && value.front() == '"' && value.back() == '"' ? value.substr(1, value.size() - 2) : value;
    const bool plain = std::all_of(inner.begin(), inner.end(), [](char c) {
      return c > 0x20 && c < 0x7f && c != '"' && c != '\\' && c != ';' && c != '`';
    });
    if (!plain) r.fail("sources", fmt::format("a file list's +define+{}={}: a value of printable characters, a string in quotes", name, value));
    d.defines[name] = value;
  }
  for (const char* table : {"defines", "parameters"}) {
    const TomlValue* t = r.find(root, table);
    if (!t) continue;
    if (!t->is_table()) r.fail(table, "expected a table, e.g. { NAME = 1 }");
    for (const auto& [name, value] : t->as_table()) {
      const std::string label = fmt::format("{}.{}", table, name);
      r.identifier(name, label);
      if (std::string(table) == "defines") {
        d.defines[name] = value.is_string() && value.as_string().empty() ? "" : r.literal(value, label);
      } else {
        d.parameters[name] = r.literal(value, label);
      }
    }
  }
  const TomlValue& clock = r.need(root, "clock", "clock");
  d.clock_hz = r.frequency_of(clock, "clock");
  if (!(d.clock_hz >= 1e3 && d.clock_hz <= 10e9)) r.fail("clock", "must be 1 kHz to 10 GHz");

  // A design without a reset (an FPGA's registers with initial values) says "none": its initial
  // state stands for the reset.
  const TomlValue& reset = r.need(root, "reset", "reset");
  if (!(reset.is_string() && reset.as_string() == "none")) {
    if (!reset.is_table()) {
      r.fail("reset", "expected { port = \"...\", active = \"low\" or \"high\" }, or \"none\" for a design without one");
    }
    for (const auto& [k, v] : reset.as_table()) {
      if (k != "port" && k != "active" && k != "release_cycles") r.fail("reset." + k, "unknown key (port, active, release_cycles)");
      (void)v;
    }
    d.reset_port = r.identifier(r.string_of(r.need(reset, "port", "reset.port"), "reset.port"), "reset.port");
    const std::string active = r.string_of(r.need(reset, "active", "reset.active"), "reset.active");
    if (active != "low" && active != "high") r.fail("reset.active", "must be \"low\" or \"high\"");
    d.reset_active_high = active == "high";
    if (const TomlValue* release = r.find(reset, "release_cycles")) {
      if (!release->is_integer() || release->as_integer() < 0 || release->as_integer() > kMaxResetReleaseCycles) {
        r.fail("reset.release_cycles", fmt::format("expected an integer from 0 to {} (the edges the design's own reset "
                                                   "synchroniser holds it in reset past the release)",
                                                   kMaxResetReleaseCycles));
      }
      d.reset_release_cycles = static_cast<int>(release->as_integer());
    }
  }

  const TomlValue& ports = r.need(root, "ports", "ports");
  if (!ports.is_table()) r.fail("ports", "expected a table of role = \"port name\"");
  for (const auto& entry : ports.as_table()) {
    const std::string& role = entry.first;
    const TomlValue& value = entry.second;
    const std::string key = "ports." + role;
    const auto& roles = port_roles();
    if (std::none_of(roles.begin(), roles.end(), [&role](const PortRole& p) { return role == p.name; })) {
      r.fail(key, "not a port role (clk, req, ack, addr, contention, valid, ready, out_addr, timestamp, "
                  "flags, overflow_count, special, time_in)");
    }
    std::string text;
    if (role == "clk" && value.is_array()) {
      // ["clk_i", "usb_clk"]: the clock on each of these ports, the first the receiver's own; a
      // table { port, clock } is the output side's clock, at a frequency of its own.
      const auto& names = value.as_array();
      if (names.empty()) r.fail(key, "expected a port name or a list of them");
      for (std::size_t i = 1; i < names.size(); ++i) {
        if (!names[i].is_table()) {
          d.clock_also.push_back(r.identifier(r.string_of(names[i], key), key));
          continue;
        }
        const std::string label = fmt::format("{}[{}]", key, i);
        for (const auto& [k, v] : names[i].as_table()) {
          if (k != "port" && k != "clock") r.fail(label + "." + k, "unknown key (port, clock)");
          (void)v;
        }
        if (d.has_out_clock()) r.fail(label, "a second clock of its own: the output side has one clock");
        d.out_clock_port = r.identifier(r.string_of(r.need(names[i], "port", label + ".port"), label + ".port"), label + ".port");
        const TomlValue& clock = r.need(names[i], "clock", label + ".clock");
        if (clock.is_array()) {
          const auto& range = clock.as_array();
          if (range.size() != 2) r.fail(label + ".clock", "expected a frequency or a range of two, [\"24MHz\", \"100MHz\"]");
          d.out_clock_hz = r.frequency_of(range[0], label + ".clock");
          d.out_clock_hz_max = r.frequency_of(range[1], label + ".clock");
          if (!(d.out_clock_hz <= d.out_clock_hz_max)) r.fail(label + ".clock", "a range from its lower frequency to its higher");
        } else {
          d.out_clock_hz = d.out_clock_hz_max = r.frequency_of(clock, label + ".clock");
        }
        for (const double hz : {d.out_clock_hz, d.out_clock_hz_max}) {
          if (!(hz >= 1e3 && hz <= 10e9)) r.fail(label + ".clock", "must be 1 kHz to 10 GHz");
        }
      }
      if (!names[0].is_string()) r.fail(key, "the first is the receiver's own clock, as its port name (its frequency is `clock`)");
      text = r.string_of(names[0], key);
    } else if (value.is_table() && (role == "out_addr" || role == "timestamp" || role == "flags")) {
      // { port = "fifo_data[9:0]", word = 0 }: which of an event's output words carries the role.
      for (const auto& [k, v] : value.as_table()) {
        if (k != "port" && k != "word") r.fail(key + "." + k, "unknown key (port, word)");
        (void)v;
      }
      text = r.string_of(r.need(value, "port", key + ".port"), key + ".port");
      if (const TomlValue* word = r.find(value, "word")) {
        if (!word->is_integer() || word->as_integer() < 0 || word->as_integer() > 7) {
          r.fail(key + ".word", "expected the word of the event that carries it, 0 (the first) to 7");
        }
        if (word->as_integer() > 0) d.word_of[role] = static_cast<int>(word->as_integer());
      }
    } else if (value.is_table()) {
      // { port = "aer_req_n", active = "low" }: a one-bit role's polarity (an FX2 FIFO's write
      // strobe, SLWR#, is a valid active low); valid also takes { port = "data_ready", beat =
      // "rise" }: a level held for each word.
      const bool one_bit =
          role == "req" || role == "ack" || role == "valid" || role == "ready" || role == "contention" || role == "special";
      if (!one_bit) {
        r.fail(key, "only req, ack, valid, ready, contention and special take { port, active } (and valid { port, beat }); "
                    "give the port name");
      }
      const char* keys = role == "valid" ? "port, active, beat" : role == "special" ? "port, active, word" : "port, active";
      for (const auto& [k, v] : value.as_table()) {
        if (k != "port" && k != "active" && !(k == "beat" && role == "valid") && !(k == "word" && role == "special")) {
          r.fail(key + "." + k, fmt::format("unknown key ({})", keys));
        }
        (void)v;
      }
      text = r.string_of(r.need(value, "port", key + ".port"), key + ".port");
      if (const TomlValue* word = r.find(value, "word")) {
        if (!word->is_integer() || word->as_integer() < 0 || word->as_integer() > 7) {
          r.fail(key + ".word", "expected the word of the event that carries the mark, 0 (the first) to 7");
        }
        d.special_word = static_cast<int>(word->as_integer());
        if (*d.special_word > 0) d.word_of[role] = *d.special_word;
      }
      if (const TomlValue* active = r.find(value, "active")) {
        const std::string a = r.string_of(*active, key + ".active");
        if (a != "low" && a != "high") r.fail(key + ".active", "must be \"low\" or \"high\"");
        if (a == "low") d.active_low.insert(role);
      }
      if (const TomlValue* beat = r.find(value, "beat")) {
        const std::string b = r.string_of(*beat, key + ".beat");
        if (b != "high" && b != "rise" && b != "change") {
          r.fail(key + ".beat", "must be \"high\" (a beat at every edge valid is high), \"rise\" (at the edge it "
                                "rises: a level held for each word) or \"change\" (at each edge it toggled: a two-phase "
                                "strobe)");
        }
        d.valid_beat = b == "rise"     ? ReceiverDescription::ValidBeat::Rise
                       : b == "change" ? ReceiverDescription::ValidBeat::Change
                                       : ReceiverDescription::ValidBeat::High;
      }
    } else {
      text = r.string_of(value, key);
    }
    if (!text.empty() && text.front() == '{' && text.back() == '}') {
      if (role != "addr" && role != "out_addr" && role != "timestamp" && role != "time_in") {
        r.fail(key, fmt::format("'{}': only addr, out_addr, timestamp and time_in may join ports", text));
      }
      d.ports[role] = r.joined_ref(text, key);
    } else {
      d.ports[role] = r.port_ref(text, key);
    }
  }
  for (const PortRole& p : port_roles()) {
    if (!p.optional && !d.has(p.name)) r.fail(fmt::format("ports.{}", p.name), "missing");
  }
  // With back-pressure a word stays on the output, valid high, until the consumer takes it: a beat
  // is valid and ready high together, and a level held for each word is what valid already is.
  if (d.valid_beat != ReceiverDescription::ValidBeat::High && d.has("ready")) {
    r.fail("ports.valid.beat", "\"rise\" and \"change\" are for an output without back-pressure; with a ready port a "
                               "beat is an edge where valid and ready are both high");
  }
  // A port plays one role, except that slices of it may play several when their bits do not meet.
  std::map<std::string, std::string> used;  // port -> what uses it
  if (d.has_reset()) used[d.reset_port] = "reset.port";
  // Every piece (a joined role's parts each) against every other, its own role's included.
  std::vector<std::pair<std::string, PortRef>> pieces;
  for (const auto& [role, ref] : d.ports) {
    for (const PortRef& piece : ref.pieces()) pieces.emplace_back(role, piece);
  }
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const auto& [role, ref] = pieces[i];
    for (std::size_t j = 0; j < i; ++j) {
      const auto& [other_role, other] = pieces[j];
      if (other.port != ref.port) continue;
      // Roles read from different words of an event share the output's bits.
      const bool apart = (ref.sliced() && other.sliced() && (ref.lsb > other.msb || other.lsb > ref.msb)) ||
                         d.word(role) != d.word(other_role);
      if (!apart) r.fail("ports." + role, fmt::format("port {} is also ports.{}", ref.port, other_role));
    }
    if (used.count(ref.port) && used[ref.port] == "reset.port") {
      r.fail("ports." + role, fmt::format("port {} is also reset.port", ref.port));
    }
    used[ref.port] = "ports." + role;
  }
  for (const std::string& name : d.clock_also) {
    if (used.count(name)) r.fail("ports.clk", fmt::format("port {} is also {}", name, used[name]));
    used[name] = "ports.clk";
  }
  if (d.has_out_clock()) {
    if (used.count(d.out_clock_port)) r.fail("ports.clk", fmt::format("port {} is also {}", d.out_clock_port, used[d.out_clock_port]));
    used[d.out_clock_port] = "ports.clk";
  }
  if (const TomlValue* inputs = r.find(root, "inputs")) {
    if (!inputs->is_table()) r.fail("inputs", "expected a table of PORT = value");
    for (const auto& [name, value] : inputs->as_table()) {
      const std::string label = "inputs." + name;
      r.identifier(name, label);
      if (used.count(name)) r.fail(label, fmt::format("port {} is also {}", name, used[name]));
      if (value.is_boolean()) {
        d.inputs[name] = value.as_boolean() ? 1 : 0;
      } else if (value.is_integer() && value.as_integer() >= 0) {
        d.inputs[name] = static_cast<std::uint64_t>(value.as_integer());
      } else if (const std::optional<std::string> number =
                     value.is_string() ? verilog_integer(value.as_string()) : std::nullopt;
                 number && number->front() != '-') {
        d.inputs[name] = std::stoull(*number);
      } else {
        r.fail(label, "expected a non-negative integer (a number, or a Verilog literal such as \"8'd50\") or a boolean");
      }
    }
  }

  if (const TomlValue* bus = r.find(root, "bus")) {
    if (!bus->is_table()) r.fail("bus", "expected a table");
    for (const auto& [key, value] : bus->as_table()) {
      if (key == "address_held") {
        const std::string held = r.string_of(value, "bus.address_held");
        if (held == "until_ack_rises") d.address_held = ReceiverDescription::AddressHeld::UntilAckRises;
        else if (held == "until_ack_falls") d.address_held = ReceiverDescription::AddressHeld::UntilAckFalls;
        else r.fail("bus.address_held", "must be \"until_ack_rises\" (the imager's pixels) or \"until_ack_falls\"");
      } else if (key == "handshake") {
        const std::string handshake = r.string_of(value, "bus.handshake");
        if (handshake == "four_phase") d.handshake = ReceiverDescription::Handshake::FourPhase;
        else if (handshake == "two_phase") d.handshake = ReceiverDescription::Handshake::TwoPhase;
        else r.fail("bus.handshake", "must be \"four_phase\" (the imager's bus) or \"two_phase\" (each edge of Req an event)");
      } else {
        r.fail("bus." + key, "unknown key (address_held, handshake)");
      }
    }
    if (d.two_phase() && d.address_held == ReceiverDescription::AddressHeld::UntilAckFalls) {
      r.fail("bus.address_held", "a two-phase Ack does not fall: its sender holds the address until Ack changes, "
                                 "\"until_ack_rises\"");
    }
  }

  const TomlValue& behaviour = r.need(root, "behaviour", "behaviour");
  if (!behaviour.is_table()) r.fail("behaviour", "expected a table");
  for (const auto& [key, value] : behaviour.as_table()) {
    static const char* known[] = {"collisions", "full", "timestamp_tick", "timestamp_bits", "timestamp_offset_cycles",
                                  "ack_latency_cycles", "synchroniser_flops", "event_words"};
    if (std::find(std::begin(known), std::end(known), key) == std::end(known)) {
      r.fail("behaviour." + key, "unknown key" + did_you_mean(key, {std::begin(known), std::end(known)}));
    }
    (void)value;
  }
  const std::string collisions = r.string_of(r.need(behaviour, "collisions", "behaviour.collisions"), "behaviour.collisions");
  if (collisions == "discard") d.collisions = ReceiverDescription::Collisions::Discard;
  else if (collisions == "flag") d.collisions = ReceiverDescription::Collisions::Flag;
  else if (collisions == "pass") d.collisions = ReceiverDescription::Collisions::Pass;
  else r.fail("behaviour.collisions", "must be \"discard\", \"flag\" or \"pass\"");
  // Without a ready port the output takes every beat at once, so it is never full.
  const TomlValue* full_value = r.find(behaviour, "full");
  if (!full_value && d.has("ready")) r.fail("behaviour.full", "missing (needed with a ready port)");
  const std::string full = full_value ? r.string_of(*full_value, "behaviour.full") : "drop";
  if (full == "drop") d.full = ReceiverDescription::Full::Drop;
  else if (full == "hold") d.full = ReceiverDescription::Full::Hold;
  else r.fail("behaviour.full", "must be \"drop\" or \"hold\"");

  const TomlValue& latency = r.need(behaviour, "ack_latency_cycles", "behaviour.ack_latency_cycles");
  const auto& l = latency.as_array();
  if (!latency.is_array() || l.size() != 2 || !l[0].is_integer() || !l[1].is_integer() || l[0].as_integer() < 1 ||
      l[1].as_integer() < l[0].as_integer() || l[1].as_integer() > 1000) {
    r.fail("behaviour.ack_latency_cycles", "expected [min, max] clock edges, 1 <= min <= max <= 1000");
  }
  d.ack_latency_min = static_cast<int>(l[0].as_integer());
  d.ack_latency_max = static_cast<int>(l[1].as_integer());
  if (const TomlValue* flops = r.find(behaviour, "synchroniser_flops")) {
    if (!flops->is_integer() || flops->as_integer() < 0 || flops->as_integer() > 8) {
      r.fail("behaviour.synchroniser_flops",
             "expected the flops Req passes before any logic reads it, 0 (synchronised outside the design) to 8");
    }
    d.synchroniser_flops = static_cast<int>(flops->as_integer());
  }

  // The tick and the wrap are the stamp's, and the time a design reads (time_in) counts the same.
  if (const TomlValue* words = r.find(behaviour, "event_words")) {
    if (!words->is_integer() || words->as_integer() < 1 || words->as_integer() > 8) {
      r.fail("behaviour.event_words", "expected the output words an event takes, 1 to 8");
    }
    d.event_words = static_cast<int>(words->as_integer());
  }
  for (const auto& [role, word] : d.word_of) {
    if (word >= d.event_words) {
      r.fail("ports." + role + ".word",
             fmt::format("word {} of an event of {} (behaviour.event_words; the first is 0)", word, d.event_words));
    }
  }
  if (d.event_words > 1 && d.valid_beat != ReceiverDescription::ValidBeat::High) {
    r.fail("behaviour.event_words", "an event of several words takes a valid that is high for each word taken");
  }

  if (d.has("timestamp") || d.has("time_in")) {
    const TomlValue& tick = r.need(behaviour, "timestamp_tick", "behaviour.timestamp_tick");
    d.timestamp_tick = r.quantity_of(tick, "behaviour.timestamp_tick", "s");
    if (!(d.timestamp_tick <= 1.0)) r.fail("behaviour.timestamp_tick", "at most 1 s");
    // The receiver counts clock cycles, so a tick is a whole number of them.
    const double cycles = d.timestamp_tick * d.clock_hz;
    if (!(cycles >= 1 - 1e-9)) r.fail("behaviour.timestamp_tick", "shorter than a clock period");
    if (std::fabs(cycles - std::round(cycles)) > 1e-6 * cycles) {
      r.fail("behaviour.timestamp_tick", fmt::format("{:.6g} clock periods; a tick is a whole number of them", cycles));
    }
    d.timestamp_cycles = static_cast<std::uint64_t>(std::llround(cycles));
    const TomlValue& bits = r.need(behaviour, "timestamp_bits", "behaviour.timestamp_bits");
    if (!bits.is_integer() || bits.as_integer() < 2 || bits.as_integer() > 64) {
      r.fail("behaviour.timestamp_bits", "expected an integer from 2 to 64");
    }
    d.timestamp_bits = static_cast<int>(bits.as_integer());
    if (const TomlValue* offset = r.find(behaviour, "timestamp_offset_cycles")) {
      if (!d.has("timestamp")) r.fail("behaviour.timestamp_offset_cycles", "given, but [ports] names no timestamp");
      if (!offset->is_integer() || offset->as_integer() < 0 || offset->as_integer() > d.ack_latency_max + 1) {
        r.fail("behaviour.timestamp_offset_cycles",
               fmt::format("expected the edge of the stamp, 0 to {} (ack_latency_cycles max + 1), counting the first "
                           "rising edge after Req rose as 1",
                           d.ack_latency_max + 1));
      }
      d.timestamp_offset_cycles = static_cast<int>(offset->as_integer());
    }
  } else {
    for (const char* key : {"timestamp_tick", "timestamp_bits", "timestamp_offset_cycles"}) {
      if (r.find(behaviour, key)) r.fail(fmt::format("behaviour.{}", key), "given, but [ports] names no timestamp or time_in");
    }
  }

  if (const TomlValue* formal = r.find(root, "formal")) {
    if (!formal->is_table()) r.fail("formal", "expected a table");
    for (const auto& [key, value] : formal->as_table()) {
      const std::string label = "formal." + key;
      if (key == "parameters") {
        if (!value.is_table()) r.fail(label, "expected a table, e.g. { DEPTH = 4 }");
        for (const auto& [name, v] : value.as_table()) {
          r.identifier(name, label + "." + name);
          d.formal.parameters[name] = r.literal(v, label + "." + name);
        }
      } else if (key == "inputs") {
        if (!value.is_table()) r.fail(label, "expected a table of PORT = value");
        for (const auto& [name, v] : value.as_table()) {
          if (!d.inputs.count(name)) r.fail(label + "." + name, "not one of [inputs]");
          if (!v.is_integer() || v.as_integer() < 0) r.fail(label + "." + name, "expected a non-negative integer");
          d.formal.inputs[name] = static_cast<std::uint64_t>(v.as_integer());
        }
      } else if (key == "sources") {
        d.formal.sources = r.paths_in(&value, label, false, true);
        for (std::size_t i = 0; i < d.formal.sources.size(); ++i) {
          if (is_vhdl_source(d.formal.sources[i])) {
            r.fail(fmt::format("{}[{}]", label, i),
                   "yosys reads Verilog or SystemVerilog here; a VHDL design's proof reads GHDL's Verilog of `sources`");
          }
        }
      } else if (key == "unsynchronised_outputs") {
        if (!value.is_array()) r.fail(label, "expected a list of output port names");
        for (const TomlValue& v : value.as_array()) d.formal.unsynchronised_outputs.push_back(r.identifier(r.string_of(v, label), label));
      } else if (key == "fifo_words" || key == "depth") {
        const long hi = key == "depth" ? 5000 : 4096;
        if (!value.is_integer() || value.as_integer() < (key == "depth" ? 1 : 0) || value.as_integer() > hi) {
          r.fail(label, fmt::format("expected an integer up to {}", hi));
        }
        if (key == "depth") d.formal.depth = static_cast<int>(value.as_integer());
        else d.formal.fifo_words = static_cast<int>(value.as_integer());
      } else {
        r.fail(label, "unknown key (parameters, inputs, fifo_words, depth, unsynchronised_outputs, sources)");
      }
    }
  }

  if (d.collisions != ReceiverDescription::Collisions::Pass && !d.has("contention")) {
    r.fail("behaviour.collisions", fmt::format("\"{}\" needs the contention port ([ports] contention)", collisions));
  }
  if (d.collisions == ReceiverDescription::Collisions::Flag && !d.has("flags")) {
    r.fail("behaviour.collisions", "\"flag\" needs the flags port ([ports] flags)");
  }
  return d;
}

}  // namespace aesim
