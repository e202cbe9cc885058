#pragma once
#include <cstddef>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"

namespace aesim {

// A container's bytes read in order (little-endian numbers, this machine's order), each read
// checked against the end; a failure is one line naming the file, what is being read and where.
class CheckedBytes {
 public:
  // Throws for a failure's message; it must not return.
  using Refusal = void (*)(const std::string& message);
  // `where` names what `data` is ("chunk 3"); `base`: where `data` starts in it, for the messages.
  // A failure is an InputError naming the event file `label`.
  CheckedBytes(std::string_view data, std::string label, std::string where, std::size_t base = 0)
      : data_(data), label_(std::move(label)), where_(std::move(where)), base_(base) {}
  // For a decoder that does not know its file (a codec HDF5 calls): a failure is whatever
  // `refuse` throws, its message naming `where` and the byte.
  CheckedBytes(std::string_view data, std::string where, Refusal refuse) : data_(data), where_(std::move(where)), refuse_(refuse) {}
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
    T v = peek<T>(what);
    at_ += sizeof v;
    return v;
  }
  // The next number, left to be read.
  template <typename T>
  T peek(const char* what) const {
    if (sizeof(T) > left()) fail(fmt::format("{} of {} bytes runs past the end", what, sizeof(T)));
    T v;
    std::memcpy(&v, data_.data() + at_, sizeof v);
    return v;
  }
  [[noreturn]] void fail(const std::string& why) const {
    if (refuse_ == nullptr) throw InputError(fmt::format("event file '{}': {}, byte {}: {}", label_, where_, base_ + at_, why));
    refuse_(fmt::format("{}, byte {}: {}", where_, base_ + at_, why));
    throw std::logic_error("a CheckedBytes refusal returned");
  }

 private:
  std::string_view data_;
  std::size_t at_ = 0;
  std::string label_, where_;
  std::size_t base_ = 0;
  Refusal refuse_ = nullptr;
};

}  // namespace aesim
