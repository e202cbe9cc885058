#include "driver/rtl_working_folder.hpp"

#include <system_error>

namespace aesim {

namespace fs = std::filesystem;

// A folder that cannot be entered (or left) leaves the process where it is: the RTL's relative
// names then read from there, as they would without this.
RtlWorkingFolder::RtlWorkingFolder(const fs::path& description_file) {
  std::error_code ec;
  before_ = fs::current_path(ec);
  if (ec) return;
  const fs::path folder = fs::absolute(description_file, ec).parent_path();
  if (!ec && !folder.empty()) fs::current_path(folder, ec);
}

RtlWorkingFolder::~RtlWorkingFolder() {
  std::error_code ec;
  if (!before_.empty()) fs::current_path(before_, ec);
}

}  // namespace aesim
