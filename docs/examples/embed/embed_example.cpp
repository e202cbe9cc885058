// The aesim imager inside a user's own sc_main: the aloha sensor on a scene at the cycle fidelity,
// run by this program's sc_start(), and what the four tiles' receivers delivered written as
// `aesim run --csv` writes it.   usage: embed_example [SCENE [DURATION]] > events.csv
#include <iostream>

#include <aesim/aesim.hpp>

int sc_main(int argc, char* argv[]) {
  aesim::ImagerSpec spec;                       // the aloha preset
  if (argc > 1) spec.scene = argv[1];           // default: scenes/letters/A.pgm
  spec.settings = {{"sim.duration", argc > 2 ? argv[2] : "200ms"}};
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
              << collided << " lost to collisions, at " << sc_core::sc_time_stamp() << "\n";
  } catch (const std::exception& e) {
    std::cerr << "embed_example: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
