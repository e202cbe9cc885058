#pragma once
#include <string>

#include "aesim/event_files/aedat4.hpp"

namespace aesim {

// The events of a ROS 1 bag (`.bag`, format 2.0 as the ROS wiki's Bags/Format/2.0 defines it: the
// Event Camera Dataset's, MVSEC's and every DAVIS or Prophesee camera recorded under ROS): its
// records read in file order, chunks uncompressed (none, bz2 or lz4, as rosbag writes them), and
// the messages of the topic whose layout is dvs_msgs/EventArray (the md5sum
// 5e8beee5a6c107e504c2e78903c224b8, which prophesee_event_msgs/EventArray shares) decoded: each
// event's x and y (uint16), its stamp (ROS time: seconds and nanoseconds, kept as whole
// microseconds since the epoch, as the bag holds them) and its polarity. The array is the
// messages' width and height. With several event topics (a stereo rig's left and right cameras)
// the first by name is read and the others counted in `notes`, as are the other topics' messages
// (frames, IMU). Throws InputError naming `label` for anything malformed, a version other than
// 2.0, an encrypted bag, or a bag with no event topic (naming the topics it has).
PolarityRecording decode_ros_bag(const std::string& data, const std::string& label);

}  // namespace aesim
