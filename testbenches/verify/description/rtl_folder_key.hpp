#pragma once
#include <filesystem>
#include <functional>
#include <string>

namespace aesim {

// Which of a folder's files a build of the RTL may read: every one (an include folder: Verilator
// may open any of them), or only its Verilog files (a source's own folder, where an `include
// finds them).
enum class RtlFolderFiles { All, VerilogOnly };

// Appends `dir` and each of its files (sorted by name) to `key`, a cache's key that is hashed whole:
// each file as `place` renders its path, then its text, so that a change to any of them changes the
// key. Before a file would take the key past 256 MiB, an InputError names `role` and the folder.
void add_rtl_folder_to_key(std::string& key, const std::filesystem::path& dir, RtlFolderFiles files,
                           const std::function<std::string(const std::filesystem::path&)>& place,
                           const std::string& role);

}  // namespace aesim
