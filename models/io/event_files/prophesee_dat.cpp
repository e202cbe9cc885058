#include "aesim/event_files/prophesee_dat.hpp"

#include <cstdint>
#include <cstring>
#include <sstream>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/event_files/little_endian.hpp"

namespace aesim {
namespace {

// The event types of a DAT file's type byte that hold CD events, in the same 8-byte layout.
constexpr int kEvent2d = 0;
constexpr int kEventCd = 12;
// x and y are 14 bits of the event's second word.
constexpr int kDatSide = 1 << 14;

// "% Width 304" -> 304 (0 when the line is another or the number is not one from 1 to 65535).
int header_size(const std::string& line, const char* key) {
  std::istringstream in(line);
  std::string percent, word;
  long value = 0;
  if (!(in >> percent >> word >> value) || word != key || value < 1 || value > 65535) return 0;
  return static_cast<int>(value);
}

}  // namespace

bool is_prophesee_dat(const std::string& data) { return !data.empty() && data[0] == '%'; }

PolarityRecording decode_prophesee_dat(const std::string& data, const std::string& label) {
  PolarityRecording rec;
  std::size_t at = 0;
  while (at < data.size() && data[at] == '%') {
    const std::size_t end = data.find('\n', at);
    if (end == std::string::npos) {
      throw InputError(fmt::format("event file '{}': the Prophesee DAT header does not end", label));
    }
    const std::string line = data.substr(at, end - at);
    if (const int w = header_size(line, "Width")) rec.width = w;
    if (const int h = header_size(line, "Height")) rec.height = h;
    at = end + 1;
  }
  if (data.size() < at + 2) throw InputError(fmt::format("event file '{}': no event type after the header", label));
  const int type = static_cast<unsigned char>(data[at]), size = static_cast<unsigned char>(data[at + 1]);
  if ((type != kEvent2d && type != kEventCd) || size != 8) {
    throw InputError(fmt::format("event file '{}': Prophesee DAT events of type {} and size {} (aesim reads CD "
                                 "events: type 0 or 12, 8 bytes{})",
                                 label, type, size, type == 14 ? "; type 14 is external triggers" : ""));
  }
  at += 2;
  if ((data.size() - at) % 8 != 0) {
    throw InputError(fmt::format("event file '{}': the file ends inside event {}", label, (data.size() - at) / 8));
  }
  rec.events.reserve((data.size() - at) / 8);
  std::uint64_t wraps = 0;
  std::uint32_t last = 0;
  for (; at < data.size(); at += 8) {
    const auto t = little<std::uint32_t>(data, at), w = little<std::uint32_t>(data, at + 4);
    if (t < last) ++wraps;
    last = t;
    PolarityEvent e;
    e.t_us = static_cast<std::int64_t>((wraps << 32) | t);
    e.x = static_cast<std::int32_t>(w & 0x3FFF);
    e.y = static_cast<std::int32_t>((w >> 14) & 0x3FFF);
    e.on = ((w >> 28) & 0xF) != 0;
    rec.events.push_back(e);
  }
  return rec;
}

PropheseeDatWriter::PropheseeDatWriter(std::ostream& out, const ArrayParams& array, double tick)
    : BufferedStreamWriter(out, tick) {
  if (array.cols > kDatSide || array.rows > kDatSide) {
    throw InputError(fmt::format("Prophesee DAT holds x and y of 14 bits: a {}x{} array does not fit (at most "
                                 "16384x16384; write .aedat4, .npy or .h5)",
                                 array.cols, array.rows));
  }
  const std::string header = fmt::format("% Data file containing CD events\n% Version 2\n% Width {}\n% Height {}\n",
                                         array.cols, array.rows);
  out_.write(header.data(), static_cast<std::streamsize>(header.size()));
  const char type_and_size[2] = {static_cast<char>(kEventCd), 8};
  out_.write(type_and_size, 2);
}

void PropheseeDatWriter::events(const AddressEvent* first, std::size_t count) {
  // Little-endian words, this machine's order (little_endian.hpp).
  for (const AddressEvent* e = first; e != first + count; ++e) {
    const std::uint64_t stamp = stamps_(e->t);
    // A run's --out refuses runs this long before they start (EventFormatRow::longest_run); a caller
    // of the writer itself is told here rather than given a wrapped stamp.
    if (stamp > 0xFFFFFFFFu) {
      throw InputError(fmt::format("Prophesee DAT stamps are 32-bit microseconds: an event at {:.6g} s does not fit", e->t));
    }
    const auto t = static_cast<std::uint32_t>(stamp);
    const std::uint32_t p = e->flags == kGhostEvent ? 0 : 1;
    const std::uint32_t word = e->x | (e->y << 14) | (p << 28);
    std::memcpy(buffer_.data() + used_, &t, 4);
    std::memcpy(buffer_.data() + used_ + 4, &word, 4);
    used_ += 8;
    // kBufferBytes is a multiple of the 8-byte event.
    if (used_ == buffer_.size()) flush();
  }
}

}  // namespace aesim
