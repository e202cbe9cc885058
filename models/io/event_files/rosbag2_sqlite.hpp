#pragma once
#include <string>

#include "aesim/event_files/aedat4.hpp"
#include "aesim/event_files/ros_event_messages.hpp"

namespace aesim {

// The events of a ROS 2 bag stored in SQLite (`.db3`, rosbag2's default storage before Iron): its
// topics table, and its messages in the order they were written (by id), CDR decoded where the
// topic's type is of dvs_msgs/EventArray's or event_camera_msgs/EventPacket's layout (told by the
// message_definitions table where the bag has one, by the type's name otherwise;
// ros_event_messages.hpp), as a ROS bag's are. The database is read from `data` by SQLite itself,
// read-only. Throws InputError naming `label` for a file that is not an SQLite database, one
// without rosbag2's tables, one SQLite finds malformed, or a bag without an event topic.
PolarityRecording decode_rosbag2_sqlite(const std::string& data, const std::string& label);
// The same into `topics`, which a ROS 2 bag split into several files reads each into in turn.
void read_rosbag2_sqlite_topics(const std::string& data, const std::string& label, RosEventTopics& topics);

}  // namespace aesim
