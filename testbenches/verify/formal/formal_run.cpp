#include "formal/formal_run.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "build/tool_output.hpp"
#include "description/rtl_folder_key.hpp"
#include "driver/bound_ports.hpp"
#include "aesim/errors/input_error.hpp"
#include "aesim/files/content_hash.hpp"
#include "aesim/files/scratch_folder.hpp"
#include "aesim/files/scratch_text.hpp"
#include "aesim/process/child_process.hpp"

namespace aesim {
namespace {

namespace fs = std::filesystem;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

bool is_systemverilog(const std::string& path) {
  const std::string ext = fs::path(path).extension().string();
  return ext == ".sv" || ext == ".svh";
}

// Yosys's first error line, as one line: "pkt_rx.sv:9: ERROR: syntax error, ...".
std::string yosys_first_error(const std::string& log) {
  std::istringstream lines(log);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.find("ERROR:") != std::string::npos) {
      while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
      return line;
    }
  }
  return "yosys failed (see its log)";
}

std::string read_sources(const ReceiverDescription& d, bool checker = true) {
  std::string flags;
  for (const std::string& dir : d.include_dirs) flags += " -I" + dir;
  for (const auto& [k, v] : d.defines) flags += v.empty() ? " -D" + k : " -D" + k + "=" + v;
  std::string s;
  for (const std::string& src : d.sources) {
    s += fmt::format("read_verilog -formal{}{} \"{}\"\n", is_systemverilog(src) ? " -sv" : "", flags, src);
  }
  return checker ? s + "read_verilog -formal -sv aesim_formal.sv\n" : s;
}

// A counterexample (ABC's witness) simulated by yosys into a VCD of the checker and the RTL.
std::string replay_script(const ReceiverDescription& d, int check, const std::string& base) {
  return read_sources(d) + fmt::format(
                               "hierarchy -top aesim_formal_top -chparam CHECK {0}\nprep -top aesim_formal_top\nasync2sync\n"
                               "memory_map\nflatten\nsetundef -undriven -anyseq\ndffunmap\n"
                               "sim -clock clk -r {1}.aiw -map {1}.aim -scope aesim_formal_top -vcd {1}.vcd -q\n",
                               check, base);
}

// The yosys script: the team's sources and the checker read once, then per property (CHECK) an
// AIGER model for ABC.
std::string yosys_script(const ReceiverDescription& d, const std::vector<FormalProperty>& properties) {
  std::string s = read_sources(d) + "design -save sources\n";
  for (const FormalProperty& p : properties) {
    // The AIGER model ABC checks.
    s += fmt::format(
        "design -load sources\nhierarchy -top aesim_formal_top -chparam CHECK {0}\nprep -top aesim_formal_top\n"
        "async2sync\nmemory_map\nflatten\nsetundef -undriven -anyseq\ndffunmap\n"
        "opt -fast\ndelete -output\nopt -full\ntechmap\nopt -fast\ndffunmap\nabc -g AND -fast\nopt_clean\n"
        "write_aiger -zinit -map p{0}.aim p{0}.aig\n",
        p.id);
  }
  return s;
}

struct SolverRun {
  pid_t pid = -1;
  std::size_t index = 0;
  bool bounded = false;
  fs::path log;
  std::chrono::steady_clock::time_point start;
};

// ABC's verdict: 0 none asserted (bmc3: to `frames`; pdr: proved), 1 asserted (in frame `frame`),
// -1 neither (stopped by its time limit).
int abc_status(const std::string& log, std::optional<int>& frame, int& frames) {
  std::istringstream lines(log);
  std::string line;
  int status = -1;
  while (std::getline(lines, line)) {
    int n = 0;
    if (line.find("Property proved") != std::string::npos) status = 0;
    if (const auto at = line.find("was asserted in frame"); at != std::string::npos) {
      if (std::sscanf(line.c_str() + at, "was asserted in frame %d", &n) == 1) frame = n;
      status = 1;
    }
    if (const auto at = line.find("No output asserted in"); at != std::string::npos) {
      if (std::sscanf(line.c_str() + at, "No output asserted in %d frames", &n) == 1) frames = n;
      status = 0;
    }
    if (const auto at = line.find("Reached timeout"); at != std::string::npos) status = -1;
  }
  return status;
}

}  // namespace

