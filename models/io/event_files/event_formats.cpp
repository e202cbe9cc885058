#include "aesim/event_files/event_formats.hpp"

#include <algorithm>
#include <filesystem>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/files/input_path.hpp"
#include "aesim/event_files/aedat.hpp"
#include "aesim/event_files/aedat4.hpp"
#include "aesim/event_files/dsec_h5.hpp"
#include "aesim/event_files/event_file.hpp"
#include "aesim/event_files/event_writer.hpp"
#include "aesim/event_files/events_text.hpp"
#include "aesim/event_files/mat_events.hpp"
#include "aesim/event_files/mcap_bag.hpp"
#include "aesim/event_files/nmnist_bin.hpp"
#include "aesim/event_files/npy_events.hpp"
#include "aesim/event_files/npz_events.hpp"
#include "aesim/event_files/prophesee_dat.hpp"
#include "aesim/event_files/prophesee_raw.hpp"
#include "aesim/event_files/ros_bag.hpp"
#include "aesim/event_files/rosbag2_sqlite.hpp"
#include "aesim/output/atomic_file.hpp"

namespace aesim {
namespace {

// A reader from a path for a format decoded from its bytes.
template <EventRecording (*decode)(const std::string&, const std::string&, const std::string&)>
EventRecording read_bytes(const std::string& path, const std::string& layout) {
  return decode(read_event_file_bytes(path), path, layout);
}

// A row's decoder for a format that has no layout to choose (only AEDAT 2.0 has jAER's).
template <EventRecording (*decode)(const std::string&, const std::string&)>
EventRecording without_layout(const std::string& data, const std::string& label, const std::string&) {
  return decode(data, label);
}
// A row's reader for a format read from its path (by a library that reads files, or line by line).
template <EventRecording (*read)(const std::string&)>
EventRecording path_only(const std::string& path, const std::string&) {
  return read(path);
}

// A row's decoder for a polarity format (event_file.hpp's from_polarity), from its bytes or from
// its path.
template <PolarityRecording (*decode)(const std::string&, const std::string&)>
EventRecording polarity_bytes(const std::string& data, const std::string& label) {
  return from_polarity(decode(data, label), label);
}
template <PolarityRecording (*read)(const std::string&)>
EventRecording polarity_file(const std::string& path) {
  return from_polarity(read(path), path);
}

// The row of a format read from its bytes and not written.
template <EventRecording (*decode)(const std::string&, const std::string&)>
EventFormatRow read_only(EventFileFormat format, const char* name, std::vector<std::string> extensions, const char* help) {
  EventFormatRow r{format, name, std::move(extensions), help};
  r.decode = without_layout<decode>;
  r.read = read_bytes<without_layout<decode>>;
  return r;
}

std::vector<EventFormatRow> make_rows() {
  std::vector<EventFormatRow> rows;
  {
    // Read: AEDAT 2.0 or 3.1 (and Prophesee's DAT from a file whose header lines begin with '%').
    EventFormatRow r{EventFileFormat::Aedat2, "AEDAT 2.0", {".aedat", ".aedat2"}, "jAER's"};
    r.longest_run = 2147;
    r.stamps = "AEDAT 2.0 timestamps are int32 microseconds";
    r.open = [](OutputFiles& files, const std::string& path, const EventFileSpec& spec) -> std::unique_ptr<EventFileWriter> {
      const AddressMap map(spec.array);
      std::vector<std::string> header = aedat_header(map, spec.sensor, spec.layout);
      header.insert(header.begin() + 1, spec.notes.begin(), spec.notes.end());
      return std::make_unique<AedatWriter>(files.open(path), header, map, spec.tick, spec.layout);
    };
    r.decode = decode_aedat_recording;
    r.read = read_bytes<decode_aedat_recording>;
    rows.push_back(std::move(r));
  }
  {
    EventFormatRow r{EventFileFormat::Aedat4, "AEDAT 4.0", {".aedat4"}, "DV's"};
    r.open = [](OutputFiles& files, const std::string& path, const EventFileSpec& spec) -> std::unique_ptr<EventFileWriter> {
      return std::make_unique<Aedat4Writer>(files.open(path), spec);
    };
    r.decode = without_layout<polarity_bytes<decode_aedat4>>;
    r.read = read_bytes<without_layout<polarity_bytes<decode_aedat4>>>;
    rows.push_back(std::move(r));
  }
  {
    EventFormatRow r{EventFileFormat::Npy, ".npy", {".npy"}, "tonic's dtype"};
    r.open = [](OutputFiles& files, const std::string& path, const EventFileSpec& spec) -> std::unique_ptr<EventFileWriter> {
      return std::make_unique<NpyWriter>(files.adopt(path), spec.tick);
    };
    r.decode = without_layout<polarity_bytes<decode_npy>>;
    r.read = read_bytes<without_layout<polarity_bytes<decode_npy>>>;
    rows.push_back(std::move(r));
  }
  {
    EventFormatRow r{EventFileFormat::Hdf5, "HDF5", {".h5", ".hdf5"}, "DSEC layout"};
    r.longest_run = 4294;
    r.stamps = "DSEC timestamps are uint32 microseconds";
    r.open = [](OutputFiles& files, const std::string& path, const EventFileSpec& spec) -> std::unique_ptr<EventFileWriter> {
      return std::make_unique<DsecWriter>(files.adopt(path), spec, spec.duration);
    };
    r.read = path_only<polarity_file<read_dsec_h5>>;
    rows.push_back(std::move(r));
  }
  {
    // Read: EVT 2.0, 2.1 and 3.0 (a camera's recording); written: EVT 2.0 or 3.0 (--raw-encoding).
    EventFormatRow r{EventFileFormat::PropheseeRaw, "Prophesee RAW", {".raw"}, "Metavision's, EVT 2.0 or 3.0"};
    r.longest_run = 17179;
    r.stamps = "EVT 2.0 timestamps are 34-bit microseconds";
    r.open = [](OutputFiles& files, const std::string& path, const EventFileSpec& spec) -> std::unique_ptr<EventFileWriter> {
      return std::make_unique<PropheseeRawWriter>(files.open(path), spec.array, spec.tick, spec.raw_encoding);
    };
    r.decode = without_layout<polarity_bytes<decode_prophesee_raw>>;
    r.read = read_bytes<without_layout<polarity_bytes<decode_prophesee_raw>>>;
    rows.push_back(std::move(r));
  }
  {
    // Written: CD events. Read: the first line says which of the formats that end in .dat the file
    // is, Prophesee's (header lines beginning with '%') or jAER's older AEDAT 2.0 ('#').
    EventFormatRow r{EventFileFormat::PropheseeDat, "Prophesee DAT", {".dat"}, "Metavision's CD events"};
    // aestream reads a DAT stamp as a signed 32-bit number.
    r.longest_run = 2147;
    r.stamps = "DAT timestamps are 32-bit microseconds, read as signed by some readers";
    r.open = [](OutputFiles& files, const std::string& path, const EventFileSpec& spec) -> std::unique_ptr<EventFileWriter> {
      return std::make_unique<PropheseeDatWriter>(files.open(path), spec.array, spec.tick);
    };
    r.decode = decode_aedat_recording;
    r.read = read_bytes<decode_aedat_recording>;
    rows.push_back(std::move(r));
  }
  // Formats read, not written, from their bytes: NumPy archives of events; the ATIS saccade
  // datasets' recordings (N-MNIST, N-Caltech101); `t x y p` a line (the Event Camera Dataset's events.txt, ESIM, v2e,
  // rpg_e2vid); a ROS bag's event topic (the Event Camera Dataset, MVSEC, DAVIS and Prophesee
  // cameras under ROS 1; under ROS 2, bags in MCAP or SQLite).
  rows.push_back(read_only<polarity_bytes<decode_npz>>(EventFileFormat::Npz, "NumPy archive", {".npz"},
                                                 "numpy.savez of an x, y, t, p array or of arrays x, y, t, p"));
  rows.push_back(read_only<polarity_bytes<decode_nmnist_bin>>(EventFileFormat::NmnistBin, "N-MNIST binary", {".bin"},
                                                        "N-MNIST's and N-Caltech101's"));
  rows.push_back(read_only<polarity_bytes<decode_events_text>>(EventFileFormat::EventsText, "events text", {".txt"},
                                                         "t x y p a line, t in s"));
  rows.push_back(read_only<polarity_bytes<decode_ros_bag>>(EventFileFormat::RosBag, "ROS bag", {".bag"},
                                                     "ROS 1's, dvs_msgs/EventArray"));
  rows.push_back(read_only<polarity_bytes<decode_mcap>>(EventFileFormat::Mcap, "MCAP", {".mcap"},
                                                  "ROS 2's bags since Iron, event_camera_msgs/EventPacket"));
  rows.push_back(read_only<polarity_bytes<decode_rosbag2_sqlite>>(EventFileFormat::Rosbag2Sqlite, "ROS 2 SQLite bag", {".db3"},
                                                            "ROS 2's bags before Iron"));
  {
    // Read: MATLAB files of event vectors (ASL-DVS; Orchard's TD structs), from a path (matio
    // reads files).
    EventFormatRow r{EventFileFormat::MatEvents, "MATLAB", {".mat"}, "x, y, ts, p vectors or a TD struct"};
    r.read = path_only<polarity_file<read_mat_events>>;
    rows.push_back(std::move(r));
  }
  {
    EventFormatRow r{EventFileFormat::Csv, "CSV", {".csv"}, "t_us,x,y,tile,flags"};
    r.decode = without_layout<decode_csv_recording>;
    r.read = path_only<read_csv_recording>;
    rows.push_back(std::move(r));
  }
  return rows;
}

// ".a, .b or .c"
std::string listed(const std::vector<std::string>& items) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i > 0) out += i + 1 == items.size() ? " or " : ", ";
    out += items[i];
  }
  return out;
}

}  // namespace

