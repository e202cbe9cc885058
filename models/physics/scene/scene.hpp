#pragma once
#include <limits>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "aesim/config/sensor_config.hpp"
#include "aesim/scene/image.hpp"

namespace aesim {

// Where a scene comes from: one image file, a folder of numbered frames with an optional
// scene.toml (frame_rate, loop) that sets the scene.* keys before the command line does, a Y4M
// video (a .y4m file: its frames, at the frame rate its header gives scene.frame_rate), a 3-D
// NumPy array (a .npy file of frames, rows, columns: its frames, at scene.frame_rate), or a
// multi-page TIFF (its full-resolution pages, at scene.frame_rate).
struct SceneFiles {
  std::string source;
  std::vector<std::string> frames;  // in frame order; a video's or a 3-D array's one file
  std::string settings;             // scene.toml, or empty
  bool video = false;
  double video_frame_rate = 0;  // Hz, from a video's header
  bool npy_stack = false;       // a 3-D .npy array
  std::vector<std::size_t> tiff_pages;  // a multi-page TIFF's frames (tiff_pages), when it has more than one
};

SceneFiles find_scene(const std::string& file_or_dir);
// The scene a command uses when given none, relative to the data folder, and its full path.
inline constexpr char kDefaultScene[] = "scenes/letters/A.pgm";
std::string default_scene_path();
// Applies the folder's scene.toml to config.scene (command-line --set applies after this).
void apply_scene_settings(const SceneFiles& files, SensorConfig& config);

// A setting "section.key" = "value" as text with units, applied in order (later wins).
using Setting = std::pair<std::string, std::string>;
// "section.key=value" (--set) as a Setting; InputError naming the text when it is not one.
Setting parse_setting(const std::string& assignment);

// The configuration of a run, made the one way every command makes it: the sensor, then the
// scene's own settings (scene.toml), then `settings` in order; validated and resolved.
ResolvedConfig configure_run(SensorConfig sensor, const SceneFiles& scene, const std::vector<Setting>& settings);

// A scene at the array's resolution: frames shown one after the other, each for frame_period.
struct Scene {
  std::vector<Image> frames;
  double frame_period = 0;  // s; irrelevant for a single frame
  bool loop = false;
  int source_width = 0, source_height = 0;
};

// The frames as stored (values of full scale), all of one size; throws InputError otherwise.
std::vector<Image> read_frames(const SceneFiles& files);

// The scene at the array's resolution (array.cols x array.rows, area resampling), shown as `shown` says.
// Reads the frames one at a time, resampled to the array as they come; only those a run of
// `duration` shows (the first ceil(duration x frame_rate) + 1, when the loop does not wrap), after
// checking that they fit kMaxSceneBytes.
Scene load_scene(const SceneFiles& files, const ArrayParams& array, const SceneParams& shown,
                 double duration = std::numeric_limits<double>::infinity());
// The same from frames in memory (all of one size; the Python module's arrays).
Scene load_scene(const std::vector<Image>& frames, const ArrayParams& array, const SceneParams& shown);

// The frame shown from boundary k on (frame k starts at k * period): sequences loop, or hold
// their last frame.
inline std::size_t frame_index(std::uint64_t boundary, std::size_t frames, bool loop) {
  if (loop) return static_cast<std::size_t>(boundary % frames);
  return boundary < frames ? static_cast<std::size_t>(boundary) : frames - 1;
}

// How long each of `frames` frames is shown within [0, duration] when a new frame starts every
// `period` (sequences loop or hold their last frame). O(frames), however many boundaries pass.
std::vector<double> frame_exposures(std::size_t frames, double period, bool loop, double duration);

// The light each pixel saw, averaged over [0, duration], as a fraction of full scale.
Image mean_frame(const Scene& scene, double duration);

}  // namespace aesim
