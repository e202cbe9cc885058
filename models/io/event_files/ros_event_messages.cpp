#include "aesim/event_files/ros_event_messages.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <limits>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/event_files/checked_bytes.hpp"
#include "aesim/event_files/compressed_block.hpp"
#include "aesim/event_files/prophesee_raw.hpp"
#include "aesim/limits/limits.hpp"

namespace aesim {

// A message's bytes read in order, in ROS 1's layout or CDR's.
class RosMessageBytes {
 public:
  RosMessageBytes(std::string_view data, RosWire wire, const std::string& label, std::string where)
      : in_(data, label, std::move(where)), cdr_(wire == RosWire::Cdr) {
    if (!cdr_) return;
    // The encapsulation's kind, big-endian; its options (the other two bytes) say only how much
    // padding ends the message.
    const std::string_view head = in_.take(4, "CDR's encapsulation header");
    const unsigned kind = (static_cast<unsigned>(static_cast<std::uint8_t>(head[0])) << 8) | static_cast<std::uint8_t>(head[1]);
    switch (kind) {
      case 0x0000: swap_ = true; break;                  // CDR_BE
      case 0x0001: break;                                // CDR_LE, what ROS 2 writes
      case 0x0006: swap_ = true; max_align_ = 4; break;  // PLAIN_CDR2_BE
      case 0x0007: max_align_ = 4; break;                // PLAIN_CDR2_LE
      default: fail(fmt::format("CDR encapsulation 0x{:04x} (aesim reads plain CDR and XCDR2, either byte order)", kind));
    }
  }

  std::size_t left() const { return in_.left(); }
  std::string_view take(std::size_t n, const char* what) { return in_.take(n, what); }
  template <typename T>
  T number(const char* what) {
    align(sizeof(T));
    std::array<char, sizeof(T)> b;
    std::memcpy(b.data(), in_.take(sizeof(T), what).data(), sizeof(T));
    if (swap_) std::reverse(b.begin(), b.end());
    T v;
    std::memcpy(&v, b.data(), sizeof v);
    return v;
  }
  // A string: ROS 1's bytes as they are, CDR's ending in a NUL its length counts.
  std::string_view text(const char* what) {
    std::string_view s = in_.take(number<std::uint32_t>(what), what);
    if (cdr_) {
      if (s.empty() || s.back() != '\0') fail(fmt::format("{} does not end in the NUL CDR gives a string", what));
      s.remove_suffix(1);
    }
    return s;
  }
  // std_msgs/Header: ROS 1's seq, stamp and frame_id; ROS 2's stamp and frame_id.
  void header() {
    if (!cdr_) number<std::uint32_t>("the header's seq");
    number<std::uint32_t>("the header's seconds");
    number<std::uint32_t>("the header's nanoseconds");
    text("the frame id");
  }
  // A ROS time in whole microseconds: seconds (ROS 1's unsigned, ROS 2's builtin_interfaces/Time
  // signed) and nanoseconds.
  std::int64_t time_us(std::uint32_t event) {
    const std::int64_t sec = cdr_ ? std::int64_t(number<std::int32_t>("the stamp's seconds"))
                                  : std::int64_t(number<std::uint32_t>("the stamp's seconds"));
    const auto nsec = number<std::uint32_t>("the stamp's nanoseconds");
    if (nsec >= 1000000000u) fail(fmt::format("event {} has {} nanoseconds past its second", event, nsec));
    return sec * 1000000 + nsec / 1000;
  }
  // Nothing may follow the last field but CDR's padding of the message to a multiple of 4 bytes.
  void end() {
    if (left() > (cdr_ ? 3u : 0u)) fail(fmt::format("{} bytes after the message's last field", left()));
  }
  bool cdr() const { return cdr_; }
  [[noreturn]] void fail(const std::string& why) const { in_.fail(why); }

 private:
  // CDR puts a number at a multiple of its size (up to max_align_) from the encapsulation's end.
  void align(std::size_t size) {
    if (!cdr_) return;
    const std::size_t n = std::min(size, max_align_);
    const std::size_t off = (in_.at() - 4) % n;
    if (off != 0) in_.take(n - off, "padding");
  }

