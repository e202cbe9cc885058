#include "aesim/scene/scene.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/limits/limits.hpp"
#include "aesim/files/data_dir.hpp"
#include "aesim/files/input_path.hpp"
#include "aesim/scene/netpbm.hpp"
#include "aesim/scene/npy_scene.hpp"
#include "aesim/scene/resample.hpp"
#include "aesim/scene/scene_file.hpp"
#include "aesim/scene/tiff_image.hpp"
#include "aesim/scene/y4m_video.hpp"

namespace aesim {
namespace fs = std::filesystem;
namespace {

// The last run of digits in a file name orders the frames ("frame_9" before "frame_10").
long long frame_number(const std::string& stem) {
  auto end = stem.find_last_of("0123456789");
  if (end == std::string::npos) return -1;
  auto begin = end;
  while (begin > 0 && std::isdigit(static_cast<unsigned char>(stem[begin - 1]))) --begin;
  // Up to 15 digits (a frame's number, not a date and time stamp run together): more is refused.
  if (end - begin + 1 > 15) return -2;
  return std::stoll(stem.substr(begin, end - begin + 1));
}


// A scene's frames however they are stored: image files, a Y4M video's frames, a 3-D NumPy
// array's or a multi-page TIFF's. A file of many frames is held whole while its frames are taken
// from it.
class SceneFrames {
 public:
  explicit SceneFrames(const SceneFiles& files) : files_(files) {
    if (files.video) video_ = open_y4m(files.frames.front());
    if (files.npy_stack) stack_ = open_npy_scene(files.frames.front());
    if (!files.tiff_pages.empty()) tiff_ = read_scene_file(files.frames.front());
  }
  std::size_t count() const {
    if (files_.video) return video_.layout.luma.size();
    if (files_.npy_stack) return stack_.layout.frames;
    return files_.tiff_pages.empty() ? files_.frames.size() : files_.tiff_pages.size();
  }
  Image frame(std::size_t k) const {
    if (files_.video) return y4m_light(video_.data, video_.layout, k);
    if (files_.npy_stack) return npy_scene_frame(stack_, k, files_.frames.front());
    if (!files_.tiff_pages.empty()) return decode_tiff(tiff_, files_.frames.front(), files_.tiff_pages[k]);
    return read_image(files_.frames[k]);
  }
  // Frame k's name in a message.
  std::string name(std::size_t k) const {
    return files_.video || files_.npy_stack || !files_.tiff_pages.empty() ? fmt::format("{} frame {}", files_.frames.front(), k)
                                                                          : files_.frames[k];
  }

 private:
  const SceneFiles& files_;
  Y4mFile video_;
  NpySceneFile stack_;
  std::string tiff_;
};

}  // namespace

std::string default_scene_path() { return data_dir() + "/" + kDefaultScene; }

SceneFiles find_scene(const std::string& given) {
  const std::string file_or_dir = shipped_if_missing(given);
  SceneFiles files;
  files.source = file_or_dir;
  if (is_input_file(file_or_dir, "scene")) {
    files.frames.push_back(file_or_dir);
    if (file_extension(file_or_dir) == ".y4m") {
      files.video = true;
      files.video_frame_rate = read_y4m_header(file_or_dir).frame_rate;
    }
    if (file_extension(file_or_dir) == ".npy") files.npy_stack = read_npy_scene_header(file_or_dir).header.shape.size() == 3;
    if (file_extension(file_or_dir) == ".tif" || file_extension(file_or_dir) == ".tiff") {
      files.tiff_pages = tiff_file_pages(file_or_dir);
      if (files.tiff_pages.size() == 1) files.tiff_pages.clear();
    }
    return files;
  }
  if (!is_input_folder(file_or_dir, "scene")) {
    throw InputError(fmt::format("scene '{}': {}", file_or_dir, not_a_file(file_or_dir)));
  }
  std::vector<std::pair<long long, std::string>> numbered;
  std::error_code ec;
  fs::directory_iterator it(file_or_dir, ec);
  if (ec) throw InputError(fmt::format("scene folder '{}': {}", file_or_dir, ec.message()));
  for (; it != fs::directory_iterator(); it.increment(ec)) {
    if (ec) throw InputError(fmt::format("scene folder '{}': {}", file_or_dir, ec.message()));
    const fs::directory_entry& entry = *it;
    const fs::path& p = entry.path();
    std::error_code kind;
    if (!entry.is_regular_file(kind)) {
      // A frame that is a broken link, a FIFO or a device is named, not skipped.
      if (is_scene_image(p.string()) || p.filename() == "scene.toml") {
        throw InputError(fmt::format("scene folder '{}': '{}' {}", file_or_dir, p.filename().string(), not_a_file(p.string())));
      }
      continue;
    }
    if (p.filename() == "scene.toml") files.settings = p.string();
    if (!is_scene_image(p.string())) continue;
    if (numbered.size() == kMaxSceneFrames) {
      throw InputError(fmt::format("scene folder '{}': more than {} frames, the most aesim reads", file_or_dir, kMaxSceneFrames));
    }
    const long long n = frame_number(p.stem().string());
    if (n == -2) {
      throw InputError(fmt::format("scene folder '{}': frame '{}' has a number of over 15 digits", file_or_dir, p.filename().string()));
    }
    if (n < 0) throw InputError(fmt::format("scene folder '{}': frame '{}' has no number", file_or_dir, p.filename().string()));
    numbered.emplace_back(n, p.string());
  }
  if (numbered.empty()) {
    throw InputError(fmt::format("scene folder '{}' has no numbered {} frames", file_or_dir, scene_image_formats()));
  }
  std::sort(numbered.begin(), numbered.end());
  for (std::size_t i = 1; i < numbered.size(); ++i) {
    if (numbered[i].first == numbered[i - 1].first) {
      throw InputError(fmt::format("scene folder '{}': frames '{}' and '{}' share number {}", file_or_dir,
                                   numbered[i - 1].second, numbered[i].second, numbered[i].first));
    }
  }
  for (auto& entry : numbered) files.frames.push_back(std::move(entry.second));
  return files;
}

void apply_scene_settings(const SceneFiles& files, SensorConfig& config) {
  if (files.video) config.scene.frame_rate = files.video_frame_rate;
  if (files.settings.empty()) return;
  apply_toml_file(config, files.settings, "scene");
}

Setting parse_setting(const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw InputError(fmt::format("--set '{}': expected section.key=value", assignment));
  }
  return {assignment.substr(0, eq), assignment.substr(eq + 1)};
}

