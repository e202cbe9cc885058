#include "aesim/event_files/nmnist_bin.hpp"

#include <cstdint>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/limits/limits.hpp"

namespace aesim {
namespace {

constexpr std::size_t kRecordBytes = 5;
constexpr unsigned kOverflowY = 240;
constexpr std::int64_t kOverflowStep = std::int64_t(1) << 13;

}  // namespace

PolarityRecording decode_nmnist_bin(const std::string& data, const std::string& label) {
  if (data.size() % kRecordBytes != 0) {
    throw InputError(fmt::format("event file '{}': the file ends inside record {} (N-MNIST records are {} bytes)",
                                 label, data.size() / kRecordBytes, kRecordBytes));
  }
  // Five bytes a record: more events a byte than the 8-byte formats, so bounded as the formats
  // whose words expand are.
  if (data.size() / kRecordBytes > kMaxExpandedEvents) {
    throw InputError(fmt::format("event file '{}': {} records, more than the {} aesim reads from one file", label,
                                 data.size() / kRecordBytes, kMaxExpandedEvents));
  }
  PolarityRecording rec;
  rec.events.reserve(data.size() / kRecordBytes);
  const auto* b = reinterpret_cast<const unsigned char*>(data.data());
  std::int64_t added = 0;
  std::uint64_t overflows = 0;
  for (std::size_t at = 0; at < data.size(); at += kRecordBytes) {
    if (b[at + 1] == kOverflowY) {
      added += kOverflowStep;
      ++overflows;
      continue;
    }
    PolarityEvent e;
    e.x = b[at];
    e.y = b[at + 1];
    e.on = (b[at + 2] & 0x80) != 0;
    e.t_us = added + ((std::int64_t(b[at + 2] & 0x7F) << 16) | (std::int64_t(b[at + 3]) << 8) | b[at + 4]);
    rec.events.push_back(e);
  }
  if (overflows > 0) {
    rec.notes.push_back(fmt::format("{} stamp overflow records (y 240), each adding {} us to the stamps after it",
                                    overflows, kOverflowStep));
  }
  return rec;
}

}  // namespace aesim
