#include "aesim/event_files/ros2_bag_folder.hpp"

#include <algorithm>
#include <filesystem>
#include <tuple>
#include <vector>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/event_files/event_file.hpp"
#include "aesim/event_files/mcap_bag.hpp"
#include "aesim/event_files/ros_event_messages.hpp"
#include "aesim/event_files/rosbag2_sqlite.hpp"

namespace aesim {
namespace {

namespace fs = std::filesystem;

// A storage file's place in the recording: rosbag2 names the n-th `<name>_<n>`, so that
// bag_10 comes after bag_9, where names alone would put it after bag_1.
std::tuple<std::string, unsigned long long, std::string> split_order(const fs::path& file) {
  const std::string stem = file.stem().string();
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
  std::vector<std::string> compressed;
  std::error_code error;
  for (fs::directory_iterator it(path, error), end; !error && it != end; it.increment(error)) {
    if (!it->is_regular_file(error)) continue;
    const fs::path& p = it->path();
    const std::string ext = p.extension().string();
    if (ext == ".mcap" || ext == ".db3") files.push_back(p);
    if (ext == ".zstd") compressed.push_back(p.filename().string());
  }
  if (error) throw InputError(fmt::format("event file '{}': cannot list the folder: {}", path, error.message()));
  if (!compressed.empty()) {
    throw InputError(fmt::format("event file '{}': a ROS 2 bag whose files rosbag2 compressed whole ({}): "
                                 "uncompress them first (`ros2 bag decompress` or `zstd -d`)",
                                 path, compressed.front()));
  }
  if (files.empty()) {
    throw InputError(fmt::format("event file '{}': a folder holding no .mcap or .db3 file (a ROS 2 bag's folder holds one "
                                 "or more)", path));
  }
  std::sort(files.begin(), files.end(), [](const fs::path& a, const fs::path& b) { return split_order(a) < split_order(b); });
  RosEventTopics topics(path);
  for (const fs::path& file : files) {
    const std::string name = file.string();
    const std::string data = read_event_file_bytes(name);
    if (file.extension() == ".mcap") {
      read_mcap_topics(data, name, topics);
    } else {
      read_rosbag2_sqlite_topics(data, name, topics);
    }
  }
  return topics.result();
}

}  // namespace aesim
