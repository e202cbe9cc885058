#include <fcntl.h>
#include <sys/statvfs.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstring>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "error_exit.hpp"
#include "aesim/files/data_dir.hpp"
#include "aesim/errors/input_error.hpp"
#include "aesim/files/input_path.hpp"
#include "aesim/files/content_hash.hpp"
#include "aesim/files/scratch_folder.hpp"
#include "aesim/output/atomic_file.hpp"
#include "aesim/output/temp_files.hpp"
#include "aesim/process/child_process.hpp"
#ifdef AESIM_HAVE_MPI
#include <mpi.h>
#endif

#include "aesim/sizing/sizing_report.hpp"
#include "aesim/spec/sweep_spec.hpp"
#include "report_stream.hpp"

namespace aesim {
namespace fs = std::filesystem;
namespace {

// The docs/reference.md section 5 summary columns, then aesim's extra ones, in this order.
const char* const kSummaryColumns[] = {
    "events_fired", "events_delivered", "events_collided", "events_ghost", "events_dropped",
    "offered_load", "throughput", "tau_s", "sim_time_s", "wall_time_s", "fidelity",
    "events_pending", "collision_fraction", "latency_mean_s", "latency_p99_s", "latency_max_s",
    "protocol_violations", "pixel_rate_min_hz", "pixel_rate_mean_hz", "pixel_rate_max_hz", "dynamic_range_covered",
    "psnr_db", "energy_per_event_j", "power_w", "power_per_tile_w", "offered_load_max_tile",
    "collision_fraction_max_tile"};

// RFC 4180: a field holding a comma, quote or newline is quoted, quotes doubled.
std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string cell(const nlohmann::json& v) { return csv_field(v.is_string() ? v.get<std::string>() : v.dump()); }

std::string display_path(const std::string& p) {
  const std::string root = fs::weakly_canonical(data_dir()).string() + "/";
  return p.rfind(root, 0) == 0 ? p.substr(root.size()) : p;
}

// The identity of a sweep's points, so that a journal is only resumed by the same sweep.
std::string sweep_identity(const SweepSpec& spec) {
  std::string all = spec.sensor + "|" + spec.duration;
  for (const SweepPoint& p : spec.points) {
    all += "|" + p.scene;
    for (const auto& [k, v] : p.sets) all += "," + k + "=" + v;
  }
  return content_hash_hex(all);
}

// This process's share of a sweep: under mpirun, point i belongs to rank i mod size.
struct Share {
  int rank = 0, size = 1;
  bool mine(std::size_t i) const { return static_cast<int>(i % static_cast<std::size_t>(size)) == rank; }
};

// Runs `aesim run` for each point as a child process, `jobs` at a time. Every finished point's
// summary is appended to the journal as one line, in one write, so an interrupted sweep loses at
// most the points in flight, and a torn last line (a kill mid-write) is recognised and ignored.
class PointRunner {
 public:
  PointRunner(const SweepSpec& spec, fs::path work, std::string journal, Share share = {})
      : spec_(spec),
        work_(std::move(work)),
        journal_path_(std::move(journal)),
        share_(share),
        summaries_(spec.points.size()) {}

  void set_summary(std::size_t index, nlohmann::json s) { summaries_[index] = std::move(s); }

  // Reads what an earlier, interrupted run of the same sweep finished. Returns how many.
  std::size_t resume() {
    std::ifstream in(journal_path_);
    if (!in) return 0;
    std::string line;
    std::size_t found = 0;
    if (!std::getline(in, line) || line != "aesim-sweep " + sweep_identity(spec_)) {
      throw InputError(fmt::format("'{}' holds partial results of a different sweep; delete it to start afresh",
                                   journal_path_));
    }
    while (std::getline(in, line)) {
      if (in.eof()) break;  // no newline: torn by an interruption
      const nlohmann::json j = nlohmann::json::parse(line, nullptr, false);
      if (j.is_discarded() || !j.contains("index")) break;
      const std::size_t i = j["index"].get<std::size_t>();
      if (i < summaries_.size() && summaries_[i].is_null()) {
        summaries_[i] = j["summary"];
        ++found;
      }
    }
    return found;
  }

