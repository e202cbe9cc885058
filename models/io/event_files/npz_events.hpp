#pragma once
#include <string>

#include "aesim/event_files/aedat4.hpp"

namespace aesim {

// The events of a NumPy .npz archive (numpy.savez or savez_compressed: a ZIP file, Zip64 as NumPy
// writes it, of one .npy file an array, stored or deflated, each checked against its CRC32):
// either a 1-D structured array with fields x, y, t and p (as a .npy event file; N-ImageNet's
// `event_data`), the first such array in the archive, or four 1-D arrays (or N x 1) named x, y, a
// stamp (t, ts, timestamp or timestamps) and a polarity (p, polarity, pol or polarities), as
// event-based deblurring and interpolation datasets save them (whole stamps are microseconds;
// stamps of floats with fractions are seconds, said in `read_as`); or EVIMO's `events`, N x 4 rows
// of a stamp in seconds, x, y and polarity, beside its `index` and `discretization`. A polarity
// above 0 is ON. The archive records no array size. Throws InputError naming `label` for anything
// malformed or an archive without events (naming the arrays it holds).
PolarityRecording decode_npz(const std::string& data, const std::string& label);

}  // namespace aesim
