// The Python module `aesim` (docs/reference.md section 8): run, emulate, classify and sweep as the commands do
// them, through the same library (the commands' own functions where they exist), with results as
// NumPy arrays filled in one pass and errors as the command line's one-line messages.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <unistd.h>

#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "command_settings.hpp"
#include "commands.hpp"
#include "aesim/errors/input_error.hpp"
#include "aesim/events/event_stream.hpp"
#include "aesim/events/timestamps.hpp"
#include "aesim/limits/limits.hpp"
#include "aesim/output/temp_files.hpp"
#include "aesim/process/interrupt.hpp"
#include "aesim/scene/npy_scene.hpp"
#include "aesim/scene/scene.hpp"
#include "aesim/sensor_run/sensor_run.hpp"
#include "aesim/version.hpp"

namespace py = pybind11;

namespace aesim {
namespace {

// Ctrl-C while a call runs: Python's own handler only sets a flag that Python code would look at,
// and none runs while the call holds the thread. This records the request where the run looks
// for it (the event rung between windows, a sweep between points) and puts Python's handler back
// afterwards; the call then raises KeyboardInterrupt.
class CtrlC {
 public:
  CtrlC() {
    clear_interrupt();
    struct sigaction action {};
    action.sa_handler = [](int sig) { request_interrupt(sig); };
    sigemptyset(&action.sa_mask);
    installed_ = ::sigaction(SIGINT, &action, &previous_) == 0;
  }
  ~CtrlC() {
    if (installed_) ::sigaction(SIGINT, &previous_, nullptr);
  }
  CtrlC(const CtrlC&) = delete;
  CtrlC& operator=(const CtrlC&) = delete;
  // Raises KeyboardInterrupt if Ctrl-C came during the call.
  static void raise_if_interrupted() {
    if (!interrupt_requested()) return;
    clear_interrupt();
    PyErr_SetNone(PyExc_KeyboardInterrupt);
    throw py::error_already_set();
  }

 private:
  struct sigaction previous_ {};
  bool installed_ = false;
};

// Runs `work` without the GIL (other Python threads go on), interruptible by Ctrl-C.
template <typename F>
auto without_gil(F&& work) {
  CtrlC ctrl_c;
  try {
    py::gil_scoped_release release;
    return work();
  } catch (const Interrupted&) {
    request_interrupt(SIGINT);
    CtrlC::raise_if_interrupted();
    throw;
  }
}

// A folder of its own for files a call writes for the library (a scene given as an array, a
// sweep's CSV), removed when the call ends.
class CallFolder {
 public:
  CallFolder() {
    const char* base = std::getenv("TMPDIR");
    std::string pattern = std::string(base && *base ? base : "/tmp") + "/aesim-python-XXXXXX";
    std::vector<char> buf(pattern.begin(), pattern.end());
    buf.push_back('\0');
    if (!::mkdtemp(buf.data())) throw OutputError(fmt::format("cannot make a temporary folder: {}", std::strerror(errno)));
    path_ = buf.data();
  }
  ~CallFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  CallFolder(const CallFolder&) = delete;
  CallFolder& operator=(const CallFolder&) = delete;
  std::string file(const std::string& name) const { return path_ + "/" + name; }

