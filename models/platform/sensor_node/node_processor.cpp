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
  socket.register_nb_transport_bw(this, &NodeProcessor::nb_transport_bw);
  SC_THREAD(firmware);
}

sc_core::sc_time NodeProcessor::local_now() const {
  return config_.approximately_timed ? sc_core::sc_time_stamp() : sc_core::sc_time_stamp() + keeper_.get_local_time();
}

void NodeProcessor::compute(double cycles) {
  if (cycles <= 0) return;
  const sc_core::sc_time t(cycles / config_.clock_hz, sc_core::SC_SEC);
  busy_s_ += t.to_seconds();
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
  tlm::tlm_generic_payload t;
  t.set_command(command);
  t.set_address(offset);
  t.set_data_ptr(data);
  t.set_data_length(4);
  t.set_streaming_width(4);
  t.set_byte_enable_ptr(nullptr);
  t.set_dmi_allowed(false);
  t.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
  const sc_core::sc_time before = local_now();
  if (config_.approximately_timed) {
    tlm::tlm_phase phase = tlm::BEGIN_REQ;
    sc_core::sc_time delay = sc_core::SC_ZERO_TIME;
    const tlm::tlm_sync_enum sync = socket->nb_transport_fw(t, phase, delay);
    if (sync == tlm::TLM_COMPLETED || (sync == tlm::TLM_UPDATED && phase == tlm::BEGIN_RESP)) {
      sc_core::wait(delay);
    } else {
      sc_core::wait(response_);
    }
  } else {
    sc_core::sc_time delay = keeper_.get_local_time();
    socket->b_transport(t, delay);
    keeper_.set(delay);
  }
  busy_s_ += (local_now() - before).to_seconds();
  if (!t.is_response_ok()) {
    SC_REPORT_ERROR("aesim/NodeProcessor", fmt::format("access to the event FIFO at 0x{:02X} failed: {}", offset,
                                                       t.get_response_string()).c_str());
  }
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
  compute(config_.isr_cycles);
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
  positions_.push_back(p);
  if (config_.classifier.center_events == 0 || centred_) {
    score(p);
    return;
  }
  buffer_.push_back(p);
  if (buffer_.size() < config_.classifier.center_events) return;
  double sx = 0, sy = 0;
  for (const auto& [x, y] : buffer_) {
    sx += x;
    sy += y;
  }
  recogniser_->centre_on(sx / static_cast<double>(buffer_.size()), sy / static_cast<double>(buffer_.size()));
  centred_ = true;
  const std::vector<std::pair<double, double>> centring = std::move(buffer_);
  buffer_.clear();
  for (const auto& q : centring) {
    if (score(q)) break;
  }
}

bool NodeProcessor::score(const std::pair<double, double>& p) {
  const double cycles = config_.cycles_per_template * static_cast<double>(templates_.size());
  compute(cycles);
  recognition_s_ += cycles / config_.clock_hz;
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
  d.recognition_s = recognition_s_;
  d.overflows = access(tlm::TLM_READ_COMMAND, reg::kOverflows);
  decisions_.push_back(d);
  if (!config_.keep_recognising) {
    stopped_ = true;
    return;
  }
  recogniser_.emplace(templates_, config_.classifier);
  centred_ = false;
  buffer_.clear();
  recognition_read_ = recognition_scored_ = 0;
  recognition_s_ = 0;
}

}  // namespace aesim
