#include "aesim/event_files/aedat.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <ostream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "aesim/errors/input_error.hpp"
#include "aesim/files/input_file.hpp"
#include "aesim/event_files/event_stamps.hpp"

namespace aesim {
namespace {

// One byte-swapped store on this little-endian host (as every target of aesim is): written byte
// by byte, GCC joined a record's two words into one 64-bit store built a byte at a time.
void put_be32(char* p, std::uint32_t v) {
  const std::uint32_t big = __builtin_bswap32(v);
  std::memcpy(p, &big, sizeof big);
}

constexpr std::size_t kBufferBytes = std::size_t(1) << 20;

std::uint32_t get_be32(const unsigned char* p) {
  return (std::uint32_t(p[0]) << 24) | (std::uint32_t(p[1]) << 16) | (std::uint32_t(p[2]) << 8) | p[3];
}

// Header lines hold printable ASCII only: jAER counts the header's length in characters it
// decoded (a UTF-8 character is one of them, and two or three bytes), and a line break would end
// the line. Anything else, and the backslash, is written \xNN.
std::string escape_header_text(const std::string& text) {
  std::string out;
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 32 || u > 126 || c == '\\') {
      out += fmt::format("\\x{:02X}", u);
    } else {
      out += c;
    }
  }
  return out;
}

std::string unescape_header_text(const std::string& text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '\\' && i + 3 < text.size() && text[i + 1] == 'x' && std::isxdigit(static_cast<unsigned char>(text[i + 2])) &&
        std::isxdigit(static_cast<unsigned char>(text[i + 3]))) {
      out += static_cast<char>(std::stoi(text.substr(i + 2, 2), nullptr, 16));
      i += 3;
    } else {
      out += text[i];
    }
  }
  return out;
}

}  // namespace

std::map<std::string, std::string> sensor_metadata(const nlohmann::json& sensor) {
  std::map<std::string, std::string> flat;
  for (const auto& [section, body] : sensor.items()) {
    for (const auto& [key, value] : body.items()) {
      if (value.is_null()) continue;  // a key that is not set (pixel.transfer without a table)
      flat[section + "." + key] = value.is_string() ? value.get<std::string>() : value.dump();
    }
  }
  return flat;
}

std::vector<std::string> aedat_header(const AddressMap& map, const std::map<std::string, std::string>& sensor,
                                      AedatLayout layout) {
  std::vector<std::string> h = {
      "#!AER-DAT2.0",
      "# This is a raw AE data file created by aesim, the address-event imager simulator",
      "# Data format is int32 address, int32 timestamp (8 bytes total), repeated for each event",
      "# Timestamps tick is 1 us",
  };
  if (layout == AedatLayout::Aesim) {
    h.push_back(fmt::format("# Address layout: address = (tile << {}) | (y_local << {}) | x_local; "
                            "tile = tile_row * {} + tile_col, numbered row-major from the top-left",
                            map.bus_bits(), map.xbits(), map.tiles_per_row()));
  } else {
    const JaerChip chip = jaer_chip(layout, map);
    h.push_back(fmt::format("# AEChip: {}", chip.java_class));
    h.push_back(fmt::format("# Address layout: jAER {} ({}x{}): the {}x{} array at the bottom-left, y = 0 at the "
                            "bottom; polarity ON for a normal event, OFF for a ghost",
                            to_string(layout), chip.width, chip.height, map.cols(), map.rows()));
  }
  h.push_back(fmt::format("# aesim.layout.kind: {}", to_string(layout)));
  h.push_back(fmt::format("# aesim.layout.bus_bits: {}", map.bus_bits()));
  h.push_back(fmt::format("# aesim.layout.xbits: {}", map.xbits()));
  h.push_back(fmt::format("# aesim.layout.ybits: {}", map.ybits()));
  h.push_back(fmt::format("# aesim.layout.tiles: {}", map.tiles()));
  for (const auto& [key, value] : sensor) {
    h.push_back(fmt::format("# aesim.sensor.{}: {}", escape_header_text(key), escape_header_text(value)));
  }
  // jAER's own writer ends its header so, and jAER's reader stops there: without it, a first event
  // whose address begins with the byte '#' (0x23) is taken for a header line.
  h.push_back("#End Of ASCII Header");
  return h;
}

