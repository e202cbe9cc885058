#include "ngspice/ngspice_run.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstring>
#include <fstream>
#include <mutex>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/files/scratch_text.hpp"
#include "aesim/text/ascii_case.hpp"
#include "aesim/process/child_process.hpp"

namespace aesim {
namespace {

namespace fs = std::filesystem;

// A run is a few thousand time steps of a small circuit (a fraction of a second; a foundry deck's
// BSIM models a few seconds); one that takes this long has collapsed its time step and would
// never finish, so the next solver settings are tried.
constexpr double kRunSeconds = 120;
// The pace StepCollapseWatch judges a run by: its last 10 s of progress, from 20 s on.
constexpr double kProgressWindow = 10;

// The simulated time ngspice last reported in `log`, or a negative number before its first report.
double reported_time(const fs::path& log) {
  std::ifstream in(log, std::ios::binary | std::ios::ate);
  if (!in) return -1;
  const std::streamoff size = in.tellg();
  const std::streamoff from = std::max<std::streamoff>(0, size - 256);
  in.seekg(from);
  std::string tail(static_cast<std::size_t>(size - from), '\0');
  in.read(tail.data(), static_cast<std::streamsize>(tail.size()));
  const std::size_t at = tail.rfind("Reference value :");
  if (at == std::string::npos) return -1;
  try {
    return std::stod(tail.substr(at + 17));
  } catch (const std::exception&) {
    return -1;
  }
}

// ngspice's progress lines ("Reference value : 1.2e-05", "No. of Data Rows : 1234"), which say
// nothing of why a run failed.
bool progress_line(const std::string& lower) {
  for (const char* p : {"reference value", "no. of data rows", "doing analysis", "initial transient solution",
                        "circuit:", "total analysis time", "binary raw file", "ascii raw file"}) {
    if (lower.rfind(p, 0) == 0) return true;
  }
  return false;
}

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r\n");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t\r\n") - a + 1);
}


// ngspice's first error as one line: the "Error" line and the lines that explain it, up to the
// line that says the run stopped; without such a line (ngspice's parser words some errors
// otherwise, e.g. 'Closing "}" not found.'), its first two lines.
std::string first_error(const std::string& log) {
  std::istringstream in(log);
  std::string line, message, opening;
  bool in_error = false;
  int extra = 0, lines = 0;
  while (std::getline(in, line)) {
    const std::string t = trim(line);
    if (t.empty()) continue;
    const std::string l = ascii_lower(t);
    if (progress_line(l)) continue;
    if (lines < 2 && l.rfind("note:", 0) != 0) {
      opening += (lines ? " " : "") + t;
      ++lines;
    }
    if (!in_error && l.find("error") != std::string::npos) {
      in_error = true;
      message = t;
    } else if (in_error) {
      if (l.find("simulation interrupted") != std::string::npos || l.rfind("note:", 0) == 0 || ++extra > 2) break;
      message += " " + t;
    }
  }
  // ngspice's parser says what is wrong first and then only "ERROR: fatal error in ngspice": the
  // first is the cause.
  if (in_error && ascii_lower(message).find("fatal error in ngspice") != std::string::npos && !opening.empty() &&
      ascii_lower(opening).find("fatal error in ngspice") == std::string::npos) {
    return opening;
  }
  return in_error ? message : opening;
}

// The model type ngspice's log says it does not know ("Unknown model type pspnqs103va -
// ignored"), or empty.
std::string unknown_model_type(const std::string& log) {
  static const std::string kUnknown = "unknown model type ";
  const std::string lower = ascii_lower(log);
  const auto at = lower.find(kUnknown);
  if (at == std::string::npos) return "";
  const auto from = at + kUnknown.size();
  const auto to = log.find_first_of(" \t\r\n", from);
  return log.substr(from, to == std::string::npos ? std::string::npos : to - from);
}

// The element ngspice's log says it cannot build when it is an N element, the letter of the
// devices OSDI libraries define, or empty: ngspice 39 without OSDI, "Error on line: n.xpix.nva
// out 0 0 0 vamos ... unknown device type"; ngspice 46 with it, "Error on line 18 or its
// substitute: n.xpix.nva ... Unable to find definition of model xpix:vamos".
std::string unknown_osdi_element(const std::string& log) {
  const std::string lower = ascii_lower(log);
  const auto at = lower.find("error on line");
  const auto colon = at == std::string::npos ? at : lower.find(':', at);
  if (colon == std::string::npos || (lower.find("unknown device type", colon) == std::string::npos &&
                                     lower.find("unable to find definition of model", colon) == std::string::npos)) {
    return "";
  }
  std::istringstream rest(log.substr(colon + 1));
  std::string element;
  rest >> element;
  return !element.empty() && (element[0] == 'n' || element[0] == 'N') ? element : "";
}

