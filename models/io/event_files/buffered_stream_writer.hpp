#pragma once
#include <cstddef>
#include <ostream>
#include <vector>

#include "aesim/event_files/event_stamps.hpp"
#include "aesim/event_files/event_writer.hpp"

namespace aesim {

// An event file writer of fixed-size records (Prophesee RAW's words, DAT's events) that packs them
// into a buffer of its own and writes it to the stream a MiB at a time: a vector grown by each
// record, or a stream write of each, costs more than the packing.
class BufferedStreamWriter : public EventFileWriter {
 public:
  void finish() override {
    flush();
    out_.flush();
  }

 protected:
  static constexpr std::size_t kBufferBytes = std::size_t(1) << 20;
  BufferedStreamWriter(std::ostream& out, double tick) : out_(out), stamps_(tick), buffer_(kBufferBytes) {}
  // Writes the buffer's first used_ bytes.
  void flush() {
    out_.write(buffer_.data(), static_cast<std::streamsize>(used_));
    used_ = 0;
  }

  std::ostream& out_;
  MicrosecondStamps stamps_;
  std::vector<char> buffer_;  // kBufferBytes
  std::size_t used_ = 0;
};

}  // namespace aesim
