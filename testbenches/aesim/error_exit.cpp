#include "error_exit.hpp"

#include <cstdio>
#include <cstdlib>
#include <string>
#include <exception>
#include <filesystem>
#include <systemc>

#include <fmt/format.h>

#include "errors/input_error.hpp"
#include "output/temp_files.hpp"

namespace aesim {

int with_error_exit(const std::function<int()>& command) {
  try {
    return command();
  } catch (const InputError& e) {
    std::fprintf(stderr, "aesim: %s\n", e.what());
    return 2;
  } catch (const std::filesystem::filesystem_error& e) {
    // Every path aesim looks up came from the user (or derives from one); the readers ask without
    // exceptions, so this is a safety net that still gives one line and the input's status.
    std::fprintf(stderr, "aesim: %s\n", e.what());
    return 2;
  } catch (const OutputError& e) {
    std::fprintf(stderr, "aesim: %s\n", e.what());
    return 1;
  } catch (const Interrupted& e) {
    std::fprintf(stderr, "aesim: interrupted (signal %d); no output written\n", e.signal);
    return 128 + e.signal;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "aesim: out of memory (a limit the checks before the run did not foresee)\n");
    return 1;
  } catch (const sc_core::sc_report& e) {
    std::string what = e.what();
    for (char& c : what) c = c == '\n' ? ' ' : c;
    std::fprintf(stderr, "aesim: internal error: SystemC: %s\n", what.c_str());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "aesim: internal error: %s\n", e.what());
    return 1;
  }
}

}  // namespace aesim
