#pragma once
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include <systemc>
#include <tlm>
#include <tlm_utils/simple_initiator_socket.h>
#include <tlm_utils/tlm_quantumkeeper.h>

#include "aesim/classify/template_classifier.hpp"
#include "aesim/embed/event_fifo_target.hpp"

namespace aesim {

// The processor of the source paper's sensor node and its firmware, timed. Defaults are the paper's:
// the XYZ node's ARM7TDMI at 57.6 MHz, 100 cycles per template per event, the subject centred on its
// first 1000 events.
struct NodeProcessorConfig {
  double clock_hz = 57.6e6;
  double cycles_per_template = 100;  // one event against one template
  double isr_cycles = 0;             // entering and leaving the interrupt handler, once per interrupt
  std::uint32_t irq_threshold = 1;   // events in the FIFO that raise the interrupt
  // Loosely timed (false): blocking transport with the cycles annotated and the kernel met once a
  // quantum (tlm_global_quantum); approximately timed (true): non-blocking transport, each access's
  // response and each computation waited for.
  bool approximately_timed = false;
  // The recogniser: k, max_events, center_events (the subject's centroid from its first N events,
  // then every template compared as if centred: center_templates), ranks. The paper's: centred on
  // 1000 events; k as `aesim classify` takes it.
  ClassifierOptions classifier = [] {
    ClassifierOptions o;
    o.center_events = 1000;
    o.center_templates = true;
    return o;
  }();
  int array_width = 64, array_height = 64;  // event coordinates are scaled onto the templates
  bool keep_recognising = true;             // after a decision, start again on the next events
  // The paper's accounting (its 1281.8 events x 6 templates x 100 cycles): the centring events cost
  // the recogniser's cycles too. False: they cost nothing (a centroid's two additions).
  bool charge_centring = true;
  bool record_positions = false;  // keep every event read (read_positions()), for checks
};

// What the firmware concluded, once per decision.
struct NodeDecision {
  int winner = -1;                  // template index
  std::uint64_t events_read = 0;    // events taken from the FIFO for this recognition (ghosts skipped)
  std::uint64_t events_scored = 0;  // of them, run through the recogniser (the rest were centring)
  double at_s = 0;                  // simulation time of the decision
  double recognition_s = 0;         // processor time charged for this recognition's events
  std::uint32_t overflows = 0;      // the FIFO's kOverflows, read by the firmware at the decision
};

// The cycles of the paper's recogniser: `events` events against `templates` templates at
// `cycles_per_template` each, in seconds at `clock_hz`. The firmware charges exactly this per event.
double recognition_seconds(double events, std::size_t templates, double cycles_per_template, double clock_hz);

// A processor model whose firmware reads the event FIFO on its interrupt and runs aesim's
// RankRecogniser on each event, charging the recogniser's cycles. Interrupt handler: read kFill,
// then kEvent that many times; a ghost (a collision's corrupted address) is skipped. Recognition,
// as the paper's node does it: the first center_events events find the subject's centre (their
// mean), then every later event is scored until a template leads by k r_max (RankRecogniser); a
// decision starts a new recognition (centring again) from the next event when keep_recognising.
// Bind `socket` to the FIFO's socket and `irq` to its interrupt line.
//
// Loosely timed, the processor runs ahead of the kernel by up to the global quantum; while it waits
// for its interrupt it asks the FIFO when the line will rise (EventFifoTarget::irq_due, exact for
// a FIFO fed by a timed stream and read by this processor alone) and skips there, meeting the
// kernel only when the quantum is used up; so a run costs a kernel switch a quantum, not an event.
// Approximately timed, every access and computation is waited for; both give the same decisions,
// times and losses.
class NodeProcessor : public sc_core::sc_module {
 public:
  tlm_utils::simple_initiator_socket<NodeProcessor> socket{"socket"};
  sc_core::sc_in<bool> irq{"irq"};

  NodeProcessor(const sc_core::sc_module_name& name, const std::vector<Template>& templates,
                const NodeProcessorConfig& config, EventFifoTarget* forecast = nullptr);
  SC_HAS_PROCESS(NodeProcessor);

  const std::vector<NodeDecision>& decisions() const { return decisions_; }
  std::uint64_t events_read() const { return events_read_; }
  std::uint64_t interrupts() const { return interrupts_; }
  // Time the processor was not waiting for its interrupt (computing or on the bus), s.
  double busy_s() const { return busy_.to_seconds(); }
  // With record_positions, the positions (template coordinates) of every event read, in order:
  // what the recogniser saw.
  const std::vector<std::pair<double, double>>& read_positions() const { return positions_; }

 private:
  void firmware();
  void wait_for_interrupt();
  void handle_interrupt();
  void take(std::uint32_t word);
  // Scores one event; true when it decided.
  bool score(const std::pair<double, double>& p);
  void charge_recognition();
  void decide();
  void compute(const sc_core::sc_time& t);
  std::uint32_t access(tlm::tlm_command command, std::uint32_t offset, std::uint32_t value = 0);
  sc_core::sc_time local_now() const;
  tlm::tlm_sync_enum nb_transport_bw(tlm::tlm_generic_payload& trans, tlm::tlm_phase& phase, sc_core::sc_time& delay);

  const std::vector<Template>& templates_;
  NodeProcessorConfig config_;
  EventFifoTarget* forecast_;
  tlm_utils::tlm_quantumkeeper keeper_;
  tlm::tlm_generic_payload payload_;
  sc_core::sc_time per_event_, per_interrupt_;  // the recogniser's cycles for one event; the handler's
  sc_core::sc_event response_;
  std::optional<RankRecogniser> recogniser_;
  bool centred_ = false, stopped_ = false;
  std::vector<std::pair<double, double>> positions_;
  double centre_x_ = 0, centre_y_ = 0;
  // This recognition's events: read, scored, and charged the recogniser's cycles.
  std::uint64_t recognition_read_ = 0, recognition_scored_ = 0, recognition_charged_ = 0;
  sc_core::sc_time busy_ = sc_core::SC_ZERO_TIME;
  std::uint64_t events_read_ = 0, interrupts_ = 0;
  std::vector<NodeDecision> decisions_;
};

}  // namespace aesim
