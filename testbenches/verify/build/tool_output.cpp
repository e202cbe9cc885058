#include "build/tool_output.hpp"

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/files/scratch_text.hpp"
#include "aesim/process/child_process.hpp"

namespace aesim {

std::string tool_output(const std::string& program, const std::vector<std::string>& args, const std::filesystem::path& scratch) {
  const std::filesystem::path out = scratch / "tool_output.txt";
  if (run_child(program, args, {out.string(), out.string()}) != 0) {
    throw InputError(fmt::format("'{} {}' failed: {}", program, args.empty() ? "" : args[0], read_scratch_text(out)));
  }
  std::string text = read_scratch_text(out);
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  return text;
}

}  // namespace aesim
