#pragma once
#include <string>
#include <vector>

namespace aesim {

// A team's pixel netlist as `aesim calibrate` takes it (docs/reference.md section 7): a deck that defines
// `.subckt NAME vdd out gnd params: iph=...`, its models and includes its own.
struct PixelDeck {
  std::string path;      // absolute, as the generated testbench .include's it
  std::string given;     // as the user named it, for messages and provenance
  std::string subckt;    // as the deck spells it
  std::string probe;     // the integration node when the subcircuit has one by that name, else empty
  std::string hash;      // FNV-1a 64 of the deck's bytes and its .include'd files', for provenance
  // The subcircuit declares a parameter `mc`: aesim passes mc=1 in Monte Carlo runs and mc=0
  // otherwise, so that one deck gives the nominal table and the statistical spread.
  bool mc_parameter = false;
};

// Reads the deck and finds the subcircuit (in the deck or the files it .include's, one level),
// checks its three ports and its iph parameter, and looks for `probe_node` inside it. Throws
// InputError naming the deck and the problem; what only ngspice can judge (syntax, models) is
// left to the first run.
PixelDeck read_pixel_deck(const std::string& path, const std::string& subckt, const std::string& probe_node);

}  // namespace aesim
