"""The Python example of docs/python.md: sweep the integration capacitance of the ALOHA pixel from Python,
and plot what a sizing engineer looks at: the event rate against eq. 2, and what the shared bus
delivers of it.

    scripts/python scripts/examples/c_int_sweep.py [OUT.png]
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import aesim  # noqa: E402

out = sys.argv[1] if len(sys.argv) > 1 else "out/c_int_sweep.png"
scene = np.full((64, 64), 0.5)  # half of full scale everywhere: every pixel sees 0.5 pA
c_int = np.array([10, 20, 50, 100, 200, 500]) * 1e-15
fired, delivered = [], []
for c in c_int:
    r = aesim.run(scene=scene, duration="1s", set={"pixel.c_int": f"{c:.3g}F"})
    fired.append(r.summary["events_fired"])
    delivered.append(len(r.events[r.events["flags"] == 0]))

# Eq. 2: each pixel fires every C dV / I + t_reset; 4096 pixels.
i_ph, dv, t_reset = 0.5e-12 + 1e-15, 1.0, 1e-6  # photocurrent plus the preset's 1 fA dark current
theory = 4096 / (c_int * dv / i_ph + t_reset)
for c, f, d, t in zip(c_int, fired, delivered, theory):
    print(f"c_int {c * 1e15:5.0f} fF: fired {f:8.0f} events/s (eq. 2: {t:8.0f}), delivered {d / f:6.1%} "
          f"(ALOHA: {np.exp(-2 * f / 4 * 150e-9):6.1%})")

# Pure ALOHA: an event survives if no other starts within tau either side, exp(-2G), with G the
# offered load per bus (four buses, tau = bus.t_event = 150 ns).
tau = 150e-9
load = np.array(fired) / 4 * tau
fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
left.loglog(c_int * 1e15, theory, "k-", label="eq. 2: 4096 I / (C dV + I t_reset)")
left.loglog(c_int * 1e15, fired, "o", label="fired (aesim.run)")
left.set_xlabel("c_int (fF)")
left.set_ylabel("events per second")
left.set_title("rate: 64x64 at half scale, 1 s a point")
left.legend()
left.grid(True, which="both", alpha=0.3)
g = np.logspace(-4, -1.5, 50)
right.semilogx(g, np.exp(-2 * g), "k-", label="pure ALOHA: exp(-2G)")
right.semilogx(load, np.array(delivered) / np.array(fired), "s", label="delivered / fired (aesim.run)")
right.set_xlabel("offered load G per bus")
right.set_ylabel("fraction delivered")
right.set_title("what the shared buses deliver")
right.legend()
right.grid(True, which="both", alpha=0.3)
fig.tight_layout()
fig.savefig(out, dpi=100)
print(f"wrote {out}")
