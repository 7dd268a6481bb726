#!/usr/bin/env python3
"""Writes shaft_pad.ply, the scan shaft_pad.lmd builds a flat pad on.

A shaft of radius 40 mm lies along x, its axis at y = 0, z = 0: its top
is the cylinder

    z(x, y) = sqrt(40^2 - y^2)

40 mm high on the crown, 38.16 mm at y = +-12 mm, where its surface
slopes 17.5 deg. The scan covers x -23..23 mm, y -15..15 mm every
0.5 mm (5 673 points), with the noise a line scanner gives (Gaussian,
sigma 0.02 mm) and three stray returns 2-3 mm above the surface, in the
part's coordinates.

Binary little-endian PLY, points only, float32. Deterministic: the same
bytes every run (a seeded generator).

    python3 examples/repair/make_shaft_pad.py
"""
import math
import random
import struct
from pathlib import Path

HERE = Path(__file__).parent
RADIUS = 40.0


def surface(x, y):
    return math.sqrt(RADIUS * RADIUS - y * y)


def points():
    rng = random.Random(35)
    out = []
    for j in range(61):
        for i in range(93):
            x, y = -23.0 + 0.5 * i, -15.0 + 0.5 * j
            out.append((x, y, surface(x, y) + rng.gauss(0.0, 0.02)))
    # Stray returns: a speck of spatter, a reflection.
    for x, y, up in [(-8.0, 3.5, 2.0), (6.5, -7.0, 3.0), (15.0, 9.5, 2.5)]:
        out.append((x, y, surface(x, y) + up))
    return out


def write_ply(path, pts):
    head = (
        "ply\nformat binary_little_endian 1.0\n"
        f"element vertex {len(pts)}\n"
        "property float x\nproperty float y\nproperty float z\nend_header\n"
    )
    with open(path, "wb") as f:
        f.write(head.encode("ascii"))
        for p in pts:
            f.write(struct.pack("<3f", *p))


if __name__ == "__main__":
    write_ply(HERE / "shaft_pad.ply", points())