bool FormalResult::failed() const {
  return std::any_of(verdicts.begin(), verdicts.end(), [](const FormalVerdict& v) { return v.verdict == "failed"; });
}

std::vector<ReplayStep> counterexample_inputs(const std::string& aim_text, const std::string& aiw_text) {
  // The map: "input INDEX BIT NAME" for each AIGER input.
  struct Bit {
    std::string name;
    int bit;
  };
  std::map<int, Bit> inputs;
  std::istringstream map(aim_text);
  std::string kind, name;
  int index = 0, bit = 0;
  while (map >> kind >> index >> bit >> name) {
    if (kind == "input") inputs[index] = {name, bit};
  }
  // The witness: the initial latches on the first line, then the inputs of each frame.
  std::istringstream lines(aiw_text);
  std::string line;
  std::vector<ReplayStep> steps;
  bool initial = true;
  while (std::getline(lines, line)) {
    if (line.empty() || line[0] == '.' || line[0] == 'b' || line[0] == 'c') continue;
    if (initial) {
      initial = false;
      continue;
    }
    ReplayStep s;
    for (std::size_t i = 0; i < line.size(); ++i) {
      const auto in = inputs.find(static_cast<int>(i));
      if (in == inputs.end() || line[i] != '1') continue;
      const Bit& b = in->second;
      if (b.name == "req_i") s.req = true;
      if (b.name == "contention_i") s.contention = true;
      if (b.name == "addr_i" && b.bit < 64) s.addr |= 1ULL << b.bit;
    }
    const auto ready = std::find_if(inputs.begin(), inputs.end(), [](const auto& e) { return e.second.name == "ready_i"; });
    s.ready = ready == inputs.end() || (static_cast<std::size_t>(ready->first) < line.size() && line[static_cast<std::size_t>(ready->first)] == '1');
    steps.push_back(s);
  }
  return steps;
}

