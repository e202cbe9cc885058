#pragma once
#include <string>

#include "aesim/event_files/aedat4.hpp"
#include "aesim/event_files/ros_event_messages.hpp"

namespace aesim {

// The events of an MCAP file (`.mcap`, major version 0, as mcap.dev's specification defines it):
// ROS 2's bags since Iron (rosbag2's default storage) and Foxglove's recordings. Its records are
// read in file order, chunks plain or compressed (lz4 frames or zstd) and checked against their
// CRC32 where the writer gave one; the channels' messages in CDR (ROS 2) or ROS 1's layout are
// decoded where their schema is of dvs_msgs/EventArray's or event_camera_msgs/EventPacket's layout
// (ros_event_messages.hpp), as a ROS bag's are. Throws InputError naming `label` for anything
// malformed, a file cut short (a recording that did not end: `mcap recover` rewrites what it
// holds), or a file without an event topic (naming the topics it has).
PolarityRecording decode_mcap(const std::string& data, const std::string& label);
// The same into `topics`, which a ROS 2 bag split into several files reads each into in turn.
void read_mcap_topics(const std::string& data, const std::string& label, RosEventTopics& topics);

}  // namespace aesim
