#include "aesim/event_files/ros2_bag_folder.hpp"

#include <algorithm>
#include <filesystem>
#include <tuple>
#include <vector>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/files/input_path.hpp"
#include "aesim/limits/limits.hpp"
#include "aesim/event_files/compressed_block.hpp"
#include "aesim/event_files/event_file.hpp"
#include "aesim/event_files/mcap_bag.hpp"
#include "aesim/event_files/ros_event_messages.hpp"
#include "aesim/event_files/rosbag2_sqlite.hpp"

namespace aesim {
namespace {

namespace fs = std::filesystem;

// ".mcap" or ".db3" for a ROS 2 bag's storage file, compressed whole by rosbag2 (".mcap.zstd") or
// not; "" for any other file.
std::string storage_extension(const fs::path& file) {
  const fs::path inner = file.extension() == ".zstd" ? file.stem() : file;
  const std::string ext = inner.extension().string();
  return ext == ".mcap" || ext == ".db3" ? ext : "";
}

// A storage file's place in the recording: rosbag2 names the n-th `<name>_<n>`, so that
// bag_10 comes after bag_9, where names alone would put it after bag_1.
std::tuple<std::string, unsigned long long, std::string> split_order(const fs::path& file) {
  const std::string stem = (file.extension() == ".zstd" ? file.stem() : file).stem().string();
  const std::size_t underscore = stem.rfind('_');
  const std::string number = underscore == std::string::npos ? "" : stem.substr(underscore + 1);
  if (number.empty() || number.size() > 18 || number.find_first_not_of("0123456789") != std::string::npos) {
    return {stem, 0, file.filename().string()};
  }
  return {stem.substr(0, underscore), std::stoull(number), file.filename().string()};
}

}  // namespace

PolarityRecording read_ros2_bag_folder(const std::string& path) {
  std::vector<fs::path> files;
  std::error_code error;
  for (fs::directory_iterator it(path, error), end; !error && it != end; it.increment(error)) {
    if (!it->is_regular_file(error)) continue;
    if (!storage_extension(it->path()).empty()) files.push_back(it->path());
  }
  if (error) throw InputError(fmt::format("event file '{}': cannot list the folder: {}", path, error.message()));
  if (files.empty()) {
    throw InputError(fmt::format("event file '{}': a folder holding no .mcap or .db3 file (a ROS 2 bag's folder holds one "
                                 "or more) and no dataset_events_t.npy (an EVIMO2 sequence's)", path));
  }
  std::sort(files.begin(), files.end(), [](const fs::path& a, const fs::path& b) { return split_order(a) < split_order(b); });
  RosEventTopics topics(path);
  for (const fs::path& file : files) read_ros2_bag_file(file.string(), topics);
  return topics.result();
}

bool is_compressed_ros2_bag_file(const std::string& path) {
  return file_extension(path) == ".zstd" && !storage_extension(path).empty();
}

PolarityRecording read_compressed_ros2_bag_file(const std::string& path) {
  RosEventTopics topics(path);
  read_ros2_bag_file(path, topics);
  return topics.result();
}

void read_ros2_bag_file(const std::string& path, RosEventTopics& topics) {
  const std::string extension = storage_extension(path);
  std::string data = read_event_file_bytes(path);
  // rosbag2's file compression: the whole file one zstd frame, named <file>.zstd.
  if (file_extension(path) == ".zstd") {
    try {
      data = uncompressed_zstd(data, kMaxEventFileBytes, "file");
    } catch (const BlockError& e) {
      throw InputError(fmt::format("event file '{}': {}", path, e.what()));
    }
  }
  if (extension == ".mcap") {
    read_mcap_topics(data, path, topics);
  } else {
    read_rosbag2_sqlite_topics(data, path, topics);
  }
}

}  // namespace aesim
