#pragma once
#include <memory>
#include <string>
#include <vector>

namespace aesim {

class EventFileWriter;
class OutputFiles;
struct EventFileSpec;
struct EventRecording;

// The event file formats aesim writes and reads.
enum class EventFileFormat {
  Aedat2,
  Aedat4,
  Npy,
  Npz,
  Hdf5,
  PropheseeRaw,
  PropheseeDat,
  NmnistBin,
  EventsText,
  RosBag,
  Mcap,
  Rosbag2Sqlite,
  MatEvents,
  Csv
};

// One format, one row: what names it, what writes and reads it, what it cannot hold. Every command,
// the CLI's help texts and docs/reference.md's format table follow from the rows; adding a format
// is a row here (event_formats.cpp) plus its writer and reader files (docs/architecture.md).
struct EventFormatRow {
  EventFileFormat format;
  const char* name;                     // "AEDAT 2.0"
  std::vector<std::string> extensions;  // ".aedat", ...; the first names the format in help texts
  const char* help;                     // what the format is, for --out's help: "jAER's"
  // The longest run its stamps can hold, s (0: no limit), and why; --out refuses a longer run
  // before it starts.
  double longest_run = 0;
  const char* stamps = "";
  // A writer for `path` in this format through `files` (null: not an --out format; CSV has --csv).
  std::unique_ptr<EventFileWriter> (*open)(OutputFiles& files, const std::string& path, const EventFileSpec& spec) =
      nullptr;
  // The events of a file, from its path; `layout` is a jAER chip for an AEDAT 2.0 file without
  // one (empty otherwise). Throws InputError naming the file.
  EventRecording (*read)(const std::string& path, const std::string& layout) = nullptr;
  // The same from a file's bytes (null where the library reads only from a path: HDF5).
  EventRecording (*decode)(const std::string& data, const std::string& label, const std::string& layout) = nullptr;
};

// Every row, in the order help texts list them.
const std::vector<EventFormatRow>& event_formats();
const EventFormatRow& event_format(EventFileFormat format);
// The row of `path`'s extension (no extension: AEDAT 2.0, as --out always wrote); throws InputError
// naming `option` and listing the extensions.
const EventFormatRow& event_format_of(const std::string& path, const std::string& option);
// The row of `path` when --out can write it; InputError otherwise (CSV: use --csv; a format aesim
// only reads: which ones it writes).
const EventFormatRow& writable_event_format(const std::string& path, const std::string& option);
// The extensions as a help text lists them: ".aedat, .aedat4, .npy, .h5 or .csv" (`writable`: only
// --out's).
std::string event_extensions(bool writable = false);
// What a command that reads events takes: every format's first extension, or a ROS 2 bag's or an EVIMO2
// sequence's folder.
std::string event_inputs();
// The formats as --out's help lists them: ".aedat (AEDAT 2.0, jAER's), .aedat4 (...), ...".
std::string event_formats_help();

}  // namespace aesim
