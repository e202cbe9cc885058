#include "aesim/embed/event_fifo_target.hpp"

#include <algorithm>
#include <cstring>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/events/timestamps.hpp"

namespace aesim {

namespace reg = event_fifo;

EventFifoTarget::EventFifoTarget(const sc_core::sc_module_name& name, std::uint32_t depth, double tick,
                                 const sc_core::sc_time& access)
    : sc_module(name), socket("socket"), irq("irq"), depth_(depth), tick_(tick), access_(access) {
  if (depth_ < 1) throw InputError("EventFifoTarget: the depth must be at least 1 event");
  if (!(tick_ > 0)) throw InputError("EventFifoTarget: the tick must be positive");
  socket.register_b_transport(this, &EventFifoTarget::b_transport);
  socket.register_transport_dbg(this, &EventFifoTarget::transport_dbg);
  socket.register_get_direct_mem_ptr(this, &EventFifoTarget::get_direct_mem_ptr);
  // One process drives the interrupt line, whichever process changed the fill or the settings.
  SC_METHOD(drive_irq);
  sensitive << irq_changed_;
}

void EventFifoTarget::push(const AddressEvent& e) {
  if (fifo_.size() >= depth_) {
    ++overflows_;
    overflowed_ = true;
    return;
  }
  fifo_.push_back({reg::event_word(e.x, e.y, e.tile, (e.flags & kGhostEvent) != 0),
                   static_cast<std::uint32_t>(timestamp_ticks(e.t, tick_))});
  update_irq();
}

bool EventFifoTarget::valid_access(tlm::tlm_generic_payload& trans) const {
  const sc_dt::uint64 offset = trans.get_address();
  if (trans.get_byte_enable_ptr() != nullptr) {
    trans.set_response_status(tlm::TLM_BYTE_ENABLE_ERROR_RESPONSE);
  } else if (trans.get_data_length() != 4 || trans.get_streaming_width() != 4) {
    trans.set_response_status(tlm::TLM_BURST_ERROR_RESPONSE);
  } else if (offset % 4 != 0 || offset >= reg::kMapBytes) {
    trans.set_response_status(tlm::TLM_ADDRESS_ERROR_RESPONSE);
  } else {
    return true;
  }
  return false;
}

void EventFifoTarget::b_transport(tlm::tlm_generic_payload& trans, sc_core::sc_time& delay) {
  trans.set_dmi_allowed(false);
  if (trans.get_command() == tlm::TLM_IGNORE_COMMAND) {
    trans.set_response_status(tlm::TLM_OK_RESPONSE);
    return;
  }
  if (!valid_access(trans)) return;
  const auto offset = static_cast<std::uint32_t>(trans.get_address());
  if (trans.is_read()) {
    if (offset == reg::kControl) {
      trans.set_response_status(tlm::TLM_COMMAND_ERROR_RESPONSE);
      return;
    }
    const std::uint32_t value = read(offset, true);
    std::memcpy(trans.get_data_ptr(), &value, 4);
  } else {
    std::uint32_t value = 0;
    std::memcpy(&value, trans.get_data_ptr(), 4);
    if (!write(offset, value)) {
      trans.set_response_status(tlm::TLM_COMMAND_ERROR_RESPONSE);
      return;
    }
  }
  delay += access_;
  trans.set_response_status(tlm::TLM_OK_RESPONSE);
}

unsigned int EventFifoTarget::transport_dbg(tlm::tlm_generic_payload& trans) {
  if (!trans.is_read() || trans.get_data_length() != 4 || trans.get_address() % 4 != 0 ||
      trans.get_address() >= reg::kMapBytes || trans.get_address() == reg::kControl) {
    return 0;
  }
  const std::uint32_t value = read(static_cast<std::uint32_t>(trans.get_address()), false);
  std::memcpy(trans.get_data_ptr(), &value, 4);
  return 4;
}

bool EventFifoTarget::get_direct_mem_ptr(tlm::tlm_generic_payload& trans, tlm::tlm_dmi& dmi) {
  (void)trans;
  (void)dmi;
  return false;  // registers with side effects: no direct access
}

std::uint32_t EventFifoTarget::read(std::uint32_t offset, bool side_effects) {
  switch (offset) {
    case reg::kStatus:
      return (fifo_.empty() ? 0 : reg::kNotEmpty) | (fifo_.size() >= depth_ ? reg::kFull : 0) |
             (irq_level_ ? reg::kIrqPending : 0) | (overflowed_ ? reg::kOverflowed : 0);
    case reg::kEvent: {
      if (fifo_.empty()) return reg::kEmptyEvent;
      const Entry head = fifo_.front();
      if (side_effects) {
        fifo_.pop_front();
        stamp_ = head.stamp;
        update_irq();
      }
      return head.word;
    }
    case reg::kStamp: return stamp_;
    case reg::kFill: return fill();
    case reg::kIrqEnable: return irq_enable_;
    case reg::kIrqThreshold: return irq_threshold_;
    case reg::kOverflows: return static_cast<std::uint32_t>(std::min<std::uint64_t>(overflows_, 0xFFFFFFFFu));
    case reg::kDepth: return depth_;
    default: return 0;
  }
}

bool EventFifoTarget::write(std::uint32_t offset, std::uint32_t value) {
  switch (offset) {
    case reg::kIrqEnable: irq_enable_ = value & 1u; break;
    case reg::kIrqThreshold: irq_threshold_ = std::max<std::uint32_t>(value, 1); break;
    case reg::kControl:
      if (value & reg::kClear) {
        fifo_.clear();
        overflows_ = 0;
        overflowed_ = false;
      }
      break;
    default: return false;  // read-only
  }
  update_irq();
  return true;
}

void EventFifoTarget::update_irq() {
  const bool level = (irq_enable_ & 1u) != 0 && fifo_.size() >= irq_threshold_;
  if (level != irq_level_) {
    irq_level_ = level;
    irq_changed_.notify(sc_core::SC_ZERO_TIME);
  }
}

void EventFifoTarget::drive_irq() { irq.write(irq_level_); }

}  // namespace aesim
