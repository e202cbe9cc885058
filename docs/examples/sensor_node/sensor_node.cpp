// The source paper's sensor node, end to end, as a virtual platform in a user's own sc_main: the
// ALOHA imager on a hand sign, the receivers, a memory-mapped event FIFO with an interrupt
// (aesim::EventFifoTarget, TLM-2.0) and the node's processor (aesim::NodeProcessor) running the
// paper's rank-weighted recogniser as timed firmware, reading the FIFO over its socket on the
// interrupt. One scene a run; a CSV row of what the node did on stdout, a summary on stderr.
//
//   usage: sensor_node [--sign NAME | --scene FILE] [--templates FOLDER] [--set KEY=VALUE]...
//                      [--fifo DEPTH] [--clock HZ]
//                      [--cycles-per-template N] [--k K] [--fidelity event|cycle]
//                      [--timing loose|approximate] [--quantum SECONDS] [--csv-header]
//
// At the event fidelity the FIFO takes the event rung's events as a timed stream; at the cycle
// fidelity each tile's receiver (aesim::Receiver on the tile's ports) streams into it.
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

#include <aesim/aesim.hpp>
#include <tlm>

namespace {

struct Options {
  std::string sign = "victory";
  std::string scene, templates;  // empty: the sign's scene; the hand-sign templates
  std::vector<aesim::Setting> settings;
  std::uint32_t fifo = 64;
  aesim::NodeProcessorConfig cpu;
  std::string fidelity = "event";
  double quantum_s = 1e-3;
  bool header = false;
};

double number(const std::string& flag, const std::string& text) {
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || !(v > 0)) throw std::invalid_argument(flag + ": '" + text + "' is not a positive number");
  return v;
}

Options parse(int argc, char* argv[]) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "--csv-header") {
      o.header = true;
      continue;
    }
    if (i + 1 >= argc) throw std::invalid_argument(flag + ": needs a value");
    const std::string value = argv[++i];
    if (flag == "--sign") {
      o.sign = value;
    } else if (flag == "--scene") {
      o.scene = value;
    } else if (flag == "--templates") {
      o.templates = value;
    } else if (flag == "--set") {
      const std::size_t eq = value.find('=');
      if (eq == std::string::npos) throw std::invalid_argument("--set: '" + value + "' is not KEY=VALUE");
      o.settings.push_back({value.substr(0, eq), value.substr(eq + 1)});
    } else if (flag == "--fifo") {
      const double depth = number(flag, value);
      if (depth != static_cast<double>(static_cast<std::uint32_t>(depth))) {
        throw std::invalid_argument("--fifo: '" + value + "' is not a whole number of events");
      }
      o.fifo = static_cast<std::uint32_t>(depth);
    } else if (flag == "--clock") {
      o.cpu.clock_hz = number(flag, value);
    } else if (flag == "--cycles-per-template") {
      o.cpu.cycles_per_template = number(flag, value);
    } else if (flag == "--k") {
      o.cpu.classifier.k = number(flag, value);
    } else if (flag == "--quantum") {
      o.quantum_s = number(flag, value);
    } else if (flag == "--fidelity" && (value == "event" || value == "cycle")) {
      o.fidelity = value;
    } else if (flag == "--timing" && (value == "loose" || value == "approximate")) {
      o.cpu.approximately_timed = value == "approximate";
    } else {
      throw std::invalid_argument("unknown option or value: " + flag + " " + value);
    }
  }
  return o;
}

// One tile's bus and stream wires: aesim's bundled receiver on the tile's ports, its output stream
// into the event FIFO.
struct TileReceiver {
  sc_core::sc_signal<bool> clk, rst_n, req, contention, ack, idle, valid, ready, flags;
  sc_core::sc_signal<std::uint32_t> addr, ts, evt_addr, evt_ts;
  aesim::Receiver receiver;
  aesim::ReceiverStreamFeed feed;

