#pragma once
#include <optional>
#include <string>
#include <vector>

#include "aesim/event_files/event_formats.hpp"
#include "aesim/events/address_event.hpp"

namespace aesim {

// An array's size as a user gives it: WIDTHxHEIGHT.
struct ArraySize {
  int width = 0, height = 0;
};
// Parses "64x64" (1 to 4096 each); throws InputError naming `option`.
ArraySize parse_array_size(const std::string& text, const std::string& option);

// Events read back from an event file (AEDAT 2.0 or 4.0, .npy, .h5 or CSV, by extension), with the
// array size they belong to: the sensor parameters aesim wrote into the file, the file's own size
// (AEDAT 4.0's sizeX/sizeY), or the size given (--size). A CSV or a .npy records no size; without
// one given, the size is the span of its events and `size_recorded` is false.
struct EventRecording {
  std::vector<AddressEvent> events;  // t in seconds
  int width = 0, height = 0, tiles = 0;
  bool size_recorded = false;
  std::vector<std::string> skipped;  // other streams' packets, in words ("12 packets of IMUS (3400 bytes)")
  // Another recorder's events whose stamps went back (jAER interleaves IMU and frame samples
  // stamped otherwise): read in time order (a stable sort), and counted here.
  std::uint64_t reordered = 0;
  std::uint64_t stamp_wraps = 0;     // jAER stamps that wrapped past 2^32 us, unwrapped
  // How the reader took numbers the format leaves open, in words ("TD counts from 1, as MATLAB
  // does: x and y one less, polarity 2 ON").
  std::vector<std::string> read_as;
};

// `size`, when given, is the array's: a CSV takes it (its events must lie within), an AEDAT
// file's header must agree with it. `layout` names the chip of a jAER AEDAT 2.0 recording whose
// header has no "# AEChip:" line (dvs128, davis240c, davis346). Throws InputError naming the file.
EventRecording load_events(const std::string& path, const std::optional<ArraySize>& size = std::nullopt,
                           const std::string& layout = "");

// The same from a file's bytes; `label` names it in messages.
EventRecording decode_events(const std::string& data, const std::string& label, EventFileFormat format);

// The readers behind event_formats()'s rows that are not a polarity format's (from_polarity): an
// AEDAT file (2.0 or 3.1, by its first line), CSV from its bytes or its path; a file's bytes,
// bounded.
EventRecording decode_aedat_recording(const std::string& data, const std::string& label, const std::string& layout);
EventRecording decode_csv_recording(const std::string& data, const std::string& label);
EventRecording read_csv_recording(const std::string& path);
std::string read_event_file_bytes(const std::string& path);

// A polarity format's events (another tool's recording, or aesim's .npy/.h5/.aedat4/.raw) as a
// recording: a file aesim wrote keeps its array and tiles and reads polarity 0 as a ghost; another
// tool's keeps ON and OFF, its size the file's or the events' span. Throws InputError naming
// `path` for negative or decreasing stamps, or events outside a recorded array.
struct PolarityRecording;  // aedat4.hpp: what every polarity format's reader gives
EventRecording from_polarity(const PolarityRecording& in, const std::string& path);

}  // namespace aesim
