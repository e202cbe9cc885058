// Y4M videos: the emulator's luma codes and frame rate; as scenes, luma decoded to light from
// video levels (or full range) with BT.709's transfer function inverted, against values worked
// out by hand from ITU-R BT.709-6; `aesim run` on a video shows its frames at the header's rate
// (or scene.frame_rate's), each pixel firing as eq. 2 says under each frame's light; malformed
// videos are one-line errors.
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "aesim/errors/input_error.hpp"
#include "aesim/scene/scene.hpp"
#include "aesim/scene/y4m_video.hpp"
#include "support/temp_dir_test.hpp"

namespace aesim {
namespace {

class Y4mTest : public testing::TempDirTest {};

TEST_F(Y4mTest, LumaOfEveryFrameAndTheFrameRate) {
  std::string v = "YUV4MPEG2 W4 H2 F30000:1001 Ip A1:1 C420jpeg\n";
  for (int f = 0; f < 3; ++f) {
    v += "FRAME\n";
    for (int i = 0; i < 8; ++i) v += static_cast<char>(f * 100 + i);
    v += std::string(2 * 2 * 1, '\x80');  // U and V, 2x1 each
  }
  const Y4mVideo video = read_y4m(write("v.y4m", v));
  ASSERT_EQ(video.frames.size(), 3u);
  EXPECT_NEAR(video.frame_rate, 29.97, 0.01);
  EXPECT_EQ(video.frames[2].width, 4);
  EXPECT_DOUBLE_EQ(video.frames[2].at(3, 1), 207 / 255.0);
}

TEST_F(Y4mTest, MalformedVideosAreInputErrors) {
  const std::pair<std::string, std::string> cases[] = {
      {"not a YUV4MPEG2", "P5\n1 1\n255\n\x01"},
      {"bad frame size", "YUV4MPEG2 W0 H2\nFRAME\n"},
      {"truncated", "YUV4MPEG2 W4 H2 Cmono\nFRAME\nabc"},
      {"missing FRAME", "YUV4MPEG2 W1 H1 Cmono\nFRAMX\nz"},
      {"unsupported colour space C420p20 (aesim reads 420, 422, 444 and mono, 8-bit or 9 to 16 bits", "YUV4MPEG2 W1 H1 C420p20\nFRAME\n"},
      {"unsupported colour space C420p (", "YUV4MPEG2 W1 H1 C420p\nFRAME\n"},
      {"unsupported colour space Cmono8 (", "YUV4MPEG2 W1 H1 Cmono8\nFRAME\n"},
      {"unsupported colour space C411 (", "YUV4MPEG2 W1 H1 C411\nFRAME\n"},
      {"frame 0: truncated", "YUV4MPEG2 W2 H1 Cmono10\nFRAME\nabc"},  // 2 samples of 2 bytes
      {"malformed header", "YUV4MPEG2 Wx H1\n"},
      {"no frames", "YUV4MPEG2 W1 H1 Cmono\n"},
  };
  for (const auto& [needle, bytes] : cases) {
    try {
      read_y4m(write("bad.y4m", bytes));
      FAIL() << needle;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
    // The same as a scene: a one-line error, exit status 2, nothing written.
    expect_scene_refused("bad.y4m", needle);
  }
}

// A mono video of uniform frames, one code each.
std::string uniform_video(int width, int height, const std::string& rate, const std::vector<int>& codes,
                          const std::string& extra = "") {
  std::string v = "YUV4MPEG2 W" + std::to_string(width) + " H" + std::to_string(height) + " F" + rate + " Ip A1:1 Cmono" +
                  extra + "\n";
  for (const int c : codes) v += "FRAME\n" + std::string(static_cast<std::size_t>(width * height), static_cast<char>(c));
  return v;
}

TEST_F(Y4mTest, LumaLevelsAreLightThroughBt709sTransferFunctionInverted) {
  // By hand: level = (code - 16) / 219 (video levels), or code / 255 (XCOLORRANGE=FULL);
  // light = level / 4.5 below a level of 0.081, ((level + 0.099) / 1.099)^(1 / 0.45) above.
  const struct {
    std::string extra;
    int code;
    double light;
  } cases[] = {
      {"", 0, 0.0},  // below black: black
      {"", 16, 0.0},
      {"", 20, 0.004058853373921867},  // the linear segment
      {"", 126, 0.26179326153360133},
      {"", 200, 0.7052426932157294},
      {"", 235, 1.0},
      {"", 255, 1.0},  // above white: white
      {" XCOLORRANGE=LIMITED", 126, 0.26179326153360133},
      {" XCOLORRANGE=FULL", 0, 0.0},
      {" XCOLORRANGE=FULL", 128, 0.26148150693314937},
      {" XCOLORRANGE=FULL", 255, 1.0},
  };
  for (const auto& c : cases) {
    const std::string data = uniform_video(2, 2, "25:1", {c.code}, c.extra);
    const Y4mLayout layout = parse_y4m(data, "v.y4m");
    EXPECT_NEAR(y4m_light(data, layout, 0).pixels[3], c.light, 1e-12) << c.code << c.extra;
    // The emulator's grey levels stay the codes.
    EXPECT_DOUBLE_EQ(y4m_luma_codes(data, layout, 0).pixels[3], c.code / 255.0);
  }
}

// 9- to 16-bit video as ffmpeg writes it (C420p10, Cmono16, ...: two bytes a sample, little-endian;
// the chroma planes' bytes doubled too). By hand: video levels scale with the depth, black 16 x
// 2^(bits - 8) and white 235 x 2^(bits - 8) (BT.2020's 64 and 940 at 10 bits); full range 0 to
// 2^bits - 1; then BT.709's transfer function inverted, as at 8 bits.
TEST_F(Y4mTest, DeepVideoIsReadAtItsOwnDepth) {
  const auto little_endian = [](const std::vector<int>& codes) {
    std::string out;
    for (const int c : codes) out += std::string{static_cast<char>(c & 0xFF), static_cast<char>(c >> 8)};
    return out;
  };
  const struct {
    std::string header;
    std::vector<int> codes;
    std::size_t chroma_bytes;
    std::vector<double> light;
    double most;
  } cases[] = {
      // 10-bit video levels: below black, black, (502 - 64) / 876 = 0.5, white, above white.
      {"W5 H1 C444p10", {0, 64, 502, 940, 1023}, 2 * 5 * 2, {0, 0, 0.25958940050628576, 1, 1}, 1023},
      // The same level at 12 bits ((2008 - 256) / 3504 = 0.5), chroma planes of 3x1.
      {"W5 H1 C420p12", {256, 2008, 3760, 4095, 0}, 2 * 3 * 2, {0, 0.25958940050628576, 1, 1, 0}, 4095},
      // 16-bit grey, full range: 32768 / 65535 is a level of 0.5000076.
      {"W3 H1 Cmono16 XCOLORRANGE=FULL", {0, 32768, 65535}, 0, {0, 0.2595967481434192, 1}, 65535},
  };
  for (const auto& c : cases) {
    std::string v = "YUV4MPEG2 " + c.header + " F25:1\n";
    for (int f = 0; f < 2; ++f) v += "FRAME\n" + little_endian(c.codes) + std::string(c.chroma_bytes, '\x02');
    const Y4mLayout layout = parse_y4m(v, "deep.y4m");
    ASSERT_EQ(layout.luma.size(), 2u) << c.header;
    for (std::size_t i = 0; i < c.codes.size(); ++i) {
      EXPECT_NEAR(y4m_light(v, layout, 1).pixels[i], c.light[i], 1e-12) << c.header << " code " << c.codes[i];
      EXPECT_DOUBLE_EQ(y4m_luma_codes(v, layout, 1).pixels[i], c.codes[i] / c.most) << c.header;
    }
    // A frame short of one sample's second byte is truncated.
    EXPECT_THROW(parse_y4m(v.substr(0, v.size() - 1), "cut.y4m"), InputError) << c.header;
  }
}

struct Pixel {
  double c_int, dv_int, i_max, i_dark, t_reset;
  // Eq. 2 with the reset: firings a second under light `v` (a fraction of full scale).
  double rate(double v) const { return 1 / (c_int * dv_int / (i_dark + i_max * v) + t_reset); }
};

// Events of a run's CSV (t_us,x,y,tile,flags) in [from, to) seconds.
std::size_t events_between(const std::string& csv, double from, double to) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  std::size_t n = 0;
  while (std::getline(in, line)) {
    const double t = std::stod(line.substr(0, line.find(','))) * 1e-6;
    n += t >= from && t < to ? 1 : 0;
  }
  return n;
}

TEST_F(Y4mTest, AVideoIsAMovingSceneAtItsOwnFrameRate) {
  // Three uniform frames at 20 Hz (white, a quarter of its light, white again), on a 32x32 array
  // without mismatch on an ideal bus (no collisions), run past the last frame (held). Each pixel fires at eq. 2's rate under each
  // frame's light, so a frame of 50 ms holds 50 ms x rate firings a pixel, give or take the one
  // its charge carries over a boundary.
  write("v.y4m", uniform_video(32, 32, "20:1", {235, 126, 235}));
  const SceneFiles files = find_scene((dir_ / "v.y4m").string());
  EXPECT_TRUE(files.video);
  EXPECT_DOUBLE_EQ(files.video_frame_rate, 20.0);
  const std::string common = "--set array.rows=32 --set array.cols=32 --set pixel.mismatch=0 --set pixel.i_max=200pA "
                             "--set sim.fidelity=event --set bus.access=ideal --duration 200ms --csv e.csv --summary s.json";
  ASSERT_EQ(aesim("run --scene v.y4m " + common).status, 0);
  const nlohmann::json summary = nlohmann::json::parse(testing::slurp(dir_ / "s.json"));
  const nlohmann::json& p = summary["sensor"]["pixel"];
  EXPECT_DOUBLE_EQ(summary["sensor"]["scene"]["frame_rate"].get<double>(), 20.0);
  const Pixel pixel{p["c_int"].get<double>(), p["dv_int"].get<double>(), p["i_max"].get<double>(),
                    p["i_dark"].get<double>(), p["t_reset"].get<double>()};
  const std::string csv = testing::slurp(dir_ / "e.csv");
  const double quarter = 0.26179326153360133;  // code 126, by hand above
  const struct {
    double from, to, light;
  } frames[] = {{0.0, 0.05, 1.0}, {0.05, 0.10, quarter}, {0.10, 0.15, 1.0}, {0.15, 0.20, 1.0}};
  for (const auto& f : frames) {
    const double expected = 1024 * (f.to - f.from) * pixel.rate(f.light);
    ASSERT_GT(expected, 1024 * 20.0);  // enough firings a pixel that one more or less is 5 %
    EXPECT_NEAR(static_cast<double>(events_between(csv, f.from, f.to)), expected, 1024.0) << f.from;
  }
  // scene.frame_rate given on the command line wins over the header: at 10 Hz the dim frame
  // runs from 100 to 200 ms.
  ASSERT_EQ(aesim("run --scene v.y4m " + common + " --set scene.frame_rate=10").status, 0);
  const std::string slow = testing::slurp(dir_ / "e.csv");
  EXPECT_NEAR(static_cast<double>(events_between(slow, 0.10, 0.20)), 1024 * 0.1 * pixel.rate(quarter), 1024.0);
}

}  // namespace
}  // namespace aesim
