// The command line: every command's options, in the one translation unit that includes CLI11
// (a header-only library that costs seconds of compile time in every file that uses it).
#include <CLI/CLI.hpp>

#include <fmt/format.h>

#include "commands.hpp"
#include "report_stream.hpp"
#include "aesim/scene/netpbm.hpp"
#include "aesim/errors/input_error.hpp"
#include "aesim/event_files/event_formats.hpp"
#include "aesim/text/nearest_name.hpp"
#include "aesim/version.hpp"

namespace aesim {
namespace {

// A file output named '-' is the standard output, as Unix tools take it (the same as /dev/stdout:
// written through, the report moved to stderr, the format that of a name without an extension).
CLI::Option* file_output(CLI::App* cmd, const std::string& name, std::string& path, const std::string& help) {
  return cmd->add_option(name, path, help + " ('-': standard output)")
      ->transform([](std::string value) { return value == "-" ? std::string("/dev/stdout") : value; });
}

void add_run(CLI::App& app, int& status) {
  auto opt = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand(
      "run", "Simulate a sensor looking at a scene; with no options, the aloha sensor on scenes/letters/A.pgm "
             "with all outputs under out/");
  cmd->add_option("--sensor", opt->sensor, "Sensor preset name (models/sensors/NAME.toml) or a .toml file")
      ->capture_default_str();
  cmd->add_option("--scene", opt->scene, "Scene: a " + scene_image_formats() + " image, a .y4m video, or a folder of numbered frames");
  cmd->add_option("--duration", opt->duration, "Simulated time, e.g. 2s or 500ms (same as --set sim.duration=)");
  cmd->add_option("--set", opt->sets, "Override a parameter: section.key=value with SI units, e.g. pixel.c_int=50fF")
      ->allow_extra_args(false);
  file_output(cmd, "-o,--out", opt->out, "Event file, its type by extension (none: AEDAT 2.0): " + event_formats_help());
  cmd->add_option("--aedat-layout", opt->aedat_layout,
                  "Address words of an AEDAT 2.0 --out: aesim (default), dvs128 or davis (jAER's layouts, y = 0 at the "
                  "bottom, polarity ON for a normal event and OFF for a ghost)");
  cmd->add_option("--aedat4-compression", opt->aedat4_compression, "Packets of an .aedat4 --out: lz4, zstd or none")
      ->capture_default_str();
  cmd->add_option("--raw-encoding", opt->raw_encoding, "Words of a Prophesee .raw --out: evt2 or evt3")
      ->capture_default_str();
  file_output(cmd, "--csv", opt->csv, "Events as CSV (t_us,x,y,tile,flags)");
  cmd->add_option("--recon", opt->recon, "Histogram reconstruction image (.png or .pgm)");
  file_output(cmd, "--vcd", opt->vcd, "Bus wires of every tile as a VCD file (needs sim.fidelity=cycle or auto)");
  cmd->add_option("--vcd-from", opt->vcd_from, "Start of the VCD window, e.g. 100ms")->capture_default_str();
  cmd->add_option("--vcd-to", opt->vcd_to, "End of the VCD window (default: end of the run)");
  file_output(cmd, "--truth", opt->truth, "Ground truth CSV: every fired event, its fate, delivery time and latency");
  file_output(cmd, "--summary", opt->summary, "Summary JSON");
  cmd->add_option("--max-events", opt->max_events,
                  "The most work the run may ask for, in fired events (default 1e8; same as --set sim.max_events=)");
  cmd->callback([opt, &status] { status = run_command(*opt); });
}

void add_recon(CLI::App& app, int& status) {
  auto opt = std::make_shared<ReconOptions>();
  CLI::App* cmd = app.add_subcommand("recon", "Reconstruct an image from an event file (" + event_inputs() + ")");
  cmd->add_option("EVENTS", opt->events, "Event file")->required();
  auto* window = cmd->add_option("--window", opt->window, "Use the events within this time of the first, e.g. 100ms");
  cmd->add_option("--events", opt->count, "Use the first N events")->excludes(window);
  cmd->add_option("--mode", opt->mode, "histogram (events per pixel) or interval (1 / time between a pixel's last two events)")
      ->capture_default_str();
  cmd->add_option("-o,--output", opt->output, "Output image (.png or .pgm)")->required();
  cmd->add_option("--size", opt->size, "The array's WIDTHxHEIGHT (an AEDAT header records it; aesim's CSV does not)");
  cmd->add_option("--layout", opt->layout, "The chip of a jAER AEDAT 2.0 recording with no # AEChip line: dvs128, davis240c or davis346");
  cmd->callback([opt, &status] { status = recon_command(*opt); });
}

void add_info(CLI::App& app, int& status) {
  auto path = std::make_shared<std::string>();
  auto layout = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("info", "Counts, time span, rate and per-tile breakdown of an event file");
  cmd->add_option("EVENTS", *path, "Event file (" + event_inputs() + ")")->required();
  cmd->add_option("--layout", *layout, "The chip of a jAER AEDAT 2.0 recording with no # AEChip line: dvs128, davis240c or davis346");
  cmd->callback([path, layout, &status] { status = info_command(*path, *layout); });
}

void add_sweep(CLI::App& app, int& status) {
  auto opt = std::make_shared<SweepOptions>();
  CLI::App* cmd = app.add_subcommand(
      "sweep", "Run a sweep of design points (a TOML spec) in parallel processes, or across hosts under mpirun, and "
               "write one CSV (and a sizing report when the spec has [constraints]); an interrupted sweep resumes");
  cmd->add_option("SPEC", opt->spec, "Sweep spec, e.g. scripts/sweeps/collisions.toml")->required();
  cmd->add_option("-o,--output", opt->output, "CSV file (default out/SPEC_NAME.csv)");
  cmd->add_option("-j,--jobs", opt->jobs, "Parallel processes (default: the spec's jobs; 0 = all cores)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--no-chart", opt->no_chart, "Do not draw the spec's chart");
  cmd->callback([opt, &status] { status = sweep_command(*opt); });
}

void add_verify(CLI::App& app, int& status) {
  auto opt = std::make_shared<VerifyCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "verify", "Verify a receiver RTL against its description (a TOML file): Verilated at run time (VHDL synthesised to Verilog by GHDL first; cached), driven "
                "by directed protocol cases and scene runs, checked transaction by transaction");
  cmd->add_option("RECEIVER", opt->description, "Receiver description, e.g. rtl/aer_receiver.toml")->required();
  cmd->add_option("--plan", opt->plan, "quick (seconds), full (millions of transactions) or a plan file")
      ->capture_default_str();
  cmd->add_option("--seed", opt->seed, "Seed of the scene runs' pixels, back-pressure and output clock (where the output has one of its own)")->capture_default_str();
  cmd->add_option("--out", opt->out, "Folder for verify.json (and failure.vcd)")->capture_default_str();
  cmd->add_option("--export-tb", opt->export_tb, "Folder for a self-checking Verilog testbench of a scene run");
  cmd->add_flag("--formal", opt->formal,
                "Also prove the description's properties with yosys and ABC (an unbounded proof, else a bounded check)");
  cmd->add_option("--formal-seconds", opt->formal_seconds,
                  "Time each property's proof, then its bounded check, may take before it is stopped")
      ->check(CLI::Range(1, 3600))
      ->capture_default_str();
  cmd->add_flag("--allow-system-tasks", opt->allow_system_tasks,
                "Let the RTL call $system (it runs shell commands on this machine); refused otherwise");
  cmd->callback([opt, &status] { status = verify_command(*opt); });
}

void add_calibrate(CLI::App& app, int& status) {
  auto opt = std::make_shared<CalibrateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "calibrate", "Fit the pixel model to a pixel circuit: ngspice runs the deck over a range of photocurrents; "
                   "writes a preset with the fitted c_int, t_reset, i_dark, the measured period table and the energy");
  cmd->add_option("DECK", opt->deck, "SPICE deck defining .subckt NAME vdd out gnd params: iph=1p")->required();
  cmd->add_option("--subckt", opt->subckt, "The pixel's subcircuit in the deck (default: the deck's one with three ports and iph)");
  cmd->add_option("-o,--output", opt->output, "Preset to write (.toml)")->required();
  cmd->add_option("--base", opt->base, "Preset whose other keys the calibrated one keeps")->capture_default_str();
  cmd->add_option("--vdd", opt->vdd, "Supply voltage; a firing is out rising through vdd/2")->capture_default_str();
  cmd->add_option("--currents", opt->currents, "Photocurrent range LOW:HIGH, points spaced logarithmically")
      ->capture_default_str();
  cmd->add_option("--points", opt->points, "Photocurrents in the range (more are added where log-log interpolation "
                                          "between them would miss by over 0.2 %)")->capture_default_str();
  cmd->add_option("--mc", opt->mc, "Monte Carlo runs (ngspice seeds 1..N) at the range's geometric middle: "
                                   "pixel.mismatch from the spread of periods")->capture_default_str();
  cmd->add_option("--chart", opt->chart, "Period against photocurrent: ngspice, calibrated model, ideal eq. 2 (.png)");
  cmd->add_option("--firings", opt->firings, "Periods each transient measures")->capture_default_str();
  cmd->add_option("--probe", opt->probe, "Integration node inside the subcircuit, for the comparator delay "
                                         "(skipped when the subcircuit has no such node)")->capture_default_str();
  cmd->add_option("--osdi", opt->osdi, "A compiled Verilog-A model library (OpenVAF's .osdi) each run loads first, "
                                     "e.g. IHP SG13G2's psp103.osdi (repeatable; needs an ngspice built with OSDI)");
  cmd->add_option("--bias", opt->biases, "A port of the pixel beyond vdd out gnd held at a voltage in every run, "
                                       "NAME=VOLTS, e.g. vbias=0.9V (repeatable)");
  cmd->add_option("--ngbehavior", opt->ngbehavior, "ngspice's compatibility mode for every run, e.g. hsa (default: the "
                                                  "one a .spiceinit beside the deck sets, else ngspice's own)");
  cmd->add_option("-j,--jobs", opt->jobs, "ngspice processes at once (0: all cores)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->callback([opt, &status] { status = calibrate_command(*opt); });
}

void add_compare(CLI::App& app, int& status) {
  auto opt = std::make_shared<CompareOptions>();
  CLI::App* cmd = app.add_subcommand(
      "compare", "Run every fidelity rung on the same scenes and sensor and measure each against the event rung");
  cmd->add_option("--sensor", opt->sensor, "Sensor preset or .toml file")->capture_default_str();
  cmd->add_option("--scene", opt->scenes, "Scene file or folder (repeatable; default scenes/letters/A.pgm)");
  cmd->add_option("--duration", opt->duration, "Simulated time per run")->capture_default_str();
  cmd->add_option("--set", opt->sets, "Override a parameter for every rung: section.key=value");
  cmd->add_option("--steps", opt->steps, "Steps of the fixed_step baseline")->delimiter(',')->capture_default_str();
  cmd->add_option("-o,--output", opt->output, "CSV file")->capture_default_str();
  cmd->add_option("--max-events", opt->max_events, "The most work one run may ask for (default 1e8 fired events)");
  cmd->callback([opt, &status] { status = compare_command(*opt); });
}

void add_emulate(CLI::App& app, int& status) {
  auto opt = std::make_shared<EmulateOptions>();
  CLI::App* cmd = app.add_subcommand("emulate", "Turn ordinary frames (an image, numbered frames, a TIFF stack, Y4M video) into "
                                                "address events as the source paper's emulator does (eq. 1 and eq. 3)");
  cmd->add_option("INPUT", opt->input,
                  fmt::format("An image ({}), a folder of numbered frames, a multi-page TIFF or a .y4m video", scene_image_formats()))
      ->required();
  cmd->add_option("--behaviour", opt->behaviour, "intensity, motion, edge or centroid")->capture_default_str();
  cmd->add_option("--threshold", opt->threshold, "Grey level (0-255) at or below which the behaviour's map is zero")
      ->capture_default_str();
  cmd->add_option("--clip", opt->clip, "LOW,HIGH: grey levels below LOW become 0, above HIGH become HIGH")
      ->capture_default_str();
  cmd->add_option("--size", opt->size, "Imager resolution WIDTHxHEIGHT (default: the input's)");
  cmd->add_option("--f-max", opt->f_max, "Events per frame of a full-scale (255) pixel")->capture_default_str();
  cmd->add_option("--spread", opt->spread, "even: each pixel enters round(f_max * P) times per frame (eq. 1), spread "
                                           "evenly; literal: eq. 3 as written (counts of N / k only)")
      ->capture_default_str();
  cmd->add_option("--frame-rate", opt->frame_rate, "Frames per second for the timestamps (default: the input's, else 25)");
  cmd->add_option("--chaos-in", opt->chaos_in, "Probability that a random event enters after each event")->capture_default_str();
  cmd->add_option("--chaos-out", opt->chaos_out, "Probability that an event leaves the queue")->capture_default_str();
  cmd->add_option("--seed", opt->seed, "Seed of the chaos draws")->capture_default_str();
  cmd->add_option("--queue", opt->queue, "The event queue as text, one 'x y' per line in queue order");
  file_output(cmd, "-o,--out", opt->out,
              "Events with synthetic timestamps, by extension (none: AEDAT 2.0): " + event_formats_help());
  cmd->add_option("--aedat4-compression", opt->aedat4_compression, "Packets of an .aedat4 --out: lz4, zstd or none")
      ->capture_default_str();
  cmd->add_option("--raw-encoding", opt->raw_encoding, "Words of a Prophesee .raw --out: evt2 or evt3")
      ->capture_default_str();
  cmd->add_option("--recon", opt->recon, "Histogram reconstruction (.png or .pgm)");
  cmd->add_option("--events", opt->events, "Reconstruct from the first N events (default: all)");
  cmd->add_option("--max-events", opt->max_events, "The most events (and a hundred times as many pixel visits) the "
                  "emulation may ask for")->capture_default_str();
  cmd->callback([opt, &status] { status = emulate_command(*opt); });
}

void add_classify(CLI::App& app, int& status) {
  auto opt = std::make_shared<ClassifyOptions>();
  CLI::App* cmd = app.add_subcommand("classify", "Recognise the subject of an event file with the paper's rank-weighted templates");
  cmd->add_option("EVENTS", opt->events, "Event file (" + event_inputs() + ")")->required();
  cmd->add_option("--templates", opt->templates, "Folder of binary .pgm templates (default scenes/templates/letters)");
  cmd->add_option("--size", opt->size, "The array's WIDTHxHEIGHT: needed for aesim's CSV, which records none");
  cmd->add_option("--layout", opt->layout, "The chip of a jAER AEDAT 2.0 recording with no # AEChip line: dvs128, davis240c or davis346");
  cmd->add_option("--k", opt->classifier.k, "A winner leads the second score by at least K * r_max")->capture_default_str();
  cmd->add_option("--max-events", opt->classifier.max_events, "Restart after this many events without a decision")
      ->capture_default_str();
  cmd->add_option("--overflow", opt->classifier.overflow, "Restart when a score exceeds this")->capture_default_str();
  cmd->add_option("--center", opt->classifier.center_events,
                  "Centre the subject on the centroid of the first N events, and each template on its own centroid");
  cmd->add_flag("--center-templates", opt->classifier.center_templates,
                "Centre each template on its own centroid only (for subjects centred before they became events)");
  cmd->add_flag("--no-ranks", opt->no_ranks, "Plain counting: every template adds 1");
  cmd->add_flag("--json", opt->json, "Machine-readable output");
  cmd->add_option("--cycles-per-template", opt->cycles_per_template, "For the time estimate")->capture_default_str();
  cmd->add_option("--clock", opt->clock, "Processor clock for the time estimate")->capture_default_str();
  cmd->callback([opt, &status] { status = classify_command(*opt); });
}

void add_report(CLI::App& app, int& status) {
  CLI::App* report = app.add_subcommand("report", "Reports of the source paper");
  report->require_subcommand(1);
  auto opt = std::make_shared<BandwidthOptions>();
  CLI::App* cmd = report->add_subcommand("bandwidth", "Bits of a raw frame against bits of its events, and frame memory");
  cmd->add_option("--width", opt->width)->capture_default_str();
  cmd->add_option("--height", opt->height)->capture_default_str();
  cmd->add_option("--bits", opt->bits, "Bits per pixel of the frame")->capture_default_str();
  cmd->add_option("--events", opt->events, "Events that carry the image")->capture_default_str();
  cmd->add_option("--frame-overhead", opt->frame_overhead, "Bytes a frame carries beyond its pixels (the paper's 12)")
      ->capture_default_str();
  cmd->add_option("--bit-rate", opt->radio.bit_rate, "Radio bit rate, bit/s (IEEE 802.15.4: 250e3)")->capture_default_str();
  cmd->add_option("--packet-bytes", opt->radio.packet_bytes, "Largest packet (802.15.4: 127)")->capture_default_str();
  cmd->add_option("--packet-overhead", opt->radio.packet_overhead, "Bytes of each packet spent on headers (the paper's 8)")
      ->capture_default_str();
  cmd->callback([opt, &status] { status = bandwidth_command(*opt); });
}

void add_config(CLI::App& app, int& status) {
  CLI::App* config = app.add_subcommand("config", "The configuration keys");
  config->require_subcommand(1);
  auto sensor = std::make_shared<std::string>("aloha");
  auto markdown = std::make_shared<bool>(false);
  CLI::App* cmd = config->add_subcommand("keys", "Every key --set takes: unit, value in a preset, meaning");
  cmd->add_option("--sensor", *sensor, "Preset whose values are listed (a name in models/sensors or a .toml file)")
      ->capture_default_str();
  cmd->add_flag("--markdown", *markdown, "A Markdown table (docs/configuration_keys.md)");
  cmd->callback([sensor, markdown, &status] { status = config_keys_command(*sensor, *markdown); });
}

// For "aesim run --outt x": the first argument the command took for no option of its own, as
// "aesim run: unknown option '--outt', did you mean '--out'?"; empty when the extras are not
// options (stray values, which CLI11's own message lists).
std::string unknown_option(const CLI::App& app) {
  for (const CLI::App* sub : app.get_subcommands()) {
    for (const std::string& arg : sub->remaining()) {
      if (arg.size() < 2 || arg[0] != '-' || (arg[1] >= '0' && arg[1] <= '9') || arg[1] == '.') continue;
      const std::string given = arg.substr(0, arg.find('='));
      std::vector<std::string> names;
      for (const CLI::Option* o : sub->get_options()) {
        for (const std::string& l : o->get_lnames()) names.push_back("--" + l);
        for (const std::string& n : o->get_snames()) names.push_back("-" + n);
      }
      return fmt::format("aesim {}: unknown option '{}'{} (aesim {} --help lists them)", sub->get_name(), given,
                         did_you_mean(given, names), sub->get_name());
    }
  }
  return {};
}

// "aesim" alone or "aesim rnu": the commands there are, and the one meant.
std::string command_list(const CLI::App& app) {
  std::string list;
  for (const CLI::App* sub : app.get_subcommands({})) list += (list.empty() ? "" : ", ") + sub->get_name();
  return list;
}

}  // namespace

