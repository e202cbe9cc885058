#include "aesim/event_files/ros_bag.hpp"

#include <bzlib.h>
#include <lz4frame.h>

#include <cstdint>
#include <cstring>
#include <map>
#include <memory>
#include <string_view>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/event_files/prophesee_raw.hpp"
#include "aesim/limits/limits.hpp"

namespace aesim {
namespace {

constexpr std::string_view kMagic = "#ROSBAG V2.0\n";
// The md5sum ROS gives a message's layout: dvs_msgs/EventArray's (std_msgs/Header, uint32 height,
// uint32 width, dvs_msgs/Event[] of uint16 x, uint16 y, time ts, bool polarity). Any type of that
// layout carries it, whatever its package (prophesee_event_msgs/EventArray does).
constexpr std::string_view kEventArrayMd5 = "5e8beee5a6c107e504c2e78903c224b8";
constexpr std::size_t kEventBytes = 13;
// event_camera_msgs/EventPacket's (std_msgs/Header, uint32 height, uint32 width, uint64 seq, uint64
// time_base, string encoding, bool is_bigendian, uint8[] events), as genmsg computes it from the
// package's msg_ros1/EventPacket.msg: the camera's own words in `events`, in the encoding named.
constexpr std::string_view kEventPacketMd5 = "8a6101b351a64529ac77bd8b71074e52";

enum Op : std::uint8_t { kMessageData = 2, kBagHeader = 3, kIndexData = 4, kChunk = 5, kChunkInfo = 6, kConnection = 7 };

// Bytes read in order, each read checked against the end; `where` says what is being read.
class Bytes {
 public:
  // `base`: where `data` starts in what `where` names, for the messages.
  Bytes(std::string_view data, std::string label, std::string where, std::size_t base = 0)
      : data_(data), label_(std::move(label)), where_(std::move(where)), base_(base) {}
  bool done() const { return at_ == data_.size(); }
  std::size_t at() const { return at_; }
  std::string_view take(std::size_t n, const char* what) {
    if (n > data_.size() - at_) fail(fmt::format("{} of {} bytes runs past the end", what, n));
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

// A record's header: fields of a 4-byte length then name=value (the value bytes as they are).
std::map<std::string, std::string_view, std::less<>> header_fields(std::string_view header, const Bytes& in) {
  std::map<std::string, std::string_view, std::less<>> fields;
  Bytes b(header, "", "");
  while (!b.done()) {
    if (header.size() - b.at() < 4) in.fail("a record header ends inside a field's length");
    const auto n = b.number<std::uint32_t>("field length");
    if (n > header.size() - b.at()) in.fail("a record header's field runs past the header");
    const std::string_view field = b.take(n, "field");
    const std::size_t eq = field.find('=');
    if (eq == std::string_view::npos) in.fail("a record header's field has no '='");
    fields.emplace(std::string(field.substr(0, eq)), field.substr(eq + 1));
  }
  return fields;
}

template <typename T>
T field_number(const std::map<std::string, std::string_view, std::less<>>& fields, std::string_view name, const Bytes& in) {
  const auto it = fields.find(name);
  if (it == fields.end() || it->second.size() != sizeof(T)) {
    in.fail(fmt::format("no {}-byte '{}' field in the record header", sizeof(T), name));
  }
  T v;
  std::memcpy(&v, it->second.data(), sizeof v);
  return v;
}

std::string_view field_text(const std::map<std::string, std::string_view, std::less<>>& fields, std::string_view name) {
  const auto it = fields.find(name);
  return it == fields.end() ? std::string_view() : it->second;
}

enum class Carries { Other, EventArray, EventPacket };

struct Connection {
  std::string topic, type;
  Carries carries = Carries::Other;
  std::uint64_t messages = 0, bytes = 0;
};

// One event topic as read so far: decoded events (EventArray), or the camera's words of every
// packet in order (EventPacket: a decoder's state runs on from one packet to the next).
struct TopicEvents {
  Carries carries = Carries::EventArray;
  std::vector<PolarityEvent> events;
  std::string encoding, words;
  std::uint32_t width = 0, height = 0;
  std::uint64_t messages = 0;
};

class BagReader {
 public:
  explicit BagReader(const std::string& label) : label_(label) {}

  PolarityRecording read(const std::string& data) {
    if (data.compare(0, kMagic.size(), kMagic) != 0) {
      const std::size_t line = data.find('\n');
      if (data.rfind("#ROS", 0) == 0 && line != std::string::npos && line < 40) {
        throw InputError(fmt::format("event file '{}': a ROS bag of '{}' (aesim reads version 2.0)", label_,
                                     data.substr(1, line - 1)));
      }
      throw InputError(fmt::format("event file '{}': not a ROS bag (no '#ROSBAG V2.0' line)", label_));
    }
    records(std::string_view(data).substr(kMagic.size()), "the bag", kMagic.size());
    return result();
  }

 private:
  // The records of the file, or of one chunk once uncompressed; `where` and `base` name them in
  // messages.
  void records(std::string_view block, const std::string& where, std::size_t base) {
    Bytes in(block, label_, where, base);
    while (!in.done()) {
      const auto header_length = in.number<std::uint32_t>("a record's header length");
      const std::string_view header = in.take(header_length, "a record's header");
      const auto fields = header_fields(header, in);
      const auto data_length = in.number<std::uint32_t>("a record's data length");
      const std::string_view data = in.take(data_length, "a record's data");
      const std::string_view op = field_text(fields, "op");
      if (op.size() != 1) in.fail("a record without its one-byte 'op' field");
      switch (static_cast<std::uint8_t>(op[0])) {
        case kBagHeader:
          if (!field_text(fields, "encryptor").empty()) {
            in.fail(fmt::format("an encrypted bag ({}): decrypt it with rosbag first", field_text(fields, "encryptor")));
          }
          break;
        case kChunk: chunk(fields, data, in); break;
        case kConnection: connection(fields, data, in); break;
        case kMessageData: message(fields, data, in); break;
        case kIndexData:
        case kChunkInfo: break;  // where things are, for a reader that seeks: this one reads in order
        default: in.fail(fmt::format("a record of unknown op {}", static_cast<unsigned>(static_cast<std::uint8_t>(op[0]))));
      }
    }
  }

  void chunk(const std::map<std::string, std::string_view, std::less<>>& fields, std::string_view data, const Bytes& in) {
    const std::string_view compression = field_text(fields, "compression");
    const auto size = field_number<std::uint32_t>(fields, "size", in);
    if (size > kMaxInputFileBytes) in.fail(fmt::format("a chunk of {} bytes, more than aesim reads in one", size));
    ++chunks_;
    if (compression == "none") {
      if (size != data.size()) in.fail(fmt::format("an uncompressed chunk of {} bytes says it holds {}", data.size(), size));
      records(data, fmt::format("chunk {}", chunks_), 0);
      return;
    }
    std::string plain(size, '\0');
    if (compression == "bz2") {
      unsigned int out = size;
      // bzlib takes no const input; it does not write to it.
      const int status = BZ2_bzBuffToBuffDecompress(plain.data(), &out, const_cast<char*>(data.data()),
                                                    static_cast<unsigned int>(data.size()), 0, 0);
      if (status != BZ_OK || out != size) {
        in.fail(fmt::format("a bz2 chunk does not uncompress to its {} bytes (bzlib status {})", size, status));
      }
    } else if (compression == "lz4") {
      LZ4F_dctx* raw = nullptr;
      if (LZ4F_isError(LZ4F_createDecompressionContext(&raw, LZ4F_VERSION))) throw std::bad_alloc();
      const std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> dctx(raw, LZ4F_freeDecompressionContext);
      std::size_t made = 0, used = 0, hint = 1;
      while (hint != 0) {
        std::size_t out = size - made, consumed = data.size() - used;
        hint = LZ4F_decompress(dctx.get(), plain.data() + made, &out, data.data() + used, &consumed, nullptr);
        if (LZ4F_isError(hint)) in.fail(fmt::format("an lz4 chunk: LZ4: {}", LZ4F_getErrorName(hint)));
        made += out;
        used += consumed;
        if (hint != 0 && out == 0 && consumed == 0) break;  // no progress: the frame is cut or overflows
      }
      if (hint != 0 || made != size || used != data.size()) {
        in.fail(fmt::format("an lz4 chunk does not uncompress to its {} bytes", size));
      }
    } else {
      in.fail(fmt::format("a chunk compressed with '{}' (rosbag writes none, bz2 or lz4)", compression));
    }
    records(plain, fmt::format("chunk {} uncompressed", chunks_), 0);
  }

  void connection(const std::map<std::string, std::string_view, std::less<>>& fields, std::string_view data, const Bytes& in) {
    const auto id = field_number<std::uint32_t>(fields, "conn", in);
    // The data is itself a header: the publisher's topic, type, md5sum and message definition.
    const auto about = header_fields(data, in);
    Connection c;
    c.topic = std::string(field_text(fields, "topic"));
    c.type = std::string(field_text(about, "type"));
    const std::string_view md5 = field_text(about, "md5sum");
    c.carries = md5 == kEventArrayMd5 ? Carries::EventArray : md5 == kEventPacketMd5 ? Carries::EventPacket : Carries::Other;
    // rosbag writes each connection in the chunk of its first message and again after the chunks.
    const auto [it, added] = connections_.emplace(id, c);
    if (!added && it->second.topic != c.topic) {
      in.fail(fmt::format("connection {} is declared for '{}' and for '{}'", id, it->second.topic, c.topic));
    }
  }

  void message(const std::map<std::string, std::string_view, std::less<>>& fields, std::string_view data, const Bytes& in) {
    const auto id = field_number<std::uint32_t>(fields, "conn", in);
    const auto it = connections_.find(id);
    if (it == connections_.end()) in.fail(fmt::format("a message of connection {}, which no record declared before it", id));
    Connection& c = it->second;
    ++c.messages;
    c.bytes += data.size();
    if (c.carries == Carries::Other) return;
    TopicEvents& topic = topics_[c.topic];
    topic.carries = c.carries;
    ++topic.messages;
    Bytes m(data, label_, fmt::format("message {} of {}", topic.messages, c.topic));
    m.take(12, "the header's seq and stamp");
    m.take(m.number<std::uint32_t>("the frame id's length"), "the frame id");
    const auto height = m.number<std::uint32_t>("height");
    const auto width = m.number<std::uint32_t>("width");
    if (width > 0 && height > 0) {
      if (topic.width == 0) {
        topic.width = width;
        topic.height = height;
      } else if (topic.width != width || topic.height != height) {
        m.fail(fmt::format("the array is {}x{}, where the topic's messages before said {}x{}", width, height,
                           topic.width, topic.height));
      }
    }
    if (c.carries == Carries::EventPacket) {
      packet(topic, m);
      return;
    }
    const auto n = m.number<std::uint32_t>("the events' count");
    if (std::uint64_t(n) * kEventBytes != data.size() - m.at()) {
      m.fail(fmt::format("{} events take {} bytes, where the message holds {} after its count", n,
                         std::uint64_t(n) * kEventBytes, data.size() - m.at()));
    }
    events_ += n;
    if (events_ > kMaxExpandedEvents) m.fail(fmt::format("more than the {} events aesim reads from one file", kMaxExpandedEvents));
    for (std::uint32_t k = 0; k < n; ++k) {
      PolarityEvent e;
      e.x = m.number<std::uint16_t>("x");
      e.y = m.number<std::uint16_t>("y");
      const auto sec = m.number<std::uint32_t>("the stamp's seconds");
      const auto nsec = m.number<std::uint32_t>("the stamp's nanoseconds");
      if (nsec >= 1000000000u) m.fail(fmt::format("event {} has {} nanoseconds past its second", k, nsec));
      e.t_us = std::int64_t(sec) * 1000000 + nsec / 1000;
      e.on = m.number<std::uint8_t>("polarity") != 0;
      topic.events.push_back(e);
    }
  }

  // The rest of an EventPacket after its header and size: its words kept for the topic's decoder.
  void packet(TopicEvents& topic, Bytes& m) {
    m.take(16, "seq and time_base");
    const std::string_view encoding = m.take(m.number<std::uint32_t>("the encoding's length"), "the encoding");
    if (topic.messages > 1 && encoding != topic.encoding) {
      m.fail(fmt::format("encoding '{}', where the topic's messages before said '{}'", encoding, topic.encoding));
    }
    topic.encoding = std::string(encoding);
    if (m.number<std::uint8_t>("is_bigendian") != 0) m.fail("big-endian words (cameras and aesim are little-endian)");
    const auto n = m.number<std::uint32_t>("the words' length");
    if (topic.words.size() + n > kMaxEventFileBytes) {
      m.fail(fmt::format("more than the {} bytes of words aesim reads from one file", kMaxEventFileBytes));
    }
    topic.words += m.take(n, "the camera's words");
    if (!m.done()) m.fail("bytes after the packet's words");
  }

  // An EventPacket topic's words decoded as one stream, as the camera wrote them: EVT 3.0 read by
  // the Prophesee RAW reader (metavision_driver's "evt3"); the stamps the camera's microseconds.
  PolarityRecording decode_packets(const std::string& name, const TopicEvents& topic) const {
    if (topic.encoding != "evt3") {
      throw InputError(fmt::format("event file '{}': {} carries events encoded '{}' (aesim reads 'evt3' packets)", label_,
                                   name, topic.encoding));
    }
    const std::string stream = topic.width > 0 ? fmt::format("% format EVT3;height={};width={}\n% end\n", topic.height, topic.width)
                                               : std::string("% evt 3.0\n% end\n");
    return decode_prophesee_raw(stream + topic.words, fmt::format("{} ({})", label_, name));
  }

  PolarityRecording result() {
    if (topics_.empty()) {
      std::string held;
      for (const auto& [id, c] : connections_) {
        held += fmt::format("{}{} ({})", held.empty() ? "" : ", ", c.topic, c.type);
      }
      throw InputError(fmt::format("event file '{}': no topic of dvs_msgs/EventArray's or event_camera_msgs/EventPacket's layout (the bag holds {})", label_,
                                   held.empty() ? "no messages" : held));
    }
    // std::map: the first event topic by name (MVSEC's /davis/left/events before its right).
    auto chosen = topics_.begin();
    PolarityRecording rec;
    if (chosen->second.carries == Carries::EventPacket) {
      rec = decode_packets(chosen->first, chosen->second);
    } else {
      rec.events = std::move(chosen->second.events);
    }
    rec.width = static_cast<int>(chosen->second.width);
    rec.height = static_cast<int>(chosen->second.height);
    for (const auto& [name, topic] : topics_) {
      if (name == chosen->first) continue;
      rec.notes.push_back(fmt::format("{} messages of {} (aesim reads one event topic, {})", topic.messages, name,
                                      chosen->first));
    }
    for (const auto& [id, c] : connections_) {
      if (c.carries == Carries::Other && c.messages > 0) {
        rec.notes.push_back(fmt::format("{} messages of {} ({}, {} bytes)", c.messages, c.topic, c.type, c.bytes));
      }
    }
    put_in_time_order(rec);
    return rec;
  }

  std::string label_;
  std::map<std::uint32_t, Connection> connections_;
  std::map<std::string, TopicEvents> topics_;
  std::uint64_t events_ = 0;
  std::size_t chunks_ = 0;
};

}  // namespace

PolarityRecording decode_ros_bag(const std::string& data, const std::string& label) { return BagReader(label).read(data); }

}  // namespace aesim
