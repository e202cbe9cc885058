#include "aesim/event_files/ros_bag.hpp"

#include <cstdint>
#include <cstring>
#include <map>
#include <string_view>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/event_files/checked_bytes.hpp"
#include "aesim/event_files/compressed_block.hpp"
#include "aesim/event_files/ros_event_messages.hpp"
#include "aesim/limits/limits.hpp"

namespace aesim {
namespace {

constexpr std::string_view kMagic = "#ROSBAG V2.0\n";
// The md5sum ROS gives a message's layout: dvs_msgs/EventArray's (std_msgs/Header, uint32 height,
// uint32 width, dvs_msgs/Event[] of uint16 x, uint16 y, time ts, bool polarity). Any type of that
// layout carries it, whatever its package (prophesee_event_msgs/EventArray does).
constexpr std::string_view kEventArrayMd5 = "5e8beee5a6c107e504c2e78903c224b8";
// event_camera_msgs/EventPacket's (std_msgs/Header, uint32 height, uint32 width, uint64 seq, uint64
// time_base, string encoding, bool is_bigendian, uint8[] events), as genmsg computes it from the
// package's msg_ros1/EventPacket.msg: the camera's own words in `events`, in the encoding named.
constexpr std::string_view kEventPacketMd5 = "8a6101b351a64529ac77bd8b71074e52";

enum Op : std::uint8_t { kMessageData = 2, kBagHeader = 3, kIndexData = 4, kChunk = 5, kChunkInfo = 6, kConnection = 7 };

// A record's header: fields of a 4-byte length then name=value (the value bytes as they are).
std::map<std::string, std::string_view, std::less<>> header_fields(std::string_view header, const CheckedBytes& in) {
  std::map<std::string, std::string_view, std::less<>> fields;
  CheckedBytes b(header, "", "");
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
T field_number(const std::map<std::string, std::string_view, std::less<>>& fields, std::string_view name, const CheckedBytes& in) {
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

struct Connection {
  std::string topic;
  RosEventLayout carries = RosEventLayout::Other;
};

class BagReader {
 public:
  explicit BagReader(const std::string& label) : label_(label), topics_(label) {}

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
    return topics_.result();
  }

 private:
  // The records of the file, or of one chunk once uncompressed; `where` and `base` name them in
  // messages.
  void records(std::string_view block, const std::string& where, std::size_t base) {
    CheckedBytes in(block, label_, where, base);
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

  void chunk(const std::map<std::string, std::string_view, std::less<>>& fields, std::string_view data, const CheckedBytes& in) {
    const std::string_view compression = field_text(fields, "compression");
    const auto size = field_number<std::uint32_t>(fields, "size", in);
    if (size > kMaxInputFileBytes) in.fail(fmt::format("a chunk of {} bytes, more than aesim reads in one", size));
    ++chunks_;
    if (compression == "none") {
      if (size != data.size()) in.fail(fmt::format("an uncompressed chunk of {} bytes says it holds {}", data.size(), size));
      records(data, fmt::format("chunk {}", chunks_), 0);
      return;
    }
    const auto how = block_compression_named(compression);
    if (!how || *how == BlockCompression::Zstd) {
      in.fail(fmt::format("a chunk compressed with '{}' (rosbag writes none, bz2 or lz4)", compression));
    }
    std::string plain;
    try {
      plain = uncompressed_block(*how, data, size, "chunk");
    } catch (const BlockError& e) {
      in.fail(e.what());
    }
    records(plain, fmt::format("chunk {} uncompressed", chunks_), 0);
  }

  void connection(const std::map<std::string, std::string_view, std::less<>>& fields, std::string_view data, const CheckedBytes& in) {
    const auto id = field_number<std::uint32_t>(fields, "conn", in);
    // The data is itself a header: the publisher's topic, type, md5sum and message definition.
    const auto about = header_fields(data, in);
    Connection c;
    c.topic = std::string(field_text(fields, "topic"));
    const std::string_view md5 = field_text(about, "md5sum");
    c.carries = md5 == kEventArrayMd5    ? RosEventLayout::EventArray
                : md5 == kEventPacketMd5 ? RosEventLayout::EventPacket
                                         : RosEventLayout::Other;
    // rosbag writes each connection in the chunk of its first message and again after the chunks.
    const auto [it, added] = connections_.emplace(id, c);
    if (!added && it->second.topic != c.topic) {
      in.fail(fmt::format("connection {} is declared for '{}' and for '{}'", id, it->second.topic, c.topic));
    }
    if (added) topics_.declare(c.topic, std::string(field_text(about, "type")));
  }

  void message(const std::map<std::string, std::string_view, std::less<>>& fields, std::string_view data, const CheckedBytes& in) {
    const auto id = field_number<std::uint32_t>(fields, "conn", in);
    const auto it = connections_.find(id);
    if (it == connections_.end()) in.fail(fmt::format("a message of connection {}, which no record declared before it", id));
    topics_.message(it->second.topic, it->second.carries, RosWire::Ros1, data);
  }

  std::string label_;
  std::map<std::uint32_t, Connection> connections_;
  RosEventTopics topics_;
  std::size_t chunks_ = 0;
};

}  // namespace

PolarityRecording decode_ros_bag(const std::string& data, const std::string& label) { return BagReader(label).read(data); }

}  // namespace aesim
