#include "event_files/event_file.hpp"

#include <algorithm>
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
  rec.width = map.cols();
  rec.height = map.rows();
  rec.tiles = map.tiles();
  rec.events.reserve(file.records.size());
  for (std::size_t i = 0; i < file.records.size(); ++i) {
    const AedatRecord& r = file.records[i];
    const auto p = map.decode(r.address);
    if (!p) throw InputError(fmt::format("event file '{}': event {} has address 0x{:x}, outside the array", path, i, r.address));
    AddressEvent e = map.event_at(*p);
    e.t = r.timestamp_us * 1e-6;
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

EventRecording load_events(const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".csv") return from_csv(read_events_csv(path), path);
  if (ext == ".aedat" || ext == ".dat") return from_aedat(read_aedat(path), path);
  throw InputError(fmt::format("event file '{}': unsupported format (use .aedat or .csv)", path));
}

EventRecording decode_events(const std::string& data, const std::string& label, EventFormat format) {
  if (format == EventFormat::Aedat2) return from_aedat(decode_aedat(data, label), label);
  std::istringstream in(data);
  return from_csv(parse_events_csv(in, label), label);
}

}  // namespace aesim
