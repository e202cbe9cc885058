// The TLM-2.0 event peripheral: each register as the map says, the interrupt, the blocking
// transport's base-protocol rules (checked on every access by the initiator below, from the
// TLM-2.0 standard's rules for b_transport), and the imager's events read by an interrupt-driven
// processor model, every one of them, in order, with its stamp.
#include <cstdint>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <systemc>
#include <tlm>
#include <tlm_utils/simple_initiator_socket.h>

#include "aesim/embed/event_fifo_target.hpp"
#include "aesim/embed/event_source.hpp"
#include "aesim/events/timestamps.hpp"
#include "aesim/kernel/systemc_kernel.hpp"

namespace aesim {
namespace {

namespace reg = event_fifo;

// An initiator whose accesses check the base protocol's rules for the blocking transport: the
// target sets a response status (never leaves it incomplete) and does not modify the command,
// address, data pointer, data length, byte enables or streaming width; a write's data is left as
// it was; the target grants no DMI.
struct Initiator : sc_core::sc_module {
  tlm_utils::simple_initiator_socket<Initiator> socket{"socket"};
  std::function<void(Initiator&)> body;
  sc_core::sc_time delay = sc_core::SC_ZERO_TIME;
  std::uint64_t rule_breaks = 0;
  SC_HAS_PROCESS(Initiator);
  Initiator(const sc_core::sc_module_name& name, std::function<void(Initiator&)> b) : sc_module(name), body(std::move(b)) {
    SC_THREAD(run);
  }
  void run() { body(*this); }

