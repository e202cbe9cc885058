// Scene files: PBM/PGM/PPM/PFM decoding, malformed files, resampling, frame folders.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/scene/netpbm.hpp"
#include "aesim/scene/resample.hpp"
#include "aesim/scene/scene.hpp"
#include "support/temp_dir_test.hpp"

namespace aesim {
namespace {
namespace fs = std::filesystem;

using SceneFilesTest = testing::TempDirTest;

TEST_F(SceneFilesTest, AsciiAndBinaryPgmIn8And16Bit) {
  const Image a = read_pnm(write("a.pgm", "P2\n# comment\n3 2\n255\n0 51 255\n# inline\n102 153 204\n"));
  ASSERT_EQ(a.width, 3);
  ASSERT_EQ(a.height, 2);
  EXPECT_DOUBLE_EQ(a.at(1, 0), 51 / 255.0);
  EXPECT_DOUBLE_EQ(a.at(2, 1), 204 / 255.0);

  const Image b = read_pnm(write("b.pgm", std::string("P5\n2 1\n255\n") + char(0) + char(255)));
  EXPECT_DOUBLE_EQ(b.at(0, 0), 0.0);
  EXPECT_DOUBLE_EQ(b.at(1, 0), 1.0);

  // 16-bit samples are big-endian: 0x0100 = 256, 0xFFFF = full scale.
  const Image c = read_pnm(write("c.pgm", std::string("P5\n2 1\n65535\n") + char(1) + char(0) + char(255) + char(255)));
  EXPECT_DOUBLE_EQ(c.at(0, 0), 256 / 65535.0);
  EXPECT_DOUBLE_EQ(c.at(1, 0), 1.0);
}

// PPM: three samples a pixel, taken as the Rec. 709 luminance of linear values, as PGM's grey.
TEST_F(SceneFilesTest, PpmIsRec709LuminanceInAsciiAndBinaryAnd16Bit) {
  const Image a = read_pnm(write("a.ppm", "P3\n# comment\n2 1\n255\n255 0 0  0 51 255\n"));
  ASSERT_EQ(a.width, 2);
  ASSERT_EQ(a.height, 1);
  EXPECT_DOUBLE_EQ(a.at(0, 0), 0.2126);
  EXPECT_DOUBLE_EQ(a.at(1, 0), 0.7152 * 51 / 255.0 + 0.0722);
  const Image b = read_pnm(write("b.ppm", std::string("P6\n1 2\n255\n") + char(0) + char(255) + char(0) + char(255) +
                                              char(255) + char(255)));
  EXPECT_DOUBLE_EQ(b.at(0, 0), 0.7152);
  EXPECT_NEAR(b.at(0, 1), 1.0, 1e-15);
  // 16-bit samples are big-endian, as PGM's.
  const Image c = read_pnm(write("c.ppm", std::string("P6\n1 1\n65535\n") + char(1) + char(0) + char(0) + char(0) +
                                              char(0) + char(0)));
  EXPECT_DOUBLE_EQ(c.at(0, 0), 0.2126 * 256 / 65535.0);
  // A grey PPM reads as the same PGM, through read_image by its extension in either case.
  const Image grey = read_image(write("GREY.PPM", "P3\n2 1\n255\n10 10 10 200 200 200\n"));
  const Image same = read_image(write("grey.PGM", "P2\n2 1\n255\n10 200\n"));
  ASSERT_EQ(grey.pixels.size(), same.pixels.size());
  for (std::size_t i = 0; i < grey.pixels.size(); ++i) EXPECT_NEAR(grey.pixels[i], same.pixels[i], 1e-15) << i;
  for (const auto& [needle, bytes] : {std::pair<std::string, std::string>{"truncated pixel data", "P6\n2 1\n255\nabc"},
                                      {"not a Netpbm image (expected the magic number P1 to P6", "P7\n1 1\n255\nx"},
                                      {"pixel value 300", "P3\n1 1\n255\n1 2 300\n"}}) {
    try {
      read_pnm(write("bad.ppm", bytes));
      FAIL() << "accepted a file that should fail with '" << needle << "'";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  }
}

// Netpbm's tools tell PBM, PGM and PPM apart by the magic number, not the name: a grey picture an
// imaging library wrote as P5 under .ppm, or a colour one under .pgm or .pnm, reads as what it is.
TEST_F(SceneFilesTest, TheMagicNumberNotTheExtensionTellsGreyFromColour) {
  const std::string grey = std::string("P5\n2 1\n255\n") + char(51) + char(255);
  const std::string colour = std::string("P6\n2 1\n255\n") + char(255) + char(0) + char(0) + char(0) + char(0) + char(255);
  for (const char* name : {"g.ppm", "g.pgm", "g.PNM", "g.pbm"}) {
    const Image g = read_image(write(name, grey));
    ASSERT_EQ(g.width, 2) << name;
    EXPECT_DOUBLE_EQ(g.at(0, 0), 51 / 255.0) << name;
    EXPECT_DOUBLE_EQ(g.at(1, 0), 1.0) << name;
    const Image c = read_image(write(name, colour));
    EXPECT_DOUBLE_EQ(c.at(0, 0), 0.2126) << name;
    EXPECT_DOUBLE_EQ(c.at(1, 0), 0.0722) << name;
  }
  EXPECT_TRUE(is_scene_image("frame_001.pnm"));
  EXPECT_TRUE(is_scene_image("frame_001.PBM"));
}

// PBM, as Netpbm's pbm(5) lays it out: 1 is black. Plain (P1) digits with or without space
// between them; raw (P4) bits packed from the most significant, each row starting a new byte.
TEST_F(SceneFilesTest, PbmBitmapsAreBlackForOneInPlainAndPackedRows) {
  // Hand-worked 10x2: row 0 alternates from black, row 1 is black only at x = 9.
  const std::string plain = "P1\n# a comment\n10 2\n1010101010\n0 0 0 0 0 0 0 0 0 1\n";
  // Row 0: 1010 1010 | 10 padded -> 0xAA 0x80; row 1: 0000 0000 | 01 padded -> 0x00 0x40.
  const std::string packed = std::string("P4\n10 2\n") + char(0xAA) + char(0x80) + char(0x00) + char(0x40);
  for (const std::string& bytes : {plain, packed}) {
    const Image img = read_pnm(write("b.pbm", bytes));
    ASSERT_EQ(img.width, 10);
    ASSERT_EQ(img.height, 2);
    for (int x = 0; x < 10; ++x) {
      EXPECT_EQ(img.at(x, 0), x % 2 == 0 ? 0.0 : 1.0) << bytes.substr(0, 2) << " x " << x;
      EXPECT_EQ(img.at(x, 1), x == 9 ? 0.0 : 1.0) << bytes.substr(0, 2) << " x " << x;
    }
  }
  for (const auto& [needle, bytes] : {std::pair<std::string, std::string>{"truncated pixel data (1 of 4 bytes)",
                                                                          std::string("P4\n10 2\n") + char(0xAA)},
                                      {"room for at most", "P1\n4 4\n1 0\n"},
                                      {"malformed pixel '2'", "P1\n2 1\n12\n"}}) {
    try {
      read_pnm(write("bad.pbm", bytes));
      FAIL() << "accepted a file that should fail with '" << needle << "'";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  }
}

std::string pfm_bytes(const char* magic, int w, int h, float scale, const std::vector<float>& rows_bottom_up) {
  std::string s = std::string(magic) + "\n" + std::to_string(w) + " " + std::to_string(h) + "\n" +
                  std::to_string(scale) + "\n";
  for (float v : rows_bottom_up) {
    char b[4];
    std::memcpy(b, &v, 4);
    if (scale > 0) {
      std::swap(b[0], b[3]);
      std::swap(b[1], b[2]);
    }
    s.append(b, 4);
  }
  return s;
}

TEST_F(SceneFilesTest, PfmIsBottomUpInEitherByteOrderAndKeepsHdrValues) {
  for (float scale : {-1.0f, 1.0f}) {
    const Image img = read_pfm(write("h.pfm", pfm_bytes("Pf", 2, 2, scale, {1e-4f, 2e-4f, 10.0f, 1000.0f})));
    EXPECT_FLOAT_EQ(static_cast<float>(img.at(0, 0)), 10.0f);  // top row is stored last
    EXPECT_FLOAT_EQ(static_cast<float>(img.at(1, 0)), 1000.0f);
    EXPECT_FLOAT_EQ(static_cast<float>(img.at(0, 1)), 1e-4f);
  }
  const Image rgb = read_pfm(write("c.pfm", pfm_bytes("PF", 1, 1, -1.0f, {1.0f, 1.0f, 1.0f})));
  EXPECT_NEAR(rgb.at(0, 0), 1.0, 1e-6);
}

TEST_F(SceneFilesTest, MalformedFilesAreInputErrorsNamingTheDefect) {
  const std::pair<const char*, std::string> cases[] = {
      {"truncated", std::string("P5\n4 4\n255\n") + std::string(10, 'x')},
      {"not a Netpbm image", "Pf\n1 1\n-1\n\0\0\0\0"},
      {"maxval", "P2\n1 1\n70000\n5\n"},
      {"pixel value 101", "P2\n1 1\n100\n101\n"},
      {"malformed width", "P2\nx 1\n255\n0\n"},
      {"truncated header", "P5\n4"},
      {"more than the 16777216 pixels", "P5\n65536 65536\n255\n"},
      {"", ""},
  };
  for (const auto& [needle, bytes] : cases) {
    try {
      read_pnm(write("bad.pgm", bytes));
      FAIL() << "accepted a file that should fail with '" << needle << "'";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "one line: " << e.what();
    }
  }
  EXPECT_THROW(read_pfm(write("t.pfm", pfm_bytes("Pf", 2, 2, -1.0f, {1, 2, 3}))), InputError);
  EXPECT_THROW(read_pfm(write("n.pfm", pfm_bytes("Pf", 1, 1, -1.0f, {-1.0f}))), InputError);
  EXPECT_THROW(read_pfm(write("nan.pfm", pfm_bytes("Pf", 1, 1, -1.0f, {std::nanf("")}))), InputError);
  EXPECT_THROW(read_pfm(write("s.pfm", "Pf\n1 1\n0\nxxxx")), InputError);
  EXPECT_THROW(read_image((dir_ / "missing.pgm").string()), InputError);
  EXPECT_THROW(read_image(write("x.png", "x")), InputError);
  // Formats aesim does not decode name the conversion that gives one it does.
  for (const auto& [name, words] : {std::pair<const char*, const char*>{"clip.MP4", "ffmpeg -i"},
                                    {"clip.mov", "convert the video to Y4M"},
                                    {"frames.gif", "convert the image to PNG or TIFF"},
                                    {"scan.bmp", "convert the image to PNG or TIFF"}}) {
    try {
      read_image(write(name, "x"));
      ADD_FAILURE() << name;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("unsupported format"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  }
}

TEST(Resample, IntegerUpsamplingReplicatesDownsamplingAverages) {
  Image in;
  in.width = 2;
  in.height = 1;
  in.pixels = {0.2, 0.8};
  const Image up = resample_area(in, 4, 2);
  EXPECT_DOUBLE_EQ(up.at(0, 0), 0.2);
  EXPECT_DOUBLE_EQ(up.at(1, 1), 0.2);
  EXPECT_DOUBLE_EQ(up.at(2, 0), 0.8);
  const Image down = resample_area(in, 1, 1);
  EXPECT_DOUBLE_EQ(down.at(0, 0), 0.5);
}

TEST(Resample, NonIntegerRatiosWeightPartialOverlapsAndKeepTheMean) {
  Image in;
  in.width = 3;
  in.height = 1;
  in.pixels = {0.0, 0.3, 0.9};
  const Image out = resample_area(in, 2, 1);
  // Output 0 covers source [0, 1.5): (0 * 1 + 0.3 * 0.5) / 1.5; output 1 covers [1.5, 3).
  EXPECT_NEAR(out.at(0, 0), 0.1, 1e-12);
  EXPECT_NEAR(out.at(1, 0), (0.3 * 0.5 + 0.9) / 1.5, 1e-12);
  EXPECT_NEAR((out.at(0, 0) + out.at(1, 0)) / 2, 0.4, 1e-12);
}

TEST_F(SceneFilesTest, FrameFolderOrdersByNumberAndReadsSceneToml) {
  const std::string frame = std::string("P5\n1 1\n255\n");
  write("f_10.pgm", frame + char(10));
  write("f_9.pgm", frame + char(9));
  write("f_100.pgm", frame + char(100));
  write("scene.toml", "frame_rate = \"4Hz\"\nloop = true\n");
  const SceneFiles files = find_scene(dir_.string());
  ASSERT_EQ(files.frames.size(), 3u);
  EXPECT_NE(files.frames[0].find("f_9"), std::string::npos);
  EXPECT_NE(files.frames[2].find("f_100"), std::string::npos);
  SensorConfig c;
  c.array.rows = c.array.cols = 1;
  c.array.tile_rows = c.array.tile_cols = 1;
  apply_scene_settings(files, c);
  EXPECT_DOUBLE_EQ(c.scene.frame_rate, 4.0);
  EXPECT_TRUE(c.scene.loop);
  const Scene s = load_scene(files, c.array, c.scene);
  EXPECT_DOUBLE_EQ(s.frame_period, 0.25);
  EXPECT_DOUBLE_EQ(s.frames[1].at(0, 0), 10 / 255.0);
}

TEST_F(SceneFilesTest, FramesOfDifferentSizesAreRejected) {
  write("f_1.pgm", std::string("P5\n1 1\n255\n") + char(1));
  write("f_2.pgm", std::string("P5\n2 1\n255\n") + char(1) + char(2));
  SensorConfig c;
  EXPECT_THROW(load_scene(find_scene(dir_.string()), c.array, c.scene), InputError);
}

}  // namespace
}  // namespace aesim
