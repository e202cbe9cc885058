#pragma once
#include <string>

#include "aesim/event_files/aedat4.hpp"

namespace aesim {

// A ROS 2 bag as rosbag2 records it: a folder holding metadata.yaml and the bag's storage files,
// `<name>_<n>.mcap` or `.db3` (a new one each time a recording splits). Every storage file is read
// in the order of its split number, all into one recording, as one bag. Throws InputError for a
// folder that holds no storage file, or holds files rosbag2 compressed whole (`.zstd`).
PolarityRecording read_ros2_bag_folder(const std::string& path);

}  // namespace aesim
