#include "aesim/embed/event_fifo_target.hpp"

#include <algorithm>
#include <cmath>
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
  // One process drives the interrupt line, whichever process changed the fill or the settings;
  // another brings the FIFO up to date when a delivered event lifts the fill to the threshold.
  SC_METHOD(drive_irq);
  sensitive << irq_changed_;
  SC_METHOD(on_due);
  sensitive << due_;
  dont_initialize();
}

namespace {
sc_dt::uint64 now_value() { return sc_core::sc_time_stamp().value(); }
}  // namespace

void EventFifoTarget::deliver(const std::vector<AddressEvent>& events) {
  const double step = sc_core::sc_get_time_resolution().to_seconds();
  sc_dt::uint64 last = stream_at_.empty() ? 0 : stream_at_.back();
  for (const AddressEvent& e : events) {
    if (!(e.t >= 0) || !std::isfinite(e.t)) throw InputError("EventFifoTarget::deliver: an event time is negative or not finite");
    const auto at = static_cast<sc_dt::uint64>(std::llround(e.t / step));
    if (at < last) throw InputError("EventFifoTarget::deliver: the events are not in time order");
    last = at;
    stream_.push_back(entry(e));
    stream_at_.push_back(at);
  }
  if (sc_core::sc_is_running()) {
    admit(now_value());
    schedule_due();
  }
}

void EventFifoTarget::start_of_simulation() { schedule_due(); }

void EventFifoTarget::admit(sc_dt::uint64 at) {
  const std::size_t before = stream_next_;
  while (stream_next_ < stream_.size() && stream_at_[stream_next_] <= at) enter(stream_[stream_next_++]);
  if (stream_next_ != before) update_irq();
}

std::optional<sc_dt::uint64> EventFifoTarget::threshold_arrival() const {
  if ((irq_enable_ & 1u) == 0 || irq_threshold_ > depth_) return std::nullopt;
  const std::size_t index = stream_next_ + (irq_threshold_ - fifo_.size()) - 1;
  if (index >= stream_.size()) return std::nullopt;
  return stream_at_[index];
}

std::optional<sc_core::sc_time> EventFifoTarget::irq_due(const sc_core::sc_time& from) {
  admit(from.value());
  if (irq_level_) return from;
  const std::optional<sc_dt::uint64> at = threshold_arrival();
  if (!at) return std::nullopt;
  return sc_core::sc_time::from_value(*at);
}

void EventFifoTarget::schedule_due() {
  if (irq_level_) return;
  const std::optional<sc_dt::uint64> at = threshold_arrival();
  // An earlier wake-up already set stays: it finds the FIFO as it is then and sets the next one.
  if (!at || (due_at_ && *due_at_ <= *at)) return;
  const sc_dt::uint64 now = now_value();
  due_at_ = *at;
  due_.notify(sc_core::sc_time::from_value(*at > now ? *at - now : 0));
}

void EventFifoTarget::on_due() {
  due_at_.reset();
  admit(now_value());
  schedule_due();
}

void EventFifoTarget::push(const AddressEvent& e) {
  admit(now_value());
  enter(entry(e));
  update_irq();
  schedule_due();
}

std::uint32_t EventFifoTarget::fill() {
  admit(now_value());
  return static_cast<std::uint32_t>(fifo_.size());
}

std::uint64_t EventFifoTarget::overflows() {
  admit(now_value());
  return overflows_;
}

EventFifoTarget::Entry EventFifoTarget::entry(const AddressEvent& e) const {
  return {reg::event_word(e.x, e.y, e.tile, (e.flags & kGhostEvent) != 0),
          static_cast<std::uint32_t>(timestamp_ticks(e.t, tick_))};
}

void EventFifoTarget::enter(const Entry& e) {
  if (fifo_.size() >= depth_) {
    ++overflows_;
    overflowed_ = true;
    return;
  }
  fifo_.push_back(e);
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
  admit(now_value() + delay.value());
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
  schedule_due();
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
    case reg::kFill: return static_cast<std::uint32_t>(fifo_.size());
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
  irq_level_ = (irq_enable_ & 1u) != 0 && fifo_.size() >= irq_threshold_;
  // One wake-up of the driver however often the level flips before it runs (a decoupled
  // processor draining the FIFO flips it at every event).
  if (irq_level_ != irq_driven_ && !irq_notified_) {
    irq_notified_ = true;
    irq_changed_.notify(sc_core::SC_ZERO_TIME);
  }
}

void EventFifoTarget::drive_irq() {
  irq_notified_ = false;
  irq_driven_ = irq_level_;
  irq.write(irq_level_);
}

}  // namespace aesim
