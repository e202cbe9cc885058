#include "aesim/embed/tile_ports.hpp"

#include <string>

#include <fmt/format.h>

#include "aesim/tile/cycle_tile.hpp"

namespace aesim {
namespace {

constexpr const char* kReportId = "aesim/Imager";

// A method process that copies `from` to `to` whenever it changes (and once at the start). Each
// hop costs one delta cycle in both directions and on the clock alike, so the receiver sees the
// same order of edges and values as one inside the tile.
template <class T>
void forward(const sc_core::sc_signal_in_if<T>& from, sc_core::sc_signal_inout_if<T>& to, const std::string& name) {
  sc_core::sc_spawn_options options;
  options.spawn_method();
  options.set_sensitivity(&from.value_changed_event());
  sc_core::sc_spawn([&from, &to] { to.write(from.read()); }, name.c_str(), &options);
}

template <class T>
void drive(OptionalOut<T>& port, const sc_core::sc_signal_in_if<T>& wire, const char* name) {
  if (port.size() > 0) forward(wire, *port[0], std::string("to_") + name);
}

template <class T>
void take(OptionalIn<T>& port, sc_core::sc_signal_inout_if<T>& wire, const char* name) {
  if (port.size() > 0) forward(*port[0], wire, std::string("from_") + name);
}

}  // namespace

TilePorts::TilePorts(const sc_core::sc_module_name& name)
    : sc_module(name),
      clk("clk"),
      rst_n("rst_n"),
      req("req"),
      contention("contention"),
      addr("addr"),
      ack("ack"),
      ts("ts"),
      prescale("prescale"),
      fifo_limit("fifo_limit"),
      discard_collisions("discard_collisions"),
      ts_external("ts_external"),
      idle("idle"),
      evt_valid("evt_valid"),
      evt_flags("evt_flags"),
      evt_addr("evt_addr"),
      evt_ts("evt_ts"),
      evt_ready("evt_ready"),
      events("events"),
      fifo_count("fifo_count") {}

void TilePorts::attach(CycleTile& tile, std::uint32_t index, double duration) {
  tile_ = &tile;
  index_ = index;
  duration_ = duration;
}

bool TilePorts::any_bound() const {
  const auto bound = [](const auto&... ports) { return ((ports.size() > 0) || ...); };
  return bound(clk, rst_n, req, contention, addr, ack, ts, prescale, fifo_limit, discard_collisions, ts_external,
               idle, evt_valid, evt_flags, evt_addr, evt_ts, evt_ready, events, fifo_count);
}

void TilePorts::end_of_elaboration() {
  if (!tile_) return;
  if (!tile_->receiver_outside()) {
    if (any_bound()) {
      SC_REPORT_ERROR(kReportId, fmt::format("{} is bound, but tile {} has aesim's receiver: name the tile in "
                                             "ImagerSpec::outside_receivers to connect a receiver of your own",
                                             name(), index_)
                                     .c_str());
    }
    return;
  }
  if (ack.size() == 0) {
    SC_REPORT_ERROR(kReportId, fmt::format("{}.ack is not bound: tile {}'s receiver is outside the Imager "
                                           "(ImagerSpec::outside_receivers), so its Ack must be connected",
                                           name(), index_)
                                   .c_str());
  }
  ReceiverSignals& w = tile_->wires();
  drive(clk, w.clk, "clk");
  drive(rst_n, w.rst_n, "rst_n");
  drive(req, w.req, "req");
  drive(contention, w.contention, "contention");
  drive(addr, w.addr, "addr");
  drive(ts, w.ts, "ts");
  drive(prescale, w.prescale, "prescale");
  drive(fifo_limit, w.fifo_limit, "fifo_limit");
  drive(discard_collisions, w.discard_collisions, "discard_collisions");
  drive(ts_external, w.ts_external, "ts_external");
  drive(evt_ready, w.evt_ready, "evt_ready");
  take(ack, w.ack, "ack");
  take(idle, w.idle, "idle");
  take(evt_valid, w.evt_valid, "evt_valid");
  take(evt_flags, w.evt_flags, "evt_flags");
  take(evt_addr, w.evt_addr, "evt_addr");
  take(evt_ts, w.evt_ts, "evt_ts");
  take(events, w.events, "events");
  take(fifo_count, w.fifo_count, "fifo_count");
  tile_->outside_receiver_reports(idle.size() > 0, events.size() > 0 && fifo_count.size() > 0,
                                  sc_core::sc_time(duration_, sc_core::SC_SEC));
}

}  // namespace aesim
