#include "build/vhdl_conversion.hpp"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <vector>

#include <fmt/format.h>

#include "build/tool_output.hpp"
#include "aesim/errors/input_error.hpp"
#include "aesim/files/content_hash.hpp"
#include "aesim/files/scratch_folder.hpp"
#include "aesim/files/scratch_text.hpp"
#include "aesim/process/child_process.hpp"
#include "aesim/text/ascii_case.hpp"

namespace aesim {
namespace {

namespace fs = std::filesystem;

// A generic's value for GHDL's -g option: a description's string literal ("abc") without its
// quotes; a number or an identifier as it is.
std::string generic_value(const std::string& literal) {
  if (literal.size() >= 2 && literal.front() == '"' && literal.back() == '"') return literal.substr(1, literal.size() - 2);
  return literal;
}

// What went wrong, from GHDL's log: its own report of an internal failure (the exception it
// raised), else its first line that reports an error (file:line:col: message), else its first line.
std::string first_error(const std::string& log) {
  std::vector<std::string> lines;
  for (std::size_t at = 0; at < log.size();) {
    const std::size_t end = std::min(log.find('\n', at), log.size());
    if (end > at) lines.push_back(log.substr(at, end - at));
    at = end + 1;
  }
  if (log.find("GHDL Bug occurred") != std::string::npos) {
    for (const std::string& line : lines) {
      if (line.rfind("raised ", 0) == 0) return "GHDL failed inside (" + line + ")";
    }
    return "GHDL failed inside";
  }
  for (const std::string& line : lines) {
    if (line.find("error") != std::string::npos || line.find(": cannot") != std::string::npos) return line;
  }
  return lines.empty() ? "ghdl failed (see its log)" : lines.front();
}

// GHDL is given this long for one attempt: it only catches a synthesis that runs away.
constexpr double kGhdlSeconds = 600;

// The standards GHDL is asked to read the sources in, in turn: VHDL-2008 with Synopsys's
// arithmetic packages (std_logic_arith, std_logic_unsigned), which older designs use; then
// VHDL-93 with the same, for the few that 2008 no longer reads (a name that became reserved).
const std::vector<std::vector<std::string>>& standards() {
  static const std::vector<std::vector<std::string>> s = {{"--std=08", "-fsynopsys"}, {"--std=93c", "--ieee=synopsys"}};
  return s;
}

// Verilog's and SystemVerilog's reserved words (IEEE 1364-2005 and 1800-2017, Annex B) that
// GHDL's netlists never use as keywords (those it may write, such as `signed`, `integer`,
// `function` or `for`, are left out, as are the ones it does write): a VHDL name that is one of them (a signal called
// `config`, `table` or `type`) GHDL writes as it is, which Verilator, yosys and Icarus refuse.
const std::set<std::string>& reserved_elsewhere() {
  static const std::set<std::string> words = {
      "accept_on", "alias", "always_comb", "always_ff", "always_latch", "and", "assert", "assume", "automatic",
      "before", "bind", "bins", "binsof", "bit", "break", "buf", "bufif0", "bufif1", "byte", "cell", "chandle",
      "checker", "class", "clocking", "cmos", "config", "const", "constraint", "context", "continue", "cover",
      "covergroup", "coverpoint", "cross", "deassign", "defparam", "design", "disable", "dist", "do", "edge",
      "endchecker", "endclass", "endclocking", "endconfig", "endgroup", "endinterface", "endpackage",
      "endprimitive", "endprogram", "endproperty", "endsequence", "endspecify", "endtable", "endtask", "enum",
      "event", "eventually", "expect", "export", "extends", "extern", "final", "first_match", "force", "foreach",
      "forever", "fork", "forkjoin", "global", "highz0", "highz1", "ignore_bins", "illegal_bins", "implements",
      "implies", "import", "incdir", "include", "inside", "instance", "int", "interconnect", "interface",
      "intersect", "join", "join_any", "join_none", "large", "let", "liblist", "library", "local", "logic",
      "longint", "macromodule", "matches", "medium", "modport", "nand", "nettype", "new", "nexttime", "nmos",
      "nor", "noshowcancelled", "not", "notif0", "notif1", "null", "package", "packed", "pmos", "program",
      "property", "protected", "pull0", "pull1", "pulldown", "pullup", "pulsestyle_ondetect", "pulsestyle_onevent",
      "pure", "rand", "randc", "randcase", "randsequence", "rcmos", "real", "realtime", "ref", "reject_on",
      "release", "repeat", "restrict", "return", "rnmos", "rpmos", "rtran", "rtranif0", "rtranif1", "s_always",
      "s_eventually", "s_nexttime", "s_until", "s_until_with", "scalared", "sequence", "shortint", "shortreal",
      "showcancelled", "small", "soft", "solve", "specify", "specparam", "static", "string", "strong", "strong0",
      "strong1", "struct", "super", "supply0", "supply1", "sync_accept_on", "sync_reject_on", "table", "tagged",
      "task", "this", "throughout", "time", "timeprecision", "timeunit", "tran", "tranif0", "tranif1", "tri",
      "tri0", "tri1", "triand", "trior", "trireg", "type", "typedef", "union", "unique", "unique0", "until",
      "until_with", "untyped", "use", "uwire", "var", "vectored", "virtual", "void", "wait", "wait_order", "wand",
      "weak", "weak0", "weak1", "while", "wildcard", "with", "within", "wor", "xnor", "xor", "casex", "casez",
      "primitive"};
  return words;
}

// GHDL's Verilog with every name that is a reserved word elsewhere written as an escaped
// identifier (`\config `), which every Verilog reader takes as a plain name. Comments, strings,
// system functions ($unsigned) and the letters of based numbers (8'b0110) are left as they are.
std::string escape_reserved_names(const std::string& text) {
  std::string out;
  out.reserve(text.size() + text.size() / 64);
  const auto ident_start = [](char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; };
  const auto ident_char = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '$'; };
  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (c == '/' && i + 1 < text.size() && (text[i + 1] == '*' || text[i + 1] == '/')) {
      const std::size_t end = text[i + 1] == '*' ? text.find("*/", i + 2) : text.find('\n', i + 2);
      const std::size_t stop = end == std::string::npos ? text.size() : end + (text[i + 1] == '*' ? 2 : 0);
      out.append(text, i, stop - i);
      i = stop;
    } else if (c == '"' || c == '\\') {
      // A string to its closing quote, or an escaped identifier to the white space that ends it.
      std::size_t stop = i + 1;
      while (stop < text.size() && (c == '"' ? text[stop] != '"' : !std::isspace(static_cast<unsigned char>(text[stop])))) {
        stop += c == '"' && text[stop] == '\\' ? 2 : 1;
      }
      stop = std::min(text.size(), stop + (c == '"' ? 1 : 0));
      out.append(text, i, stop - i);
      i = stop;
    } else if (c == '$' || c == '\'' || std::isdigit(static_cast<unsigned char>(c))) {
      // A system function's name, or a number with its base and digits.
      std::size_t stop = i + 1;
      if (c == '\'' && stop < text.size() && (text[stop] == 's' || text[stop] == 'S')) ++stop;
      while (stop < text.size() && ident_char(text[stop])) ++stop;
      out.append(text, i, stop - i);
      i = stop;
    } else if (ident_start(c)) {
      std::size_t stop = i + 1;
      while (stop < text.size() && ident_char(text[stop])) ++stop;
      const std::string name = text.substr(i, stop - i);
      out += reserved_elsewhere().count(name) ? "\\" + name + " " : name;
      i = stop;
    } else {
      out += c;
      ++i;
    }
  }
  return out;
}

