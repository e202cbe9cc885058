// The field's event files (docs/reference.md section 5): AEDAT 4.0, NumPy .npy with tonic's dtype and HDF5 in
// the DSEC layout, each checked at the byte level against its published layout and read back by
// every command that reads events. (tests/python reads them with NumPy, h5py and FlatBuffers'
// Python code: readers that are not aesim's.)
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <tuple>

#include <flatbuffers/flatbuffers.h>
#include <gtest/gtest.h>
#include <hdf5.h>
#include <lz4frame.h>

#include "FileDataTable_generated.h"
#include "IOHeader_generated.h"
#include "aesim/errors/input_error.hpp"
#include "aesim/event_files/aedat4.hpp"
#include "aesim/event_files/aedat_layout.hpp"
#include "aesim/event_files/ecf_codec.hpp"
#include "aesim/event_files/event_formats.hpp"
#include "aesim/event_files/event_file.hpp"
#include "aesim/event_files/event_writer.hpp"
#include "aesim/event_files/npy_events.hpp"
#include "aesim/event_files/prophesee_dat.hpp"
#include "events_generated.h"
#include "aesim/output/atomic_file.hpp"
#include "support/recorded_events.hpp"
#include "support/temp_dir_test.hpp"

namespace aesim {
namespace {
namespace fs = std::filesystem;
using testing::noted;

// A .npy and a Prophesee RAW file hold no tiles: read back, the array is one.
bool no_tiles_in(const std::string& name) {
  return name.size() >= 4 && (name.compare(name.size() - 4, 4, ".npy") == 0 || name.compare(name.size() - 4, 4, ".raw") == 0);
}

class EventFormats : public testing::TempDirTest {
 protected:
  // Events of a 64x64 array in 32x32 tiles: times in whole microseconds, one ghost.
  static std::vector<AddressEvent> sample(const AddressMap& map) {
    const struct {
      std::uint32_t x, y;
      double t;
      bool ghost;
    } given[] = {{0, 0, 0.0, false}, {37, 2, 1e-6, false}, {5, 40, 2.5e-3, true}, {63, 63, 1.0, false}, {63, 63, 1.0, false}};
    std::vector<AddressEvent> out;
    for (const auto& g : given) {
      AddressEvent e = map.event_at({g.x, g.y});
      e.t = g.t;
      e.flags = g.ghost ? kGhostEvent : kNormalEvent;
      out.push_back(e);
    }
    return out;
  }

  std::string write(const std::string& name, const std::vector<AddressEvent>& events,
                    Aedat4Compression compression = Aedat4Compression::Lz4) {
    EventFileSpec spec;
    spec.array = ArrayParams{};
    spec.sensor = {{"array.rows", "64"}, {"array.cols", "64"}, {"array.tile_rows", "32"}, {"array.tile_cols", "32"},
                   {"pixel.c_int", "1e-13"}};
    spec.duration = 1.002;
    spec.compression = compression;
    const std::string path = (dir_ / name).string();
    write(spec, path, events);
    return path;
  }
  // `events` as a Prophesee RAW file in EVT 3.0 from a run of `duration` s.
  std::string write_evt3(const std::string& name, const std::vector<AddressEvent>& events, double duration) {
    EventFileSpec spec;
    spec.array = ArrayParams{};
    spec.duration = duration;
    spec.raw_encoding = RawEncoding::Evt3;
    const std::string path = (dir_ / name).string();
    write(spec, path, events);
    return path;
  }
  // Writes `events` to `path` as `spec` says; how many the writer left out as naming no pixel.
  static std::uint64_t write(const EventFileSpec& spec, const std::string& path, const std::vector<AddressEvent>& events) {
    OutputFiles files;
    auto writer = open_event_writer(files, path, spec);
    writer->events(events.data(), events.size());
    writer->finish();
    const std::uint64_t off_array = writer->off_array();
    writer.reset();  // before the files it writes to
    files.commit();
    return off_array;
  }

