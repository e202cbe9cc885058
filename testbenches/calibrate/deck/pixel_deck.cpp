#include "deck/pixel_deck.hpp"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <regex>
#include <sstream>
#include <string_view>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/text/ascii_case.hpp"
#include "aesim/files/input_path.hpp"

namespace aesim {
namespace {

namespace fs = std::filesystem;

// Decks are text of kilobytes; a PDK's model file can be megabytes. Beyond this it is not a deck.
constexpr std::uintmax_t kMaxDeckBytes = 64u << 20;

std::string read_text(const std::string& path, const std::string& what) {
  require_input_file(path, what);
  std::error_code ec;
  if (fs::file_size(path, ec) > kMaxDeckBytes) {
    throw InputError(fmt::format("{} '{}' is larger than {} MiB", what, path, kMaxDeckBytes >> 20));
  }
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in && !in.eof()) throw InputError(fmt::format("{} '{}' cannot be read", what, path));
  return text.str();
}

std::uint64_t fnv1a(const std::string& text, std::uint64_t h) {
  for (unsigned char c : text) h = (h ^ c) * 0x100000001b3ull;
  return h;
}

// SPICE lines with their '+' continuations joined and comments dropped, as ngspice reads them.
std::vector<std::string> logical_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") != std::string::npos && line[line.find_first_not_of(" \t")] == '*') continue;
    for (const char* marker : {"$ ", ";"}) {
      const auto comment = line.find(marker);
      if (comment != std::string::npos) line.erase(comment);
    }
    const auto first = line.find_first_not_of(" \t");
    if (first == std::string::npos) continue;
    if (line[first] == '+' && !lines.empty()) {
      lines.back() += " " + line.substr(first + 1);
    } else {
      lines.push_back(line.substr(first));
    }
  }
  return lines;
}

std::vector<std::string> tokens(const std::string& line) {
  std::vector<std::string> out;
  std::istringstream in(line);
  std::string t;
  while (in >> t) out.push_back(t);
  return out;
}

// A file a deck reads: all of it (`.include FILE`), or one section of it (`.lib FILE SECTION`).
struct Included {
  std::string path;
  std::string section;  // lower case; empty for the whole file
};

// The file an `.include FILE` or `.lib FILE SECTION` line names (quoted or not), and what follows
// it; nothing for other lines and for `.lib SECTION` (a section's start).
struct IncludeLine {
  std::string keyword, file, rest;
};
std::optional<IncludeLine> include_line(const std::string& line) {
  std::istringstream in(line);
  std::string keyword;
  in >> keyword;
  const std::string lower = ascii_lower(keyword);
  if (lower != ".include" && lower != ".inc" && lower != ".lib") return std::nullopt;
  std::string rest;
  std::getline(in, rest);
  rest.erase(0, rest.find_first_not_of(" \t"));
  if (rest.empty()) return std::nullopt;
  std::string file;
  if (rest.front() == '"' || rest.front() == '\'') {
    const auto close = rest.find(rest.front(), 1);
    if (close == std::string::npos) return std::nullopt;
    file = rest.substr(1, close - 1);
    rest.erase(0, close + 1);
  } else {
    const auto end = rest.find_first_of(" \t");
    file = rest.substr(0, end);
    rest.erase(0, end == std::string::npos ? rest.size() : end);
  }
  if (lower == ".lib" && tokens(rest).empty()) return std::nullopt;
  return IncludeLine{keyword, file, rest};
}

// The files a deck's lines read, resolved against its folder as ngspice does (a `.lib NAME` of
// one word opens a section of the file it is in, not a file).
std::vector<Included> includes(const std::vector<std::string>& lines, const fs::path& folder) {
  std::vector<Included> out;
  for (const std::string& line : lines) {
    const std::optional<IncludeLine> inc = include_line(line);
    if (!inc) continue;
    const fs::path p = fs::path(inc->file).is_absolute() ? fs::path(inc->file) : folder / inc->file;
    const std::vector<std::string> section = tokens(inc->rest);
    out.push_back({p.string(), ascii_lower(inc->keyword) == ".lib" ? ascii_lower(section.front()) : ""});
  }
  return out;
}

