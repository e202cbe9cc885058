#include "event_files/on_array_events.hpp"

#include <algorithm>

namespace aesim {

void OnArrayEvents::events(const AddressEvent* first, std::size_t count) {
  // AddressMap::decode without its division: an event's coordinates are its address located, so
  // the address names a pixel when it lies within its tile's sides and the coordinates within
  // the array's (this runs over every event on the merge thread).
  const std::uint32_t xbits = static_cast<std::uint32_t>(map_.xbits()), xmask = (1u << xbits) - 1;
  const auto tile_cols = static_cast<std::uint32_t>(map_.tile_cols()), tile_rows = static_cast<std::uint32_t>(map_.tile_rows());
  const auto cols = static_cast<std::uint32_t>(map_.cols()), rows = static_cast<std::uint32_t>(map_.rows());
  const auto off = [=](const AddressEvent& e) {
    return (e.bus_address & xmask) >= tile_cols || (e.bus_address >> xbits) >= tile_rows || e.x >= cols || e.y >= rows;
  };
  // Nearly always every event of a chunk is on the array, and the chunk goes on as it is.
  const AddressEvent* const end = first + count;
  if (std::none_of(first, end, off)) return writer_->events(first, count);
  kept_.clear();
  for (const AddressEvent* e = first; e != end; ++e) {
    if (off(*e)) {
      ++off_array_;
    } else {
      kept_.push_back(*e);
    }
  }
  writer_->events(kept_.data(), kept_.size());
}

}  // namespace aesim