  static std::string slurp(const std::string& path) { return testing::slurp(path); }
  static std::vector<std::uint64_t> aligned(const std::string& bytes) {
    std::vector<std::uint64_t> words((bytes.size() + 7) / 8);
    std::memcpy(words.data(), bytes.data(), bytes.size());
    return words;
  }
};

TEST_F(EventFormats, EveryFormatReadsBackEventForEventWithItsArray) {
  const AddressMap map{ArrayParams{}};
  const std::vector<AddressEvent> events = sample(map);
  for (const std::string name : {"e.aedat", "e.aedat2", "e.aedat4", "n.aedat4", "e.npy", "e.h5", "e.raw"}) {
    const std::string path =
        write(name, events, name[0] == 'n' ? Aedat4Compression::None : Aedat4Compression::Lz4);
    const EventRecording rec = load_events(path);
    ASSERT_EQ(rec.events.size(), events.size()) << name;
    for (std::size_t i = 0; i < events.size(); ++i) {
      EXPECT_EQ(rec.events[i].x, events[i].x) << name << " event " << i;
      EXPECT_EQ(rec.events[i].y, events[i].y) << name << " event " << i;
      const bool no_tiles = name == "e.npy" || name == "e.raw";
      if (!no_tiles) {  // a .npy or .raw records no tiles
        EXPECT_EQ(rec.events[i].tile, events[i].tile) << name << " event " << i;
        EXPECT_EQ(rec.events[i].bus_address, events[i].bus_address) << name << " event " << i;
      }
      EXPECT_DOUBLE_EQ(rec.events[i].t, events[i].t) << name << " event " << i;
      // aesim's AEDAT 2.0 layout has no polarity bit: a ghost reads back as an event.
      const bool aedat2 = name == "e.aedat" || name == "e.aedat2";
      // A .npy or .raw cannot say who wrote it, so p = 0 (CD_OFF) reads as a DVS's OFF event, an
      // aesim ghost too.
      const bool ghost = events[i].flags == kGhostEvent;
      const std::uint8_t flags = aedat2               ? std::uint8_t{kNormalEvent}
                                 : no_tiles && ghost ? std::uint8_t{kOffEvent}
                                                     : events[i].flags;
      EXPECT_EQ(rec.events[i].flags, flags) << name << " event " << i;
    }
    // .npy cannot carry the array (NumPy refuses extra header keys): the events' span stands in.
    EXPECT_EQ(rec.size_recorded, name != "e.npy") << name;
    EXPECT_EQ(rec.width, 64) << name;
    EXPECT_EQ(rec.tiles, no_tiles_in(name) ? 1 : 4) << name;
  }
}

// Each format is one row of event_formats(): every extension of a row names that row; what --out
// writes each row reads back; the program's help texts list the rows; docs/event_files.md's format
// table names every extension. A format added without its row, or a row left out of the help or the
// docs, fails here.
TEST_F(EventFormats, EveryFormatIsOneRowOfTheTable) {
  const AddressMap map{ArrayParams{}};
  const std::string docs = testing::slurp(std::string(AESIM_SOURCE_DIR) + "/docs/event_files.md");
  const testing::Outcome run_help = aesim("run --help");
  const testing::Outcome recon_help = aesim("recon --help");
  std::size_t writable = 0;
  for (const EventFormatRow& row : event_formats()) {
    SCOPED_TRACE(row.name);
    ASSERT_FALSE(row.extensions.empty());
    ASSERT_NE(row.read, nullptr);
    for (const std::string& ext : row.extensions) {
      EXPECT_EQ(event_format_of("a/b" + ext, "--out").format, row.format) << ext;
      EXPECT_NE(docs.find("`" + ext + "`"), std::string::npos) << ext << " is not in docs/event_files.md";
    }
    EXPECT_NE(recon_help.out.find(row.extensions.front()), std::string::npos);
    if (row.longest_run > 0) {
      EXPECT_FALSE(std::string(row.stamps).empty());
    }
    if (!row.open) continue;
    ++writable;
    const std::string path = write("row" + row.extensions.back(), sample(map));
    EXPECT_EQ(load_events(path).events.size(), sample(map).size());
    if (row.decode) {
      EXPECT_EQ(decode_events(slurp(path), path, row.format).events.size(), sample(map).size());
    }
  }
  EXPECT_EQ(writable, 6u);
  EXPECT_NE(run_help.out.find(event_formats_help()), std::string::npos) << run_help.out;
  EXPECT_THROW(event_format_of("events.mp4", "--out"), InputError);
}

// HDF5 stamps every object's header with the wall-clock time unless told not to, so two runs of
// the same inputs would differ in bytes a second apart: an .h5 records no time in any object.
TEST_F(EventFormats, AnH5FileHoldsNoWallClockTimeSoRunsGiveTheSameBytes) {
  const AddressMap map{ArrayParams{}};
  const std::string path = write("t.h5", sample(map), Aedat4Compression::Lz4);
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  for (const char* object : {"/", "/events", "/events/x", "/events/y", "/events/t", "/events/p", "/ms_to_idx", "/t_offset"}) {
    H5O_info_t info;
    ASSERT_GE(H5Oget_info_by_name2(file, object, &info, H5O_INFO_TIME, H5P_DEFAULT), 0) << object;
    EXPECT_EQ(info.atime, 0) << object;
    EXPECT_EQ(info.mtime, 0) << object;
    EXPECT_EQ(info.ctime, 0) << object;
    EXPECT_EQ(info.btime, 0) << object;
  }
  H5Fclose(file);
}

// Metavision's HDF5 event file as Prophesee's format page and the evt3 crate's reader describe it:
// /CD/events, a 1-D compound of x, y (uint16), p (int16), t (int64, us). Written here with HDF5's C
// API, uncompressed (the ECF codec it is compressed with in Metavision's files is not in Debian);
// with ECF's filter code on the dataset and no plugin, a one-line error naming the way out.
TEST_F(EventFormats, MetavisionHdf5CdEventsAreReadWithTheirChunksFilteredOrNot) {
  struct Cd {
    std::uint16_t x, y;
    std::int16_t p;
    std::int64_t t;
  };
  const Cd written[] = {{303, 7, 1, 16}, {0, 239, 0, 17}, {12, 34, 1, 5000016}};
  const auto make = [&](const std::string& name, bool ecf) {
    const std::string path = (dir_ / name).string();
    const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    const hid_t group = H5Gcreate2(file, "CD", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    const hid_t type = H5Tcreate(H5T_COMPOUND, sizeof(Cd));
    H5Tinsert(type, "x", HOFFSET(Cd, x), H5T_NATIVE_UINT16);
    H5Tinsert(type, "y", HOFFSET(Cd, y), H5T_NATIVE_UINT16);
    H5Tinsert(type, "p", HOFFSET(Cd, p), H5T_NATIVE_INT16);
    H5Tinsert(type, "t", HOFFSET(Cd, t), H5T_NATIVE_INT64);
    const hsize_t n = 3;
    const hid_t space = H5Screate_simple(1, &n, nullptr);
    const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_chunk(dcpl, 1, &n);
    // Optional: this HDF5 (no ECF encoder) then writes the chunk unfiltered, marked so, while the
    // dataset names the filter, as ECF's do; the chunk is read as stored.
    if (ecf) H5Pset_filter(dcpl, 0x8ECF, H5Z_FLAG_OPTIONAL, 0, nullptr);
    const hid_t d = H5Dcreate2(group, "events", type, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    EXPECT_GE(H5Dwrite(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, written), 0);
    for (const hid_t id : {d, dcpl, space, type, group}) H5Idec_ref(id);
    H5Fclose(file);
    return path;
  };
  for (const bool ecf : {false, true}) {
    SCOPED_TRACE(ecf);
    const EventRecording rec = load_events(make(ecf ? "ecf.hdf5" : "mv.hdf5", ecf));
    ASSERT_EQ(rec.events.size(), 3u);
    for (std::size_t i = 0; i < 3; ++i) {
      SCOPED_TRACE(i);
      EXPECT_EQ(rec.events[i].x, written[i].x);
      EXPECT_EQ(rec.events[i].y, written[i].y);
      EXPECT_DOUBLE_EQ(rec.events[i].t, static_cast<double>(written[i].t) * 1e-6);
      EXPECT_EQ(rec.events[i].flags, written[i].p ? kNormalEvent : kOffEvent);
    }
    EXPECT_FALSE(rec.size_recorded);
  }
}

// A file written by Prophesee's own ECF plugin (scripts/make_ecf_fixture.py: three chunks of 1000
// events, one in each of ECF's three packings), read with aesim's decoder: every event as the
// script's formulas give it. A chunk whose block claims more events than ECF allows is one line.
TEST_F(EventFormats, MetavisionHdf5WithPropheseesEcfIsRead) {
  const std::string fixture = std::string(AESIM_SOURCE_DIR) + "/tests/fuzz/corpus/h5/metavision_ecf.hdf5";
  const EventRecording rec = load_events(fixture);
  ASSERT_EQ(rec.events.size(), 3000u);
  for (std::int64_t k = 0; k < 3000; ++k) {
    const std::int64_t c = k / 1000, j = k % 1000;
    const std::int64_t x = c == 0 ? (j * 101) % 640 : c == 1 ? (j * 131) % 640 : 10 + j % 64;
    const std::int64_t y = c == 0 ? (j * 37) % 480 : c == 1 ? 100 + j / 50 : 200 + j / 64;
    const bool on = (c == 2 ? (j / 7) % 2 : j % 2) != 0;
    const std::int64_t t = 1000 + (k / 20) * 3 + (k / 500) * 100000;
    const AddressEvent& e = rec.events[static_cast<std::size_t>(k)];
    ASSERT_TRUE(e.x == x && e.y == y && e.flags == (on ? kNormalEvent : kOffEvent) && std::llround(e.t * 1e6) == t)
        << "event " << k << ": (" << e.x << ", " << e.y << ") at " << e.t << " s, flags " << int(e.flags);
  }
  // jAER's chips are for AEDAT 2.0 alone.
  testing::expect_refused_saying([&] { load_events(fixture, std::nullopt, "dvs128"); },
                                 "--layout: jAER's layouts are for AEDAT 2.0 files; this one is HDF5");
  // The third chunk's block begins with its count word, 1000 << 2 and no packing: 0x00000FA0.
  std::string bytes = testing::slurp(fixture);
  const auto at = bytes.find(std::string("\xA0\x0F\x00\x00", 4));
  ASSERT_NE(at, std::string::npos);
  const std::uint32_t claim = 70000u << 2;
  bytes.replace(at, 4, reinterpret_cast<const char*>(&claim), 4);
  std::ofstream(dir_ / "claims.hdf5", std::ios::binary) << bytes;
  testing::expect_refused_saying([&] { load_events((dir_ / "claims.hdf5").string()); },
                                 "cannot read /CD/events: in the chunk from event 0, ECF block, byte 4: the block claims 70000 events");
}

// ECF blocks laid out by hand from the codec's format (ecf_codec.hpp), through each escape: a step
// of time in three nibbles, counts past their short fields (stamps, a row, a polarity), masked
// columns, and both packings; a block cut short or describing more events than it claims throws.
TEST(EcfBlocks, DecodeAsTheirFormatSays) {
  const auto u16 = [](unsigned v) { return std::string{static_cast<char>(v & 0xFF), static_cast<char>(v >> 8)}; };
  const auto u32 = [&](std::uint32_t v) { return u16(v & 0xFFFF) + u16(v >> 16); };
  const auto u64 = [&](std::uint64_t v) { return u32(static_cast<std::uint32_t>(v)) + u32(static_cast<std::uint32_t>(v >> 32)); };
  struct Out {
    unsigned x, y;
    int p;
    std::int64_t t;
  };
  const auto decode = [](const std::string& block) {
    std::vector<unsigned char> out(kEcfMostEvents * kEcfEventBytes);
    const std::size_t n = decode_ecf_block(reinterpret_cast<const unsigned char*>(block.data()), block.size(), out.data()) / kEcfEventBytes;
    std::vector<Out> events;
    for (std::size_t i = 0; i < n; ++i) {
      std::uint16_t x, y;
      std::int16_t p;
      std::int64_t t;
      std::memcpy(&x, &out[i * 16], 2);
      std::memcpy(&y, &out[i * 16 + 2], 2);
      std::memcpy(&p, &out[i * 16 + 4], 2);
      std::memcpy(&t, &out[i * 16 + 8], 8);
      events.push_back({x, y, p, t});
    }
    return events;
  };
  // Masked columns: 20 events. Stamps from 1000: a step of 300 (0x12C: nibbles C, 2, 1, each in a
  // byte whose step is 15), then 4 events; a step of 2 with 16 events (a count of 15, then 16 bits).
  const std::string stamps = u64(1000) + "\xFC\xF2\xF1" + std::string("\x04", 1) + "\x2F" + u16(16);
  const std::string masked = u32(20 << 2) + stamps + u16((7 << 5) | 31) + u16(20) +         // row 7, 20 events
                             u16((100 << 5) | 0b11111) + u16((200 << 5) | 0b10100) +       // 100-105; 200, 201, 203
                             u16((300 << 5) | 0b11111) + u16((400 << 5) | 0b11110) +       // 300-305; 400-404
                             "\xFF" + u16(12) + "\x08";                                    // 12 ON, then 8 OFF
  const std::vector<Out> m = decode(masked);
  ASSERT_EQ(m.size(), 20u);
  const unsigned xs[20] = {100, 101, 102, 103, 104, 105, 200, 201, 203, 300, 301, 302, 303, 304, 305, 400, 401, 402, 403, 404};
  for (std::size_t i = 0; i < 20; ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(m[i].x, xs[i]);
    EXPECT_EQ(m[i].y, 7u);
    EXPECT_EQ(m[i].p, i < 12 ? 1 : 0);
    EXPECT_EQ(m[i].t, i < 4 ? 1300 : 1302);
  }
  // x and p in 12 bits (x << 1 | p), four to three 16-bit words; five events, so two groups.
  const auto pack12 = [&](const std::array<unsigned, 4>& v) {
    return u16((v[0] << 4) | (v[1] & 0xF)) + u16(((v[1] >> 4) << 8) | (v[2] & 0xFF)) + u16(((v[2] >> 8) << 12) | v[3]);
  };
  const std::vector<Out> b = decode(u32((5 << 2) | 1) + u64(7) + "\x05" + u16((9 << 5) | 5) +
                                    pack12({(1 << 1) | 1, 2 << 1, (2047 << 1) | 1, 640 << 1}) + pack12({5 << 1, 0, 0, 0}));
  ASSERT_EQ(b.size(), 5u);
  const unsigned bx[5] = {1, 2, 2047, 640, 5};
  const int bp[5] = {1, 0, 1, 0, 0};
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(b[i].x, bx[i]);
    EXPECT_EQ(b[i].y, 9u);
    EXPECT_EQ(b[i].p, bp[i]);
    EXPECT_EQ(b[i].t, 7);
  }
  // y, x and p in 24 bits (y << 12 | x << 1 | p), four to three 32-bit words.
  const std::array<std::uint32_t, 4> v = {(479u << 12) | (639u << 1) | 1, (1u << 12) | (2u << 1), (2047u << 12) | 1, 3u << 1};
  const std::string pack24 =
      u32((v[0] << 8) | (v[1] & 0xFF)) + u32(((v[1] >> 8) << 16) | (v[2] & 0xFFFF)) + u32(((v[2] >> 16) << 24) | v[3]);
  const std::vector<Out> a = decode(u32((4 << 2) | 2) + u64(5) + "\x14" + pack24);
  ASSERT_EQ(a.size(), 4u);
  EXPECT_TRUE(a[0].x == 639 && a[0].y == 479 && a[0].p == 1 && a[0].t == 6);
  EXPECT_TRUE(a[1].x == 2 && a[1].y == 1 && a[1].p == 0 && a[1].t == 6);
  EXPECT_TRUE(a[2].x == 0 && a[2].y == 2047 && a[2].p == 1 && a[2].t == 6);
  EXPECT_TRUE(a[3].x == 3 && a[3].y == 0 && a[3].p == 0 && a[3].t == 6);
  EXPECT_EQ(decode(u32(0) + u64(9)).size(), 0u);
  const auto refused = [&](const std::string& block, const std::string& words) {
    try {
      decode(block);
      ADD_FAILURE() << "decoded: " << words;
    } catch (const EcfError& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  refused(masked.substr(0, masked.size() - 1), "ECF block, byte " + std::to_string(masked.size() - 1) + ": its polarities of 1 bytes runs past the end");
  refused(u32(19 << 2) + masked.substr(4), "stamps for 20 events past the block's 19");
  refused(u32(70000u << 2), "the block claims 70000 events");
  refused(u32(1 << 2) + u64(0) + std::string(17, '\xFF'), "a step of time of more than 64 bits");
}

// Event tables, one row an event, as their writers lay them out: v2e's emulator (`/events`, uint32
// rows t in us, x, y, p 0/1, appended in batches; v2e warns that its stamps may go back) and
// MVSEC's data files (`/davis/left/events` and `/davis/right/events`, float64 rows x, y, t in s of
// ROS time, p -1/1). Written here with HDF5's C API.
TEST_F(EventFormats, V2eAndMvsecHdf5EventTablesAreReadInTimeOrder) {
  const auto make = [&](const std::string& name, const std::vector<std::string>& groups, const char* dataset,
                        hid_t type, const void* rows, hsize_t n) {
    const std::string path = (dir_ / name).string();
    const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    for (const std::string& g : groups) H5Idec_ref(H5Gcreate2(file, g.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
    const hsize_t dims[2] = {n, 4};
    const hid_t space = H5Screate_simple(2, dims, nullptr);
    const hid_t d = H5Dcreate2(file, dataset, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    EXPECT_GE(H5Dwrite(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, rows), 0);
    H5Idec_ref(d);
    H5Idec_ref(space);
    H5Fclose(file);
    return path;
  };
  const std::uint32_t v2e_rows[][4] = {{10, 345, 259, 1}, {25, 0, 0, 0}, {20, 7, 8, 1}, {4000000, 9, 9, 0}};
  const EventRecording v2e = load_events(make("v2e.h5", {}, "/events", H5T_NATIVE_UINT32, v2e_rows, 4));
  ASSERT_EQ(v2e.events.size(), 4u);
  const std::size_t v2e_order[] = {0, 2, 1, 3};  // 20 us before 25 us
  for (std::size_t i = 0; i < 4; ++i) {
    SCOPED_TRACE(i);
    const std::uint32_t* row = v2e_rows[v2e_order[i]];
    EXPECT_DOUBLE_EQ(v2e.events[i].t, row[0] * 1e-6);
    EXPECT_EQ(v2e.events[i].x, row[1]);
    EXPECT_EQ(v2e.events[i].y, row[2]);
    EXPECT_EQ(v2e.events[i].flags, row[3] ? kNormalEvent : kOffEvent);
  }
  EXPECT_EQ(v2e.reordered, 1u);
  EXPECT_FALSE(v2e.size_recorded);
  EXPECT_EQ(v2e.width, 346);
  const double mvsec_rows[][4] = {{3, 4, 1506117899.000001, -1}, {345, 259, 1506117899.5, 1}};
  const EventRecording mvsec =
      load_events(make("mvsec.hdf5", {"davis", "davis/left", "davis/right"}, "/davis/left/events", H5T_NATIVE_DOUBLE, mvsec_rows, 2));
  ASSERT_EQ(mvsec.events.size(), 2u);
  EXPECT_EQ(mvsec.events[0].x, 3u);
  EXPECT_EQ(mvsec.events[0].y, 4u);
  EXPECT_EQ(mvsec.events[0].flags, kOffEvent);
  EXPECT_EQ(mvsec.events[1].flags, kNormalEvent);
  EXPECT_EQ(std::llround(mvsec.events[0].t * 1e6), 1506117899000001LL);
  EXPECT_EQ(std::llround((mvsec.events[1].t - mvsec.events[0].t) * 1e6), 499999);
  // A table that is no event table: a one-line error naming it.
  const double three[][3] = {{1, 2, 3}};
  const std::string path = (dir_ / "three.h5").string();
  const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const hsize_t dims[2] = {1, 3};
  const hid_t space = H5Screate_simple(2, dims, nullptr);
  const hid_t d = H5Dcreate2(file, "events", H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, three);
  H5Idec_ref(d);
  H5Idec_ref(space);
  H5Fclose(file);
  try {
    load_events(path);
    ADD_FAILURE() << "read a table of three columns";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/events is not a table of numbers with four columns"), std::string::npos) << e.what();
  }
  const double off_pixel[][4] = {{1.5, 2, 0.1, 1}};
  try {
    load_events(make("half.hdf5", {"davis", "davis/left"}, "/davis/left/events", H5T_NATIVE_DOUBLE, off_pixel, 1));
    ADD_FAILURE() << "read x = 1.5";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("is not a pixel"), std::string::npos) << e.what();
  }
}

// A 1-D dataset `name` of `n` values of `type` in `group`, by HDF5's C API.
void h5_column(hid_t group, const char* name, hid_t type, const void* values, hsize_t n) {
  const hid_t space = H5Screate_simple(1, &n, nullptr);
  const hid_t d = H5Dcreate2(group, name, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  EXPECT_GE(H5Dwrite(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values), 0);
  H5Idec_ref(d);
  H5Idec_ref(space);
}

// Other datasets keep an event column a dataset in a group of their own: M3ED's
// /prophesee/left/{x,y,t,p} beside its right camera's (uint16 x and y, int64 t in us, int8 p), or
// a file's root holding x, y, ts and polarity (-1/1). The first such group by name is read, the
// others counted; the columns' names are said in `info`'s "read as". Written here with HDF5's C
// API.
TEST_F(EventFormats, AnyGroupOfEventColumnsIsReadTheFirstByName) {
  const std::uint16_t x[] = {1279, 3, 4}, y[] = {719, 5, 6};
  const std::int64_t t[] = {300, 100, 200};
  const std::int8_t p[] = {1, 0, 1};
  const std::string m3ed = (dir_ / "m3ed.h5").string();
  hid_t file = H5Fcreate(m3ed.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  H5Idec_ref(H5Gcreate2(file, "prophesee", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  for (const char* camera : {"prophesee/right", "prophesee/left"}) {
    const hid_t g = H5Gcreate2(file, camera, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    const hsize_t n = std::string(camera) == "prophesee/left" ? 3 : 1;
    h5_column(g, "x", H5T_NATIVE_UINT16, x, n);
    h5_column(g, "y", H5T_NATIVE_UINT16, y, n);
    h5_column(g, "t", H5T_NATIVE_INT64, t, n);
    h5_column(g, "p", H5T_NATIVE_INT8, p, n);
    H5Idec_ref(g);
  }
  H5Fclose(file);
  const EventRecording rec = load_events(m3ed);
  ASSERT_EQ(rec.events.size(), 3u);
  const std::size_t order[] = {1, 2, 0};
  for (std::size_t i = 0; i < 3; ++i) {
    SCOPED_TRACE(i);
    EXPECT_DOUBLE_EQ(rec.events[i].t, static_cast<double>(t[order[i]]) * 1e-6);
    EXPECT_EQ(rec.events[i].x, x[order[i]]);
    EXPECT_EQ(rec.events[i].y, y[order[i]]);
    EXPECT_EQ(rec.events[i].flags, p[order[i]] ? kNormalEvent : kOffEvent);
  }
  EXPECT_TRUE(noted(rec, "the events of /prophesee/right (/prophesee/left's are read)"));
  ASSERT_EQ(rec.read_as.size(), 1u);
  EXPECT_NE(rec.read_as[0].find("/prophesee/left/x, /prophesee/left/y, /prophesee/left/t, /prophesee/left/p"), std::string::npos);

  const std::string root = (dir_ / "root.h5").string();
  file = H5Fcreate(root.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const std::int32_t ts[] = {7, 9};
  const std::int16_t polarity[] = {-1, 1};
  h5_column(file, "x", H5T_NATIVE_UINT16, x, 2);
  h5_column(file, "y", H5T_NATIVE_UINT16, y, 2);
  h5_column(file, "ts", H5T_NATIVE_INT32, ts, 2);
  h5_column(file, "polarity", H5T_NATIVE_INT16, polarity, 2);
  H5Fclose(file);
  const EventRecording flat = load_events(root);
  ASSERT_EQ(flat.events.size(), 2u);
  EXPECT_EQ(flat.events[0].flags, kOffEvent);  // -1
  EXPECT_EQ(flat.events[1].flags, kNormalEvent);
  EXPECT_DOUBLE_EQ(flat.events[1].t, 9e-6);

  const std::string none = (dir_ / "none.h5").string();
  file = H5Fcreate(none.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  h5_column(file, "x", H5T_NATIVE_UINT16, x, 2);
  h5_column(file, "t", H5T_NATIVE_INT64, t, 2);
  H5Fclose(file);
  try {
    load_events(none);
    ADD_FAILURE() << "a file of no events read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no events (aesim reads /events/{x,y,t,p} as DSEC"), std::string::npos) << e.what();
  }
}

// event_utils' HDF5 (Stoffregen's, for E2VID and its kin): /events/xs, ys, ts in float seconds and
// ps as h5py writes a bool (an enum), the size as the root's sensor_resolution [height, width]. A
// float stamp of whole numbers is microseconds. Written here with HDF5's C API.
TEST_F(EventFormats, EventUtilsHdf5WithFloatSecondsIsRead) {
  // h5py's bool: an enum over a signed byte, FALSE 0 and TRUE 1.
  const hid_t boolean = H5Tenum_create(H5T_NATIVE_INT8);
  const std::int8_t no = 0, yes = 1;
  H5Tenum_insert(boolean, "FALSE", &no);
  H5Tenum_insert(boolean, "TRUE", &yes);
  const std::int16_t xs[] = {239, 3}, ys[] = {179, 5};
  const std::int8_t ps[] = {1, 0};
  for (const auto& [name, t0, t1, expected, words] :
       {std::tuple<const char*, double, double, double, const char*>{"seconds.h5", 0.5, 0.75, 0.75, "in seconds"},
        {"micro.h5", 1000.0, 2500.0, 2.5e-3, "in microseconds"}}) {
    const std::string path = (dir_ / name).string();
    const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    const hid_t g = H5Gcreate2(file, "events", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    const double ts[] = {t0, t1};
    h5_column(g, "xs", H5T_NATIVE_INT16, xs, 2);
    h5_column(g, "ys", H5T_NATIVE_INT16, ys, 2);
    h5_column(g, "ts", H5T_NATIVE_DOUBLE, ts, 2);
    h5_column(g, "ps", boolean, ps, 2);
    const hsize_t two = 2;
    const long long hw[] = {180, 240};
    const hid_t space = H5Screate_simple(1, &two, nullptr);
    const hid_t attr = H5Acreate2(file, "sensor_resolution", H5T_NATIVE_LLONG, space, H5P_DEFAULT, H5P_DEFAULT);
    EXPECT_GE(H5Awrite(attr, H5T_NATIVE_LLONG, hw), 0);
    H5Aclose(attr);
    H5Sclose(space);
    H5Gclose(g);
    H5Fclose(file);
    const EventRecording rec = load_events(path);
    SCOPED_TRACE(name);
    EXPECT_EQ(rec.width, 240);
    EXPECT_EQ(rec.height, 180);
    ASSERT_EQ(rec.events.size(), 2u);
    EXPECT_EQ(rec.events[0].x, 239u);
    EXPECT_EQ(rec.events[0].y, 179u);
    EXPECT_EQ(rec.events[0].flags, kNormalEvent);
    EXPECT_EQ(rec.events[1].flags, kOffEvent);
    EXPECT_DOUBLE_EQ(rec.events[1].t, expected);
    ASSERT_EQ(rec.read_as.size(), 2u);
    EXPECT_NE(rec.read_as[0].find("/events/xs, /events/ys, /events/ts, /events/ps"), std::string::npos) << rec.read_as[0];
    EXPECT_NE(rec.read_as[1].find(words), std::string::npos) << rec.read_as[1];
  }
  H5Tclose(boolean);
}

// A ghost (the OR of colliding addresses) may name no pixel of the array: past a narrow edge tile.
// Every event file leaves it out and counts it: no reader could place it (aesim's own AEDAT 2.0
// reader refuses such an address).
TEST_F(EventFormats, AGhostNamingNoPixelIsLeftOutOfCoordinateFormats) {
  ArrayParams array;
  array.rows = 40;
  array.cols = 40;  // tile 1 is 8 columns wide, its bus addresses 5 bits of x
  array.tile_rows = array.tile_cols = 32;
  const AddressMap map(array);
  std::vector<AddressEvent> events = {map.event_at({3, 4}), map.event_at({36, 9})};
  AddressEvent ghost = map.event_at({33, 9});
  ghost.bus_address |= 20u;  // local x 21: x 53, past the 40 columns
  const PixelAddress at = map.locate(ghost.tile, ghost.bus_address);
  ghost.x = at.x;
  ghost.y = at.y;
  ghost.flags = kGhostEvent;
  ASSERT_GE(ghost.x, 40u);
  events.insert(events.begin() + 1, ghost);
  for (std::size_t i = 0; i < events.size(); ++i) events[i].t = 1e-3 * static_cast<double>(i + 1);
  for (const std::string name : {"g.aedat4", "g.npy", "g.h5", "g.aedat", "g_dvs.aedat"}) {
    EventFileSpec spec;
    spec.array = array;
    spec.sensor = {{"array.rows", "40"}, {"array.cols", "40"}, {"array.tile_rows", "32"}, {"array.tile_cols", "32"}};
    spec.duration = 0.01;
    if (name == "g_dvs.aedat") spec.layout = AedatLayout::Dvs128;
    const std::string path = (dir_ / name).string();
    EXPECT_EQ(write(spec, path, events), 1u) << name;
    const EventRecording rec = load_events(path);
    ASSERT_EQ(rec.events.size(), 2u) << name;
    EXPECT_EQ(rec.events[0].x, 3u) << name;
    EXPECT_EQ(rec.events[1].x, 36u) << name;
  }
}

TEST_F(EventFormats, NpyIsFormatOneWithTonicsPackedDtype) {
  const AddressMap map{ArrayParams{}};
  const std::string data = slurp(write("e.npy", sample(map)));
  // 10 bytes of preamble and the header text make 256 (NumPy aligns data to 64); 13-byte records.
  ASSERT_EQ(data.size(), 256u + 5 * 13);
  EXPECT_EQ(data.substr(0, 8), std::string("\x93NUMPY\x01\x00", 8));
  EXPECT_EQ(static_cast<unsigned char>(data[8]) | (static_cast<unsigned char>(data[9]) << 8), 246);
  const std::string header = data.substr(10, 246);
  EXPECT_NE(header.find("'descr': [('x', '<i2'), ('y', '<i2'), ('t', '<i8'), ('p', '|b1')]"), std::string::npos);
  EXPECT_NE(header.find("'fortran_order': False"), std::string::npos);
  EXPECT_NE(header.find("5,)"), std::string::npos);
  EXPECT_EQ(header.back(), '\n');
  // Event 2: x = 5, y = 40, t = 2500 us, a ghost (p = 0), little-endian.
  const std::string r = data.substr(256 + 2 * 13, 13);
  EXPECT_EQ(r, std::string("\x05\x00\x28\x00\xc4\x09\x00\x00\x00\x00\x00\x00\x00", 13));
  EXPECT_EQ(data[256 + 3 * 13 + 12], 1);  // event 3 is normal
}

// Other scripts' structured arrays: the time named ts, timestamp or time and the polarity pol,
// polarity or on (or none: every event ON), either byte order, a float time (seconds when any
// stamp has a fraction, microseconds when all are whole, said in read_as), rows out of time order
// put in it and counted. Records laid out by hand as NumPy lays them (format 1.0, C order).
TEST_F(EventFormats, NpyArraysOfOtherScriptsAreReadByTheirFields) {
  const auto npy_of = [](const std::string& descr, std::size_t n, const std::string& records) {
    std::string text = "{'descr': " + descr + ", 'fortran_order': False, 'shape': (" + std::to_string(n) + ",), }";
    while ((10 + text.size() + 1) % 64 != 0) text += ' ';
    text += '\n';
    return std::string("\x93NUMPY\x01\x00", 8) + static_cast<char>(text.size() & 0xff) + static_cast<char>(text.size() >> 8) +
           text + records;
  };
  const auto le = [](std::uint64_t v, int bytes) {
    std::string out;
    for (int i = 0; i < bytes; ++i) out += static_cast<char>((v >> (8 * i)) & 0xff);
    return out;
  };
  const auto be = [&](std::uint64_t v, int bytes) {
    std::string out = le(v, bytes);
    return std::string(out.rbegin(), out.rend());
  };
  const auto f8 = [&](double d) {
    std::uint64_t bits;
    std::memcpy(&bits, &d, 8);
    return le(bits, 8);
  };
  // Big-endian 64-bit fields in tonic's order of names, the polarity named `polarity`.
  const EventRecording big = decode_events(
      npy_of("[('x', '>i8'), ('y', '>i8'), ('polarity', '>i8'), ('timestamp', '>i8')]", 2,
             be(7, 8) + be(9, 8) + be(1, 8) + be(1500, 8) + be(8, 8) + be(3, 8) + be(0, 8) + be(2500, 8)),
      "big.npy", EventFileFormat::Npy);
  ASSERT_EQ(big.events.size(), 2u);
  EXPECT_EQ(big.events[0].x, 7u);
  EXPECT_EQ(big.events[1].y, 3u);
  EXPECT_DOUBLE_EQ(big.events[1].t, 2.5e-3);
  EXPECT_EQ(big.events[1].flags, kOffEvent);
  // A float time with fractions is seconds; the same field of whole numbers microseconds.
  for (const auto& [t0, t1, expected, words] :
       {std::tuple<double, double, double, const char*>{0.25, 0.5, 0.5, "in seconds"}, {1000.0, 2000.0, 2e-3, "in microseconds"}}) {
    const EventRecording r = decode_events(npy_of("[('t', '<f8'), ('x', '<u2'), ('y', '<u2')]", 2,
                                                  f8(t0) + le(1, 2) + le(2, 2) + f8(t1) + le(3, 2) + le(4, 2)),
                                           "float.npy", EventFileFormat::Npy);
    ASSERT_EQ(r.events.size(), 2u);
    EXPECT_DOUBLE_EQ(r.events[1].t, expected);
    EXPECT_EQ(r.events[0].flags, kNormalEvent);  // no polarity field: ON
    ASSERT_EQ(r.read_as.size(), 1u);
    EXPECT_NE(r.read_as[0].find(words), std::string::npos) << r.read_as[0];
  }
  // Rows out of time order, as a concatenation of two recordings leaves them.
  const EventRecording late = decode_events(npy_of("[('x', '<i2'), ('y', '<i2'), ('ts', '<i8'), ('p', '|b1')]", 2,
                                                   le(1, 2) + le(1, 2) + le(3000, 8) + le(1, 1) + le(2, 2) + le(2, 2) +
                                                       le(1000, 8) + le(1, 1)),
                                            "late.npy", EventFileFormat::Npy);
  ASSERT_EQ(late.events.size(), 2u);
  EXPECT_EQ(late.events[0].x, 2u);
  EXPECT_EQ(late.reordered, 1u);
}

// NpyWriter is given OutputFiles' empty temporary and opens it as it is (no truncation, which
// would have ext4 write the whole file out when it is closed); a file that holds anything is
// truncated first: either way the file is the .npy's bytes and nothing after them.
TEST_F(EventFormats, NpyWriterLeavesNothingOfWhatTheFileHeld) {
  const AddressMap map{ArrayParams{}};
  const std::string expected = slurp(write("e.npy", sample(map)));
  for (const std::size_t held : {std::size_t(0), std::size_t(3), expected.size() + 4096}) {
    const std::string path = (dir_ / ("held_" + std::to_string(held) + ".npy")).string();
    { std::ofstream(path, std::ios::binary) << std::string(held, 'z'); }
    ASSERT_EQ(fs::file_size(path), held);
    NpyWriter writer(path, 1e-6);
    const std::vector<AddressEvent> events = sample(map);
    writer.events(events.data(), events.size());
    writer.finish();
    EXPECT_EQ(slurp(path), expected) << held << " bytes held before";
  }
  // A path with no file: made.
  const std::string fresh = (dir_ / "fresh.npy").string();
  NpyWriter writer(fresh, 1e-6);
  const std::vector<AddressEvent> events = sample(map);
  writer.events(events.data(), events.size());
  writer.finish();
  EXPECT_EQ(slurp(fresh), expected);
}

// A file that is `header` then exactly the little-endian words `expected` (16 or 32 bits).
template <typename Word>
void expect_words_after(const std::string& data, const std::string& header, const std::vector<Word>& expected) {
  ASSERT_EQ(data.compare(0, header.size(), header), 0) << data.substr(0, 200);
  ASSERT_EQ(data.size(), header.size() + sizeof(Word) * expected.size());
  std::vector<Word> words(expected.size());
  std::memcpy(words.data(), data.data() + header.size(), sizeof(Word) * words.size());
  EXPECT_EQ(words, expected);
}

// Prophesee's EVT 2.0, word by word as its format page defines them: a 32-bit little-endian word,
// its type in bits 31-28 (EVT_TIME_HIGH 0x8: the stamp's bits 33-6 in bits 27-0; CD_OFF 0x0 and
// CD_ON 0x1: the stamp's bits 5-0 in 27-22, x in 21-11, y in 10-0).
TEST_F(EventFormats, PropheseeRawIsEvt2WordsAfterItsHeader) {
  const AddressMap map{ArrayParams{}};
  const std::vector<AddressEvent> events = sample(map);  // 0 us, 1 us, 2500 us (a ghost), 1 s twice
  const std::string header = "% evt 2.0\n% format EVT2;height=64;width=64\n% geometry 64x64\n% integrator_name aesim\n% end\n";
  const std::vector<std::uint32_t> expected = {
      0x80000000u,                                  // time high 0
      0x10000000u | (0u << 22) | (0u << 11) | 0u,   // ON at 0 us, (0, 0)
      0x10000000u | (1u << 22) | (37u << 11) | 2u,  // ON at 1 us, (37, 2)
      0x80000000u | (2500u >> 6),                   // time high 39
      0x00000000u | ((2500u & 63) << 22) | (5u << 11) | 40u,  // OFF (the ghost) at 2500 us, (5, 40)
      0x80000000u | (1000000u >> 6),                // time high 15625
      0x10000000u | ((1000000u & 63) << 22) | (63u << 11) | 63u,
      0x10000000u | ((1000000u & 63) << 22) | (63u << 11) | 63u,  // the same stamp: no second time high
  };
  expect_words_after(slurp(write("e.raw", events)), header, expected);
}

// Prophesee's EVT 3.0 (--raw-encoding evt3), word by word as its format page defines them: a 16-bit
// little-endian word, its type in bits 15-12: EVT_TIME_HIGH 0x8 (the stamp's bits 23-12),
// EVT_TIME_LOW 0x6 (bits 11-0), EVT_ADDR_Y 0x0 (y; bit 11, the system type, 0), EVT_ADDR_X 0x2
// (polarity in bit 11, x).
TEST_F(EventFormats, PropheseeRawInEvt3IsItsWordsAfterItsHeader) {
  const AddressMap map{ArrayParams{}};
  const std::vector<AddressEvent> events = sample(map);  // 0 us, 1 us, 2500 us (a ghost), 1 s twice
  const std::string header = "% evt 3.0\n% format EVT3;height=64;width=64\n% geometry 64x64\n% integrator_name aesim\n% end\n";
  const auto word = [](unsigned type, unsigned value) { return static_cast<std::uint16_t>((type << 12) | value); };
  const std::uint16_t on = 1u << 11;
  // 1 s = 1,000,000 us = 244 * 4096 + 576.
  const std::vector<std::uint16_t> expected = {
      word(0x8, 0), word(0x6, 0), word(0x0, 0), word(0x2, on | 0),  // ON at 0 us, (0, 0)
      word(0x6, 1), word(0x0, 2), word(0x2, on | 37),               // ON at 1 us, (37, 2)
      word(0x6, 2500), word(0x0, 40), word(0x2, 5),                 // OFF (the ghost) at 2500 us, (5, 40)
      word(0x8, 244), word(0x6, 576), word(0x0, 63), word(0x2, on | 63),
      word(0x2, on | 63),  // the same instant and row: the event's word alone
  };
  expect_words_after(slurp(write_evt3("e3.raw", events, 1.002)), header, expected);
}

// EVT 3.0's time is 24 bits (16.8 s): from 0 us and across gaps of several wraps a time-high word
// every 2047 of its steps lets a reader count each wrap; aesim's reader gives back every stamp,
// also where the first event comes after several wraps.
TEST_F(EventFormats, PropheseeRawInEvt3KeepsStampsAcrossGapsOfSeveralWraps) {
  const AddressMap map{ArrayParams{}};
  for (const std::vector<double>& times : {std::vector<double>{0.0, 8.388607, 40.0, 40.000001, 100.25, 1000.0},
                                           std::vector<double>{50.5, 50.6}}) {
    std::vector<AddressEvent> events;
    for (const double t : times) {
      AddressEvent e = map.event_at({3, 4});
      e.t = t;
      events.push_back(e);
    }
    const EventRecording back = load_events(write_evt3("gaps.raw", events, 1000.001));
    ASSERT_EQ(back.events.size(), events.size());
    for (std::size_t i = 0; i < events.size(); ++i) {
      EXPECT_DOUBLE_EQ(back.events[i].t, std::round(events[i].t * 1e6) * 1e-6) << times.front() << " " << i;
    }
  }
}

// Prophesee's DAT, as its format page lays it out: '%' header lines, the event type (12, EventCd)
// and size (8) bytes, then two little-endian 32-bit words an event: the stamp in microseconds, and
// x in bits 13-0, y in 27-14, polarity in 31-28.
TEST_F(EventFormats, PropheseeDatIsTwoWordsAnEventAfterItsHeader) {
  const AddressMap map{ArrayParams{}};
  const std::vector<AddressEvent> events = sample(map);  // 0 us, 1 us, 2500 us (a ghost), 1 s twice
  const std::string header = "% Data file containing CD events\n% Version 2\n% Width 64\n% Height 64\n\x0c\x08";
  const std::vector<std::uint32_t> expected = {
      0u,       (1u << 28) | (0u << 14) | 0u,    // ON at 0 us, (0, 0)
      1u,       (1u << 28) | (2u << 14) | 37u,   // ON at 1 us, (37, 2)
      2500u,    (0u << 28) | (40u << 14) | 5u,   // OFF (the ghost) at 2500 us, (5, 40)
      1000000u, (1u << 28) | (63u << 14) | 63u,  // ON at 1 s, (63, 63), twice
      1000000u, (1u << 28) | (63u << 14) | 63u,
  };
  expect_words_after(slurp(write("e.dat", events)), header, expected);
  // A stamp past 32 bits (2^32 us is 4295 s) is refused, not wrapped.
  std::ostringstream out;
  PropheseeDatWriter writer(out, ArrayParams{}, 1e-6);
  std::vector<AddressEvent> late = {events[0]};
  late[0].t = 4295.0;
  EXPECT_THROW(writer.events(late.data(), late.size()), InputError);
  late[0].t = 4294.0;
  EXPECT_NO_THROW(writer.events(late.data(), late.size()));
}

TEST_F(EventFormats, Aedat4IsDvsFileHeaderAndSizePrefixedPackets) {
  const AddressMap map{ArrayParams{}};
  for (const Aedat4Compression c : {Aedat4Compression::None, Aedat4Compression::Lz4, Aedat4Compression::Zstd}) {
    const std::string data = slurp(write("e.aedat4", sample(map), c));
    ASSERT_EQ(data.compare(0, 14, "#!AER-DAT4.0\r\n"), 0);
    const auto* b = reinterpret_cast<const std::uint8_t*>(data.data());
    const std::uint32_t header_size = b[14] | (b[15] << 8) | (b[16] << 16) | (b[17] << 24);
    // Size-prefixed: the size, the root offset, then the file identifier.
    EXPECT_EQ(data.substr(22, 4), "IOHE");
    // FlatBuffers reads in place and needs its buffers aligned: read copies.
    const std::vector<std::uint64_t> header_copy = aligned(data.substr(14, 4 + header_size));
    const dv::IOHeader* h = dv::GetSizePrefixedIOHeader(header_copy.data());
    EXPECT_EQ(h->compression(), c == Aedat4Compression::Lz4    ? dv::CompressionType_LZ4
                                : c == Aedat4Compression::Zstd ? dv::CompressionType_ZSTD
                                                               : dv::CompressionType_NONE);
    const std::string info = h->infoNode()->str();
    EXPECT_NE(info.find("<attr key=\"typeIdentifier\" type=\"string\">EVTS</attr>"), std::string::npos);
    EXPECT_NE(info.find("<attr key=\"sizeX\" type=\"int\">64</attr>"), std::string::npos);
    EXPECT_NE(info.find("<attr key=\"aesim.sensor.pixel.c_int\" type=\"string\">1e-13</attr>"), std::string::npos);
    // One packet: stream 0, its size, then the body to the end of the file.
    const std::size_t at = 14 + 4 + header_size;
    ASSERT_GE(data.size(), at + 8);
    EXPECT_EQ(b[at] | (b[at + 1] << 8) | (b[at + 2] << 16) | (b[at + 3] << 24), 0);
    const std::uint32_t size = b[at + 4] | (b[at + 5] << 8) | (b[at + 6] << 16) | (b[at + 7] << 24);
    // The data table follows the last packet, where the header points; it fills the file.
    ASSERT_EQ(h->dataTablePosition(), static_cast<std::int64_t>(at + 8 + size));
    // Compressed as the packets are, with no packet header of its own.
    const std::string table = data.substr(at + 8 + size);
    if (c == Aedat4Compression::Lz4) {
      EXPECT_EQ(table.substr(0, 4), std::string("\x04\x22\x4d\x18", 4));
    }
    if (c == Aedat4Compression::Zstd) {
      EXPECT_EQ(table.substr(0, 4), std::string("\x28\xb5\x2f\xfd", 4));  // zstd's frame magic
    }
    if (c == Aedat4Compression::None) {
      const std::uint32_t table_size = b[at + 8 + size] | (b[at + 9 + size] << 8) | (b[at + 10 + size] << 16) |
                                       (static_cast<std::uint32_t>(b[at + 11 + size]) << 24);
      EXPECT_EQ(table.size(), 4u + table_size);
      EXPECT_EQ(table.substr(8, 4), "FTAB");
      const std::vector<std::uint64_t> table_copy = aligned(table);
      const dv::FileDataTable* t = dv::GetSizePrefixedFileDataTable(table_copy.data());
      ASSERT_EQ(t->Table()->size(), 1u);
      const dv::FileDataDefinition* d = t->Table()->Get(0);
      EXPECT_EQ(d->ByteOffset(), static_cast<std::int64_t>(at + 8));  // the packet's data
      EXPECT_EQ(d->PacketInfo()->StreamID(), 0);
      EXPECT_EQ(d->PacketInfo()->Size(), static_cast<std::int32_t>(size));
      EXPECT_EQ(d->NumElements(), 5);
      EXPECT_EQ(d->TimestampStart(), 0);
      EXPECT_EQ(d->TimestampEnd(), 1000000);
    }
    if (c == Aedat4Compression::Lz4) {
      EXPECT_EQ(data.substr(at + 8, 4), std::string("\x04\x22\x4d\x18", 4));  // an LZ4 frame
    } else if (c == Aedat4Compression::Zstd) {
      EXPECT_EQ(data.substr(at + 8, 4), std::string("\x28\xb5\x2f\xfd", 4));  // a zstd frame
    } else {
      EXPECT_EQ(data.substr(at + 8 + 8, 4), "EVTS");
      const std::vector<std::uint64_t> packet_copy = aligned(data.substr(at + 8, size));
      const dv::EventPacket* p = dv::GetSizePrefixedEventPacket(packet_copy.data());
      ASSERT_EQ(p->elements()->size(), 5u);
      const dv::Event* e = p->elements()->Get(2);
      EXPECT_EQ(e->timestamp(), 2500);
      EXPECT_EQ(e->x(), 5);
      EXPECT_EQ(e->y(), 40);
      EXPECT_FALSE(e->polarity());
      EXPECT_EQ(sizeof(dv::Event), 16u);
    }
  }
}

// The packets of many compressed at once on two threads (the writer's, and the caller's while the
// writer's is behind and when the file is finished) are the plain file's packets, in its order:
// each LZ4 frame decompresses to the body the uncompressed file holds at the same place.
TEST_F(EventFormats, Aedat4PacketsCompressedOnEitherThreadAreThePlainPacketsInOrder) {
  const AddressMap map{ArrayParams{}};
  std::vector<AddressEvent> events;
  constexpr std::size_t kEvents = 300'000;  // 73 full packets of 4096 and one of 992
  for (std::size_t i = 0; i < kEvents; ++i) {
    AddressEvent e = map.event_at({static_cast<std::uint32_t>(i * 7 % 64), static_cast<std::uint32_t>(i * 13 / 64 % 64)});
    e.t = static_cast<double>(i) * 3e-6;
    events.push_back(e);
  }
  // Each packet's body after the header, by the packets' own sizes up to the data table.
  const auto bodies = [](const std::string& data) {
    const auto* b = reinterpret_cast<const std::uint8_t*>(data.data());
    const auto le32 = [&](std::size_t at) {
      return std::uint32_t(b[at]) | (std::uint32_t(b[at + 1]) << 8) | (std::uint32_t(b[at + 2]) << 16) |
             (std::uint32_t(b[at + 3]) << 24);
    };
    const std::uint32_t header_size = le32(14);
    const std::vector<std::uint64_t> header_copy = aligned(data.substr(14, 4 + header_size));
    const auto end = static_cast<std::size_t>(dv::GetSizePrefixedIOHeader(header_copy.data())->dataTablePosition());
    std::vector<std::string> out;
    for (std::size_t at = 14 + 4 + header_size; at < end;) {
      EXPECT_EQ(le32(at), 0u);  // the events' stream
      const std::uint32_t size = le32(at + 4);
      out.push_back(data.substr(at + 8, size));
      at += 8 + size;
    }
    return out;
  };
  const std::vector<std::string> plain = bodies(slurp(write("plain.aedat4", events, Aedat4Compression::None)));
  const std::vector<std::string> packed = bodies(slurp(write("lz4.aedat4", events, Aedat4Compression::Lz4)));
  ASSERT_EQ(plain.size(), (kEvents + 4095) / 4096);
  ASSERT_EQ(packed.size(), plain.size());
  LZ4F_dctx* context = nullptr;
  ASSERT_FALSE(LZ4F_isError(LZ4F_createDecompressionContext(&context, LZ4F_VERSION)));
  for (std::size_t i = 0; i < plain.size(); ++i) {
    std::string body(plain[i].size() + 1, '\0');
    std::size_t out_size = body.size(), in_size = packed[i].size();
    const std::size_t rest = LZ4F_decompress(context, body.data(), &out_size, packed[i].data(), &in_size, nullptr);
    EXPECT_EQ(rest, 0u) << "packet " << i << ": one whole frame";
    body.resize(out_size);
    EXPECT_EQ(body, plain[i]) << "packet " << i;
    LZ4F_resetDecompressionContext(context);
  }
  LZ4F_freeDecompressionContext(context);
}

TEST_F(EventFormats, AnotherRecordersAedat4KeepsItsPolarityAsEvents) {
  // A file as DV writes it for a 346x260 camera: no aesim parameters, an OFF event is a real OFF
  // event (not a ghost), and a second stream of another type is skipped.
  flatbuffers::FlatBufferBuilder fbb;
  const std::string xml =
      "<dv version=\"2.0\"><node name=\"outInfo\" path=\"/outInfo/\">"
      "<node name=\"0\" path=\"/outInfo/0/\"><attr key=\"typeIdentifier\" type=\"string\">FRME</attr></node>"
      "<node name=\"1\" path=\"/outInfo/1/\"><attr key=\"typeIdentifier\" type=\"string\">EVTS</attr>"
      "<node name=\"info\" path=\"/outInfo/1/info/\"><attr key=\"sizeX\" type=\"int\">346</attr>"
      "<attr key=\"sizeY\" type=\"int\">260</attr></node></node></node></dv>";
  dv::FinishSizePrefixedIOHeaderBuffer(fbb, dv::CreateIOHeader(fbb, dv::CompressionType_NONE, -1, fbb.CreateString(xml)));
  std::string file = "#!AER-DAT4.0\r\n" + std::string(reinterpret_cast<const char*>(fbb.GetBufferPointer()), fbb.GetSize());
  const auto packet = [&](std::int32_t stream, const std::string& body) {
    for (std::uint32_t v : {static_cast<std::uint32_t>(stream), static_cast<std::uint32_t>(body.size())}) {
      for (int i = 0; i < 4; ++i) file += static_cast<char>(v >> (8 * i));
    }
    file += body;
  };
  packet(0, std::string(40, '\x7f'));  // a frame packet aesim does not decode
  flatbuffers::FlatBufferBuilder events;
  const std::vector<dv::Event> e = {dv::Event(10, 345, 259, false), dv::Event(20, 0, 0, true)};
  dv::FinishSizePrefixedEventPacketBuffer(events, dv::CreateEventPacket(events, events.CreateVectorOfStructs(e)));
  packet(1, std::string(reinterpret_cast<const char*>(events.GetBufferPointer()), events.GetSize()));
  const EventRecording rec = decode_events(file, "dv.aedat4", EventFileFormat::Aedat4);
  ASSERT_EQ(rec.events.size(), 2u);
  EXPECT_EQ(rec.width, 346);
  EXPECT_EQ(rec.height, 260);
  EXPECT_TRUE(rec.size_recorded);
  EXPECT_EQ(rec.events[0].x, 345u);
  EXPECT_EQ(rec.events[0].flags, kOffEvent);
  EXPECT_EQ(rec.events[1].flags, kNormalEvent);
  ASSERT_EQ(rec.skipped.size(), 1u);
  EXPECT_NE(rec.skipped[0].find("1 packet"), std::string::npos) << rec.skipped[0];
  EXPECT_NE(rec.skipped[0].find("FRME"), std::string::npos) << rec.skipped[0];
  EXPECT_DOUBLE_EQ(rec.events[1].t, 20e-6);
}

TEST_F(EventFormats, MalformedFilesAreOneLineErrorsNamingTheFile) {
  const AddressMap map{ArrayParams{}};
  const std::string aedat4 = slurp(write("e.aedat4", sample(map)));
  const std::string npy = slurp(write("e.npy", sample(map)));
  const auto refused = [](const std::string& data, EventFileFormat f, const std::string& words) {
    try {
      decode_events(data, "bad", f);
      ADD_FAILURE() << "accepted: " << words;
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("'bad'"), std::string::npos) << what;
      EXPECT_NE(what.find(words), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  };
  // The packets end where the data table starts (IOHeader.dataTablePosition).
  const auto* b = reinterpret_cast<const std::uint8_t*>(aedat4.data());
  const std::uint32_t header_size = b[14] | (b[15] << 8) | (b[16] << 16) | (b[17] << 24);
  const std::vector<std::uint64_t> header_copy = aligned(aedat4.substr(14, 4 + header_size));
  const auto packets_end = static_cast<std::size_t>(dv::GetSizePrefixedIOHeader(header_copy.data())->dataTablePosition());
  ASSERT_LT(packets_end, aedat4.size());
  refused(aedat4.substr(0, packets_end - 3), EventFileFormat::Aedat4, "truncated");
  refused(aedat4.substr(0, 20), EventFileFormat::Aedat4, "truncated in the IOHeader");
  refused(std::string("#!AER-DAT4.0\r\n\x08\x00\x00\x00garbage!", 26), EventFileFormat::Aedat4, "not a valid FlatBuffer");
  std::string corrupt = aedat4;
  for (std::size_t i = packets_end - 20; i < packets_end; ++i) corrupt[i] = '\xff';
  refused(corrupt, EventFileFormat::Aedat4, "packet 0");
  // A packet of a stream the header does not declare: its bytes cannot be told from damage.
  std::string stray = aedat4;
  stray[header_size + 18] = '\x07';
  refused(stray, EventFileFormat::Aedat4, "stream 7, which the header does not declare");
  // A damaged data table costs nothing: it is an index of packets aesim reads in order (DV too
  // rebuilds a missing one).
  EXPECT_EQ(decode_events(aedat4.substr(0, aedat4.size() - 3), "cut table", EventFileFormat::Aedat4).events.size(), 5u);
  refused("#!AER-DAT2.0\r\n", EventFileFormat::Aedat4, "not AEDAT 4.0");
  refused(npy.substr(0, npy.size() - 1), EventFileFormat::Npy, "truncated");
  std::string other_dtype = npy;
  other_dtype.replace(other_dtype.find("('t', '<i8')"), 12, "('q', '<i8')");
  refused(other_dtype, EventFileFormat::Npy, "no field 't'");
  std::string complex_time = npy;
  complex_time.replace(complex_time.find("('t', '<i8')"), 12, "('t', '<c8')");
  refused(complex_time, EventFileFormat::Npy, "aesim reads integers, bools and 32- or 64-bit floats");
  refused("not numpy at all", EventFileFormat::Npy, "not a NumPy .npy file");
  std::ofstream(dir_ / "fake.h5") << "not hdf5";
  try {
    load_events((dir_ / "fake.h5").string());
    ADD_FAILURE() << "accepted a fake .h5";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not an HDF5 file"), std::string::npos) << e.what();
  }
  // A recording in a repository cloned without Git LFS is a pointer file (the spec's three lines).
  std::ofstream(dir_ / "pointer.aedat4") << "version https://git-lfs.github.com/spec/v1\n"
                                            "oid sha256:f23eb34e1eacadf059cf0b46441c1bd4d05cf1b0bc4b3c8a0e4a3d1bcb5d2c97\n"
                                            "size 1191471\n";
  try {
    load_events((dir_ / "pointer.aedat4").string());
    ADD_FAILURE() << "accepted a Git LFS pointer";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("Git LFS pointer"), std::string::npos) << e.what();
  }
}

TEST_F(EventFormats, EveryCommandThatReadsEventsReadsEveryFormatItWrites) {
  const std::string scene = std::string(AESIM_SOURCE_DIR) + "/scenes/letters/A.pgm";
  std::map<std::string, std::string> recon;
  for (const std::string out : {"e.aedat", "e.aedat4", "e.npy", "e.h5", "e.raw"}) {
    const testing::Outcome run = aesim("run --scene " + scene + " --duration 300ms --out " + out);
    ASSERT_EQ(run.status, 0) << run.err;
    const std::string size = out == "e.npy" ? " --size 64x64" : "";
    const testing::Outcome r = aesim("recon " + out + " -o " + out + ".pgm" + size);
    ASSERT_EQ(r.status, 0) << out << ": " << r.err;
    recon[out] = testing::slurp(dir_ / (out + ".pgm"));
    const testing::Outcome info = aesim("info " + out);
    ASSERT_EQ(info.status, 0) << out << ": " << info.err;
    EXPECT_NE(info.out.find(out + ": "), std::string::npos) << info.out;
    // The aesim layouts carry the tiles (the letter's 64x64 in four 32x32); a .npy or .raw has none: one.
    EXPECT_NE(info.out.find(no_tiles_in(out) ? ", 1 tile\n" : ", 4 tiles\n"), std::string::npos) << info.out;
    const testing::Outcome c = aesim("classify " + out + " --json" + size);
    ASSERT_EQ(c.status, 0) << out << ": " << c.err;
    EXPECT_NE(c.out.find("\"winner\": \"A\""), std::string::npos) << out << ": " << c.out;
  }
  for (const auto& [name, image] : recon) EXPECT_EQ(image, recon["e.aedat"]) << name;
}

TEST_F(EventFormats, BadOutputsAreRefusedBeforeTheRunAndLeaveNothing) {
  const struct {
    std::string args, words;
  } cases[] = {{"--out e.mp4", "unknown event file type (write .aedat, .aedat4, .npy, .h5, .raw or .dat)"},
               {"--out e.txt", "events text is read, not written"},
               {"--out e.bin", "N-MNIST binary is read, not written"},
               {"--out e.npy --aedat-layout dvs128", "AEDAT 2.0"},
               {"--out e.aedat4 --aedat4-compression zip", "--aedat4-compression"},
               {"--out e.csv", "--csv"},
               {"--out e.raw --set array.rows=4096 --set array.cols=32", "x and y of 11 bits"},
               {"--out e.h5 --set sim.duration=5000s", "4294 s"}};
  for (const auto& c : cases) {
    const testing::Outcome o = aesim("run --scene " + std::string(AESIM_SOURCE_DIR) + "/scenes/uniform.pgm " + c.args);
    EXPECT_EQ(o.status, 2) << c.args;
    EXPECT_NE(o.err.find(c.words), std::string::npos) << c.args << ": " << o.err;
    EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 0) << c.args;
  }
}

TEST_F(EventFormats, EmulatesHeaderDescribesItsEventsNotASimulation) {
  // 24 frames at 10 Hz: the header says so, and carries no simulation defaults (sim.duration 1 s,
  // scene.frame_rate 25 Hz) that the outside check found there.
  const testing::Outcome o = aesim("emulate " + std::string(AESIM_SOURCE_DIR) + "/scenes/moving_disc --out m.aedat");
  ASSERT_EQ(o.status, 0) << o.err;
  const std::string data = testing::slurp(dir_ / "m.aedat");
  const std::string header = data.substr(0, data.find("\r\n#!END") == std::string::npos ? 4000 : data.find("#!END"));
  EXPECT_NE(header.find("# aesim.sensor.emulate.frames: 24\r\n"), std::string::npos);
  EXPECT_NE(header.find("# aesim.sensor.emulate.frame_rate: 10Hz\r\n"), std::string::npos);
  EXPECT_NE(header.find("# aesim.sensor.emulate.duration: 2.4s\r\n"), std::string::npos);
  EXPECT_NE(header.find("# aesim.sensor.array.rows: 64\r\n"), std::string::npos);
  EXPECT_EQ(header.find("sim.duration"), std::string::npos);
  EXPECT_EQ(header.find("scene.frame_rate"), std::string::npos);
  EXPECT_EQ(header.find("pixel."), std::string::npos);
  // It still reads back, and as .h5 too.
  EXPECT_EQ(aesim("info m.aedat").status, 0);
  ASSERT_EQ(aesim("emulate " + std::string(AESIM_SOURCE_DIR) + "/scenes/moving_disc --out m.h5").status, 0);
  const testing::Outcome info = aesim("info m.h5");
  EXPECT_EQ(info.status, 0) << info.err;
}

}  // namespace
}  // namespace aesim