// The lines of a file ngspice reads for `section`: those between `.lib SECTION` and its `.endl`;
// for the whole file (no section), those outside every section, which ngspice reads only when
// another line names them. So the includes, devices and statistics of a PDK's other corners (its
// `mos_tt_stat` beside the `mos_tt` a deck names) are not taken for the deck's.
std::vector<std::string> section_lines(const std::vector<std::string>& lines, const std::string& section) {
  std::vector<std::string> out;
  std::string open;  // the section the line is in, lower case; empty outside sections
  bool inside = false;
  for (const std::string& line : lines) {
    const std::vector<std::string> t = tokens(line);
    const std::string keyword = t.empty() ? "" : ascii_lower(t[0]);
    if (keyword == ".lib" && t.size() == 2) {
      inside = true;
      open = ascii_lower(t[1]);
      continue;
    }
    if (keyword == ".endl") {
      inside = false;
      continue;
    }
    if (section.empty() ? !inside : (inside && open == section)) out.push_back(line);
  }
  return out;
}

// ngspice runs commands from a deck's .control (and .exec) blocks, `shell` among them, which could
// run any program: the files a deck includes must describe a circuit only, and the deck's own
// blocks are left out of the runs (circuit_of), except one that loads an OSDI library, which the
// runs need given with --osdi instead.
void refuse_commands(const std::string& text, const std::string& file, bool own_deck) {
  std::istringstream in(text);
  std::string line;
  int block = 0;  // the line of the block's opening, 0 outside one
  std::string keyword_of_block;
  for (int n = 1; std::getline(in, line); ++n) {
    const std::vector<std::string> t = tokens(line);
    if (t.empty()) continue;
    const std::string keyword = ascii_lower(t[0]);
    if (block == 0 && (keyword == ".control" || keyword == ".exec")) {
      block = n;
      keyword_of_block = keyword;
      continue;
    }
    if (block == 0) continue;
    // A block that loads OSDI libraries (as a PDK's examples do) has a way aesim runs itself.
    if (keyword == "osdi" || keyword == "pre_osdi") {
      throw InputError(fmt::format("'{}' line {}: a {} block that loads an OSDI library ({} {}); aesim calibrate runs "
                                   "the circuit of a deck only: remove the block and give the library with --osdi",
                                   file, block, keyword_of_block, t[0], t.size() > 1 ? t[1] : std::string()));
    }
    if (keyword == ".endc") break;
  }
  if (block != 0 && !own_deck) {
    throw InputError(fmt::format("'{}' line {}: a {} block in a file the deck includes, whose commands ngspice would "
                                 "run (shell commands among them); aesim calibrate runs circuits only: remove the block",
                                 file, block, keyword_of_block));
  }
}

// Statements of a deck's own testbench, which a deck run on its own needs and the runs replace.
bool testbench_statement(const std::string& keyword) {
  static const char* const kStatements[] = {".tran", ".ac",    ".dc",    ".op",     ".noise", ".tf",   ".sens",
                                            ".pz",   ".disto", ".four",  ".sp",     ".pss",   ".print", ".plot",
                                            ".probe", ".save", ".meas",  ".measure", ".ic",   ".nodeset", ".width"};
  return std::any_of(std::begin(kStatements), std::end(kStatements), [&](const char* s) { return keyword == s; });
}

}  // namespace

