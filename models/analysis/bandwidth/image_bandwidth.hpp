#pragma once
#include <string>
#include <vector>

namespace aesim {

// The source paper's Table 2: what one image costs to hold and to send, as a frame and as
// address events. A radio sends packets of at most `packet_bytes`, each spending
// `packet_overhead` of them on headers (IEEE 802.15.4: 127-byte frames at 250 kbit/s; the
// paper's 8 bytes of overhead per packet).
struct RadioModel {
  double bit_rate = 250e3;  // bit/s
  int packet_bytes = 127;
  int packet_overhead = 8;
};

struct ImageCost {
  std::string form;      // "frame", "event queue", "event histogram (16-bit)"
  double payload_bits = 0;
  double bytes = 0;      // memory: the payload in whole bytes plus the form's own overhead
  double packets = 0;
  double airtime_s = 0;  // bytes and the packets' overhead at the radio's rate
};

struct ImageShape {
  int width = 0, height = 0, bits = 8;  // the frame's pixels and bits per pixel
  double events = 0;                    // events that carry the image
  int frame_overhead = 12;              // bytes a frame carries beyond its pixels (the paper's)
};

// Frame (width x height x bits, plus the frame overhead), event queue (events x the address
// bits of x and y) and the 16-bit histogram a receiver would accumulate.
std::vector<ImageCost> image_costs(const ImageShape& shape, const RadioModel& radio);

}  // namespace aesim
