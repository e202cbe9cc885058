#pragma once
#include <ostream>
#include <string>

#include "aesim/event_files/aedat4.hpp"
#include "aesim/event_files/buffered_stream_writer.hpp"

namespace aesim {

// Whether `data` starts as a Prophesee DAT file does (a header line beginning with '%'); jAER's
// AEDAT files, which share the .dat extension, begin with '#'.
bool is_prophesee_dat(const std::string& data);

// The CD events of a Prophesee DAT file (ATIS and Prophesee cameras; N-CARS, Gen1 and Prophesee's
// own tools write it): ASCII header lines beginning with '%' ("% Width 304", "% Height 240" when
// the recorder gave the size), then one byte of event type (0: Event2d, as N-CARS and Gen1 hold;
// 12: EventCd, as Metavision writes CD events; the same 8-byte layout) and one of event size (8),
// then little-endian events of two 32-bit words: the stamp in microseconds (a stamp below the last
// one means the counter wrapped, and 2^32 us is added, as Prophesee's readers and expelliarmus do)
// and x in bits 0-13, y in bits 14-27, polarity in bits 28-31 (1 ON, 0 OFF). Throws InputError
// naming `label` for another event type or size (external triggers, type 14, included), a file
// that ends inside an event, or a malformed header.
PolarityRecording decode_prophesee_dat(const std::string& data, const std::string& label);

// Writes a run's events as a Prophesee DAT file of CD events, as Prophesee's DAT format page lays
// it out: the header "% Data file containing CD events", "% Version 2", "% Width W", "% Height H"
// (no date, so the same run writes the same bytes), the event type 12 (EventCd) and size 8, then
// an event of two little-endian 32-bit words each: the stamp in microseconds, and x | y << 14 |
// p << 28 with p 1 for an event and 0 for a ghost (as .npy's p). x and y are 14 bits: arrays of
// more than 16384 rows or columns are refused (InputError) before anything is written.
class PropheseeDatWriter : public BufferedStreamWriter {
 public:
  PropheseeDatWriter(std::ostream& out, const ArrayParams& array, double tick);
  void events(const AddressEvent* first, std::size_t count) override;
};

}  // namespace aesim
