#include "aesim/embed/receiver_stream_feed.hpp"

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"

namespace aesim {

ReceiverStreamFeed::ReceiverStreamFeed(const sc_core::sc_module_name& name, EventFifoTarget& fifo, const Imager& imager,
                                       std::uint32_t tile)
    : sc_module(name),
      fifo_(fifo),
      map_(imager.config().array),
      decoder_(tile, map_, imager.tick(), imager.receiver_config().ts_width) {
  if (static_cast<int>(tile) >= map_.tiles()) {
    throw InputError(fmt::format("ReceiverStreamFeed: tile {} does not exist (the array has {})", tile, map_.tiles()));
  }
  SC_METHOD(on_clock);
  sensitive << clk.pos();
}

void ReceiverStreamFeed::on_clock() {
  // Runs once at initialisation too, so ready is high from the first edge on.
  const bool ready = evt_ready.read();
  evt_ready.write(true);
  if (!evt_valid.read() || !ready) return;
  const AddressEvent e = decoder_.decode(evt_ts.read(), evt_addr.read(), evt_flags.read());
  ++beats_;
  fifo_.push(e);
}

}  // namespace aesim
