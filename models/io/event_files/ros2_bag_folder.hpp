#pragma once
#include <string>

#include "aesim/event_files/aedat4.hpp"
#include "aesim/event_files/ros_event_messages.hpp"

namespace aesim {

// A ROS 2 bag as rosbag2 records it: a folder holding metadata.yaml and the bag's storage files,
// `<name>_<n>.mcap` or `.db3` (a new one each time a recording splits; `.mcap.zstd` or `.db3.zstd`
// where rosbag2 compressed each file whole). Every storage file is read in the order of its split
// number, all into one recording, as one bag. Throws InputError for a folder that holds no
// storage file.
PolarityRecording read_ros2_bag_folder(const std::string& path);
// One storage file (compressed whole or not) read into `topics`.
void read_ros2_bag_file(const std::string& path, RosEventTopics& topics);
// Whether `path` names a storage file rosbag2 compressed whole (`.mcap.zstd`, `.db3.zstd`).
bool is_compressed_ros2_bag_file(const std::string& path);
// One such file alone, as a bag.
PolarityRecording read_compressed_ros2_bag_file(const std::string& path);

}  // namespace aesim
