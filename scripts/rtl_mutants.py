#!/usr/bin/env python3
"""Writes deliberately broken copies of the receiver RTL, one folder per mutant, for the test
that shows the verification catches each. Every mutation names the exact text it replaces and
fails if that text is gone, so the mutants cannot silently drift from the RTL.

usage: rtl_mutants.py RTL_DIR OUT_DIR
"""
import os
import shutil
import sys

MUTANTS = {
    # The asynchronous Req used directly, without the two-flop synchronizer.
    "no_sync": ("aer_receiver.v", [
        ("wire req_high = req_s2 && req_s3;", "wire req_high = req_i;"),
        ("wire req_low = !req_s2 && !req_s3;", "wire req_low = !req_i;"),
    ]),
    # Ack raised one cycle early: one synchronizer sample is taken as a stable Req.
    "ack_early": ("aer_receiver.v", [
        ("wire req_high = req_s2 && req_s3;", "wire req_high = req_s2;"),
    ]),
    # FIFO pointers wrap one word early (off by one), so the last slot is skipped.
    "fifo_off_by_one": ("aer_fifo.v", [
        ("advance = (ptr == DEPTH[PW-1:0] - {{(PW - 1) {1'b0}}, 1'b1})",
         "advance = (ptr == DEPTH[PW-1:0] - {{(PW - 2) {1'b0}}, 2'b10})"),
    ]),
}
SOURCES = ["aer_receiver.v", "aer_req_sync.v", "aer_timestamp.v", "aer_fifo.v"]


def main():
    rtl, out = sys.argv[1], sys.argv[2]
    for name, (target, edits) in MUTANTS.items():
        folder = os.path.join(out, name)
        os.makedirs(folder, exist_ok=True)
        for source in SOURCES:
            shutil.copy(os.path.join(rtl, source), os.path.join(folder, source))
        path = os.path.join(folder, target)
        text = open(path).read()
        for before, after in edits:
            if before not in text:
                sys.exit(f"rtl_mutants.py: mutant {name}: '{before}' not found in {target}")
            text = text.replace(before, after)
        open(path, "w").write(text)


if __name__ == "__main__":
    main()
