#!/usr/bin/env python3
"""Issue 38's numbers for the Python module, as a timed run (not a unit test):

  1. `import faultline` in a fresh interpreter (median of 5);
  2. `ds.frame(i)["strain"]`: the frame's load through the core plus the column view, against the
     load alone (the view copies nothing, so the two should agree);
  3. a loop over every frame computing candidates and metrics in Python, against the same
     journal through `faultline replay`.

    PYTHONPATH=build/python python3 bench/python_bench.py [DATA] [--cli build/app/faultline]

DATA defaults to the demo model (faultline.generate.demo(): 204,800 spheres, 40 frames).
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

import faultline

ap = argparse.ArgumentParser()
ap.add_argument("data", nargs="?")
ap.add_argument("--cli", default=os.path.join(os.path.dirname(__file__), "..", "build", "app", "faultline"))
ap.add_argument("--variable", default="broken_bonds")
ap.add_argument("--low", type=float, default=3)
args = ap.parse_args()
data = args.data or faultline.generate.demo()
env = dict(os.environ)

# 1. import
times = []
for _ in range(5):
    out = subprocess.run([sys.executable, "-c", "import time; t = time.perf_counter(); import faultline; "
                          "print(time.perf_counter() - t)"], capture_output=True, text=True, env=env, check=True)
    times.append(float(out.stdout))
print("import faultline: median %.1f ms (of 5: %s)" % (1e3 * statistics.median(times),
                                                         ", ".join("%.1f" % (1e3 * t) for t in times)))

# 2. a frame's column
ds = faultline.open(data)
n = len(ds)
load, view = [], []
for i in range(min(n, 10)):
    d = faultline.open(data)  # a fresh dataset: nothing cached
    t0 = time.perf_counter()
    f = d.frame(i)
    t1 = time.perf_counter()
    col = f[args.variable]
    t2 = time.perf_counter()
    load.append(t1 - t0)
    view.append(t2 - t1)
print("frame load (%d spheres): median %.1f ms; the column view after it: median %.3f ms (%.2f%%)"
      % (len(f), 1e3 * statistics.median(load), 1e3 * statistics.median(view),
         100 * statistics.median(view) / statistics.median(load)))

# 3. candidates and metrics over every frame: Python loop against faultline replay.
ops = [{"op": "data.open", "paths": [data]},
       {"op": "threshold.add", "variable": args.variable, "low": args.low, "high": 1e30}]
per_frame = []
for i in range(n):  # each frame's candidates, dropped again; the last frame's kept
    per_frame += [{"op": "frame.set", "frame": i}, {"op": "fault.candidates", "min_size": 50}]
    if i + 1 < n:
        per_frame.append({"op": "undo"})
with tempfile.TemporaryDirectory() as tmp:
    metrics = {"op": "export.csv", "what": "fault_metrics", "path": os.path.join(tmp, "m.csv")}
    journal = os.path.join(tmp, "loop.jsonl")
    with open(journal, "w") as j:
        for op in ops + per_frame + [metrics]:
            j.write(json.dumps(op) + "\n")
    t0 = time.perf_counter()
    r = subprocess.run([args.cli, "replay", journal], capture_output=True, text=True)
    if r.returncode:
        sys.exit("faultline replay failed: " + r.stdout[-600:] + r.stderr[-600:])
    cli = time.perf_counter() - t0

    t0 = time.perf_counter()
    s = faultline.Session(data)
    for op in ops[1:] + per_frame:
        s.run(op)
    m = s.fault_metrics()
    py = time.perf_counter() - t0
print("candidates in %d frames + metrics of %d faults: python %.2f s, faultline replay %.2f s "
      "(python / replay = %.2f)" % (n, len(set(m["fault"])), py, cli, py / cli))
