#include "aesim/embed/receiver_stream_feed.hpp"

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"

namespace aesim {

ReceiverStreamFeed::ReceiverStreamFeed(const sc_core::sc_module_name& name, EventFifoTarget& fifo, const Imager& imager,
                                       std::uint32_t tile)
    : sc_module(name), fifo_(fifo), map_(imager.config().array), tile_(tile), tick_(imager.tick()) {
  if (static_cast<int>(tile) >= map_.tiles()) {
    throw InputError(fmt::format("ReceiverStreamFeed: tile {} does not exist (the array has {})", tile, map_.tiles()));
  }
  const int width = imager.receiver_config().ts_width;
  ts_modulus_ = width >= 64 ? 0 : (1ULL << width);
  SC_METHOD(on_clock);
  sensitive << clk.pos();
}

void ReceiverStreamFeed::on_clock() {
  // Runs once at initialisation too, so ready is high from the first edge on.
  const bool ready = evt_ready.read();
  evt_ready.write(true);
  if (!evt_valid.read() || !ready) return;
  const std::uint64_t ts = evt_ts.read();
  if (ts < last_ts_) ++wraps_;
  last_ts_ = ts;
  AddressEvent e;
  e.t = static_cast<double>(ts + wraps_ * ts_modulus_) * tick_;
  e.tile = tile_;
  e.bus_address = evt_addr.read();
  const PixelAddress p = map_.locate(tile_, e.bus_address);
  e.x = p.x;
  e.y = p.y;
  e.flags = evt_flags.read() ? kGhostEvent : kNormalEvent;
  ++beats_;
  fifo_.push(e);
}

}  // namespace aesim
