#pragma once
#include <fstream>
#include <memory>
#include <string>
#include <vector>

namespace aesim {

// A set of output files written to temporary names beside their targets and renamed into place
// only by commit(), so a run that fails part-way leaves no half-written output. Files not
// committed are removed when the set is destroyed.
class OutputFiles {
 public:
  OutputFiles() = default;
  OutputFiles(const OutputFiles&) = delete;
  OutputFiles& operator=(const OutputFiles&) = delete;
  ~OutputFiles();

  // Opens a temporary file for `path` (creating its folder); throws InputError if impossible.
  std::ostream& open(const std::string& path);
  // A temporary name for `path` that someone else writes (e.g. a library), renamed with the rest.
  std::string adopt(const std::string& path);
  // Flushes and renames every file into place.
  void commit();

 private:
  struct Pending {
    std::string target, temp;
    std::ofstream stream;
  };
  std::vector<std::unique_ptr<Pending>> files_;
};

}  // namespace aesim