void write_aedat(std::ostream& out, const std::vector<std::string>& header,
                 const std::vector<AedatRecord>& records) {
  for (const std::string& line : header) out << line << "\r\n";
  std::vector<char> buffer;
  buffer.reserve(kBufferBytes);
  for (const AedatRecord& r : records) {
    buffer.resize(buffer.size() + 8);
    put_be32(buffer.data() + buffer.size() - 8, r.address);
    put_be32(buffer.data() + buffer.size() - 4, static_cast<std::uint32_t>(r.timestamp_us));
    if (buffer.size() >= kBufferBytes) {
      out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
      buffer.clear();
    }
  }
  out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
}

AedatWriter::AedatWriter(std::ostream& out, const std::vector<std::string>& header, const AddressMap& map, double tick,
                         AedatLayout layout)
    : out_(out),
      bus_bits_(static_cast<unsigned>(map.bus_bits())),
      stamps_(tick),
      layout_(layout),
      chip_(jaer_chip(layout, map)),
      rows_(map.rows()) {
  for (const std::string& line : header) out_ << line << "\r\n";
  buffer_.resize(kBufferBytes);
}

// A write's failure shows in the stream's state too, where whoever owns the stream finds it.
AedatWriter::~AedatWriter() {
  try {
    finish();
  } catch (...) {
  }
}

void AedatWriter::events(const AddressEvent* first, std::size_t count) {
  if (count == 0) return;
  if (!first_written_) {
    first_written_ = true;
    first_is_hash_ = (address_of(first[0]) >> 24) == '#';
  }
  if (layout_ == AedatLayout::Aesim) {
    const unsigned bus_bits = bus_bits_;
    pack(first, count, [bus_bits](const AddressEvent& e) { return aedat_address(e, bus_bits); });
  } else {
    pack(first, count, [this](const AddressEvent& e) { return jaer_address(layout_, chip_, rows_, e); });
  }
}

template <class Address>
void AedatWriter::pack(const AddressEvent* first, std::size_t count, Address address) {
  // Through locals, the stamps' constants too: the stores into the buffer would make the compiler
  // reload every member a record (a quarter of the writer's time).
  const MicrosecondStamps stamps = stamps_;
  char* out = buffer_.data() + used_;
  char* full = buffer_.data() + buffer_.size();
  bool takes_next = jaer_takes_next_;
  std::uint64_t lost = jaer_lost_;
  for (std::size_t i = 0; i < count; ++i) {
    const std::int64_t stamp = aedat_stamp(first[i], stamps);
    put_be32(out, address(first[i]));
    // jAER reads the record after one stamped 0 in its place without looking at its stamp: of a run
    // of such records it loses every other one.
    const bool zero = stamp == 0 && !takes_next;
    lost += zero;
    takes_next = zero;
    put_be32(out + 4, static_cast<std::uint32_t>(stamp));
    // Packed into a buffer of fixed size (growing a vector by 8 bytes an event cost a fifth of
    // the writing).
    out += 8;
    if (out == full) {
      used_ = buffer_.size();
      flush();
      // Another buffer now: one given back, or a new one.
      out = buffer_.data();
      full = buffer_.data() + buffer_.size();
    }
  }
  used_ = static_cast<std::size_t>(out - buffer_.data());
  jaer_takes_next_ = takes_next;
  jaer_lost_ = lost;
}

std::string AedatWriter::reader_warning() const {
  std::string warning;
  if (first_is_hash_) {
    warning = "its first event's address begins with the byte '#' (0x23): jAER and aesim end the header at "
              "'#End Of ASCII Header', but a reader that takes every line starting with '#' for header (tonic's "
              "read_aedat_header_from_file) will misread the events";
  }
  if (layout_ != AedatLayout::Aesim && jaer_lost_ > 0) {
    warning += fmt::format("{}jAER's reader will lose {} events stamped 0 us (it reads the record after such "
                           "an event in its place); aesim's readers keep them",
                           warning.empty() ? "" : "; ", jaer_lost_);
  }
  return warning;
}

