#!/usr/bin/env python3
"""Fault throw against length through time, on a real LAMMPS run (issue 38's example).

Opens the graben run of examples/lammps (tests/data/real_runs/lammps/dump.extension.gz, or the
dump given), derives strain from motion, takes the candidates of the last frame's incremental
shear strain as faults, follows them back through every frame and plots each fault's throw
against its length with matplotlib. Run from a build:

    PYTHONPATH=build/python python3 examples/python/throw_vs_length.py [dump] [out.png]
"""
import csv
import os
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt

import faultline

here = os.path.dirname(os.path.abspath(__file__))
dump = sys.argv[1] if len(sys.argv) > 1 and sys.argv[1] else os.path.join(
    here, "..", "..", "tests", "data", "real_runs", "lammps", "dump.extension.gz")
out = sys.argv[2] if len(sys.argv) > 2 else "throw_vs_length.png"

s = faultline.Session(dump)
last = len(s.dataset) - 1
s.run({"op": "frame.set", "frame": last})
s.run({"op": "strain.add", "since_offset": -1, "prefix": "inc_"})  # the faults active then
s.run({"op": "strain.add", "since_frame": 0})  # reference positions: the throw since frame 0
strain = s.frame["inc_shear_strain"]
low = float(sorted(v for v in strain if v == v)[int(0.87 * len(strain))])  # 87th percentile
s.run({"op": "threshold.add", "variable": "inc_shear_strain", "low": low, "high": 1e30})
s.run({"op": "fault.candidates", "min_size": 50, "prefix": "F"})
print("faults at frame %d: %s" % (last, {k: len(v) for k, v in s.faults.items()}))

with tempfile.TemporaryDirectory() as tmp:
    growth = os.path.join(tmp, "growth.csv")
    # What each fault is in each frame (followed as candidates of the visible spheres).
    s.run({"op": "export.csv", "what": "fault_growth", "path": growth})
    rows = [r for r in csv.DictReader(open(growth)) if r["throw_status"] == "ok"]

fig, ax = plt.subplots(figsize=(6, 4.5))
for fault in sorted({r["fault"] for r in rows}):
    mine = [r for r in rows if r["fault"] == fault]
    # A section model (6 grains deep, periodic): along strike every fault spans the model, so
    # its length is its extent down dip (the `height` metric); in 3-D take `length`.
    length = [float(r["height"]) for r in mine]
    throw = [abs(float(r["throw"])) for r in mine]
    ax.plot(length, throw, "o-", label=fault)
    for r, x, y in zip(mine, length, throw):
        ax.annotate(r["frame"], (x, y), textcoords="offset points", xytext=(4, 4), fontsize=8)
    print(fault, "frame, length, |throw|:", [(int(r["frame"]), round(x, 1), round(y, 2))
                                              for r, x, y in zip(mine, length, throw)])
ax.set_xlabel("length down dip (model units)")
ax.set_ylabel("|throw| since frame 0 (model units)")
ax.set_title("Graben faults through time (numbers: frames)")
ax.legend()
fig.tight_layout()
fig.savefig(out, dpi=120)
print("wrote", out)
