#pragma once
#include <string>
#include <vector>

namespace aesim {

// A port of the pixel beyond vdd, out and gnd (a comparator's or a reset's bias) held at a voltage
// in every run (`--bias NAME=VOLTS`).
struct PortBias {
  std::string port;  // as the subcircuit spells it
  double volts = 0;
};

// A team's pixel netlist as `aesim calibrate` takes it (docs/reference.md section 7): a deck that defines
// `.subckt NAME vdd out gnd params: iph=...`, its models and includes its own.
struct PixelDeck {
  std::string path;      // absolute, as the generated testbench .include's it
  std::string given;     // as the user named it, for messages and provenance
  std::string subckt;    // as the deck spells it
  std::string probe;     // the integration node when the subcircuit has one by that name, else empty
  // The runs' nets on the subcircuit's ports, in its order: vdd out 0 (supply, output, ground),
  // unless its port names say another order (port_nets_by_name).
  std::vector<std::string> port_nets{"vdd", "out", "0"};
  // Its other ports, each on a net of its own held at its voltage (net bias_net(port)).
  std::vector<PortBias> biases;
  std::string ports_by_name;  // "vdd gnd out" when the names set another order than vdd out gnd, else empty
  std::string hash;      // FNV-1a 64 of the deck's bytes and its .include'd files', for provenance
  // What each run reads of the deck: its circuit (circuit_of), and what of it was left out.
  std::string circuit;
  std::vector<std::string> left_out;
  // The subcircuit declares a parameter `mc`: aesim passes mc=1 in Monte Carlo runs and mc=0
  // otherwise, so that one deck gives the nominal table and the statistical spread.
  bool mc_parameter = false;
  // A foundry PDK's statistical models: the switches the deck or its includes define for them
  // (`.param sw_stat_global`, `sw_stat_mismatch` (GF180), `mc_mm_switch`, `mc_pr_switch` (SKY130),
  // any sw_stat_* or mc_*switch*), which aesim sets to 0 for the table's runs (nominal models) and
  // to 1 in Monte Carlo runs; and the first file that draws with agauss, gauss, aunif or unif
  // (empty if none does).
  std::vector<std::string> statistical_switches;
  std::string statistical_file;
  // The lowest supply a MOS device of the deck's own file (and of the file holding the
  // subcircuit) is made for, as open PDKs spell it in the model's name: SKY130's
  // `sky130_fd_pr__nfet_01v8` 1.8 V (`..._g5v0d10v5` 5 V, its gate's), GF180's `nmos_3p3` and
  // `nfet_03v3` 3.3 V; that device's name. 0 and empty where no name says (IHP's `sg13_lv_nmos`,
  // a level-1 `nmos`). Read from element lines only, never from the PDK's own files, which define
  // every device of the process.
  double device_rating = 0;
  std::string rated_device;
  // Compiled Verilog-A models (OpenVAF's OSDI libraries, as IHP SG13G2's PSP 103 MOS models are)
  // that each run loads before ngspice reads the deck (`pre_osdi`): absolute paths, their bytes
  // in `hash` after the deck's.
  std::vector<std::string> osdi;
  // ngspice's compatibility mode for every run (`ngbehavior`, given as `-D ngbehavior=...`: a
  // `.control` block's `pre_set` comes too late for it); empty: ngspice's own. A PDK setup's
  // `.spiceinit` sets it (IIC-OSIC-TOOLS' `hsa`, under which a binned model is chosen by a
  // finger's width, W / nf, not the device's); `ngbehavior_spiceinit` is that file when the mode
  // is its, empty when --ngbehavior chose it.
  std::string ngbehavior, ngbehavior_spiceinit;
};

// The compatibility mode the `.spiceinit` in `folder` sets (its last `set ngbehavior=MODE` line),
// or empty: what the user's own ngspice runs of a deck there use. Nothing else of the file is run.
std::string spiceinit_ngbehavior(const std::string& folder);
// Sets the deck's compatibility mode: `chosen` (--ngbehavior) when given, else the one of the
// `.spiceinit` beside the deck. A mode of anything but ngspice's letters and digits (hs, hsa, ps,
// lt, ltpsa, ki, ...) is an InputError naming where it came from.
void choose_ngbehavior(PixelDeck& deck, const std::string& chosen);

// A deck's circuit, as each run includes it: its subcircuits, models, parameters, options and the
// files it reads (named from its folder, so the runs' testbench may be anywhere), without what a
// deck run on its own carries beside them (its title line, the testbench's sources and instances,
// analyses, output and measurement statements, .control blocks, and all after .end), which the
// runs replace; `left_out` says what of that the deck had, for a note.
struct DeckCircuit {
  std::string text;
  std::vector<std::string> left_out;
};
DeckCircuit circuit_of(const std::string& text, const std::string& folder);

// The runs' nets on a subcircuit's ports named `ports`: by their names when each is plainly the
// supply (vdd, vcc, avdd, vpwr, ...), the output (out, spike, fire, req, ...) or the ground (gnd,
// vss, 0, vgnd, ...), one of each; else vdd out 0 in their order, as the interface says.
std::vector<std::string> port_nets_by_name(const std::vector<std::string>& ports);

// Reads the deck and finds the subcircuit (in the deck or the files it .include's, one level),
// checks its three ports and its iph parameter, and looks for `probe_node` inside it. Throws
// InputError naming the deck and the problem; what only ngspice can judge (syntax, models) is
// left to the first run.
PixelDeck read_pixel_deck(const std::string& path, const std::string& subckt, const std::string& probe_node,
                          const std::vector<std::string>& osdi = {}, const std::vector<PortBias>& biases = {});

// The runs' net for a biased port: aesim_bias_ and its name in lower case (a port name is one SPICE
// word).
std::string bias_net(const std::string& port);

// What the table's runs make of the deck's statistical models, for the preset's provenance: the
// switches set to 0 (nominal), or, for a deck that draws at random with no switch and no `mc`
// parameter, that each point is one draw (`warning` then true). Empty for a deck without them.
struct StatisticsNote {
  std::string text;
  bool warning = false;
};
StatisticsNote statistics_note(const PixelDeck& deck);

// Empty, or a warning that the runs' supply `vdd` is above what the deck's devices are made for
// (device_rating, with a tenth to spare): a 1.8 V pixel calibrated at the default 3.3 V fires with
// periods of a circuit nobody will fabricate.
std::string supply_rating_note(const PixelDeck& deck, double vdd);

}  // namespace aesim
