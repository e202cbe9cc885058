#include "event_files/event_writer.hpp"

#include <filesystem>

#include <fmt/format.h>

#include "errors/input_error.hpp"
#include "event_files/aedat.hpp"
#include "event_files/aedat4.hpp"
#include "event_files/dsec_h5.hpp"
#include "event_files/npy_events.hpp"
#include "event_files/on_array_events.hpp"
#include "output/atomic_file.hpp"

namespace aesim {

EventFileFormat event_file_format(const std::string& path, const std::string& option) {
  const std::string ext = std::filesystem::path(path).extension().string();
  // No extension keeps the AEDAT 2.0 that --out always wrote; jAER itself names its files .dat.
  if (ext.empty() || ext == ".aedat" || ext == ".aedat2" || ext == ".dat") return EventFileFormat::Aedat2;
  if (ext == ".aedat4") return EventFileFormat::Aedat4;
  if (ext == ".npy") return EventFileFormat::Npy;
  if (ext == ".h5" || ext == ".hdf5") return EventFileFormat::Hdf5;
  if (ext == ".csv") return EventFileFormat::Csv;
  throw InputError(fmt::format("{} '{}': unknown event file type (use .aedat, .aedat2, .aedat4, .npy, .h5 or .csv)",
                               option, path));
}

std::unique_ptr<EventFileWriter> open_event_writer(OutputFiles& files, const std::string& path,
                                                   const EventFileSpec& spec) {
  const AddressMap map(spec.array);
  const auto on_array = [&map](std::unique_ptr<EventFileWriter> writer) -> std::unique_ptr<EventFileWriter> {
    return std::make_unique<OnArrayEvents>(std::move(writer), map);
  };
  switch (event_file_format(path, "--out")) {
    case EventFileFormat::Aedat2: {
      std::vector<std::string> header = aedat_header(map, spec.sensor, spec.layout);
      header.insert(header.begin() + 1, spec.notes.begin(), spec.notes.end());
      return on_array(std::make_unique<AedatWriter>(files.open(path), header, map, spec.tick, spec.layout));
    }
    case EventFileFormat::Aedat4:
      return on_array(std::make_unique<Aedat4Writer>(files.open(path), spec));
    case EventFileFormat::Npy:
      return on_array(std::make_unique<NpyWriter>(files.adopt(path), spec.tick));
    case EventFileFormat::Hdf5:
      return on_array(std::make_unique<DsecWriter>(files.adopt(path), spec, spec.duration));
    case EventFileFormat::Csv:
      break;
  }
  throw InputError(fmt::format("--out '{}': write events CSV with --csv", path));
}

}  // namespace aesim