 private:
  std::string path_;
};

bool is_path(const py::handle& h) {
  return py::isinstance<py::str>(h) || py::hasattr(h, "__fspath__");
}

std::string as_path(const py::handle& h) { return py::str(py::module_::import("os").attr("fspath")(h)); }

// A 2-D array as an image of full-scale fractions, its numbers taken as a .npy scene file's
// (array_full_scale: 8- and 16-bit integer codes, floats as they are). Linear light.
Image image_from_array(const py::handle& object, const char* what) {
  py::array a = py::array::ensure(object);
  if (!a) throw InputError(fmt::format("{}: expected a path or a 2-D or 3-D NumPy array", what));
  if (a.ndim() != 2) {
    throw InputError(fmt::format("{}: expected a 2-D array (rows, columns) or a 3-D one (frames, rows, columns), got {} "
                                 "dimension{}",
                                 what, a.ndim(), a.ndim() == 1 ? "" : "s"));
  }
  const long rows = static_cast<long>(a.shape(0)), cols = static_cast<long>(a.shape(1));
  if (rows < 1 || cols < 1 || static_cast<long long>(rows) * cols > (1LL << 24)) {
    throw InputError(fmt::format("{}: an array of {} rows and {} columns; aesim takes 1 to 16,777,216 (4096x4096) pixels",
                                 what, rows, cols));
  }
  const double scale = array_full_scale(a.dtype().kind(), static_cast<int>(a.dtype().itemsize()),
                                        fmt::format("{}: dtype {}", what, std::string(py::str(a.dtype()))));
  py::array_t<double, py::array::c_style | py::array::forcecast> values(a);
  Image img;
  img.width = static_cast<int>(cols);
  img.height = static_cast<int>(rows);
  img.pixels.assign(values.data(), values.data() + rows * cols);
  const double per_code = 1.0 / scale;  // as the PGM reader scales its codes, to the last bit
  for (double& v : img.pixels) {
    v *= per_code;
    if (!std::isfinite(v) || v < 0) throw InputError(fmt::format("{}: values must be finite and not negative", what));
  }
  return img;
}

// A 2-D array as one frame, a 3-D array (frames, rows, columns) as a sequence of them.
std::vector<Image> frames_from_array(const py::handle& object, const char* what) {
  const py::array a = py::array::ensure(object);
  std::vector<Image> frames;
  if (a && a.ndim() == 3) {
    if (a.shape(0) < 1 || static_cast<std::size_t>(a.shape(0)) > kMaxSceneFrames) {
      throw InputError(fmt::format("{}: an array of {} frames; aesim takes 1 to {}", what, a.shape(0), kMaxSceneFrames));
    }
    check_not_colour_last({static_cast<std::uint64_t>(a.shape(0)), static_cast<std::uint64_t>(a.shape(1)),
                           static_cast<std::uint64_t>(a.shape(2))},
                          what);
    for (py::ssize_t k = 0; k < a.shape(0); ++k) frames.push_back(image_from_array(a[py::int_(k)], what));
  } else {
    frames.push_back(image_from_array(object, what));
  }
  return frames;
}

std::vector<std::string> settings_text(const py::object& set) {
  std::vector<std::string> out;
  if (set.is_none()) return out;
  for (const auto& [key, value] : set.cast<py::dict>()) {
    out.push_back(std::string(py::str(key)) + "=" + std::string(py::str(value)));
  }
  return out;
}

py::object json_to_python(const nlohmann::json& j) { return py::module_::import("json").attr("loads")(j.dump()); }

py::dtype packed_dtype(const std::vector<std::pair<const char*, const char*>>& fields) {
  py::list list;
  for (const auto& [name, type] : fields) list.append(py::make_tuple(name, type));
  return py::dtype::from_args(list);
}

// Copies `records` into a new structured array of `dtype`, one record at a time in C++.
template <typename Record, typename Fill>
py::array records_array(const py::dtype& dtype, const std::vector<Record>& records, Fill fill) {
  py::array out(dtype, std::vector<py::ssize_t>{static_cast<py::ssize_t>(records.size())});
  auto* base = static_cast<char*>(out.mutable_data());
  const std::size_t size = static_cast<std::size_t>(dtype.itemsize());
  for (std::size_t i = 0; i < records.size(); ++i) fill(base + i * size, records[i]);
  return out;
}

template <typename T>
void put(char* at, std::size_t offset, T value) {
  std::memcpy(at + offset, &value, sizeof(T));
}

py::object py_run(const std::string& sensor, const py::object& scene, const py::object& duration, const py::object& set,
               bool truth, const py::object& max_events) {
  // A path is read as the program reads it. A 2-D array is the scene's one frame, as it is; a 3-D
  // array (frames, rows, columns) a moving scene shown at scene.frame_rate, as a 3-D .npy file is.
  RunSpec spec;
  spec.sensor = sensor;
  if (!scene.is_none() && is_path(scene)) {
    spec.scene = as_path(scene);
  } else if (!scene.is_none()) {
    spec.frames = frames_from_array(scene, "scene");
  }
  const std::string duration_text = duration.is_none() ? "" : std::string(py::str(duration));
  const std::string max_text = max_events.is_none() ? "" : std::string(py::str(max_events));
  spec.settings = command_settings(settings_text(set), duration_text, max_text);
  EventCollector collected;
  spec.stream = &collected;
  spec.keep_truth = truth;
  const RunReport report = without_gil([&] { return run_sensor(spec); });
  const double tick = report.tick;
  const nlohmann::json& summary = report.summary;
  if (!report.warnings.empty()) {
    const py::object warn = py::module_::import("warnings").attr("warn");
    for (const std::string& w : report.warnings) warn(w, py::module_::import("builtins").attr("RuntimeWarning"), 2);
  }

  // t is the receiver's stamp (whole ticks), as in the event files.
  const py::dtype event_type = packed_dtype({{"t", "<f8"}, {"x", "<u2"}, {"y", "<u2"}, {"tile", "<u4"}, {"flags", "u1"}});
  py::array events = records_array(event_type, collected.events(), [tick](char* at, const AddressEvent& e) {
    put(at, 0, static_cast<double>(timestamp_ticks(e.t, tick)) * tick);
    put(at, 8, static_cast<std::uint16_t>(e.x));
    put(at, 10, static_cast<std::uint16_t>(e.y));
    put(at, 12, e.tile);
    put(at, 16, e.flags);
  });
  py::object truth_array = py::none();
  if (truth) {
    const py::dtype truth_type = packed_dtype({{"t_fire", "<f8"}, {"x", "<u2"}, {"y", "<u2"}, {"tile", "<u4"},
                                               {"fate", "U9"}, {"t_deliver", "<f8"}});
    py::array a(truth_type, std::vector<py::ssize_t>{static_cast<py::ssize_t>(collected.truth().size())});
    auto* base = static_cast<char*>(a.mutable_data());
    for (std::size_t i = 0; i < collected.truth().size(); ++i) {
      const TruthRecord& r = collected.truth()[i];
      char* at = base + i * static_cast<std::size_t>(truth_type.itemsize());
      put(at, 0, r.firing.t);
      put(at, 8, static_cast<std::uint16_t>(r.firing.x));
      put(at, 10, static_cast<std::uint16_t>(r.firing.y));
      put(at, 12, r.firing.tile);
      // NumPy's U9: nine UCS-4 code points, zero-padded.
      const char* fate = to_string(r.fate);
      for (std::size_t c = 0; c < 9; ++c) put<std::uint32_t>(at, 16 + 4 * c, c < std::strlen(fate) ? static_cast<std::uint32_t>(fate[c]) : 0u);
      put(at, 52, r.fate == Fate::Delivered ? r.t_deliver : std::nan(""));
    }
    truth_array = a;
  }
  py::object ns = py::module_::import("types").attr("SimpleNamespace")();
  ns.attr("events") = events;
  ns.attr("summary") = json_to_python(summary);
  ns.attr("truth") = truth_array;
  return ns;
}

py::array py_emulate(const py::object& input, double f_max, const std::string& behaviour, const std::string& spread,
                         double threshold, const std::string& clip, const py::object& size, double frame_rate,
                         double chaos_in, double chaos_out, std::uint64_t seed, double max_events) {
  EmulateOptions opt;
  opt.f_max = f_max;
  opt.behaviour = behaviour;
  opt.spread = spread;
  opt.threshold = threshold;
  opt.clip = clip;
  opt.size = size.is_none() ? "" : std::string(py::str(size));
  opt.frame_rate = frame_rate;
  opt.chaos_in = chaos_in;
  opt.chaos_out = chaos_out;
  opt.seed = seed;
  opt.max_events = max_events;
  std::vector<Image> frames;
  if (is_path(input)) {
    opt.input = as_path(input);
  } else {
    // Grey levels as the emulator's own files hold them: 8-bit codes or fractions of full scale.
    frames = frames_from_array(input, "input");
  }
  const EmulatedRun result = without_gil([&] { return emulate_frames(opt, std::move(frames)); });
  const py::dtype type = packed_dtype({{"t", "<f8"}, {"x", "<u2"}, {"y", "<u2"}, {"frame", "<u4"}});
  return records_array(type, result.events, [](char* at, const EmulatedEvent& e) {
    put(at, 0, e.t);
    put(at, 8, static_cast<std::uint16_t>(e.x));
    put(at, 10, static_cast<std::uint16_t>(e.y));
    put(at, 12, e.frame);
  });
}

py::object py_classify(const py::object& events, const py::object& templates, double k, std::uint64_t max_events,
                    double overflow, std::uint64_t center, bool center_templates, bool ranks, const py::object& size,
                    double cycles_per_template, const std::string& clock) {
  ClassifyOptions opt;
  opt.templates = templates.is_none() ? "" : as_path(templates);
  opt.classifier.k = k;
  opt.classifier.max_events = max_events;
  opt.classifier.overflow = overflow;
  opt.classifier.center_events = center;
  opt.classifier.center_templates = center_templates;
  opt.no_ranks = !ranks;
  opt.size = size.is_none() ? "" : std::string(py::str(size));
  opt.cycles_per_template = cycles_per_template;
  opt.clock = clock;
  if (is_path(events)) {
    opt.events = as_path(events);
    return json_to_python(without_gil([&] { return classify_recording(opt); }));
  }
  // A structured array with x and y (and flags, when it has them), in time order.
  py::array a = py::array::ensure(events);
  if (!a || a.ndim() != 1 || !a.dtype().attr("names").cast<py::object>() ||
      !a.dtype().attr("fields").contains("x") || !a.dtype().attr("fields").contains("y")) {
    throw InputError("events: expected a path or a structured array with fields x and y");
  }
  if (opt.size.empty()) throw InputError("events: an array records no array size: give size='WIDTHxHEIGHT'");
  const ArraySize array = parse_array_size(opt.size, "size");
  py::array_t<long long, py::array::forcecast> xs(a[py::str("x")]), ys(a[py::str("y")]);
  const bool has_flags = a.dtype().attr("fields").contains("flags");
  py::array_t<long long, py::array::forcecast> flags = has_flags ? py::array_t<long long, py::array::forcecast>(a[py::str("flags")])
                                                                 : py::array_t<long long, py::array::forcecast>(0);
  EventRecording rec;
  rec.width = array.width;
  rec.height = array.height;
  rec.tiles = 1;
  rec.size_recorded = true;
  for (py::ssize_t i = 0; i < xs.size(); ++i) {
    if (xs.data()[i] < 0 || ys.data()[i] < 0 || xs.data()[i] >= array.width || ys.data()[i] >= array.height) {
      throw InputError(fmt::format("events: event {} at ({}, {}) lies outside size {}x{}", i, xs.data()[i], ys.data()[i],
                                   array.width, array.height));
    }
    AddressEvent e;
    e.x = static_cast<std::uint32_t>(xs.data()[i]);
    e.y = static_cast<std::uint32_t>(ys.data()[i]);
    e.flags = has_flags && flags.data()[i] ? kGhostEvent : kNormalEvent;
    rec.events.push_back(e);
  }
  opt.events = "events";
  return json_to_python(without_gil([&] { return classify_recording(opt, &rec); }));
}

py::object py_sweep(const py::object& spec, const py::object& output, int jobs) {
  CallFolder folder;
  SweepOptions opt;
  opt.spec = as_path(spec);
  opt.output = output.is_none() ? folder.file("sweep.csv") : as_path(output);
  opt.jobs = jobs;
  opt.no_chart = true;
  const int status = without_gil([&] {
    Cooperative cooperate;
    return sweep_command(opt);
  });
  if (status != 0) throw InputError(fmt::format("sweep '{}' failed (status {})", opt.spec, status));
  // The sweep's CSV as a list of dicts, numbers as floats.
  py::object csv = py::module_::import("csv");
  py::object builtins = py::module_::import("builtins");
  py::list rows;
  py::object file = builtins.attr("open")(opt.output, "r", py::arg("newline") = "");
  for (const py::handle row : csv.attr("DictReader")(file)) {
    py::dict out;
    for (const auto& [key, value] : row.cast<py::dict>()) {
      try {
        out[key] = builtins.attr("float")(value);
      } catch (const py::error_already_set&) {
        out[key] = value;
      }
    }
    rows.append(out);
  }
  file.attr("close")();
  return rows;
}

}  // namespace
}  // namespace aesim