// GHDL's Verilog for one entity, its generics set: tried in each standard in turn, each in a
// fresh folder under `work` (GHDL analyses into a work library where it runs). Throws InputError
// with the first attempt's first error, its log kept beside the cache's entries.
std::string synthesise(const std::string& entity, const std::map<std::string, std::string>& generics,
                       const std::vector<std::string>& sources, const fs::path& work, const fs::path& cache) {
  std::string log;
  for (const std::vector<std::string>& standard : standards()) {
    const fs::path run = work / (ascii_lower(entity) + "-" + standard.front().substr(6));
    fs::create_directories(run);
    std::vector<std::string> args = {"--synth", "--out=verilog", "--no-formal"};
    args.insert(args.end(), standard.begin(), standard.end());
    for (const auto& [k, v] : generics) args.push_back("-g" + k + "=" + generic_value(v));
    args.insert(args.end(), sources.begin(), sources.end());
    args.push_back("-e");
    args.push_back(entity);
    const fs::path out = run / "out.v", err = run / "ghdl.log";
    const pid_t pid = spawn_child("ghdl", args, {out.string(), err.string(), run.string()});
    const std::optional<int> ended = wait_child_for(pid, kGhdlSeconds);
    if (!ended) throw InputError(fmt::format("receiver VHDL: GHDL's synthesis ran past {:.0f} s", kGhdlSeconds));
    std::error_code ec;
    if (*ended == 0 && fs::file_size(out, ec) > 0) return read_scratch_text(out);
    if (log.empty()) log = read_scratch_text(err);
  }
  const fs::path kept = cache / fmt::format("vhdl-failed-{}.log", ascii_lower(entity));
  write_scratch_text(kept, log);
  throw InputError(fmt::format("receiver VHDL does not synthesise: {} (GHDL's log: {})", first_error(log), kept.string()));
}

