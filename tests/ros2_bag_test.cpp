// ROS 2 bags: MCAP files laid out record by record from mcap.dev's specification (magic, header,
// schemas, channels, messages in chunks plain or compressed, data end, summary, footer), rosbag2's
// SQLite tables made through SQLite itself, and messages serialized as CDR lays them out (an
// encapsulation header, then each number at a multiple of its size from the header's end), by a
// writer of the test's own whose padding is checked against a count made by hand.
#include <lz4frame.h>
#include <sqlite3.h>
#include <zlib.h>
#include <zstd.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/event_files/event_file.hpp"
#include "aesim/event_files/event_formats.hpp"
#include "aesim/event_files/ros_event_messages.hpp"
#include "support/recorded_events.hpp"
#include "support/temp_dir_test.hpp"

namespace aesim {
namespace {

using testing::Cd;
using testing::expect_events;
using testing::LittleEndianBytes;
using testing::little;
using testing::noted;

// A CDR message: XCDR1 little-endian unless said (big-endian, or XCDR2's alignment of at most 4).
class Cdr {
 public:
  explicit Cdr(bool big_endian = false, bool xcdr2 = false) : big_(big_endian), max_align_(xcdr2 ? 4 : 8) {
    const char kind = static_cast<char>((xcdr2 ? 0x06 : 0x00) | (big_endian ? 0 : 1));
    bytes_ = std::string("\0", 1) + kind + std::string(2, '\0');
  }
  template <typename T>
  Cdr& put(T v) {
    const std::size_t align = std::min(sizeof(T), max_align_);
    while ((bytes_.size() - 4) % align != 0) bytes_ += '\0';
    std::string b = little(v);
    if (big_) std::reverse(b.begin(), b.end());
    bytes_ += b;
    return *this;
  }
  Cdr& text(const std::string& s) {
    put<std::uint32_t>(static_cast<std::uint32_t>(s.size() + 1));
    bytes_ += s;
    bytes_ += '\0';
    return *this;
  }
  Cdr& raw(const std::string& s) {
    bytes_ += s;
    return *this;
  }
  // std_msgs/Header: a builtin_interfaces/Time and the frame id.
  Cdr& header(std::int32_t sec) { return put<std::int32_t>(sec).put<std::uint32_t>(0).text("cam0"); }
  const std::string& bytes() const { return bytes_; }

