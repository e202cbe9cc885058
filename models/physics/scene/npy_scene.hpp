#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "aesim/files/npy_header.hpp"
#include "aesim/scene/image.hpp"

namespace aesim {

// A NumPy .npy array of light as a scene (numpy.save of a 2-D array (rows, columns): one frame;
// of a 3-D one (frames, rows, columns): a moving scene, shown at scene.frame_rate). The numbers
// are taken as the Python module takes an array: see array_full_scale. C or Fortran order, either
// byte order.
struct NpySceneLayout {
  NpyHeader header;
  std::size_t frames = 1;
  int rows = 0, cols = 0;
  char kind = 'f';  // NumPy's kind: 'b' bool, 'u' unsigned, 'i' signed, 'f' float
  int item_bytes = 8;
  bool big_endian = false;
  double full_scale = 1.0;
};

// What a value of full scale (1.0, white) is in an array of NumPy kind `kind` and `item_bytes`:
// 8- and 16-bit integers are code values over 255 and 65535 (as in PGM); floats (16, 32 or 64
// bit) are fractions as they are (as in PFM, above 1 is brighter); bools are 0 or 1. Any other
// type is refused, InputError("<what>: ...").
double array_full_scale(char kind, int item_bytes, const std::string& what);

// An image array as imaging libraries hand it to NumPy, colour last (rows, columns, 3 or 4), would
// read as frames of 3 or 4 columns: refused, InputError("<what>: ..."), for a .npy file and a
// Python array alike, since its codes are gamma-encoded in most tools that make one. Only a
// picture's shape is refused (both other sides over 4): a stack of 4x4 frames is a moving scene.
void check_not_colour_last(const std::vector<std::uint64_t>& shape, const std::string& what);

// The layout from the file's header alone (whether it is one frame or many, before reading it).
NpySceneLayout read_npy_scene_header(const std::string& path);
// The layout of a whole file, its data checked to be all there.
NpySceneLayout parse_npy_scene(const std::string& data, const std::string& path);

// A .npy scene's bytes, bounded, and their layout.
struct NpySceneFile {
  std::string data;
  NpySceneLayout layout;
};
NpySceneFile open_npy_scene(const std::string& path);

// Frame k as light, a fraction of full scale; InputError naming the first value that is negative,
// infinite or NaN.
Image npy_scene_frame(const NpySceneFile& file, std::size_t k, const std::string& path);

}  // namespace aesim