DeckCircuit circuit_of(const std::string& text, const std::string& folder) {
  DeckCircuit c;
  std::istringstream in(text);
  std::string line;
  int depth = 0;  // .subckt nesting
  bool in_section = false, in_block = false, kept = true;
  int block_from = 0, elements = 0;
  std::vector<std::string> statements;
  for (int n = 1; std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const auto first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '*') {
      if (!in_block) c.text += line + "\n";
      continue;
    }
    if (line[first] == '+') {  // a continuation goes where its line went
      if (kept && !in_block) c.text += line + "\n";
      continue;
    }
    const std::vector<std::string> t = tokens(line);
    if (t.empty()) {  // white space SPICE reads as such (a stray carriage return)
      if (!in_block) c.text += line + "\n";
      continue;
    }
    const std::string keyword = ascii_lower(t[0]);
    if (in_block) {
      if (keyword == ".endc") {
        in_block = false;
        c.left_out.push_back(fmt::format("its .control block (lines {} to {})", block_from, n));
      }
      continue;
    }
    kept = true;
    if (n == 1 && line[first] != '.') {  // SPICE reads a netlist's first line as its title
      kept = false;
      c.left_out.push_back("its title line");
      continue;
    }
    if (depth == 0 && !in_section) {
      if (keyword == ".end") break;
      if (keyword == ".control" || keyword == ".exec") {
        in_block = true;
        block_from = n;
        continue;
      }
      if (line[first] != '.' || testbench_statement(keyword)) {
        kept = false;
        if (line[first] != '.') {
          ++elements;
        } else if (std::find(statements.begin(), statements.end(), keyword) == statements.end()) {
          statements.push_back(keyword);
        }
        continue;
      }
    }
    if (keyword == ".subckt") ++depth;
    if (keyword == ".ends" && depth > 0) --depth;
    if (keyword == ".lib" && t.size() == 2) in_section = true;
    if (keyword == ".endl") in_section = false;
    // The runs' testbench is elsewhere: a file named from the deck's folder is named whole.
    const std::optional<IncludeLine> inc = include_line(line);
    if (inc && !fs::path(inc->file).is_absolute()) {
      c.text += fmt::format("{} \"{}\"{}\n", inc->keyword, (fs::path(folder) / inc->file).lexically_normal().string(), inc->rest);
    } else {
      c.text += line + "\n";
    }
  }
  if (elements > 0) c.left_out.push_back(fmt::format("its testbench's {} element line{}", elements, elements == 1 ? "" : "s"));
  if (!statements.empty()) c.left_out.push_back(fmt::format("its {}", fmt::join(statements, ", ")));
  return c;
}

namespace {

struct Subcircuit {
  std::vector<std::string> ports, params;
  std::vector<std::string> body;
};

std::optional<Subcircuit> find_subckt(const std::vector<std::string>& lines, const std::string& name) {
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::vector<std::string> t = tokens(lines[i]);
    if (t.size() < 2 || ascii_lower(t[0]) != ".subckt" || ascii_lower(t[1]) != ascii_lower(name)) continue;
    Subcircuit s;
    bool in_params = false;
    for (std::size_t k = 2; k < t.size(); ++k) {
      const std::string word = ascii_lower(t[k]);
      if (word == "params:") {
        in_params = true;
      } else if (in_params || word.find('=') != std::string::npos) {
        in_params = true;
        s.params.push_back(word.substr(0, word.find('=')));
      } else {
        s.ports.push_back(t[k]);
      }
    }
    for (std::size_t j = i + 1; j < lines.size(); ++j) {
      const std::vector<std::string> words = tokens(lines[j]);
      if (!words.empty() && ascii_lower(words.front()) == ".ends") break;
      s.body.push_back(lines[j]);
    }
    return s;
  }
  return std::nullopt;
}

// The deck's own subcircuit a run calibrates when --subckt names none: the one of its own
// (not its included models') with three ports (and one more for each --bias) and a parameter iph;
// none or several is an InputError listing them.
std::string only_pixel_subckt(const std::vector<std::string>& lines, const std::string& path, std::size_t biased) {
  std::vector<std::string> all, pixels;
  for (const std::string& line : lines) {
    const std::vector<std::string> t = tokens(line);
    if (t.size() < 2 || ascii_lower(t[0]) != ".subckt") continue;
    all.push_back(t[1]);
    const std::optional<Subcircuit> s = find_subckt({line}, t[1]);
    if (s && s->ports.size() == 3 + biased && std::find(s->params.begin(), s->params.end(), "iph") != s->params.end()) {
      pixels.push_back(t[1]);
    }
  }
  if (pixels.size() == 1) return pixels.front();
  std::string list;
  for (const std::string& name : pixels.empty() ? all : pixels) list += (list.empty() ? "" : ", ") + name;
  throw InputError(fmt::format("deck '{}': --subckt names the pixel's subcircuit ({})", path,
                               pixels.size() > 1 ? "the deck defines several with three ports and iph: " + list
                               : all.empty()     ? std::string("the deck itself defines none")
                               : biased == 0     ? "none of the deck's own has three ports, vdd out gnd, and a parameter iph: " + list
                                                 : fmt::format("none of the deck's own has {} ports, vdd out gnd and those --bias "
                                                               "holds, and a parameter iph: {}", 3 + biased, list)));
}