// Why a deck ngspice rejected failed, where the log shows a model it could not load: a library
// given with --osdi that this ngspice cannot load at all, or a model type (or an N element's
// device) nothing defined.
std::string model_failure(const std::string& log, const PixelDeck& deck, const std::string& log_note) {
  if (!deck.osdi.empty() && ascii_lower(log).find("osdi: no such command") != std::string::npos) {
    return fmt::format("--osdi: this ngspice cannot load OSDI libraries (it has no osdi command: built without "
                       "--enable-osdi); use an ngspice built with OSDI{}",
                       log_note);
  }
  // ngspice 46: 'Error opening osdi lib "PATH": No such file or directory!' (or the loader's own
  // complaint), then 'Error: Library PATH couldn't be loaded!'.
  if (!deck.osdi.empty()) {
    std::istringstream lines(log);
    for (std::string line; std::getline(lines, line);) {
      const std::string lower = ascii_lower(line);
      if (lower.find("osdi lib") != std::string::npos || lower.find("couldn't be loaded") != std::string::npos) {
        return fmt::format("--osdi: ngspice could not load a library: {}{}", trim(line), log_note);
      }
    }
  }
  std::string type = unknown_model_type(log);
  if (type.empty()) {
    const std::string element = unknown_osdi_element(log);
    if (element.empty()) return "";
    type = fmt::format("of the N element {}", element);
  } else {
    type = fmt::format("'{}'", type);
  }
  if (!deck.osdi.empty()) {
    return fmt::format("deck '{}': ngspice does not know the model type {}, which none of the --osdi libraries "
                       "defines{}",
                       deck.given, type, log_note);
  }
  return fmt::format("deck '{}': ngspice does not know the model type {}; a Verilog-A model compiled by OpenVAF "
                     "(as IHP SG13G2's PSP 103 MOS models are) loads with --osdi FILE.osdi, in an ngspice built with "
                     "OSDI{}",
                     deck.given, type, log_note);
}

}  // namespace

SolverSettings solver_settings(std::size_t level, double iph, double vdd) {
  SolverSettings s;  // level 0
  if (level == 0) return s;
  s.abstol = std::max(s.abstol, 1e-3 * iph);
  s.chgtol = std::max(s.chgtol, 1e-2 * s.abstol);  // the ratio level 0 keeps (C per A)
  s.gmin = std::max(s.gmin, 1e-3 * iph / vdd);
  if (level >= 2) s.method = "trap";
  return s;
}

std::string SolverSettings::label() const {
  return fmt::format("{}, abstol {:g}, chgtol {:g}, gmin {:g}", method, abstol, chgtol, gmin);
}

const char* solver_level_text(std::size_t level) {
  switch (level) {
    case 0: return "gear, abstol 1e-17, chgtol 1e-19, gmin 1e-18";
    case 1: return "gear, abstol and gmin x vdd at 1e-3 of the photocurrent";
    default: return "trap, abstol and gmin x vdd at 1e-3 of the photocurrent";
  }
}

