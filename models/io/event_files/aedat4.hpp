#pragma once
#include <cstdint>
#include <map>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "aesim/event_files/event_stamps.hpp"
#include "aesim/event_files/event_writer.hpp"

namespace aesim {

// AEDAT 4.0, DV's format: "#!AER-DAT4.0\r\n", the size-prefixed FlatBuffer IOHeader (compression,
// no data table, an XML info node naming one stream "events" of type EVTS with the array's sizeX
// and sizeY and aesim's sensor parameters), then packets: int32 stream id, int32 body size, and
// the body, a size-prefixed EventPacket FlatBuffer, as an LZ4 frame when compressed. x and y are
// global (0, 0 top-left); polarity is 1 for a normal event and 0 for a ghost.
//
// Events are put in a packet's layout as they come, on the caller's thread (the merge's); a full
// packet's compression and writing run on a thread of the writer's own (SerialWorker) while the
// next packet fills: LZ4 costs more than the merge that feeds it. The caller compresses packets
// too while that thread is behind, and at finish() those still waiting, from the newest back; the
// writer's thread writes every packet in order. Uncompressed, they are written at once.
class Aedat4Writer : public EventFileWriter {
 public:
  Aedat4Writer(std::ostream& out, const EventFileSpec& spec);
  ~Aedat4Writer() override;
  void events(const AddressEvent* first, std::size_t count) override;
  void finish() override;

 private:
  struct Packets;
  // The data table DV writes at the end: one entry a packet, and where the header's
  // dataTablePosition lies in the file, to be patched (-1 when the output cannot seek).
  struct Written {
    std::int64_t offset, size, elements, first_us, last_us;
  };
  void write_packet();
  void write_body(const char* body, std::size_t size, Written entry);
  void write_data_table();
  // Compresses `size` bytes at `body` into `out` as the header says (copies them uncompressed);
  // returns the size to write.
  std::size_t compress(const char* body, std::size_t size, std::vector<char>& out) const;
  void help_pack();
  std::ostream& out_;
  MicrosecondStamps stamps_;
  Aedat4Compression compression_;
  std::vector<char> body_;
  std::vector<Written> written_;
  std::int64_t table_field_at_ = -1;
  bool any_packet_ = false;
  std::unique_ptr<Packets> packets_;  // last: its worker's jobs use the members above
};

// A polarity event as the field's formats carry it.
struct PolarityEvent {
  std::int64_t t_us = 0;
  std::int32_t x = 0, y = 0;
  bool on = true;
};

// Packets of streams other than the events (DV's IMU, triggers, frames), counted.
struct SkippedPackets {
  std::string type;  // the stream's typeIdentifier (IMUS, TRIG, FRME, ...)
  std::uint64_t packets = 0, bytes = 0;
};

// What an event file of the polarity formats (AEDAT 4.0, .npy, .h5) holds. width and height are 0
// when the file records none; `sensor` holds aesim's parameters when aesim wrote it.
struct PolarityRecording {
  std::vector<PolarityEvent> events;
  int width = 0, height = 0;
  std::map<std::string, std::string> sensor;
  std::vector<SkippedPackets> skipped;  // other streams' packets, by stream
  std::uint64_t invalid = 0;            // events their producer marked invalid (AEDAT 3.1), left out
  std::vector<std::string> notes;       // anything else left out, in words ("3 external trigger events")
  std::vector<std::string> read_as;     // how numbers the format leaves open were taken (EventRecording's)
  // Events stamped before the one ahead of them, put in time order by their reader (a stable
  // sort); those readers' files may hold them (v2e's text output).
  std::uint64_t reordered = 0;
};

// Counts the events stamped before the one ahead of them (`reordered`) and, if there are any, puts
// the events in time order, equal stamps in the file's order (a stable sort).
void put_in_time_order(PolarityRecording& rec);

// Reads the events stream (the first of type EVTS) of an AEDAT 4.0 file, up to its data table
// (dataTablePosition) when it has one; other streams' packets are skipped and counted, a packet of
// a stream the header does not declare is an error. Throws InputError naming `label` on anything
// malformed.
PolarityRecording decode_aedat4(const std::string& data, const std::string& label);

}  // namespace aesim
