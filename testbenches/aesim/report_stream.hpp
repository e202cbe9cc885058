#pragma once
#include <cstdio>

namespace aesim {

// Where the commands write their report (what they did, what they wrote): standard output, unless
// an output of the command is standard output itself (`aesim run --csv /dev/stdout | ...`): then
// standard error, so that the data a pipe or a redirection receives holds nothing but the data.
std::FILE* report_stream();

// Sends the report to standard error when any of the arguments is a name for standard output
// (/dev/stdout, /dev/fd/1, /proc/self/fd/1, or '-', alone or after `--option=`). Called before the command
// runs, so that the whole report goes to one place.
void report_beside_standard_output(int argc, char** argv);

}  // namespace aesim
