#include "aesim/event_files/event_writer.hpp"

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/event_files/event_formats.hpp"
#include "aesim/event_files/on_array_events.hpp"

namespace aesim {

std::unique_ptr<EventFileWriter> open_event_writer(OutputFiles& files, const std::string& path,
                                                   const EventFileSpec& spec) {
  const EventFormatRow& row = writable_event_format(path, "--out");
  return std::make_unique<OnArrayEvents>(row.open(files, path, spec), AddressMap(spec.array));
}

}  // namespace aesim
