#pragma once
#include <string>

namespace aesim {

// Where the presets (models/sensors), the shipped circuits, scenes/ and the chart scripts live:
// $AESIM_DATA_DIR when set; else PREFIX/share/aesim when this code runs installed (from
// PREFIX/lib or PREFIX/bin); else the source tree it was built from.
std::string data_dir();

}  // namespace aesim