// libsystemc refers to the program's sc_main (its own main() calls it); in a module loaded into
// Python nothing calls it, but the symbol must be there.
extern "C" __attribute__((visibility("default"))) int sc_main(int, char*[]) { return 0; }

PYBIND11_MODULE(aesim, m) {
  using namespace aesim;
  setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "1", 0);
  m.doc() = "aesim: the address-event imager simulator (docs/reference.md section 8). Same library as the aesim program.";
  m.attr("__version__") = kVersion;
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const OutputError& e) {
      PyErr_SetString(PyExc_OSError, e.what());
    } catch (const Interrupted&) {
      PyErr_SetNone(PyExc_KeyboardInterrupt);
    }
  });
  m.def("run", &py_run, py::arg("sensor") = "aloha", py::arg("scene") = py::none(), py::arg("duration") = py::none(),
        py::arg("set") = py::none(), py::arg("truth") = false, py::arg("max_events") = py::none(),
        "Simulate the imager as `aesim run` does. scene: a path (image, frame folder) or a 2-D array of linear "
        "light (8/16-bit codes over full scale, or floats as fractions of it), or a 3-D one (frames, rows, columns) "
        "shown at scene.frame_rate. Returns an object with `events` "
        "(structured array: t s, x, y, tile, flags), `summary` (dict) and `truth` (structured array, or None).");
  m.def("emulate", &py_emulate, py::arg("input"), py::arg("f_max") = 20.0, py::arg("behaviour") = "intensity",
        py::arg("spread") = "even", py::arg("threshold") = 0.0, py::arg("clip") = "0,255", py::arg("size") = py::none(),
        py::arg("frame_rate") = 0.0, py::arg("chaos_in") = 0.0, py::arg("chaos_out") = 0.0, py::arg("seed") = 1,
        py::arg("max_events") = 1e8,
        "The paper's emulator as `aesim emulate` runs it, on a path or an array (2-D: one frame; 3-D: frames). "
        "Returns a structured array (t s, x, y, frame).");
  m.def("classify", &py_classify, py::arg("events"), py::arg("templates") = py::none(), py::arg("k") = 20.0,
        py::arg("max_events") = 1000, py::arg("overflow") = 65535.0, py::arg("center") = 0,
        py::arg("center_templates") = false, py::arg("ranks") = true, py::arg("size") = py::none(),
        py::arg("cycles_per_template") = 100.0, py::arg("clock") = "57.6MHz",
        "The paper's recogniser as `aesim classify --json` runs it, on an event file or a structured array with x "
        "and y (give size='WxH'). Returns the JSON as a dict.");
  m.def("sweep", &py_sweep, py::arg("spec"), py::arg("output") = py::none(), py::arg("jobs") = 1,
        "A sweep spec (TOML) run as `aesim sweep` runs it; returns its rows as dicts (numbers as floats).");
}
