// AEDAT 2.0 in jAER's DVS128 and DAVIS address layouts: every event of a run with ghosts decodes,
// by jAER's own extraction rules (written here from its documented formats: masks, mirrored raw
// x, DVS128's flipped type, DAVIS's DVS and special-event bits), to its pixel with y = 0 at the
// bottom and polarity ON for a normal event and OFF for a ghost; the header names the chip; aesim
// reads the files back to the same events; arrays a chip cannot hold are refused.
#include <sstream>

#include <gtest/gtest.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/event_files/aedat.hpp"
#include "aesim/event_files/event_file.hpp"
#include "aesim/scene/photocurrents.hpp"
#include "support/scenes.hpp"
#include "support/temp_dir_test.hpp"

namespace aesim {
namespace {

// What jAER's extractors make of a word (x, y with y = 0 at the bottom, ON or OFF), for the
// chip's width; `pixel` false for words they do not turn into a DVS pixel event.
struct JaerEvent {
  bool pixel = false;
  int x = 0, y = 0;
  bool on = false;
};

JaerEvent jaer_dvs128(std::uint32_t a) {
  // Masks 0xfe (x, shift 1) and 0x7f00 (y, shift 8), type mask 1; x flipped (127 - raw), type
  // flipped (raw 0 becomes type 1, ON).
  JaerEvent e;
  e.pixel = true;
  e.x = 127 - static_cast<int>((a & 0xfe) >> 1);
  e.y = static_cast<int>((a & 0x7f00) >> 8);
  e.on = (1 - static_cast<int>(a & 1)) == 1;
  return e;
}

JaerEvent jaer_davis(std::uint32_t a, int width) {
  // Bit 31 clear: a DVS event; bit 10 set would make it special. y bits 30-22, x bits 21-12
  // mirrored (sizeX - 1 - raw), polarity bit 11 (set: ON).
  JaerEvent e;
  e.pixel = (a & 0x80000000u) == 0 && (a & (1u << 10)) == 0;
  e.x = (width - 1) - static_cast<int>((a & (1023u << 12)) >> 12);
  e.y = static_cast<int>((a & (511u << 22)) >> 22);
  e.on = (a & (1u << 11)) != 0;
  return e;
}

SimulationResult ghostly_run(int rows, int cols) {
  SensorConfig c = testing::exact_sensor(rows, cols, 32);
  c.bus.access = BusAccess::Aloha;
  c.bus.contention_detect = false;
  c.bus.t_event = 20e-6;
  c.pixel.initial = InitialState::Random;
  c.pixel.i_max = 4e-12;
  c.sim.duration = 0.5;
  const Photocurrents p(testing::make_scene({testing::make_image(cols, rows, [](int x, int y) {
                          return 0.1 + 0.9 * ((x / 8 + y / 8) % 2);
                        })}),
                        c.pixel);
  return simulate(c.resolved(), p);
}

std::string written(const SimulationResult& r, const AddressMap& map, AedatLayout layout) {
  std::ostringstream out;
  {
    AedatWriter writer(out, aedat_header(map, {{"array.rows", std::to_string(map.rows())},
                                              {"array.cols", std::to_string(map.cols())},
                                              {"array.tile_rows", "32"}, {"array.tile_cols", "32"}},
                                         layout),
                       map, 1e-6, layout);
    writer.events(r.log.events().data(), r.log.events().size());
  }
  return out.str();
}

void expect_jaer_decodes(int rows, int cols, AedatLayout layout, const char* chip, int chip_width) {
  SCOPED_TRACE(to_string(layout));
  ArrayParams a;
  a.rows = rows;
  a.cols = cols;
  const AddressMap map(a);
  const SimulationResult r = ghostly_run(rows, cols);
  ASSERT_GT(r.log.totals().ghost, 20u);
  const std::string bytes = written(r, map, layout);
  const AedatFile file = decode_aedat(bytes, "layout.aedat");
  bool named = false;
  for (const std::string& line : file.header) named |= line == std::string("# AEChip: ") + chip;
  EXPECT_TRUE(named) << "no '# AEChip: " << chip << "' line";
  ASSERT_EQ(file.records.size(), r.log.events().size());
  for (std::size_t i = 0; i < file.records.size(); ++i) {
    const AddressEvent& e = r.log.events()[i];
    const std::uint32_t word = file.records[i].address;
    const JaerEvent j = layout == AedatLayout::Dvs128 ? jaer_dvs128(word) : jaer_davis(word, chip_width);
    ASSERT_TRUE(j.pixel) << i;
    ASSERT_EQ(j.x, static_cast<int>(e.x)) << i;
    ASSERT_EQ(j.y, rows - 1 - static_cast<int>(e.y)) << i;
    ASSERT_EQ(j.on, (e.flags & kGhostEvent) == 0) << i;
  }
  // aesim's readers get the same events back, ghosts included.
  const EventRecording back = decode_events(bytes, "layout.aedat", EventFileFormat::Aedat2);
  ASSERT_EQ(back.events.size(), r.log.events().size());
  for (std::size_t i = 0; i < back.events.size(); ++i) {
    const AddressEvent& e = r.log.events()[i];
    ASSERT_EQ(back.events[i].x, e.x);
    ASSERT_EQ(back.events[i].y, e.y);
    ASSERT_EQ(back.events[i].tile, e.tile);
    ASSERT_EQ(back.events[i].flags, e.flags);
  }
}

TEST(AedatLayout, Dvs128WordsDecodeByJaersRules) {
  expect_jaer_decodes(64, 64, AedatLayout::Dvs128, "ch.unizh.ini.jaer.chip.retina.DVS128", 128);
}

TEST(AedatLayout, DavisWordsDecodeByJaersRules) {
  expect_jaer_decodes(64, 64, AedatLayout::Davis, "eu.seebetter.ini.chips.davis.DAVIS240C", 240);
  // An array wider than the DAVIS240 goes out as a DAVIS346.
  expect_jaer_decodes(96, 256, AedatLayout::Davis, "eu.seebetter.ini.chips.davis.Davis346red", 346);
}

TEST(AedatLayout, ArraysAChipCannotHoldAreRefused) {
  ArrayParams a;
  a.rows = 144;
  a.cols = 176;
  EXPECT_THROW(jaer_chip(AedatLayout::Dvs128, AddressMap(a)), InputError);
  EXPECT_NO_THROW(jaer_chip(AedatLayout::Davis, AddressMap(a)));
  a.rows = 288;
  a.cols = 352;
  EXPECT_THROW(jaer_chip(AedatLayout::Davis, AddressMap(a)), InputError);
  EXPECT_THROW(parse_aedat_layout("davis346"), InputError);
}

class AedatLayoutCli : public testing::TempDirTest {};

TEST_F(AedatLayoutCli, RunWritesAndInfoReadsEachLayout) {
  for (const char* layout : {"aesim", "dvs128", "davis"}) {
    const testing::Outcome o =
        aesim(std::string("run --duration 0.3 --aedat-layout ") + layout + " --out " + layout + ".aedat");
    ASSERT_EQ(o.status, 0) << o.err;
    const testing::Outcome info = aesim(std::string("info ") + layout + ".aedat");
    ASSERT_EQ(info.status, 0) << info.err;
    EXPECT_NE(info.out.find("array 64x64"), std::string::npos) << info.out;
  }
  const testing::Outcome big = aesim("run --duration 0.01 --set array.rows=144 --set array.cols=176 "
                                     "--aedat-layout dvs128 --out big.aedat");
  EXPECT_EQ(big.status, 2);
  EXPECT_NE(big.err.find("does not fit the DVS128"), std::string::npos) << big.err;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "big.aedat"));
  EXPECT_EQ(aesim("run --duration 0.01 --aedat-layout jaer --out x.aedat").status, 2);
}

}  // namespace
}  // namespace aesim
