#!/usr/bin/env python3
"""Writes deliberately broken copies of a receiver's RTL, one folder per mutant (with the
receiver's description files beside the sources), for the tests that show the verification
catches each. Every mutation names the exact text it replaces and fails if that text is gone, so
the mutants cannot silently drift from the RTL.

usage: rtl_mutants.py RECEIVER SOURCE_DIR OUT_DIR
  RECEIVER: aer_receiver (rtl/), ae_rx_alt (tests/rtl/second_receiver/) or pkt_rx
  (tests/rtl/third_receiver/)
"""
import glob
import os
import sys

RECEIVERS = {
    "aer_receiver": (["aer_receiver.v", "aer_req_sync.v", "aer_timestamp.v", "aer_fifo.v"], {
        # The asynchronous Req used directly, without the synchronizer.
        "no_sync": ("aer_receiver.v", [
            ("wire req_high = req_s2 && req_s3;", "wire req_high = req_i;"),
            ("wire req_low = !req_s2 && !req_s3;", "wire req_low = !req_i;"),
        ]),
        # Ack raised one cycle early: one settled synchronizer sample is taken as a stable Req.
        "ack_early": ("aer_receiver.v", [
            ("wire req_high = req_s2 && req_s3;", "wire req_high = req_s2;"),
        ]),
        # FIFO pointers wrap one word early (off by one), so the last slot is skipped and a full
        # FIFO overwrites its oldest word.
        "fifo_off_by_one": ("aer_fifo.v", [
            ("advance = (ptr == DEPTH[PW-1:0] - {{(PW - 1) {1'b0}}, 1'b1})",
             "advance = (ptr == DEPTH[PW-1:0] - {{(PW - 2) {1'b0}}, 2'b10})"),
        ]),
    }),
    "ae_rx_alt": (["ae_rx_alt.v"], {
        # The decision reads the asynchronous Req itself.
        "unsynchronised_decision": ("ae_rx_alt.v", [
            ("wire seen_high = sync[2] & held;", "wire seen_high = bus_req;"),
            ("wire seen_low = ~sync[2] & ~held;", "wire seen_low = ~bus_req;"),
        ]),
        # A transaction meeting a full FIFO is lost without being counted.
        "uncounted_drop": ("ae_rx_alt.v", [
            ("lost_count <= lost_count + 16'd1;", "lost_count <= lost_count;"),
        ]),
        # Full one word too late: the ninth word overwrites the oldest.
        "fifo_off_by_one": ("ae_rx_alt.v", [
            ("wire full = used == DEPTH;", "wire full = used == DEPTH + 1;"),
        ]),
        # The contention line is not stored: a collision comes out unflagged.
        "lost_collision_flag": ("ae_rx_alt.v", [
            ("ring[wr[LOG_DEPTH-1:0]] <= {now, bus_collide, bus_addr};",
             "ring[wr[LOG_DEPTH-1:0]] <= {now, 1'b0, bus_addr};"),
        ]),
        # The stamp of the previous transaction goes out with this one.
        "stale_timestamp": ("ae_rx_alt.v", [
            ("ring[wr[LOG_DEPTH-1:0]] <= {now, bus_collide, bus_addr};",
             "ring[wr[LOG_DEPTH-1:0]] <= {last, bus_collide, bus_addr};\n          last <= now;"),
            ("  reg busy;\n", "  reg busy;\n  reg [TSW-1:0] last = {TSW{1'b0}};\n"),
        ]),
        # The output advances whether or not it was taken: beats move while stalled.
        "moves_while_stalled": ("ae_rx_alt.v", [
            ("else if (out_valid && out_ready) rd <= rd + 1'b1;", "else if (out_valid) rd <= rd + 1'b1;"),
        ]),
    }),
    "pkt_rx": (["pkt_rx_pkg.sv", "pkt_rx.sv"], {
        # The decision reads the first synchroniser flop, which may be metastable.
        "first_flop_decision": ("pkt_rx.sv", [
            ("wire offer = state == IDLE && req_sync;", "wire offer = state == IDLE && req_meta;"),
        ]),
        # The stamp is the tick counter's previous value: one tick stale.
        "stale_tick": ("pkt_rx.sv", [
            ("      now <= now + 1'b1;\n", "      now <= now + 1'b1;\n      previous <= now;\n"),
            ("      stamp <= now;\n", "      stamp <= previous;\n"),
            ("  logic [TSW-1:0] now;\n", "  logic [TSW-1:0] now;\n  logic [TSW-1:0] previous = '0;\n"),
        ]),
        # The divider counts one cycle too many: a tick of 11 cycles.
        "divider_off_by_one": ("pkt_rx.sv", [
            ("divider == 16'(TICK_CYCLES - 1)", "divider == 16'(TICK_CYCLES)"),
        ]),
        # The counter skips a tick once, at 7.
        "skipped_tick": ("pkt_rx.sv", [
            ("      now <= now + 1'b1;\n", "      now <= now + (now == 7 ? 2'd2 : 2'd1);\n"),
        ]),
        # The design's own check fails on every request.
        "own_fatal": ("pkt_rx.sv", [
            ("  assign pkt_valid = offer && !col_q;",
             "  always_ff @(posedge clk) if (rst_n && offer) $fatal(1, \"boom\");\n  assign pkt_valid = offer && !col_q;"),
        ]),
    }),
}


def write_if_changed(path, text):
    # CMake runs this at every configure of every preset, which share the folder: a file rewritten
    # as it was would rebuild every mutant, and one half-written could be read by another preset.
    if os.path.exists(path) and open(path).read() == text:
        return
    temp = f"{path}.tmp.{os.getpid()}"
    with open(temp, "w") as f:
        f.write(text)
    os.replace(temp, path)


def main():
    if len(sys.argv) != 4 or sys.argv[1] not in RECEIVERS:
        sys.exit(__doc__)
    receiver, source_dir, out = sys.argv[1:]
    sources, mutants = RECEIVERS[receiver]
    descriptions = glob.glob(os.path.join(source_dir, "*.toml"))
    for name, (target, edits) in mutants.items():
        folder = os.path.join(out, name)
        os.makedirs(folder, exist_ok=True)
        texts = {os.path.basename(f): open(f).read()
                 for f in [os.path.join(source_dir, s) for s in sources] + descriptions}
        text = texts[os.path.basename(target)]
        for before, after in edits:
            if before not in text:
                sys.exit(f"rtl_mutants.py: mutant {name}: '{before}' not found in {target}")
            text = text.replace(before, after)
        texts[os.path.basename(target)] = text
        for base, content in texts.items():
            write_if_changed(os.path.join(folder, base), content)


if __name__ == "__main__":
    main()