std::string testbench_text(const PixelDeck& deck, double vdd, const TransientRequest& r, const std::string& data_path) {
  std::string probe;
  if (!deck.probe.empty()) probe = fmt::format(" v(xpix.{})", deck.probe);
  // After the deck, so that they win over its own values (ngspice keeps a .param's last value).
  std::string switches;
  for (const std::string& name : deck.statistical_switches) {
    switches += fmt::format(".param {}={}\n", name, r.monte_carlo ? 1 : 0);
  }
  const SolverSettings solver = solver_settings(r.settings, r.iph, vdd);
  const std::string nets = fmt::format("{}", fmt::join(deck.port_nets, " "));
  std::string bias_sources;
  for (const PortBias& b : deck.biases) bias_sources += fmt::format("V{0} {0} 0 {1:.12g}\n", bias_net(b.port), b.volts);
  // OSDI libraries load before ngspice reads the circuit (the `pre_` prefix), wherever the block is.
  std::string osdi;
  for (const std::string& library : deck.osdi) osdi += fmt::format("pre_osdi '{}'\n", library);
  // First settings: Gear integration (the trapezoidal rule rings on the pixel's fast edges and
  // fakes firings at slow ramps), tolerances sized for femtoamps and femtocoulombs (the defaults,
  // 1 pA and 10 fC, are the size of what is measured), and gmin, the conductance ngspice puts
  // across every junction (1 pS by default, i.e. picoamps of fake leakage), far below the deck's
  // own leakage. The deck comes after them, so its own .options win. One thread: ngspice's BSIM3
  // and BSIM4 models evaluate devices on two OpenMP threads by default, which on a pixel's handful
  // of transistors only spins the second (a GF180 transient: 25 s of CPU on one thread, 54 s on two,
  // no sooner done), and with `--jobs` runs at once the spinning threads starve the others.
  return fmt::format(
      "* aesim calibrate: {} at iph = {:.6g} A\n"
      ".options method={} reltol=1e-4 abstol={:g} chgtol={:g} gmin={:g} seed={}\n"
      "{}"
      "{}"
      "Vdd vdd 0 {:.12g}\n"
      "{}"
      "Xpix {} {} iph={:.12g}{}\n"
      ".control\n"
      "{}"
      "set num_threads=1\n"
      "tran {:.6g} {:.12g} 0 {:.6g} uic\n"
      "set wr_singlescale\n"
      "set numdgt=15\n"
      "set wr_vecnames\n"
      "wrdata {} v(out) i(vdd){}\n"
      "quit 0\n"
      ".endc\n"
      ".end\n",
      deck.subckt, r.iph, solver.method, solver.abstol, solver.chgtol, solver.gmin, r.seed, deck.circuit, switches, vdd,
      bias_sources, nets, deck.subckt, r.iph,
      deck.mc_parameter ? fmt::format(" mc={}", r.monte_carlo ? 1 : 0) : std::string(), osdi, r.t_max, r.t_stop, r.t_max,
      data_path, probe);
}

namespace {

// Copies the testbench and ngspice's log to `target` for the user, once a calibration: its first
// run that fails there writes it (replacing the log of an earlier calibration, which would
// otherwise be named as this one's), later ones (other currents, other jobs) leave it. Never
// written through anything but a regular file. Returns `target` when it now holds this
// calibration's log, empty otherwise.
std::string keep_failure_log(const std::string& target, const fs::path& cir, const fs::path& log) {
  if (target.empty()) return "";
  static std::mutex once;
  static std::set<std::string> written;
  const std::lock_guard<std::mutex> lock(once);
  if (written.count(target)) return target;
  std::error_code ec;
  if (fs::exists(target, ec) && !fs::is_regular_file(fs::symlink_status(target, ec))) return "";
  written.insert(target);
  std::ofstream out(target, std::ios::trunc);
  out << "* the testbench aesim calibrate ran (" << cir.filename().string() << ")\n"
      << read_scratch_text(cir) << "\n* ngspice's output\n"
      << read_scratch_text(log);
  return out ? target : "";
}

}  // namespace

bool StepCollapseWatch::keep_waiting(double wall, double reported) {
  if (reported < 0) return true;
  samples_.emplace_back(wall, reported);
  while (samples_.size() > 2 && samples_.front().first < wall - window_) samples_.pop_front();
  if (wall < 2 * window_) return true;
  const double pace = (reported - samples_.front().second) / (wall - samples_.front().first);
  // ngspice's pace swings (fine steps through each firing's edges, long ones between), so only a
  // pace that would need ten times the time left is taken for a collapse; a slower run meets the limit.
  if (pace > 0 && (t_stop_ - reported) / pace < 10 * (run_seconds_ - wall)) return true;
  stalled_at_ = reported;
  return false;
}

