#include "aesim/event_files/evimo2_folder.hpp"

#include <filesystem>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/event_files/npy_columns.hpp"
#include "aesim/files/input_file.hpp"
#include "aesim/limits/limits.hpp"

namespace aesim {

namespace fs = std::filesystem;

bool is_evimo2_folder(const std::string& path) {
  std::error_code ec;
  return fs::is_regular_file(fs::path(path) / "dataset_events_t.npy", ec);
}

PolarityRecording read_evimo2_folder(const std::string& path) {
  const auto file = [&](const char* name) {
    const std::string at = (fs::path(path) / name).string();
    if (!fs::is_regular_file(at)) {
      throw InputError(fmt::format("event file '{}': an EVIMO2 sequence's folder (it holds dataset_events_t.npy) without {}", path, name));
    }
    return std::pair{read_input_file(at, "event file", kMaxEventFileBytes), fmt::format("event file '{}' ({})", path, name)};
  };
  NpyNumbers ts, xs, ys, ps;
  {
    const auto [bytes, what] = file("dataset_events_t.npy");
    ts = read_npy_numbers(bytes, what);
  }
  {
    const auto [bytes, what] = file("dataset_events_xy.npy");
    xs = read_npy_numbers(bytes, what, 0, 2);
    ys = read_npy_numbers(bytes, what, 1, 2);
  }
  {
    const auto [bytes, what] = file("dataset_events_p.npy");
    ps = read_npy_numbers(bytes, what);
  }
  PolarityRecording rec = events_from_columns(xs, ys, ts, ps, true,
                                              {"dataset_events_xy[:, 0]", "dataset_events_xy[:, 1]", "dataset_events_t",
                                               "dataset_events_p"},
                                              path);
  rec.read_as.push_back("an EVIMO2 sequence's folder: dataset_events_t (seconds), dataset_events_xy, dataset_events_p (ON "
                        "where the polarity is above 0; EVIMO2's Samsung camera's polarity is the other way round)");
  put_in_time_order(rec);
  return rec;
}

}  // namespace aesim
