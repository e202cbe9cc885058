#include "aesim/bandwidth/image_bandwidth.hpp"

#include <cmath>

#include "aesim/array/address_map.hpp"

namespace aesim {
namespace {

ImageCost cost(const std::string& form, double payload_bits, double overhead_bytes, const RadioModel& radio) {
  ImageCost c;
  c.form = form;
  c.payload_bits = payload_bits;
  c.bytes = std::ceil(payload_bits / 8) + overhead_bytes;
  const int room = radio.packet_bytes - radio.packet_overhead;
  c.packets = c.bytes > 0 ? std::ceil(c.bytes / room) : 0;
  c.airtime_s = (c.bytes + c.packets * radio.packet_overhead) * 8 / radio.bit_rate;
  return c;
}

}  // namespace

std::vector<ImageCost> image_costs(const ImageShape& s, const RadioModel& radio) {
  const double pixels = static_cast<double>(s.width) * s.height;
  const int address_bits = address_bits_for(s.width) + address_bits_for(s.height);
  return {cost("frame", pixels * s.bits, s.frame_overhead, radio),
          cost("event queue", s.events * address_bits, 0, radio),
          cost("event histogram (16-bit)", pixels * 16, 0, radio)};
}

}  // namespace aesim
