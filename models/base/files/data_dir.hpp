#pragma once
#include <string>

namespace aesim {

// Where the presets (models/sensors), the shipped circuits, scenes/ and the chart scripts live:
// $AESIM_DATA_DIR when set; else PREFIX/share/aesim when this code runs installed (from
// PREFIX/lib or PREFIX/bin); else the source tree it was built from.
std::string data_dir();

// `path`, or the same relative path under data_dir() when it names nothing from the current folder
// but names something there: the commands the documentation gives (`--scene scenes/natural.pgm`,
// `sweep scripts/sweeps/sizing.toml`, `calibrate models/circuits/aesim_pixel.cir`) then work from
// any folder with an installed aesim. What is in the current folder always wins.
std::string shipped_if_missing(const std::string& path);

}  // namespace aesim
