// aesim's event files as other readers parse them, each reader's rule written out here from its
// source (jAER's AEFileInputStream.readHeader, tonic's read_aedat_header_from_file, jAER's
// DavisBaseCamera address extractor), and recordings laid out as those tools write them.
#include <algorithm>
#include <cctype>
#include <cstdint>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/event_files/aedat.hpp"
#include "aesim/event_files/aedat_layout.hpp"
#include "aesim/event_files/event_file.hpp"
#include "aesim/event_files/event_writer.hpp"
#include "aesim/output/atomic_file.hpp"
#include "support/recorded_events.hpp"
#include "support/temp_dir_test.hpp"

namespace aesim {
namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// jAER: a line is header while it starts with '#'; the line "#End Of ASCII Header" (any case)
// ends the header whatever follows. Returns where the events start.
std::size_t jaer_data_start(const std::string& data) {
  std::size_t pos = 0;
  while (pos < data.size()) {
    const std::size_t eol = std::min(data.find('\n', pos), data.size());
    std::string line = data.substr(pos, eol - pos);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (lower(line.substr(1)) == "end of ascii header") return eol + 1;
    if (data[pos] != '#') return pos;
    pos = eol + 1;
  }
  return pos;
}

// tonic: every line starting with '#' is header, whatever it says.
std::size_t tonic_data_start(const std::string& data) {
  std::size_t pos = 0;
  while (pos < data.size() && data[pos] == '#') {
    const std::size_t eol = data.find('\n', pos);
    if (eol == std::string::npos) return data.size();  // all of it taken for header
    pos = eol + 1;
  }
  return pos;
}

std::uint32_t be32(const std::string& data, std::size_t at) {
  const auto* p = reinterpret_cast<const unsigned char*>(data.data() + at);
  return (std::uint32_t(p[0]) << 24) | (std::uint32_t(p[1]) << 16) | (std::uint32_t(p[2]) << 8) | p[3];
}

// One event at (0, row) at `t`, in the jAER DAVIS layout of a 160x160 array.
std::string davis_file_with_one_event(int row, double t, std::string* warning) {
  ArrayParams array;
  array.rows = array.cols = 160;
  const AddressMap map(array);
  std::ostringstream out;
  AedatWriter writer(out, aedat_header(map,
                                       {{"array.rows", "160"}, {"array.cols", "160"}, {"array.tile_rows", "32"},
                                        {"array.tile_cols", "32"}},
                                       AedatLayout::Davis), map,
                     1e-6, AedatLayout::Davis);
  AddressEvent e = map.event_at({0, static_cast<std::uint32_t>(row)});
  e.t = t;
  writer.events(&e, 1);
  writer.finish();
  *warning = writer.reader_warning();
  return out.str();
}

TEST(ForeignReaders, JaerFindsEveryEventAfterTheHeader) {
  int hash_rows = 0;
  for (int row = 0; row < 160; ++row) {
    std::string warning;
    const std::string data = davis_file_with_one_event(row, 25e-6, &warning);
    const std::size_t start = jaer_data_start(data);
    ASSERT_EQ(start, data.size() - 8) << "row " << row;
    EXPECT_EQ(be32(data, start + 4), 25u) << "row " << row;
    const bool hash = data[start] == '#';
    hash_rows += hash ? 1 : 0;
    // A reader that stops only at a line not starting with '#' misreads exactly these files, and
    // the writer says so.
    EXPECT_EQ(tonic_data_start(data) != start, hash) << "row " << row;
    EXPECT_EQ(!warning.empty(), hash) << "row " << row;
    const EventRecording back = decode_events(data, "one.aedat", EventFileFormat::Aedat2);
    ASSERT_EQ(back.events.size(), 1u) << "row " << row;
    EXPECT_EQ(back.events[0].y, static_cast<std::uint32_t>(row));
    EXPECT_EQ(back.events[0].x, 0u);
    EXPECT_DOUBLE_EQ(back.events[0].t, 25e-6);
  }
  // DAVIS words carry y (jAER's, from the bottom) in bits 22-30: the first byte is '#' (35)
  // for y = 140..143, rows 16..19 of a 160-row array.
  EXPECT_EQ(hash_rows, 4);
}

// jAER's reader (AEFileInputStream.readEventForwards), for a record stamped 0, reads the next record
// in its place without looking at that one's stamp. The events it loses, by that rule.
std::size_t jaer_lost(const std::string& data) {
  std::size_t lost = 0;
  for (std::size_t at = jaer_data_start(data); at + 8 <= data.size(); at += 8) {
    if (be32(data, at + 4) == 0) {
      ++lost;
      at += 8;  // the next record is taken as the event, whatever its stamp
    }
  }
  return lost;
}

TEST(ForeignReaders, TheEventsJaerLosesToZeroStampsAreCountedAsItLosesThem) {
  ArrayParams array;
  array.rows = array.cols = 160;
  const AddressMap map(array);
  for (const std::vector<double>& times : {std::vector<double>{0.1e-6}, std::vector<double>{0, 0.2e-6, 0.4e-6, 5e-6},
                                           std::vector<double>{0, 0.3e-6, 2e-6, 3e-6}}) {
    std::ostringstream out;
    AedatWriter writer(out,
                       aedat_header(map,
                                    {{"array.rows", "160"}, {"array.cols", "160"}, {"array.tile_rows", "32"},
                                     {"array.tile_cols", "32"}},
                                    AedatLayout::Davis),
                       map, 1e-6, AedatLayout::Davis);
    for (std::size_t i = 0; i < times.size(); ++i) {
      AddressEvent e = map.event_at({static_cast<std::uint32_t>(i), 0});
      e.t = times[i];
      writer.events(&e, 1);
    }
    writer.finish();
    const std::size_t lost = jaer_lost(out.str());
    ASSERT_GT(lost, 0u);
    EXPECT_NE(writer.reader_warning().find(fmt::format("will lose {} events stamped 0 us", lost)), std::string::npos)
        << writer.reader_warning();
  }
}

// AEDAT 3.1 as cAER writes it (libcaer's events/common.h and polarity.h): the header to
// "#!END-HEADER", then packets of a 28-byte little-endian header and their events.
struct Aedat31 {
  std::string data = "#!AER-DAT3.1\r\n#Format: RAW\r\n#Source 1: DAVIS346\r\n#!END-HEADER\r\n";
  template <typename T>
  void put(T v) {
    data.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  void packet(std::int16_t type, std::int32_t size, std::int32_t overflow, std::int32_t capacity, std::int32_t number) {
    put<std::int16_t>(type);
    put<std::int16_t>(1);  // eventSource
    put<std::int32_t>(size);
    put<std::int32_t>(4);  // eventTSOffset
    put<std::int32_t>(overflow);
    put<std::int32_t>(capacity);
    put<std::int32_t>(number);
    put<std::int32_t>(number);  // eventValid
  }
  void polarity(std::uint32_t x, std::uint32_t y, bool on, std::int32_t t_us, bool valid = true) {
    put<std::uint32_t>((x << 17) | (y << 2) | (on ? 2u : 0u) | (valid ? 1u : 0u));
    put<std::int32_t>(t_us);
  }
};

TEST(ForeignReaders, Aedat31GivesItsValidPolarityEventsWithOverflowedStampsAndCountsTheRest) {
  Aedat31 f;
  f.packet(0, 8, 0, 1, 1);  // a SPECIAL event (a timestamp reset, say): skipped, counted
  f.put<std::uint32_t>(0);
  f.put<std::int32_t>(5);
  f.packet(1, 8, 0, 3, 3);
  f.polarity(345, 259, true, 10);
  f.polarity(7, 3, false, 20, false);  // not valid: left out
  f.polarity(0, 0, false, 2147483647);
  f.packet(1, 8, 1, 2, 1);  // the stamps' 2^31 overflow; one slot of capacity unused
  f.polarity(12, 34, true, 5);
  f.polarity(0, 0, true, 0);
  const EventRecording rec = decode_events(f.data, "rec.aedat", EventFileFormat::Aedat2);
  ASSERT_EQ(rec.events.size(), 3u);
  EXPECT_EQ(rec.events[0].x, 345u);
  EXPECT_EQ(rec.events[0].y, 259u);
  EXPECT_EQ(rec.events[0].flags, kNormalEvent);
  EXPECT_DOUBLE_EQ(rec.events[0].t, 10e-6);
  EXPECT_EQ(rec.events[1].flags, kOffEvent);
  EXPECT_DOUBLE_EQ(rec.events[1].t, 2147483647e-6);
  EXPECT_EQ(rec.events[2].x, 12u);
  EXPECT_EQ(rec.events[2].y, 34u);
  EXPECT_DOUBLE_EQ(rec.events[2].t, (2147483648.0 + 5) * 1e-6);
  ASSERT_EQ(rec.skipped.size(), 2u);
  EXPECT_EQ(rec.skipped[0], "1 packets of SPECIAL (36 bytes)");
  EXPECT_EQ(rec.skipped[1], "1 events their recorder marked invalid");
  // Some writers end the header's lines in LF alone.
  std::string lf = f.data;
  lf.replace(lf.find("#!END-HEADER\r\n"), 14, "#!END-HEADER\n");
  EXPECT_EQ(decode_events(lf, "lf.aedat", EventFileFormat::Aedat2).events.size(), 3u);
}

TEST(ForeignReaders, MalformedAedat31IsAnInputErrorReadingNothingPastItsBytes) {
  const auto refused = [](const std::string& data, const char* says) {
    try {
      decode_events(data, "bad.aedat", EventFileFormat::Aedat2);
      ADD_FAILURE() << "accepted: " << says;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
    }
  };
  Aedat31 no_end;
  no_end.data = "#!AER-DAT3.1\r\n#Format: RAW\r\n";
  refused(no_end.data, "without its #!END-HEADER");
  Aedat31 cut;
  cut.packet(1, 8, 0, 2, 2);
  cut.polarity(1, 1, true, 1);
  refused(cut.data, "more than the file holds");
  Aedat31 huge;
  huge.packet(1, 8, 0, 2000000000, 1);
  refused(huge.data, "more than the file holds");
  Aedat31 wide;
  wide.packet(1, 12, 0, 1, 1);
  wide.data.append(12, '\0');
  refused(wide.data, "polarity events of 12 bytes");
  Aedat31 half;
  half.packet(1, 8, 0, 0, 0);
  half.data.resize(half.data.size() - 3);
  refused(half.data, "cut short in its header");
  Aedat31 negative;
  negative.packet(1, 8, 0, -1, 0);
  refused(negative.data, "impossible header");
}

TEST(ForeignReaders, HeaderTextIsPrintableAsciiAndReadsBackAsWritten) {
  const AddressMap map{ArrayParams{}};
  const std::map<std::string, std::string> sensor = {{"scene.note", "caf\xc3\xa9\r\nline two \\x41"}, {"pixel.c_int", "1e-13"}};
  const std::vector<std::string> header = aedat_header(map, sensor);
  for (const std::string& line : header) {
    for (const char c : line) {
      EXPECT_TRUE(c >= 32 && c <= 126) << "byte " << static_cast<int>(static_cast<unsigned char>(c)) << " in " << line;
    }
  }
  std::ostringstream out;
  write_aedat(out, header, {});
  const AedatFile back = decode_aedat(out.str(), "text.aedat");
  EXPECT_EQ(back.metadata.at("sensor.scene.note"), sensor.at("scene.note"));
  EXPECT_EQ(back.metadata.at("sensor.pixel.c_int"), "1e-13");
}

// A DAVIS240C recording as jAER writes it: polarity events between APS samples and special words.
TEST(ForeignReaders, JaerDavisRecordingGivesItsPolarityEventsAndCountsTheRest) {
  std::string file = "#!AER-DAT2.0\r\n# This is a raw AE data file - do not edit\r\n"
                     "# AEChip: eu.seebetter.ini.chips.davis.DAVIS240C\r\n#End Of ASCII Header\r\n";
  const auto record = [&](std::uint32_t address, std::uint32_t stamp) {
    for (const std::uint32_t v : {address, stamp}) {
      for (int shift = 24; shift >= 0; shift -= 8) file += static_cast<char>(v >> shift);
    }
  };
  // jAER's DAVIS word: y (from the bottom) << 22, the raw x (x flipped: 239 - x) << 12, ON << 11;
  // bit 31 an APS sample, bit 10 a special event.
  record((20u << 22) | (10u << 12) | (1u << 11), 1000);  // ON at jAER (229, 20)
  record(0x80000000u | (5u << 22), 1500);                 // APS
  record((0u << 22) | (0u << 12), 2000);                  // OFF at jAER (239, 0)
  record(1u << 10, 2500);                                 // special
  const EventRecording rec = decode_events(file, "davis.aedat", EventFileFormat::Aedat2);
  EXPECT_EQ(rec.width, 240);
  EXPECT_EQ(rec.height, 180);
  ASSERT_EQ(rec.events.size(), 2u);
  // aesim's y counts from the top.
  EXPECT_EQ(rec.events[0].x, 229u);
  EXPECT_EQ(rec.events[0].y, 159u);
  EXPECT_EQ(rec.events[0].flags, kNormalEvent);
  EXPECT_DOUBLE_EQ(rec.events[0].t, 1e-3);
  EXPECT_EQ(rec.events[1].x, 239u);
  EXPECT_EQ(rec.events[1].y, 179u);
  EXPECT_EQ(rec.events[1].flags, kOffEvent);
  ASSERT_EQ(rec.skipped.size(), 2u);
  EXPECT_EQ(rec.skipped[0], "1 APS (frame) samples");
  EXPECT_EQ(rec.skipped[1], "1 special and IMU words");
  // Without a chip line the words cannot be decoded: the error says how to name the chip.
  std::string anonymous = file;
  anonymous.replace(anonymous.find("# AEChip"), anonymous.find("#End") - anonymous.find("# AEChip"), "");
  try {
    decode_events(anonymous, "anon.aedat", EventFileFormat::Aedat2);
    ADD_FAILURE() << "decoded words of no named chip";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--layout"), std::string::npos) << e.what();
  }
}

// A DAVIS camera's 32-bit microsecond counter passes 2^31 (jAER's int32 goes negative) and wraps
// at 2^32 after 71.6 minutes; IMU and frame samples are stamped otherwise than the events around
// them. Read as jAER reads them: unsigned, a step back of over half the range a wrap, and events
// out of order put in time order and counted. aesim's own files keep their strict rules.
TEST(ForeignReaders, JaerStampsPastTwoToTheThirtyOneAndAcrossAWrapReadInOrder) {
  std::string file = "#!AER-DAT2.0\r\n# AEChip: eu.seebetter.ini.chips.davis.DAVIS240C\r\n#End Of ASCII Header\r\n";
  const auto record = [&](std::uint32_t address, std::uint32_t stamp) {
    for (const std::uint32_t v : {address, stamp}) {
      for (int shift = 24; shift >= 0; shift -= 8) file += static_cast<char>(v >> shift);
    }
  };
  const std::uint32_t on = (1u << 11);
  record(on | (1u << 12), 0x7FFFFFF0u);   // just below 2^31 us
  record(on | (2u << 12), 0x80000010u);   // past it: negative as jAER's int32, read on
  record(on | (3u << 12), 0x80000008u);   // 8 us earlier than the one before: put in order
  record(on | (4u << 12), 0xFFFFFFF0u);   // just below 2^32
  record(on | (5u << 12), 0x00000020u);   // the counter wrapped
  const EventRecording rec = decode_events(file, "long.aedat", EventFileFormat::Aedat2);
  ASSERT_EQ(rec.events.size(), 5u);
  const double us = 1e-6;
  EXPECT_DOUBLE_EQ(rec.events[0].t, 2147483632 * us);
  EXPECT_DOUBLE_EQ(rec.events[1].t, 2147483656 * us);  // 0x80000008: the reordered one
  EXPECT_EQ(rec.events[1].x, 239u - 3u);
  EXPECT_DOUBLE_EQ(rec.events[2].t, 2147483664 * us);
  EXPECT_DOUBLE_EQ(rec.events[3].t, 4294967280 * us);
  EXPECT_DOUBLE_EQ(rec.events[4].t, (4294967296.0 + 32) * us);
  EXPECT_EQ(rec.reordered, 1u);
  EXPECT_EQ(rec.stamp_wraps, 1u);
  for (std::size_t i = 1; i < rec.events.size(); ++i) EXPECT_LE(rec.events[i - 1].t, rec.events[i].t);
}

// A recording of `format` that is refused: an InputError holding `words`, on one line.
void expect_decode_refused(const std::string& data, EventFileFormat format, const std::string& words) {
  try {
    decode_events(data, "bad", format);
    ADD_FAILURE() << "accepted: " << words;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
  }
}

// Prophesee's DAT (ATIS cameras, N-CARS, Gen1), laid out as its documentation and expelliarmus's
// read_dat give it: '%' header lines, a type byte (0 Event2d or 12 EventCd, the same layout) and a
// size byte (8), then per event a little-endian stamp (us) and a word with x in bits 0-13, y in
// 14-27, polarity in 28-31. A stamp below the last means the 32-bit counter wrapped. It shares .dat
// with jAER, whose files begin '#'.
TEST(ForeignReaders, PropheseeDatGivesItsCdEventsWithWrappedStampsAndItsSize) {
  std::string file = "% Data file containing Event2D events.\n% Version 2\n% Width 304\n% Height 240\n";
  file += std::string("\x00\x08", 2);
  const auto put32 = [&](std::uint32_t v) {
    for (int b = 0; b < 4; ++b) file += static_cast<char>((v >> (8 * b)) & 0xFF);
  };
  const auto event = [&](std::uint32_t t, std::uint32_t x, std::uint32_t y, std::uint32_t p) {
    put32(t);
    put32(x | (y << 14) | (p << 28));
  };
  event(5, 303, 239, 1);
  event(900, 0, 7, 0);
  event(0xFFFFFFF0u, 12, 34, 1);
  event(0x10, 12, 35, 0);  // the counter wrapped
  const EventRecording rec = decode_events(file, "atis.dat", EventFileFormat::PropheseeDat);
  ASSERT_EQ(rec.events.size(), 4u);
  EXPECT_EQ(rec.width, 304);
  EXPECT_EQ(rec.height, 240);
  EXPECT_TRUE(rec.size_recorded);
  EXPECT_EQ(rec.events[0].x, 303u);
  EXPECT_EQ(rec.events[0].y, 239u);
  EXPECT_EQ(rec.events[0].flags, kNormalEvent);
  EXPECT_EQ(rec.events[1].flags, kOffEvent);
  EXPECT_DOUBLE_EQ(rec.events[1].t, 900e-6);
  EXPECT_DOUBLE_EQ(rec.events[3].t, (4294967296.0 + 16) * 1e-6);
  EXPECT_EQ(rec.events[3].y, 35u);
  // Type 12 (EventCd, as Metavision writes CD events): the same events.
  const std::size_t type_at = file.find(std::string("\x00\x08", 2));
  std::string cd = file;
  cd[type_at] = 0x0C;
  const EventRecording as_cd = decode_events(cd, "cd.dat", EventFileFormat::PropheseeDat);
  ASSERT_EQ(as_cd.events.size(), rec.events.size());
  for (std::size_t i = 0; i < rec.events.size(); ++i) {
    EXPECT_EQ(as_cd.events[i].t, rec.events[i].t);
    EXPECT_EQ(as_cd.events[i].x, rec.events[i].x);
    EXPECT_EQ(as_cd.events[i].y, rec.events[i].y);
    EXPECT_EQ(as_cd.events[i].flags, rec.events[i].flags);
  }
  // Other event types and sizes, a file cut inside an event, a header without its end: one-line errors.
  const auto refused = [](const std::string& data, const std::string& words) {
    expect_decode_refused(data, EventFileFormat::PropheseeDat, words);
  };
  std::string triggers = file;
  triggers[type_at] = 0x0E;
  refused(triggers, "type 14 is external triggers");
  std::string wide = cd;
  wide[type_at + 1] = 16;
  refused(wide, "type 12 and size 16");
  refused(file.substr(0, file.size() - 3), "ends inside event 3");
  refused("% no end", "header does not end");
}

// Prophesee RAW: '%' header lines naming the encoding, then the camera's words, little-endian,
// laid out here bit by bit from Prophesee's format pages (EVT 2.0, 2.1, 3.0) and OpenEB's decoders.
using RawWords = testing::LittleEndianBytes;
using testing::Cd;
using testing::expect_events;
using testing::noted;

TEST(ForeignReaders, PropheseeRawEvt3DecodesRowsVectorsAndTheWrappingTime) {
  RawWords w;
  const auto word = [&](unsigned type, unsigned v) { w.put<std::uint16_t>(static_cast<std::uint16_t>((type << 12) | v)); };
  word(0x2, 5);                  // EVT_ADDR_X before any time: no time, left out
  word(0x8, 0x005);              // EVT_TIME_HIGH
  word(0x6, 0x010);              // EVT_TIME_LOW: t = 5 * 4096 + 16
  word(0x0, 3);                  // EVT_ADDR_Y: row 3
  word(0x2, (1u << 11) | 7);     // EVT_ADDR_X: (7, 3) ON
  word(0x3, 16);                 // VECT_BASE_X: column 16, OFF
  word(0x4, 0b100000000101);     // VECT_12: columns 16, 18, 27; the base moves to 28
  word(0x5, 0x81);               // VECT_8: columns 28, 35; the base moves to 36
  word(0xA, 0x001);              // EXT_TRIGGER: counted, left out
  word(0xE, 0x014);              // OTHERS (an ERC count) and its CONTINUED words
  word(0xF, 0x123);
  word(0x8, 0xFFF);              // the high part at the top of its range ...
  word(0x8, 0x001);              // ... falls: the 24-bit time wrapped
  word(0x6, 0x002);              // t = 2^24 + 4096 + 2
  word(0x2, 39);                 // (39, 3) OFF
  word(0x0, 9);                  // row 9, past the header's 8 rows
  word(0x2, 1);                  // left out
  const std::string header = "% camera_integrator_name Prophesee\n% evt 3.0\n% format EVT3;height=8;width=40\n"
                             "% geometry 40x8\n% end\n";
  const EventRecording rec = decode_events(header + w.bytes + "\x01", "evt3.raw", EventFileFormat::PropheseeRaw);
  const std::int64_t t0 = 5 * 4096 + 16, t1 = (std::int64_t(1) << 24) + 4096 + 2;
  expect_events(rec, {{t0, 7, 3, true}, {t0, 16, 3, false}, {t0, 18, 3, false}, {t0, 27, 3, false},
                      {t0, 28, 3, false}, {t0, 35, 3, false}, {t1, 39, 3, false}});
  EXPECT_EQ(rec.width, 40);
  EXPECT_EQ(rec.height, 8);
  EXPECT_TRUE(rec.size_recorded);
  EXPECT_TRUE(noted(rec, "1 event before the first time-high word")) << rec.skipped.size();
  EXPECT_TRUE(noted(rec, "1 event outside the header's 40x8 array"));
  EXPECT_TRUE(noted(rec, "1 external trigger event"));
  EXPECT_TRUE(noted(rec, "2 other words"));
  EXPECT_TRUE(noted(rec, "1 byte at the end, a word cut short"));
}

TEST(ForeignReaders, PropheseeRawEvt2AndEvt21DecodeTheirWordsAndTimeHigh) {
  // EVT 2.0 (a file of before Metavision 4: "% evt 2.0", no "% end", no size).
  RawWords e2;
  const auto cd2 = [&](unsigned type, unsigned ts, unsigned x, unsigned y) {
    e2.put<std::uint32_t>((type << 28) | (ts << 22) | (x << 11) | y);
  };
  cd2(1, 0, 1, 1);                                        // before any time: left out
  e2.put<std::uint32_t>((0x8u << 28) | 3);                // EVT_TIME_HIGH: 3 * 64 us
  cd2(1, 5, 10, 2);                                       // CD_ON at 192 + 5
  cd2(0, 63, 0, 7);                                       // CD_OFF at 192 + 63
  e2.put<std::uint32_t>(0xAu << 28);                      // EXT_TRIGGER
  e2.put<std::uint32_t>((0x8u << 28) | 0x0FFFFFFFu);      // the top of the high part's range
  e2.put<std::uint32_t>((0x8u << 28) | 1);                // falls: wrapped, 2^34 us on
  cd2(1, 0, 2047, 2047);                                  // at 2^34 + 64
  const EventRecording r2 = decode_events("% Date 2020-09-14\n% evt 2.0\n" + e2.bytes, "evt2.raw", EventFileFormat::PropheseeRaw);
  const std::int64_t wrapped = (std::int64_t(1) << 34) + 64;
  expect_events(r2, {{197, 10, 2, true}, {255, 0, 7, false}, {wrapped, 2047, 2047, true}});
  EXPECT_FALSE(r2.size_recorded);  // no size in the header: the events' span
  EXPECT_TRUE(noted(r2, "1 external trigger event"));

  // EVT 2.1: a row, a base column and a mask of 32 pixels; the IMX636's legacy layout swaps the
  // two 32-bit halves of each word.
  for (const bool legacy : {false, true}) {
    RawWords e21;
    const auto put64 = [&](std::uint64_t v) { e21.put<std::uint64_t>(legacy ? (v << 32) | (v >> 32) : v); };
    put64((std::uint64_t(0x8) << 60) | (std::uint64_t(2) << 32));  // EVT_TIME_HIGH: 2 * 64 us
    put64((std::uint64_t(0x1) << 60) | (std::uint64_t(1) << 54) | (std::uint64_t(32) << 43) | (std::uint64_t(5) << 32) |
          0x80000001u);                                                // EVT_POS at 129: columns 32 and 63 of row 5
    put64((std::uint64_t(0x0) << 60) | (std::uint64_t(9) << 54) | (std::uint64_t(0) << 43) | (std::uint64_t(6) << 32) |
          0x4u);                                                       // EVT_NEG at 137: column 2 of row 6
    const std::string header = std::string("% format EVT21;height=8;width=64") + (legacy ? ";endianness=legacy" : "") + "\n% end\n";
    const EventRecording r21 = decode_events(header + e21.bytes, "evt21.raw", EventFileFormat::PropheseeRaw);
    SCOPED_TRACE(legacy);
    expect_events(r21, {{129, 32, 5, true}, {129, 63, 5, true}, {137, 2, 6, false}});
    EXPECT_EQ(r21.width, 64);
  }
}

// expelliarmus's RAW writer ends each header line with a space ("% evt 2.0 \n") and writes no
// "% end"; other writers leave blanks around a format's fields. The words after it are the same.
TEST(ForeignReaders, PropheseeRawHeaderLinesReadWithBlanksAroundTheirValues) {
  RawWords words;
  words.put<std::uint32_t>((0x8u << 28) | 2);                            // EVT_TIME_HIGH: 128 us
  words.put<std::uint32_t>((0x1u << 28) | (3u << 22) | (4u << 11) | 5);  // CD_ON (4, 5) at 131
  const EventRecording trailing = decode_events(
      "% Date 1970-12-25 07:51:03 \n% evt 2.0 \n% integrator_name Prophesee \n% system_ID 21 \n" + words.bytes,
      "expelliarmus.raw", EventFileFormat::PropheseeRaw);
  expect_events(trailing, {{131, 4, 5, true}});
  const EventRecording spaced = decode_events("% format EVT2 ; height = 8 ;width=6\t\n% end \n" + words.bytes,
                                              "spaced.raw", EventFileFormat::PropheseeRaw);
  expect_events(spaced, {{131, 4, 5, true}});
  EXPECT_EQ(spaced.width, 6);
  EXPECT_EQ(spaced.height, 8);
}

TEST(ForeignReaders, PropheseeRawHeadersThatNameNoReadableEncodingAreOneLineErrors) {
  const auto refused = [](const std::string& data, const std::string& words) {
    expect_decode_refused(data, EventFileFormat::PropheseeRaw, words);
  };
  refused("% format HISTO3D;height=320;width=320\n% end\n", "HISTO3D");
  refused("% evt 4.0\n% end\n", "evt 4.0");
  refused("% Date 2024-01-01\n% end\n\x01\x02", "names no encoding");
  refused("% evt 3.0", "header does not end");
}

// N-MNIST and N-Caltech101 (.bin), laid out as Orchard's Read_Ndataset.m and tonic's
// read_mnist_file read them: 5 bytes a record, x, y, then polarity in bit 7 and a 23-bit stamp
// (us), most significant byte first. A record with y 240 marks a stamp overflow: 2^13 us more for
// it and every record after it, and it is no event.
TEST(ForeignReaders, NmnistBinGivesItsRecordsWithTheOverflowMarkersAddedAndCounted) {
  std::string file;
  const auto record = [&](unsigned x, unsigned y, bool on, std::uint32_t t) {
    file += static_cast<char>(x);
    file += static_cast<char>(y);
    file += static_cast<char>((on ? 0x80 : 0) | ((t >> 16) & 0x7F));
    file += static_cast<char>((t >> 8) & 0xFF);
    file += static_cast<char>(t & 0xFF);
  };
  record(33, 0, true, 654);
  record(0, 33, false, 0x7FFFFF);  // the largest 23-bit stamp
  record(0, 240, false, 0);        // overflow
  record(7, 9, true, 0x7FFFFF);
  record(0, 240, true, 0);  // overflow
  record(255, 239, false, 0x7FE005);
  const EventRecording rec = decode_events(file, "n.bin", EventFileFormat::NmnistBin);
  expect_events(rec, {{654, 33, 0, true}, {8388607, 0, 33, false}, {8388607 + 8192, 7, 9, true}, {0x7FE005 + 2 * 8192, 255, 239, false}});
  EXPECT_FALSE(rec.size_recorded);
  EXPECT_EQ(rec.width, 256);  // the events' span: x reaches 255
  EXPECT_EQ(rec.height, 240);
  EXPECT_TRUE(noted(rec, "2 stamp overflow records"));
  expect_decode_refused(file.substr(0, 12), EventFileFormat::NmnistBin, "ends inside record 2");
  // Stamps that go back (not a recording in time order, or not this format): refused.
  std::string back = file.substr(0, 10);
  back[9] = 0;
  back[8] = 0;
  back[7] = 0;
  expect_decode_refused(back, EventFileFormat::NmnistBin, "timestamps decrease at event 1");
  EXPECT_TRUE(decode_events("", "empty.bin", EventFileFormat::NmnistBin).events.empty());
}

// Text events, one `t x y p` a line: the Event Camera Dataset's events.txt (t in s with nine
// decimals), v2e's (its '#' header, Python's float repr such as 1e-06, an optional signal/noise
// column), rpg_e2vid's (a first line `width height`), polarity 1 or 0 (or -1 for OFF).
TEST(ForeignReaders, EventsTextReadsTheDatasetsAndSimulatorsLines) {
  const EventRecording ecd =
      decode_events("0.000000000 33 39 1\n0.000011001 158 145 1\r\n0.000050000 88 143 0\n", "events.txt", EventFileFormat::EventsText);
  expect_events(ecd, {{0, 33, 39, true}, {11, 158, 145, true}, {50, 88, 143, false}});
  EXPECT_FALSE(ecd.size_recorded);
  const EventRecording v2e = decode_events(
      "#!events.txt\n# This is a text DVS created by v2e\n# Format is time (float s), x, y, polarity (0=off, 1=on)\n"
      "1e-06 3 4 0 1\n2.5e-05 5 6 1 0\n\n0.5 7 8 -1 1\n",
      "v2e.txt", EventFileFormat::EventsText);
  expect_events(v2e, {{1, 3, 4, false}, {25, 5, 6, true}, {500000, 7, 8, false}});
  const EventRecording e2vid = decode_events("240 180\n1.0000004 239 179 1\n1.0000006\t0\t0\t0\n", "e2vid.txt",
                                             EventFileFormat::EventsText);
  expect_events(e2vid, {{1000000, 239, 179, true}, {1000001, 0, 0, false}});
  EXPECT_TRUE(e2vid.size_recorded);
  EXPECT_EQ(e2vid.width, 240);
  EXPECT_EQ(e2vid.height, 180);
  // jAER's DavisTextOutputWriter: its header, Java's %f (six decimals) or, with useUsTimestamps,
  // whole microseconds as its header says; with useCSV, commas; with useSignedPolarity, -1 for OFF.
  const std::string jaer_header = "# jAER DAVIS/DVS camera text file output\n# created Sat Nov 28 01:00:00 UTC 2026\n"
                                  "# source-file: (live input)\n";
  const EventRecording jaer_s = decode_events(
      jaer_header + "# dvs-events: One event per line:  timestamp(float s) x y polarity(off/on=0/1)\n0.000123 1 2 0\n",
      "jaer-events.txt", EventFileFormat::EventsText);
  expect_events(jaer_s, {{123, 1, 2, false}});
  const EventRecording jaer_us = decode_events(
      jaer_header + "# dvs-events: One event per line:  timestamp(int32 us) x y polarity(off/on=-1/+1)\n"
                    "123,1,2,-1\n2147483647,3,4,1\n",
      "jaer-us-events.txt", EventFileFormat::EventsText);
  expect_events(jaer_us, {{123, 1, 2, false}, {2147483647, 3, 4, true}});
  // A Windows editor's byte order mark.
  expect_events(decode_events("\xEF\xBB\xBF" "0.5 1 2 1\n", "bom.txt", EventFileFormat::EventsText), {{500000, 1, 2, true}});
  const auto refused = [](const std::string& data, const std::string& words) {
    expect_decode_refused(data, EventFileFormat::EventsText, words);
  };
  // Stamps that go back (v2e warns that it writes some): read in time order, equal stamps in the
  // file's order, and counted.
  const EventRecording back = decode_events("0.1 1 2 1\n0.05 3 4 1\n0.1 5 6 0\n0.05 7 8 0\n0.2 9 9 1\n", "back.txt",
                                            EventFileFormat::EventsText);
  expect_events(back, {{50000, 3, 4, true}, {50000, 7, 8, false}, {100000, 1, 2, true}, {100000, 5, 6, false}, {200000, 9, 9, true}});
  EXPECT_EQ(back.reordered, 2u);
  refused("0.1 1 2 2\n", "polarity must be 1 (ON), 0 or -1 (OFF)");
  refused("0.1 1 2\n", "expected 't x y p'");
  refused("0.1 1 2 1 0 9\n", "expected 't x y p'");
  refused("t x y p\n", "the time is not a number");
  refused("nan 1 2 1\n", "the time is not a number");
  refused("-0.5 1 2 1\n", "outside 0 to");
  refused("0.1 -1 2 1\n", "x and y must be whole numbers");
  refused("0.1 1.5 2 1\n", "x and y must be whole numbers");
  refused("240 0\n", "two whole numbers from 1 to 65535");
  refused("0.1 1 2 1\n240 180\n", "line 2");
  refused("240 180\n0.1 300 2 1\n", "outside its 240x180 array");
  refused("# timestamp(int32 us)\n0.5 1 2 1\n", "not a whole number of microseconds");
}

// The containers events come in that aesim does not open (a file compressed whole that is not a
// ROS 2 bag's, Event Stream files): the one-line refusal names the way out where there is one.
// Event CSVs other tools write. Metavision's, as OpenEB's RAW-to-CSV sample writes it ("%d,%d,%d,%d"
// of x, y, p, t in microseconds, after its `%geometry:W,H` line in metavision_file_to_csv's): the
// camera's size and stamps as written. A header naming the columns in any order and separator:
// the time's unit from its name, else microseconds for whole numbers and seconds for fractions,
// said in `read_as`; rows out of time order put in it and counted.
TEST(ForeignReaders, EventCsvsOfOtherToolsAreReadByTheirColumns) {
  const EventRecording mv = decode_events("%geometry:1280,720\n1279,0,1,1000000\n3,719,0,1000250\n", "mv.csv",
                                          EventFileFormat::Csv);
  EXPECT_EQ(mv.width, 1280);
  EXPECT_EQ(mv.height, 720);
  ASSERT_EQ(mv.events.size(), 2u);
  EXPECT_EQ(mv.events[0].x, 1279u);
  EXPECT_DOUBLE_EQ(mv.events[1].t, 1.00025);
  EXPECT_EQ(mv.events[1].y, 719u);
  EXPECT_EQ(mv.events[0].flags, kNormalEvent);
  EXPECT_EQ(mv.events[1].flags, kOffEvent);
  ASSERT_EQ(mv.read_as.size(), 1u);
  EXPECT_NE(mv.read_as[0].find("Metavision's CSV rows x,y,p,t"), std::string::npos);
  struct Case {
    const char* text;
    double t1;  // the second event's stamp, s
    const char* read_as;
  } cases[] = {{"timestamp,x,y,polarity\n1000,1,2,1\n2500,3,4,0\n", 2.5e-3, "time 'timestamp' in us (microseconds"},
               {"x,y,p,t\n1,2,1,0.5\n3,4,0,0.75\n", 0.75, "time 't' in s (seconds"},
               {"x;y;t_ms;pol\n1;2;1;1\n3;4;2.5;-1\n", 2.5e-3, "time 't_ms' in ms"},
               {"\xEF\xBB\xBF\"t [us]\"\t\"x\"\t\"y\"\t\"on\"\n10\t1\t2\tTrue\n20\t3\t4\tFalse\n", 20e-6, "time 't [us]' in us"},
               {"# exported\nx,y,timestamp\n1,2,5\n3,4,7\n", 7e-6, "time 'timestamp' in us"}};
  for (const Case& c : cases) {
    const EventRecording r = decode_events(c.text, "named.csv", EventFileFormat::Csv);
    ASSERT_EQ(r.events.size(), 2u) << c.text;
    EXPECT_EQ(r.events[0].x, 1u) << c.text;
    EXPECT_EQ(r.events[1].y, 4u) << c.text;
    EXPECT_NEAR(r.events[1].t, c.t1, 1e-12) << c.text;
    ASSERT_EQ(r.read_as.size(), 1u) << c.text;
    EXPECT_NE(r.read_as[0].find(c.read_as), std::string::npos) << r.read_as[0];
  }
  // No polarity column: every event ON; rows out of order put in order and counted.
  const EventRecording late = decode_events("t,x,y\n30,1,1\n10,2,2\n20,3,3\n", "late.csv", EventFileFormat::Csv);
  ASSERT_EQ(late.events.size(), 3u);
  EXPECT_EQ(late.events[0].x, 2u);
  EXPECT_EQ(late.reordered, 1u);
  EXPECT_EQ(late.events[2].flags, kNormalEvent);
  // Refused in one line naming the way out: rows in another order without a header, a header
  // without a time, two time columns.
  for (const auto& [text, needle] : {std::pair<const char*, const char*>{"1000,1,2,1\n", "needs a header naming its columns"},
                                     {"x,y,p\n1,2,1\n", "needs x, y and the time"},
                                     {"t,x,y,timestamp\n1,2,3,4\n", "two columns give the time"},
                                     {"x,y,t\n1,2\n", "2 fields where the header has 3"}}) {
    try {
      decode_events(text, "bad.csv", EventFileFormat::Csv);
      ADD_FAILURE() << text;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  }
}

TEST(ForeignReaders, ContainersAesimDoesNotOpenNameTheWayOut) {
  for (const auto& [path, words] : {std::pair<const char*, const char*>{"events.txt.zstd", "a file compressed whole: uncompress it with `zstd -d`"},
                                    {"events.es", "unsupported format (use .aedat"}}) {
    try {
      load_events(path);
      ADD_FAILURE() << path;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
  }
}

class EmptyRuns : public testing::TempDirTest {};

// A run that delivers no event still writes a file each reader opens: DV's AEDAT 4.0 readers
// expect a packet, so an empty one is written.
TEST_F(EmptyRuns, EveryFormatWritesAFileThatReadsBackEmptyWithItsArray) {
  for (const std::string name : {"e.aedat", "e.aedat4", "e.npy", "e.h5", "e.raw", "e.dat"}) {
    EventFileSpec spec;
    spec.sensor = {{"array.rows", "64"}, {"array.cols", "64"}, {"array.tile_rows", "32"}, {"array.tile_cols", "32"}};
    spec.duration = 0.01;
    const std::string path = (dir_ / name).string();
    {
      OutputFiles files;
      auto writer = open_event_writer(files, path, spec);
      writer->finish();
      // DSEC's EventSlicer reads the last stamp on opening: an empty file is named as one it cannot open.
      EXPECT_EQ(writer->reader_warning().find("EventSlicer") != std::string::npos, name == "e.h5") << name;
      writer.reset();
      files.commit();
    }
    const EventRecording rec = load_events(path, ArraySize{64, 64});
    EXPECT_TRUE(rec.events.empty()) << name;
    EXPECT_EQ(rec.width, 64) << name;
  }
}

}  // namespace
}  // namespace aesim
