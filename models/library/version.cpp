#include "aesim/version.hpp"

namespace aesim {

const char* version() { return kVersion; }

}  // namespace aesim
