#pragma once
#include <cstdint>
#include <ostream>
#include <string>

#include "aesim/event_files/aedat4.hpp"
#include "aesim/event_files/buffered_stream_writer.hpp"

namespace aesim {

// The CD events of a Prophesee RAW file (.raw, what Metavision records from Prophesee cameras and
// their integrators' boards): ASCII header lines beginning with '%' (to "% end" where the recorder
// wrote one), then the camera's own event stream, little-endian words of the encoding the header
// names ("% format EVT3;height=720;width=1280", or "% evt 3.0" in files before Metavision 4):
//  - EVT 3.0, 16-bit words, Prophesee's docs and OpenEB's decoder: a 24-bit microsecond time
//    (EVT_TIME_HIGH, EVT_TIME_LOW; a fall of the high part by half its range or more is a wrap,
//    2^24 us more), a row (EVT_ADDR_Y), then single events (EVT_ADDR_X) or vectors of 12 and 8
//    pixels from a base column (VECT_BASE_X, VECT_12, VECT_8);
//  - EVT 2.0, 32-bit words: CD_OFF/CD_ON carrying x, y and the stamp's low 6 bits after
//    EVT_TIME_HIGH's upper 28 (wraps past 2^34 us unwrapped);
//  - EVT 2.1, 64-bit words: EVT_NEG/EVT_POS with a row, a base column aligned to 32 and a mask
//    of 32 pixels, after EVT_TIME_HIGH; in the IMX636's layout when the format says
//    "endianness=legacy" (the two 32-bit halves swapped).
// Stamps are the camera's own microseconds, as the file holds them (Metavision's RAW-to-CSV
// samples read them so; its Camera shifts them by default to start near 0). Events before the
// first time-high word have no time and are left out, as Metavision does; so are external
// triggers, ERC counts, IMU samples and other words, counted in `notes`; events past the header's
// height or width, and a last word cut short, likewise. The size is the header's (format or
// geometry line) when given. Throws InputError naming `label` for a header that does not end, does
// not name its encoding, or names another (HISTO3D, DIFF3D, EVT 4.0, ...).
PolarityRecording decode_prophesee_raw(const std::string& data, const std::string& label);

// Writes a run's events as a Prophesee RAW file, after a header naming its encoding ("% evt 2.0"
// or "% evt 3.0", "% format EVT2;height=H;width=W" or EVT3, "% geometry WxH", "% integrator_name
// aesim", "% end"; no date, so the same run writes the same bytes); CD ON for an event and CD OFF
// for a ghost (as .npy's p). x and y are 11 bits in both: arrays of more than 2048 rows or columns
// are refused (InputError) before anything is written.
//  - EVT 2.0 (32-bit words): an EVT_TIME_HIGH word (the microsecond stamp >> 6) whenever it
//    differs from the last one written, and a CD word an event with the stamp's low 6 bits, x, y.
//  - EVT 3.0 (16-bit words), single events (no vectors): EVT_TIME_HIGH (stamp bits 23-12) where
//    those bits change, EVT_TIME_LOW (bits 11-0) where they or the high part change, EVT_ADDR_Y
//    where the row changes, then EVT_ADDR_X (polarity, x) an event. The 24-bit time wraps every
//    16.8 s: readers count a wrap where the high part falls, so from 0 us to the first event and
//    across a gap between events a time-high word is written at least every 2047 of its steps
//    (8.4 s), each wrap then seen.
class PropheseeRawWriter : public BufferedStreamWriter {
 public:
  PropheseeRawWriter(std::ostream& out, const ArrayParams& array, double tick, RawEncoding encoding = RawEncoding::Evt2);
  void events(const AddressEvent* first, std::size_t count) override;

 private:
  void evt2(const AddressEvent* first, std::size_t count);
  void evt3(const AddressEvent* first, std::size_t count);
  RawEncoding encoding_;
  std::uint64_t time_high_ = ~std::uint64_t(0);  // the last EVT_TIME_HIGH's value, none yet
  // EVT 3.0: the last EVT_TIME_LOW and EVT_ADDR_Y written (none yet).
  std::uint64_t time_low_ = ~std::uint64_t(0);
  std::uint32_t row_ = ~std::uint32_t(0);
};

}  // namespace aesim
