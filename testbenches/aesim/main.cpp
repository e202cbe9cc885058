// The aesim program.
#include <systemc>

#include "commands.hpp"
#include "error_exit.hpp"
#include "aesim/output/temp_files.hpp"

int sc_main(int argc, char* argv[]) {
  aesim::install_signal_cleanup();
  return aesim::with_error_exit([&] { return aesim::run_command_line(argc, argv); });
}
