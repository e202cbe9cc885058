#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "aesim/array/address_map.hpp"
#include "aesim/event_files/event_writer.hpp"

namespace aesim {

// In front of every event file writer: passes on only the events whose address (tile and bus
// address) names a pixel of the array. A ghost, the OR of colliding addresses, may name a column
// past its tile's (in the next tile's columns, or past the array with a narrow edge tile) or a row
// past the bottom. Such an event belongs to no pixel: placed by its coordinates it would land on
// another tile's pixel or outside the size the file declares (a reader indexing an image by them
// would go past its end; in jAER's layouts they do not fit the address word), and aesim's own
// reader refuses an AEDAT 2.0 address naming no pixel. They are counted instead (`off_array`) and
// the run says how many; the events CSV, which is text, keeps them.
class OnArrayEvents : public EventFileWriter {
 public:
  OnArrayEvents(std::unique_ptr<EventFileWriter> writer, const AddressMap& map)
      : writer_(std::move(writer)), map_(map) {}
  void events(const AddressEvent* first, std::size_t count) override;
  void truth(const TruthRecord* first, std::size_t count) override { writer_->truth(first, count); }
  void finish() override { writer_->finish(); }
  std::uint64_t off_array() const override { return off_array_; }
  std::string reader_warning() const override { return writer_->reader_warning(); }

 private:
  std::unique_ptr<EventFileWriter> writer_;
  AddressMap map_;
  std::uint64_t off_array_ = 0;
  std::vector<AddressEvent> kept_;
};

}  // namespace aesim
