#!/usr/bin/env python3
"""Writes Metavision's HDF5 layout (/CD/events: x u2 at 0, y u2 at 2, p i2 at 4, t i8 at 8, 16 bytes,
as Metavision's EventCD; chunks of 1000 events), compressed by Prophesee's own ECF plugin (filter
0x8ECF), in three chunks that take its three
packings: every event on a row of its own (y, x and p packed in 24 bits), rows of 50 events at
scattered columns (x and p packed in 12 bits), rows of 64 neighbouring columns (x masked, p
run-length). Stamps: runs at one instant longer than 15 events and gaps past 15 us.

tests/fuzz/corpus/h5/metavision_ecf.hdf5 was made so (EventFormats.MetavisionHdf5WithPropheseesEcfIsRead
checks every event against the same formulas; the fuzz harness starts from it). It needs the codec
aesim stands in for: Prophesee's hdf5_ecf built (cmake and ninja in its repository), its folder on
HDF5_PLUGIN_PATH, then `python3 scripts/make_ecf_fixture.py OUT.hdf5`."""
import sys

import h5py
import numpy as np

n = 1000
k = np.arange(3 * n)
c, j = k // n, k % n
x = np.where(c == 0, (j * 101) % 640, np.where(c == 1, (j * 131) % 640, 10 + (j % 64)))
y = np.where(c == 0, (j * 37) % 480, np.where(c == 1, 100 + j // 50, 200 + j // 64))
p = np.where(c == 2, (j // 7) % 2, j % 2)
t = 1000 + (k // 20) * 3 + (k // 500) * 100000
ev = np.zeros(3 * n, dtype=np.dtype({'names': ['x', 'y', 'p', 't'], 'formats': ['<u2', '<u2', '<i2', '<i8'], 'offsets': [0, 2, 4, 8], 'itemsize': 16}))
ev['x'], ev['y'], ev['p'], ev['t'] = x, y, p, t
with h5py.File(sys.argv[1], 'w') as f:
    f.create_dataset('CD/events', data=ev, chunks=(n,), compression=0x8ECF)
