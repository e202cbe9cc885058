#include "aesim/event_files/event_file.hpp"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>
#include <string_view>

#include <fmt/format.h>

#include "aesim/array/address_map.hpp"
#include "aesim/errors/input_error.hpp"
#include "aesim/config/sensor_config.hpp"
#include "aesim/event_files/aedat.hpp"
#include "aesim/event_files/aedat31.hpp"
#include "aesim/event_files/aedat4.hpp"
#include "aesim/event_files/event_formats.hpp"
#include "aesim/event_files/event_writer.hpp"
#include "aesim/event_files/events_csv.hpp"
#include "aesim/event_files/evimo2_folder.hpp"
#include "aesim/event_files/events_text.hpp"
#include "aesim/event_files/ros2_bag_folder.hpp"
#include "aesim/event_files/prophesee_dat.hpp"
#include "aesim/files/input_path.hpp"
#include "aesim/files/input_file.hpp"

namespace aesim {
namespace {

// The array an aesim-written file records in its sensor parameters ("array.rows" -> text ...).
ArrayParams recorded_array(const std::map<std::string, std::string>& sensor_keys, const std::string& path) {
  SensorConfig sensor;
  for (const char* key : {"array.rows", "array.cols", "array.tile_rows", "array.tile_cols"}) {
    const auto it = sensor_keys.find(key);
    if (it == sensor_keys.end()) {
      throw InputError(fmt::format("event file '{}': header has no aesim.sensor.{} (not written by aesim?)", path, key));
    }
    try {
      sensor.set(key, it->second);
    } catch (const InputError& e) {
      throw InputError(fmt::format("event file '{}': header: {}", path, e.what()));
    }
  }
  try {
    sensor.validate();
  } catch (const InputError& e) {
    throw InputError(fmt::format("event file '{}': header: {}", path, e.what()));
  }
  return sensor.array;
}

// A jAER recording (no aesim keys in its header): the chip's words decoded as jAER's extractor does,
// DVS events kept with their polarity as contrast, APS samples and special (IMU) words counted.
EventRecording from_jaer(const AedatFile& file, const std::string& path, const std::string& layout) {
  std::string named = layout;
  for (const std::string& line : file.header) {
    if (named.empty() && line.rfind("# AEChip:", 0) == 0) named = line.substr(9);
  }
  while (!named.empty() && named.front() == ' ') named.erase(named.begin());
  if (named.empty()) {
    throw InputError(fmt::format("event file '{}': AEDAT 2.0 with neither aesim's header keys nor a '# AEChip:' line: "
                                 "name its chip with --layout dvs128, davis240c or davis346",
                                 path));
  }
  const std::optional<JaerRecordingChip> chip = jaer_recording_chip(named);
  if (!chip) {
    throw InputError(fmt::format("event file '{}': jAER chip '{}': aesim decodes DVS128, DAVIS240C and Davis346 words "
                                 "(--layout dvs128, davis240c or davis346)",
                                 path, named));
  }
  EventRecording rec;
  rec.width = chip->chip.width;
  rec.height = chip->chip.height;
  rec.tiles = 1;
  rec.size_recorded = true;
  std::uint64_t aps = 0, special = 0;
  for (const AedatRecord& r : file.records) {
    const bool dvs = chip->layout == AedatLayout::Dvs128 ? (r.address >> 15) == 0 : !(r.address >> 31) && !(r.address & (1u << 10));
    if (!dvs) {
      ((chip->layout == AedatLayout::Davis && (r.address >> 31)) ? aps : special) += 1;
      continue;
    }
    const auto j = decode_jaer_address(chip->layout, chip->chip, rec.height, rec.width, r.address);
    if (!j) {
      ++special;
      continue;
    }
    AddressEvent e;
    e.t = r.timestamp_us * 1e-6;
    e.x = j->pixel.x;
    e.y = j->pixel.y;
    e.flags = j->ghost ? kOffEvent : kNormalEvent;  // jAER's OFF: contrast, not a collision
    rec.events.push_back(e);
  }
  if (aps) rec.skipped.push_back(fmt::format("{} APS (frame) samples", aps));
  if (special) rec.skipped.push_back(fmt::format("{} special and IMU words", special));
  rec.stamp_wraps = file.stamp_wraps;
  for (std::size_t i = 1; i < rec.events.size(); ++i) rec.reordered += rec.events[i].t < rec.events[i - 1].t ? 1 : 0;
  if (rec.reordered > 0) {
    std::stable_sort(rec.events.begin(), rec.events.end(),
                     [](const AddressEvent& a, const AddressEvent& b) { return a.t < b.t; });
  }
  return rec;
}

EventRecording from_aedat(const AedatFile& file, const std::string& path, const std::string& jaer_layout) {
  if (!file.metadata.count("sensor.array.rows")) return from_jaer(file, path, jaer_layout);
  std::map<std::string, std::string> sensor_keys;
  for (const auto& [key, value] : file.metadata) {
    if (key.rfind("sensor.", 0) == 0) sensor_keys[key.substr(7)] = value;
  }
  const AddressMap map(recorded_array(sensor_keys, path));
  EventRecording rec;
  // A header of another layout than a reader knows, or an array its chip cannot hold, names the file.
  try {
    const auto kind = file.metadata.find("layout.kind");
    if (kind != file.metadata.end()) jaer_chip(parse_aedat_layout(kind->second), map);
  } catch (const InputError& e) {
    throw InputError(fmt::format("event file '{}': header: {}", path, e.what()));
  }
  rec.width = map.cols();
  rec.height = map.rows();
  rec.tiles = map.tiles();
  rec.size_recorded = true;
  const auto kind = file.metadata.find("layout.kind");
  const AedatLayout layout = kind == file.metadata.end() ? AedatLayout::Aesim : parse_aedat_layout(kind->second);
  const JaerChip chip = jaer_chip(layout, map);
  rec.events.reserve(file.records.size());
  for (std::size_t i = 0; i < file.records.size(); ++i) {
    const AedatRecord& r = file.records[i];
    std::optional<PixelAddress> p;
    bool ghost = false;
    if (layout == AedatLayout::Aesim) {
      p = map.decode(r.address);
    } else if (const auto j = decode_jaer_address(layout, chip, map.rows(), map.cols(), r.address)) {
      p = j->pixel;
      ghost = j->ghost;
    }
    if (!p) throw InputError(fmt::format("event file '{}': event {} has address 0x{:x}, outside the array", path, i, r.address));
    AddressEvent e = map.event_at(*p);
    e.t = r.timestamp_us * 1e-6;
    e.flags = ghost ? kGhostEvent : kNormalEvent;
    rec.events.push_back(e);
  }
  return rec;
}

EventRecording from_csv(std::vector<AddressEvent> events, const std::string& path) {
  EventRecording rec;
  rec.events = std::move(events);
  for (const AddressEvent& e : rec.events) {
    rec.width = std::max(rec.width, static_cast<int>(e.x) + 1);
    rec.height = std::max(rec.height, static_cast<int>(e.y) + 1);
    rec.tiles = std::max(rec.tiles, static_cast<int>(e.tile) + 1);
  }
  if (static_cast<long long>(rec.width) * rec.height > kMaxArrayPixels) {
    throw InputError(fmt::format("event file '{}': coordinates up to ({}, {}) span {}x{} pixels, more than the {} "
                                 "aesim images", path, rec.width - 1, rec.height - 1, rec.width, rec.height,
                                 kMaxArrayPixels));
  }
  return rec;
}

}  // namespace

// Events of the polarity formats. A file aesim wrote records its array (and tiles), and polarity 0
// is a ghost (docs/reference.md section 5); so in a .npy, which cannot say who wrote it. In another recorder's
// AEDAT 4.0 or HDF5 file polarity is a camera's ON/OFF and every event counts as a normal one;
// the size is the file's (AEDAT 4.0's sizeX/sizeY) or, when it records none, the events' span.
EventRecording from_polarity(const PolarityRecording& in, const std::string& path) {
  EventRecording rec;
  rec.events.reserve(in.events.size());
  std::int64_t last = 0;
  const auto check_time = [&](std::size_t i, std::int64_t t) {
    if (t < 0) throw InputError(fmt::format("event file '{}': event {} has a negative timestamp ({} us)", path, i, t));
    if (t < last) throw InputError(fmt::format("event file '{}': timestamps decrease at event {}", path, i));
    last = t;
  };
  if (in.sensor.count("array.rows")) {
    const AddressMap map(recorded_array(in.sensor, path));
    rec.width = map.cols();
    rec.height = map.rows();
    rec.tiles = map.tiles();
    rec.size_recorded = true;
    for (std::size_t i = 0; i < in.events.size(); ++i) {
      const PolarityEvent& p = in.events[i];
      check_time(i, p.t_us);
      if (p.x >= rec.width || p.y >= rec.height) {
        throw InputError(fmt::format("event file '{}': event {} at ({}, {}) lies outside its {}x{} array", path, i, p.x,
                                     p.y, rec.width, rec.height));
      }
      AddressEvent e = map.event_at({static_cast<std::uint32_t>(p.x), static_cast<std::uint32_t>(p.y)});
      e.t = static_cast<double>(p.t_us) * 1e-6;
      e.flags = p.on ? kNormalEvent : kGhostEvent;
      rec.events.push_back(e);
    }
    return rec;
  }
  std::vector<AddressEvent> events;
  events.reserve(in.events.size());
  for (std::size_t i = 0; i < in.events.size(); ++i) {
    const PolarityEvent& p = in.events[i];
    check_time(i, p.t_us);
    AddressEvent e;
    e.t = static_cast<double>(p.t_us) * 1e-6;
    e.x = static_cast<std::uint32_t>(p.x);
    e.y = static_cast<std::uint32_t>(p.y);
    // Not aesim's file: its polarity is a camera's contrast, kept as ON and OFF.
    e.flags = p.on ? kNormalEvent : kOffEvent;
    events.push_back(e);
  }
  rec = from_csv(std::move(events), path);
  rec.reordered = in.reordered;
  for (const SkippedPackets& s : in.skipped) {
    rec.skipped.push_back(fmt::format("{} packets of {} ({} bytes)", s.packets, s.type, s.bytes));
  }
  if (in.invalid > 0) rec.skipped.push_back(fmt::format("{} events their recorder marked invalid", in.invalid));
  rec.skipped.insert(rec.skipped.end(), in.notes.begin(), in.notes.end());
  rec.read_as = in.read_as;
  if (in.width > 0 && in.height > 0) {
    if (rec.width > in.width || rec.height > in.height) {
      throw InputError(fmt::format("event file '{}': events reach ({}, {}), outside its {}x{} array", path,
                                   rec.width - 1, rec.height - 1, in.width, in.height));
    }
    rec.width = in.width;
    rec.height = in.height;
    rec.tiles = 1;
    rec.size_recorded = true;
  }
  return rec;
}

namespace {

std::string read_whole(const std::string& path) { return read_input_file(path, "event file", kMaxEventFileBytes); }

}  // namespace

ArraySize parse_array_size(const std::string& text, const std::string& option) {
  // Digits only, each number read whole (no sign, no wrap of a number past the int's range).
  const auto x = text.find('x');
  long long w = 0, h = 0;
  const char* end = text.data() + text.size();
  const bool ok = x != std::string::npos && x > 0 && x + 1 < text.size() &&
                  std::all_of(text.begin(), text.begin() + static_cast<long>(x), ::isdigit) &&
                  std::all_of(text.begin() + static_cast<long>(x) + 1, text.end(), ::isdigit) &&
                  std::from_chars(text.data(), text.data() + x, w).ptr == text.data() + x &&
                  std::from_chars(text.data() + x + 1, end, h).ptr == end;
  if (!ok || w < 1 || h < 1 || w > 4096 || h > 4096) {
    throw InputError(fmt::format("{}: expected WIDTHxHEIGHT up to 4096x4096 (got '{}')", option, text));
  }
  return ArraySize{static_cast<int>(w), static_cast<int>(h)};
}

EventRecording decode_aedat_recording(const std::string& data, const std::string& label, const std::string& layout) {
  // .aedat holds AEDAT 2.0 (jAER) or 3.1 (cAER, jAER), and .dat jAER's or Prophesee's: the first
  // line says which.
  if (is_prophesee_dat(data)) {
    if (!layout.empty()) throw InputError("--layout: jAER's layouts are for AEDAT 2.0 files; this one is Prophesee DAT");
    return from_polarity(decode_prophesee_dat(data, label), label);
  }
  if (is_aedat31(data)) {
    if (!layout.empty()) throw InputError("--layout: jAER's layouts are for AEDAT 2.0 files; this one is AEDAT 3.1");
    return from_polarity(decode_aedat31(data, label), label);
  }
  return from_aedat(decode_aedat(data, label), label, layout);
}

// aesim's own CSV begins with its header; any other is another tool's (foreign_csv).
bool is_aesim_csv(std::string_view head) { return head.rfind("t_us,x,y,tile,flags", 0) == 0; }

EventRecording decode_csv_recording(const std::string& data, const std::string& label) {
  if (!is_aesim_csv(data)) return from_polarity(decode_foreign_csv(data, label), label);
  std::istringstream in(data);
  return from_csv(parse_events_csv(in, label), label);
}

EventRecording read_csv_recording(const std::string& path) {
  if (!is_aesim_csv(read_input_head(path, "event file", 32))) return decode_csv_recording(read_whole(path), path);
  return from_csv(read_events_csv(path), path);
}

std::string read_event_file_bytes(const std::string& path) { return read_whole(path); }

EventRecording load_events(const std::string& path, const std::optional<ArraySize>& size, const std::string& layout) {
  EventRecording rec;
  std::error_code not_a_folder;
  // jAER's chips name an AEDAT 2.0 file's address layout (Prophesee's .dat and jAER's older .dat
  // are told apart by their first line, where the reader refuses it for Prophesee's).
  const auto no_layout = [&layout](const std::string& what) {
    if (!layout.empty()) throw InputError(fmt::format("--layout: jAER's layouts are for AEDAT 2.0 files; this one is {}", what));
  };
  if (std::filesystem::is_directory(path, not_a_folder)) {
    no_layout(is_evimo2_folder(path) ? "an EVIMO2 sequence's folder" : "a ROS 2 bag's folder");
    // An EVIMO2 sequence keeps its events in three arrays of a folder; a ROS 2 bag is a folder of
    // its storage files.
    rec = from_polarity(is_evimo2_folder(path) ? read_evimo2_folder(path) : read_ros2_bag_folder(path), path);
  } else if (is_compressed_ros2_bag_file(path)) {
    no_layout("a ROS 2 bag's file");
    rec = from_polarity(read_compressed_ros2_bag_file(path), path);
  } else {
    const EventFormatRow* row = nullptr;
    try {
      row = &event_format_of(path, "event file");
    } catch (const InputError&) {
      const std::string hint =
          file_extension(path) == ".zstd" ? ": a file compressed whole: uncompress it with `zstd -d`" : "";
      throw InputError(fmt::format("event file '{}': unsupported format (use {}){}", path, event_inputs(), hint));
    }
    if (row->format != EventFileFormat::Aedat2 && row->format != EventFileFormat::PropheseeDat) no_layout(row->name);
    rec = row->read(path, layout);
  }
  if (!size) return rec;
  if (rec.size_recorded && (rec.width != size->width || rec.height != size->height)) {
    throw InputError(fmt::format("--size {}x{}: event file '{}' records a {}x{} array", size->width, size->height, path,
                                 rec.width, rec.height));
  }
  for (std::size_t i = 0; i < rec.events.size(); ++i) {
    const AddressEvent& e = rec.events[i];
    if (static_cast<int>(e.x) >= size->width || static_cast<int>(e.y) >= size->height) {
      throw InputError(fmt::format("event file '{}': event {} at ({}, {}) lies outside --size {}x{}", path, i, e.x, e.y,
                                   size->width, size->height));
    }
  }
  rec.width = size->width;
  rec.height = size->height;
  rec.size_recorded = true;
  return rec;
}

EventRecording decode_events(const std::string& data, const std::string& label, EventFileFormat format) {
  const EventFormatRow& row = event_format(format);
  if (!row.decode) throw InputError(fmt::format("event file '{}': {} is read from a file, not from memory", label, row.name));
  return row.decode(data, label, "");
}

}  // namespace aesim
