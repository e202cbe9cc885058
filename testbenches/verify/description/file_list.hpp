#pragma once
#include <map>
#include <string>
#include <vector>

namespace aesim {

// What a simulator's file list (`files.f`, as `verilator -F`, VCS and Xcelium read one) names:
// its sources in order, include folders and defines.
struct FileList {
  std::vector<std::string> sources, include_dirs;
  std::map<std::string, std::string> defines;  // NAME -> value ("" for a bare define)
};

// Reads `path`: one entry a line or several separated by blanks; `//` and `#` start a comment,
// `/* */` encloses one.
// A path is a source, relative to the list's own folder (as `-F` takes it) unless absolute;
// `+incdir+DIR[+DIR...]` include folders, `+define+NAME[=VALUE][+...]` defines, `-v FILE` a
// source, `-f`/`-F LIST` another list read in its place (8 deep at most); `$VAR` and `${VAR}` are
// the environment's. Any other option (a library folder `-y`, a simulator's switch) is an
// InputError naming `label`, the list and its line, since what it asks of the tool aesim cannot
// pass on; so is a list over 1 MiB or a loop of lists. Nothing reaches a shell.
FileList read_file_list(const std::string& path, const std::string& label);

}  // namespace aesim
