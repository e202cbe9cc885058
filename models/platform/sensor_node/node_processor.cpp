#include "aesim/sensor_node/node_processor.hpp"

#include <cmath>
#include <cstring>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"

namespace aesim {

namespace reg = event_fifo;

double recognition_seconds(double events, std::size_t templates, double cycles_per_template, double clock_hz) {
  return events * static_cast<double>(templates) * cycles_per_template / clock_hz;
}

NodeProcessor::NodeProcessor(const sc_core::sc_module_name& name, const std::vector<Template>& templates,
                             const NodeProcessorConfig& config, EventFifoTarget* forecast)
    : sc_module(name), templates_(templates), config_(config), forecast_(forecast) {
  if (!(config_.clock_hz > 0) || !std::isfinite(config_.clock_hz)) throw InputError("NodeProcessor: the clock must be positive");
  if (!(config_.cycles_per_template >= 0) || !std::isfinite(config_.cycles_per_template) || !(config_.isr_cycles >= 0) ||
      !std::isfinite(config_.isr_cycles)) {
    throw InputError("NodeProcessor: cycle counts must be finite and not negative");
  }
  if (config_.array_width < 1 || config_.array_height < 1) throw InputError("NodeProcessor: the array size must be positive");
  if (templates_.size() < 2) throw InputError("NodeProcessor: the recogniser needs at least two templates");
  recogniser_.emplace(templates_, config_.classifier);
  per_event_ = sc_core::sc_time(config_.cycles_per_template * static_cast<double>(templates_.size()) / config_.clock_hz,
                                sc_core::SC_SEC);
  per_interrupt_ = sc_core::sc_time(config_.isr_cycles / config_.clock_hz, sc_core::SC_SEC);
  socket.register_nb_transport_bw(this, &NodeProcessor::nb_transport_bw);
  SC_THREAD(firmware);
}

sc_core::sc_time NodeProcessor::local_now() const {
  return config_.approximately_timed ? sc_core::sc_time_stamp() : sc_core::sc_time_stamp() + keeper_.get_local_time();
}

void NodeProcessor::compute(const sc_core::sc_time& t) {
  if (t == sc_core::SC_ZERO_TIME) return;
  busy_ += t;
  if (config_.approximately_timed) {
    sc_core::wait(t);
    return;
  }
  keeper_.inc(t);
  if (keeper_.need_sync()) keeper_.sync();
}

tlm::tlm_sync_enum NodeProcessor::nb_transport_bw(tlm::tlm_generic_payload&, tlm::tlm_phase& phase,
                                                  sc_core::sc_time& delay) {
  if (phase == tlm::BEGIN_RESP) {
    response_.notify(delay);
    return tlm::TLM_COMPLETED;
  }
  return tlm::TLM_ACCEPTED;  // END_REQ: the response follows
}

std::uint32_t NodeProcessor::access(tlm::tlm_command command, std::uint32_t offset, std::uint32_t value) {
  unsigned char data[4];
  std::memcpy(data, &value, 4);
  // One payload for every access (its extension array is allocated once, not per access); the
  // fields a target may change are set again each time.
  tlm::tlm_generic_payload& t = payload_;
  t.set_command(command);
  t.set_address(offset);
  t.set_data_ptr(data);
  t.set_data_length(4);
  t.set_streaming_width(4);
  t.set_byte_enable_ptr(nullptr);
  t.set_dmi_allowed(false);
  t.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
  if (config_.approximately_timed) {
    const sc_core::sc_time before = sc_core::sc_time_stamp();
    tlm::tlm_phase phase = tlm::BEGIN_REQ;
    sc_core::sc_time delay = sc_core::SC_ZERO_TIME;
    const tlm::tlm_sync_enum sync = socket->nb_transport_fw(t, phase, delay);
    if (sync == tlm::TLM_COMPLETED || (sync == tlm::TLM_UPDATED && phase == tlm::BEGIN_RESP)) {
      sc_core::wait(delay);
    } else {
      sc_core::wait(response_);
    }
    busy_ += sc_core::sc_time_stamp() - before;
  } else {
    const sc_core::sc_time before = keeper_.get_local_time();
    sc_core::sc_time delay = before;
    socket->b_transport(t, delay);
    keeper_.set(delay);
    busy_ += delay - before;
  }
  if (!t.is_response_ok()) {
    SC_REPORT_ERROR("aesim/NodeProcessor", fmt::format("access to the event FIFO at 0x{:02X} failed: {}", offset,
                                                       t.get_response_string()).c_str());
  }
  t.set_data_ptr(nullptr);
  std::memcpy(&value, data, 4);
  return value;
}

void NodeProcessor::wait_for_interrupt() {
  if (!config_.approximately_timed) {
    if (forecast_) {
      const sc_core::sc_time now = local_now();
      if (const std::optional<sc_core::sc_time> due = forecast_->irq_due(now)) {
        if (*due > now) keeper_.set(*due - sc_core::sc_time_stamp());
        if (keeper_.need_sync()) keeper_.sync();
        return;
      }
    }
    keeper_.sync();
  }
  if (!irq.read()) sc_core::wait(irq.posedge_event());
}

void NodeProcessor::firmware() {
  keeper_.reset();
  access(tlm::TLM_WRITE_COMMAND, reg::kIrqThreshold, config_.irq_threshold);
  access(tlm::TLM_WRITE_COMMAND, reg::kIrqEnable, 1);
  while (!stopped_) {
    wait_for_interrupt();
    handle_interrupt();
  }
  access(tlm::TLM_WRITE_COMMAND, reg::kIrqEnable, 0);
  if (!config_.approximately_timed) keeper_.sync();
}

void NodeProcessor::handle_interrupt() {
  ++interrupts_;
  compute(per_interrupt_);
  const std::uint32_t held = access(tlm::TLM_READ_COMMAND, reg::kFill);
  for (std::uint32_t i = 0; i < held && !stopped_; ++i) take(access(tlm::TLM_READ_COMMAND, reg::kEvent));
}

void NodeProcessor::take(std::uint32_t word) {
  if (word == reg::kEmptyEvent || reg::event_ghost(word)) return;
  const std::pair<double, double> p =
      template_position(reg::event_x(word), reg::event_y(word), config_.array_width, config_.array_height,
                        templates_.front().width, templates_.front().height);
  ++events_read_;
  ++recognition_read_;
  if (config_.record_positions) positions_.push_back(p);
  if (config_.classifier.center_events == 0 || centred_) {
    score(p);
    return;
  }
  // The paper's accounting charges every event read the recogniser's cycles, centring ones too.
  if (config_.charge_centring) charge_recognition();
  centre_x_ += p.first;
  centre_y_ += p.second;
  // Until centred, every event this recognition read was a centring one.
  if (recognition_read_ < config_.classifier.center_events) return;
  recogniser_->centre_on(centre_x_ / static_cast<double>(recognition_read_), centre_y_ / static_cast<double>(recognition_read_));
  centred_ = true;
}

void NodeProcessor::charge_recognition() {
  compute(per_event_);
  ++recognition_charged_;
}

bool NodeProcessor::score(const std::pair<double, double>& p) {
  charge_recognition();
  ++recognition_scored_;
  if (!recogniser_->add(p.first, p.second)) return false;
  decide();
  return true;
}

void NodeProcessor::decide() {
  NodeDecision d;
  d.winner = recogniser_->result().winner;
  d.events_read = recognition_read_;
  d.events_scored = recognition_scored_;
  d.at_s = local_now().to_seconds();
  // The cycles' own time, not the kernel's rounding of each event's to its resolution.
  d.recognition_s = recognition_seconds(static_cast<double>(recognition_charged_), templates_.size(),
                                        config_.cycles_per_template, config_.clock_hz);
  d.overflows = access(tlm::TLM_READ_COMMAND, reg::kOverflows);
  decisions_.push_back(d);
  if (!config_.keep_recognising) {
    stopped_ = true;
    return;
  }
  recogniser_.emplace(templates_, config_.classifier);
  centred_ = false;
  centre_x_ = centre_y_ = 0;
  recognition_read_ = recognition_scored_ = recognition_charged_ = 0;
}

}  // namespace aesim