std::string synchroniser_path_violation(const std::string& netlist_json, const std::string& top, const PortRef& req,
                                        int flops, const std::vector<std::string>& unsynchronised_outputs) {
  const nlohmann::json netlist = nlohmann::json::parse(netlist_json);
  const nlohmann::json& module = netlist.at("modules").at(top);
  const nlohmann::json& port = module.at("ports").at(req.port);
  const auto& port_bits = port.at("bits");
  const int offset = port.contains("offset") ? port["offset"].get<int>() : 0;
  const int index = req.sliced() ? req.lsb - offset : 0;
  const nlohmann::json start = port_bits.at(static_cast<std::size_t>(index));
  // A net's name, for the path.
  std::map<long, std::string> names;
  for (const auto& [name, net] : module.at("netnames").items()) {
    const auto& bits = net.at("bits");
    for (std::size_t i = 0; i < bits.size(); ++i) {
      if (!bits[i].is_number()) continue;
      const long b = bits[i].get<long>();
      const bool hidden = net.contains("hide_name") && net["hide_name"].get<int>() != 0;
      if (!names.count(b) || (!hidden && names[b].front() == '$')) names[b] = bits.size() > 1 ? fmt::format("{}[{}]", name, i) : name;
    }
  }
  auto is_flop = [](const std::string& type) { return type.find("dff") != std::string::npos || type == "$ff"; };
  auto is_buffer = [](const std::string& type) { return type == "$not" || type == "$pos" || type == "$_NOT_" || type == "$_BUF_"; };
  // A multiplexer passing Req as data (a flop's synchronous reset or enable) decides nothing on it.
  auto is_mux_data = [](const std::string& type, const std::string& pin) {
    return (type == "$mux" || type == "$pmux" || type == "$_MUX_") && (pin == "A" || pin == "B");
  };
  // Where a cell's outputs lead through combinational logic alone: true if only to the outputs the
  // description names as unsynchronised.
  auto only_to_waived_outputs = [&](const nlohmann::json& first) {
    if (unsynchronised_outputs.empty()) return false;
    std::vector<long> bits;
    for (const auto& [pin, b] : first.at("connections").items()) {
      if (first.at("port_directions").at(pin) != "output") continue;
      for (const auto& x : b) {
        if (x.is_number()) bits.push_back(x.get<long>());
      }
    }
    std::set<long> seen_bits;
    while (!bits.empty()) {
      const long bit = bits.back();
      bits.pop_back();
      if (!seen_bits.insert(bit).second) continue;
      for (const auto& [pname, p] : module.at("ports").items()) {
        if (p.at("direction") != "output") continue;
        for (const auto& b : p.at("bits")) {
          if (b.is_number() && b.get<long>() == bit &&
              std::find(unsynchronised_outputs.begin(), unsynchronised_outputs.end(), pname) == unsynchronised_outputs.end()) {
            return false;
          }
        }
      }
      for (const auto& [cname, cell] : module.at("cells").items()) {
        const std::string type = cell.at("type");
        const auto& dirs = cell.at("port_directions");
        for (const auto& [pin, pbits] : cell.at("connections").items()) {
          if (dirs.at(pin) != "input") continue;
          for (const auto& x : pbits) {
            if (!x.is_number() || x.get<long>() != bit) continue;
            if (type.find("dff") != std::string::npos || type == "$ff" || type == "$mem" || type.rfind("$mem", 0) == 0) return false;
            for (const auto& [opin, obits] : cell.at("connections").items()) {
              if (dirs.at(opin) != "output") continue;
              for (const auto& o : obits) {
                if (o.is_number()) bits.push_back(o.get<long>());
              }
            }
          }
        }
      }
    }
    return true;
  };
  auto src = [](const nlohmann::json& cell) {
    if (!cell.contains("attributes") || !cell["attributes"].contains("src")) return std::string();
    // "/x/pkt_rx.sv:48.16-48.39" -> "pkt_rx.sv:48"
    std::string s = cell["attributes"]["src"].get<std::string>();
    s = s.substr(0, s.find('|'));
    const auto colon = s.rfind(':');
    if (colon != std::string::npos) s = s.substr(0, s.find('.', colon));
    return fs::path(s).filename().string();
  };
  if (!start.is_number()) return "";
  struct Reach {
    long bit;
    int level;
    std::string path;
  };
  std::vector<Reach> frontier = {{start.get<long>(), 0, req.text()}};
  std::set<std::pair<long, int>> seen;
  bool reached = false;
  while (!frontier.empty()) {
    const Reach r = frontier.back();
    frontier.pop_back();
    if (!seen.insert({r.bit, r.level}).second) continue;
    if (r.level >= flops) {
      reached = true;
      continue;
    }
    for (const auto& [pname, p] : module.at("ports").items()) {
      if (p.at("direction") != "output") continue;
      for (const auto& b : p.at("bits")) {
        if (b.is_number() && b.get<long>() == r.bit) {
          return fmt::format("{} -> output {}: Req reaches an output after {} of {} flops", r.path, pname, r.level, flops);
        }
      }
    }
    for (const auto& [cname, cell] : module.at("cells").items()) {
      const std::string type = cell.at("type");
      const auto& dirs = cell.at("port_directions");
      for (const auto& [pin, bits] : cell.at("connections").items()) {
        if (dirs.at(pin) != "input") continue;
        for (std::size_t i = 0; i < bits.size(); ++i) {
          if (!bits[i].is_number() || bits[i].get<long>() != r.bit) continue;
          if (is_flop(type) && pin == "D") {
            const auto& q = cell.at("connections").at("Q").at(i);
            if (q.is_number()) {
              const long qb = q.get<long>();
              frontier.push_back({qb, r.level + 1, r.path + " -> " + (names.count(qb) ? names[qb] : cname)});
            }
          } else if (is_buffer(type) || is_mux_data(type, pin)) {
            // Bit for bit: input bit i (of each word, for a $pmux's B) is output bit i.
            const auto& y = cell.at("connections").at("Y");
            const auto& o = y.at(i % y.size());
            if (o.is_number()) frontier.push_back({o.get<long>(), r.level, r.path});
          } else if (!only_to_waived_outputs(cell)) {
            const std::string where = src(cell);
            return fmt::format("{} -> {}{}: logic reads Req after {} of the {} synchroniser flops", r.path, type,
                               where.empty() ? "" : " (" + where + ")", r.level, flops);
          }
        }
      }
    }
  }
  return reached ? "" : fmt::format("{} reaches no chain of {} flops", req.text(), flops);
}