 private:
  bool big_;
  std::size_t max_align_;
  std::string bytes_;
};

struct BagEvent {
  std::uint16_t x, y;
  std::int32_t sec;
  std::uint32_t nsec;
  bool on;
};

std::string event_array(const std::vector<BagEvent>& events, std::uint32_t width = 240, std::uint32_t height = 180, bool big = false) {
  Cdr m(big);
  m.header(1700000000).put<std::uint32_t>(height).put<std::uint32_t>(width).put<std::uint32_t>(static_cast<std::uint32_t>(events.size()));
  for (const BagEvent& e : events) m.put(e.x).put(e.y).put(e.sec).put(e.nsec).put<std::uint8_t>(e.on);
  return m.bytes();
}

std::string event_packet(const std::string& words, bool xcdr2 = false, const std::string& encoding = "evt3",
                         std::uint64_t time_base = 0) {
  Cdr m(false, xcdr2);
  m.header(1700000000).put<std::uint32_t>(8).put<std::uint32_t>(40).put<std::uint64_t>(0).put<std::uint64_t>(time_base);
  m.text(encoding).put<std::uint8_t>(0).put<std::uint32_t>(static_cast<std::uint32_t>(words.size())).raw(words);
  return m.bytes();
}

const std::string kSeparator = "\n" + std::string(80, '=') + "\n";
const std::string kHeaderDefinition = kSeparator + "MSG: std_msgs/Header\n# Standard metadata\nbuiltin_interfaces/Time stamp\nstring frame_id\n" +
                                      kSeparator + "MSG: builtin_interfaces/Time\nint32 sec\nuint32 nanosec\n";
const std::string kEventArrayDefinition = "std_msgs/Header header\nuint32 height\nuint32 width\nEvent[] events\n" + kHeaderDefinition +
                                          kSeparator + "MSG: dvs_msgs/Event\nuint16 x\nuint16 y\nbuiltin_interfaces/Time ts\nbool polarity\n";
const std::string kEventPacketDefinition =
    "std_msgs/Header header\nuint32 height\nuint32 width\nuint64 seq\nuint64 time_base\nstring encoding\nbool is_bigendian\nuint8[] events\n" +
    kHeaderDefinition;

// MCAP's records: an opcode, the content's 8-byte length, the content.
std::string sized(const std::string& s) { return little<std::uint32_t>(static_cast<std::uint32_t>(s.size())) + s; }
std::string mcap_record(std::uint8_t op, const std::string& content) {
  return std::string(1, static_cast<char>(op)) + little<std::uint64_t>(content.size()) + content;
}
std::string schema(std::uint16_t id, const std::string& name, const std::string& definition, const std::string& encoding = "ros2msg") {
  return mcap_record(0x03, little(id) + sized(name) + sized(encoding) + sized(definition));
}
std::string channel(std::uint16_t id, std::uint16_t schema_id, const std::string& topic, const std::string& encoding = "cdr") {
  // An empty metadata map: its 4-byte length, 0.
  return mcap_record(0x04, little(id) + little(schema_id) + sized(topic) + sized(encoding) + little<std::uint32_t>(0));
}
std::string message(std::uint16_t channel_id, const std::string& data) {
  return mcap_record(0x05, little(channel_id) + little<std::uint32_t>(0) + little<std::uint64_t>(7) + little<std::uint64_t>(7) + data);
}

std::string compressed(const std::string& plain, const std::string& how) {
  std::string out;
  if (how == "lz4") {
    out.resize(LZ4F_compressFrameBound(plain.size(), nullptr));
    out.resize(LZ4F_compressFrame(out.data(), out.size(), plain.data(), plain.size(), nullptr));
  } else if (how == "zstd") {
    out.resize(ZSTD_compressBound(plain.size()));
    out.resize(ZSTD_compress(out.data(), out.size(), plain.data(), plain.size(), 3));
  } else {
    out = plain;
  }
  return out;
}

std::uint32_t crc_of(const std::string& s) {
  return static_cast<std::uint32_t>(crc32_z(crc32_z(0, nullptr, 0), reinterpret_cast<const Bytef*>(s.data()), s.size()));
}

std::string chunk(const std::string& records, const std::string& how, std::uint32_t crc) {
  return mcap_record(0x06, little<std::uint64_t>(7) + little<std::uint64_t>(7) + little<std::uint64_t>(records.size()) + little(crc) +
                               sized(how) + little<std::uint64_t>(compressed(records, how).size()) + compressed(records, how));
}
std::string chunk(const std::string& records, const std::string& how) { return chunk(records, how, crc_of(records)); }

const std::string kMagic("\x89MCAP0\r\n", 8);

// A whole file: the header, `data`, the data end, `summary`, the footer.
std::string mcap(const std::string& data, const std::string& summary = "") {
  return kMagic + mcap_record(0x01, sized("ros2") + sized("aesim's test")) + data + mcap_record(0x0F, little<std::uint32_t>(0)) + summary +
         mcap_record(0x02, little<std::uint64_t>(0) + little<std::uint64_t>(0) + little<std::uint32_t>(0)) + kMagic;
}

EventRecording read_mcap(const std::string& bytes) { return decode_events(bytes, "test.mcap", EventFileFormat::Mcap); }

void expect_refused(const std::string& bytes, EventFileFormat format, const std::string& words) {
  testing::expect_refused_saying([&] { decode_events(bytes, "test.bag", format); }, words);
}

// The test's CDR writer pads as CDR's rule says, counted by hand (offsets after the 4-byte
// encapsulation header): the stamp (8 bytes) and the frame id (4 + "cam0" and its NUL) end at 17;
// height starts at 20, the events' count at 28, the first event at 32 (x, y, seconds at 36,
// nanoseconds, polarity at 44); the second's x at 46 (a multiple of 2, after a byte of padding),
// its seconds at 52 (of 4, after two more), its polarity at 60: 61 bytes and the header's 4.
TEST(Ros2Bags, TheTestsCdrWriterPadsAsCountedByHand) {
  EXPECT_EQ(event_array({{1, 2, 3, 4, true}, {5, 6, 7, 8, false}}).size(), 65u);
}

// A DVS recorded under ROS 2 (rosbag2's MCAP storage): its event topic beside a temperature, two
// messages whose second starts before the first ends, one message outside any chunk, the schemas
// and channels again in the summary; chunks stored plain, lz4 and zstd.
TEST(Ros2Bags, EventArraysInCdrAreReadInTimeOrderWhateverTheChunksCompression) {
  const std::string declared = schema(1, "dvs_msgs/msg/EventArray", kEventArrayDefinition) +
                               schema(2, "sensor_msgs/msg/Temperature", "std_msgs/Header header\nfloat64 temperature\nfloat64 variance\n") +
                               channel(1, 1, "/dvs/events") + channel(2, 2, "/temperature");
  const std::string records = declared +
                              message(1, event_array({{0, 0, 1700000000, 120004999, true}, {239, 179, 1700000000, 120010000, false}})) +
                              message(2, std::string(28, '\x01'));
  const std::string later = message(1, event_array({{5, 6, 1700000000, 120008000, true}, {7, 8, 1700000001, 0, false}}));
  for (const std::string how : {"", "lz4", "zstd"}) {
    SCOPED_TRACE(how);
    const EventRecording rec = read_mcap(mcap(chunk(records, how) + later, declared));
    const std::int64_t s = 1700000000LL * 1000000;
    // 120004999 ns is 120004 whole microseconds: stamps are kept as whole microseconds, cut down.
    expect_events(rec, {{s + 120004, 0, 0, true}, {s + 120008, 5, 6, true}, {s + 120010, 239, 179, false}, {s + 1000000, 7, 8, false}});
    EXPECT_EQ(rec.width, 240);
    EXPECT_EQ(rec.height, 180);
    EXPECT_EQ(rec.reordered, 1u);
    EXPECT_TRUE(noted(rec, "1 messages of /temperature (sensor_msgs/msg/Temperature, 28 bytes)"));
  }
}

// metavision_driver's packets under ROS 2: the camera's EVT 3.0 words cut between a vector's base
// and the vector and inside a word, read as one stream; the packets in XCDR1 (seq at a multiple
// of 8) and XCDR2 (of 4), and an EventArray in big-endian CDR, give the same events.
TEST(Ros2Bags, EventPacketsAreOneStreamAndEveryCdrByteOrderAndAlignmentReads) {
  const testing::CutEvt3Words c = testing::cut_evt3_words();
  for (const bool xcdr2 : {false, true}) {
    SCOPED_TRACE(xcdr2);
    // seq at 28 (XCDR2) or 32 (XCDR1) after the 4-byte header, so the words' length at 56 or 60.
    EXPECT_EQ(event_packet("", xcdr2).size(), xcdr2 ? 64u : 68u);
    const std::string records = schema(3, "event_camera_msgs/msg/EventPacket", kEventPacketDefinition) + channel(9, 3, "/event_camera/events") +
                                message(9, event_packet(c.words.substr(0, c.first_cut), xcdr2)) +
                                message(9, event_packet(c.words.substr(c.first_cut, c.second_cut - c.first_cut), xcdr2)) +
                                message(9, event_packet(c.words.substr(c.second_cut), xcdr2));
    const EventRecording rec = read_mcap(mcap(chunk(records, "zstd")));
    expect_events(rec, c.events);
    EXPECT_EQ(rec.width, 40);
    EXPECT_EQ(rec.height, 8);
  }
  const std::string declared = schema(1, "dvs_msgs/msg/EventArray", kEventArrayDefinition) + channel(1, 1, "/events");
  const EventRecording big =
      read_mcap(mcap(declared + message(1, event_array({{300, 2, 2, 500000000, true}, {3, 200, 4, 7000, false}}, 346, 260, true))));
  expect_events(big, {{2500000, 300, 2, true}, {4000007, 3, 200, false}});
  // builtin_interfaces/Time's seconds are signed: -1 s is before the epoch, not 2^32 - 1 s after.
  expect_refused(mcap(declared + message(1, event_array({{1, 1, -1, 0, true}}, 346, 260, true))), EventFileFormat::Mcap,
                 "event 0 has a negative timestamp (-1000000 us)");
}

// event_camera_codecs' encodings of 8-byte events, stamped from their message's time_base (ns) and
// kept as whole microseconds: "mono" (event_array_msgs' README: bit 63 ON, y in bits 48-62, x in
// 32-47, the nanoseconds in 0-31), on event_array_msgs/EventArray (EventPacket's fields, told by
// the name alone); "libcaer" (libcaer's polarity event: x in bits 17-31, y in 2-16, the polarity
// in bit 1, the valid mark in bit 0; then its 31-bit microseconds, whose fall within a message
// adds 2^31 us). A topic of "trigger" packets is passed over for the events'. Worked by hand.
TEST(Ros2Bags, MonoAndLibcaerPacketsAreStampedFromTheirTimeBase) {
  const auto mono = [](std::uint64_t ns, std::uint64_t x, std::uint64_t y, bool on) {
    return little<std::uint64_t>((std::uint64_t(on) << 63) | (y << 48) | (x << 32) | ns);
  };
  const std::string monos = schema(3, "event_array_msgs/msg/EventArray", "") + channel(9, 3, "/event_camera/events") +
                            message(9, event_packet(mono(1500, 3, 4, true) + mono(2999, 5, 6, false), false, "mono", 1000000000)) +
                            message(9, event_packet(mono(0, 7, 2, true), false, "mono", 1000010000));
  const std::string triggers = channel(10, 3, "/event_camera/aux") + message(10, event_packet(mono(5, 0, 0, true) + mono(9, 0, 0, false), false, "trigger"));
  const EventRecording m = read_mcap(mcap(monos + triggers));
  expect_events(m, {{1000001, 3, 4, true}, {1000002, 5, 6, false}, {1000010, 7, 2, true}});
  EXPECT_TRUE(testing::noted(m, "2 external trigger events of /event_camera/aux"));
  expect_refused(mcap(schema(3, "event_array_msgs/msg/EventArray", "") + triggers), EventFileFormat::Mcap,
                 "/event_camera/aux carries external triggers alone");

  const auto libcaer = [](std::uint32_t x, std::uint32_t y, bool on, std::int32_t us) {
    return little<std::uint32_t>((x << 17) | (y << 2) | (std::uint32_t(on) << 1) | 1u) + little<std::int32_t>(us);
  };
  const std::string declared = schema(3, "event_camera_msgs/msg/EventPacket", kEventPacketDefinition) + channel(9, 3, "/events");
  const EventRecording c = read_mcap(mcap(declared +
                                          message(9, event_packet(libcaer(10, 1, true, 2147483000) + libcaer(39, 7, false, 100), false,
                                                                  "libcaer", 5000000000)) +
                                          message(9, event_packet(libcaer(12, 3, true, 5), false, "libcaer", 2152500000000))));
  // 5 s + 2,147,483,000 us; then past the fall, 5 s + 2^31 us + 100 us; then the next time_base.
  expect_events(c, {{2152483000, 10, 1, true}, {2152483748, 39, 7, false}, {2152500005, 12, 3, true}});
  expect_refused(mcap(declared + message(9, event_packet(libcaer(1, 1, true, -1), false, "libcaer"))), EventFileFormat::Mcap,
                 "libcaer event 0 stamped -1 us (a negative stamp)");
  expect_refused(mcap(declared + message(9, event_packet("1234567", false, "mono"))), EventFileFormat::Mcap,
                 "7 bytes of 'mono' events, not a whole number of 8-byte events");
}

// libcaer_driver's default encoding, "libcaer_cmp" (event_camera_codecs' libcaer_cmp_types.h: a
// 16-bit word of a 4-bit code over 12 bits), worked by hand on a 40x8 array: every code, a
// vector's rows, events outside the array and words of no event left out and counted, the time
// starting again at each message while the column runs on (the codec's decoder keeps it).
TEST(Ros2Bags, CompressedLibcaerPacketsAreReadWordByWord) {
  const auto word = [](unsigned code, unsigned rest) { return little<std::uint16_t>(static_cast<std::uint16_t>((code << 12) | rest)); };
  const unsigned on = 1u << 11;
  const std::string first = word(2, 3) + word(3, on | 2) +         // x 3; (3, 2) ON at 0 us
                            word(1, 5) + word(4, 0) + word(5, 0x85) +  // at 5 us, rows 0, 2 and 7 OFF from base row 0
                            word(2, 39) + word(3, on | 7) +          // (39, 7) ON
                            word(2, 40) + word(3, on | 1) +          // column 40: outside
                            word(0, 1) + word(2, 10) + word(3, 9) +  // at 4096 + 5 us; row 9: outside
                            word(4, on | 4) + word(5, 0x0F) +        // rows 4-7 ON
                            word(5, 0x01) +                          // row 12 (the base moved on 8): outside
                            word(6, 0xABC) + word(15, 0);            // VECT_12 and an unassigned code
  const std::string second = word(3, 3);  // (10, 3) OFF at the next message's own time_base
  const std::string declared = schema(3, "event_camera_msgs/msg/EventPacket", kEventPacketDefinition) + channel(9, 3, "/dvxplorer/events");
  const EventRecording rec = read_mcap(mcap(declared + message(9, event_packet(first, false, "libcaer_cmp", 5000000000)) +
                                            message(9, event_packet(second, false, "libcaer_cmp", 5000010000))));
  const std::int64_t t = 5000000;
  expect_events(rec, {{t, 3, 2, true},
                      {t + 5, 3, 0, false},
                      {t + 5, 3, 2, false},
                      {t + 5, 3, 7, false},
                      {t + 5, 39, 7, true},
                      {t + 10, 10, 3, false},
                      {t + 4101, 10, 4, true},
                      {t + 4101, 10, 5, true},
                      {t + 4101, 10, 6, true},
                      {t + 4101, 10, 7, true}});
  EXPECT_TRUE(noted(rec, "3 'libcaer_cmp' events of /dvxplorer/events outside its 40x8 array"));
  EXPECT_TRUE(noted(rec, "2 'libcaer_cmp' words of /dvxplorer/events that are no event"));
  expect_refused(mcap(declared + message(9, event_packet("123", false, "libcaer_cmp"))), EventFileFormat::Mcap,
                 "3 bytes of 'libcaer_cmp' words, not a whole number of 16-bit words");
}

// libcaer_cmp as libcaer_driver's message_converter.cpp writes a camera's packets: per packet an
// ADDR_X of its first event; per event a TIME_HIGH where the microseconds since the message's
// first event change bits 12-23, a TIME_LOW where bits 0-11 change, an ADDR_X where the column
// changes; events of one column, time and polarity within one block of 8 rows gathered, and
// written as an ADDR_Y when one, as VECT_BASE_Y and VECT_8 when several. 3,000 events in three
// messages (a column run by run, as a DVS's readout gives them) read back as they went in.
TEST(Ros2Bags, CompressedLibcaerPacketsReadBackAsTheDriverWroteThem) {
  struct Ev {
    std::uint64_t us;
    std::uint16_t x, y;
    bool on;
  };
  const auto encode = [](const std::vector<Ev>& events) {
    std::string w;
    const auto put = [&w](unsigned code, unsigned rest) { w += little<std::uint16_t>(static_cast<std::uint16_t>((code << 12) | rest)); };
    const std::uint64_t t0 = events.front().us;
    std::uint64_t high = 0, low = 0;
    unsigned x = events.front().x, block = 0xFFFF, mask = 0, first_y = 0;
    int polarity = -1;
    const auto flush = [&] {
      if (mask == 0) return;
      const unsigned rest_pol = polarity == 1 ? 1u << 11 : 0u;
      if ((mask & (mask - 1)) == 0) {
        put(3, rest_pol | first_y);
      } else {
        put(4, rest_pol | block);
        put(5, mask);
      }
      mask = 0;
    };
    put(2, x);
    for (const Ev& e : events) {
      const std::uint64_t dt = e.us - t0;
      if ((dt & 0xFFF000) != high) {
        flush();
        high = dt & 0xFFF000;
        put(0, static_cast<unsigned>(high >> 12));
      }
      if ((dt & 0xFFF) != low) {
        flush();
        low = dt & 0xFFF;
        put(1, static_cast<unsigned>(low));
      }
      if (e.x != x) {
        flush();
        x = e.x;
        put(2, x);
      }
      if (int(e.on) != polarity) {
        flush();
        polarity = e.on;
      }
      if ((e.y & ~7u) != block) {
        flush();
        block = e.y & ~7u;
      }
      if (mask == 0) first_y = e.y;
      mask |= 1u << (e.y & 7u);
    }
    flush();
    return w;
  };
  // A column's events at one time, then the next column's, times rising by 0-39 us (past 4,096 us
  // within a message, and so across TIME_HIGH words), each event's row distinct within its column
  // and time.
  std::vector<std::vector<Ev>> packets(3);
  std::uint64_t us = 1700000000000000ULL;
  std::uint32_t state = 12345;
  const auto draw = [&state](std::uint32_t n) {
    state = state * 1664525u + 1013904223u;
    return (state >> 8) % n;
  };
  for (std::vector<Ev>& p : packets) {
    while (p.size() < 1000) {
      us += draw(40);
      const auto x = static_cast<std::uint16_t>(draw(640));
      const bool on = draw(2) == 1;
      const std::uint32_t rows = 1 + draw(5), start = draw(470);
      for (std::uint32_t r = 0; r < rows; ++r) p.push_back({us, x, static_cast<std::uint16_t>(start + 2 * r), on});
    }
  }
  const std::string declared = schema(3, "event_camera_msgs/msg/EventPacket", kEventPacketDefinition) + channel(9, 3, "/events");
  std::string messages;
  std::vector<Cd> expected;
  for (const std::vector<Ev>& p : packets) {
    Cdr m(false, false);
    m.header(1700000000).put<std::uint32_t>(480).put<std::uint32_t>(640).put<std::uint64_t>(0).put<std::uint64_t>(p.front().us * 1000);
    const std::string words = encode(p);
    m.text("libcaer_cmp").put<std::uint8_t>(0).put<std::uint32_t>(static_cast<std::uint32_t>(words.size())).raw(words);
    messages += message(9, m.bytes());
    for (const Ev& e : p) expected.push_back({static_cast<std::int64_t>(e.us), e.x, e.y, e.on});
  }
  const EventRecording rec = read_mcap(mcap(declared + messages));
  // Events of one time come out by column, then row within each block of 8 (a vector's order).
  std::stable_sort(expected.begin(), expected.end(), [](const Cd& a, const Cd& b) { return a.t_us < b.t_us; });
  ASSERT_GT(packets[0].back().us - packets[0].front().us, 4096u);
  expect_events(rec, expected);
  EXPECT_EQ(rec.width, 640);
  EXPECT_EQ(rec.height, 480);
}

// An MCAP of ROS 1's profile holds ROS 1's messages (told by the schema's ROS 1 text); rosbag2's
// message compression makes each message's CDR a zstd frame of its own.
TEST(Ros2Bags, Ros1MessagesInMcapAndMessagesCompressedOneByOneRead) {
  std::string ros1 = little<std::uint32_t>(0) + little<std::uint32_t>(7) + little<std::uint32_t>(0) + sized("cam0") +
                     little<std::uint32_t>(180) + little<std::uint32_t>(240) + little<std::uint32_t>(1);
  ros1 += little<std::uint16_t>(3) + little<std::uint16_t>(4) + little<std::uint32_t>(7) + little<std::uint32_t>(5000) + std::string(1, '\1');
  const std::string ros1_text = "Header header\nuint32 height\nuint32 width\nEvent[] events\n" + kSeparator +
                                "MSG: dvs_msgs/Event\nuint16 x\nuint16 y\ntime ts\nbool polarity\n";
  const EventRecording one = read_mcap(mcap(schema(1, "dvs_msgs/EventArray", ros1_text, "ros1msg") + channel(1, 1, "/dvs/events", "ros1") +
                                            message(1, ros1)));
  expect_events(one, {{7000005, 3, 4, true}});
  EXPECT_EQ(one.width, 240);

  const std::string cdr = event_array({{1, 2, 3, 0, true}, {5, 6, 3, 1000, false}});
  const EventRecording packed = read_mcap(mcap(schema(1, "dvs_msgs/msg/EventArray", kEventArrayDefinition) + channel(1, 1, "/events") +
                                               message(1, compressed(cdr, "zstd"))));
  expect_events(packed, {{3000000, 1, 2, true}, {3000001, 5, 6, false}});
}

// ROS 2 gives a type no checksum: its definition decides where the bag holds one, whatever the
// package (a lab's copy of the layout), and a known name with other fields is not read as
// events; an IDL definition, which aesim does not compare, leaves the name to decide.
TEST(Ros2Bags, TheLayoutIsToldByTheDefinitionFieldByFieldOrElseByTheName) {
  EXPECT_EQ(ros_event_layout("lab_msgs/msg/Spikes", kEventArrayDefinition), RosEventLayout::EventArray);
  EXPECT_EQ(ros_event_layout("x/Packet", "# camera words\nHeader header  # stamp\nuint32 height\nuint32 width 0\nuint64 seq\n"
                                         "uint64 time_base\nstring encoding\nbool is_bigendian\nuint8 KIND=3\nuint8[] events\n"),
            RosEventLayout::EventPacket);
  // ROS 1's text of the same layout (its primitive `time`, the header's own seq).
  EXPECT_EQ(ros_event_layout("dvs_msgs/EventArray", "Header header\nuint32 height\nuint32 width\nEvent[] events\n" + kSeparator +
                                                        "MSG: std_msgs/Header\nuint32 seq\ntime stamp\nstring frame_id\n" + kSeparator +
                                                        "MSG: dvs_msgs/Event\nuint16 x\nuint16 y\ntime ts\nbool polarity\n"),
            RosEventLayout::EventArray);
  EXPECT_EQ(ros_event_layout("dvs_msgs/msg/EventArray", "std_msgs/Header header\nuint32 width\nuint32 height\nEvent[] events\n"),
            RosEventLayout::Other);
  const std::string float_x = "std_msgs/Header header\nuint32 height\nuint32 width\nEvent[] events\n" + kSeparator +
                              "MSG: dvs_msgs/Event\nfloat32 x\nuint16 y\nbuiltin_interfaces/Time ts\nbool polarity\n";
  EXPECT_EQ(ros_event_layout("dvs_msgs/msg/EventArray", float_x), RosEventLayout::Other);
  EXPECT_EQ(ros_event_layout("prophesee_event_msgs/msg/EventArray", ""), RosEventLayout::EventArray);
  EXPECT_EQ(ros_event_layout("event_camera_msgs/msg/EventPacket", ""), RosEventLayout::EventPacket);
  EXPECT_EQ(ros_event_layout("sensor_msgs/msg/Image", ""), RosEventLayout::Other);

  const std::string one = event_array({{1, 2, 3, 0, true}});
  const EventRecording copy = read_mcap(mcap(schema(1, "lab_msgs/msg/Spikes", kEventArrayDefinition) + channel(1, 1, "/spikes") + message(1, one)));
  expect_events(copy, {{3000000, 1, 2, true}});
  const EventRecording idl = read_mcap(mcap(schema(1, "dvs_msgs/msg/EventArray", "module dvs_msgs { ... };", "ros2idl") +
                                            channel(1, 1, "/events") + message(1, one)));
  expect_events(idl, {{3000000, 1, 2, true}});
  expect_refused(mcap(schema(1, "dvs_msgs/msg/EventArray", float_x) + channel(1, 1, "/events") + message(1, one)), EventFileFormat::Mcap,
                 "no topic of dvs_msgs/EventArray's or event_camera_msgs/EventPacket's layout (the bag holds /events (dvs_msgs/msg/EventArray))");
  // Messages that are not CDR (JSON here) are counted, not decoded.
  expect_refused(mcap(schema(1, "dvs_msgs/msg/EventArray", kEventArrayDefinition) + channel(1, 1, "/events", "json") + message(1, "{}")),
                 EventFileFormat::Mcap, "no topic of");
}

TEST(Ros2Bags, MalformedMcapFilesAreOneLineErrors) {
  const std::string declared = schema(1, "dvs_msgs/msg/EventArray", kEventArrayDefinition) + channel(1, 1, "/events");
  const std::string records = declared + message(1, event_array({{1, 2, 3, 0, true}}));
  const std::string good = mcap(chunk(records, "zstd"));
  ASSERT_EQ(read_mcap(good).events.size(), 1u);
  const auto refused = [](const std::string& bytes, const std::string& words) { expect_refused(bytes, EventFileFormat::Mcap, words); };
  refused("#ROSBAG V2.0\n", "not an MCAP file");
  refused("\x89MCAP1\r\n", "MCAP of major version '1' (aesim reads version '0')");
  refused("\x89MCAP\n\r\n", "MCAP of major version byte 0x0a");
  // A recording that did not end: cut inside a chunk, or before its footer.
  refused(good.substr(0, good.size() / 2), "runs past the end (a recording that did not end? `mcap recover` rewrites what it holds)");
  refused(good.substr(0, good.size() - 8 - 29), "the file ends without MCAP's footer");
  refused(good.substr(0, good.size() - 3), "MCAP's footer is not followed by its closing magic bytes");
  refused(mcap(chunk(records, "zstd", crc_of(records) ^ 1)), "chunk 1's records do not match their CRC32");
  refused(mcap(chunk(records, "bz2", 0)), "a chunk compressed with 'bz2' (MCAP's writers use lz4 or zstd)");
  refused(mcap(mcap_record(0x06, little<std::uint64_t>(0) + little<std::uint64_t>(0) + little<std::uint64_t>(records.size()) +
                                     little<std::uint32_t>(0) + sized("zstd") + little<std::uint64_t>(7) + "garbage")),
          "a zstd chunk");
  refused(mcap(mcap_record(0x06, little<std::uint64_t>(0) + little<std::uint64_t>(0) + little<std::uint64_t>(1ULL << 40) +
                                     little<std::uint32_t>(0) + sized("zstd") + little<std::uint64_t>(0))),
          "a chunk of 1099511627776 bytes uncompressed, more than aesim reads in one");
  refused(mcap(chunk(chunk(records, ""), "")), "a chunk inside a chunk");
  refused(mcap(mcap_record(0x00, "")), "a record of opcode 0");
  refused(mcap(channel(1, 4, "/events") + message(1, "")), "channel 1 names schema 4, which no record declared before it");
  refused(mcap(declared + message(2, "")), "a message of channel 2, which no record declared before it");
  refused(mcap(declared + channel(1, 1, "/other")), "channel 1 is declared for '/events' and for '/other'");
  // Messages: CDR's kinds aesim does not read (parameter lists), a string without its NUL, a count
  // the bytes cannot hold, padding past CDR's three bytes.
  std::string pl = event_array({{1, 2, 3, 0, true}});
  pl[1] = 0x03;
  refused(mcap(declared + message(1, pl)), "CDR encapsulation 0x0003 (aesim reads plain CDR and XCDR2, either byte order)");
  refused(mcap(declared + message(1, Cdr().put<std::int32_t>(0).put<std::uint32_t>(0).put<std::uint32_t>(2).raw("ab").bytes())),
          "the frame id does not end in the NUL CDR gives a string");
  refused(mcap(declared + message(1, Cdr().header(0).put<std::uint32_t>(1).put<std::uint32_t>(1).put<std::uint32_t>(1000).bytes())),
          "1000 events take at least 13000 bytes, where the message holds 0 after its count");
  refused(mcap(declared + message(1, event_array({{1, 2, 3, 0, true}}) + std::string(4, '\0'))), "4 bytes after the message's last field");
  refused(mcap(schema(3, "event_camera_msgs/msg/EventPacket", kEventPacketDefinition) + channel(9, 3, "/ev") +
               message(9, event_packet("1234", false, "evt4"))),
          "/ev carries events encoded 'evt4' (aesim reads 'evt3', 'mono', 'libcaer' and 'libcaer_cmp' packets)");
}

// rosbag2's SQLite storage as Humble writes it (schema 3: no definitions, so names decide; a
// write-ahead-log file's header) and as Jazzy does (schema 4, message_definitions: a lab's type
// name told by its definition); messages read in the order written.
class Ros2SqliteBags : public testing::TempDirTest {
 protected:
  std::string make_bag(bool definitions, bool wal) {
    const std::filesystem::path path = dir_ / "bag.db3";
    std::filesystem::remove(path);
    sqlite3* db = nullptr;
    EXPECT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
    std::string sql = std::string(wal ? "PRAGMA journal_mode=WAL;" : "") +
                      "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL, serialization_format TEXT NOT NULL,"
                      " offered_qos_profiles TEXT NOT NULL);"
                      "CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, timestamp INTEGER NOT NULL, data BLOB NOT NULL);"
                      "CREATE INDEX timestamp_idx ON messages (timestamp ASC);"
                      "INSERT INTO topics VALUES(1, '/imu', 'sensor_msgs/msg/Imu', 'cdr', '');";
    sql += definitions ? "CREATE TABLE message_definitions(id INTEGER PRIMARY KEY, topic_type TEXT NOT NULL, encoding TEXT NOT NULL,"
                         " encoded_message_definition TEXT NOT NULL, type_description_hash TEXT NOT NULL);"
                         "INSERT INTO topics VALUES(2, '/spikes', 'lab_msgs/msg/Spikes', 'cdr', '');"
                       : "INSERT INTO topics VALUES(2, '/spikes', 'dvs_msgs/msg/EventArray', 'cdr', '');";
    EXPECT_EQ(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr), SQLITE_OK) << sqlite3_errmsg(db);
    if (definitions) insert(db, "INSERT INTO message_definitions VALUES(1, 'lab_msgs/msg/Spikes', 'ros2msg', ?, 'RIHS01_0')", kEventArrayDefinition);
    // Stamps later than the second message's but written first: the order is the writing's.
    insert(db, "INSERT INTO messages(topic_id, timestamp, data) VALUES(2, 9, ?)", event_array({{10, 11, 5, 0, true}}, 346, 260));
    insert(db, "INSERT INTO messages(topic_id, timestamp, data) VALUES(1, 8, ?)", std::string(40, '\x02'));
    insert(db, "INSERT INTO messages(topic_id, timestamp, data) VALUES(2, 1, ?)", event_array({{12, 13, 4, 1000, false}}, 346, 260));
    sqlite3_close(db);
    return testing::slurp(path);
  }
  static void insert(sqlite3* db, const char* sql, const std::string& blob) {
    sqlite3_stmt* s = nullptr;
    ASSERT_EQ(sqlite3_prepare_v2(db, sql, -1, &s, nullptr), SQLITE_OK);
    sqlite3_bind_blob(s, 1, blob.data(), static_cast<int>(blob.size()), SQLITE_TRANSIENT);
    EXPECT_EQ(sqlite3_step(s), SQLITE_DONE);
    sqlite3_finalize(s);
  }
};

TEST_F(Ros2SqliteBags, AreReadAsWrittenWithTheirDefinitionsWhereTheyKeepThem) {
  for (const bool definitions : {false, true}) {
    for (const bool wal : {false, true}) {
      SCOPED_TRACE(::testing::Message() << definitions << wal);
      const std::string bytes = make_bag(definitions, wal);
      ASSERT_EQ(bytes[18], wal ? 2 : 1);  // the header's read and write versions: 2 is a write-ahead log
      const EventRecording rec = decode_events(bytes, "bag.db3", EventFileFormat::Rosbag2Sqlite);
      expect_events(rec, {{4000001, 12, 13, false}, {5000000, 10, 11, true}});
      EXPECT_EQ(rec.width, 346);
      EXPECT_TRUE(noted(rec, "1 messages of /imu (sensor_msgs/msg/Imu, 40 bytes)"));
    }
  }
}

TEST_F(Ros2SqliteBags, OtherDatabasesAndDamagedOnesAreOneLineErrors) {
  const std::string good = make_bag(false, false);
  expect_refused(good.substr(0, 15), EventFileFormat::Rosbag2Sqlite, "not an SQLite database (a ROS 2 .db3 bag is one)");
  expect_refused(good.substr(0, good.size() / 2), EventFileFormat::Rosbag2Sqlite, "database disk image is malformed");
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open((dir_ / "other.db3").c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db, "CREATE TABLE notes(a TEXT);", nullptr, nullptr, nullptr), SQLITE_OK);
  sqlite3_close(db);
  expect_refused(testing::slurp(dir_ / "other.db3"), EventFileFormat::Rosbag2Sqlite,
                 "an SQLite database without rosbag2's topics and messages tables");
}

