#include "error_exit.hpp"

#include <cstdio>
#include <cstdlib>
#include <string>
#include <exception>
#include <filesystem>
#include <systemc>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/output/temp_files.hpp"

namespace aesim {
namespace {

// The message as one line whatever it quotes (a file name may hold a newline): control characters
// are written as escapes.
void say(const char* prefix, const std::string& message) {
  std::string line;
  for (const char c : message) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '\n') line += "\\n";
    else if (c == '\r') line += "\\r";
    else if (c == '\t') line += "\\t";
    else if (u < 0x20 || u == 0x7f) line += fmt::format("\\x{:02x}", u);
    else line += c;
  }
  std::fprintf(stderr, "aesim: %s%s\n", prefix, line.c_str());
}

}  // namespace

int with_error_exit(const std::function<int()>& command) {
  try {
    return command();
  } catch (const InputError& e) {
    say("", e.what());
    return 2;
  } catch (const std::filesystem::filesystem_error& e) {
    // Every path aesim looks up came from the user (or derives from one); the readers ask without
    // exceptions, so this is a safety net that still gives one line and the input's status.
    say("", e.what());
    return 2;
  } catch (const OutputError& e) {
    say("", e.what());
    return 1;
  } catch (const Interrupted& e) {
    std::fprintf(stderr, "aesim: interrupted (signal %d); no output written\n", e.signal);
    return 128 + e.signal;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "aesim: out of memory (a limit the checks before the run did not foresee)\n");
    return 1;
  } catch (const sc_core::sc_report& e) {
    say("internal error: SystemC: ", e.what());
    return 1;
  } catch (const std::exception& e) {
    say("internal error: ", e.what());
    return 1;
  }
}

}  // namespace aesim
