// AEDAT 2.0 and the address layout (docs/reference.md sections 2 and 5).
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "aesim/array/address_map.hpp"
#include "aesim/errors/input_error.hpp"
#include "aesim/event_files/aedat.hpp"
#include "aesim/event_files/event_file.hpp"
#include "aesim/scene/photocurrents.hpp"
#include "support/scenes.hpp"
#include "aesim/run/imager_simulation.hpp"

namespace aesim {
namespace {
namespace fs = std::filesystem;

TEST(AddressMap, AlohaLayoutIsTenBitsPerQuadrant) {
  ArrayParams a;  // 64x64 in 32x32 tiles
  const AddressMap map(a);
  EXPECT_EQ(map.bus_bits(), 10);
  EXPECT_EQ(map.tiles(), 4);
  // Pixel (x=37, y=2): tile 1 (top-right), local (5, 2): bus address (2 << 5) | 5 = 69.
  const PixelAddress p{37, 2};
  EXPECT_EQ(map.tile_of(p), 1u);
  EXPECT_EQ(map.bus_address(p), 69u);
  EXPECT_EQ(map.word(p), (1u << 10) | 69u);
  // Bottom-left quadrant is tile 2.
  EXPECT_EQ(map.tile_of({0, 40}), 2u);
}

TEST(AddressMap, DecodeInvertsEveryPixelIncludingPartialEdgeTiles) {
  ArrayParams a;
  a.rows = 144;
  a.cols = 176;  // QCIF: 5.5 x 4.5 tiles of 32x32
  const AddressMap map(a);
  EXPECT_EQ(map.tiles(), 6 * 5);
  for (std::uint32_t y = 0; y < 144; ++y) {
    for (std::uint32_t x = 0; x < 176; ++x) {
      const auto back = map.decode(map.word({x, y}));
      ASSERT_TRUE(back.has_value());
      ASSERT_EQ(back->x, x);
      ASSERT_EQ(back->y, y);
    }
  }
  // Column 176 would be local x 16 of the last tile column, which does not exist.
  EXPECT_FALSE(map.decode((5u << 10) | 16u).has_value());
}

class AedatFileTest : public ::testing::Test {
 protected:
  void TearDown() override { fs::remove(path_); }
  std::string path_ = (fs::temp_directory_path() / ("aesim_aedat_" + std::to_string(::getpid()) + ".aedat")).string();
};

TEST_F(AedatFileTest, WrittenAndReadBackByteExact) {
  SensorConfig c = testing::exact_sensor(64, 64, 32);
  c.pixel.mismatch = 0.02;
  c.pixel.initial = InitialState::Random;
  c.sim.duration = 0.5;
  const Photocurrents photocurrents(
      testing::make_scene({testing::make_image(64, 64, [](int x, int y) { return (x ^ y) / 63.0; })}), c.pixel);
  const SimulationResult r = simulate(c.resolved(), photocurrents);
  const AddressMap map(c.array);
  const auto header = aedat_header(map, {{"array.rows", "64"}, {"array.cols", "64"}, {"array.tile_rows", "32"},
                                         {"array.tile_cols", "32"}, {"pixel.c_int", "1e-13"}});
  const auto records = aedat_records(r.log.events(), map, 1e-6);
  ASSERT_GT(records.size(), 1000u);
  std::ostringstream first;
  write_aedat(first, header, records);
  std::ofstream(path_, std::ios::binary) << first.str();

  const AedatFile back = read_aedat(path_);
  EXPECT_EQ(back.header, header);
  EXPECT_EQ(back.metadata.at("sensor.pixel.c_int"), "1e-13");
  EXPECT_EQ(back.metadata.at("layout.bus_bits"), "10");
  ASSERT_EQ(back.records.size(), records.size());
  std::ostringstream second;
  write_aedat(second, back.header, back.records);
  EXPECT_EQ(first.str(), second.str());

  // Every header line ends in CRLF, the first is the format line, records are big-endian.
  const std::string bytes = first.str();
  EXPECT_EQ(bytes.rfind("#!AER-DAT2.0\r\n", 0), 0u);
  std::size_t pos = 0, lines = 0;
  while (bytes[pos] == '#') {
    const std::size_t eol = bytes.find('\n', pos);
    ASSERT_EQ(bytes[eol - 1], '\r');
    pos = eol + 1;
    ++lines;
  }
  EXPECT_EQ(lines, header.size());
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data() + pos);
  EXPECT_EQ((std::uint32_t(p[0]) << 24 | std::uint32_t(p[1]) << 16 | std::uint32_t(p[2]) << 8 | p[3]),
            records[0].address);

  // Decoded through the header's own layout, events come back to their pixels and microseconds.
  const EventRecording rec = load_events(path_);
  ASSERT_EQ(rec.events.size(), r.log.events().size());
  EXPECT_EQ(rec.width, 64);
  for (std::size_t i = 0; i < rec.events.size(); ++i) {
    ASSERT_EQ(rec.events[i].x, r.log.events()[i].x);
    ASSERT_EQ(rec.events[i].y, r.log.events()[i].y);
    ASSERT_NEAR(rec.events[i].t, r.log.events()[i].t, 1e-6);
  }
}

TEST_F(AedatFileTest, TruncatedAndForeignFilesAreInputErrors) {
  std::ofstream(path_, std::ios::binary) << "#!AER-DAT2.0\r\n" << std::string(12, '\0');
  EXPECT_THROW(read_aedat(path_), InputError);
  std::ofstream(path_, std::ios::binary) << "#!AER-DAT3.1\r\n";
  EXPECT_THROW(read_aedat(path_), InputError);
  std::ofstream(path_, std::ios::binary) << "#!AER-DAT2.0\r\n" << std::string(8, '\0');
  EXPECT_THROW(load_events(path_), InputError);  // no aesim layout in the header
}

}  // namespace
}  // namespace aesim
