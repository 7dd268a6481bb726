#!/usr/bin/env python3
"""Writes two_pillars.stl (binary, mm) beside this script: the part of
examples/two_pillars.lmd, two square pillars standing apart on a plate, as
CAD would export them in one file (two shells).

Each pillar is 12 mm square and 10 mm tall, their corners at (0, 0) and
(40, 0): 28 mm of plate between them, so every layer of the part is two
islands. Each box is 12 triangles facing out. Run:
python3 examples/mesh/make_two_pillars.py
"""
import os
import struct

SIDE = 12.0
HEIGHT = 10.0
CORNERS = [(0.0, 0.0), (40.0, 0.0)]


def box(x0, y0):
    """The 12 triangles of a box from (x0, y0, 0), counter-clockwise seen
    from outside."""
    x1, y1, z1 = x0 + SIDE, y0 + SIDE, HEIGHT
    p = [
        (x0, y0, 0), (x1, y0, 0), (x1, y1, 0), (x0, y1, 0),
        (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1),
    ]
    quads = [
        (0, 3, 2, 1),  # bottom, facing down
        (4, 5, 6, 7),  # top
        (0, 1, 5, 4),  # y = y0
        (1, 2, 6, 5),  # x = x1
        (2, 3, 7, 6),  # y = y1
        (3, 0, 4, 7),  # x = x0
    ]
    tris = []
    for a, b, c, d in quads:
        tris.append((p[a], p[b], p[c]))
        tris.append((p[a], p[c], p[d]))
    return tris


def normal(t):
    (ax, ay, az), (bx, by, bz), (cx, cy, cz) = t
    u = (bx - ax, by - ay, bz - az)
    v = (cx - ax, cy - ay, cz - az)
    n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    length = sum(x * x for x in n) ** 0.5
    return tuple(x / length for x in n)


def main():
    tris = [t for x, y in CORNERS for t in box(x, y)]
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "two_pillars.stl")
    with open(out, "wb") as f:
        f.write(b"two pillars, lmdc example".ljust(80, b" "))
        f.write(struct.pack("<I", len(tris)))
        for t in tris:
            f.write(struct.pack("<3f", *normal(t)))
            for v in t:
                f.write(struct.pack("<3f", *v))
            f.write(b"\0\0")


if __name__ == "__main__":
    main()
