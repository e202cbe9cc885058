#pragma once
#include <string>

#include <nlohmann/json.hpp>

#include "build/dut_build.hpp"
#include "description/receiver_description.hpp"
#include "formal/formal_run.hpp"
#include "session/verify_session.hpp"

namespace aesim {

// verify.json (docs/reference.md section 6): the verdict, the counts, the first failure, and how the run went.
nlohmann::json verify_report(const ReceiverDescription& d, const std::string& plan, std::uint64_t seed,
                             const DutBuild& build, const VerifyResult& r, const std::vector<std::string>& notes, double wall_time_s);

// The formal check's part of verify.json: `formal`, a list of {property, verdict, depth, time_s}
// (docs/reference.md section 6), and `formal_run`: how it ran, what it assumed and left out, the failure.
void add_formal_report(nlohmann::json& report, const FormalResult& formal, const std::string& counterexample_path,
                       const std::string& replay);

}  // namespace aesim
