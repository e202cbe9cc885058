#pragma once
#include <cstddef>
#include <cstring>
#include <string>
#include <string_view>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"

namespace aesim {

// A container's bytes read in order (little-endian numbers, this machine's order), each read
// checked against the end; a failure is one line naming the file, what is being read and where.
class CheckedBytes {
 public:
  // `where` names what `data` is ("chunk 3"); `base`: where `data` starts in it, for the messages.
  CheckedBytes(std::string_view data, std::string label, std::string where, std::size_t base = 0)
      : data_(data), label_(std::move(label)), where_(std::move(where)), base_(base) {}
  bool done() const { return at_ == data_.size(); }
  std::size_t at() const { return at_; }
  std::size_t left() const { return data_.size() - at_; }
  std::string_view take(std::size_t n, const char* what) {
    if (n > left()) fail(fmt::format("{} of {} bytes runs past the end", what, n));
    const std::string_view out = data_.substr(at_, n);
    at_ += n;
    return out;
  }
  template <typename T>
  T number(const char* what) {
    T v;
    std::memcpy(&v, take(sizeof v, what).data(), sizeof v);
    return v;
  }
  [[noreturn]] void fail(const std::string& why) const {
    throw InputError(fmt::format("event file '{}': {}, byte {}: {}", label_, where_, base_ + at_, why));
  }

 private:
  std::string_view data_;
  std::size_t at_ = 0;
  std::string label_, where_;
  std::size_t base_;
};

}  // namespace aesim
