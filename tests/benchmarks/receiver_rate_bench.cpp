// Receiver clock cycles per wall second with the RTL in the loop (scripts/bench prints the
// ratios): the bundled receiver, Verilated at run time as `aesim verify` builds it, under
//  - a plain C++ eval() loop: the clock toggled and nothing else (the ceiling);
//  - the verify driver on a scene run (medium load, the consumer ready 90 % of the time), without
//    and with the transaction scoreboard.
// The SystemC cycle rung with the same RTL is BM_CycleFreeRunningClock/Rtl in event_rate_bench.
#include <cstdlib>
#include <memory>

#include <benchmark/benchmark.h>

#include "build/dut_build.hpp"
#include "description/receiver_description.hpp"
#include "driver/bound_ports.hpp"
#include "driver/case_driver.hpp"
#include "driver/dut_library.hpp"
#include "scoreboard/transaction_scoreboard.hpp"
#include "stimulus/scene_cases.hpp"

namespace aesim {
namespace {

struct Receiver {
  ReceiverDescription d;
  DutBuild build;
  std::unique_ptr<DutLibrary> library;
  VerifyCase scene;
};

const Receiver& receiver() {
  static const Receiver r = [] {
    Receiver out;
    out.d = read_receiver_description(AESIM_SOURCE_DIR "/rtl/aer_receiver.toml");
    DutBuildOptions options;
    options.cache_dir = std::getenv("AESIM_CACHE_DIR") ? default_cache_dir() : AESIM_VERIFY_CACHE;
    options.progress = false;
    out.build = build_dut(out.d, options);
    out.library = std::make_unique<DutLibrary>(out.build.library);
    out.scene = scene_case({AESIM_SOURCE_DIR "/scenes/letters/A.pgm", 0.3, 1, 20000, 0.9}, out.d);
    return out;
  }();
  return r;
}

void BM_PlainEvalLoop(benchmark::State& state) {
  const Receiver& r = receiver();
  DutInstance dut(*r.library, false);
  const BoundPorts ports = bind_ports(dut, r.d, r.build.ports);
  ports.set_reset(true);
  dut.eval();
  ports.set_reset(false);
  ports.set_ready(true);
  constexpr int kCycles = 1000000;
  for (auto _ : state) {
    for (int i = 0; i < kCycles; ++i) {
      ports.clk.write(1);
      dut.eval();
      ports.clk.write(0);
      dut.eval();
    }
  }
  state.counters["cycles_per_s"] = benchmark::Counter(static_cast<double>(state.iterations()) * kCycles,
                                                      benchmark::Counter::kIsRate);
}

void BM_VerifyDriver(benchmark::State& state, bool scoreboard) {
  const Receiver& r = receiver();
  TransactionScoreboard sb(r.d, true, 32);
  double cycles = 0, transactions = 0;
  for (auto _ : state) {
    DutInstance dut(*r.library, false);
    const BoundPorts ports = bind_ports(dut, r.d, r.build.ports);
    cycles += static_cast<double>(run_case(dut, ports, r.d, r.scene, scoreboard ? &sb : nullptr).edges);
  }
  transactions = static_cast<double>(sb.transactions());
  if (sb.failures()) state.SkipWithError("the scoreboard failed the bundled receiver");
  state.counters["cycles_per_s"] = benchmark::Counter(cycles, benchmark::Counter::kIsRate);
  if (scoreboard) state.counters["transactions_per_s"] = benchmark::Counter(transactions, benchmark::Counter::kIsRate);
}

BENCHMARK(BM_PlainEvalLoop)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK_CAPTURE(BM_VerifyDriver, bare, false)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK_CAPTURE(BM_VerifyDriver, scoreboard, true)->Unit(benchmark::kMillisecond)->MinTime(2.0);

}  // namespace
}  // namespace aesim
