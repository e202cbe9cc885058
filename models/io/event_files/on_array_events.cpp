#include "aesim/event_files/on_array_events.hpp"

#include <algorithm>

namespace aesim {

void OnArrayEvents::events(const AddressEvent* first, std::size_t count) {
  const auto off = [this](const AddressEvent& e) { return !map_.names_pixel(e); };
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
