#pragma once
#include <cstdint>

#include <systemc>

#include "aesim/array/address_map.hpp"
#include "aesim/embed/event_fifo_target.hpp"
#include "aesim/embed/imager.hpp"
#include "aesim/receiver/beat_decoder.hpp"

namespace aesim {

// A tile's receiver output stream at the cycle fidelity into an EventFifoTarget: the FIFO as the
// stream's consumer. One beat is taken at each rising edge of `clk` with evt_valid high (evt_ready
// is held high: the peripheral takes every beat, and one that finds the FIFO full is dropped and
// counted there, as with the timed stream). The beat becomes its event (BeatDecoder: the tile's
// pixel, the stamp unwrapped) and enters the FIFO at the edge. Bind the ports to the signals a receiver on Imager::tile[t]'s ports drives, in place of the
// tile's own evt_* ports (the FIFO, not Imager::events(), then holds that tile's events).
class ReceiverStreamFeed : public sc_core::sc_module {
 public:
  sc_core::sc_in<bool> clk{"clk"};
  sc_core::sc_in<bool> evt_valid{"evt_valid"}, evt_flags{"evt_flags"};
  sc_core::sc_in<std::uint32_t> evt_addr{"evt_addr"}, evt_ts{"evt_ts"};
  sc_core::sc_out<bool> evt_ready{"evt_ready"};

  ReceiverStreamFeed(const sc_core::sc_module_name& name, EventFifoTarget& fifo, const Imager& imager,
                     std::uint32_t tile);
  SC_HAS_PROCESS(ReceiverStreamFeed);

  std::uint64_t beats() const { return beats_; }

 private:
  void on_clock();

  EventFifoTarget& fifo_;
  AddressMap map_;  // before decoder_, which refers to it
  BeatDecoder decoder_;
  std::uint64_t beats_ = 0;
};

}  // namespace aesim
