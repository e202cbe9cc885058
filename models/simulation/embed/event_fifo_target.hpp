#pragma once
#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include <systemc>
#include <tlm>
#include <tlm_utils/simple_target_socket.h>

#include "aesim/embed/event_fifo_registers.hpp"
#include "aesim/events/address_event.hpp"

namespace aesim {

// A memory-mapped FIFO of received events with an interrupt, for a virtual platform: the
// receiver's output as a processor sees it, read over a TLM-2.0 target socket (register map in
// event_fifo_registers.hpp). `irq` is high while the interrupt is enabled and the fill has reached
// the threshold. Arrays up to 4096 x 4096 in up to 64 tiles fit the event word.
//
// Events come in two ways. deliver() hands over a timed stream known in advance (the event
// fidelity's run, EventSource::events()): each event enters at its own delivery time, without a
// process of its own, and the FIFO is brought up to date whenever it is touched; push() enters one
// event at the current simulation time (a process that watches a tile's receiver stream at the cycle
// fidelity: ReceiverStreamFeed). A full FIFO drops the event and counts it.
//
// Timing. Blocking transport (b_transport): an access happens at the initiator's time, the
// simulation time plus the annotated delay it passes (a loosely timed initiator's local time), and
// adds `access` to that delay; so a temporally decoupled initiator, running ahead of the kernel by
// up to its quantum, sees the FIFO exactly as it is at its own time, as long as its accesses come in
// time order. Non-blocking transport (an approximately timed initiator: BEGIN_REQ, then BEGIN_RESP
// on the backward path after `access`) is the socket's conversion to the same b_transport. DMI is
// refused; transport_dbg reads without side effects.
class EventFifoTarget : public sc_core::sc_module {
 public:
  tlm_utils::simple_target_socket<EventFifoTarget> socket;
  sc_core::sc_out<bool> irq;

  // `depth` events (at least 1); stamps are delivery times in ticks of `tick` seconds; each
  // register access takes `access`.
  EventFifoTarget(const sc_core::sc_module_name& name, std::uint32_t depth, double tick,
                  const sc_core::sc_time& access = sc_core::sc_time(10, sc_core::SC_NS));
  SC_HAS_PROCESS(EventFifoTarget);

  // Events that enter at their times `t` (s of simulation time, in time order, none earlier than
  // the events already handed over): the timed stream of a run known in advance.
  void deliver(const std::vector<AddressEvent>& events);
  // One event entering now (its `t` gives only its stamp); dropped and counted when the FIFO is full.
  void push(const AddressEvent& e);

  // When the interrupt line is high at or after `from` (absolute simulation time) if nothing reads
  // the FIFO meanwhile: `from` itself when it is high then, the arrival of the event that lifts the
  // fill to the threshold, or nothing when that is not known (disabled, or not enough events in the
  // delivered stream). A temporally decoupled processor waiting for its interrupt skips to this time
  // within its quantum instead of yielding to the kernel (the line itself rises at the same time).
  std::optional<sc_core::sc_time> irq_due(const sc_core::sc_time& from);

  // At the current simulation time (or the latest access, if an initiator ran ahead of it).
  std::uint32_t fill();
  std::uint64_t overflows();
  std::uint32_t depth() const { return depth_; }

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
  Entry entry(const AddressEvent& e) const;
  void enter(const Entry& e);
  // Every delivered event due by `at` (ps of simulation time) enters, in order.
  void admit(sc_dt::uint64 at);
  void update_irq();
  void drive_irq();
  void on_due();
  // When the delivered event that lifts the fill to the threshold arrives (ps), if nothing is read
  // first: none while the interrupt is disabled or the stream ends short of it.
  std::optional<sc_dt::uint64> threshold_arrival() const;
  void schedule_due();
  void start_of_simulation() override;

  std::uint32_t depth_;
  double tick_;
  sc_core::sc_time access_;
  std::deque<Entry> fifo_;
  std::vector<Entry> stream_;              // delivered, not yet entered from stream_next_ on
  std::vector<sc_dt::uint64> stream_at_;   // their arrival times, ps
  std::size_t stream_next_ = 0;
  std::uint32_t stamp_ = 0, irq_enable_ = 0, irq_threshold_ = 1;
  std::uint64_t overflows_ = 0;
  bool overflowed_ = false, irq_level_ = false, irq_driven_ = false, irq_notified_ = false;
  sc_core::sc_event irq_changed_, due_;
  std::optional<sc_dt::uint64> due_at_;    // when due_ is set to fire, ps
};

}  // namespace aesim
