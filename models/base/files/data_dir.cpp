#include "files/data_dir.hpp"

#include <cstdlib>

namespace aesim {

std::string data_dir() {
  if (const char* env = std::getenv("AESIM_DATA_DIR"); env != nullptr && *env != '\0') return env;
  return AESIM_SOURCE_DIR;
}

}  // namespace aesim