// Modules of several GHDL outputs as one file, each module once (entities under two of the
// converted ones come out in both).
std::string joined_modules(const std::vector<std::string>& outputs) {
  std::set<std::string> seen;
  std::string joined;
  for (const std::string& text : outputs) {
    std::istringstream lines(text);
    std::string line, block, name;
    while (std::getline(lines, line)) {
      if (line.rfind("module ", 0) == 0) {
        name = line.substr(7, line.find_first_of(" (", 7) - 7);
        block.clear();
      }
      block += line + "\n";
      if (line == "endmodule") {
        if (seen.insert(name).second) joined += block;
        block.clear();
      }
    }
  }
  return joined;
}

// The entities the VHDL sources declare, as they spell them.
std::vector<std::string> declared_entities(const std::vector<std::string>& sources) {
  static const std::regex entity(R"((?:^|\n)\s*entity\s+([A-Za-z][A-Za-z0-9_]*)\s+is\b)", std::regex::icase);
  std::vector<std::string> names;
  for (const std::string& s : sources) {
    const std::string text = read_scratch_text(s);
    for (auto m = std::sregex_iterator(text.begin(), text.end(), entity); m != std::sregex_iterator(); ++m) {
      names.push_back((*m)[1].str());
    }
  }
  return names;
}

// Verilog text without its comments (strings kept as they are), for reading instances from.
std::string without_comments(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    if (text[i] == '"') {
      const std::size_t end = text.find('"', i + 1);
      const std::size_t stop = end == std::string::npos ? text.size() : end + 1;
      out.append(text, i, stop - i);
      i = stop;
    } else if (text.compare(i, 2, "//") == 0) {
      i = std::min(text.find('\n', i), text.size());
    } else if (text.compare(i, 2, "/*") == 0) {
      const std::size_t end = text.find("*/", i + 2);
      i = end == std::string::npos ? text.size() : end + 2;
      out += ' ';
    } else {
      out += text[i++];
    }
  }
  return out;
}

