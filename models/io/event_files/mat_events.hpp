#pragma once
#include <string>

#include "aesim/event_files/aedat4.hpp"

namespace aesim {

// The events of a MATLAB file (`.mat`, versions 4, 5 and 7.3, read by matio): four vectors of one
// length, x, y, a stamp (`ts`, `t` or `timestamp`) and a polarity (`pol`, `p` or `polarity`),
// either as variables of their own (ASL-DVS's files) or as the fields of one struct (`TD`, as
// Garrick Orchard's MATLAB tools for N-MNIST and N-Caltech101 make it, or any name). Which
// convention the numbers follow is told by the polarities:
//  - 0 and 1, or -1 and 1 (0-based, as Python and C write): x and y as they are, ON where p > 0;
//  - 1 and 2 (MATLAB's 1-based indexing, Orchard's Read_Ndataset: x + 1, y + 1, p + 1): x and y
//    one less, ON where p is 2 (noted).
// Stamps are whole microseconds; stamps with fractions are seconds, rounded to the microsecond
// (noted). The file records no size. Events out of time order are put in order and counted. Read
// in a forked copy (matio, like HDF5, is a C library that may crash on a hostile file). Throws
// InputError naming the file for anything else: no such vectors (naming the variables it has),
// vectors of different lengths, complex or sparse ones, coordinates that are not whole pixels of
// a 4096x4096 array, negative stamps.
PolarityRecording read_mat_events(const std::string& path);

}  // namespace aesim
