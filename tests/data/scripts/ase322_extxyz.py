# Writes the XYZ fixtures with ASE 3.22 (Debian python3-ase; run with /usr/bin/python3): 3 frames of 6 particles of two
# species with per-particle arrays radius (R), id (I), strain (R), velocities (R:3, momenta /
# masses are ASE's own "momenta"), a flag (L), in an orthogonal periodic cell.
import numpy as np
from ase import Atoms
from ase.io import write

frames = []
for t in range(3):
    n = 6
    pos = np.array([[1.0 * i, 0.5 * (i % 2), 0.25 * t] for i in range(n)])
    a = Atoms(symbols=["Si", "O", "Si", "O", "O", "Si"], positions=pos,
              cell=[10.0, 5.0, 4.0], pbc=[True, True, False])
    a.new_array("radius", np.array([0.5 + 0.125 * i for i in range(n)]))
    a.new_array("id", np.array([100 + i for i in range(n)], dtype=int))
    a.new_array("strain", np.array([0.01 * i * (t + 1) for i in range(n)]))
    a.new_array("broken", np.array([i % 2 == 0 and t > 0 for i in range(n)], dtype=bool))
    a.set_velocities(np.array([[0.1 * i, -0.1 * i, 0.0] for i in range(n)]))
    a.info["Timestep"] = 1000 * t
    frames.append(a)
write("ase322_extxyz_3frames.xyz", frames, format="extxyz")
# Plain XYZ as ASE's "xyz" writer makes it (element x y z, comment line free text).
from ase.io.xyz import write_xyz
with open("ase322_plain.xyz", "w") as f:
    write_xyz(f, [frames[0]], comment="plain xyz from ase.io.xyz")
print("ok")
