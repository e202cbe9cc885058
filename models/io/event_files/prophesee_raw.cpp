#include "aesim/event_files/prophesee_raw.hpp"

#include <cstdint>
#include <cstring>
#include <sstream>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/event_files/little_endian.hpp"
#include "aesim/limits/limits.hpp"

namespace aesim {
namespace {

enum class Encoding { Unknown, Evt2, Evt21, Evt21Legacy, Evt3 };

struct RawHeader {
  Encoding encoding = Encoding::Unknown;
  std::string named;  // the encoding as the header gives it, for a message
  int width = 0, height = 0;
  std::size_t data_at = 0;  // where the events start
};

// "1280" -> 1280; 0 unless a whole number from 1 to 65535.
int dimension(const std::string& text) {
  if (text.empty() || text.size() > 5 || text.find_first_not_of("0123456789") != std::string::npos) return 0;
  const long v = std::stol(text);
  return v >= 1 && v <= 65535 ? static_cast<int>(v) : 0;
}

// `text` without the spaces and tabs at either end: writers leave them in header lines
// (expelliarmus's ends each with a space, "% evt 2.0 ").
std::string without_blanks(const std::string& text) {
  const std::size_t first = text.find_first_not_of(" \t\r");
  return first == std::string::npos ? std::string() : text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
}

// "% format EVT3;height=720;width=1280[;endianness=legacy]"
void read_format(const std::string& value, RawHeader& h) {
  std::istringstream fields(value);
  std::string field;
  bool legacy = false;
  std::string name;
  for (bool first = true; std::getline(fields, field, ';'); first = false) {
    field = without_blanks(field);
    if (first) {
      name = field;
      continue;
    }
    const auto eq = field.find('=');
    const std::string key = without_blanks(field.substr(0, eq)),
                      v = eq == std::string::npos ? "" : without_blanks(field.substr(eq + 1));
    if (key == "height") h.height = dimension(v);
    if (key == "width") h.width = dimension(v);
    if (key == "endianness" && v == "legacy") legacy = true;
  }
  h.named = name;
  if (name == "EVT3" || name == "EVT30") h.encoding = Encoding::Evt3;
  else if (name == "EVT2" || name == "EVT20") h.encoding = Encoding::Evt2;
  else if (name == "EVT21") h.encoding = legacy ? Encoding::Evt21Legacy : Encoding::Evt21;
  else h.encoding = Encoding::Unknown;
}

RawHeader read_header(const std::string& data, const std::string& label) {
  RawHeader h;
  Encoding from_evt = Encoding::Unknown;  // "% evt 3.0", the older line
  std::string evt_named;
  std::size_t at = 0;
  while (at < data.size() && data[at] == '%') {
    const std::size_t end = data.find('\n', at);
    if (end == std::string::npos) throw InputError(fmt::format("event file '{}': the Prophesee RAW header does not end", label));
    const std::string line = without_blanks(data.substr(at + 1, end - at - 1));
    at = end + 1;
    std::istringstream words(line);
    std::string key, value;
    words >> key;
    std::getline(words >> std::ws, value);
    if (key == "end" && value.empty()) break;
    if (key == "format") read_format(value, h);
    if (key == "evt") {
      evt_named = "evt " + value;
      from_evt = value == "3.0" ? Encoding::Evt3 : value == "2.0" ? Encoding::Evt2 : value == "2.1" ? Encoding::Evt21 : Encoding::Unknown;
    }
    if (key == "geometry") {
      const auto x = value.find('x');
      if (x != std::string::npos && h.width == 0 && h.height == 0) {
        h.width = dimension(value.substr(0, x));
        h.height = dimension(value.substr(x + 1));
      }
    }
  }
  h.data_at = at;
  if (h.named.empty()) {
    h.encoding = from_evt;
    h.named = evt_named;
  }
  if (h.named.empty()) {
    throw InputError(fmt::format("event file '{}': the Prophesee RAW header names no encoding (no '% format' or "
                                 "'% evt' line)", label));
  }
  if (h.encoding == Encoding::Unknown) {
    throw InputError(fmt::format("event file '{}': Prophesee RAW in '{}' (aesim reads EVT 2.0, 2.1 and 3.0)", label, h.named));
  }
  if (h.width == 0 || h.height == 0) h.width = h.height = 0;
  return h;
}

// Events as they are decoded, with what is left out counted.
struct Decoded {
  PolarityRecording& rec;
  const std::string& label;
  std::uint64_t untimed = 0, outside = 0, triggers = 0, other = 0;
  void event(std::int64_t t, int x, int y, bool on) {
    if ((rec.width > 0 && x >= rec.width) || (rec.height > 0 && y >= rec.height)) {
      ++outside;
      return;
    }
    if (rec.events.size() == kMaxExpandedEvents) {
      throw InputError(fmt::format("event file '{}': more than {} events, the most aesim reads from a Prophesee RAW "
                                   "file (cut it with Metavision's tools)", label, kMaxExpandedEvents));
    }
    rec.events.push_back({t, x, y, on});
  }
};

// EVT 3.0: 16-bit words, the type in the top 4 bits.
void decode_evt3(const std::string& data, std::size_t at, std::size_t words, Decoded& d) {
  std::uint32_t y = 0, base_x = 0, high = 0, low = 0;
  bool base_on = false, cd_row = true, timed = false;
  std::int64_t loops = 0;
  const auto time = [&] { return (loops << 24) | (std::int64_t(high) << 12) | low; };
  for (std::size_t i = 0; i < words; ++i) {
    const auto w = little<std::uint16_t>(data, at + 2 * i);
    const std::uint32_t v = w & 0xFFFu;
    switch (w >> 12) {
      case 0x0:  // EVT_ADDR_Y: a CD row (bit 11 says master or slave camera)
        y = v & 0x7FFu;
        cd_row = true;
        break;
      case 0x1:  // an exposure-measurement row (ATIS): not CD events
        cd_row = false;
        break;
      case 0x2:  // EVT_ADDR_X
        if (!cd_row) break;
        if (!timed) {
          ++d.untimed;
          break;
        }
        d.event(time(), static_cast<int>(v & 0x7FFu), static_cast<int>(y), (v >> 11) & 1u);
        break;
      case 0x3:  // VECT_BASE_X
        base_x = v & 0x7FFu;
        base_on = (v >> 11) & 1u;
        break;
      case 0x4:    // VECT_12
      case 0x5: {  // VECT_8
        const unsigned n = (w >> 12) == 0x4 ? 12 : 8;
        for (unsigned b = 0; b < n; ++b) {
          if (!((v >> b) & 1u) || !cd_row) continue;
          if (!timed) {
            ++d.untimed;
            continue;
          }
          d.event(time(), static_cast<int>(base_x + b), static_cast<int>(y), base_on);
        }
        base_x += n;
        break;
      }
      case 0x6:  // EVT_TIME_LOW
        low = v;
        break;
      case 0x8:  // EVT_TIME_HIGH: a fall by half the range or more is the 24-bit time wrapping
        if (timed && high >= v + 2048) ++loops;
        if (!timed || v != high) low = 0;
        high = v;
        timed = true;
        break;
      case 0xA:  // EXT_TRIGGER
        ++d.triggers;
        break;
      default:  // CONTINUED_4, IMU, OTHERS (ERC counts), CONTINUED_12
        ++d.other;
        break;
    }
  }
}

// EVT 2.x's time base: EVT_TIME_HIGH's 28 bits over the events' own low 6 (64 us steps); a high
// part that falls by half its range or more wrapped, 2^34 us on.
struct TimeHigh {
  std::int64_t base = 0, loops = 0;
  std::uint32_t last = 0;
  bool timed = false;
  void set(std::uint32_t high) {
    if (timed && last >= high + (1u << 27)) ++loops;
    last = high;
    base = (loops << 34) | (std::int64_t(high) << 6);
    timed = true;
  }
};

// EVT 2.0: 32-bit words.
void decode_evt2(const std::string& data, std::size_t at, std::size_t words, Decoded& d) {
  TimeHigh time;
  for (std::size_t i = 0; i < words; ++i) {
    const auto w = little<std::uint32_t>(data, at + 4 * i);
    const std::uint32_t type = w >> 28;
    if (type == 0x8) {
      time.set(w & 0x0FFFFFFFu);
    } else if (type == 0x0 || type == 0x1) {
      if (!time.timed) {
        ++d.untimed;
        continue;
      }
      d.event(time.base + ((w >> 22) & 0x3Fu), static_cast<int>((w >> 11) & 0x7FFu), static_cast<int>(w & 0x7FFu), type == 1);
    } else if (type == 0xA) {
      ++d.triggers;
    } else {
      ++d.other;
    }
  }
}

// EVT 2.1: 64-bit words (standard: the type in bits 60-63; legacy: the halves swapped).
void decode_evt21(const std::string& data, std::size_t at, std::size_t words, bool legacy, Decoded& d) {
  TimeHigh time;
  for (std::size_t i = 0; i < words; ++i) {
    std::uint64_t w = little<std::uint64_t>(data, at + 8 * i);
    if (legacy) w = (w << 32) | (w >> 32);
    const auto type = static_cast<std::uint32_t>(w >> 60);
    if (type == 0x8) {
      time.set(static_cast<std::uint32_t>((w >> 32) & 0x0FFFFFFFu));
    } else if (type == 0x0 || type == 0x1) {
      const auto mask = static_cast<std::uint32_t>(w);
      if (!time.timed) {
        for (std::uint32_t m = mask; m != 0; m &= m - 1) ++d.untimed;
        continue;
      }
      const std::int64_t t = time.base + static_cast<std::int64_t>((w >> 54) & 0x3Fu);
      const int x = static_cast<int>((w >> 43) & 0x7FFu), y = static_cast<int>((w >> 32) & 0x7FFu);
      for (int b = 0; b < 32; ++b) {
        if ((mask >> b) & 1u) d.event(t, x + b, y, type == 1);
      }
    } else if (type == 0xA) {
      ++d.triggers;
    } else {
      ++d.other;
    }
  }
}

}  // namespace

PolarityRecording decode_prophesee_raw(const std::string& data, const std::string& label) {
  const RawHeader h = read_header(data, label);
  PolarityRecording rec;
  rec.width = h.width;
  rec.height = h.height;
  const std::size_t word = h.encoding == Encoding::Evt3 ? 2 : h.encoding == Encoding::Evt2 ? 4 : 8;
  const std::size_t bytes = data.size() - h.data_at, words = bytes / word;
  Decoded d{rec, label};
  switch (h.encoding) {
    case Encoding::Evt3: decode_evt3(data, h.data_at, words, d); break;
    case Encoding::Evt2: decode_evt2(data, h.data_at, words, d); break;
    case Encoding::Evt21: decode_evt21(data, h.data_at, words, false, d); break;
    case Encoding::Evt21Legacy: decode_evt21(data, h.data_at, words, true, d); break;
    case Encoding::Unknown: break;
  }
  const auto counted = [](std::uint64_t n, const char* one) { return fmt::format("{} {}{}", n, one, n == 1 ? "" : "s"); };
  if (d.untimed > 0) rec.notes.push_back(counted(d.untimed, "event") + " before the first time-high word (no time yet)");
  if (d.outside > 0) {
    rec.notes.push_back(counted(d.outside, "event") + fmt::format(" outside the header's {}x{} array", rec.width, rec.height));
  }
  if (d.triggers > 0) rec.notes.push_back(counted(d.triggers, "external trigger event"));
  if (d.other > 0) rec.notes.push_back(counted(d.other, "other word") + " (ERC counts, IMU samples, ...)");
  if (bytes % word != 0) rec.notes.push_back(counted(bytes % word, "byte") + " at the end, a word cut short");
  return rec;
}

namespace {

// EVT 2.0's and EVT 3.0's x and y fields are 11 bits wide.
constexpr int kRawSide = 2048;
// EVT 3.0's time-high word holds 12 bits: across a gap, one at least every 2047 of its steps, so
// that each fall of the written value (a wrap) is seen, and no rise is taken for one.
constexpr std::uint64_t kEvt3HighStep = 2047;

}  // namespace

RawEncoding parse_raw_encoding(const std::string& text) {
  if (text == "evt2") return RawEncoding::Evt2;
  if (text == "evt3") return RawEncoding::Evt3;
  throw InputError(fmt::format("--raw-encoding: expected evt2 or evt3 (got '{}')", text));
}

PropheseeRawWriter::PropheseeRawWriter(std::ostream& out, const ArrayParams& array, double tick, RawEncoding encoding)
    : BufferedStreamWriter(out, tick), encoding_(encoding) {
  const bool evt3 = encoding == RawEncoding::Evt3;
  if (array.cols > kRawSide || array.rows > kRawSide) {
    throw InputError(fmt::format("Prophesee RAW ({}) holds x and y of 11 bits: a {}x{} array does not fit "
                                 "(at most 2048x2048; write .aedat4, .npy or .h5)",
                                 evt3 ? "EVT 3.0" : "EVT 2.0", array.cols, array.rows));
  }
  const std::string header = fmt::format(
      "% evt {2}\n% format {3};height={1};width={0}\n% geometry {0}x{1}\n% integrator_name aesim\n% end\n", array.cols,
      array.rows, evt3 ? "3.0" : "2.0", evt3 ? "EVT3" : "EVT2");
  out_.write(header.data(), static_cast<std::streamsize>(header.size()));
}

void PropheseeRawWriter::events(const AddressEvent* first, std::size_t count) {
  if (encoding_ == RawEncoding::Evt3) {
    evt3(first, count);
  } else {
    evt2(first, count);
  }
}

void PropheseeRawWriter::evt3(const AddressEvent* first, std::size_t count) {
  const auto put = [this](unsigned type, std::uint32_t value) {
    if (used_ + 2 > buffer_.size()) flush();
    const auto word = static_cast<std::uint16_t>((type << 12) | value);
    std::memcpy(buffer_.data() + used_, &word, 2);
    used_ += 2;
  };
  for (const AddressEvent* e = first; e != first + count; ++e) {
    const std::uint64_t t = stamps_(e->t);
    const std::uint64_t high = t >> 12, low = t & 0xFFF;
    // The stream starts at 0 us, so that a first event past the first wrap keeps its stamp.
    if (time_high_ == ~std::uint64_t(0)) {
      put(0x8, 0);
      time_high_ = 0;
    }
    if (high != time_high_) {
      for (std::uint64_t step = time_high_ + kEvt3HighStep; step < high; step += kEvt3HighStep) put(0x8, step & 0xFFF);
      put(0x8, high & 0xFFF);  // EVT_TIME_HIGH
      time_high_ = high;
      time_low_ = ~std::uint64_t(0);
    }
    if (low != time_low_) {
      put(0x6, static_cast<std::uint32_t>(low));  // EVT_TIME_LOW
      time_low_ = low;
    }
    if (e->y != row_) {
      put(0x0, e->y);  // EVT_ADDR_Y, system type 0 (the camera itself)
      row_ = e->y;
    }
    const std::uint32_t on = e->flags == kGhostEvent ? 0 : 1;
    put(0x2, (on << 11) | e->x);  // EVT_ADDR_X
  }
}

void PropheseeRawWriter::evt2(const AddressEvent* first, std::size_t count) {
  // Through locals: the words' stores would make the compiler reload the members every event (the
  // buffer grown a word at a time and the members reloaded, the writer ran at 52 M events/s against
  // 68 M for DAT's 8 bytes an event, bright QCIF in event_rate_bench).
  const MicrosecondStamps stamps = stamps_;
  std::uint64_t time_high = time_high_;
  char* out = buffer_.data() + used_;
  // Room for an event's two words at most.
  char* const last = buffer_.data() + buffer_.size() - 8;
  // Little-endian words, this machine's order (little_endian.hpp).
  const auto put = [&out](std::uint32_t word) {
    std::memcpy(out, &word, 4);
    out += 4;
  };
  for (const AddressEvent* e = first; e != first + count; ++e) {
    const std::uint64_t t = stamps(e->t);
    if (t >> 6 != time_high) {
      time_high = t >> 6;
      put((std::uint32_t(0x8) << 28) | static_cast<std::uint32_t>(time_high & 0x0fffffff));
    }
    const std::uint32_t type = e->flags == kGhostEvent ? 0x0 : 0x1;  // CD_OFF, CD_ON
    put((type << 28) | (static_cast<std::uint32_t>(t & 0x3f) << 22) | (e->x << 11) | e->y);
    if (out > last) {
      used_ = static_cast<std::size_t>(out - buffer_.data());
      flush();
      out = buffer_.data();
    }
  }
  used_ = static_cast<std::size_t>(out - buffer_.data());
  time_high_ = time_high;
}

}  // namespace aesim
