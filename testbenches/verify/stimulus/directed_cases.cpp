#include "stimulus/directed_cases.hpp"

#include "driver/case_driver.hpp"

namespace aesim {

std::vector<VerifyCase> directed_cases(const ReceiverDescription& d) {
  const std::uint64_t period = clock_period_ps(d);
  // A time `frac` of a period after rising edge `edge` (never on an edge).
  auto at = [period](std::uint64_t edge, double frac) {
    return edge * period + static_cast<std::uint64_t>(frac * static_cast<double>(period));
  };
  const std::uint64_t lat = static_cast<std::uint64_t>(d.ack_latency_max);
  const std::uint64_t handshake = 2 * lat + 4;  // edges one transaction may take
  auto listed = [](std::vector<Firing> f) {
    return [f] { return std::make_unique<ListedFirings>(f); };
  };
  std::vector<VerifyCase> cases;
  auto add = [&](const char* name, std::vector<Firing> firings, std::uint64_t edges) -> VerifyCase& {
    VerifyCase c;
    c.name = name;
    c.kind = "directed";
    c.expected_firings = static_cast<double>(firings.size());
    c.make_firings = listed(std::move(firings));
    c.max_edges = edges + 20 * handshake + 200;
    cases.push_back(std::move(c));
    return cases.back();
  };

  add("single_event", {{at(10, 0.3), 0x2A5}}, 10);

  std::vector<Firing> burst;
  for (std::uint32_t i = 0; i < 16; ++i) burst.push_back({at(10, 0.3) + i, (i * 0x47u + 1u) & 0x3FFu});
  add("back_to_back", burst, 16 * handshake).queued_senders = true;

  VerifyCase& glitch = add("req_glitch", {{at(20 + handshake, 0.3), 0x0AA}}, 20 + handshake);
  glitch.glitches.push_back({at(9, 0.75), at(10, 0.25), 0x155});  // half a period across edge 10

  add("collision", {{at(10, 0.2), 0x0F0}, {at(10, 0.6), 0x00F}}, 10);

  // A pixel that fires while the receiver is still in reset and holds Req through its release:
  // the receiver sees it as soon as it may (at once, if its first synchroniser flop has no reset).
  add("req_through_reset", {{at(1, 0.4), 0x13C}}, 10);

  VerifyCase& reset = add("reset_mid_handshake", {{at(10, 0.3), 0x2A5}, {at(40 + 2 * handshake, 0.3), 0x15A}},
                          40 + 2 * handshake);
  reset.reset_after_ack = 1;
  reset.reset_delay = 1;  // Ack is high and due to fall
  reset.reset_edges = 4;

  std::vector<Firing> twelve(burst.begin(), burst.begin() + 12);
  VerifyCase& backpressure = add("long_backpressure", twelve, 12 * handshake + 2000);
  backpressure.queued_senders = true;
  backpressure.stalls.push_back({5, 2000});

  std::vector<Firing> many;
  for (std::uint32_t i = 0; i < 200; ++i) many.push_back({at(10, 0.3) + i, (i * 0x35u + 3u) & 0x3FFu});
  VerifyCase& full = add("full_output", many, 400 * handshake);
  full.queued_senders = true;
  full.stalls.push_back({5, 5 + 200 * handshake});

  // The output filled with its pointers at many offsets: k transactions taken first (a FIFO's
  // pointers moved on, past their first wrap once k reaches its depth), then 70 against a consumer
  // that takes nothing, then drained; k from 1 to 9 and either side of 16, 32 and 64. A FIFO whose
  // fullness is told from its pointers wrongly (a difference taken wider than the pointers) is
  // full only before they first wrap, which a fill from reset (full_output) never reaches.
  constexpr std::uint32_t kFill = 70;
  std::vector<Firing> offsets;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> fills;
  std::uint64_t edge = 10;
  std::uint32_t n = 0;
  // `count` firings queued at `edge`, each with the next address.
  const auto queue = [&](std::uint32_t count) {
    for (std::uint32_t i = 0; i < count; ++i, ++n) offsets.push_back({at(edge, 0.3) + i, (n * 0x59u + 7u) & 0x3FFu});
  };
  for (const std::uint32_t k : {1u, 2u, 3u, 4u, 5u, 6u, 7u, 8u, 9u, 15u, 16u, 17u, 31u, 32u, 33u, 63u, 64u, 65u}) {
    queue(k);
    edge += k * handshake + 4;
    const std::uint64_t stall_from = edge;
    edge += 2;  // the consumer stops before the fill comes
    queue(kFill);
    edge += kFill * handshake;
    fills.push_back({stall_from, edge});
    edge += kFill * handshake + 4;  // drained
  }
  VerifyCase& wrapped = add("full_at_pointer_offsets", std::move(offsets), edge);
  wrapped.queued_senders = true;
  wrapped.stalls = std::move(fills);
  return cases;
}

}  // namespace aesim