Waveform run_transient(const PixelDeck& deck, double vdd, const TransientRequest& request, const fs::path& scratch,
                       const std::string& name) {
  const fs::path cir = scratch / (name + ".cir"), data = scratch / (name + ".txt"), log = scratch / (name + ".log");
  {
    std::ofstream out(cir);
    out << testbench_text(deck, vdd, request, data.string());
    if (!out) throw std::runtime_error(fmt::format("cannot write '{}'", cir.string()));
  }
  pid_t pid = 0;
  try {
    // In the deck's folder, as the user runs it: ngspice finds a relative .include beside the file
    // that names it, but a relative .lib (a PDK's model library) only from its working folder.
    std::vector<std::string> args{"-b", "-n"};
    if (!deck.ngbehavior.empty()) args.insert(args.end(), {"-D", "ngbehavior=" + deck.ngbehavior});
    args.push_back(cir.string());
    pid = spawn_child("ngspice", args,
                      {(scratch / (name + ".out")).string(), log.string(), fs::path(deck.path).parent_path().string()});
  } catch (const ToolMissing&) {
    throw InputError("ngspice is not installed: run scripts/setup (or apt-get install ngspice)");
  }
  StepCollapseWatch watch(request.t_stop, kRunSeconds, kProgressWindow);
  const auto started = std::chrono::steady_clock::now();
  bool abandoned = false;
  const auto will_finish = [&] {
    if (request.abandon && request.abandon()) {
      abandoned = true;
      return false;
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    return watch.keep_waiting(wall, reported_time(log));
  };
  const std::optional<int> status = wait_child_while(pid, kRunSeconds, will_finish, 1.0);
  if (!status && abandoned) throw TransientAbandoned();
  if (!status) {
    if (const double stalled_at = watch.stalled_at(); stalled_at >= 0) {
      throw TransientAborted(fmt::format("ngspice's time step collapsed near t = {:.4g} s: at its pace it would not "
                                         "finish within {:.0f} s",
                                         stalled_at, kRunSeconds));
    }
    throw TransientAborted(fmt::format("ngspice ran longer than {:.0f} s (its time step collapsed)", kRunSeconds));
  }
  // Ended by SIGINT or SIGTERM: a Ctrl-C or a kill reaches ngspice with the rest of the process
  // group, often before this process has seen its own; the signal, not the deck, is why.
  if (*status == 128 + SIGINT || *status == 128 + SIGTERM) throw Interrupted(*status - 128);
  if (*status > 128) {
    throw InputError(fmt::format("deck '{}': ngspice crashed on it (signal {}: {})", deck.given, *status - 128,
                                 strsignal(*status - 128)));
  }
  if (*status != 0) {
    const std::string log_text = read_scratch_text(log);
    std::string error = first_error(log_text), log_note;
    if (const std::string kept = keep_failure_log(request.failure_log, cir, log); !kept.empty()) {
      log_note = fmt::format(" (ngspice's log: {})", kept);
      error += log_note;
    }
    if (const std::string model = model_failure(log_text, deck, log_note); !model.empty()) throw InputError(model);
    if (ascii_lower(error).find("unknown subckt") != std::string::npos) {
      throw InputError(fmt::format("deck '{}': ngspice finds no subcircuit '{}' ({})", deck.given, deck.subckt, error));
    }
    throw InputError(fmt::format("deck '{}': ngspice rejects it: {}", deck.given,
                                 error.empty() ? fmt::format("exit status {}", *status) : error));
  }
  const std::string messages = read_scratch_text(log);
  if (ascii_lower(messages).find("timestep too small") != std::string::npos) {
    throw TransientAborted(first_error(messages).empty() ? "timestep too small" : first_error(messages));
  }
  Waveform w;
  std::ifstream in(data);
  std::string header;
  if (!std::getline(in, header)) {
    throw InputError(fmt::format("deck '{}': ngspice wrote no waveform at iph = {:.3g} A ({})", deck.given, request.iph,
                                 first_error(read_scratch_text(log))));
  }
  const bool probe = !deck.probe.empty();
  double t = 0, out = 0, supply = 0, node = 0;
  while (in >> t >> out >> supply) {
    if (probe && !(in >> node)) break;
    w.t.push_back(t);
    w.out.push_back(out);
    w.supply.push_back(supply);
    if (probe) w.probe.push_back(node);
  }
  return w;
}

std::string ngspice_version() {
  static const std::string version = [] {
    const fs::path out = fs::temp_directory_path() / fmt::format("aesim-ngspice-version-{}", ::getpid());
    std::string v = "ngspice (version unknown)";
    try {
      if (run_child("ngspice", {"-v"}, {out.string(), "/dev/null"}) == 0) {
        std::istringstream in(read_scratch_text(out));
        std::string line;
        while (std::getline(in, line)) {
          const auto at = line.find("ngspice-");
          if (at != std::string::npos) {
            std::istringstream words(line.substr(at));
            words >> v;
            break;
          }
        }
      }
    } catch (const ToolMissing&) {
    }
    std::error_code ec;
    fs::remove(out, ec);
    return v;
  }();
  return version;
}

}  // namespace aesim