// A name a PDK gives a switch of its statistical models.
bool statistical_switch(const std::string& name) {
  return name.rfind("sw_stat_", 0) == 0 || (name.rfind("mc_", 0) == 0 && name.find("switch") != std::string::npos);
}

// Notes in `deck` the statistical switches `lines` define and whether they draw at random.
void find_statistics(const std::vector<std::string>& lines, const std::string& file, PixelDeck& deck) {
  for (const std::string& line : lines) {
    const std::string lower = ascii_lower(line);
    if (deck.statistical_file.empty()) {
      for (const char* f : {"agauss(", "gauss(", "aunif(", "unif("}) {
        const auto at = lower.find(f);
        // A whole word: "agauss(" inside "xagauss(" is someone's own function.
        if (at != std::string::npos && (at == 0 || !(std::isalnum(static_cast<unsigned char>(lower[at - 1])) || lower[at - 1] == '_'))) {
          deck.statistical_file = file;
          break;
        }
      }
    }
    if (lower.rfind(".param", 0) != 0) continue;
    // .param a=1 b = 2 ...: each name is the word before an '='.
    std::string spaced = lower.substr(6);
    for (std::size_t at = spaced.find('='); at != std::string::npos; at = spaced.find('=', at + 1)) {
      std::size_t end = at;
      while (end > 0 && spaced[end - 1] == ' ') --end;
      std::size_t begin = end;
      while (begin > 0 && (std::isalnum(static_cast<unsigned char>(spaced[begin - 1])) || spaced[begin - 1] == '_')) --begin;
      const std::string name = spaced.substr(begin, end - begin);
      if (statistical_switch(name) &&
          std::find(deck.statistical_switches.begin(), deck.statistical_switches.end(), name) == deck.statistical_switches.end()) {
        deck.statistical_switches.push_back(name);
      }
    }
  }
}

// The supply a MOS model's name gives, 0 where it gives none: digits, 'v' or 'p', a digit (SKY130's
// and open_pdks' GF180's `_01v8`, `_03v3`, GF180's own `_3p3`) after '_' or a gate's 'g'
// (`_g5v0d10v5`), ending the name or followed by a letter or '_'. Only names of MOS devices ("fet",
// "mos"): a capacitor's `mim_2p0fF` is its density, not a supply.
double rating_in_name(const std::string& word) {
  const std::string w = ascii_lower(word);
  const std::size_t kind = std::min(w.find("fet"), w.find("mos"));
  if (kind == std::string::npos || w.find('=') != std::string::npos) return 0;
  static const std::regex rated("[_g]([0-9]{1,2})[vp]([0-9])(?=$|[_a-z])");
  std::smatch m;
  const std::string tail = w.substr(kind);
  if (!std::regex_search(tail, m, rated)) return 0;
  return std::stoi(m[1].str()) + std::stoi(m[2].str()) / 10.0;
}

// Notes in `deck` the lowest-rated MOS device the element lines (M, or X for a PDK's subcircuit
// devices) of `lines` use.
void find_ratings(const std::vector<std::string>& lines, PixelDeck& deck) {
  for (const std::string& line : lines) {
    const std::vector<std::string> t = tokens(line);
    if (t.empty()) continue;
    const char kind = static_cast<char>(std::tolower(static_cast<unsigned char>(t[0][0])));
    if (kind != 'm' && kind != 'x') continue;
    for (std::size_t k = 1; k < t.size(); ++k) {
      const double r = rating_in_name(t[k]);
      if (r > 0 && (deck.device_rating == 0 || r < deck.device_rating)) {
        deck.device_rating = r;
        deck.rated_device = t[k];
      }
    }
  }
}

}  // namespace

