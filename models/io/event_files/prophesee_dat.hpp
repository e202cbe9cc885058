#pragma once
#include <string>

#include "aesim/event_files/aedat4.hpp"

namespace aesim {

// Whether `data` starts as a Prophesee DAT file does (a header line beginning with '%'); jAER's
// AEDAT files, which share the .dat extension, begin with '#'.
bool is_prophesee_dat(const std::string& data);

// The CD events of a Prophesee DAT file (ATIS and Prophesee cameras; N-CARS, Gen1 and Prophesee's
// own tools write it): ASCII header lines beginning with '%' ("% Width 304", "% Height 240" when
// the recorder gave the size), then one byte of event type (0: CD) and one of event size (8), then
// little-endian events of two 32-bit words: the stamp in microseconds (a stamp below the last one
// means the counter wrapped, and 2^32 us is added, as Prophesee's readers and expelliarmus do) and
// x in bits 0-13, y in bits 14-27, polarity in bits 28-31 (1 ON, 0 OFF). Throws InputError naming
// `label` for another event type or size, a file that ends inside an event, or a malformed header.
PolarityRecording decode_prophesee_dat(const std::string& data, const std::string& label);

}  // namespace aesim
