#pragma once
#include <cstdint>
#include <deque>

#include <systemc>
#include <tlm>
#include <tlm_utils/simple_target_socket.h>

#include "aesim/embed/event_fifo_registers.hpp"
#include "aesim/events/address_event.hpp"

namespace aesim {

// A memory-mapped FIFO of received events with an interrupt, for a virtual platform: the
// receiver's output as a processor sees it. Events arrive through push() (from an EventSource's
// callback or a tile's stream) at their delivery time; a processor model reads them over a
// TLM-2.0 target socket (blocking transport, loosely timed: each access adds `access` to the
// annotated delay; DMI refused; transport_dbg reads without side effects), register map in
// event_fifo_registers.hpp. `irq` is high while the interrupt is enabled and the fill has reached
// the threshold. Arrays up to 4096 x 4096 in up to 64 tiles fit the event word.
class EventFifoTarget : public sc_core::sc_module {
 public:
  tlm_utils::simple_target_socket<EventFifoTarget> socket;
  sc_core::sc_out<bool> irq;

  // `depth` events (at least 1); stamps are delivery times in ticks of `tick` seconds; each
  // register access takes `access` (annotated, not waited).
  EventFifoTarget(const sc_core::sc_module_name& name, std::uint32_t depth, double tick,
                  const sc_core::sc_time& access = sc_core::sc_time(10, sc_core::SC_NS));
  SC_HAS_PROCESS(EventFifoTarget);

  // One event delivered now; dropped and counted when the FIFO is full.
  void push(const AddressEvent& e);

  std::uint32_t fill() const { return static_cast<std::uint32_t>(fifo_.size()); }
  std::uint64_t overflows() const { return overflows_; }

 private:
  struct Entry {
    std::uint32_t word, stamp;
  };
  void b_transport(tlm::tlm_generic_payload& trans, sc_core::sc_time& delay);
  unsigned int transport_dbg(tlm::tlm_generic_payload& trans);
  bool get_direct_mem_ptr(tlm::tlm_generic_payload& trans, tlm::tlm_dmi& dmi);
  // Checks an access against the map's rules; sets the error response and returns false if it breaks one.
  bool valid_access(tlm::tlm_generic_payload& trans) const;
  std::uint32_t read(std::uint32_t offset, bool side_effects);
  bool write(std::uint32_t offset, std::uint32_t value);
  void update_irq();
  void drive_irq();

  std::uint32_t depth_;
  double tick_;
  sc_core::sc_time access_;
  std::deque<Entry> fifo_;
  std::uint32_t stamp_ = 0, irq_enable_ = 0, irq_threshold_ = 1;
  std::uint64_t overflows_ = 0;
  bool overflowed_ = false, irq_level_ = false;
  sc_core::sc_event irq_changed_;
};

}  // namespace aesim
