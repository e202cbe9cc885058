#include "aesim/event_files/mcap_bag.hpp"

#include <zlib.h>

#include <cstdint>
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

constexpr std::string_view kMcapMagic("\x89MCAP0\r\n", 8);

enum McapOp : std::uint8_t {
  kMcapHeader = 0x01,
  kMcapFooter = 0x02,
  kMcapSchema = 0x03,
  kMcapChannel = 0x04,
  kMcapMessage = 0x05,
  kMcapChunk = 0x06,
};

// What a record is, for messages.
std::string record_name(std::uint8_t op) {
  switch (op) {
    case kMcapHeader: return "the header";
    case kMcapFooter: return "the footer";
    case kMcapSchema: return "a schema";
    case kMcapChannel: return "a channel";
    case kMcapMessage: return "a message";
    case kMcapChunk: return "a chunk";
    default: return fmt::format("an opcode 0x{:02x}", op);
  }
}

// A string or byte array after its 4-byte length, as MCAP stores one.
std::string_view sized(CheckedBytes& in, const char* what) { return in.take(in.number<std::uint32_t>(what), what); }

struct McapChannel {
  std::string topic;
  RosEventLayout layout = RosEventLayout::Other;
  RosWire wire = RosWire::Cdr;
};

class McapReader {
 public:
  McapReader(RosEventTopics& topics, const std::string& label) : label_(label), topics_(topics) {}

  void read(const std::string& data) {
    if (data.compare(0, kMcapMagic.size(), kMcapMagic) != 0) {
      if (data.compare(0, 5, kMcapMagic.substr(0, 5)) == 0 && data.size() > 5) {
        const auto v = static_cast<unsigned char>(data[5]);
        throw InputError(fmt::format("event file '{}': MCAP of major version {} (aesim reads version '0')", label_,
                                     v >= 0x20 && v < 0x7F ? fmt::format("'{}'", static_cast<char>(v)) : fmt::format("byte 0x{:02x}", v)));
      }
      throw InputError(fmt::format("event file '{}': not an MCAP file (it does not begin with MCAP's magic bytes)", label_));
    }
    const std::string_view rest = std::string_view(data).substr(kMcapMagic.size());
    const std::size_t footer_end = records(rest, "the file", kMcapMagic.size(), true);
    if (footer_end == 0) {
      throw InputError(fmt::format("event file '{}': the file ends without MCAP's footer (a recording that did not end? "
                                   "`mcap recover` rewrites what it holds)", label_));
    }
    if (rest.substr(footer_end) != kMcapMagic) {
      throw InputError(fmt::format("event file '{}': MCAP's footer is not followed by its closing magic bytes", label_));
    }
  }

 private:
  // The records of the file (`top`) or of a chunk once uncompressed; `where` and `base` name them in
  // messages. Returns where the footer's record ends in the file (0 if none came).
  std::size_t records(std::string_view block, const std::string& where, std::size_t base, bool top) {
    CheckedBytes in(block, label_, where, base);
    while (!in.done()) {
      const auto op = in.number<std::uint8_t>("a record's opcode");
      const auto length = in.number<std::uint64_t>("a record's length");
      if (length > in.left()) {
        in.fail(fmt::format("a record (opcode 0x{:02x}) of {} bytes runs past the end{}", op, length,
                            top ? " (a recording that did not end? `mcap recover` rewrites what it holds)" : ""));
      }
      const std::size_t start = base + in.at();
      CheckedBytes record(in.take(length, "a record"), label_, fmt::format("{}, {} record", where, record_name(op)), start);
      switch (op) {
        case 0x00: in.fail("a record of opcode 0, which MCAP does not use");
        case kMcapFooter:
          if (!top) in.fail("a footer inside a chunk");
          return in.at();
        case kMcapSchema: schema(record); break;
        case kMcapChannel: channel(record); break;
        case kMcapMessage: message(record); break;
        case kMcapChunk:
          if (!top) in.fail("a chunk inside a chunk");
          chunk(record);
          break;
        // The header, the indexes, statistics, attachments, metadata and records MCAP may add or a
        // writer keeps to itself: nothing about the messages a reader in file order needs.
        default: break;
      }
    }
    return 0;
  }