const std::vector<EventFormatRow>& event_formats() {
  static const std::vector<EventFormatRow> rows = make_rows();
  return rows;
}

const EventFormatRow& event_format(EventFileFormat format) {
  for (const EventFormatRow& row : event_formats()) {
    if (row.format == format) return row;
  }
  throw std::logic_error("an event file format without a row");
}

namespace {

// The row of `path`'s extension; none for an extension no format has. No extension keeps the
// AEDAT 2.0 that --out always wrote.
const EventFormatRow* format_row_of(const std::string& path) {
  const std::string ext = file_extension(path);
  if (ext.empty()) return &event_format(EventFileFormat::Aedat2);
  for (const EventFormatRow& row : event_formats()) {
    if (std::find(row.extensions.begin(), row.extensions.end(), ext) != row.extensions.end()) return &row;
  }
  return nullptr;
}

}  // namespace

const EventFormatRow& event_format_of(const std::string& path, const std::string& option) {
  if (const EventFormatRow* row = format_row_of(path)) return *row;
  std::vector<std::string> all;
  for (const EventFormatRow& row : event_formats()) all.insert(all.end(), row.extensions.begin(), row.extensions.end());
  throw InputError(fmt::format("{} '{}': unknown event file type (use {})", option, path, listed(all)));
}

