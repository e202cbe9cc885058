// NumPy .npy arrays as scenes: the numbers of every type the reader takes, against values worked
// out by hand from the type's definition (codes over full scale, IEEE half/single/double bits, C
// and Fortran order, both byte orders); a 3-D array as a moving scene, frame for frame the same as
// a folder of PFM frames holding the same floats (a reader written independently from Netpbm's
// rules); bad arrays as one-line errors.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/scene/netpbm.hpp"
#include "aesim/scene/npy_scene.hpp"
#include "aesim/scene/scene.hpp"
#include "support/temp_dir_test.hpp"

namespace aesim {
namespace {

// numpy.save's layout, format 1.0: magic, version, header length, the dict padded with spaces to
// a multiple of 64 bytes in all and ended by a newline, then the data.
std::string npy(const std::string& descr, const std::string& shape, const std::string& data, bool fortran = false) {
  std::string dict = fmt::format("{{'descr': '{}', 'fortran_order': {}, 'shape': {}, }}", descr,
                                 fortran ? "True" : "False", shape);
  if (!descr.empty() && descr.front() == '[') {
    dict = fmt::format("{{'descr': {}, 'fortran_order': False, 'shape': {}, }}", descr, shape);
  }
  while ((10 + dict.size() + 1) % 64 != 0) dict += ' ';
  dict += '\n';
  std::string out = "\x93NUMPY";
  out += '\x01';
  out += '\x00';
  out += static_cast<char>(dict.size() & 0xff);
  out += static_cast<char>(dict.size() >> 8);
  return out + dict + data;
}

template <typename T>
std::string bytes_of(const std::vector<T>& values) {
  std::string out(values.size() * sizeof(T), '\0');
  std::memcpy(out.data(), values.data(), out.size());
  return out;
}

class NpySceneTest : public testing::TempDirTest {};

TEST_F(NpySceneTest, NumbersAreReadAsTheirTypeSays) {
  // 8-bit codes over 255, C order: row 0 is 0 51 255, row 1 is 1 2 3.
  Image img = read_image(write("u1.npy", npy("|u1", "(2, 3)", std::string("\x00\x33\xff\x01\x02\x03", 6))));
  ASSERT_EQ(img.width, 3);
  ASSERT_EQ(img.height, 2);
  EXPECT_EQ(img.at(0, 0), 0.0);
  EXPECT_EQ(img.at(1, 0), 51 * (1.0 / 255));
  EXPECT_EQ(img.at(2, 0), 1.0);
  EXPECT_EQ(img.at(2, 1), 3 * (1.0 / 255));
  // 16-bit big-endian codes over 65535: 0xffff, 0x8000.
  img = read_image(write("u2.npy", npy(">u2", "(1, 2)", std::string("\xff\xff\x80\x00", 4))));
  EXPECT_EQ(img.at(0, 0), 1.0);
  EXPECT_EQ(img.at(1, 0), 32768 * (1.0 / 65535));
  // Halves: 0x3c00 is 1, 0x3800 a half, 0x0001 the least subnormal 2^-24, 0x7bff the largest 65504.
  img = read_image(write("f2.npy", npy("<f2", "(1, 4)", std::string("\x00\x3c\x00\x38\x01\x00\xff\x7b", 8))));
  EXPECT_EQ(img.at(0, 0), 1.0);
  EXPECT_EQ(img.at(1, 0), 0.5);
  EXPECT_EQ(img.at(2, 0), std::ldexp(1.0, -24));
  EXPECT_EQ(img.at(3, 0), 65504.0);
  // Singles in Fortran order: the first index runs fastest, so (r, c) lies at r + 2c.
  img = read_image(write("f4.npy", npy("<f4", "(2, 3)", bytes_of<float>({0.5f, 1.5f, 2.5f, 3.5f, 4.5f, 5.5f}), true)));
  EXPECT_EQ(img.at(0, 1), 1.5);  // (row 1, column 0)
  EXPECT_EQ(img.at(1, 0), 2.5);  // (row 0, column 1)
  EXPECT_EQ(img.at(2, 1), 5.5);
  // Bools are 0 or 1; signed 16-bit codes over 65535.
  img = read_image(write("b1.npy", npy("|b1", "(1, 2)", std::string("\x00\x01", 2))));
  EXPECT_EQ(img.at(0, 0), 0.0);
  EXPECT_EQ(img.at(1, 0), 1.0);
  img = read_image(write("i2.npy", npy("<i2", "(1, 1)", std::string("\xff\x7f", 2))));
  EXPECT_EQ(img.at(0, 0), 32767 * (1.0 / 65535));
  // Doubles, 3-D in C order (frame, row, column) and in Fortran order (frame + 2 row here).
  const std::vector<double> d = {0.25, 0.5, 0.75, 1.25};
  NpySceneFile file = open_npy_scene(write("c3.npy", npy("<f8", "(2, 1, 2)", bytes_of(d))));
  EXPECT_EQ(file.layout.frames, 2u);
  EXPECT_EQ(npy_scene_frame(file, 1, "c3.npy").at(0, 0), 0.75);
  EXPECT_EQ(npy_scene_frame(file, 1, "c3.npy").at(1, 0), 1.25);
  file = open_npy_scene(write("f3.npy", npy("<f8", "(2, 2, 1)", bytes_of(d), true)));
  EXPECT_EQ(npy_scene_frame(file, 0, "f3.npy").at(0, 1), 0.75);  // frame 0, row 1: at 0 + 2*1
  EXPECT_EQ(npy_scene_frame(file, 1, "f3.npy").at(0, 0), 0.5);   // frame 1, row 0: at 1
}

// The header is a Python dict literal: its keys in any order and either quote; a structured
// dtype's field named like a key ('shape') is not the key.
TEST_F(NpySceneTest, TheHeaderIsReadAsADictWhateverItsOrder) {
  std::string dict = "{\"shape\": (1, 2), \"fortran_order\": False, \"descr\": \">f8\"}";
  while ((10 + dict.size() + 1) % 64 != 0) dict += ' ';
  dict += '\n';
  std::string file = std::string("\x93NUMPY\x01\x00", 8) + static_cast<char>(dict.size()) + '\0' + dict;
  file += std::string("\x3f\xd0\x00\x00\x00\x00\x00\x00", 8) + std::string("\x40\x00\x00\x00\x00\x00\x00\x00", 8);
  const Image img = read_image(write("dict.npy", file));
  EXPECT_EQ(img.at(0, 0), 0.25);  // big-endian doubles 0x3fd0... and 0x4000...
  EXPECT_EQ(img.at(1, 0), 2.0);
  const NpyHeader h = parse_npy_header(npy("[('shape', '<i2'), ('x', '<i2')]", "(3,)", std::string(12, '\0')), "f");
  ASSERT_EQ(h.shape.size(), 1u);
  EXPECT_EQ(h.shape[0], 3u);
  EXPECT_EQ(h.descr, "[('shape', '<i2'), ('x', '<i2')]");
}

TEST_F(NpySceneTest, BadArraysAreOneLineErrors) {
  const std::pair<std::string, std::string> cases[] = {
      {"not a NumPy .npy file", "P5\n1 1\n255\n\x01"},
      {"structured", npy("[('x', '<i2'), ('y', '<i2')]", "(1,)", std::string(4, '\0'))},
      {"a 1-D array", npy("<f4", "(2,)", bytes_of<float>({1, 1}))},
      {"a 4-D array", npy("<f4", "(1, 1, 1, 1)", bytes_of<float>({1}))},
      {"colour channels last", npy("|u1", "(5, 6, 3)", std::string(90, '\x10'))},
      {"8 or 16 bit", npy("<i8", "(1, 1)", std::string(8, '\0'))},
      {"not an array of", npy("<c8", "(1, 1)", std::string(8, '\0'))},
      {"truncated: 16 values announced, 2 there", npy("<f4", "(4, 4)", bytes_of<float>({1, 1}))},
      {"row 0, column 1 is -1", npy("<f4", "(1, 2)", bytes_of<float>({1, -1}))},
      {"row 1, column 0 is nan", npy("<f8", "(2, 1)", bytes_of<double>({1, NAN}))},
      {"more than the", npy("|u1", "(100000, 100000)", "")},
      {"malformed .npy shape", npy("|u1", "(2, x)", "")},
  };
  for (const auto& [needle, bytes] : cases) {
    try {
      read_image(write("bad.npy", bytes));
      FAIL() << needle;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
    expect_scene_refused("bad.npy", needle);
  }
}

// A PFM frame by Netpbm's rules: "Pf", size, a negative scale for little-endian floats, then the
// rows from the bottom one up.
std::string pfm(int width, int height, const std::vector<float>& top_down) {
  std::string out = fmt::format("Pf\n{} {}\n-1.0\n", width, height);
  for (int y = height - 1; y >= 0; --y) {
    out += bytes_of(std::vector<float>(top_down.begin() + y * width, top_down.begin() + (y + 1) * width));
  }
  return out;
}

TEST_F(NpySceneTest, AThreeDArrayIsAMovingSceneLikeItsFramesInAFolder) {
  const int frames = 3, rows = 12, cols = 20;
  std::vector<float> all;
  std::filesystem::create_directory(dir_ / "frames");
  for (int f = 0; f < frames; ++f) {
    std::vector<float> frame;
    for (int y = 0; y < rows; ++y) {
      for (int x = 0; x < cols; ++x) frame.push_back(static_cast<float>(0.05 + 0.9 * ((x * 7 + y * 3 + f * 11) % 17) / 16.0));
    }
    write(fmt::format("frames/f{}.pfm", f), pfm(cols, rows, frame));
    all.insert(all.end(), frame.begin(), frame.end());
  }
  write("stack.npy", npy("<f4", fmt::format("({}, {}, {})", frames, rows, cols), bytes_of(all)));
  const SceneFiles files = find_scene((dir_ / "stack.npy").string());
  EXPECT_TRUE(files.npy_stack);
  const std::vector<Image> from_npy = read_frames(files), from_pfm = read_frames(find_scene((dir_ / "frames").string()));
  ASSERT_EQ(from_npy.size(), 3u);
  ASSERT_EQ(from_pfm.size(), 3u);
  for (int f = 0; f < frames; ++f) EXPECT_EQ(from_npy[f].pixels, from_pfm[f].pixels) << "frame " << f;
  // Run through: the same events, byte for byte, at scene.frame_rate (no rate in a .npy).
  const std::string common = "--set array.rows=32 --set array.cols=64 --set scene.frame_rate=50 --duration 100ms";
  ASSERT_EQ(aesim("run --scene stack.npy --csv a.csv --summary a.json " + common).status, 0);
  ASSERT_EQ(aesim("run --scene frames --csv b.csv " + common).status, 0);
  const std::string a = testing::slurp(dir_ / "a.csv");
  EXPECT_GT(std::count(a.begin(), a.end(), '\n'), 500);
  EXPECT_EQ(a, testing::slurp(dir_ / "b.csv"));
  EXPECT_NE(testing::slurp(dir_ / "a.json").find("\"frame_rate\": 50"), std::string::npos);
  // A 3-D array is a scene of its own, not one frame of a folder.
  std::filesystem::copy_file(dir_ / "stack.npy", dir_ / "frames" / "f3.npy");
  const testing::Outcome in_folder = aesim("run --scene frames --set scene.frame_rate=50 --duration 100ms");
  EXPECT_EQ(in_folder.status, 2);
  EXPECT_NE(in_folder.err.find("a 3-D array of 3 frames is a scene of its own"), std::string::npos) << in_folder.err;
}

}  // namespace
}  // namespace aesim