  void run_all(int jobs) {
    const int fd = ::open(journal_path_.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    if (fd < 0) throw InputError(fmt::format("cannot write '{}'", journal_path_));
    struct Closer {
      int fd;
      ~Closer() { ::close(fd); }
    } closer{fd};
    if (::lseek(fd, 0, SEEK_END) == 0) append(fd, "aesim-sweep " + sweep_identity(spec_) + "\n");
    std::vector<std::size_t> todo;
    for (std::size_t i = 0; i < summaries_.size(); ++i) {
      if (summaries_[i].is_null() && share_.mine(i)) todo.push_back(i);
    }
    std::map<pid_t, std::size_t> running;
    std::size_t next = 0, done = 0;
    const auto started = std::chrono::steady_clock::now();
    std::size_t resumed = 0;
    for (std::size_t i = 0; i < summaries_.size(); ++i) resumed += share_.mine(i) && !summaries_[i].is_null() ? 1 : 0;
    while (done < todo.size()) {
      while (next < todo.size() && static_cast<int>(running.size()) < jobs) {
        running[start(todo[next])] = todo[next];
        ++next;
      }
      int status = 0;
      const pid_t pid = waitpid(-1, &status, 0);
      if (const int sig = interrupt_requested()) {
        // Finished points are in the journal; the ones in flight are stopped and rerun on resume.
        if (pid > 0) running.erase(pid);
        for (const auto& [child, unused] : running) kill(child, SIGTERM);
        for (const auto& [child, unused] : running) waitpid(child, nullptr, 0);
        std::fprintf(stderr, "aesim sweep: stopped; the finished points are kept in %s: the same command resumes\n",
                     journal_path_.c_str());
        throw Interrupted(sig);
      }
      if (pid < 0) {
        if (errno == EINTR) continue;
        throw std::runtime_error(fmt::format("waitpid: {}", std::strerror(errno)));
      }
      const auto it = running.find(pid);
      if (it == running.end()) continue;
      const std::size_t index = it->second;
      running.erase(it);
      ++done;
      if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        for (const auto& [other, unused] : running) kill(other, SIGTERM);
        for (std::size_t i = running.size(); i > 0; --i) waitpid(-1, nullptr, 0);
        std::ifstream log(work_ / fmt::format("point_{}.log", index));
        const std::string text((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
        std::string reason = text.substr(0, text.find('\n'));
        if (reason.rfind("aesim: ", 0) == 0) reason.erase(0, 7);
        if (reason.empty()) {
          // No message: say how it ended, and whether its folder has room left (a full disk
          // leaves the log empty too).
          struct statvfs fs_info {};
          const bool full = ::statvfs(work_.c_str(), &fs_info) == 0 && fs_info.f_bavail == 0;
          reason = WIFSIGNALED(status) ? fmt::format("killed by signal {} ({})", WTERMSIG(status), strsignal(WTERMSIG(status)))
                                       : fmt::format("exit status {}", WEXITSTATUS(status));
          if (full) reason += fmt::format(" with no message: {}", std::strerror(ENOSPC));
        }
        const std::string why = fmt::format("point {} failed: {}", index + 1, reason);
        // A point refused as bad input (e.g. work past sim.max_events) makes the sweep's input bad too.
        if (WIFEXITED(status) && WEXITSTATUS(status) == 2) throw InputError(why);
        throw std::runtime_error(why);
      }
      std::ifstream in(work_ / fmt::format("point_{}.json", index));
      summaries_[index] = nlohmann::json::parse(in);
      append(fd, nlohmann::json{{"index", index}, {"summary", summaries_[index]}}.dump() + "\n");
      progress(resumed, done, todo.size(), started);
    }
  }

  const nlohmann::json& summary(std::size_t index) const { return summaries_[index]; }
  std::size_t finished() const {
    return static_cast<std::size_t>(std::count_if(summaries_.begin(), summaries_.end(), [](const auto& s) { return !s.is_null(); }));
  }

 private:
  // A point runs in a forked child: the command's own code without a new program's start-up
  // (~14 ms of loading and initialising per point), still a process of its own, so a point that
  // crashes or runs out of memory takes nothing else with it, and a journal entry is written
  // only for a point that finished.
  pid_t start(std::size_t index) {
    const SweepPoint& p = spec_.points[index];
    RunOptions run;
    run.sensor = spec_.sensor;
    run.scene = p.scene;
    run.duration = spec_.duration;
    for (const auto& [k, v] : p.sets) run.sets.push_back(k + "=" + v);
    run.summary = (work_ / fmt::format("point_{}.json", index)).string();
    const std::string log = (work_ / fmt::format("point_{}.log", index)).string();
    std::fflush(nullptr);
    const pid_t pid = fork();
    if (pid < 0) throw std::runtime_error(fmt::format("fork: {}", std::strerror(errno)));
    if (pid > 0) return pid;
    // The child: signals end it at once (the parent's polite stop is the parent's), its output
    // goes to the point's log.
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) std::signal(sig, SIG_DFL);
    const int quiet = ::open("/dev/null", O_WRONLY);
    const int err = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (quiet < 0 || err < 0 || ::dup2(quiet, STDOUT_FILENO) < 0 || ::dup2(err, STDERR_FILENO) < 0) _exit(1);
    const int status = with_error_exit([&] { return run_command(run); });
    std::fflush(nullptr);
    _exit(status);
  }

  static void append(int fd, const std::string& line) {
    if (::write(fd, line.data(), line.size()) != static_cast<ssize_t>(line.size())) {
      throw std::runtime_error("appending to the sweep journal failed");
    }
  }

  // A progress bar with an ETA on a terminal; a line every tenth of the sweep otherwise.
  void progress(std::size_t resumed, std::size_t done, std::size_t todo,
                std::chrono::steady_clock::time_point started) const {
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    const double eta = elapsed / static_cast<double>(done) * static_cast<double>(todo - done);
    const std::size_t total = resumed + todo, finished = resumed + done;
    if (isatty(STDERR_FILENO)) {
      const int width = 30, filled = static_cast<int>(width * finished / total);
      std::fprintf(stderr, "\raesim sweep: [%s%s] %zu/%zu points, %.0f s, ETA %.0f s ",
                   std::string(static_cast<std::size_t>(filled), '#').c_str(),
                   std::string(static_cast<std::size_t>(width - filled), '.').c_str(), finished, total, elapsed, eta);
      if (done == todo) std::fprintf(stderr, "\n");
    } else if (done == todo || (done * 10 / todo) != ((done - 1) * 10 / todo)) {
      std::fprintf(stderr, "aesim sweep: %zu/%zu points, %.1f s, ETA %.1f s\n", finished, total, elapsed, eta);
    }
  }

  const SweepSpec& spec_;
  fs::path work_;
  std::string journal_path_;
  Share share_;
  std::vector<nlohmann::json> summaries_;
};

#ifdef AESIM_HAVE_MPI
// Rank 0 receives every other rank's summaries (index, then the JSON text) for the one CSV.
void gather_summaries(PointRunner& runner, const SweepSpec& spec, const Share& share) {
  if (share.rank != 0) {
    for (std::size_t i = 0; i < spec.points.size(); ++i) {
      if (!share.mine(i)) continue;
      const std::string text = runner.summary(i).dump();
      const unsigned long index = i;
      MPI_Send(&index, 1, MPI_UNSIGNED_LONG, 0, 0, MPI_COMM_WORLD);
      MPI_Send(text.data(), static_cast<int>(text.size()), MPI_CHAR, 0, 1, MPI_COMM_WORLD);
    }
    return;
  }
  for (std::size_t i = 0; i < spec.points.size(); ++i) {
    if (share.mine(i)) continue;
    unsigned long index = 0;
    MPI_Status status;
    MPI_Recv(&index, 1, MPI_UNSIGNED_LONG, MPI_ANY_SOURCE, 0, MPI_COMM_WORLD, &status);
    int length = 0;
    MPI_Probe(status.MPI_SOURCE, 1, MPI_COMM_WORLD, &status);
    MPI_Get_count(&status, MPI_CHAR, &length);
    std::string text(static_cast<std::size_t>(length), '\0');
    MPI_Recv(text.data(), length, MPI_CHAR, status.MPI_SOURCE, 1, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    runner.set_summary(index, nlohmann::json::parse(text));
  }
}
#endif

// Whether mpirun started this process (OpenMPI, MPICH and PMIx launchers set these).
bool launched_by_mpirun() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"}) {
    if (std::getenv(v)) return true;
  }
  return false;
}

// Draws the spec's chart from the CSV's temporary file into temporaries of STEM.png and STEM.svg,
// committed with the CSV. gnuplot gets the paths and labels as arguments, never inside a command or
// an expression: `gnuplot -c SCRIPT CSV PNG SVG SENSOR PSNR_MIN POWER_PER_TILE_MAX` (ARG1..ARG6;
// the bounds in dB and W, empty when the spec has no such constraint). Returns false if gnuplot is
// absent.
bool draw_chart(OutputFiles& files, const SweepSpec& spec, const std::string& csv, const std::string& stem) {
  if (!program_available("gnuplot")) {
    std::fprintf(stderr, "aesim sweep: gnuplot not found; chart skipped (apt-get install gnuplot-nox)\n");
    return false;
  }
  std::string psnr_min, power_max;
  for (const Constraint& c : spec.constraints) {
    if (c.column == "psnr_db" && !c.at_most) psnr_min = fmt::format("{:.17g}", c.bound);
    if (c.column == "power_per_tile_w" && c.at_most) power_max = fmt::format("{:.17g}", c.bound);
  }
  const std::string sensor = fs::path(spec.sensor).stem().string();
  files.flush();
  const std::string png = files.adopt(stem + ".png"), svg = files.adopt(stem + ".svg");
  if (run_child("gnuplot", {"-c", spec.chart, files.temp_path(csv), png, svg, sensor, psnr_min, power_max}) != 0) {
    throw OutputError(
        fmt::format("gnuplot failed on the chart script '{}' (its message above); no output written", spec.chart));
  }
  return true;
}

}  // namespace

int sweep_command(SweepOptions opt) {
  Share share;
  if (launched_by_mpirun()) {
#ifdef AESIM_HAVE_MPI
    MPI_Init(nullptr, nullptr);
    MPI_Comm_rank(MPI_COMM_WORLD, &share.rank);
    MPI_Comm_size(MPI_COMM_WORLD, &share.size);
#else
    throw InputError("aesim sweep runs under mpirun only when built with MPI (install libopenmpi-dev)");
#endif
  }
  struct Finalize {
    bool active;
    ~Finalize() {
#ifdef AESIM_HAVE_MPI
      if (active) MPI_Finalize();
#endif
    }
  } finalize{share.size > 1 || launched_by_mpirun()};
  opt.spec = shipped_if_missing(opt.spec);
  const SweepSpec spec = load_sweep_spec(opt.spec);
  if (opt.output.empty()) opt.output = "out/" + fs::path(opt.spec).stem().string() + ".csv";
  if (file_extension(opt.output) != ".csv") throw InputError(fmt::format("-o '{}': use a .csv file name", opt.output));
  int jobs = opt.jobs >= 0 ? opt.jobs : spec.jobs;
  if (jobs == 0) jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const fs::path folder = fs::path(opt.output).parent_path();
  const std::string stem = (folder / fs::path(opt.output).stem()).string();
  const std::string report_path = stem + ".report.md";
  const bool chart = !spec.chart.empty() && !opt.no_chart;
  std::vector<std::string> inputs = {opt.spec, spec.sensor, spec.chart};
  for (const SweepPoint& p : spec.points) inputs.push_back(p.scene);
  check_output_paths({{"-o", opt.output},
                      {"the sweep report", spec.constraints.empty() ? "" : report_path},
                      {"the chart", chart ? stem + ".png" : ""},
                      {"the chart", chart ? stem + ".svg" : ""},
                      {"the resume journal", opt.output + ".partial"}},
                     inputs);
  // The journal is read back and rewritten: it must be a file, not a device or a FIFO.
  {
    std::error_code ec;
    const std::string partial = opt.output + ".partial";
    if ((fs::exists(partial, ec) || fs::is_symlink(partial, ec)) && !fs::is_regular_file(partial, ec)) {
      throw InputError(fmt::format("the resume journal '{}': {}", partial, not_a_file(partial)));
    }
  }

  const Cooperative stop_politely;  // a signal stops the points and keeps the journal for a resume
  const auto wall_start = std::chrono::steady_clock::now();
  OutputFiles files;
  // Under MPI only rank 0 writes; the other ranks work in their own folders beside it.
  std::ostream* csv_stream = share.rank == 0 ? &files.open(opt.output) : nullptr;
  fs::create_directories(folder.empty() ? fs::path(".") : folder);
  remove_stale_temps(folder.string());
  const ScratchFolder scratch(temp_name_for(opt.output, fmt::format(".points{}", share.rank)));
  const fs::path& work = scratch.path();

  // The journal of finished points: an interrupted sweep resumes from it.
  const std::string journal = share.size > 1 ? (work / "journal").string() : opt.output + ".partial";
  PointRunner runner(spec, work, journal, share);
  if (const std::size_t resumed = share.size > 1 ? 0 : runner.resume()) {
    std::fprintf(stderr, "aesim sweep: resuming: %zu of %zu points already done (%s)\n", resumed, spec.points.size(),
                 journal.c_str());
  }
  try {
    runner.run_all(jobs);
  } catch (...) {
    // A journal without a finished point resumes nothing: leave no file behind.
    std::error_code ignored;
    if (runner.finished() == 0) fs::remove(journal, ignored);
    throw;
  }
#ifdef AESIM_HAVE_MPI
  if (share.size > 1) {
    gather_summaries(runner, spec, share);
    if (share.rank != 0) return 0;
  }
#endif
  std::ostream& csv = *csv_stream;

  csv << "group,scene";
  for (const std::string& k : spec.swept_keys) csv << ',' << k;
  for (const char* c : kSummaryColumns) csv << ',' << c;
  csv << ",theory_throughput,theory_collision_fraction" << (spec.constraints.empty() ? "" : ",feasible,recommended")
      << "\n";
  // A design is the swept values without the operating conditions (the scene and light.* keys):
  // it must work on every scene in every light, so it is judged on its worst case across them.
  std::vector<DesignPoint> per_point;
  for (std::size_t i = 0; i < spec.points.size(); ++i) {
    const nlohmann::json& s = runner.summary(i);
    DesignPoint d;
    for (const auto& [k, v] : spec.points[i].sets) {
      const bool condition = k.rfind("light.", 0) == 0;
      if (!condition && std::find(spec.swept_keys.begin(), spec.swept_keys.end(), k) != spec.swept_keys.end()) {
        d.label += (d.label.empty() ? "" : " ") + k + "=" + v;
      }
    }
    for (const char* c : kSummaryColumns) {
      if (s.contains(c) && s[c].is_number()) d.values[c] = s[c].get<double>();
    }
    per_point.push_back(std::move(d));
  }
  const std::vector<DesignPoint> design = worst_case_by_label(per_point);
  const SizingAnalysis analysis = analyse_sizing(design, spec.constraints);
  std::map<std::string, bool> design_feasible;
  for (std::size_t i = 0; i < design.size(); ++i) design_feasible[design[i].label] = analysis.feasible[i];
  for (std::size_t i = 0; i < spec.points.size(); ++i) {
    const nlohmann::json& s = runner.summary(i);
    csv << csv_field(spec.points[i].group) << ',' << csv_field(display_path(spec.points[i].scene));
    for (const std::string& k : spec.swept_keys) {
      const auto dot = k.find('.');
      csv << ',' << cell(s["sensor"][k.substr(0, dot)][k.substr(dot + 1)]);
    }
    for (const char* c : kSummaryColumns) csv << ',' << cell(s[c]);
    const double g = s["offered_load"];
    csv << ',' << fmt::format("{:.17g}", g * std::exp(-2 * g)) << ',' << fmt::format("{:.17g}", 1 - std::exp(-2 * g));
    if (!spec.constraints.empty()) {
      const bool recommended = analysis.recommended >= 0 &&
                               per_point[i].label == design[static_cast<std::size_t>(analysis.recommended)].label;
      csv << ',' << (design_feasible[per_point[i].label] ? 1 : 0) << ',' << (recommended ? 1 : 0);
    }
    csv << '\n';
  }
  if (!spec.constraints.empty()) files.open(report_path) << sizing_report(design, spec.constraints, analysis);
  const bool drawn = chart && draw_chart(files, spec, opt.output, stem);
  files.commit();
  std::error_code ignored;
  fs::remove(journal, ignored);  // complete: the CSV holds it all
  if (!spec.constraints.empty()) {
    fmt::print(report_stream(), "aesim sweep: {} of {} designs feasible in every condition; report {}\n",
               std::count(analysis.feasible.begin(), analysis.feasible.end(), true), design.size(), report_path);
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  fmt::print(report_stream(), "aesim sweep: {} points on {} jobs in {:.1f} s -> {}\n", spec.points.size(), jobs, wall, opt.output);

  if (drawn) fmt::print(report_stream(), "  chart {}.png, {}.svg\n", stem, stem);
  return 0;
}

}  // namespace aesim
