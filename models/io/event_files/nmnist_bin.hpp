#pragma once
#include <string>

#include "aesim/event_files/aedat4.hpp"

namespace aesim {

// The events of an N-MNIST or N-Caltech101 recording (`.bin`, the ATIS saccade datasets), as the
// datasets' own reader (Orchard's Read_Ndataset.m) and tonic's read_mnist_file decode them: no
// header, 5 bytes an event, x in byte 0, y in byte 1, polarity in bit 7 of byte 2 (1 ON), and a
// 23-bit stamp in microseconds in the rest of bytes 2-4, most significant first. A record with y
// 240 is not an event but a stamp overflow: it and every record after it get 2^13 us more, as
// those readers add (counted in `notes`). The file records no size. Throws InputError naming
// `label` for a file that ends inside a record.
PolarityRecording decode_nmnist_bin(const std::string& data, const std::string& label);

}  // namespace aesim
