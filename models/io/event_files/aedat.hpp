#pragma once
#include <cstdint>
#include <iosfwd>
#include <map>
#include <string>
#include <vector>

#include "aesim/array/address_map.hpp"
#include "aesim/events/address_event.hpp"
#include "aesim/event_files/aedat_layout.hpp"
#include "aesim/event_files/event_stamps.hpp"
#include "aesim/event_files/event_writer.hpp"
#include "aesim/threads/buffer_hand_off.hpp"

#include <nlohmann/json_fwd.hpp>

namespace aesim {

struct AedatRecord {
  std::uint32_t address = 0;
  // us: a file aesim wrote holds int32 stamps that never go back; another recorder's are read as
  // jAER reads them, unsigned 32-bit words unwrapped past 2^32 (see decode_aedat).
  std::int64_t timestamp_us = 0;
};

// An AEDAT 2.0 (jAER) file: '#' header lines ending in CRLF, then big-endian int32 address and
// int32 timestamp (us) per event. aesim's own header lines "# aesim.KEY: VALUE" carry the address
// layout and every sensor parameter; `metadata` holds them by KEY.
struct AedatFile {
  std::vector<std::string> header;  // without the CRLF
  std::map<std::string, std::string> metadata;
  std::vector<AedatRecord> records;
  std::uint64_t stamp_wraps = 0;  // another recorder's stamps that wrapped past 2^32 us
};

// Every sensor parameter as "section.key" -> text, for the header.
std::map<std::string, std::string> sensor_metadata(const nlohmann::json& sensor);
// Header for events of `map` with `sensor` parameters (from sensor_metadata), in `layout` (a jAER
// layout adds the "# AEChip:" line naming the chip jAER decodes the words as).
std::vector<std::string> aedat_header(const AddressMap& map, const std::map<std::string, std::string>& sensor,
                                      AedatLayout layout = AedatLayout::Aesim);
void write_aedat(std::ostream& out, const std::vector<std::string>& header,
                 const std::vector<AedatRecord>& records);
AedatFile read_aedat(const std::string& path);
AedatFile decode_aedat(const std::string& data, const std::string& path);

[[noreturn]] void throw_aedat_stamp_overflow(double t);
// aesim's own address word of an event: its tile above its bus address.
inline std::uint32_t aedat_address(const AddressEvent& e, unsigned bus_bits) { return (e.tile << bus_bits) | e.bus_address; }
// An event's AEDAT stamp, whole microseconds of receiver ticks, refused past the int32 range.
inline std::int64_t aedat_stamp(const AddressEvent& e, const MicrosecondStamps& stamps) {
  const std::uint64_t stamp = stamps(e.t);
  if (stamp > 0x7FFFFFFFu) throw_aedat_stamp_overflow(e.t);
  return static_cast<std::int64_t>(stamp);
}

// Writes an AEDAT 2.0 file as a run streams its events: the header at once, then the records
// packed big-endian through a buffer, addresses in `layout`.
class AedatWriter : public EventFileWriter {
 public:
  AedatWriter(std::ostream& out, const std::vector<std::string>& header, const AddressMap& map, double tick,
              AedatLayout layout = AedatLayout::Aesim);
  ~AedatWriter() override;
  void events(const AddressEvent* first, std::size_t count) override;
  // Hands what the buffer holds over to be written (on a thread of the writer's own).
  void flush();
  // Writes everything: what the buffer holds and every buffer handed over. The destructor does it
  // too, but cannot report an error.
  void finish() override;
  // The first address beginning with '#' (tonic's header rule misreads the file); in jAER's
  // layouts, the events stamped 0 us that jAER's reader will lose.
  std::string reader_warning() const override;

 private:
  std::ostream& out_;
  unsigned bus_bits_;
  MicrosecondStamps stamps_;
  AedatLayout layout_;
  JaerChip chip_;
  int rows_;
  // An event's address word in the file's layout.
  std::uint32_t address_of(const AddressEvent& e) const {
    return layout_ == AedatLayout::Aesim ? aedat_address(e, bus_bits_) : jaer_address(layout_, chip_, rows_, e);
  }
  // Packs `count` records, each's address word `address(event)`, the layout chosen once a call.
  template <class Address>
  void pack(const AddressEvent* first, std::size_t count, Address address);

  bool first_written_ = false, first_is_hash_ = false;
  bool jaer_takes_next_ = false;
  std::uint64_t jaer_lost_ = 0;
  std::vector<char> buffer_;  // kBufferBytes, a multiple of the 8-byte record
  std::size_t used_ = 0;
  BufferHandOff<std::vector<char>> writes_;  // last: its writes use out_
};

// The AEDAT record of a delivered event (timestamp in whole microseconds of receiver ticks).
inline AedatRecord aedat_record(const AddressEvent& e, unsigned bus_bits, const MicrosecondStamps& stamps) {
  AedatRecord r;
  r.address = aedat_address(e, bus_bits);
  r.timestamp_us = aedat_stamp(e, stamps);
  return r;
}
// The AEDAT records of delivered events (timestamps in whole microseconds of receiver ticks).
std::vector<AedatRecord> aedat_records(const std::vector<AddressEvent>& events, const AddressMap& map,
                                       double tick);

}  // namespace aesim