  TileReceiver(aesim::Imager& imager, std::uint32_t t, aesim::EventFifoTarget& fifo)
      : receiver(("rx" + std::to_string(t)).c_str(), imager.receiver_config()),
        feed(("feed" + std::to_string(t)).c_str(), fifo, imager, t) {
    aesim::TilePorts& p = imager.tile[t];
    p.clk(clk), receiver.clk(clk), feed.clk(clk);
    p.rst_n(rst_n), receiver.rst_n(rst_n);
    p.req(req), receiver.req(req);
    p.addr(addr), receiver.addr(addr);
    p.contention(contention), receiver.contention(contention);
    p.ts(ts), receiver.ts(ts);
    p.ack(ack), receiver.ack(ack);
    p.idle(idle), receiver.idle(idle);
    receiver.evt_valid(valid), feed.evt_valid(valid);
    receiver.evt_ready(ready), feed.evt_ready(ready);
    receiver.evt_addr(evt_addr), feed.evt_addr(evt_addr);
    receiver.evt_ts(evt_ts), feed.evt_ts(evt_ts);
    receiver.evt_flags(flags), feed.evt_flags(flags);
  }
};

}  // namespace

int sc_main(int argc, char* argv[]) {
  sc_core::sc_report_handler::set_actions(sc_core::SC_INFO, sc_core::SC_DO_NOTHING);
  try {
    Options o = parse(argc, argv);
    const std::string data = aesim::data_dir();
    const std::vector<aesim::Template> templates =
        aesim::load_templates(o.templates.empty() ? data + "/scenes/templates/hand_signs" : o.templates);
    aesim::ImagerSpec spec;
    spec.scene = o.scene.empty() ? data + "/scenes/hand_signs/" + o.sign + ".pgm" : o.scene;
    if (!o.scene.empty()) o.sign = o.scene;
    spec.settings = o.settings;
    // Loosely timed: the processor runs ahead of the kernel by up to this quantum.
    tlm::tlm_global_quantum::instance().set(sc_core::sc_time(o.quantum_s, sc_core::SC_SEC));

    std::unique_ptr<aesim::EventSource> source;
    std::unique_ptr<aesim::Imager> imager;
    std::unique_ptr<aesim::EventFifoTarget> fifo;
    std::vector<std::unique_ptr<TileReceiver>> tiles;
    const aesim::ResolvedConfig* config = nullptr;
    if (o.fidelity == "event") {
      source = std::make_unique<aesim::EventSource>("imager", spec);
      fifo = std::make_unique<aesim::EventFifoTarget>("fifo", o.fifo, source->tick());
      fifo->deliver(source->events());  // the event rung's events, each entering at its time
      config = &source->config();
    } else {
      spec.settings.push_back({"sim.fidelity", "cycle"});
      // Every tile's receiver outside the Imager, on the tile's ports.
      const aesim::ResolvedConfig c =
          aesim::configure_run(aesim::load_sensor(spec.sensor), aesim::find_scene(spec.scene), spec.settings);
      for (int t = 0; t < aesim::AddressMap(c.array).tiles(); ++t) spec.outside_receivers.push_back(static_cast<std::uint32_t>(t));
      imager = std::make_unique<aesim::Imager>("imager", spec);
      fifo = std::make_unique<aesim::EventFifoTarget>("fifo", o.fifo, imager->tick());
      for (std::uint32_t t = 0; t < imager->tile.size(); ++t) tiles.push_back(std::make_unique<TileReceiver>(*imager, t, *fifo));
      config = &imager->config();
    }
    o.cpu.array_width = config->array.cols;
    o.cpu.array_height = config->array.rows;
    sc_core::sc_signal<bool> irq("irq");
    fifo->irq(irq);
    // The forecast lets the loosely timed processor skip to its interrupt; a FIFO fed at the cycle
    // fidelity does not know its future, so there the processor waits on the line.
    aesim::NodeProcessor cpu("cpu", templates, o.cpu, o.fidelity == "event" ? fifo.get() : nullptr);
    cpu.socket.bind(fifo->socket);
    cpu.irq(irq);

    const double duration = config->sim.duration;
    sc_core::sc_start(sc_core::sc_time(duration, sc_core::SC_SEC));

    const std::vector<aesim::TileCounters> counters = source ? source->tiles() : imager->tiles();
    std::uint64_t delivered = 0;
    for (const aesim::TileCounters& t : counters) delivered += t.delivered;
    if (imager) delivered = std::accumulate(tiles.begin(), tiles.end(), std::uint64_t{0},
                                            [](std::uint64_t n, const auto& t) { return n + t->feed.beats(); });
    const std::vector<aesim::NodeDecision>& decisions = cpu.decisions();
    const aesim::NodeDecision first = decisions.empty() ? aesim::NodeDecision{} : decisions.front();
    const std::string winner = first.winner >= 0 ? templates[static_cast<std::size_t>(first.winner)].name : "";
    if (o.header) {
      std::cout << "sign,fidelity,timing,fifo_depth,clock_hz,cycles_per_template,duration_s,events_delivered,events_per_s,"
                   "decisions,first_winner,first_events_read,first_decision_s,first_recognition_ms,first_lost,"
                   "events_read,events_lost,utilisation\n";
    }
    // A run without a decision leaves the decision's fields empty.
    char first_fields[160] = ",,,,";
    if (!decisions.empty()) {
      std::snprintf(first_fields, sizeof first_fields, "%s,%llu,%.9g,%.9g,%u", winner.c_str(),
                    static_cast<unsigned long long>(first.events_read), first.at_s, first.recognition_s * 1e3,
                    first.overflows);
    }
    std::printf("%s,%s,%s,%u,%.6g,%.6g,%.6g,%llu,%.6g,%zu,%s,%llu,%llu,%.6g\n", o.sign.c_str(), o.fidelity.c_str(),
                o.cpu.approximately_timed ? "approximate" : "loose", o.fifo, o.cpu.clock_hz, o.cpu.cycles_per_template,
                duration, static_cast<unsigned long long>(delivered), static_cast<double>(delivered) / duration,
                decisions.size(), first_fields,
                static_cast<unsigned long long>(cpu.events_read()), static_cast<unsigned long long>(fifo->overflows()),
                cpu.busy_s() / duration);
    std::fprintf(stderr,
                 "sensor_node: %s at the %s fidelity, %.3g s: %llu events delivered (%.4g/s); FIFO of %u, processor at "
                 "%.4g MHz (%s timed)\n",
                 o.sign.c_str(), o.fidelity.c_str(), duration, static_cast<unsigned long long>(delivered),
                 static_cast<double>(delivered) / duration, o.fifo, o.cpu.clock_hz / 1e6,
                 o.cpu.approximately_timed ? "approximately" : "loosely");
    if (decisions.empty()) {
      std::fprintf(stderr, "  no decision within the scene\n");
    } else {
      std::fprintf(stderr,
                   "  first decision: %s after %llu events at %.4g s, %.4g ms of recognition; %u events lost by then\n",
                   winner.c_str(), static_cast<unsigned long long>(first.events_read), first.at_s,
                   first.recognition_s * 1e3, first.overflows);
    }
    std::fprintf(stderr, "  %zu decisions; %llu events read, %llu lost in the FIFO; processor busy %.3g %% of the time\n",
                 decisions.size(), static_cast<unsigned long long>(cpu.events_read()),
                 static_cast<unsigned long long>(fifo->overflows()), 100 * cpu.busy_s() / duration);
    std::fprintf(stderr, "  the paper's inputs (1281.8 events x %zu templates x %.4g cycles at %.4g MHz): %.4g ms\n",
                 templates.size(), o.cpu.cycles_per_template, o.cpu.clock_hz / 1e6,
                 aesim::recognition_seconds(1281.8, templates.size(), o.cpu.cycles_per_template, o.cpu.clock_hz) * 1e3);
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "sensor_node: " << e.what() << "\n";
    return 2;
  }
}
