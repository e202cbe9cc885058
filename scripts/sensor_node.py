"""Runs the sensor node example over the six hand signs (scripts/sensor_node).

1. The grid: the aloha preset's own light, 2 s a sign, the FIFO's depth and the processor's clock
   varied; every run's row in sensor_node.csv, and per (clock, depth) the mean over the signs of the
   latency to the first decision and of the events lost, in sensor_node_summary.csv (the chart's).
2. Beside the paper: its node at 57.6 MHz behind a 64-event FIFO, 15 s a sign, at the light at which
   the six signs give the paper's 263 events/s on average (pixel.i_max = 23 fA); sensor_node_paper.csv.

usage: sensor_node.py SENSOR_NODE_PROGRAM DOCS_FOLDER
"""
import csv
import io
import statistics
import subprocess
import sys

SIGNS = ["fist", "palm", "point", "rock", "thumbs_up", "victory"]
DEPTHS = [1, 2, 4, 8, 16, 32, 64, 128, 256]
CLOCKS = [1.8e6, 3.6e6, 7.2e6, 14.4e6, 57.6e6]
PAPER_LIGHT = "23fA"


def run(program, *args):
    out = subprocess.run([program, "--csv-header", *args], check=True, capture_output=True, text=True).stdout
    return next(csv.DictReader(io.StringIO(out)))


def main():
    program, docs = sys.argv[1], sys.argv[2]
    rows = []
    for clock in CLOCKS:
        for depth in DEPTHS:
            for sign in SIGNS:
                rows.append(run(program, "--sign", sign, "--set", "sim.duration=2s", "--fifo", str(depth),
                                "--clock", repr(clock)))
    with open(f"{docs}/sensor_node.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()), lineterminator="\n")
        w.writeheader()
        w.writerows(rows)

    with open(f"{docs}/sensor_node_summary.csv", "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["clock_mhz", "fifo_depth", "signs_decided", "right", "mean_latency_s", "mean_lost_percent"])
        for clock in CLOCKS:
            for depth in DEPTHS:
                group = [r for r in rows if float(r["clock_hz"]) == clock and int(r["fifo_depth"]) == depth]
                decided = [r for r in group if r["first_winner"]]
                right = sum(r["first_winner"] == r["sign"] for r in decided)
                latency = statistics.mean(float(r["first_decision_s"]) for r in decided) if decided else float("nan")
                lost = statistics.mean(100 * int(r["events_lost"]) / int(r["events_delivered"]) for r in group)
                w.writerow([f"{clock / 1e6:g}", depth, len(decided), right, f"{latency:.6g}", f"{lost:.4g}"])
                print(f"{clock / 1e6:5.1f} MHz, FIFO {depth:3d}: {len(decided)} of 6 decided ({right} right), "
                      f"mean latency {latency:.4g} s, {lost:.3g} % of events lost")

    paper = [run(program, "--sign", sign, "--set", "sim.duration=15s", "--set", f"pixel.i_max={PAPER_LIGHT}",
                 "--fifo", "64") for sign in SIGNS]
    with open(f"{docs}/sensor_node_paper.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(paper[0].keys()), lineterminator="\n")
        w.writeheader()
        w.writerows(paper)
    rate = statistics.mean(float(r["events_per_s"]) for r in paper)
    events = statistics.mean(int(r["first_events_read"]) for r in paper)
    latency = statistics.mean(float(r["first_decision_s"]) for r in paper)
    processing = statistics.mean(float(r["first_recognition_ms"]) for r in paper)
    right = sum(r["first_winner"] == r["sign"] for r in paper)
    print(f"at i_max {PAPER_LIGHT}: {rate:.1f} events/s on average; {right} of 6 right; first decision after "
          f"{events:.1f} events (paper 1281.8), {latency:.3g} s (paper 4.88 s), {processing:.4g} ms of processing "
          f"(paper 13.38 ms; its inputs give 13.35 ms at 57.6 MHz)")


if __name__ == "__main__":
    main()