const EventFormatRow& writable_event_format(const std::string& path, const std::string& option) {
  const EventFormatRow* found = format_row_of(path);
  // An output is offered only what can be written.
  if (!found) throw InputError(fmt::format("{} '{}': unknown event file type (write {})", option, path, event_extensions(true)));
  const EventFormatRow& row = *found;
  if (row.open) return row;
  if (row.format == EventFileFormat::Csv) throw InputError(fmt::format("{} '{}': write events CSV with --csv", option, path));
  throw InputError(fmt::format("{} '{}': {} is read, not written (write {})", option, path, row.name, event_extensions(true)));
}

std::string event_extensions(bool writable) {
  std::vector<std::string> first;
  for (const EventFormatRow& row : event_formats()) {
    if (!writable || row.open) first.push_back(row.extensions.front());
  }
  return listed(first);
}

std::string event_inputs() { return event_extensions() + "; or a ROS 2 bag's or an EVIMO2 sequence's folder"; }

std::string event_formats_help() {
  std::vector<std::string> parts;
  for (const EventFormatRow& row : event_formats()) {
    if (!row.open) continue;
    const bool named_by_extension = row.name == row.extensions.front();
    parts.push_back(named_by_extension ? fmt::format("{} ({})", row.extensions.front(), row.help)
                                       : fmt::format("{} ({}, {})", row.extensions.front(), row.name, row.help));
  }
  return listed(parts);
}

}  // namespace aesim
