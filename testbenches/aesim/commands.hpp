#pragma once
#include <CLI/CLI.hpp>

namespace aesim {

// Each command registers its options on a CLI11 subcommand and returns the exit status.
void add_run_command(CLI::App& app, int& status);
void add_recon_command(CLI::App& app, int& status);
void add_info_command(CLI::App& app, int& status);
void add_sweep_command(CLI::App& app, int& status);
void add_compare_command(CLI::App& app, int& status);
void add_emulate_command(CLI::App& app, int& status);
void add_classify_command(CLI::App& app, int& status);
void add_report_command(CLI::App& app, int& status);

}  // namespace aesim