void AedatWriter::flush() {
  if (used_ == 0) return;
  writes_.post(buffer_, [this, size = used_](const std::vector<char>& full) {
    out_.write(full.data(), static_cast<std::streamsize>(size));
  });
  buffer_.resize(kBufferBytes);
  used_ = 0;
}

void AedatWriter::finish() {
  flush();
  writes_.drain();
  // Ends the file's writes now (an output file gives back the space it reserved ahead of them).
  out_.flush();
}

AedatFile read_aedat(const std::string& path) {
  return decode_aedat(read_input_file(path, "event file", kMaxEventFileBytes), path);
}

AedatFile decode_aedat(const std::string& data, const std::string& path) {
  if (data.rfind("#!AER-DAT2.0", 0) != 0) {
    throw InputError(fmt::format("event file '{}': not AEDAT 2.0 (first line must be #!AER-DAT2.0)", path));
  }
  AedatFile file;
  std::size_t pos = 0;
  bool ended = false;
  while (pos < data.size() && data[pos] == '#' && !ended) {
    const std::size_t eol = data.find('\n', pos);
    if (eol == std::string::npos) throw InputError(fmt::format("event file '{}': unterminated header line", path));
    std::string line = data.substr(pos, eol - pos);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::string prefix = "# aesim.";
    if (line.rfind(prefix, 0) == 0) {
      const std::size_t colon = line.find(": ");
      if (colon != std::string::npos) {
        file.metadata[unescape_header_text(line.substr(prefix.size(), colon - prefix.size()))] =
            unescape_header_text(line.substr(colon + 2));
      }
    }
    ended = line == "#End Of ASCII Header" || line == "# End Of ASCII Header";
    file.header.push_back(std::move(line));
    pos = eol + 1;
  }
  const std::size_t bytes = data.size() - pos;
  if (bytes % 8 != 0) {
    throw InputError(fmt::format("event file '{}': truncated ({} bytes after the header is not a whole number of "
                                 "8-byte events)", path, bytes));
  }
  const auto* p = reinterpret_cast<const unsigned char*>(data.data() + pos);
  file.records.resize(bytes / 8);
  // aesim's own files: int32 stamps, never negative, never going back. Another recorder's (jAER's
  // DAVIS cameras count 32 bits that pass 2^31 and wrap): unsigned words, and a step back of more
  // than half the range is a wrap, unwrapped by 2^32; smaller steps back (IMU and frame samples
  // stamped otherwise) are the decoder's to order.
  const bool own = file.metadata.count("sensor.array.rows") != 0;
  std::uint32_t previous = 0;
  for (std::size_t i = 0; i < file.records.size(); ++i) {
    file.records[i].address = get_be32(p + 8 * i);
    const std::uint32_t raw = get_be32(p + 8 * i + 4);
    if (own) {
      file.records[i].timestamp_us = static_cast<std::int32_t>(raw);
      if (file.records[i].timestamp_us < 0) {
        throw InputError(fmt::format("event file '{}': event {} has a negative timestamp ({} us)", path, i,
                                     file.records[i].timestamp_us));
      }
      if (i > 0 && file.records[i].timestamp_us < file.records[i - 1].timestamp_us) {
        throw InputError(fmt::format("event file '{}': timestamps decrease at event {}", path, i));
      }
      continue;
    }
    if (i > 0 && raw < previous && previous - raw > 0x80000000u) ++file.stamp_wraps;
    file.records[i].timestamp_us = static_cast<std::int64_t>(raw) + (static_cast<std::int64_t>(file.stamp_wraps) << 32);
    previous = raw;
  }
  return file;
}

std::vector<AedatRecord> aedat_records(const std::vector<AddressEvent>& events, const AddressMap& map,
                                       double tick) {
  std::vector<AedatRecord> out;
  out.reserve(events.size());
  const MicrosecondStamps stamps(tick);
  for (const AddressEvent& e : events) out.push_back(aedat_record(e, static_cast<unsigned>(map.bus_bits()), stamps));
  return out;
}

void throw_aedat_stamp_overflow(double t) {
  throw InputError(fmt::format("AEDAT 2.0 stamps are int32 microseconds: an event at {:.6g} s does not fit "
                               "(at most 2147 s)", t));
}

}  // namespace aesim
