// The aesim imager inside a user's own sc_main: the aloha sensor on a scene at the cycle fidelity,
// tile 0's bus wired to a receiver written here, the other tiles to aesim's reference receiver,
// run by this program's sc_start(); what the receivers delivered is written as `aesim run --csv`
// writes it.   usage: embed_example [SCENE [DURATION]] > events.csv
#include <cstdint>
#include <iostream>
#include <memory>

#include <aesim/aesim.hpp>

// A four-phase AER receiver: Req through three flops (the last two decide), Ack raised with the
// address taken and stamped with the tile's tick count, lowered when Req has fallen; a collision
// the bus flagged is acknowledged and dropped; one output register, emptied when the consumer is
// ready. `idle` tells the tile it may stop the clock.
class MyReceiver : public aesim::ReceiverModule {
 public:
  MyReceiver(const sc_core::sc_module_name& name, aesim::ReceiverSignals& s) : ReceiverModule(name), s_(s) {
    SC_METHOD(on_clock);
    sensitive << s.clk.posedge_event();
    dont_initialize();
  }
  SC_HAS_PROCESS(MyReceiver);

 private:
  void on_clock() {
    if (!s_.rst_n.read()) {
      sync_ = 0;
      acking_ = full_ = false;
      events_ = collisions_ = 0;
    } else {
      const bool req_high = (sync_ & 0b110) == 0b110, req_low = (sync_ & 0b110) == 0;
      if (full_ && s_.evt_ready.read()) full_ = false;
      if (!acking_ && req_high) {
        acking_ = true;
        if (s_.contention.read() && s_.discard_collisions.read()) {
          ++collisions_;
        } else {
          full_ = true;
          ++events_;
          beat_addr_ = s_.addr.read();
          beat_ts_ = s_.ts.read();
          beat_flag_ = s_.contention.read();
        }
      } else if (acking_ && req_low) {
        acking_ = false;
      }
      sync_ = ((sync_ << 1) | (s_.req.read() ? 1u : 0u)) & 0b111;
    }
    s_.ack.write(acking_);
    s_.evt_valid.write(full_);
    s_.evt_addr.write(full_ ? beat_addr_ : 0);
    s_.evt_ts.write(full_ ? beat_ts_ : 0);
    s_.evt_flags.write(full_ && beat_flag_);
    s_.events.write(events_);
    s_.collisions.write(collisions_);
    s_.fifo_count.write(full_ ? 1 : 0);
    s_.idle.write(!acking_ && !full_ && sync_ == 0);
  }

  aesim::ReceiverSignals& s_;
  unsigned sync_ = 0;
  bool acking_ = false, full_ = false, beat_flag_ = false;
  std::uint32_t beat_addr_ = 0, beat_ts_ = 0, events_ = 0, collisions_ = 0;
};

int sc_main(int argc, char* argv[]) {
  aesim::ImagerSpec spec;                       // the aloha preset
  if (argc > 1) spec.scene = argv[1];           // default: scenes/letters/A.pgm
  spec.settings = {{"sim.duration", argc > 2 ? argv[2] : "200ms"}};
  spec.receiver = [reference = aesim::reference_receiver_factory()](
                      const std::string& name, std::uint32_t tile, aesim::ReceiverSignals& s,
                      const aesim::ReceiverCycleModel::Config& config) -> std::unique_ptr<aesim::ReceiverModule> {
    if (tile == 0) return std::make_unique<MyReceiver>(name.c_str(), s);
    return reference(name, tile, s, config);
  };
  try {
    aesim::Imager imager("imager", spec);
    sc_core::sc_start();                        // returns when the run is done
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