  CheckedBytes in_;
  bool cdr_;
  bool swap_ = false;
  std::size_t max_align_ = 8;
};

namespace {

constexpr std::size_t kEventBytes = 13;  // x, y, the stamp's two words and the polarity, packed

// A field as a definition names it: its type without a package ("std_msgs/msg/Header" and
// "Header" are one type; ROS 1's primitive "time" is ROS 2's builtin_interfaces/Time), its name.
using Fields = std::vector<std::pair<std::string, std::string>>;

std::string bare_type(std::string_view type) {
  const std::size_t slash = type.rfind('/');
  if (slash != std::string_view::npos) type.remove_prefix(slash + 1);
  return type == "time" ? "Time" : std::string(type);
}

// A .msg text (ROS 1's or ROS 2's, with the definitions of the types it uses after lines of '='
// and "MSG: package/Type"): each type's fields, constants and comments left out, the type's own
// under "".
std::map<std::string, Fields> definition_fields(std::string_view text) {
  std::map<std::string, Fields> types;
  Fields* current = &types[""];
  while (!text.empty()) {
    const std::size_t eol = text.find('\n');
    std::string_view line = text.substr(0, eol);
    text.remove_prefix(eol == std::string_view::npos ? text.size() : eol + 1);
    if (const std::size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    const auto is_space = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
    while (!line.empty() && is_space(line.front())) line.remove_prefix(1);
    while (!line.empty() && is_space(line.back())) line.remove_suffix(1);
    if (line.empty() || line.find_first_not_of('=') == std::string_view::npos) continue;
    if (line.rfind("MSG:", 0) == 0) {
      line.remove_prefix(4);
      while (!line.empty() && is_space(line.front())) line.remove_prefix(1);
      current = &types[bare_type(line)];
      continue;
    }
    if (line.find('=') != std::string_view::npos) continue;  // a constant
    const std::size_t gap = line.find_first_of(" \t");
    if (gap == std::string_view::npos) continue;
    std::string_view name = line.substr(gap);
    while (!name.empty() && is_space(name.front())) name.remove_prefix(1);
    name = name.substr(0, name.find_first_of(" \t"));  // a default value may follow
    current->emplace_back(bare_type(line.substr(0, gap)), std::string(name));
  }
  return types;
}

const Fields& event_array_fields() {
  static const Fields f{{"Header", "header"}, {"uint32", "height"}, {"uint32", "width"}, {"Event[]", "events"}};
  return f;
}
const Fields& event_fields() {
  static const Fields f{{"uint16", "x"}, {"uint16", "y"}, {"Time", "ts"}, {"bool", "polarity"}};
  return f;
}
const Fields& event_packet_fields() {
  static const Fields f{{"Header", "header"},   {"uint32", "height"},   {"uint32", "width"},       {"uint64", "seq"},
                        {"uint64", "time_base"}, {"string", "encoding"}, {"bool", "is_bigendian"}, {"uint8[]", "events"}};
  return f;
}

}  // namespace

RosEventLayout ros_event_layout(std::string_view type, std::string_view definition) {
  if (!definition.empty()) {
    const auto types = definition_fields(definition);
    const Fields& own = types.at("");
    if (own == event_packet_fields()) return RosEventLayout::EventPacket;
    if (own == event_array_fields()) {
      const auto event = types.find("Event");
      return event == types.end() || event->second == event_fields() ? RosEventLayout::EventArray : RosEventLayout::Other;
    }
    return RosEventLayout::Other;
  }
  std::string name(type);
  if (const std::size_t msg = name.find("/msg/"); msg != std::string::npos) name.erase(msg, 4);
  if (name == "dvs_msgs/EventArray" || name == "prophesee_event_msgs/EventArray") return RosEventLayout::EventArray;
  // event_array_msgs/EventArray is EventPacket's predecessor, field for field (metavision_ros_driver).
  if (name == "event_camera_msgs/EventPacket" || name == "event_array_msgs/EventArray") return RosEventLayout::EventPacket;
  return RosEventLayout::Other;
}

void RosEventTopics::declare(const std::string& topic, const std::string& type) {
  if (events_.count(topic) == 0) others_[topic].type = type;
}

void RosEventTopics::message(const std::string& topic, RosEventLayout layout, RosWire wire, std::string_view data) {
  if (layout == RosEventLayout::Other) {
    OtherTopic& o = others_[topic];
    ++o.messages;
    o.bytes += data.size();
    return;
  }
  // rosbag2's message compression: each message's CDR a zstd frame of its own.
  std::string uncompressed;
  if (wire == RosWire::Cdr && is_zstd_frame(data)) {
    try {
      uncompressed = uncompressed_zstd(data, kMaxInputFileBytes, "message");
    } catch (const BlockError& e) {
      throw InputError(fmt::format("event file '{}': {}: {}", label_, topic, e.what()));
    }
    data = uncompressed;
  }
  others_.erase(topic);
  EventTopic& t = events_[topic];
  if (t.messages > 0 && t.layout != layout) {
    throw InputError(fmt::format("event file '{}': {} carries messages of two event layouts", label_, topic));
  }
  t.layout = layout;
  ++t.messages;
  RosMessageBytes m(data, wire, label_, fmt::format("message {} of {}", t.messages, topic));
  m.header();
  const auto height = m.number<std::uint32_t>("height");
  const auto width = m.number<std::uint32_t>("width");
  if (width > 0 && height > 0) {
    if (t.width == 0) {
      t.width = width;
      t.height = height;
    } else if (t.width != width || t.height != height) {
      m.fail(fmt::format("the array is {}x{}, where the topic's messages before said {}x{}", width, height, t.width, t.height));
    }
  }
  if (layout == RosEventLayout::EventPacket) {
    packet(t, m);
    return;
  }
  const auto n = m.number<std::uint32_t>("the events' count");
  // ROS 1 packs an event in 13 bytes; CDR adds padding between them.
  const std::uint64_t least = std::uint64_t(n) * kEventBytes;
  if (m.cdr() ? least > m.left() : least != m.left()) {
    m.fail(fmt::format("{} events take {}{} bytes, where the message holds {} after its count", n, m.cdr() ? "at least " : "",
                       least, m.left()));
  }
  event_count_ += n;
  if (event_count_ > kMaxExpandedEvents) m.fail(fmt::format("more than the {} events aesim reads from one file", kMaxExpandedEvents));
  for (std::uint32_t k = 0; k < n; ++k) {
    PolarityEvent e;
    e.x = m.number<std::uint16_t>("x");
    e.y = m.number<std::uint16_t>("y");
    e.t_us = m.time_us(k);
    e.on = m.number<std::uint8_t>("polarity") != 0;
    t.events.push_back(e);
  }
  m.end();
}

void RosEventTopics::packet(EventTopic& topic, RosMessageBytes& m) {
  m.number<std::uint64_t>("seq");
  const auto time_base = m.number<std::uint64_t>("time_base");
  const std::string_view encoding = m.text("the encoding");
  if (topic.messages > 1 && encoding != topic.encoding) {
    m.fail(fmt::format("encoding '{}', where the topic's messages before said '{}'", encoding, topic.encoding));
  }
  topic.encoding = std::string(encoding);
  if (m.number<std::uint8_t>("is_bigendian") != 0) m.fail("big-endian words (cameras and aesim are little-endian)");
  const auto n = m.number<std::uint32_t>("the words' length");
  if (encoding != "evt3") {
    const std::string_view words = m.take(n, "the camera's words");
    m.end();
    if (encoding == "mono" || encoding == "libcaer") {
      eight_byte_events(topic, m, time_base, words);
    } else if (encoding == "libcaer_cmp") {
      compressed_libcaer_events(topic, m, time_base, words);
    } else if (encoding == "trigger") {
      topic.triggers += n / 8;
    }
    return;
  }
  if (topic.stream.size() + n > kMaxEventFileBytes) {
    m.fail(fmt::format("more than the {} bytes of words aesim reads from one file", kMaxEventFileBytes));
  }
  // The stream the RAW reader takes begins with a RAW header, written before the first packet's
  // words (the array is known by then), so that the words are held once.
  if (topic.messages == 1) {
    topic.stream = topic.width > 0 ? fmt::format("% format EVT3;height={};width={}\n% end\n", topic.height, topic.width)
                                   : std::string("% evt 3.0\n% end\n");
  }
  topic.stream += m.take(n, "the camera's words");
  m.end();
}

// event_camera_codecs' encodings of 8-byte events (its mono_decoder.h and libcaer_decoder.h, and
// event_array_msgs' README for "mono"), each stamped from the message's time_base in nanoseconds:
//  - "mono" (metavision_ros_driver, event_array_msgs): a little-endian 64-bit word, bit 63 the
//    polarity (1 ON), bits 48-62 y, 32-47 x, 0-31 the nanoseconds since time_base;
//  - "libcaer" (libcaer_driver: DVS and DAVIS cameras): libcaer's polarity event, a 32-bit word
//    (bit 1 the polarity, bits 2-16 y, 17-31 x; bit 0, libcaer's valid mark, not read, as the
//    codec does not) and the camera's 31-bit microseconds, added to time_base, whose high bits
//    run on by 2^31 us each time the microseconds fall back within a message.
// Kept as whole microseconds (the nanoseconds rounded down).
void RosEventTopics::eight_byte_events(EventTopic& topic, RosMessageBytes& m, std::uint64_t time_base, std::string_view words) {
  if (words.size() % 8 != 0) m.fail(fmt::format("{} bytes of '{}' events, not a whole number of 8-byte events", words.size(), topic.encoding));
  event_count_ += words.size() / 8;
  if (event_count_ > kMaxExpandedEvents) m.fail(fmt::format("more than the {} events aesim reads from one file", kMaxExpandedEvents));
  const bool mono = topic.encoding == "mono";
  std::uint64_t high = time_base, last_low = 0;
  for (std::size_t at = 0; at < words.size(); at += 8) {
    std::uint64_t w;
    std::memcpy(&w, words.data() + at, 8);
    std::uint64_t ns;
    PolarityEvent e;
    if (mono) {
      e.x = static_cast<std::int32_t>((w >> 32) & 0xFFFF);
      e.y = static_cast<std::int32_t>((w >> 48) & 0x7FFF);
      e.on = (w >> 63) != 0;
      ns = (w & 0xFFFFFFFFu);
    } else {
      const auto data = static_cast<std::uint32_t>(w);
      const auto low = static_cast<std::int32_t>(static_cast<std::uint32_t>(w >> 32));
      if (low < 0) m.fail(fmt::format("libcaer event {} stamped {} us (a negative stamp)", at / 8, low));
      if (static_cast<std::uint64_t>(low) < last_low) high += (std::uint64_t(1) << 31) * 1000;
      last_low = static_cast<std::uint64_t>(low);
      e.x = static_cast<std::int32_t>((data >> 17) & 0x7FFF);
      e.y = static_cast<std::int32_t>((data >> 2) & 0x7FFF);
      e.on = ((data >> 1) & 1) != 0;
      ns = static_cast<std::uint64_t>(low) * 1000;
    }
    if (ns > std::numeric_limits<std::uint64_t>::max() - high) m.fail(fmt::format("event {} stamped past 2^64 ns", at / 8));
    e.t_us = static_cast<std::int64_t>((high + ns) / 1000);
    topic.events.push_back(e);
  }
}

// libcaer_driver's default encoding, "libcaer_cmp" (its message_converter.cpp writes it; event_camera_codecs'
// libcaer_cmp_types.h and libcaer_cmp_decoder.h read it): little-endian 16-bit words, a 4-bit code
// over 12 bits. TIME_HIGH (0) sets bits 12-23 of the microseconds since the message's first event,
// TIME_LOW (1) bits 0-11, both 0 at each message's start; ADDR_X (2) the column (11 bits);
// ADDR_Y (3) an event at that column, the row in bits 0-10 and the polarity in bit 11;
// VECT_BASE_Y (4) a base row and polarity, then VECT_8 (5) an event at each of its 8 low bits set,
// at the base row plus the bit's place, the base moving on 8 rows after it. An event stands at
// time_base (ns: libcaer_driver writes the ROS time the camera started plus the first event's
// microseconds) plus its microseconds. The codec leaves out events outside the message's array and
// decodes nothing of other codes; so does this, counting both. (The codec's decoder since February
// 2024 multiplies time_base by 1000 again; its first one, as here, added it.)
void RosEventTopics::compressed_libcaer_events(EventTopic& topic, RosMessageBytes& m, std::uint64_t time_base,
                                               std::string_view words) {
  if (words.size() % 2 != 0) m.fail(fmt::format("{} bytes of 'libcaer_cmp' words, not a whole number of 16-bit words", words.size()));
  const bool bounded = topic.width > 0 && topic.height > 0;
  std::uint64_t high = 0, low = 0;
  const auto add = [&](std::uint16_t x, std::uint16_t y, bool on) {
    if (bounded && (x >= topic.width || y >= topic.height)) {
      ++topic.cmp_outside;
      return;
    }
    if (++event_count_ > kMaxExpandedEvents) m.fail(fmt::format("more than the {} events aesim reads from one file", kMaxExpandedEvents));
    const std::uint64_t us = high | low;
    if (us * 1000 > std::numeric_limits<std::uint64_t>::max() - time_base) m.fail("an event stamped past 2^64 ns");
    topic.events.push_back({static_cast<std::int64_t>((time_base + us * 1000) / 1000), x, y, on});
  };
  for (std::size_t at = 0; at < words.size(); at += 2) {
    std::uint16_t w;
    std::memcpy(&w, words.data() + at, 2);
    const unsigned rest = w & 0xFFFu;
    switch (w >> 12) {
      case 0: high = std::uint64_t(rest) << 12; break;
      case 1: low = rest; break;
      case 2: topic.cmp_x = static_cast<std::uint16_t>(rest & 0x7FFu); break;
      case 3: add(topic.cmp_x, static_cast<std::uint16_t>(rest & 0x7FFu), (rest >> 11) != 0); break;
      case 4:
        topic.cmp_base_y = static_cast<std::uint16_t>(rest & 0x7FFu);
        topic.cmp_on = (rest >> 11) != 0;
        break;
      case 5:
        for (unsigned bit = 0; bit < 8; ++bit) {
          if ((rest >> bit) & 1u) add(topic.cmp_x, static_cast<std::uint16_t>(topic.cmp_base_y + bit), topic.cmp_on);
        }
        topic.cmp_base_y = static_cast<std::uint16_t>(topic.cmp_base_y + 8);
        break;
      default: ++topic.cmp_other_words; break;
    }
  }
}

// An EventPacket topic's events: the words of "evt3" decoded as one stream, as the camera wrote
// them, by the Prophesee RAW reader (metavision_driver's; the stamps the camera's microseconds), or
// those of "mono" and "libcaer", decoded as they came.
PolarityRecording RosEventTopics::decode_packets(const std::string& name, EventTopic& topic) const {
  if (topic.encoding == "mono" || topic.encoding == "libcaer" || topic.encoding == "libcaer_cmp") {
    PolarityRecording rec;
    rec.events = std::move(topic.events);
    rec.read_as.push_back(fmt::format("{}'s '{}' events stamped from each message's time_base (ns), kept as whole microseconds",
                                      name, topic.encoding));
    if (topic.cmp_outside > 0) {
      rec.notes.push_back(fmt::format("{} 'libcaer_cmp' events of {} outside its {}x{} array", topic.cmp_outside, name, topic.width,
                                      topic.height));
    }
    if (topic.cmp_other_words > 0) {
      rec.notes.push_back(fmt::format("{} 'libcaer_cmp' words of {} that are no event (VECT_12 or an unassigned code)",
                                      topic.cmp_other_words, name));
    }
    return rec;
  }
  if (topic.encoding != "evt3") {
    throw InputError(fmt::format("event file '{}': {} carries events encoded '{}' (aesim reads 'evt3', 'mono', 'libcaer' and "
                                 "'libcaer_cmp' packets)",
                                 label_, name, topic.encoding));
  }
  return decode_prophesee_raw(topic.stream, fmt::format("{} ({})", label_, name));
}

PolarityRecording RosEventTopics::result() {
  if (events_.empty()) {
    std::string held;
    for (const auto& [topic, o] : others_) held += fmt::format("{}{} ({})", held.empty() ? "" : ", ", topic, o.type);
    throw InputError(fmt::format("event file '{}': no topic of dvs_msgs/EventArray's or event_camera_msgs/EventPacket's layout (the bag holds {})",
                                 label_, held.empty() ? "no messages" : held));
  }
  // std::map: the first event topic by name, passing over those of external triggers alone (a
  // Prophesee camera's "trigger" packets) where another has events.
  auto chosen = events_.begin();
  while (chosen != events_.end() && chosen->second.encoding == "trigger") ++chosen;
  if (chosen == events_.end()) {
    throw InputError(fmt::format("event file '{}': {} carries external triggers alone ('trigger' packets), no pixel's events",
                                 label_, events_.begin()->first));
  }
  PolarityRecording rec;
  if (chosen->second.layout == RosEventLayout::EventPacket) {
    rec = decode_packets(chosen->first, chosen->second);
  } else {
    rec.events = std::move(chosen->second.events);
  }
  rec.width = static_cast<int>(chosen->second.width);
  rec.height = static_cast<int>(chosen->second.height);
  for (const auto& [name, topic] : events_) {
    if (name == chosen->first) continue;
    if (topic.encoding == "trigger") {
      rec.notes.push_back(fmt::format("{} external trigger events of {}", topic.triggers, name));
    } else {
      rec.notes.push_back(fmt::format("{} messages of {} (aesim reads one event topic, {})", topic.messages, name, chosen->first));
    }
  }
  for (const auto& [topic, o] : others_) {
    if (o.messages > 0) rec.notes.push_back(fmt::format("{} messages of {} ({}, {} bytes)", o.messages, topic, o.type, o.bytes));
  }
  put_in_time_order(rec);
  return rec;
}

}  // namespace aesim
