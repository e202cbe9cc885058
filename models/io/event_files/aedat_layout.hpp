#pragma once
#include <cstdint>
#include <optional>
#include <string>

#include "aesim/array/address_map.hpp"
#include "aesim/events/address_event.hpp"

namespace aesim {

// How an AEDAT 2.0 address word encodes an event (docs/reference.md section 5, --aedat-layout):
//  - aesim: (tile << bus_bits) | bus_address, y = 0 at the top, no polarity; aesim's own readers.
//  - dvs128, davis: jAER's DVS128 and DAVIS words, so that jAER's viewers decode the pixels. jAER
//    puts y = 0 at the bottom (an array of R rows is written with y_jAER = R - 1 - y, at the
//    bottom-left of the chip's frame) and mirrors x in the raw word (raw x = chip width - 1 -
//    x_jAER, undone by its extractors). The polarity carries the event's fate: ON (1) for a
//    normal event, OFF (0) for a ghost.
//      DVS128 (128x128): bits 14-8 y, 7-1 raw x, bit 0 the raw type, which jAER flips (raw 0 is ON).
//      DAVIS (DAVIS240C 240x180, or Davis346red 346x260 for larger arrays): bit 31 0 (a DVS event),
//      bits 30-22 y, 21-12 raw x, bit 11 polarity (1 is ON), bit 10 0 (1 would mark a special
//      event).
enum class AedatLayout { Aesim, Dvs128, Davis };

AedatLayout parse_aedat_layout(const std::string& name);  // InputError naming the option
const char* to_string(AedatLayout layout);

// The jAER chip a layout writes as: its class (the "# AEChip:" header line) and its size.
struct JaerChip {
  const char* java_class = "";
  int width = 0, height = 0;
};
// Refuses (InputError) an array larger than the chip the layout can name.
JaerChip jaer_chip(AedatLayout layout, const AddressMap& map);

// The word of an output event (x, y global, flags) in a jAER layout.
std::uint32_t jaer_address(AedatLayout layout, const JaerChip& chip, int rows, const AddressEvent& e);

// The chip of a jAER recording: named by its "# AEChip:" header line (a Java class, e.g.
// eu.seebetter.ini.chips.davis.DAVIS240C) or by the user (dvs128, davis240c, davis346); nullopt
// for a chip aesim cannot decode.
struct JaerRecordingChip {
  AedatLayout layout;
  JaerChip chip;
};
std::optional<JaerRecordingChip> jaer_recording_chip(const std::string& name);

// And back, as jAER's extractor would read it, then turned to aesim's coordinates: the pixel and
// whether the event was a ghost; nullopt for a word that is not a DVS event of the array.
struct JaerPixel {
  PixelAddress pixel;
  bool ghost = false;
};
std::optional<JaerPixel> decode_jaer_address(AedatLayout layout, const JaerChip& chip, int rows, int cols,
                                             std::uint32_t word);

}  // namespace aesim
