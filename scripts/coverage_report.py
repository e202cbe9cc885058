#!/usr/bin/env python3
"""Summarises Verilator coverage files (summed): line coverage (Verilator's statement-block and
branch points) and toggle coverage of each RTL file and in total. With --min-line P, exits 1 when
total line coverage is below P percent. With --uncovered, lists the line points never hit."""
import argparse
import collections
import glob
import os
import sys


def points(path):
    """Yields (type, file, line, comment, count) for every coverage point."""
    with open(path, encoding="latin-1") as f:
        for raw in f:
            if not raw.startswith("C '"):
                continue
            key, _, count = raw.rstrip("\n").rpartition("' ")
            fields = {}
            for item in key[3:].split("\x01"):
                if "\x02" in item:
                    name, value = item.split("\x02", 1)
                    fields[name] = value
            kind = fields.get("page", "").split("/")[0]
            kind = "v_line" if kind == "v_branch" else kind
            yield kind, fields.get("f", "?"), fields.get("l", "?"), fields.get("o", ""), int(count)


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("coverage", nargs="+", help="coverage .dat files, or folders of them")
    parser.add_argument("--min-line", type=float, default=None)
    parser.add_argument("--uncovered", action="store_true")
    args = parser.parse_args()

    # The same point appears once per model build and hierarchy; a point is covered if any hit it.
    merged = collections.defaultdict(int)
    files_in = []
    for path in args.coverage:
        files_in += sorted(glob.glob(os.path.join(path, "*.dat"))) if os.path.isdir(path) else [path]
    if not files_in:
        print("no coverage files", file=sys.stderr)
        return 1
    for path in files_in:
        for kind, file, line, comment, count in points(path):
            merged[(kind, file.split("/")[-1], line, comment)] += count
    table = collections.defaultdict(lambda: [0, 0])
    for (kind, file, _, _), count in merged.items():
        for key in ((kind, file), (kind, "total")):
            table[key][0] += 1
            table[key][1] += count > 0
    files = sorted({f for (_, f) in table if f != "total"})
    print(f"{'RTL file':<20} {'line':>16} {'toggle':>16}")
    for f in files + ["total"]:
        cells = []
        for kind in ("v_line", "v_toggle"):
            total, hit = table.get((kind, f), (0, 0))
            cells.append(f"{hit}/{total} {100.0 * hit / total:5.1f}%" if total else "-")
        print(f"{f:<20} {cells[0]:>16} {cells[1]:>16}")
    if args.uncovered:
        for (kind, file, line, comment), count in sorted(merged.items()):
            if kind == "v_line" and count == 0:
                print(f"uncovered: {file}:{line} {comment}")
    total, hit = table.get(("v_line", "total"), (0, 0))
    line_pct = 100.0 * hit / total if total else 0.0
    if args.min_line is not None and line_pct < args.min_line:
        print(f"line coverage {line_pct:.1f}% is below {args.min_line}%", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
