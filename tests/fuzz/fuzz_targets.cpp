#include "fuzz/fuzz_targets.hpp"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "aesim/errors/input_error.hpp"
#include "aesim/config/sensor_config.hpp"
#include "aesim/scene/scene.hpp"
#include "aesim/scene/y4m_video.hpp"
#include "aesim/event_files/dsec_h5.hpp"
#include "aesim/event_files/ecf_codec.hpp"
#include "aesim/event_files/event_file.hpp"
#include "aesim/scene/netpbm.hpp"
#include "aesim/scene/exr_image.hpp"
#include "aesim/scene/npy_scene.hpp"
#include "aesim/scene/photo_image.hpp"
#include "aesim/scene/tiff_image.hpp"
#include "deck/pixel_deck.hpp"
#include "description/receiver_description.hpp"
#include "plan/verification_plan.hpp"
#include "aesim/spec/sweep_spec.hpp"

namespace aesim::fuzz {
namespace {

std::string bytes(const std::uint8_t* data, std::size_t size) { return {reinterpret_cast<const char*>(data), size}; }

// Runs `parse`; an InputError is the expected answer to bad bytes, so it is swallowed.
template <class F>
int expect_result_or_input_error(F parse) {
  try {
    parse();
  } catch (const InputError&) {
  }
  return 0;
}

}  // namespace

int netpbm(const std::uint8_t* data, std::size_t size) {
  const std::string in = bytes(data, size);
  expect_result_or_input_error([&] { decode_pnm(in, "fuzz.pgm"); });
  return expect_result_or_input_error([&] { decode_pfm(in, "fuzz.pfm"); });
}

int photo(const std::uint8_t* data, std::size_t size) {
  const std::string in = bytes(data, size);
  expect_result_or_input_error([&] { decode_png(in, "fuzz.png"); });
  expect_result_or_input_error([&] { decode_tiff(in, "fuzz.tif"); });
  // A multi-page TIFF's pages, as a scene takes them (a few: each is a whole decode).
  expect_result_or_input_error([&] {
    const std::vector<std::size_t> pages = tiff_pages(in, "fuzz.tif");
    for (std::size_t k = 0; k < pages.size() && k < 4; ++k) decode_tiff(in, "fuzz.tif", pages[k]);
  });
  return expect_result_or_input_error([&] { decode_jpeg(in, "fuzz.jpg"); });
}

int exr(const std::uint8_t* data, std::size_t size) {
  return expect_result_or_input_error([&] { decode_exr(bytes(data, size), "fuzz.exr"); });
}

int y4m(const std::uint8_t* data, std::size_t size) {
  // As the emulator reads it (codes), and as a scene (light).
  expect_result_or_input_error([&] { decode_y4m(bytes(data, size), "fuzz.y4m"); });
  return expect_result_or_input_error([&] {
    const std::string video = bytes(data, size);
    const Y4mLayout layout = parse_y4m(video, "fuzz.y4m");
    for (std::size_t k = 0; k < layout.luma.size(); ++k) y4m_light(video, layout, k);
  });
}

int prophesee_raw(const std::uint8_t* data, std::size_t size) {
  return expect_result_or_input_error([&] { decode_events(bytes(data, size), "fuzz.raw", EventFileFormat::PropheseeRaw); });
}

// The first byte chooses the reader, by its remainder over 6: `t x y p` text (0), N-MNIST's .bin
// (1), a ROS 1 bag (2), an MCAP file (3), a ROS 2 SQLite bag (4) or a NumPy archive (5).
int dataset_files(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  constexpr EventFileFormat kByRemainder[] = {EventFileFormat::EventsText, EventFileFormat::NmnistBin, EventFileFormat::RosBag,
                                              EventFileFormat::Mcap,       EventFileFormat::Rosbag2Sqlite, EventFileFormat::Npz};
  const EventFileFormat format = kByRemainder[data[0] % 6];
  return expect_result_or_input_error([&] { decode_events(bytes(data + 1, size - 1), "fuzz.dataset", format); });
}

// One ECF block, as HDF5 hands the decoder a chunk (outside HDF5, so that every input reaches it):
// the events or the decoder's refusal.
int ecf(const std::uint8_t* data, std::size_t size) {
  // Made once: zeroing a megabyte each run was most of a run's time.
  static std::vector<unsigned char> out(kEcfMostEvents * kEcfEventBytes);
  try {
    decode_ecf_block(data, size, out.data());
  } catch (const EcfError&) {
  }
  return 0;
}

int aedat(const std::uint8_t* data, std::size_t size) {
  return expect_result_or_input_error([&] { decode_events(bytes(data, size), "fuzz.aedat", EventFileFormat::Aedat2); });
}

int events_csv(const std::uint8_t* data, std::size_t size) {
  return expect_result_or_input_error([&] { decode_events(bytes(data, size), "fuzz.csv", EventFileFormat::Csv); });
}

int aedat4(const std::uint8_t* data, std::size_t size) {
  return expect_result_or_input_error([&] { decode_events(bytes(data, size), "fuzz.aedat4", EventFileFormat::Aedat4); });
}

// The same header reader serves event files and scenes.
int npy(const std::uint8_t* data, std::size_t size) {
  const std::string in = bytes(data, size);
  expect_result_or_input_error([&] { decode_events(in, "fuzz.npy", EventFileFormat::Npy); });
  return expect_result_or_input_error([&] {
    const NpySceneFile scene{in, parse_npy_scene(in, "fuzz.npy")};
    for (std::size_t k = 0; k < scene.layout.frames && k < 4; ++k) npy_scene_frame(scene, k, "fuzz.npy");
  });
}

// A reader through a library that reads files, not memory (libhdf5, matio): the bytes go to a file
// of this process's own (in memory on Linux), named with `extension`, and `read` reads it under the
// fuzzer's limits.
template <typename Read>
int through_file(const std::uint8_t* data, std::size_t size, const char* extension, Read read) {
  const std::string path = fmt::format("/dev/shm/aesim-fuzz-{}{}", ::getpid(), extension);
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  const int r = expect_result_or_input_error([&] { read(path); });
  std::remove(path.c_str());
  return r;
}

int h5(const std::uint8_t* data, std::size_t size) {
  return through_file(data, size, ".h5", [](const std::string& path) { read_dsec_h5(path); });
}

int mat(const std::uint8_t* data, std::size_t size) {
  return through_file(data, size, ".mat", [](const std::string& path) { load_events(path); });
}

int set_values(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> lines;
  std::istringstream in(bytes(data, size));
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return expect_result_or_input_error([&] {
    std::vector<Setting> settings;
    for (const std::string& line : lines) settings.push_back(parse_setting(line));
    configure_run(SensorConfig{}, SceneFiles{}, settings).to_json();
  });
}

int sensor_toml(const std::uint8_t* data, std::size_t size) {
  // The first byte chooses the form: a sensor preset ([section] tables) or a folder's scene.toml.
  const std::string section = size > 0 && (data[0] & 1) ? "scene" : "";
  const std::string text = size > 0 ? bytes(data + 1, size - 1) : std::string();
  return expect_result_or_input_error([&] {
    SensorConfig config;
    apply_toml_text(config, text, "fuzz.toml", section);
    config.validate();
  });
}

namespace {

// A folder of the fuzzing process for inputs read from files (they name files relative to
// themselves), with one Verilog source for descriptions to name.
const std::filesystem::path& scratch() {
  struct Folder {
    std::filesystem::path path = std::filesystem::temp_directory_path() / ("aesim_fuzz_" + std::to_string(::getpid()));
    Folder() {
      std::filesystem::create_directories(path);
      std::ofstream(path / "rx.v") << "module rx; endmodule\n";
    }
    ~Folder() {
      std::error_code ignored;
      std::filesystem::remove_all(path, ignored);
    }
  };
  static const Folder dir;
  return dir.path;
}

std::string write_scratch(const std::string& name, const std::uint8_t* data, std::size_t size) {
  const std::string path = (scratch() / name).string();
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes(data, size);
  return path;
}

}  // namespace

int sweep_spec(const std::uint8_t* data, std::size_t size) {
  const std::string path = write_scratch("spec.toml", data, size);
  return expect_result_or_input_error([&] { load_sweep_spec(path); });
}

int receiver_toml(const std::uint8_t* data, std::size_t size) {
  // The first byte chooses the form: a receiver description or a verification plan (its cases
  // are made too: scene runs load their scenes and size their work, nothing is simulated).
  const bool plan = size > 0 && (data[0] & 1);
  const std::string path = write_scratch("receiver.toml", size > 0 ? data + 1 : data, size > 0 ? size - 1 : 0);
  return expect_result_or_input_error([&] {
    if (!plan) {
      read_receiver_description(path);
      return;
    }
    ReceiverDescription d;
    d.clock_hz = 50e6;
    d.timestamp_tick = 1e-6;
    d.timestamp_bits = 32;
    d.ack_latency_min = d.ack_latency_max = 4;
    const VerificationPlan p = make_plan(path);
    if (p.scenes.size() <= 4) plan_cycles(plan_cases(p, d, 1));
  });
}

int pixel_deck(const std::uint8_t* data, std::size_t size) {
  // The deck is read as `aesim calibrate` reads it before ngspice sees it: the subcircuit, its
  // ports and parameters, the probe node, the includes (relative to the scratch folder).
  const std::string path = write_scratch("deck.cir", data, size);
  return expect_result_or_input_error([&] { read_pixel_deck(path, "pixel", "int"); });
}

}  // namespace aesim::fuzz
