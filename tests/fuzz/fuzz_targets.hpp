#pragma once
#include <cstddef>
#include <cstdint>

// Every parser of user input as a fuzz target: the bytes go in, and the only acceptable outcomes
// are a result or an InputError. Anything else (a crash, a sanitizer report, another exception,
// a hang) is a defect. tests/fuzz/libfuzzer_entry.cpp makes each a libFuzzer binary;
// tests/fuzz_replay_test.cpp replays every corpus and regression input in the ordinary suite.
namespace aesim::fuzz {

int netpbm(const std::uint8_t* data, std::size_t size);        // PGM and PFM scenes
int photo(const std::uint8_t* data, std::size_t size);         // PNG, JPEG and TIFF scenes
int exr(const std::uint8_t* data, std::size_t size);           // OpenEXR scenes
int y4m(const std::uint8_t* data, std::size_t size);           // Y4M video (aesim emulate, and scenes)
int aedat(const std::uint8_t* data, std::size_t size);         // AEDAT 2.0 event files
int events_csv(const std::uint8_t* data, std::size_t size);    // event CSV files
int aedat4(const std::uint8_t* data, std::size_t size);        // AEDAT 4.0 event files (FlatBuffers, LZ4)
int npy(const std::uint8_t* data, std::size_t size);           // NumPy .npy event files
int prophesee_raw(const std::uint8_t* data, std::size_t size); // Prophesee RAW recordings (EVT 2.0, 2.1, 3.0)
int dataset_files(const std::uint8_t* data, std::size_t size); // text, N-MNIST .bin, ROS 1 and 2 bags, .npz
int h5(const std::uint8_t* data, std::size_t size);            // DSEC HDF5 event files (through libhdf5)
int ecf(const std::uint8_t* data, std::size_t size);           // Metavision HDF5 chunks: aesim's ECF decoder
int mat(const std::uint8_t* data, std::size_t size);           // MATLAB files of events (through matio)
int set_values(const std::uint8_t* data, std::size_t size);    // --set key=value lines with units
int sensor_toml(const std::uint8_t* data, std::size_t size);   // sensor presets and scene.toml
int sweep_spec(const std::uint8_t* data, std::size_t size);    // sweep specs
int receiver_toml(const std::uint8_t* data, std::size_t size);  // aesim verify's descriptions and plans
int pixel_deck(const std::uint8_t* data, std::size_t size);    // aesim calibrate's SPICE decks

struct Target {
  const char* name;
  int (*run)(const std::uint8_t*, std::size_t);
};
inline constexpr Target kTargets[] = {{"netpbm", netpbm},         {"y4m", y4m},
                                      {"aedat", aedat},           {"events_csv", events_csv},
                                      {"set_values", set_values}, {"sensor_toml", sensor_toml},
                                      {"sweep_spec", sweep_spec}, {"receiver_toml", receiver_toml},
                                      {"pixel_deck", pixel_deck}, {"photo", photo},
                                      {"aedat4", aedat4},         {"npy", npy},
                                      {"exr", exr},               {"h5", h5},
                                      {"prophesee_raw", prophesee_raw}, {"dataset_files", dataset_files},
                                      {"mat", mat},               {"ecf", ecf}};

}  // namespace aesim::fuzz
