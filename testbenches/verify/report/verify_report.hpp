#pragma once
#include <string>

#include <nlohmann/json.hpp>

#include "build/dut_build.hpp"
#include "description/receiver_description.hpp"
#include "session/verify_session.hpp"

namespace aesim {

// verify.json (SPEC section 6): the verdict, the counts, the first failure, and how the run went.
nlohmann::json verify_report(const ReceiverDescription& d, const std::string& plan, std::uint64_t seed,
                             const DutBuild& build, const VerifyResult& r, const std::vector<std::string>& notes, double wall_time_s);

}  // namespace aesim
