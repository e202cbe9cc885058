#pragma once
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace aesim {

// A chunk the ECF decoder cannot take, said in words (the caller names the file).
class EcfError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Metavision's CD event as its HDF5 files hold it and ECF's decoder gives it: x, y, p at 0, 2 and 4,
// the stamp (us) at 8; 16 bytes, little-endian.
inline constexpr std::size_t kEcfEventBytes = 16;
inline constexpr std::size_t kEcfMostEvents = 65535;  // events in one ECF block, as its codec allows

// Decodes one block of Prophesee's ECF codec (its hdf5_ecf repository's ecf_codec.cpp: the
// encoding Metavision compresses an HDF5 chunk of CD events with, HDF5 filter 0x8ECF) into
// `out`, which must hold kEcfMostEvents * kEcfEventBytes bytes, and returns the bytes written. The
// block: a 32-bit word of the event count (above 2 bits) and two packing flags; the first stamp (64
// bits), then each step of time and how many events share it, a byte of two nibbles each (a count
// of 15 followed by 16 bits; a step of 15 a nibble of a longer step, least significant first);
// then either y, x and p packed in 24 bits, four events in three 32-bit words; or runs of y (11
// bits and a 5-bit count, or 31 and a 16-bit count), then x and p packed in 12 bits, four events in
// three 16-bit words, or x masked (a column and a mask of the next five columns that also fired)
// and runs of p (a bit and a 7-bit count, or 127 and a 16-bit count). Every read is checked against
// `bytes`; a block that claims more events than it describes, or describes more than it claims,
// throws EcfError.
std::size_t decode_ecf_block(const unsigned char* in, std::size_t bytes, unsigned char* out);

}  // namespace aesim
