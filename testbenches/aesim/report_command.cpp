#include <cmath>

#include <fmt/format.h>

#include "commands.hpp"
#include "array/address_map.hpp"
#include "errors/input_error.hpp"

namespace aesim {

int bandwidth_command(const BandwidthOptions& o) {
  if (o.width < 1 || o.height < 1 || o.width > 65535 || o.height > 65535) throw InputError("--width/--height: 1 to 65535");
  if (o.bits < 1 || o.bits > 32) throw InputError("--bits: 1 to 32");
  if (o.events < 0) throw InputError("--events: must not be negative");
  const int xbits = address_bits_for(o.width), ybits = address_bits_for(o.height);
  const double frame_bits = static_cast<double>(o.width) * o.height * o.bits;
  const double event_bits = static_cast<double>(o.events) * (xbits + ybits);
  fmt::print("Bandwidth of one image, as a frame and as address events (the source paper's comparison)\n");
  fmt::print("  frame : {} x {} pixels x {} bits        = {:>12.0f} bits\n", o.width, o.height, o.bits, frame_bits);
  fmt::print("  events: {} events x ({} + {}) address bits = {:>12.0f} bits\n", o.events, xbits, ybits, event_bits);
  fmt::print("  ratio : the events take {:.2f} % of the frame ({:.1f}x fewer bits)\n", 100.0 * event_bits / frame_bits,
             event_bits > 0 ? frame_bits / event_bits : INFINITY);
  fmt::print("\nMemory to hold it (Table 2 form)\n");
  fmt::print("  {:<28} {:>12} {:>12}\n", "", "bits", "bytes");
  fmt::print("  {:<28} {:>12.0f} {:>12.0f}\n", "frame buffer", frame_bits, std::ceil(frame_bits / 8));
  fmt::print("  {:<28} {:>12.0f} {:>12.0f}\n", "event queue", event_bits, std::ceil(event_bits / 8));
  fmt::print("  {:<28} {:>12.0f} {:>12.0f}\n", "event histogram (16-bit)", static_cast<double>(o.width) * o.height * 16,
             static_cast<double>(o.width) * o.height * 2);
  return 0;
}

}  // namespace aesim