namespace {

// The team's top under the proof's parameters, as yosys elaborates it: its ports (the widths the
// checker wires) and its flattened netlist (the structural check).
std::vector<RtlPort> netlist_ports(const nlohmann::json& netlist, const std::string& top) {
  std::vector<RtlPort> ports;
  for (const auto& [name, p] : netlist.at("modules").at(top).at("ports").items()) {
    RtlPort r;
    r.name = name;
    r.input = p.at("direction") != "output";
    r.width = static_cast<int>(p.at("bits").size());
    r.lsb = p.contains("offset") ? p["offset"].get<int>() : 0;
    r.msb = r.lsb + r.width - 1;
    r.bytes = r.width > 64 ? 0 : 8;
    ports.push_back(r);
  }
  return ports;
}

// yosys reading, preparing and replaying the RTL is given at least this long, whatever the budget a
// property's proof has: its time follows the design and the machine's load, not the proof's (with
// `--formal-seconds 5`, reading the third receiver ran past 5 s on a loaded 2-core machine, and
// the run ended as if the RTL were bad). The limit only catches a yosys that runs away.
constexpr double kYosysLeastSeconds = 120;

// Runs yosys on a script in the scratch folder; RTL it cannot take is an InputError naming its first
// error.
void run_yosys(const fs::path& work, const std::string& script_name, const ReceiverDescription& d, double budget) {
  const double seconds = std::max(budget, kYosysLeastSeconds);
  const std::string log = script_name + ".log";
  const pid_t pid = spawn_child("yosys", {"-q", "-l", log, "-s", script_name},
                                {(work / (script_name + ".out")).string(), (work / (script_name + ".out")).string(), work.string()});
  const std::optional<int> status = wait_child_for(pid, seconds);
  if (!status) throw InputError(fmt::format("--formal: yosys ran past {:.0f} s on the RTL", seconds));
  if (*status != 0) {
    std::string first = yosys_first_error(read_scratch_text(work / log) + read_scratch_text(work / (script_name + ".out")));
    const std::string prefix = fs::absolute(d.file).parent_path().string() + "/";
    for (std::size_t at; (at = first.find(prefix)) != std::string::npos;) first.erase(at, prefix.size());
    // Yosys's SystemVerilog front end has no import: say so where that is the cause.
    std::string hint;
    unsigned line = 0;
    const auto colon = first.find(':');
    if (first.find("syntax error") != std::string::npos && colon != std::string::npos &&
        std::sscanf(first.c_str() + colon + 1, "%u", &line) == 1) {
      for (const std::string& src : d.sources) {
        if (fs::path(src).filename() != fs::path(first.substr(0, colon)).filename()) continue;
        std::istringstream text(read_scratch_text(src));
        std::string l;
        for (unsigned n = 1; std::getline(text, l) && n <= line; ++n) {
          if (n == line && l.find("import") != std::string::npos) {
            hint = " (yosys reads no package import: name package items as pkg::NAME)";
          }
        }
      }
    }
    if (hint.empty() && d.formal.sources.empty()) hint = " ([formal] sources names Verilog for the proof to read instead)";
    throw InputError("--formal: yosys: " + first + hint);
  }
}

}  // namespace

