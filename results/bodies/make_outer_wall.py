"""Writes outer_wall.txt next to this file: the tabulated level set phi0 = R2 - |x - (0.5, 0.5)|
(the outside of a circle of radius R2 = 0.4) on 129 x 129 nodes of the unit square, the fixed
outer wall of couette_torque.toml."""
import math
import os

R2, m = 0.4, 129
with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "outer_wall.txt"), "w") as f:
    f.write(f"{m} {m} 0 0 {1 / (m - 1)}\n")
    for j in range(m):
        f.write(" ".join(f"{R2 - math.hypot(i / (m - 1) - 0.5, j / (m - 1) - 0.5):.12g}" for i in range(m)) + "\n")
