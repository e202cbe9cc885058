#include <cstdio>
#include <optional>

#include <fmt/format.h>

#include "commands.hpp"
#include "aesim/errors/input_error.hpp"
#include "aesim/output/atomic_file.hpp"
#include "aesim/event_files/event_file.hpp"
#include "aesim/images/image_file.hpp"
#include "aesim/recon/reconstruct.hpp"
#include "aesim/units/si_units.hpp"
#include "report_stream.hpp"

namespace aesim {

int recon_command(const ReconOptions& opt) {
  if (opt.mode != "histogram" && opt.mode != "interval") {
    throw InputError(fmt::format("--mode: expected histogram or interval (got '{}')", opt.mode));
  }
  check_image_path(opt.output);
  if (opt.count == 0 || opt.count < -1) throw InputError("--events: must be a positive count");
  const double window = opt.window.empty() ? 0 : parse_si(opt.window, "s", "--window");
  if (!opt.window.empty() && window <= 0) throw InputError("--window: must be positive");
  check_output_paths({{"-o", opt.output}}, {opt.events});

  const std::optional<ArraySize> size =
      opt.size.empty() ? std::nullopt : std::optional<ArraySize>(parse_array_size(opt.size, "--size"));
  const EventRecording rec = load_events(opt.events, size, opt.layout);
  if (!rec.size_recorded && rec.width > 0) {
    // the reference's `aesim recon EVENTS -o IMAGE` keeps working on a CSV, which records no size; the
    // image then spans the events that fired, which may be smaller than the array.
    std::fprintf(stderr, "aesim recon: warning: '%s' records no array size; the image spans its events (%dx%d); give "
                         "--size WIDTHxHEIGHT for the array's\n", opt.events.c_str(), rec.width, rec.height);
  }
  std::vector<AddressEvent> chosen = rec.events;
  if (opt.count > 0) chosen = first_events(rec.events, static_cast<std::size_t>(opt.count));
  if (!opt.window.empty()) chosen = first_window(rec.events, window);
  if (rec.width == 0) throw InputError(fmt::format("event file '{}' has no events and no array size", opt.events));

  const ReconMode mode = opt.mode == "histogram" ? ReconMode::Histogram : ReconMode::Interval;
  OutputFiles files;
  Image image = reconstruct(chosen, rec.width, rec.height, mode);
  scale_to_percentile(image, 99.5);  // a recording's hot pixels would leave the rest black
  write_image(files.open(opt.output), opt.output, image);
  files.commit();
  fmt::print(report_stream(), "aesim recon: {} of {} events, {} reconstruction {}x{} -> {}\n", chosen.size(), rec.events.size(),
             opt.mode, rec.width, rec.height, opt.output);
  return 0;
}

}  // namespace aesim