std::string supply_rating_note(const PixelDeck& deck, double vdd) {
  if (!(deck.device_rating > 0) || vdd <= 1.1 * deck.device_rating) return {};
  return fmt::format("the deck's {} is a {:g} V device (so its name says) and the runs' supply is {:g} V (--vdd, "
                     "3.3 V unless given): its periods, reset and energy are measured at that supply; "
                     "--vdd {:g}V calibrates it at its own",
                     deck.rated_device, deck.device_rating, vdd, deck.device_rating);
}

StatisticsNote statistics_note(const PixelDeck& deck) {
  if (!deck.statistical_switches.empty()) {
    std::string names;
    for (const std::string& n : deck.statistical_switches) names += (names.empty() ? "" : ", ") + n;
    return {fmt::format("statistical models: the deck's switches {} were set to 0 for the table (nominal models) "
                        "and to 1 in the Monte Carlo runs",
                        names),
            false};
  }
  if (!deck.statistical_file.empty() && !deck.mc_parameter) {
    return {fmt::format("statistical models: '{}' draws at random (agauss, gauss, aunif or unif) and the deck has "
                        "no switch aesim knows (sw_stat_*, mc_*switch*) nor an `mc` parameter: each point of the "
                        "table is one draw of ngspice's seed 1, not the nominal circuit",
                        deck.statistical_file),
            true};
  }
  return {};
}

std::vector<std::string> port_nets_by_name(const std::vector<std::string>& ports) {
  static const char* const kSupply[] = {"vdd", "vcc", "avdd", "vdda", "dvdd", "vpwr", "vdd!", "supply", "vpos"};
  static const char* const kOutput[] = {"out", "vout", "spike", "fire", "req", "pulse", "event", "o", "q"};
  static const char* const kGround[] = {"gnd", "vss", "0", "agnd", "vssa", "dgnd", "vgnd", "gnd!", "vneg"};
  const auto in = [](const auto& names, const std::string& port) {
    return std::any_of(std::begin(names), std::end(names), [&](const char* n) { return port == n; });
  };
  std::vector<std::string> nets;
  for (const std::string& port : ports) {
    const std::string p = ascii_lower(port);
    nets.push_back(in(kSupply, p) ? "vdd" : in(kOutput, p) ? "out" : in(kGround, p) ? "0" : "");
  }
  std::vector<std::string> sorted = nets;
  std::sort(sorted.begin(), sorted.end());
  if (sorted == std::vector<std::string>{"0", "out", "vdd"}) return nets;
  return {"vdd", "out", "0"};
}

std::string bias_net(const std::string& port) { return "aesim_bias_" + ascii_lower(port); }

namespace {

// A compatibility mode as ngspice spells them (letters and digits); an InputError naming `source`
// otherwise.
void check_ngbehavior(const std::string& mode, const std::string& source) {
  const bool word = !mode.empty() && mode.size() <= 16 && std::all_of(mode.begin(), mode.end(), [](unsigned char c) {
    return std::islower(c) || std::isdigit(c);
  });
  if (!word) {
    throw InputError(fmt::format("{}: ngbehavior '{}': expected ngspice's compatibility letters (hs, hsa, ps, lt, "
                                 "ltpsa, ki, ...)", source, mode));
  }
}

}  // namespace

std::string spiceinit_ngbehavior(const std::string& folder) {
  const fs::path file = fs::path(folder) / ".spiceinit";
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) return "";
  std::istringstream in(read_text(file.string(), "the .spiceinit beside the deck"));
  std::string line, mode;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string command, rest;
    if (!(words >> command) || command != "set") continue;
    std::getline(words, rest);
    rest.erase(std::remove_if(rest.begin(), rest.end(), [](unsigned char c) { return std::isspace(c); }), rest.end());
    constexpr std::string_view kKey = "ngbehavior=";
    if (rest.compare(0, kKey.size(), kKey) != 0) continue;
    mode = rest.substr(kKey.size());
    // ngspice's `set` takes a value quoted too.
    if (mode.size() >= 2 && mode.front() == '"' && mode.back() == '"') mode = mode.substr(1, mode.size() - 2);
  }
  if (!mode.empty()) check_ngbehavior(mode, file.string());
  return mode;
}

