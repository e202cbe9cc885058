#pragma once
#include <string>
#include <vector>

#include "aesim/scene/image.hpp"

namespace aesim {

// A photograph built row by row as its decoder gives the rows, in linear light. One larger than
// aesim holds (kMaxArrayPixels: a 45-61 MP camera's, a 200 MP phone's) is averaged over blocks of
// k x k of its pixels, k the smallest whole number that brings it within, as a photodiode of k x k
// of them would integrate their light: the scene is resampled to the array by the same area rule
// afterwards (resample_area), so only detail finer than k pixels, far below any array's pitch, is
// lost. Where a side is not a multiple of k, its last block holds fewer pixels and stands for a
// whole one. Images up to kMaxDecodedPixels (sides up to 65535) are read; a larger one is an
// InputError naming the file, before anything is decoded.
class ReducedImage {
 public:
  ReducedImage(long long width, long long height, const std::string& path);
  // Whether a picture of that size is read (the constructor's test, as a value), and the same test
  // throwing the InputError.
  static bool decodable(long long width, long long height);
  static void check(long long width, long long height, const std::string& path);
  int factor() const { return k_; }
  // The next row of the picture: `width` values of linear light.
  void add_row(const double* light);
  // The image, once every row is in.
  Image take();

 private:
  void close_band();
  long long width_, height_;
  int k_ = 1;
  long long rows_in_ = 0;
  int band_rows_ = 0;  // rows summed into sums_ since the last band was closed
  std::vector<double> sums_;
  Image out_;
};

}  // namespace aesim
