#pragma once
#include <filesystem>
#include <string>
#include <vector>

namespace aesim {

// What a tool prints (standard output and error together, trailing line ends dropped) for
// `program args`, run without a shell, its output kept in `scratch` while it runs: a version for a
// cache's key, a path it reports. Throws InputError with that output if the tool fails.
std::string tool_output(const std::string& program, const std::vector<std::string>& args, const std::filesystem::path& scratch);

}  // namespace aesim