  tlm::tlm_response_status access(tlm::tlm_command command, std::uint64_t address, std::uint32_t& value,
                                  unsigned length = 4, unsigned streaming = 4, unsigned char* byte_enables = nullptr) {
    unsigned char data[8] = {};
    std::memcpy(data, &value, 4);
    unsigned char before[8];
    std::memcpy(before, data, sizeof data);
    tlm::tlm_generic_payload t;
    t.set_command(command);
    t.set_address(address);
    t.set_data_ptr(data);
    t.set_data_length(length);
    t.set_streaming_width(streaming);
    t.set_byte_enable_ptr(byte_enables);
    t.set_byte_enable_length(byte_enables ? 4 : 0);
    t.set_dmi_allowed(true);
    t.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
    socket->b_transport(t, delay);
    const bool kept = t.get_command() == command && t.get_address() == address && t.get_data_ptr() == data &&
                      t.get_data_length() == length && t.get_streaming_width() == streaming &&
                      t.get_byte_enable_ptr() == byte_enables;
    if (t.get_response_status() == tlm::TLM_INCOMPLETE_RESPONSE || !kept || t.is_dmi_allowed()) ++rule_breaks;
    if (command == tlm::TLM_WRITE_COMMAND && std::memcmp(before, data, sizeof data) != 0) ++rule_breaks;
    if (command == tlm::TLM_READ_COMMAND && t.is_response_ok()) std::memcpy(&value, data, 4);
    return t.get_response_status();
  }
  std::uint32_t read(std::uint32_t offset) {
    std::uint32_t v = 0xDEADBEEF;
    EXPECT_EQ(access(tlm::TLM_READ_COMMAND, offset, v), tlm::TLM_OK_RESPONSE) << "read 0x" << std::hex << offset;
    return v;
  }
  void write(std::uint32_t offset, std::uint32_t value) {
    EXPECT_EQ(access(tlm::TLM_WRITE_COMMAND, offset, value), tlm::TLM_OK_RESPONSE) << "write 0x" << std::hex << offset;
  }
};

AddressEvent event(double t, std::uint32_t x, std::uint32_t y, std::uint32_t tile, bool ghost = false) {
  AddressEvent e;
  e.t = t;
  e.x = x;
  e.y = y;
  e.tile = tile;
  e.flags = ghost ? kGhostEvent : kNormalEvent;
  return e;
}

TEST(EventFifoTarget, EachRegisterDoesWhatTheMapSays) {
  const ScopedKernel kernel;
  EventFifoTarget fifo("fifo", 4, 1e-6);
  sc_core::sc_signal<bool> irq("irq");
  fifo.irq(irq);
  Initiator cpu("cpu", [&fifo](Initiator& c) {
    EXPECT_EQ(c.read(reg::kDepth), 4u);
    EXPECT_EQ(c.read(reg::kFill), 0u);
    EXPECT_EQ(c.read(reg::kStatus), 0u);
    EXPECT_EQ(c.read(reg::kEvent), reg::kEmptyEvent);
    fifo.push(event(1.5e-6, 3, 5, 1));
    fifo.push(event(7e-6, 4095, 4095, 63, true));
    fifo.push(event(12e-6, 0, 1, 2));
    EXPECT_EQ(c.read(reg::kFill), 3u);
    EXPECT_EQ(c.read(reg::kStatus), reg::kNotEmpty);
    EXPECT_EQ(c.read(reg::kEvent), reg::event_word(3, 5, 1, false));
    EXPECT_EQ(c.read(reg::kStamp), 1u);  // 1.5 us in 1 us ticks
    const std::uint32_t ghost = c.read(reg::kEvent);
    EXPECT_TRUE(reg::event_ghost(ghost));
    EXPECT_EQ(reg::event_x(ghost), 4095u);
    EXPECT_EQ(reg::event_y(ghost), 4095u);
    EXPECT_EQ(reg::event_tile(ghost), 63u);
    EXPECT_EQ(c.read(reg::kStamp), 7u);
    EXPECT_EQ(c.read(reg::kFill), 1u);
    for (int k = 0; k < 5; ++k) fifo.push(event(20e-6 + k * 1e-6, 1, 1, 0));  // 3 fit, 2 are lost
    EXPECT_EQ(c.read(reg::kFill), 4u);
    EXPECT_EQ(c.read(reg::kOverflows), 2u);
    EXPECT_EQ(c.read(reg::kStatus), reg::kNotEmpty | reg::kFull | reg::kOverflowed);
    c.write(reg::kIrqThreshold, 0);
    EXPECT_EQ(c.read(reg::kIrqThreshold), 1u);  // 0 would be an interrupt without events
    c.write(reg::kIrqEnable, 3);
    EXPECT_EQ(c.read(reg::kIrqEnable), 1u);
    c.write(reg::kControl, reg::kClear);
    EXPECT_EQ(c.read(reg::kFill), 0u);
    EXPECT_EQ(c.read(reg::kOverflows), 0u);
    EXPECT_EQ(c.read(reg::kStatus), 0u);
  });
  cpu.socket.bind(fifo.socket);
  sc_core::sc_start();
  EXPECT_EQ(cpu.rule_breaks, 0u);
  // 10 ns annotated per access that succeeded: 22 of them.
  EXPECT_EQ(cpu.delay, sc_core::sc_time(220, sc_core::SC_NS));
}

TEST(EventFifoTarget, TheInterruptFollowsEnableThresholdAndFill) {
  const ScopedKernel kernel;
  EventFifoTarget fifo("fifo", 8, 1e-6);
  sc_core::sc_signal<bool> irq("irq");
  fifo.irq(irq);
  Initiator cpu("cpu", [&](Initiator& c) {
    c.write(reg::kIrqThreshold, 2);
    c.write(reg::kIrqEnable, 1);
    fifo.push(event(0, 1, 1, 0));
    sc_core::wait(sc_core::SC_ZERO_TIME);
    sc_core::wait(sc_core::SC_ZERO_TIME);
    EXPECT_FALSE(irq.read());
    fifo.push(event(0, 2, 2, 0));
    sc_core::wait(sc_core::SC_ZERO_TIME);
    sc_core::wait(sc_core::SC_ZERO_TIME);
    EXPECT_TRUE(irq.read());
    EXPECT_EQ(c.read(reg::kStatus) & reg::kIrqPending, reg::kIrqPending);
    c.read(reg::kEvent);
    sc_core::wait(sc_core::SC_ZERO_TIME);
    sc_core::wait(sc_core::SC_ZERO_TIME);
    EXPECT_FALSE(irq.read());
    fifo.push(event(0, 3, 3, 0));
    c.write(reg::kIrqEnable, 0);
    sc_core::wait(sc_core::SC_ZERO_TIME);
    sc_core::wait(sc_core::SC_ZERO_TIME);
    EXPECT_FALSE(irq.read());
  });
  cpu.socket.bind(fifo.socket);
  sc_core::sc_start();
  EXPECT_EQ(cpu.rule_breaks, 0u);
}

TEST(EventFifoTarget, BreachesOfTheMapGetTheBaseProtocolsErrorResponses) {
  const ScopedKernel kernel;
  EventFifoTarget fifo("fifo", 4, 1e-6);
  sc_core::sc_signal<bool> irq("irq");
  fifo.irq(irq);
  Initiator cpu("cpu", [&](Initiator& c) {
    std::uint32_t v = 1;
    unsigned char enables[4] = {0xFF, 0xFF, 0, 0};
    EXPECT_EQ(c.access(tlm::TLM_READ_COMMAND, reg::kMapBytes, v), tlm::TLM_ADDRESS_ERROR_RESPONSE);
    EXPECT_EQ(c.access(tlm::TLM_READ_COMMAND, 0x1000, v), tlm::TLM_ADDRESS_ERROR_RESPONSE);
    EXPECT_EQ(c.access(tlm::TLM_READ_COMMAND, 0x02, v), tlm::TLM_ADDRESS_ERROR_RESPONSE);
    EXPECT_EQ(c.access(tlm::TLM_READ_COMMAND, reg::kFill, v, 8, 8), tlm::TLM_BURST_ERROR_RESPONSE);
    EXPECT_EQ(c.access(tlm::TLM_READ_COMMAND, reg::kFill, v, 4, 2), tlm::TLM_BURST_ERROR_RESPONSE);
    EXPECT_EQ(c.access(tlm::TLM_READ_COMMAND, reg::kFill, v, 4, 4, enables), tlm::TLM_BYTE_ENABLE_ERROR_RESPONSE);
    EXPECT_EQ(c.access(tlm::TLM_WRITE_COMMAND, reg::kStatus, v), tlm::TLM_COMMAND_ERROR_RESPONSE);
    EXPECT_EQ(c.access(tlm::TLM_WRITE_COMMAND, reg::kEvent, v), tlm::TLM_COMMAND_ERROR_RESPONSE);
    EXPECT_EQ(c.access(tlm::TLM_READ_COMMAND, reg::kControl, v), tlm::TLM_COMMAND_ERROR_RESPONSE);
    EXPECT_EQ(c.access(tlm::TLM_IGNORE_COMMAND, reg::kEvent, v), tlm::TLM_OK_RESPONSE);
    EXPECT_EQ(c.delay, sc_core::SC_ZERO_TIME);  // nothing done, nothing annotated
    // Debug reads have no side effect; debug writes are refused; DMI is never granted.
    fifo.push(event(1e-6, 9, 9, 0));
    tlm::tlm_generic_payload t;
    std::uint32_t word = 0;
    t.set_command(tlm::TLM_READ_COMMAND);
    t.set_address(reg::kEvent);
    t.set_data_ptr(reinterpret_cast<unsigned char*>(&word));
    t.set_data_length(4);
    EXPECT_EQ(c.socket->transport_dbg(t), 4u);
    EXPECT_EQ(word, reg::event_word(9, 9, 0, false));
    EXPECT_EQ(c.read(reg::kFill), 1u);
    t.set_command(tlm::TLM_WRITE_COMMAND);
    t.set_address(reg::kIrqEnable);
    EXPECT_EQ(c.socket->transport_dbg(t), 0u);
    tlm::tlm_dmi dmi;
    EXPECT_FALSE(c.socket->get_direct_mem_ptr(t, dmi));
  });
  cpu.socket.bind(fifo.socket);
  sc_core::sc_start();
  EXPECT_EQ(cpu.rule_breaks, 0u);
}

// The imager's events (the event fidelity, the letter A, 200 ms) into a 64-event FIFO, read by a
// processor model woken by the interrupt: every event arrives, in order, with its stamp, none lost.
TEST(EventFifoTarget, AnInterruptDrivenReaderGetsEveryEventOfTheImager) {
  const ScopedKernel kernel;
  ImagerSpec spec;
  spec.settings = {{"sim.duration", "200ms"}};
  EventSource source("source", spec);
  EventFifoTarget fifo("fifo", 64, source.tick());
  source.on_event([&fifo](const AddressEvent& e) { fifo.push(e); });
  sc_core::sc_signal<bool> irq("irq");
  fifo.irq(irq);
  std::vector<std::uint32_t> words, stamps;
  Initiator cpu("cpu", [&](Initiator& c) {
    c.write(reg::kIrqThreshold, 1);
    c.write(reg::kIrqEnable, 1);
    for (;;) {
      if (!irq.read()) sc_core::wait(irq.posedge_event());
      while (c.read(reg::kFill) > 0) {
        words.push_back(c.read(reg::kEvent));
        stamps.push_back(c.read(reg::kStamp));
      }
      // Loosely timed: the time the reads took is waited once per batch.
      sc_core::wait(c.delay);
      c.delay = sc_core::SC_ZERO_TIME;
    }
  });
  cpu.socket.bind(fifo.socket);
  sc_core::sc_start(sc_core::sc_time(0.25, sc_core::SC_SEC));
  const std::vector<AddressEvent>& want = source.events();
  ASSERT_GT(want.size(), 1000u);
  ASSERT_EQ(words.size(), want.size());
  EXPECT_EQ(fifo.overflows(), 0u);
  for (std::size_t i = 0; i < want.size(); ++i) {
    ASSERT_EQ(words[i], reg::event_word(want[i].x, want[i].y, want[i].tile, false)) << "event " << i;
    ASSERT_EQ(stamps[i], static_cast<std::uint32_t>(timestamp_ticks(want[i].t, source.tick()))) << "event " << i;
  }
  EXPECT_EQ(cpu.rule_breaks, 0u);
}

}  // namespace
}  // namespace aesim
