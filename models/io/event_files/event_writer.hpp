#pragma once
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "aesim/array/address_map.hpp"
#include "aesim/event_files/aedat_layout.hpp"
#include "aesim/event_files/event_formats.hpp"
#include "aesim/events/event_stream.hpp"

namespace aesim {

class OutputFiles;

// An event file being written as a run streams its events (in time order).
class EventFileWriter : public EventStream {
 public:
  // Writes what is buffered and completes the file (counts, indices); the file is whole after it.
  virtual void finish() = 0;
  // A warning for readers of the file that would misread it, empty when none would.
  virtual std::string reader_warning() const { return ""; }
  // Events left out because they name no pixel of the array (see OnArrayEvents).
  virtual std::uint64_t off_array() const { return 0; }
};

enum class Aedat4Compression { None, Lz4, Zstd };
Aedat4Compression parse_aedat4_compression(const std::string& text);  // "none" | "lz4" | "zstd"
// The encoding a Prophesee RAW file is written in (prophesee_raw.hpp).
enum class RawEncoding { Evt2, Evt3 };
RawEncoding parse_raw_encoding(const std::string& text);  // "evt2" | "evt3"

// What every format records beside the events: the array (and its tiles), the sensor parameters
// (sensor_metadata, "section.key" -> text), notes for a text header, the receiver's tick.
struct EventFileSpec {
  ArrayParams array;
  std::map<std::string, std::string> sensor;
  std::vector<std::string> notes;
  double tick = 1e-6;
  double duration = 0;  // s, the run's (the HDF5 index covers every millisecond of it)
  AedatLayout layout = AedatLayout::Aesim;              // AEDAT 2.0 only
  Aedat4Compression compression = Aedat4Compression::Lz4;  // AEDAT 4.0 only
  RawEncoding raw_encoding = RawEncoding::Evt2;            // Prophesee RAW only
};

// A writer for `path` (not .csv) in the format its extension names (event_formats), writing to a
// temporary of `files` that is renamed into place with the rest.
std::unique_ptr<EventFileWriter> open_event_writer(OutputFiles& files, const std::string& path,
                                                   const EventFileSpec& spec);

}  // namespace aesim