FormalResult run_formal(const ReceiverDescription& d, const std::optional<StampRule::Candidate>& stamp,
                        const FormalOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  for (const char* tool : {"yosys", "yosys-abc"}) {
    if (!program_available(tool)) throw InputError(fmt::format("--formal needs {}, which is not installed (scripts/setup installs it)", tool));
  }
  FormalResult result;
  result.solver = "ABC (pdr, bmc3)";
  result.property_seconds = options.property_seconds;
  const fs::path cache = options.cache_dir;
  std::error_code ec;
  fs::create_directories(cache, ec);
  const ScratchFolder scratch(cache / fmt::format("tmp-formal.{}", ::getpid()));
  const fs::path& work = scratch.path();

  // Everything the verdicts follow from: the description, the sources and what they may include
  // (every file of an include folder; the Verilog files beside each source, which `include`
  // finds there), the tools, the rule. The files by their place beside the description, not by
  // where the folder lies: the verdicts and counterexamples hold no path, so a receiver's folder
  // copied or moved (a clone elsewhere, a test's scratch copy) keeps its proofs.
  std::string key = fmt::format("aesim-formal-v10\n{}\nseconds {}\n", tool_output("yosys", {"-V"}, work), options.property_seconds);
  if (stamp) key += fmt::format("stamp {} {}\n", static_cast<int>(stamp->anchor), stamp->offset);
  key += read_scratch_text(d.file);
  const fs::path home = fs::absolute(d.file).parent_path();
  const auto placed = [&home](const fs::path& f) { return fs::absolute(f).lexically_relative(home).string(); };
  std::set<fs::path> beside;
  for (const std::string& s : d.sources) {
    key += placed(s) + "\n" + read_scratch_text(s);
    beside.insert(fs::absolute(s).parent_path());
  }
  for (const fs::path& dir : beside) add_rtl_folder_to_key(key, dir, RtlFolderFiles::VerilogOnly, placed, "sources");
  for (const std::string& dir : d.include_dirs) add_rtl_folder_to_key(key, dir, RtlFolderFiles::All, placed, "include_dirs");
  const fs::path entry = cache / ("formal-" + content_hash_hex(key));
  if (fs::is_regular_file(entry / "result.json")) {
    const nlohmann::json j = nlohmann::json::parse(read_scratch_text(entry / "result.json"));
    for (const auto& v : j.at("verdicts")) {
      FormalVerdict f{v.at("property"), v.at("text"), v.at("verdict"), v.at("depth"), v.at("time_s"), std::nullopt, v.at("detail")};
      if (v.contains("step") && !v["step"].is_null()) f.step = v["step"].get<int>();
      result.verdicts.push_back(f);
    }
    result.failed_property = j.at("failed_property");
    result.depth = j.at("depth");
    result.depth_reason = j.at("depth_reason");
    result.notes = j.at("notes").get<std::vector<std::string>>();
    if (fs::is_regular_file(entry / "counterexample.vcd")) result.counterexample_vcd = read_scratch_text(entry / "counterexample.vcd");
    if (fs::is_regular_file(entry / "counterexample.aiw")) {
      result.replay = counterexample_inputs(read_scratch_text(entry / "counterexample.aim"), read_scratch_text(entry / "counterexample.aiw"));
    }
    result.cached = true;
    result.seconds = seconds_since(start);
    return result;
  }

  // The top under the proof's parameters: its ports and netlist.
  std::map<std::string, std::string> parameters = d.parameters;
  for (const auto& [k, v] : d.formal.parameters) parameters[k] = v;
  std::string chparams;
  for (const auto& [k, v] : parameters) chparams += fmt::format(" -chparam {} {}", k, v);
  write_scratch_text(work / "aesim_netlist.ys",
             read_sources(d, false) + fmt::format("hierarchy -top {}{}\nproc\nflatten\nopt_clean\nwrite_json netlist.json\n", d.top, chparams));
  run_yosys(work, "aesim_netlist.ys", d, options.property_seconds);
  const std::string netlist_text = read_scratch_text(work / "netlist.json");
  const std::vector<RtlPort> ports = netlist_ports(nlohmann::json::parse(netlist_text), d.top);
  // The proof may run narrower address and stamp paths than the simulation ([formal] parameters):
  // a receiver only moves addresses, and its stamps wrap at the width it has.
  ReceiverDescription narrowed = d;
  for (const auto& [name, value] : d.formal.inputs) narrowed.inputs[name] = value;
  try {
    if (d.has("timestamp")) {
      if (const int width = role_width(d, ports, "timestamp"); width > 0) narrowed.timestamp_bits = std::min(d.timestamp_bits, width);
    }
    check_ports(narrowed, ports, 1);
  } catch (const InputError& e) {
    throw InputError(std::string("--formal (with [formal] parameters): ") + e.what());
  }
  // A block whose Req its own top synchronises (spio's mapper behind spio_spinnaker_link_sync)
  // has no synchroniser of its own to check.
  if (d.synchroniser_flops > 0) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::string violation =
        synchroniser_path_violation(netlist_text, d.top, d.ref("req"), d.synchroniser_flops, d.formal.unsynchronised_outputs);
    result.verdicts.push_back({"req_synchronised",
                               fmt::format("Req reaches the logic only through {} flops", d.synchroniser_flops),
                               violation.empty() ? "proved" : "failed", 0, seconds_since(t0), std::nullopt, violation});
  }

  const FormalChecker checker = formal_checker(narrowed, ports, stamp);
  result.depth = checker.depth;
  result.depth_reason = checker.depth_reason;
  result.notes = checker.notes;
  if (d.synchroniser_flops == 0) {
    result.notes.push_back("Req is synchronised outside the design (behaviour.synchroniser_flops = 0): no synchroniser is checked");
  }
  if (options.progress) {
    std::fprintf(stderr, "aesim verify --formal: %zu properties: an unbounded proof (pdr) where ABC finds one in %.0f s, else a bounded check to %d steps (%s)\n",
                 checker.properties.size() + result.verdicts.size(), options.property_seconds, result.depth, result.depth_reason.c_str());
  }
  write_scratch_text(work / "aesim_formal.sv", checker.source);
  write_scratch_text(work / "aesim_formal.ys", yosys_script(d, checker.properties));
  run_yosys(work, "aesim_formal.ys", d, options.property_seconds);

  // Per property, with ABC: an unbounded proof (pdr, which also finds counterexamples), and, if it
  // decides nothing in time, a bounded check to the depth (bmc3); two runs at a time.
  std::vector<FormalVerdict> verdicts;
  for (const FormalProperty& p : checker.properties) verdicts.push_back({p.name, p.text, "", 0, 0, std::nullopt, ""});
  std::vector<SolverRun> running;
  std::vector<std::pair<std::size_t, bool>> queue;  // (property, bounded check)
  for (std::size_t i = 0; i < verdicts.size(); ++i) queue.push_back({i, false});
  const int seconds = static_cast<int>(options.property_seconds);
  auto start_run = [&](std::size_t i, bool bounded) {
    const FormalProperty& p = checker.properties[i];
    SolverRun r;
    r.index = i;
    r.bounded = bounded;
    r.log = work / fmt::format("p{}{}.log", p.id, bounded ? "bmc" : "pdr");
    const std::string base = fmt::format("p{}", p.id);
    const std::string engine = bounded ? fmt::format("bmc3 -F {} -T {}", result.depth, seconds) : fmt::format("pdr -T {}", seconds);
    r.start = std::chrono::steady_clock::now();
    r.pid = spawn_child("yosys-abc", {"-c", fmt::format("read_aiger {0}.aig; fold; strash; {1}; write_cex -a {0}.aiw", base, engine)},
                        {r.log.string(), r.log.string(), work.string()});
    running.push_back(r);
  };
  std::size_t next = 0;
  while (next < queue.size() || !running.empty()) {
    while (running.size() < 2 && next < queue.size()) {
      start_run(queue[next].first, queue[next].second);
      ++next;
    }
    const SolverRun r = running.front();
    running.erase(running.begin());
    const std::optional<int> status = wait_child_for(r.pid, options.property_seconds + 30);
    FormalVerdict& v = verdicts[r.index];
    v.time_s += seconds_since(r.start);
    std::optional<int> frame;
    int frames = 0;
    const int outcome = status ? abc_status(read_scratch_text(r.log), frame, frames) : -1;
    bool settled = true;
    if (outcome == 1) {
      v.verdict = "failed";
      v.step = frame;
      v.detail = frame ? fmt::format("fails at step {} (clock edge {} from the start)", *frame, *frame) : "";
    } else if (!r.bounded && outcome == 0) {
      v.verdict = "proved";
    } else if (!r.bounded) {
      queue.push_back({r.index, true});
      settled = false;
    } else {
      v.verdict = "bounded";
      v.depth = frames;
    }
    if (options.progress && settled) {
      std::fprintf(stderr, "  %-22s %-8s %6.1f s%s\n", v.property.c_str(), v.verdict.c_str(), v.time_s,
                   v.verdict == "bounded" ? fmt::format(" (to {} steps)", v.depth).c_str() : "");
    }
  }
  result.verdicts.insert(result.verdicts.end(), verdicts.begin(), verdicts.end());

  std::string witness;
  for (std::size_t i = 0; i < verdicts.size(); ++i) {
    if (verdicts[i].verdict != "failed") continue;
    result.failed_property = verdicts[i].property;
    // ABC's witness: its inputs for the simulation driver, and a VCD of every signal from yosys's
    // own simulation of the same design.
    const std::string base = fmt::format("p{}", checker.properties[i].id);
    witness = base;
    result.replay = counterexample_inputs(read_scratch_text(work / (base + ".aim")), read_scratch_text(work / (base + ".aiw")));
    write_scratch_text(work / "replay.ys", replay_script(d, checker.properties[i].id, base));
    const pid_t replay = spawn_child("yosys", {"-q", "-s", "replay.ys"},
                                     {(work / "replay.log").string(), (work / "replay.log").string(), work.string()});
    const std::optional<int> replayed = wait_child_for(replay, std::max(options.property_seconds, kYosysLeastSeconds));
    if (replayed && fs::is_regular_file(work / (base + ".vcd"))) result.counterexample_vcd = read_scratch_text(work / (base + ".vcd"));
    break;
  }
  if (result.failed_property.empty()) {
    for (const FormalVerdict& v : result.verdicts) {
      if (v.verdict == "failed") result.failed_property = v.property;
    }
  }

  // Into the cache, whole or not at all.
  nlohmann::json j;
  j["failed_property"] = result.failed_property;
  j["depth"] = result.depth;
  j["depth_reason"] = result.depth_reason;
  j["notes"] = result.notes;
  j["verdicts"] = nlohmann::json::array();
  for (const FormalVerdict& v : result.verdicts) {
    j["verdicts"].push_back({{"property", v.property}, {"text", v.text}, {"verdict", v.verdict}, {"depth", v.depth},
                             {"time_s", v.time_s}, {"step", v.step ? nlohmann::json(*v.step) : nlohmann::json(nullptr)},
                             {"detail", v.detail}});
  }
  const fs::path staged = cache / fmt::format("tmp-formal-entry.{}", ::getpid());
  fs::remove_all(staged, ec);
  fs::create_directories(staged, ec);
  write_scratch_text(staged / "result.json", j.dump(2));
  if (!result.counterexample_vcd.empty()) write_scratch_text(staged / "counterexample.vcd", result.counterexample_vcd);
  if (!witness.empty()) {
    fs::copy_file(work / (witness + ".aim"), staged / "counterexample.aim", ec);
    fs::copy_file(work / (witness + ".aiw"), staged / "counterexample.aiw", ec);
  }
  fs::copy_file(work / "aesim_formal.sv", staged / "aesim_formal.sv", ec);
  fs::rename(staged, entry, ec);
  if (ec) fs::remove_all(staged, ec);
  result.seconds = seconds_since(start);
  return result;
}

}  // namespace aesim
