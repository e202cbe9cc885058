// NumPy .npz archives built byte by byte: ZIP files as PKWARE's APPNOTE lays them out (local
// headers, the central directory, its end record; Zip64's extra field), members stored or
// deflated by zlib, each a .npy file as numpy.lib.format writes one.
#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <tuple>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/event_files/event_file.hpp"
#include "aesim/event_files/event_formats.hpp"
#include "support/recorded_events.hpp"
#include "support/temp_dir_test.hpp"

namespace aesim {
namespace {

using testing::expect_events;
using testing::little;
using testing::noted;

// A float's bytes as this (little-endian) machine stores them.
template <typename T>
std::string float_bytes(T v) {
  std::string b(sizeof v, '\0');
  std::memcpy(b.data(), &v, sizeof v);
  return b;
}

// A .npy file (format 1.0): magic, version, the header's length, the header padded with spaces to
// a multiple of 64 and ended by a newline, then the data.
std::string npy(const std::string& descr, const std::string& shape, const std::string& data) {
  std::string header = "{'descr': " + descr + ", 'fortran_order': False, 'shape': " + shape + ", }";
  while ((10 + header.size() + 1) % 64 != 0) header += ' ';
  header += '\n';
  return std::string("\x93NUMPY\x01\x00", 8) + little<std::uint16_t>(static_cast<std::uint16_t>(header.size())) + header + data;
}

std::string deflated(const std::string& plain) {
  z_stream z{};
  EXPECT_EQ(deflateInit2(&z, 6, Z_DEFLATED, -MAX_WBITS, 8, Z_DEFAULT_STRATEGY), Z_OK);
  std::string out(deflateBound(&z, plain.size()), '\0');
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(plain.data()));
  z.avail_in = static_cast<uInt>(plain.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  EXPECT_EQ(deflate(&z, Z_FINISH), Z_STREAM_END);
  out.resize(z.total_out);
  deflateEnd(&z);
  return out;
}

std::uint32_t crc_of(const std::string& s) {
  return static_cast<std::uint32_t>(crc32_z(crc32_z(0, nullptr, 0), reinterpret_cast<const Bytef*>(s.data()), s.size()));
}

struct Entry {
  std::string name, plain;
  bool deflate = false;
  bool zip64_directory = false;  // the directory's sizes and offset in Zip64's extra field
  std::uint32_t crc_flip = 0;
};

std::string zip(const std::vector<Entry>& entries) {
  std::string out, directory;
  for (const Entry& e : entries) {
    const std::string data = e.deflate ? deflated(e.plain) : e.plain;
    const auto offset = static_cast<std::uint32_t>(out.size());
    const std::uint16_t method = e.deflate ? 8 : 0;
    const std::uint32_t crc = crc_of(e.plain) ^ e.crc_flip;
    const std::string name = e.name + ".npy";
    // Local header: as NumPy writes it, a Zip64 field of the two sizes after the name.
    const std::string local_extra = little<std::uint16_t>(1) + little<std::uint16_t>(16) + little<std::uint64_t>(e.plain.size()) +
                                    little<std::uint64_t>(data.size());
    out += little<std::uint32_t>(0x04034b50) + little<std::uint16_t>(45) + little<std::uint16_t>(0) + little(method) +
           little<std::uint32_t>(0) + little(crc) + little<std::uint32_t>(0xFFFFFFFFu) + little<std::uint32_t>(0xFFFFFFFFu) +
           little<std::uint16_t>(static_cast<std::uint16_t>(name.size())) + little<std::uint16_t>(static_cast<std::uint16_t>(local_extra.size())) +
           name + local_extra + data;
    const std::string extra = e.zip64_directory ? little<std::uint16_t>(1) + little<std::uint16_t>(24) + little<std::uint64_t>(e.plain.size()) +
                                                      little<std::uint64_t>(data.size()) + little<std::uint64_t>(offset)
                                                : std::string();
    const auto word = [&](std::uint64_t v) { return little<std::uint32_t>(e.zip64_directory ? 0xFFFFFFFFu : static_cast<std::uint32_t>(v)); };
    directory += little<std::uint32_t>(0x02014b50) + little<std::uint16_t>(45) + little<std::uint16_t>(45) + little<std::uint16_t>(0) +
                 little(method) + little<std::uint32_t>(0) + little(crc) + word(data.size()) + word(e.plain.size()) +
                 little<std::uint16_t>(static_cast<std::uint16_t>(name.size())) + little<std::uint16_t>(static_cast<std::uint16_t>(extra.size())) +
                 little<std::uint16_t>(0) + little<std::uint16_t>(0) + little<std::uint16_t>(0) + little<std::uint32_t>(0) + word(offset) +
                 name + extra;
  }
  const auto count = static_cast<std::uint16_t>(entries.size());
  return out + directory + little<std::uint32_t>(0x06054b50) + little<std::uint16_t>(0) + little<std::uint16_t>(0) + little(count) +
         little(count) + little<std::uint32_t>(static_cast<std::uint32_t>(directory.size())) +
         little<std::uint32_t>(static_cast<std::uint32_t>(out.size())) + little<std::uint16_t>(0);
}

EventRecording read_npz(const std::string& bytes) { return decode_events(bytes, "test.npz", EventFileFormat::Npz); }

// Three events in N-ImageNet's dtype (x, y uint16; t int64 us; p bool), the second stamped first.
std::string structured() {
  std::string data;
  for (const auto& [x, y, t, p] : {std::tuple<std::uint16_t, std::uint16_t, std::int64_t, bool>{5, 6, 300, true}, {7, 8, 100, false}, {9, 10, 200, true}}) {
    data += little(x) + little(y) + little(t) + std::string(1, p ? '\1' : '\0');
  }
  return npy("[('x', '<u2'), ('y', '<u2'), ('t', '<i8'), ('p', '|b1')]", "(3,)", data);
}

TEST(NpzEvents, AStructuredArrayOfEventsIsReadStoredOrDeflated) {
  for (const bool deflate : {false, true}) {
    for (const bool zip64 : {false, true}) {
      SCOPED_TRACE(::testing::Message() << deflate << zip64);
      const std::string rgb = npy("'|u1'", "(2, 2)", "abcd");
      const EventRecording rec = read_npz(zip({{"frame", rgb, deflate, zip64}, {"event_data", structured(), deflate, zip64}}));
      expect_events(rec, {{100, 7, 8, false}, {200, 9, 10, true}, {300, 5, 6, true}});
      EXPECT_EQ(rec.reordered, 1u);
      EXPECT_TRUE(noted(rec, "the array frame (the events are event_data's)"));
      EXPECT_FALSE(rec.size_recorded);
    }
  }
}

// Arrays of their own, as event deblurring and interpolation datasets save them: whole stamps
// are microseconds, stamps with fractions seconds; polarities -1/1 or 0/1, ON above 0; N x 1
// arrays as one number an event; big-endian numbers.
TEST(NpzEvents, ArraysOfTheirOwnAreReadWithTheirStampsUnit) {
  const std::string x = npy("'<u2'", "(3,)", little<std::uint16_t>(1) + little<std::uint16_t>(2) + little<std::uint16_t>(3));
  const std::string y = npy("'<i4'", "(3, 1)", little<std::int32_t>(4) + little<std::int32_t>(5) + little<std::int32_t>(6));
  const std::string p = npy("'|i1'", "(3,)", std::string("\xff\x01\xff", 3));
  const std::string whole = npy("'<i8'", "(3,)", little<std::int64_t>(10) + little<std::int64_t>(20) + little<std::int64_t>(30));
  EventRecording rec = read_npz(zip({{"x", x}, {"y", y}, {"t", whole, true}, {"p", p}, {"start_t", npy("'<i8'", "()", little<std::int64_t>(0))}}));
  expect_events(rec, {{10, 1, 4, false}, {20, 2, 5, true}, {30, 3, 6, false}});
  ASSERT_EQ(rec.read_as.size(), 1u);
  EXPECT_NE(rec.read_as[0].find("stamps in microseconds"), std::string::npos) << rec.read_as[0];
  EXPECT_TRUE(noted(rec, "the array start_t"));
  // Seconds, as float64 big-endian: 0.5 s, 1.25 s, 2.000001 s.
  std::string be;
  for (const double v : {0.5, 1.25, 2.000001}) {
    const std::string b = float_bytes(v);
    be += std::string(b.rbegin(), b.rend());
  }
  rec = read_npz(zip({{"x", x}, {"y", y}, {"timestamp", npy("'>f8'", "(3,)", be)}, {"polarity", p}}));
  expect_events(rec, {{500000, 1, 4, false}, {1250000, 2, 5, true}, {2000001, 3, 6, false}});
  EXPECT_NE(rec.read_as[0].find("stamps in seconds: they have fractions"), std::string::npos) << rec.read_as[0];
}

// EVIMO's layouts, as its ground-truth-format page describes them and pydvs's evimo-gen.py writes
// them: rows of (t in seconds, x, y, p) as float32, in an archive with the index of the events
// every `discretization` seconds (EVIMO, EVIMO2v1); or three arrays in a sequence's folder
// (EVIMO2v2, below).
std::string evimo_rows(bool fortran) {
  const float rows[3][4] = {{0.25f, 3, 4, 1}, {0.5f, 5, 6, 0}, {0.125f, 7, 8, 1}};
  std::string data;
  for (int c = 0; c < (fortran ? 4 : 1); ++c) {
    for (const auto& row : rows) {
      if (fortran) {
        data += float_bytes(row[c]);
      } else {
        for (const float v : row) data += float_bytes(v);
      }
    }
  }
  std::string text = npy("'<f4'", "(3, 4)", data);
  if (fortran) text.replace(text.find("False"), 5, "True ");
  return text;
}

TEST(NpzEvents, EvimosArchiveAndSequenceFolderAreReadAsTheirPagesLayThemOut) {
  for (const bool fortran : {false, true}) {
    SCOPED_TRACE(fortran);
    const EventRecording rec = read_npz(zip({{"events", evimo_rows(fortran), true},
                                             {"index", npy("'<u4'", "(1,)", little<std::uint32_t>(0))},
                                             {"discretization", npy("'<f8'", "()", float_bytes(0.01))},
                                             {"classical", npy("'|O'", "()", "pickled")}}));
    expect_events(rec, {{125000, 7, 8, true}, {250000, 3, 4, true}, {500000, 5, 6, false}});
    ASSERT_EQ(rec.read_as.size(), 1u);
    EXPECT_NE(rec.read_as[0].find("EVIMO's events array, its columns t (seconds), x, y, p"), std::string::npos);
    EXPECT_TRUE(noted(rec, "the array classical"));
  }
  // The same rows without EVIMO's index name no columns: refused, naming what the archive holds.
  testing::expect_refused_saying([] { read_npz(zip({{"events", evimo_rows(false)}, {"K", npy("'<f8'", "()", float_bytes(1.0))}})); },
                                 "the archive holds events, K");

}

using EvimoFolder = testing::TempDirTest;

TEST_F(EvimoFolder, ItsThreeArraysAreReadAsTheEvents) {
  write("dataset_events_t.npy", npy("'<f4'", "(3,)", float_bytes(0.25f) + float_bytes(0.5f) + float_bytes(0.125f)));
  write("dataset_events_xy.npy", npy("'<u2'", "(3, 2)", little<std::uint16_t>(3) + little<std::uint16_t>(4) + little<std::uint16_t>(5) +
                                                            little<std::uint16_t>(6) + little<std::uint16_t>(7) + little<std::uint16_t>(8)));
  const std::string folder = dir_.string();
  testing::expect_refused_saying([&] { load_events(folder); }, "without dataset_events_p.npy");
  write("dataset_events_p.npy", npy("'|u1'", "(3,)", std::string("\x01\x00\x01", 3)));
  const EventRecording rec = load_events(folder);
  expect_events(rec, {{125000, 7, 8, true}, {250000, 3, 4, true}, {500000, 5, 6, false}});
  EXPECT_NE(rec.read_as.at(0).find("an EVIMO2 sequence's folder"), std::string::npos);
  testing::expect_refused_saying([&] { load_events(folder, std::nullopt, "davis346"); },
                                 "--layout: jAER's layouts are for AEDAT 2.0 files; this one is an EVIMO2 sequence's folder");
  write("dataset_events_p.npy", npy("'|u1'", "(2,)", std::string("\x01\x00", 2)));
  testing::expect_refused_saying([&] { load_events(folder); }, "hold 3, 3, 3 and 2 numbers");
  // A header claiming more events than aesim reads is refused before the numbers are taken.
  write("dataset_events_p.npy", npy("'|u1'", "(300000000,)", ""));
  testing::expect_refused_saying([&] { load_events(folder); }, "more than the 268435456 events");
}

TEST(NpzEvents, MalformedArchivesAndOnesWithoutEventsAreOneLineErrors) {
  const auto refused = [](const std::string& bytes, const std::string& words) {
    testing::expect_refused_saying([&] { read_npz(bytes); }, words);
  };
  const std::string good = zip({{"event_data", structured(), true}});
  ASSERT_EQ(read_npz(good).events.size(), 3u);
  refused("short", "not a .npz archive (too short for a ZIP file's end record)");
  refused(good.substr(0, good.size() - 30), "not a .npz archive (no ZIP end record)");
  refused(structured(), "a .npy file named .npz: rename it .npy");
  refused(zip({{"event_data", structured(), true, false, 1}}), "its data do not match their CRC32");
  std::string flipped = good;
  flipped[120] = static_cast<char>(flipped[120] ^ 0x55);
  refused(flipped, "event_data.npy");
  refused(zip({{"frame", npy("'|u1'", "(4,)", "abcd")}}), "no events (a structured array of x, y, t, p, arrays x, y, t and p, or EVIMO's events of N x 4 beside its "
                                                      "index and discretization; the archive holds frame)");
  refused(zip({{"events", npy("'<f8'", "(1, 4)", std::string(32, '\0'))}}), "the archive holds events");
  const std::string x = npy("'<u2'", "(2,)", little<std::uint16_t>(1) + little<std::uint16_t>(2));
  refused(zip({{"x", x}, {"y", x}, {"t", x}, {"p", npy("'<u2'", "(1,)", little<std::uint16_t>(1))}}),
          "the arrays x, y, t and p hold 2, 2, 2 and 1 numbers");
  refused(zip({{"x", npy("'<f4'", "(2,)", float_bytes(0.5f) + float_bytes(1.0f))}, {"y", x}, {"t", x}, {"p", x}}),
          "event 0 at (0.5, 1) is not a pixel");
  refused(zip({{"x", npy("'<c8'", "(2,)", std::string(16, '\0'))}, {"y", x}, {"t", x}, {"p", x}}), "its dtype '<c8' is not one of");
  // An array of more events than aesim reads, refused from its header before it is read whole.
  refused(zip({{"x", npy("'<u2'", "(300000000,)", "")}, {"y", x}, {"t", x}, {"p", x}}), "x holds more than the 268435456 events");
  // A deflated member claiming far more than deflate can make of its bytes, refused before inflating.
  std::string claim = zip({{"event_data", structured(), true}});
  const std::size_t size_at = claim.find(std::string("PK\x01\x02", 4)) + 24;
  claim.replace(size_at, 4, little<std::uint32_t>(0x7FFFFFFFu));
  refused(claim, "claims 2147483647 bytes from");
}

}  // namespace
}  // namespace aesim