// A parameter value a Verilog instance gives a VHDL entity, as GHDL's -g and the module's own
// parameter take it: a number (decimal, or sized with a base) as its decimal, a string as written.
// Anything else (an expression, another module's parameter) is refused: GHDL needs the value.
std::string literal_generic(const std::string& where, const std::string& entity, const std::string& name,
                            const std::string& text) {
  static const std::regex decimal(R"(\d+)"), based(R"((?:\d+)?\s*'\s*[sS]?([dDhHbBoO])\s*([0-9a-fA-F_]+))"),
      string(R"("[^"\\]*")");
  std::smatch m;
  std::string digits = text;
  int radix = 10;
  if (std::regex_match(text, m, based)) {
    digits = m[2].str();
    digits.erase(std::remove(digits.begin(), digits.end(), '_'), digits.end());
    const char base = static_cast<char>(std::tolower(static_cast<unsigned char>(m[1].str()[0])));
    radix = base == 'd' ? 10 : base == 'h' ? 16 : base == 'b' ? 2 : 8;
  }
  if (std::regex_match(text, decimal) || !m.empty()) {
    try {
      std::size_t used = 0;
      const unsigned long long value = std::stoull(digits, &used, radix);
      if (used == digits.size()) return std::to_string(value);
    } catch (const std::exception&) {
      // not digits of that base, or past 64 bits: refused below
    }
  }
  if (std::regex_match(text, string)) return text;
  throw InputError(fmt::format("{}: the Verilog sets the VHDL entity {}'s generic {} to '{}'; aesim passes GHDL a "
                               "number or a string there, not an expression",
                               where, entity, name, text));
}

// The generics the Verilog's instances of `entity` set (`entity #(.NAME(value), ...) name (`),
// the same for every instance: GHDL makes one module of an entity. None for instances without.
std::map<std::string, std::string> instance_generics(const std::string& where, const std::string& entity,
                                                     const std::string& verilog) {
  const std::regex use("\\b" + entity + "\\s*(#\\s*\\(|[A-Za-z_][A-Za-z0-9_$]*\\s*\\()");
  std::optional<std::map<std::string, std::string>> first;
  for (auto m = std::sregex_iterator(verilog.begin(), verilog.end(), use); m != std::sregex_iterator(); ++m) {
    std::map<std::string, std::string> set;
    if ((*m)[1].str().front() == '#') {
      // The list up to its closing parenthesis, split at the commas outside parentheses.
      const std::size_t open = static_cast<std::size_t>(m->position(0) + m->length(0)) - 1;
      std::vector<std::string> items(1);
      int depth = 0;
      std::size_t i = open + 1;
      for (; i < verilog.size(); ++i) {
        const char c = verilog[i];
        if (c == '(') ++depth;
        if (c == ')' && depth-- == 0) break;
        if (c == ',' && depth == 0) {
          items.emplace_back();
        } else {
          items.back() += c;
        }
      }
      static const std::regex named(R"(\s*\.\s*([A-Za-z_][A-Za-z0-9_$]*)\s*\(\s*(.*?)\s*\)\s*)");
      // `#()` sets none.
      if (items.size() == 1 && items[0].find_first_not_of(" \t\r\n") == std::string::npos) items.clear();
      for (const std::string& item : items) {
        std::smatch n;
        if (!std::regex_match(item, n, named)) {
          throw InputError(fmt::format("{}: the Verilog sets the VHDL entity {}'s generics by position ('{}'); name "
                                       "them: #(.NAME(value))",
                                       where, entity, item));
        }
        set[n[1].str()] = literal_generic(where, entity, n[1].str(), n[2].str());
      }
    }
    if (!first) {
      first = set;
    } else if (*first != set) {
      throw InputError(fmt::format("{}: instances of the VHDL entity {} set different generics; GHDL makes one module "
                                   "of an entity, so give them all the same",
                                   where, entity));
    }
  }
  return first.value_or(std::map<std::string, std::string>{});
}

// GHDL's module for `entity` given the parameters its Verilog instances set, which the module
// takes and ignores: GHDL has already built it with them as its generics.
std::string with_parameters(const std::string& netlist, const std::string& entity,
                            const std::map<std::string, std::string>& generics) {
  if (generics.empty()) return netlist;
  std::string list;
  for (const auto& [k, v] : generics) list += fmt::format("{}parameter {} = {}", list.empty() ? "" : ", ", k, v);
  std::istringstream lines(netlist);
  std::string line, out;
  while (std::getline(lines, line)) {
    if (line.rfind("module ", 0) == 0 && ascii_lower(line.substr(7)) == ascii_lower(entity)) line += " #(" + list + ")";
    out += line + "\n";
  }
  return out;
}

}  // namespace

