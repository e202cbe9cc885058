#include "report_stream.hpp"

#include <unistd.h>

#include <string>

#include "aesim/output/atomic_file.hpp"

namespace aesim {
namespace {
std::FILE* report = nullptr;
}  // namespace

std::FILE* report_stream() { return report ? report : stdout; }

// Read from the arguments as given, not from the parsed options: every command's every output
// counts, the image, sweep and verify outputs that are not '-'-aware included, and the decision is
// made before any command can print.
void report_beside_standard_output(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const std::size_t equals = arg.rfind("--", 0) == 0 ? arg.find('=') : std::string::npos;
    const std::string value = equals == std::string::npos ? arg : arg.substr(equals + 1);
    if (value == "-" || (!value.empty() && descriptor_named(value) == STDOUT_FILENO)) report = stderr;
  }
}

}  // namespace aesim
