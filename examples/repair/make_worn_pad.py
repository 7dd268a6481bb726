#!/usr/bin/env python3
"""Writes the scans of a worn pad: worn_pad.ply for worn_pad.lmd, and
pad_nominal.stl with worn_pad_displaced.ply for worn_pad_registered.lmd.

The pad's top was flat at z = 10 mm over x -30..30 mm, y -10..10 mm; wear
has dug a smooth trough into it, deepest (1.5 mm) at x = 5 mm, y = 0:

    z(x, y) = 10 - 1.5 * exp(-((x - 5) / 15)^2) * (1 - (y / 14)^2)

worn_pad.ply: the scan covers x -33..33 mm, y -13..13 mm every 0.5 mm,
with the noise a line scanner gives (Gaussian, sigma 0.03 mm) and six
stray returns 2-4 mm above the surface, in the part's coordinates.

pad_nominal.stl: the part as designed, in the part's coordinates: the
pad, the block x -33..33 mm, y -13..13 mm, z 0..10 mm, on a flange
x -45..45 mm, y -25..25 mm, z -5..0 mm (two boxes, 24 triangles, binary).

worn_pad_displaced.ply: the same top (the same points, noise and stray
returns as worn_pad.ply), the pad's four sides from z = 0.5 mm up to
9.5 mm every 0.5 mm, and the flange's face round the pad every 1 mm
(0.03 mm of noise across each): the trough's flanks fade across the
whole pad top, so the flange is the unworn face that fixes the scan's
height. As a scanner on a fixture only roughly known gives them: every
point turned 0.5 deg about x, then 1.5 deg about z, then moved by
(1.2, -0.8, 0.3) mm. Registered to the nominal, it comes back to
worn_pad.ply's place.

Binary little-endian PLY, points only, float32. Deterministic: the same
bytes every run (seeded generators).

    python3 examples/repair/make_worn_pad.py
"""
import math
import random
import struct
from pathlib import Path

HERE = Path(__file__).parent

# The displaced scan's move: turns about x then z (deg), then a shift (mm).
TURN_X, TURN_Z = 0.5, 1.5
SHIFT = (1.2, -0.8, 0.3)

# The nominal: the pad, and the flange it stands on.
LO, HI = (-33.0, -13.0, 0.0), (33.0, 13.0, 10.0)
FLANGE_LO, FLANGE_HI = (-45.0, -25.0, -5.0), (45.0, 25.0, 0.0)


def surface(x, y):
    return 10.0 - 1.5 * math.exp(-(((x - 5.0) / 15.0) ** 2)) * (1.0 - (y / 14.0) ** 2)


def top_points():
    """The worn top as worn_pad.ply holds it, stray returns included."""
    rng = random.Random(20261205)
    pts = []
    n_x, n_y = 133, 53  # -33..33 and -13..13 every 0.5 mm
    for j in range(n_y):
        y = -13.0 + 0.5 * j
        for i in range(n_x):
            x = -33.0 + 0.5 * i
            pts.append((x, y, surface(x, y) + rng.gauss(0.0, 0.03)))
    for _ in range(6):
        k = rng.randrange(len(pts))
        x, y, z = pts[k]
        pts[k] = (x, y, z + rng.uniform(2.0, 4.0))
    return pts


def side_points():
    """The pad's four sides from z = 0.5 mm to 9.5 mm every 0.5 mm, and
    the flange's face round it every 1 mm."""
    rng = random.Random(20261207)
    pts = []
    for k in range(19):  # z = 0.5 .. 9.5
        z = 0.5 + 0.5 * k
        for i in range(133):
            x = -33.0 + 0.5 * i
            pts.append((x, LO[1] - rng.gauss(0.0, 0.03), z))
            pts.append((x, HI[1] + rng.gauss(0.0, 0.03), z))
        for j in range(1, 52):
            y = -13.0 + 0.5 * j
            pts.append((LO[0] - rng.gauss(0.0, 0.03), y, z))
            pts.append((HI[0] + rng.gauss(0.0, 0.03), y, z))
    for j in range(51):  # y = -25 .. 25
        y = -25.0 + j
        for i in range(91):  # x = -45 .. 45
            x = -45.0 + i
            if abs(x) <= 33.5 and abs(y) <= 13.5:
                continue
            pts.append((x, y, rng.gauss(0.0, 0.03)))
    return pts


def displaced(p):
    """p turned TURN_X about x, then TURN_Z about z, then moved by SHIFT."""
    x, y, z = p
    a, b = math.radians(TURN_X), math.radians(TURN_Z)
    y, z = y * math.cos(a) - z * math.sin(a), y * math.sin(a) + z * math.cos(a)
    x, y = x * math.cos(b) - y * math.sin(b), x * math.sin(b) + y * math.cos(b)
    return (x + SHIFT[0], y + SHIFT[1], z + SHIFT[2])


def ply(pts, comment):
    head = (
        "ply\nformat binary_little_endian 1.0\n"
        f"comment {comment}\n"
        f"element vertex {len(pts)}\n"
        "property float x\nproperty float y\nproperty float z\nend_header\n"
    )
    return head.encode() + b"".join(struct.pack("<3f", *p) for p in pts)


def box(lo, hi):
    """The box lo..hi as 12 triangles, faces out."""
    def corner(i):
        return tuple(hi[k] if i >> k & 1 else lo[k] for k in range(3))

    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    tris = []
    for q in quads:
        tris.append((corner(q[0]), corner(q[1]), corner(q[2])))
        tris.append((corner(q[0]), corner(q[2]), corner(q[3])))
    return tris


def binary_stl(tris, header):
    """Triangles (three corners each, counter-clockwise seen from outside)
    as a binary STL, float32, its normals left zero (readers compute them
    from the corners)."""
    out = header.ljust(80, b" ")
    out += struct.pack("<I", len(tris))
    for t in tris:
        out += struct.pack("<3f", 0.0, 0.0, 0.0)
        for c in t:
            out += struct.pack("<3f", *c)
        out += b"\0\0"
    return out


def block_stl():
    """The nominal, the pad on its flange, as a binary STL."""
    tris = box(LO, HI) + box(FLANGE_LO, FLANGE_HI)
    return binary_stl(tris, b"pad nominal, generated by make_worn_pad.py")


def main():
    top = top_points()
    (HERE / "worn_pad.ply").write_bytes(ply(top, "worn pad, generated by make_worn_pad.py"))
    (HERE / "pad_nominal.stl").write_bytes(block_stl())
    moved = [displaced(p) for p in top + side_points()]
    (HERE / "worn_pad_displaced.ply").write_bytes(
        ply(moved, "worn pad with its sides, displaced, generated by make_worn_pad.py")
    )


if __name__ == "__main__":
    main()
