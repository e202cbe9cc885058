#include <cmath>

#include <fmt/format.h>

#include "commands.hpp"
#include "aesim/array/address_map.hpp"
#include "aesim/bandwidth/image_bandwidth.hpp"
#include "aesim/errors/input_error.hpp"
#include "report_stream.hpp"

namespace aesim {

int bandwidth_command(const BandwidthOptions& o) {
  if (o.width < 1 || o.height < 1 || o.width > 65535 || o.height > 65535) throw InputError("--width/--height: 1 to 65535");
  if (o.bits < 1 || o.bits > 32) throw InputError("--bits: 1 to 32");
  if (o.events < 0) throw InputError("--events: must not be negative");
  const int xbits = address_bits_for(o.width), ybits = address_bits_for(o.height);
  const double frame_bits = static_cast<double>(o.width) * o.height * o.bits;
  const double event_bits = static_cast<double>(o.events) * (xbits + ybits);
  fmt::print(report_stream(), "Bandwidth of one image, as a frame and as address events (the source paper's comparison)\n");
  fmt::print(report_stream(), "  frame : {} x {} pixels x {} bits        = {:>12.0f} bits\n", o.width, o.height, o.bits, frame_bits);
  fmt::print(report_stream(), "  events: {} events x ({} + {}) address bits = {:>12.0f} bits\n", o.events, xbits, ybits, event_bits);
  fmt::print(report_stream(), "  ratio : the events take {:.2f} % of the frame ({:.1f}x fewer bits)\n", 100.0 * event_bits / frame_bits,
             event_bits > 0 ? frame_bits / event_bits : INFINITY);
  if (o.frame_overhead < 0 || o.frame_overhead > 1 << 20) throw InputError("--frame-overhead: 0 to 1 MiB");
  if (!(o.radio.bit_rate > 0 && o.radio.bit_rate <= 1e12)) throw InputError("--bit-rate: from >0 to 1e12 bit/s");
  if (o.radio.packet_bytes < 2 || o.radio.packet_bytes > 1 << 20) throw InputError("--packet-bytes: 2 to 1 MiB");
  if (o.radio.packet_overhead < 0 || o.radio.packet_overhead >= o.radio.packet_bytes) {
    throw InputError("--packet-overhead: from 0 to less than --packet-bytes");
  }
  fmt::print(report_stream(), "\nMemory to hold it and time to send it (Table 2 form; frame overhead {} bytes; radio {} kbit/s, "
             "packets of {} bytes with {} of overhead)\n",
             o.frame_overhead, o.radio.bit_rate / 1e3, o.radio.packet_bytes, o.radio.packet_overhead);
  fmt::print(report_stream(), "  {:<28} {:>12} {:>12} {:>9} {:>12}\n", "", "bits", "bytes", "packets", "airtime");
  for (const ImageCost& c : image_costs({o.width, o.height, o.bits, static_cast<double>(o.events), o.frame_overhead},
                                        o.radio)) {
    fmt::print(report_stream(), "  {:<28} {:>12.0f} {:>12.0f} {:>9.0f} {:>10.4f} s\n", c.form, c.payload_bits, c.bytes, c.packets,
               c.airtime_s);
  }
  return 0;
}

}  // namespace aesim