int run_command_line(int argc, char** argv) {
  CLI::App app{"aesim: simulator of address-event image sensors (ALOHA and arbitrated buses), from an event-level "
               "model to a cycle-level SystemC one with the receiver's RTL in the loop",
               "aesim"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("aesim ") + kVersion, "Print aesim's version and exit");
  int status = 0;
  add_run(app, status);
  add_recon(app, status);
  add_info(app, status);
  add_sweep(app, status);
  add_compare(app, status);
  add_verify(app, status);
  add_calibrate(app, status);
  add_emulate(app, status);
  add_classify(app, status);
  add_report(app, status);
  add_config(app, status);
  if (argc < 2) {
    throw InputError(fmt::format("a command is required ({}); `aesim run` simulates the default scene, `aesim "
                                 "--help` says more", command_list(app)));
  }
  if (argv[1][0] != '-') {
    std::vector<std::string> names;
    for (const CLI::App* sub : app.get_subcommands({})) names.push_back(sub->get_name());
    if (std::find(names.begin(), names.end(), argv[1]) == names.end()) {
      throw InputError(fmt::format("unknown command '{}'{} (commands: {})", argv[1], did_you_mean(argv[1], names),
                                   command_list(app)));
    }
  }
  report_beside_standard_output(argc, argv);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ExtrasError& e) {
    const std::string unknown = unknown_option(app);
    std::fprintf(stderr, "%s\n", unknown.empty() ? (std::string("aesim: ") + e.what()).c_str() : unknown.c_str());
    return 2;
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "aesim: %s\n", e.what());
    return 2;
  }
  return status;
}

}  // namespace aesim
