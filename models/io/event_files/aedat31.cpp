#include "aesim/event_files/aedat31.hpp"

#include <cstdint>
#include <cstring>
#include <map>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/event_files/little_endian.hpp"

namespace aesim {
namespace {

constexpr char kMagic[] = "#!AER-DAT3.1";
constexpr char kEndOfHeader[] = "#!END-HEADER";
constexpr std::size_t kPacketHeaderBytes = 28;
constexpr std::int16_t kPolarityEvent = 1;
constexpr std::int32_t kPolarityEventBytes = 8;

// cAER's default event types, for the count of what was skipped.
const char* type_name(std::int16_t type) {
  static const char* names[] = {"SPECIAL", "POLARITY", "FRAME", "IMU6", "IMU9", "SAMPLE", "EAR",
                                "CONFIG",  "POINT1D",  "POINT2D", "POINT3D", "POINT4D", "SPIKE", "MATRIX4x4"};
  return type >= 0 && type < 14 ? names[type] : "unknown";
}

}  // namespace

bool is_aedat31(const std::string& data) { return data.rfind(kMagic, 0) == 0; }

PolarityRecording decode_aedat31(const std::string& data, const std::string& label) {
  if (!is_aedat31(data)) {
    throw InputError(fmt::format("event file '{}': not AEDAT 3.1 (must start with {})", label, kMagic));
  }
  const std::size_t end = data.find(kEndOfHeader);
  if (end == std::string::npos) {
    throw InputError(fmt::format("event file '{}': AEDAT 3.1 header without its #!END-HEADER line", label));
  }
  PolarityRecording rec;
  std::map<std::string, SkippedPackets> skipped;
  // The line ends in CRLF as the format says, or LF as some writers end it.
  std::size_t at = end + sizeof kEndOfHeader - 1;
  if (data.compare(at, 2, "\r\n") == 0) {
    at += 2;
  } else if (data.compare(at, 1, "\n") == 0) {
    at += 1;
  } else {
    throw InputError(fmt::format("event file '{}': AEDAT 3.1 header's #!END-HEADER line does not end there", label));
  }
  std::size_t packet = 0;
  while (at < data.size()) {
    if (data.size() - at < kPacketHeaderBytes) {
      throw InputError(fmt::format("event file '{}': AEDAT 3.1 packet {} is cut short in its header", label, packet));
    }
    const auto type = little<std::int16_t>(data, at);
    const auto size = little<std::int32_t>(data, at + 4);
    const auto ts_offset = little<std::int32_t>(data, at + 8);
    const auto overflow = little<std::int32_t>(data, at + 12);
    const auto capacity = little<std::int32_t>(data, at + 16);
    const auto number = little<std::int32_t>(data, at + 20);
    if (type < 0 || size <= 0 || capacity < 0 || number < 0 || number > capacity || overflow < 0) {
      throw InputError(fmt::format("event file '{}': AEDAT 3.1 packet {} has an impossible header (type {}, size {}, "
                                   "capacity {}, number {}, overflow {})",
                                   label, packet, type, size, capacity, number, overflow));
    }
    // Bounded by the bytes given before anything is read or allocated.
    const std::uint64_t bytes = static_cast<std::uint64_t>(size) * static_cast<std::uint64_t>(capacity);
    if (bytes > data.size() - at - kPacketHeaderBytes) {
      throw InputError(fmt::format("event file '{}': AEDAT 3.1 packet {} claims {} bytes of events, more than the file "
                                   "holds",
                                   label, packet, bytes));
    }
    const std::size_t events = at + kPacketHeaderBytes;
    if (type == kPolarityEvent) {
      if (size != kPolarityEventBytes || ts_offset != 4) {
        throw InputError(fmt::format("event file '{}': AEDAT 3.1 packet {}: polarity events of {} bytes with the stamp "
                                     "at {} (the format's are 8 and 4)",
                                     label, packet, size, ts_offset));
      }
      for (std::int32_t k = 0; k < number; ++k) {
        const auto word = little<std::uint32_t>(data, events + 8 * static_cast<std::size_t>(k));
        const auto stamp = little<std::int32_t>(data, events + 8 * static_cast<std::size_t>(k) + 4);
        if ((word & 1u) == 0) {  // invalidated by its producer (a filter), said in the count
          ++rec.invalid;
          continue;
        }
        if (stamp < 0) {
          throw InputError(fmt::format("event file '{}': AEDAT 3.1 packet {} event {} has a negative stamp", label,
                                       packet, k));
        }
        PolarityEvent e;
        e.t_us = (static_cast<std::int64_t>(overflow) << 31) | stamp;
        e.y = static_cast<std::int32_t>((word >> 2) & 0x7FFFu);
        e.x = static_cast<std::int32_t>((word >> 17) & 0x7FFFu);
        e.on = ((word >> 1) & 1u) != 0;
        rec.events.push_back(e);
      }
    } else {
      SkippedPackets& s = skipped[type_name(type)];
      s.type = type_name(type);
      ++s.packets;
      s.bytes += kPacketHeaderBytes + bytes;
    }
    at = events + static_cast<std::size_t>(bytes);
    ++packet;
  }
  for (auto& [name, s] : skipped) rec.skipped.push_back(s);
  return rec;
}

}  // namespace aesim
