#pragma once
#include <filesystem>

namespace aesim {

// While it lives, the process works in the folder of the receiver's description, where the
// description's own paths start: a file the RTL opens by a relative name ($readmemh("map.hex"),
// $fopen) is then the one beside its sources, whichever folder `aesim verify` was run from. Back
// in the folder it was made in when it goes. Paths of aesim's own used meanwhile must be absolute.
class RtlWorkingFolder {
 public:
  explicit RtlWorkingFolder(const std::filesystem::path& description_file);
  ~RtlWorkingFolder();
  RtlWorkingFolder(const RtlWorkingFolder&) = delete;
  RtlWorkingFolder& operator=(const RtlWorkingFolder&) = delete;

 private:
  std::filesystem::path before_;
};

}  // namespace aesim
