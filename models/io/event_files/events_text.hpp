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

// Event CSVs other tools write (aesim's own, `t_us,x,y,tile,flags`, is events_csv's):
//  - a header line naming the columns, in any order, comma-, semicolon- or tab-separated: x, y,
//    the time as t, ts, time, timestamp or event_timestamp, the polarity as p, pol, polarity or on
//    (absent: every event ON); other columns are left. A unit in the time's name (`t_us`,
//    `timestamp_ns`, `time_s`, `t [ms]`) is the unit;
//  - Metavision's (metavision_file_to_csv, its RAW-to-CSV sample): `%` lines first (its
//    `%geometry:W,H` is the array's size), then `x,y,p,t` rows without a header, t in
//    microseconds.
// A time column whose name gives no unit is microseconds when every value is a whole number
// (cameras' stamps) and seconds when any has a fraction (UnnamedStampUnit: what Python writes of
// seconds); the choice is said in `read_as`. Polarity 1, true or ON is ON; 0, -1, false or OFF is
// OFF. `#` lines and a UTF-8 byte order mark are skipped; events out of time order are put in it
// and counted. Throws InputError naming `label` and the line on anything else.
PolarityRecording decode_foreign_csv(const std::string& data, const std::string& label);

}  // namespace aesim
