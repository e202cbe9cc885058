#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace aesim {

// What every .npy file begins with (6 bytes), then the format version.
inline constexpr char kNpyMagic[] = "\x93NUMPY";

// The header of a NumPy .npy file (format versions 1.0 to 3.0, as numpy.lib.format writes them):
// the dtype, the order, the shape and where the data begin. Event files (a 1-D structured array)
// and scenes (a 2-D or 3-D array of numbers) read their data from it.
struct NpyHeader {
  // The dtype as written: a simple type's text ("<f4", "|u1") or a structured one's list
  // ("[('x', '<i2'), ('y', '<i2'), ...]").
  std::string descr;
  bool fortran_order = false;
  std::vector<std::uint64_t> shape;  // empty for a scalar
  std::size_t data_offset = 0;       // the data's first byte in the file
};

// Throws InputError("<what>: <reason>") when `data` does not start with a well-formed header.
NpyHeader parse_npy_header(const std::string& data, const std::string& what);

}  // namespace aesim