bool is_vhdl_source(const std::string& path) {
  const std::string ext = ascii_lower(fs::path(path).extension().string());
  return ext == ".vhd" || ext == ".vhdl";
}

ReceiverDescription with_vhdl_as_verilog(const ReceiverDescription& d, const std::string& cache_dir) {
  std::vector<std::string> vhdl, verilog;
  for (const std::string& s : d.sources) (is_vhdl_source(s) ? vhdl : verilog).push_back(s);
  if (vhdl.empty()) return d;
  const std::string where = fmt::format("receiver description '{}'", d.file);
  if (!program_available("ghdl")) {
    throw InputError(fmt::format("{}: its sources are VHDL, which aesim verify converts to Verilog with GHDL; GHDL is "
                                 "not installed (apt-get install ghdl)",
                                 where));
  }
  const bool mixed = !verilog.empty();
  // All VHDL: the top entity, its generics from `parameters`. Mixed: a Verilog top, and each VHDL
  // entity the Verilog sources name, with the generics its instances set (literals, the same for
  // every instance) or at their defaults.
  std::vector<std::string> entities;
  std::map<std::string, std::map<std::string, std::string>> generics;  // entity -> its generics
  if (!mixed) {
    if (!d.defines.empty() || !d.include_dirs.empty()) {
      throw InputError(fmt::format("{}: `defines` and `include_dirs` are Verilog's; VHDL takes none", where));
    }
    entities = {d.top};
    generics[d.top] = d.parameters;
  } else {
    const std::vector<std::string> declared = declared_entities(vhdl);
    std::string verilog_text;
    for (const std::string& s : verilog) verilog_text += without_comments(read_scratch_text(s)) + "\n";
    for (const std::string& e : declared) {
      if (ascii_lower(e) == ascii_lower(d.top)) {
        throw InputError(fmt::format("{}: the top '{}' is a VHDL entity and other sources are Verilog; GHDL's synthesis "
                                     "takes no Verilog, so the top of a mixed design must be the Verilog one",
                                     where, e));
      }
      if (!std::regex_search(verilog_text, std::regex("\\b" + e + "\\b"))) continue;
      generics[e] = instance_generics(where, e, verilog_text);
      entities.push_back(e);
    }
    if (entities.empty()) {
      throw InputError(fmt::format("{}: no Verilog source instantiates any of the VHDL entities ({} declared)", where,
                                   declared.size()));
    }
  }

  const fs::path cache = cache_dir;
  std::error_code ec;
  fs::create_directories(cache, ec);
  if (ec) throw InputError(fmt::format("cache folder '{}': {}", cache.string(), ec.message()));
  const ScratchFolder scratch(cache / fmt::format("tmp-vhdl.{}", ::getpid()));
  const fs::path& work = scratch.path();

  std::string key = "aesim-vhdl-v4\n" + tool_output("ghdl", {"--version"}, work) + "\n";
  for (const std::string& e : entities) {
    key += "entity " + e + "\n";
    for (const auto& [k, v] : generics[e]) key += "generic " + k + "=" + v + "\n";
  }
  for (const std::string& s : vhdl) key += "source " + s + "\n" + read_scratch_text(s) + "\n";
  const fs::path entry = cache / ("vhdl-" + content_hash_hex(key));
  const fs::path converted = entry / "receiver.v";

  if (!fs::is_regular_file(converted)) {
    std::vector<std::string> outputs;
    for (const std::string& e : entities) {
      const std::string netlist = synthesise(e, generics[e], vhdl, work, cache);
      outputs.push_back(mixed ? with_parameters(netlist, e, generics[e]) : netlist);
    }
    fs::create_directories(work / "entry");
    write_scratch_text(work / "entry" / converted.filename(), escape_reserved_names(joined_modules(outputs)));
    fs::rename(work / "entry", entry, ec);
    if (ec && !fs::is_regular_file(converted)) {
      throw InputError(fmt::format("cache folder '{}': {}", cache.string(), ec.message()));
    }
  }
  if (mixed) {
    ReceiverDescription v = d;
    v.sources = verilog;
    v.sources.push_back(converted.string());
    return v;
  }

  // GHDL keeps each name as the VHDL declares it, and VHDL does not tell case apart: the
  // description's names are matched to the module's whatever their case.
  // The top's header is the module of that name (GHDL writes the entities it instantiates as
  // modules of their own, before it), up to the end of its port list.
  const std::string netlist = read_scratch_text(converted);
  std::map<std::string, std::string> declared;
  static const std::regex module_name(R"((?:^|\n)module\s+([A-Za-z_][A-Za-z0-9_$]*))");
  static const std::regex port_name(R"(\b(?:input|output|inout)\s+(?:\[[^\]]*\]\s*)?([A-Za-z_][A-Za-z0-9_$]*))");
  for (auto m = std::sregex_iterator(netlist.begin(), netlist.end(), module_name); m != std::sregex_iterator(); ++m) {
    if (ascii_lower((*m)[1].str()) != ascii_lower(d.top)) continue;
    declared.emplace(ascii_lower(d.top), (*m)[1].str());
    const auto from = static_cast<std::size_t>(m->position(1));
    const std::string header = netlist.substr(from, netlist.find(");", from) - from);
    for (auto p = std::sregex_iterator(header.begin(), header.end(), port_name); p != std::sregex_iterator(); ++p) {
      declared.emplace(ascii_lower((*p)[1].str()), (*p)[1].str());
    }
    break;
  }
  const auto as_declared = [&](const std::string& name) {
    const auto found = declared.find(ascii_lower(name));
    return found == declared.end() ? name : found->second;
  };
  ReceiverDescription v = d;
  v.top = as_declared(d.top);
  v.sources = {converted.string()};
  v.parameters.clear();
  v.formal.parameters.clear();
  for (auto& [role, ref] : v.ports) {
    if (!ref.joined()) ref.port = as_declared(ref.port);
    for (PortRef& part : ref.parts) part.port = as_declared(part.port);
  }
  if (v.has_reset()) v.reset_port = as_declared(v.reset_port);
  v.inputs.clear();
  for (const auto& [port, value] : d.inputs) v.inputs[as_declared(port)] = value;
  v.formal.inputs.clear();
  for (const auto& [port, value] : d.formal.inputs) v.formal.inputs[as_declared(port)] = value;
  for (std::string& out : v.formal.unsynchronised_outputs) out = as_declared(out);
  return v;
}

ReceiverDescription vhdl_for_the_proof(const ReceiverDescription& written, const ReceiverDescription& converted,
                                       const std::string& cache_dir) {
  const bool all_vhdl = !written.sources.empty() && std::all_of(written.sources.begin(), written.sources.end(), is_vhdl_source);
  if (!all_vhdl || written.formal.parameters.empty()) return converted;
  ReceiverDescription proof = written;
  for (const auto& [k, v] : written.formal.parameters) proof.parameters[k] = v;
  proof.formal.parameters.clear();
  return with_vhdl_as_verilog(proof, cache_dir);
}

}  // namespace aesim
