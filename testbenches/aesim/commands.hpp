#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "aesim/bandwidth/image_bandwidth.hpp"
#include "aesim/classify/template_classifier.hpp"
#include "aesim/emulator/emulator.hpp"
#include "aesim/event_files/event_file.hpp"

#include <nlohmann/json.hpp>

namespace aesim {

// Each command's options as the command line fills them (command_line.cpp, the one file that
// knows CLI11), and the command itself, which returns the exit status.

struct ClassifyOptions {
  // The time estimate's defaults are the paper's: 100 cycles per template on a 57.6 MHz processor.
  std::string events, templates, clock = "57.6MHz", size, layout;
  ClassifierOptions classifier;
  bool no_ranks = false, json = false;
  double cycles_per_template = 100;
};

// The recogniser's decision as `aesim classify --json` prints it, on the events given or else
// the file the options name (the command and the Python module share it). Throws InputError.
nlohmann::json classify_recording(ClassifyOptions opt, const EventRecording* given = nullptr);

struct CompareOptions {
  std::string sensor = "aloha";
  std::vector<std::string> scenes;
  std::string duration = "500ms";
  std::vector<std::string> sets;
  std::vector<std::string> steps = {"1us", "10us", "100us", "1ms"};
  std::string output = "out/fidelity_ladder.csv";
  std::string max_events;
};

struct EmulateOptions {
  std::string input, behaviour = "intensity", size, clip = "0,255", queue, out, recon, spread = "even";
  std::string aedat4_compression = "lz4";
  std::string raw_encoding = "evt2";
  double threshold = 0, f_max = 20, frame_rate = 0, chaos_in = 0, chaos_out = 0, max_events = 1e8;
  long long events = 0;
  std::uint64_t seed = 1;
};

// What the emulator made of its input: the settings the options resolve to, the frames, the events.
struct EmulatedRun {
  EmulatorSettings settings;
  std::vector<Image> frames;
  std::vector<EmulatedEvent> events;
};
// Checks the options and emulates the frames given, or else the input the options name (the
// command and the Python module share it). Throws InputError.
EmulatedRun emulate_frames(const EmulateOptions& opt, std::vector<Image> given = {});

struct ReconOptions {
  std::string events, output, window, mode = "histogram", size, layout;
  long long count = -1;
};

struct BandwidthOptions {
  int width = 128, height = 96, bits = 8;
  long long events = 400;
  int frame_overhead = 12;
  RadioModel radio;
};

struct RunOptions {
  std::string sensor = "aloha";
  std::string scene;
  std::string duration;
  std::vector<std::string> sets;
  std::string out, csv, recon, vcd, summary, truth;
  std::string vcd_from = "0s", vcd_to;
  std::string max_events;
  std::string aedat_layout = "aesim";
  std::string aedat4_compression = "lz4";
  std::string raw_encoding = "evt2";
};

struct SweepOptions {
  std::string spec, output;
  int jobs = -1;
  bool no_chart = false;
};

struct VerifyCommandOptions {
  std::string description, plan = "quick", out = "out/verify", export_tb;
  std::uint64_t seed = 1;
  bool allow_system_tasks = false;
  bool formal = false;
  int formal_seconds = 20;  // each property's proof or bounded check
};

struct CalibrateOptions {
  std::string deck, subckt, output, base = "aloha", vdd = "3.3V", currents = "1fA:1nA", chart, probe = "int";
  std::vector<std::string> osdi;
  std::vector<std::string> biases;  // NAME=VOLTS, each a port beyond vdd out gnd
  std::string ngbehavior;           // ngspice's compatibility mode; empty: a .spiceinit's beside the deck
  int points = 13, mc = 0, firings = 8, jobs = 0;
};

int run_command(RunOptions opt);
int calibrate_command(const CalibrateOptions& opt);
int verify_command(const VerifyCommandOptions& opt);
int recon_command(const ReconOptions& opt);
int info_command(const std::string& path, const std::string& layout = "");
int sweep_command(SweepOptions opt);
int compare_command(CompareOptions opt);
int emulate_command(EmulateOptions opt);
int classify_command(ClassifyOptions opt);
int bandwidth_command(const BandwidthOptions& opt);
// `aesim config keys`: every configuration key with its unit, its value in `sensor` and its
// meaning; as a Markdown table with `markdown` (docs/configuration_keys.md is that table).
int config_keys_command(const std::string& sensor, bool markdown);

// Parses the command line and runs the command it names; CLI11's own errors (and --help) end
// here with their status, aesim's exceptions pass through to main().
int run_command_line(int argc, char** argv);

}  // namespace aesim
