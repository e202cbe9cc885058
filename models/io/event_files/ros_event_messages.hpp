#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <string_view>

#include "aesim/event_files/aedat4.hpp"

namespace aesim {

// The message layouts a bag's events come in: dvs_msgs/EventArray's (std_msgs/Header, uint32
// height, uint32 width, then x, y (uint16), ts (a ROS time) and polarity (bool) an event), which
// prophesee_event_msgs/EventArray shares, and event_camera_msgs/EventPacket's (std_msgs/Header,
// uint32 height, uint32 width, uint64 seq, uint64 time_base, string encoding, bool is_bigendian,
// uint8[] events: the camera's own words, in the encoding named).
enum class RosEventLayout { Other, EventArray, EventPacket };

// How a message's bytes are laid out: ROS 1's serialization (little-endian, nothing between the
// fields), or ROS 2's CDR (a 4-byte encapsulation header naming the byte order, then each number at
// a multiple of its size from the header's end: XCDR1's up to 8, XCDR2's up to 4).
enum class RosWire { Ros1, Cdr };

class RosMessageBytes;

// The layout a type carries. ROS 2 gives a type no checksum of its fields, so it is told by its
// definition where the bag holds one (the .msg text: rosbag2's MCAP schemas, "ros2msg", and a
// newer .db3's message_definitions; also ROS 1's in an MCAP file), compared field by field, package
// names aside; and otherwise by its name (dvs_msgs, prophesee_event_msgs, event_camera_msgs, and
// event_array_msgs, whose EventArray is EventPacket's predecessor, field for field).
RosEventLayout ros_event_layout(std::string_view type, std::string_view definition);

// A bag's topics read message by message: the event topics' messages decoded, the others counted.
class RosEventTopics {
 public:
  explicit RosEventTopics(std::string label) : label_(std::move(label)) {}
  // A topic the bag declares and the name of its type, listed when no topic carries events.
  void declare(const std::string& topic, const std::string& type);
  // One message on a declared topic, in the order the bag holds them (an EventPacket's decoder
  // state runs on from one packet to the next). Throws InputError naming the message.
  void message(const std::string& topic, RosEventLayout layout, RosWire wire, std::string_view data);
  // The first event topic by name (MVSEC's /davis/left/events before its right); the other event
  // topics and the others' messages counted in `notes`. Throws InputError when no topic carries
  // events, naming the topics the bag holds.
  PolarityRecording result();

 private:
  // One event topic as read so far: decoded events (EventArray), or the camera's words of every
  // packet in order after a RAW header (EventPacket).
  struct EventTopic {
    RosEventLayout layout = RosEventLayout::EventArray;
    std::vector<PolarityEvent> events;
    std::string encoding, stream;
    std::uint32_t width = 0, height = 0;
    std::uint64_t messages = 0;
    std::uint64_t triggers = 0;  // the external triggers of a topic of "trigger" packets
    // "libcaer_cmp": the decoder's state that runs on from packet to packet (the column, a vector's
    // base row and polarity), and what it left out: events outside the packets' array, and words
    // of no event (VECT_12, which libcaer_driver never writes, and unassigned codes).
    std::uint16_t cmp_x = 0, cmp_base_y = 0;
    bool cmp_on = false;
    std::uint64_t cmp_outside = 0, cmp_other_words = 0;
  };
  struct OtherTopic {
    std::string type;
    std::uint64_t messages = 0, bytes = 0;
  };
  void packet(EventTopic& topic, RosMessageBytes& m);
  void eight_byte_events(EventTopic& topic, RosMessageBytes& m, std::uint64_t time_base, std::string_view words);
  void compressed_libcaer_events(EventTopic& topic, RosMessageBytes& m, std::uint64_t time_base, std::string_view words);
  PolarityRecording decode_packets(const std::string& name, EventTopic& topic) const;

  std::string label_;
  std::map<std::string, EventTopic> events_;
  std::map<std::string, OtherTopic> others_;
  std::uint64_t event_count_ = 0;
};

}  // namespace aesim
