#pragma once
#include <string>
#include <vector>

#include "build/port_list.hpp"
#include "description/receiver_description.hpp"
#include "aesim/output/atomic_file.hpp"
#include "session/verify_session.hpp"

namespace aesim {

// A self-checking Verilog-2005 testbench of one run, for any simulator: DIR/tb.v (top module
// tb) replays the run's exact inputs (DIR/tb_inputs.hex: every change of Req, address,
// contention, ready and reset, to the picosecond) against the team's RTL, with the handshake's
// polarity, the roles' slices and the [inputs] constants of the description, and compares every
// beat taken with the beats the run gave (DIR/tb_expected.hex: address, stamp, collision flag, in
// order; absent when the run gave none). It also stops on Ack rising while Req is low. Its last
// line starts with PASS or FAIL. DIR/tb_files.f lists tb.v, the sources and the include folders:
// `iverilog -g2005 -o sim -c tb_files.f` (-g2012 for SystemVerilog sources) then `vvp sim` in DIR.
void write_testbench(const std::string& dir, const ReceiverDescription& d, const std::vector<RtlPort>& ports,
                     const ExportedRun& run, OutputFiles& files);

}  // namespace aesim