// rosbag2 records into a folder and starts a new file each time the recording splits: the folder
// is read as the bag, its files in the order of their split number (bag_10 after bag_9), an
// EventPacket's stream running on from one file to the next; each file declares its own ids.
class Ros2BagFolders : public testing::TempDirTest {};

TEST_F(Ros2BagFolders, AreReadFileByFileInSplitOrder) {
  LittleEndianBytes w;
  const auto word = [&](unsigned type, unsigned v) { w.put<std::uint16_t>(static_cast<std::uint16_t>((type << 12) | v)); };
  word(0x8, 0x001);  // EVT_TIME_HIGH: 4096
  word(0x0, 2);      // EVT_ADDR_Y: row 2
  std::vector<Cd> expected;
  for (unsigned k = 0; k < 11; ++k) {
    word(0x6, k);                // EVT_TIME_LOW
    word(0x2, (1u << 11) | k);   // (k, 2) ON
    expected.push_back({4096 + k, k, 2, true});
  }
  // Files of 4 bytes each: a time-high word in the first times the events of all the others.
  std::filesystem::create_directory(dir_ / "rec");
  write("rec/metadata.yaml", "rosbag2_bagfile_information:\n  version: 5\n");
  for (std::size_t at = 0, n = 0; at < w.bytes.size(); at += 4, ++n) {
    const auto id = static_cast<std::uint16_t>(n + 1);
    write("rec/rec_" + std::to_string(n) + ".mcap", mcap(schema(id, "event_camera_msgs/msg/EventPacket", kEventPacketDefinition) +
                                                          channel(id, id, "/events") + message(id, event_packet(w.bytes.substr(at, 4)))));
  }
  ASSERT_TRUE(std::filesystem::exists(dir_ / "rec" / "rec_11.mcap"));
  const EventRecording rec = load_events((dir_ / "rec").string());
  expect_events(rec, expected);

  // rosbag2's file compression: each file one zstd frame, `.mcap.zstd`; in a folder or alone.
  std::filesystem::create_directory(dir_ / "whole");
  const std::string one = mcap(schema(1, "dvs_msgs/msg/EventArray", kEventArrayDefinition) + channel(1, 1, "/events") +
                               message(1, event_array({{1, 2, 3, 0, true}})));
  write("whole/rec_0.mcap.zstd", compressed(one, "zstd"));
  expect_events(load_events((dir_ / "whole").string()), {{3000000, 1, 2, true}});
  expect_events(load_events((dir_ / "whole" / "rec_0.mcap.zstd").string()), {{3000000, 1, 2, true}});

  std::filesystem::create_directory(dir_ / "empty");
  write("empty/metadata.yaml", "");
  // A zstd frame that does not state its size (a stream's), which rosbag2 does not write.
  ZSTD_CCtx* cctx = ZSTD_createCCtx();
  ZSTD_CCtx_setParameter(cctx, ZSTD_c_contentSizeFlag, 0);
  std::string unsized(ZSTD_compressBound(one.size()), '\0');
  unsized.resize(ZSTD_compress2(cctx, unsized.data(), unsized.size(), one.data(), one.size()));
  ZSTD_freeCCtx(cctx);
  write("unsized.mcap.zstd", unsized);
  for (const auto& [name, words] : {std::pair<std::string, std::string>{"empty", "a folder holding no .mcap or .db3 file"},
                                    {"unsized.mcap.zstd", "a zstd file that does not state its size"}}) {
    const std::string path = (dir_ / name).string();
    testing::expect_refused_saying([&] { load_events(path); }, words);
  }
}

}  // namespace
}  // namespace aesim
