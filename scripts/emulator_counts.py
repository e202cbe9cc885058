#!/usr/bin/env python3
"""Entries per frame of every grey level 0..255 in `aesim emulate` (f_max 20), with the even spread
and with the literal eq. 3, beside eq. 1's f_max * g / 255.

One 16x16 frame holds each grey level once (so full scale is present); the emulator's --queue
output is counted per pixel. usage: emulator_counts.py AESIM_BINARY OUT.csv
"""
import os
import subprocess
import sys
import tempfile

F_MAX = 20


def main():
    aesim, out = sys.argv[1], sys.argv[2]
    counts = {}
    with tempfile.TemporaryDirectory() as tmp:
        ramp = os.path.join(tmp, "ramp.pgm")
        with open(ramp, "wb") as f:
            f.write(b"P5\n16 16\n255\n" + bytes(range(256)))
        for spread in ("even", "literal"):
            queue = os.path.join(tmp, spread + ".txt")
            subprocess.run([aesim, "emulate", ramp, "--f-max", str(F_MAX), "--spread", spread, "--queue", queue],
                           check=True, capture_output=True)
            per_grey = [0] * 256
            for line in open(queue):
                x, y = map(int, line.split())
                per_grey[y * 16 + x] += 1
            counts[spread] = per_grey
    with open(out + ".tmp", "w") as f:
        f.write("grey,eq1,even,literal\n")
        for g in range(256):
            f.write(f"{g},{F_MAX * g / 255:.4f},{counts['even'][g]},{counts['literal'][g]}\n")
    os.replace(out + ".tmp", out)
    levels = [g for g in range(1, 256) if F_MAX * g / 255 >= 1]
    off = sum(1 for g in levels if abs(counts["literal"][g] - F_MAX * g / 255) > 0.2 * F_MAX * g / 255)
    worst = max(abs(counts["even"][g] - F_MAX * g / 255) for g in range(256))
    print(f"literal eq. 3: {off} of the {len(levels)} levels eq. 1 gives an entry end more than 20 % from it; "
          f"even: every level within {worst:.2f} entries (rounding once)")


if __name__ == "__main__":
    main()
