// ROS 1 bags (.bag) laid out byte by byte from the ROS wiki's Bags/Format/2.0: the records rosbag
// writes (bag header, chunks of connections and messages, then the index, the connections again
// and the chunk infos), chunks stored plain or compressed as rosbag does (bzlib's buffer calls and
// an LZ4 frame), and the messages of dvs_msgs/EventArray and event_camera_msgs/EventPacket
// serialized as ROS serializes them (little-endian numbers, a 4-byte length before a string or an
// array).
#include <bzlib.h>
#include <lz4frame.h>

#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/event_files/event_file.hpp"
#include "aesim/event_files/event_formats.hpp"
#include "support/recorded_events.hpp"

namespace aesim {
namespace {

using testing::expect_events;
using testing::little;
using testing::noted;

const std::string kEventArrayMd5 = "5e8beee5a6c107e504c2e78903c224b8";
const std::string kEventPacketMd5 = "8a6101b351a64529ac77bd8b71074e52";
const std::string kImuMd5 = "6a62c6daae103f4ff57a132d6f95cec2";

// A length-prefixed string or byte array, as ROS serializes one and as a header field is stored.
std::string sized(const std::string& s) { return little<std::uint32_t>(static_cast<std::uint32_t>(s.size())) + s; }

std::string field(const std::string& name, const std::string& value) { return sized(name + "=" + value); }

// A record: its header's fields, then its data, each after its 4-byte length.
std::string record(const std::vector<std::string>& fields, const std::string& data) {
  std::string header;
  for (const std::string& f : fields) header += f;
  return sized(header) + sized(data);
}

std::string op(std::uint8_t code) { return field("op", std::string(1, static_cast<char>(code))); }

std::string connection(std::uint32_t id, const std::string& topic, const std::string& type, const std::string& md5) {
  const std::string about = field("topic", topic) + field("type", type) + field("md5sum", md5) +
                            field("message_definition", "(the .msg text)");
  return record({op(7), field("conn", little(id)), field("topic", topic)}, about);
}

std::string message(std::uint32_t id, std::uint32_t sec, const std::string& data) {
  return record({op(2), field("conn", little(id)), field("time", little<std::uint32_t>(sec) + little<std::uint32_t>(0))}, data);
}

// std_msgs/Header: seq, stamp (seconds, nanoseconds), frame_id.
std::string ros_header(std::uint32_t seq) { return little(seq) + little<std::uint32_t>(1473347265) + little<std::uint32_t>(0) + sized("cam0"); }

struct BagEvent {
  std::uint16_t x, y;
  std::uint32_t sec, nsec;
  bool on;
};

// dvs_msgs/EventArray: header, height, width, then the events (x, y, ts, polarity).
std::string event_array(std::uint32_t width, std::uint32_t height, const std::vector<BagEvent>& events) {
  std::string out = ros_header(0) + little(height) + little(width) + little<std::uint32_t>(static_cast<std::uint32_t>(events.size()));
  for (const BagEvent& e : events) out += little(e.x) + little(e.y) + little(e.sec) + little(e.nsec) + little<std::uint8_t>(e.on);
  return out;
}

// event_camera_msgs/EventPacket: header, height, width, seq, time_base, encoding, is_bigendian,
// then the camera's words.
std::string event_packet(const std::string& encoding, const std::string& words) {
  return ros_header(0) + little<std::uint32_t>(8) + little<std::uint32_t>(40) + little<std::uint64_t>(0) +
         little<std::uint64_t>(0) + sized(encoding) + little<std::uint8_t>(0) + sized(words);
}

std::string bag_header(std::uint32_t connections, std::uint32_t chunks, const std::string& extra = "") {
  return record({op(3), field("index_pos", little<std::uint64_t>(0)), field("conn_count", little(connections)),
                 field("chunk_count", little(chunks)), extra},
                std::string(64, ' '));
}

std::string compressed(const std::string& plain, const std::string& how) {
  if (how == "bz2") {
    std::string out(plain.size() + plain.size() / 100 + 600, '\0');
    unsigned int size = static_cast<unsigned int>(out.size());
    EXPECT_EQ(BZ2_bzBuffToBuffCompress(out.data(), &size, const_cast<char*>(plain.data()), static_cast<unsigned int>(plain.size()), 9, 0, 0), BZ_OK);
    out.resize(size);
    return out;
  }
  if (how == "lz4") {
    std::string out(LZ4F_compressFrameBound(plain.size(), nullptr), '\0');
    const std::size_t size = LZ4F_compressFrame(out.data(), out.size(), plain.data(), plain.size(), nullptr);
    EXPECT_FALSE(LZ4F_isError(size));
    out.resize(size);
    return out;
  }
  return plain;
}

std::string chunk(const std::string& records, const std::string& how) {
  return record({op(5), field("compression", how), field("size", little<std::uint32_t>(static_cast<std::uint32_t>(records.size())))},
                compressed(records, how));
}

// What rosbag writes after the chunks: an index record a connection, the connections again, one
// chunk info a chunk. A reader in file order passes over them.
std::string index_section(const std::vector<std::string>& connections) {
  std::string out = record({op(4), field("ver", little<std::uint32_t>(1)), field("conn", little<std::uint32_t>(0)),
                            field("count", little<std::uint32_t>(0))},
                           "");
  for (const std::string& c : connections) out += c;
  return out + record({op(6), field("ver", little<std::uint32_t>(1)), field("chunk_pos", little<std::uint64_t>(4117)),
                       field("start_time", little<std::uint64_t>(0)), field("end_time", little<std::uint64_t>(0)),
                       field("count", little<std::uint32_t>(0))},
                      "");
}

const std::string kMagic = "#ROSBAG V2.0\n";

EventRecording read_bag(const std::string& bytes) { return decode_events(bytes, "test.bag", EventFileFormat::RosBag); }

void expect_refused(const std::string& bytes, const std::string& words) {
  testing::expect_refused_saying([&] { read_bag(bytes); }, words);
}

// A DVS recorded under ROS: its event topic beside an IMU, two messages of events whose second
// starts before the first ends (stamps are the camera's, the messages cut where the driver sends),
// each chunk stored plain, bz2 and lz4.
TEST(RosBags, TheEventArrayTopicIsReadInTimeOrderWithItsArrayWhateverTheChunksCompression) {
  const std::string conns = connection(0, "/dvs/events", "dvs_msgs/EventArray", kEventArrayMd5) +
                            connection(1, "/dvs/imu", "sensor_msgs/Imu", kImuMd5);
  const std::string records =
      conns +
      message(0, 1473347265, event_array(240, 180, {{0, 0, 1473347265, 120004999, true}, {239, 179, 1473347265, 120010000, false}})) +
      message(1, 1473347265, std::string(300, '\x07')) +
      message(0, 1473347265, event_array(240, 180, {{5, 6, 1473347265, 120008000, true}, {7, 8, 1473347266, 0, false}}));
  for (const std::string how : {"none", "bz2", "lz4"}) {
    SCOPED_TRACE(how);
    const EventRecording rec = read_bag(kMagic + bag_header(2, 1) + chunk(records, how) + index_section({conns}));
    const std::int64_t s = 1473347265LL * 1000000;
    // 120004999 ns is 120004 whole microseconds: stamps are kept as whole microseconds, cut down.
    expect_events(rec, {{s + 120004, 0, 0, true}, {s + 120008, 5, 6, true}, {s + 120010, 239, 179, false}, {s + 1000000, 7, 8, false}});
    EXPECT_EQ(rec.width, 240);
    EXPECT_EQ(rec.height, 180);
    EXPECT_TRUE(rec.size_recorded);
    EXPECT_EQ(rec.reordered, 1u);
    EXPECT_TRUE(noted(rec, "1 messages of /dvs/imu (sensor_msgs/Imu, 300 bytes)"));
  }
}

// MVSEC's bags hold both cameras of its stereo rig; the left one is read (first by name, as the
// HDF5 reader takes /davis/left), whatever order the connections come in, and the right counted.
TEST(RosBags, OfSeveralEventTopicsTheFirstByNameIsReadAndTheOthersCounted) {
  const std::string records = connection(0, "/davis/right/events", "dvs_msgs/EventArray", kEventArrayMd5) +
                              connection(1, "/davis/left/events", "prophesee_event_msgs/EventArray", kEventArrayMd5) +
                              message(0, 1, event_array(346, 260, {{1, 1, 1, 0, true}})) +
                              message(1, 1, event_array(346, 260, {{2, 3, 1, 5000, false}})) +
                              message(0, 1, event_array(346, 260, {{1, 1, 1, 9000, true}}));
  const EventRecording rec = read_bag(kMagic + bag_header(2, 1) + chunk(records, "none"));
  expect_events(rec, {{1000005, 2, 3, false}});
  EXPECT_EQ(rec.width, 346);
  EXPECT_TRUE(noted(rec, "2 messages of /davis/right/events (aesim reads one event topic, /davis/left/events)"));
}

// metavision_driver's packets: the camera's EVT 3.0 words cut wherever a packet filled, here
// between a vector's base and the vector, and inside a word. Read as one stream, as the camera
// wrote it (a time-high word in one packet still times the events of the next).
TEST(RosBags, EventPacketsOfEvt3AreOneStreamOfTheCamerasWords) {
  const testing::CutEvt3Words c = testing::cut_evt3_words();
  const std::string conns = connection(4, "/event_camera/events", "event_camera_msgs/EventPacket", kEventPacketMd5);
  const std::string records = conns + message(4, 1, event_packet("evt3", c.words.substr(0, c.first_cut))) +
                              message(4, 1, event_packet("evt3", c.words.substr(c.first_cut, c.second_cut - c.first_cut))) +
                              message(4, 1, event_packet("evt3", c.words.substr(c.second_cut)));
  const EventRecording rec = read_bag(kMagic + bag_header(1, 1) + chunk(records, "lz4") + index_section({conns}));
  expect_events(rec, c.events);
  EXPECT_EQ(rec.width, 40);
  EXPECT_EQ(rec.height, 8);
}

TEST(RosBags, MalformedAndUnreadableBagsAreOneLineErrors) {
  const std::string events = connection(0, "/dvs/events", "dvs_msgs/EventArray", kEventArrayMd5);
  const std::string one = message(0, 1, event_array(240, 180, {{1, 2, 1, 0, true}}));
  const std::string good = kMagic + bag_header(1, 1) + chunk(events + one, "none");
  ASSERT_EQ(read_bag(good).events.size(), 1u);

  expect_refused("#ROSRECORD V1.2\n" + std::string(40, '\0'), "a ROS bag of 'ROSRECORD V1.2' (aesim reads version 2.0)");
  expect_refused("t x y p\n", "not a ROS bag");
  expect_refused(good.substr(0, good.size() - 5), "runs past the end");
  expect_refused(kMagic + bag_header(1, 1, field("encryptor", "rosbag/AesCbcEncryptor")) + chunk(events + one, "none"),
                 "an encrypted bag (rosbag/AesCbcEncryptor)");
  expect_refused(kMagic + bag_header(1, 1) + chunk(connection(1, "/dvs/imu", "sensor_msgs/Imu", kImuMd5) + message(1, 1, "x"), "none"),
                 "no topic of dvs_msgs/EventArray's or event_camera_msgs/EventPacket's layout (the bag holds /dvs/imu (sensor_msgs/Imu))");
  expect_refused(kMagic + bag_header(1, 1) + chunk(one + events, "none"), "a message of connection 0, which no record declared before it");
  expect_refused(kMagic + bag_header(1, 1) + sized(op(3) + sized("index_pos")) + sized(""), "has no '='");
  // Chunks: a size that is not the bytes', a size past what aesim takes (refused before anything is
  // allocated), compressed bytes that are not what they say, a compression rosbag does not write.
  const std::string plain = events + one;
  const auto chunk_saying = [&](const std::string& how, std::uint32_t size, const std::string& data) {
    return kMagic + bag_header(1, 1) + record({op(5), field("compression", how), field("size", little(size))}, data);
  };
  expect_refused(chunk_saying("none", static_cast<std::uint32_t>(plain.size() + 1), plain), "an uncompressed chunk of");
  expect_refused(chunk_saying("bz2", 4000000000u, "BZh9"), "a chunk of 4000000000 bytes, more than aesim reads in one");
  expect_refused(chunk_saying("bz2", static_cast<std::uint32_t>(plain.size()), "BZh9garbage"), "a bz2 chunk does not uncompress");
  expect_refused(chunk_saying("lz4", static_cast<std::uint32_t>(plain.size()), "garbage"), "an lz4 chunk");
  expect_refused(chunk_saying("lz4", static_cast<std::uint32_t>(plain.size() + 9), compressed(plain, "lz4")),
                 "an lz4 chunk does not uncompress to its");
  expect_refused(chunk_saying("zstd", static_cast<std::uint32_t>(plain.size()), plain), "a chunk compressed with 'zstd'");
  // Messages: a count the bytes do not hold, a stamp's nanoseconds past a second, an array that
  // changes size, packets in an encoding aesim does not decode.
  std::string short_count = event_array(240, 180, {{1, 2, 1, 0, true}});
  short_count.pop_back();
  expect_refused(kMagic + bag_header(1, 1) + chunk(events + message(0, 1, short_count), "none"), "1 events take 13 bytes");
  expect_refused(kMagic + bag_header(1, 1) + chunk(events + message(0, 1, event_array(240, 180, {{1, 2, 1, 1000000000u, true}})), "none"),
                 "event 0 has 1000000000 nanoseconds past its second");
  expect_refused(kMagic + bag_header(1, 1) + chunk(events + one + message(0, 1, event_array(346, 260, {})), "none"),
                 "the array is 346x260, where the topic's messages before said 240x180");
  expect_refused(kMagic + bag_header(1, 1) +
                     chunk(connection(0, "/events", "event_camera_msgs/EventPacket", kEventPacketMd5) + message(0, 1, event_packet("evt4", "12345678")), "none"),
                 "/events carries events encoded 'evt4' (aesim reads 'evt3', 'mono', 'libcaer' and 'libcaer_cmp' packets)");
}

}  // namespace
}  // namespace aesim