ResolvedConfig configure_run(SensorConfig sensor, const SceneFiles& scene, const std::vector<Setting>& settings) {
  apply_scene_settings(scene, sensor);
  for (const auto& [key, value] : settings) sensor.set(key, value);
  return sensor.resolved();
}

std::vector<Image> read_frames(const SceneFiles& files) {
  const SceneFrames source(files);
  std::vector<Image> frames;
  for (std::size_t k = 0; k < source.count(); ++k) {
    Image img = source.frame(k);
    if (!frames.empty() && (img.width != frames.front().width || img.height != frames.front().height)) {
      throw InputError(fmt::format("scene frame '{}' is {}x{}, the first frame is {}x{}", source.name(k), img.width,
                                   img.height, frames.front().width, frames.front().height));
    }
    frames.push_back(std::move(img));
  }
  return frames;
}

Scene load_scene(const SceneFiles& files, const ArrayParams& array, const SceneParams& shown, double duration) {
  const SceneFrames source(files);
  // The frames a run of `duration` shows: without a wrap of the loop, only the first ones.
  std::size_t needed = source.count();
  if (needed > 1 && std::isfinite(duration)) {
    const double started = std::ceil(duration * shown.frame_rate) + 1;
    if (started < static_cast<double>(needed)) needed = static_cast<std::size_t>(started);
  }
  const double bytes = static_cast<double>(needed) * static_cast<double>(array.rows) * array.cols * 16.0;
  if (bytes > kMaxSceneBytes) {
    throw InputError(fmt::format("scene '{}': {} frames at {}x{} would take {:.3g} GB (at most {:.3g} GB): use fewer "
                                 "frames, a smaller array or a shorter sim.duration",
                                 files.source, needed, array.cols, array.rows, bytes / 1e9, kMaxSceneBytes / 1e9));
  }
  // One frame in memory at a time before it is resampled to the array.
  Scene scene;
  scene.frame_period = 1.0 / shown.frame_rate;
  scene.loop = shown.loop;
  for (std::size_t f = 0; f < needed; ++f) {
    const Image img = source.frame(f);
    if (f > 0 && (img.width != scene.source_width || img.height != scene.source_height)) {
      throw InputError(fmt::format("scene frame '{}' is {}x{}, the first frame is {}x{}", source.name(f), img.width,
                                   img.height, scene.source_width, scene.source_height));
    }
    scene.source_width = img.width;
    scene.source_height = img.height;
    scene.frames.push_back(resample_area(img, array.cols, array.rows));
  }
  return scene;
}

Scene load_scene(const std::vector<Image>& frames, const ArrayParams& array, const SceneParams& shown) {
  Scene scene;
  scene.frame_period = 1.0 / shown.frame_rate;
  scene.loop = shown.loop;
  for (const Image& img : frames) {
    scene.source_width = img.width;
    scene.source_height = img.height;
    scene.frames.push_back(resample_area(img, array.cols, array.rows));
  }
  return scene;
}

std::vector<double> frame_exposures(std::size_t frames, double period, bool loop, double duration) {
  std::vector<double> shown(frames, 0.0);
  if (frames == 1) {
    shown[0] = duration;
    return shown;
  }
  // Frame k starts at k * period; `started` counts the k with k * period < duration.
  double estimate = std::ceil(duration / period);
  while (estimate > 0 && (estimate - 1) * period >= duration) estimate -= 1;
  while (estimate * period < duration) estimate += 1;
  const auto started = static_cast<std::uint64_t>(estimate);
  const std::uint64_t full = started - 1;  // every started frame but the last lasts a whole period
  const std::uint64_t n = frames;
  if (loop) {
    for (std::uint64_t f = 0; f < n; ++f) {
      shown[f] = static_cast<double>(full / n + (f < full % n ? 1 : 0)) * period;
    }
  } else {
    for (std::uint64_t f = 0; f + 1 < n && f < full; ++f) shown[f] = period;
    if (full > n - 1) shown[n - 1] = static_cast<double>(full - (n - 1)) * period;
  }
  shown[frame_index(full, frames, loop)] += duration - static_cast<double>(full) * period;
  return shown;
}

Image mean_frame(const Scene& scene, double duration) {
  Image mean = scene.frames.front();
  if (scene.frames.size() == 1) return mean;
  std::fill(mean.pixels.begin(), mean.pixels.end(), 0.0);
  const std::vector<double> shown = frame_exposures(scene.frames.size(), scene.frame_period, scene.loop, duration);
  for (std::size_t f = 0; f < shown.size(); ++f) {
    const double weight = shown[f] / duration;
    if (weight == 0) continue;
    for (std::size_t i = 0; i < mean.pixels.size(); ++i) mean.pixels[i] += weight * scene.frames[f].pixels[i];
  }
  return mean;
}

}  // namespace aesim
