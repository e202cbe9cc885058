#include "event_files/event_file.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include <fmt/format.h>

#include "array/address_map.hpp"
#include "errors/input_error.hpp"
#include "config/sensor_config.hpp"
#include "event_files/aedat.hpp"
#include "event_files/events_csv.hpp"

namespace aesim {
namespace {

EventRecording from_aedat(const AedatFile& file, const std::string& path) {
  SensorConfig sensor;
  for (const char* key : {"array.rows", "array.cols", "array.tile_rows", "array.tile_cols"}) {
    const auto it = file.metadata.find(std::string("sensor.") + key);
    if (it == file.metadata.end()) {
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
  const AddressMap map(sensor.array);
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

ArraySize parse_array_size(const std::string& text, const std::string& option) {
  ArraySize s;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%dx%d%c", &s.width, &s.height, &tail) != 2 || s.width < 1 || s.height < 1 ||
      s.width > 4096 || s.height > 4096) {
    throw InputError(fmt::format("{}: expected WIDTHxHEIGHT up to 4096x4096 (got '{}')", option, text));
  }
  return s;
}

EventRecording load_events(const std::string& path, const std::optional<ArraySize>& size) {
  const std::string ext = std::filesystem::path(path).extension().string();
  EventRecording rec;
  if (ext == ".csv") {
    rec = from_csv(read_events_csv(path), path);
  } else if (ext == ".aedat" || ext == ".dat") {
    rec = from_aedat(read_aedat(path), path);
  } else {
    throw InputError(fmt::format("event file '{}': unsupported format (use .aedat or .csv)", path));
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

EventRecording decode_events(const std::string& data, const std::string& label, EventFormat format) {
  if (format == EventFormat::Aedat2) return from_aedat(decode_aedat(data, label), label);
  std::istringstream in(data);
  return from_csv(parse_events_csv(in, label), label);
}

}  // namespace aesim