  void schema(CheckedBytes& in) {
    const auto id = in.number<std::uint16_t>("the schema's id");
    const std::string_view name = sized(in, "the schema's name");
    const std::string_view encoding = sized(in, "the schema's encoding");
    const std::string_view text = sized(in, "the schema's data");
    if (id == 0) return;  // the specification's "invalid, ignored"
    // A definition of fields aesim can compare: ROS 2's .msg text or ROS 1's; otherwise (IDL, none)
    // the type is told by its name.
    const bool msg_text = encoding == "ros2msg" || encoding == "ros1msg";
    schemas_.insert_or_assign(id, ros_event_layout(name, msg_text ? text : std::string_view()));
    names_.insert_or_assign(id, std::string(name));
  }

  void channel(CheckedBytes& in) {
    const auto id = in.number<std::uint16_t>("the channel's id");
    const auto schema = in.number<std::uint16_t>("the channel's schema id");
    McapChannel c;
    c.topic = std::string(sized(in, "the channel's topic"));
    const std::string_view encoding = sized(in, "the channel's message encoding");
    std::string type = "no schema";
    if (schema != 0) {
      const auto it = schemas_.find(schema);
      if (it == schemas_.end()) in.fail(fmt::format("channel {} names schema {}, which no record declared before it", id, schema));
      type = names_.at(schema);
      // Messages in CDR (ROS 2) or ROS 1's layout; JSON, protobuf and the rest are counted.
      if (encoding == "cdr" || encoding == "ros1") {
        c.layout = it->second;
        c.wire = encoding == "cdr" ? RosWire::Cdr : RosWire::Ros1;
      }
    }
    // Channels come again in the summary, the same.
    const auto [it, added] = channels_.emplace(id, c);
    if (!added && it->second.topic != c.topic) {
      in.fail(fmt::format("channel {} is declared for '{}' and for '{}'", id, it->second.topic, c.topic));
    }
    if (added) topics_.declare(c.topic, type);
  }

  void message(CheckedBytes& in) {
    const auto id = in.number<std::uint16_t>("the message's channel id");
    in.take(4 + 8 + 8, "the message's sequence, log time and publish time");
    const auto it = channels_.find(id);
    if (it == channels_.end()) in.fail(fmt::format("a message of channel {}, which no record declared before it", id));
    topics_.message(it->second.topic, it->second.layout, it->second.wire, in.take(in.left(), "the message"));
  }

  void chunk(CheckedBytes& in) {
    in.take(16, "the chunk's start and end times");
    const auto size = in.number<std::uint64_t>("the chunk's uncompressed size");
    const auto crc = in.number<std::uint32_t>("the chunk's CRC");
    const std::string_view compression = sized(in, "the chunk's compression");
    const std::string_view data = in.take(in.number<std::uint64_t>("the chunk's records' length"), "the chunk's records");
    if (size > kMaxInputFileBytes) in.fail(fmt::format("a chunk of {} bytes uncompressed, more than aesim reads in one", size));
    ++chunks_;
    std::string plain;
    if (compression.empty()) {
      if (size != data.size()) in.fail(fmt::format("an uncompressed chunk of {} bytes says it holds {}", data.size(), size));
    } else {
      const auto how = block_compression_named(compression);
      if (!how || *how == BlockCompression::Bz2) {
        in.fail(fmt::format("a chunk compressed with '{}' (MCAP's writers use lz4 or zstd)", compression));
      }
      try {
        plain = uncompressed_block(*how, data, size, "chunk");
      } catch (const BlockError& e) {
        in.fail(e.what());
      }
    }
    const std::string_view records_of = compression.empty() ? data : std::string_view(plain);
    if (crc != 0) {
      const auto sum = static_cast<std::uint32_t>(crc32_z(crc32_z(0, nullptr, 0), reinterpret_cast<const Bytef*>(records_of.data()),
                                                          records_of.size()));
      if (sum != crc) in.fail(fmt::format("chunk {}'s records do not match their CRC32 (0x{:08x}, the file says 0x{:08x})", chunks_, sum, crc));
    }
    records(records_of, fmt::format("chunk {}{}", chunks_, compression.empty() ? "" : " uncompressed"), 0, false);
  }

  std::string label_;
  std::map<std::uint16_t, RosEventLayout> schemas_;
  std::map<std::uint16_t, std::string> names_;
  std::map<std::uint16_t, McapChannel> channels_;
  RosEventTopics& topics_;
  std::size_t chunks_ = 0;
};

}  // namespace

void read_mcap_topics(const std::string& data, const std::string& label, RosEventTopics& topics) {
  McapReader(topics, label).read(data);
}

PolarityRecording decode_mcap(const std::string& data, const std::string& label) {
  RosEventTopics topics(label);
  read_mcap_topics(data, label, topics);
  return topics.result();
}

}  // namespace aesim
