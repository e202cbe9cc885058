#pragma once
#include <string>

namespace aesim {

// Root of the aesim source tree, where the presets (models/sensors) and scenes/ live.
// AESIM_DATA_DIR in the environment overrides the location compiled in.
std::string data_dir();

}  // namespace aesim
