#pragma once
#include <string>

#include "aesim/event_files/aedat4.hpp"

namespace aesim {

// The events of a text file of one event a line, `t x y p`: the Event Camera Dataset's
// events.txt (RPG's davis_data page), ESIM's, v2e's and jAER's text output, rpg_e2vid's input. t
// in seconds (a decimal or exponent number, rounded to the nearest microsecond), or in whole
// microseconds where a '#' line says `timestamp(int32 us)` (jAER's header for that option); x and
// y whole pixels; p 1 (ON) or 0 or -1 (OFF); fields apart by blanks or commas (jAER's CSV
// option); a fifth field (v2e's signal/noise label) is allowed and left. Lines beginning with '#'
// (v2e's and jAER's headers), empty lines and a leading UTF-8 byte order mark are skipped. A first
// line of two whole numbers is rpg_e2vid's `width height`, taken as the array's size; without one
// the file records no size. Events stamped before the line above's (v2e warns that it writes
// some) are put in time order, a stable sort, and counted (`reordered`). Throws InputError naming
// `label` and the line for anything else.
PolarityRecording decode_events_text(const std::string& data, const std::string& label);

}  // namespace aesim
