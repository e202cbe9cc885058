// The aesim imager inside a user's own sc_main: the aloha sensor on a scene at the cycle fidelity,
// tile 0's bus wired through sc_signals to a receiver written here (plain sc_in/sc_out ports, as a
// SystemC model or a `verilator --sc` module has), tile 1's to aesim's bundled receiver
// (aesim::Receiver) the same way, the other tiles with the receiver inside the Imager, run by this
// program's sc_start(); what the receivers delivered is written as `aesim run --csv` writes it,
// and with a third argument the bus wires go to the VCD file WAVES.vcd (sc_trace).
//   usage: embed_example [SCENE [DURATION [WAVES]]] > events.csv
#include <cstdint>
#include <iostream>

#include <aesim/aesim.hpp>

// A four-phase AER receiver: Req through three flops (the last two decide), Ack raised with the
// address taken and stamped with the tile's tick count, lowered when Req has fallen; a collision
// the bus flagged is acknowledged and dropped; one output register, emptied when the consumer is
// ready. `idle` tells the tile it may stop the clock.
SC_MODULE(MyReceiver) {
  sc_core::sc_in<bool> clk, rst_n, req, contention, evt_ready;
  sc_core::sc_in<std::uint32_t> addr, ts;
  sc_core::sc_out<bool> ack, idle, evt_valid, evt_flags;
  sc_core::sc_out<std::uint32_t> evt_addr, evt_ts;

  SC_CTOR(MyReceiver) {
    SC_METHOD(on_clock);
    sensitive << clk.pos();
    dont_initialize();
  }

  void on_clock() {
    if (!rst_n.read()) {
      sync_ = 0;
      acking_ = full_ = false;
    } else {
      const bool req_high = (sync_ & 0b110) == 0b110, req_low = (sync_ & 0b110) == 0;
      if (full_ && evt_ready.read()) full_ = false;
      if (!acking_ && req_high) {
        acking_ = true;
        if (!contention.read()) {
          full_ = true;
          addr_ = addr.read();
          ts_ = ts.read();
        }
      } else if (acking_ && req_low) {
        acking_ = false;
      }
      sync_ = ((sync_ << 1) | (req.read() ? 1u : 0u)) & 0b111;
    }
    ack.write(acking_);
    evt_valid.write(full_);
    evt_addr.write(full_ ? addr_ : 0);
    evt_ts.write(full_ ? ts_ : 0);
    evt_flags.write(false);
    idle.write(!acking_ && !full_ && sync_ == 0);
  }

  unsigned sync_ = 0;
  bool acking_ = false, full_ = false;
  std::uint32_t addr_ = 0, ts_ = 0;
};

int sc_main(int argc, char* argv[]) {
  aesim::ImagerSpec spec;                       // the aloha preset
  if (argc > 1) spec.scene = argv[1];           // default: scenes/letters/A.pgm
  spec.settings = {{"sim.duration", argc > 2 ? argv[2] : "200ms"}};
  spec.outside_receivers = {0, 1};              // tiles 0 and 1: receivers on the tile's ports
  // SystemC prints its notes (a trace file's time unit, ...) on stdout, where the CSV goes.
  sc_core::sc_report_handler::set_actions(sc_core::SC_INFO, sc_core::SC_DO_NOTHING);
  try {
    aesim::Imager imager("imager", spec);
    MyReceiver rx("my_receiver");
    sc_core::sc_signal<bool> clk, rst_n, req, contention, ack, idle, valid, ready, flags;
    sc_core::sc_signal<std::uint32_t> addr, ts, evt_addr, evt_ts;
    aesim::TilePorts& tile0 = imager.tile[0];
    tile0.clk(clk), rx.clk(clk);
    tile0.rst_n(rst_n), rx.rst_n(rst_n);
    tile0.req(req), rx.req(req);
    tile0.addr(addr), rx.addr(addr);
    tile0.contention(contention), rx.contention(contention);
    tile0.ts(ts), rx.ts(ts);
    tile0.ack(ack), rx.ack(ack);
    tile0.idle(idle), rx.idle(idle);                // optional: lets the tile stop the clock
    tile0.evt_valid(valid), rx.evt_valid(valid);    // optional: the tile collects the stream
    tile0.evt_ready(ready), rx.evt_ready(ready);
    tile0.evt_addr(evt_addr), rx.evt_addr(evt_addr);
    tile0.evt_ts(evt_ts), rx.evt_ts(evt_ts);
    tile0.evt_flags(flags), rx.evt_flags(flags);

    aesim::Receiver bundled("bundled_receiver", imager.receiver_config());
    sc_core::sc_signal<bool> clk1, rst_n1, req1, contention1, ack1, idle1, valid1, ready1, flags1;
    sc_core::sc_signal<std::uint32_t> addr1, ts1, evt_addr1, evt_ts1;
    aesim::TilePorts& tile1 = imager.tile[1];
    tile1.clk(clk1), bundled.clk(clk1);
    tile1.rst_n(rst_n1), bundled.rst_n(rst_n1);
    tile1.req(req1), bundled.req(req1);
    tile1.addr(addr1), bundled.addr(addr1);
    tile1.contention(contention1), bundled.contention(contention1);
    tile1.ts(ts1), bundled.ts(ts1);
    tile1.ack(ack1), bundled.ack(ack1);
    tile1.idle(idle1), bundled.idle(idle1);
    tile1.evt_valid(valid1), bundled.evt_valid(valid1);
    tile1.evt_ready(ready1), bundled.evt_ready(ready1);
    tile1.evt_addr(evt_addr1), bundled.evt_addr(evt_addr1);
    tile1.evt_ts(evt_ts1), bundled.evt_ts(evt_ts1);
    tile1.evt_flags(flags1), bundled.evt_flags(flags1);

    sc_core::sc_trace_file* waves = argc > 3 ? sc_core::sc_create_vcd_trace_file(argv[3]) : nullptr;
    if (waves) imager.trace(waves);
    sc_core::sc_start();                        // returns when the run is done
    if (waves) sc_core::sc_close_vcd_trace_file(waves);
    aesim::write_events_csv(std::cout, imager.events(), imager.tick());
    std::uint64_t fired = 0, collided = 0;
    for (const aesim::TileCounters& t : imager.tiles()) {
      fired += t.fired;
      collided += t.collided;
    }
    std::cerr << "embed_example: " << imager.events().size() << " events delivered of " << fired << " fired, "
              << collided << " lost to collisions, " << imager.protocol_violations() << " protocol violations, at "
              << sc_core::sc_time_stamp() << "\n";
    return imager.protocol_violations() == 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "embed_example: " << e.what() << "\n";
    return 2;
  }
}
