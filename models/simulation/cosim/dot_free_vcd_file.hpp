#pragma once
#include <string>

#include <verilated_vcd_c.h>

namespace aesim {

// Verilator names a SystemC model's top scope after its full SystemC name, dots and all
// ("imager.tile1.receiver.rtl" as one VCD scope, which GTKWave splits into a second hierarchy).
// This file holds the VCD header back until it is complete, writes its $scope names with '_' for
// '.', and passes everything after it through unchanged.
class DotFreeScopesFile : public VerilatedVcdFile {
 public:
  ssize_t write(const char* bufp, ssize_t len) override {
    if (header_done_) return write_all(bufp, len) ? len : -1;
    header_.append(bufp, static_cast<std::size_t>(len));
    if (header_.find("$enddefinitions") == std::string::npos) return len;
    return flush_header() ? len : -1;
  }
  void close() override {
    if (!header_done_) flush_header();
    VerilatedVcdFile::close();
  }

 private:
  bool flush_header() {
    header_done_ = true;
    for (std::size_t at = header_.find("$scope "); at != std::string::npos; at = header_.find("$scope ", at + 1)) {
      const std::size_t end = header_.find("$end", at);
      for (std::size_t i = at; i < end && i < header_.size(); ++i) {
        if (header_[i] == '.') header_[i] = '_';
      }
    }
    const bool ok = write_all(header_.data(), static_cast<ssize_t>(header_.size()));
    header_.clear();
    return ok;
  }
  bool write_all(const char* p, ssize_t len) {
    while (len > 0) {
      const ssize_t n = VerilatedVcdFile::write(p, len);
      if (n <= 0) return false;
      p += n;
      len -= n;
    }
    return true;
  }

  std::string header_;
  bool header_done_ = false;
};

}  // namespace aesim