void choose_ngbehavior(PixelDeck& deck, const std::string& chosen) {
  if (!chosen.empty()) {
    check_ngbehavior(chosen, "--ngbehavior");
    deck.ngbehavior = chosen;
    deck.ngbehavior_spiceinit.clear();
    return;
  }
  const fs::path folder = fs::path(deck.path).parent_path();
  deck.ngbehavior = spiceinit_ngbehavior(folder.string());
  deck.ngbehavior_spiceinit = deck.ngbehavior.empty() ? "" : (folder / ".spiceinit").string();
}

PixelDeck read_pixel_deck(const std::string& path, const std::string& subckt, const std::string& probe_node,
                          const std::vector<std::string>& osdi, const std::vector<PortBias>& biases) {
  PixelDeck deck;
  const std::string text = read_text(path, "deck");
  std::error_code ec;
  deck.path = fs::absolute(path, ec).lexically_normal().string();
  // The deck's folder goes into the testbench in the paths of the files it includes (`.include
  // "FOLDER/FILE"`, circuit_of), and ngspice's reader cuts that line at a ';' or a " $" (its comment
  // marks) and has no escape for a quote: measured on ngspice 39.
  const auto unquotable = [](const std::string& p) {
    const bool control =
        std::any_of(p.begin(), p.end(), [](char c) { return c == '"' || static_cast<unsigned char>(c) < 0x20; });
    return control || p.find(';') != std::string::npos || p.find(" $") != std::string::npos;
  };
  // An OSDI library's goes into a control line, `pre_osdi 'PATH'`: ngspice 46 keeps a double quote
  // as part of the name, keeps blanks inside single quotes, and replaces $NAME with a variable
  // even there.
  const auto unquotable_command = [](const std::string& p) {
    return std::any_of(p.begin(), p.end(), [](char c) {
      return c == '\'' || c == '"' || c == '$' || c == ';' || c == '\\' || static_cast<unsigned char>(c) < 0x20;
    });
  };
  if (unquotable(deck.path)) {
    throw InputError(fmt::format("deck '{}': its path has a quote, ';', ' $' or a control character, which ngspice's "
                                 ".include cannot carry; rename or move the deck",
                                 path));
  }
  for (const std::string& library : osdi) {
    require_input_file(library, "--osdi");
    const std::string absolute = fs::absolute(library, ec).lexically_normal().string();
    if (unquotable_command(absolute)) {
      throw InputError(fmt::format("--osdi '{}': its path has a quote, '$', ';', a backslash or a control character, "
                                   "which ngspice's pre_osdi cannot carry; rename or move the file",
                                   library));
    }
    deck.osdi.push_back(absolute);
  }
  deck.given = path;
  std::uint64_t h = fnv1a(text, 0xcbf29ce484222325ull);
  refuse_commands(text, path, true);
  const DeckCircuit circuit = circuit_of(text, fs::path(deck.path).parent_path().string());
  deck.circuit = circuit.text;
  deck.left_out = circuit.left_out;
  const std::vector<std::string> lines = logical_lines(text);
  deck.subckt = subckt.empty() ? only_pixel_subckt(lines, path, biases.size()) : subckt;
  const std::string& name = deck.subckt;
  std::optional<Subcircuit> found = find_subckt(lines, name);
  find_statistics(lines, path, deck);
  find_ratings(lines, deck);
  // Every file (or section of one) the deck reads, and those they read (a PDK's .lib files nest),
  // once each; a file is read, hashed and searched for commands once, whole, however many of its
  // sections are named.
  std::vector<Included> pending = includes(lines, fs::path(deck.path).parent_path());
  std::vector<std::string> seen;
  std::map<std::string, std::vector<std::string>> lines_of;  // each file read, by its canonical path
  while (!pending.empty()) {
    const std::string inc = pending.front().path, section = pending.front().section;
    pending.erase(pending.begin());
    const std::string file_key = fs::weakly_canonical(inc, ec).string(), key = file_key + "\n" + section;
    if (std::find(seen.begin(), seen.end(), key) != seen.end()) continue;
    seen.push_back(key);
    if (seen.size() > 4096) throw InputError(fmt::format("deck '{}' includes more than 4096 files", path));
    if (!is_input_file(inc, "included file")) {
      if (fs::exists(inc, ec) || fs::is_symlink(inc, ec)) throw InputError(fmt::format("file '{}' included by the deck: {}", inc, not_a_file(inc)));
      continue;  // missing: ngspice names it on the first run
    }
    auto file = lines_of.find(file_key);
    if (file == lines_of.end()) {
      const std::string included = read_text(inc, "included file");
      refuse_commands(included, inc, false);
      h = fnv1a(included, h);
      file = lines_of.emplace(file_key, logical_lines(included)).first;
    }
    const std::vector<std::string> included_lines = section_lines(file->second, section);
    if (!found) {
      found = find_subckt(included_lines, name);
      if (found) find_ratings(included_lines, deck);
    }
    find_statistics(included_lines, inc, deck);
    for (const Included& next : includes(included_lines, fs::path(inc).parent_path())) pending.push_back(next);
  }
  for (const std::string& library : deck.osdi) h = fnv1a(read_text(library, "--osdi"), h);
  deck.hash = fmt::format("{:016x}", h);
  if (!found) {
    throw InputError(fmt::format("deck '{}': no subcircuit '{}' (in the deck or the files it includes)", path, name));
  }
  const std::string port_list = fmt::format("{}", fmt::join(found->ports, " "));
  // Its ports: those --bias holds, and three more, the supply, the output and the ground.
  std::vector<std::string> rest;
  std::vector<bool> biased(found->ports.size(), false);
  for (const PortBias& b : biases) {
    const auto at = std::find_if(found->ports.begin(), found->ports.end(),
                                 [&](const std::string& port) { return ascii_lower(port) == ascii_lower(b.port); });
    if (at == found->ports.end()) {
      throw InputError(fmt::format("--bias {}: subcircuit '{}' has no port {} (its ports: {})", b.port, name, b.port, port_list));
    }
    if (biased[static_cast<std::size_t>(at - found->ports.begin())]) {
      throw InputError(fmt::format("--bias {}: given twice", b.port));
    }
    biased[static_cast<std::size_t>(at - found->ports.begin())] = true;
    deck.biases.push_back({*at, b.volts});
  }
  for (std::size_t i = 0; i < found->ports.size(); ++i) {
    if (!biased[i]) rest.push_back(found->ports[i]);
  }
  if (rest.size() != 3) {
    throw InputError(fmt::format("deck '{}': subcircuit '{}' has {} port{} ({}); aesim calibrate needs three, vdd out gnd, "
                                 "and holds each other one at a voltage given as --bias NAME=VOLTS",
                                 path, name, found->ports.size(), found->ports.size() == 1 ? "" : "s", port_list));
  }
  if (std::find(found->params.begin(), found->params.end(), "iph") == found->params.end()) {
    throw InputError(fmt::format("deck '{}': subcircuit '{}' has no parameter iph (params: iph=1p)", path, name));
  }
  deck.mc_parameter = std::find(found->params.begin(), found->params.end(), "mc") != found->params.end();
  const std::vector<std::string> nets = port_nets_by_name(rest);
  if (nets != std::vector<std::string>{"vdd", "out", "0"}) deck.ports_by_name = fmt::format("{}", fmt::join(rest, " "));
  deck.port_nets.clear();
  for (std::size_t i = 0, k = 0; i < found->ports.size(); ++i) {
    deck.port_nets.push_back(biased[i] ? bias_net(found->ports[i]) : nets[k++]);
  }
  if (!probe_node.empty()) {
    for (const std::string& line : found->body) {
      const std::vector<std::string> t = tokens(line);
      if (t.empty() || t[0][0] == '.') continue;
      if (std::any_of(t.begin() + 1, t.end(), [&](const std::string& w) { return ascii_lower(w) == ascii_lower(probe_node); })) {
        deck.probe = probe_node;
        break;
      }
    }
  }
  return deck;
}

}  // namespace aesim
