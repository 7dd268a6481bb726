#!/usr/bin/env python3
"""Writes bracket.stl (binary, mm) beside this script: the part of
examples/bracket.lmd, a bracket given as a mesh as CAD would export it; and
bracket.3mf, the same mesh as a 3MF package (millimetres, one object, one
build item whose transform turns it 90 deg about z and moves it 30 mm along
x, so it stands along y with its corner at the origin): the part of
examples/bracket_3mf.lmd.

A base plate 60 x 30 x 6 mm, its corner at the origin, with a 10 mm hole
through it at (15, 15), and a boss of 20 mm diameter, 16 mm tall over the
plate, at (45, 15), bored 8 mm right through boss and base.

The base is two 30 mm square cells, one round each feature; each cell's
faces are cut by N rays from the feature's centre into quads between the
square and the circles, so the square's corners are corners of the mesh and
the two cells meet on the same points. The script checks the mesh is closed
(every edge shared by two triangles running along it opposite ways) before
it writes it. Run: python3 examples/mesh/make_bracket.py
"""
import math
import os
import struct
import zipfile

N = 64  # rays per cell: a multiple of 8, so the square's corners are on rays
CELL = 15.0  # half the cell's side
BASE = 6.0  # plate thickness
TOP = 22.0  # the boss's top
HOLE = 5.0  # radius of the hole in the first cell
BOSS = 10.0  # the boss's radius
BORE = 4.0  # the bore's radius


def ray(i):
    return 2 * math.pi * (i % N) / N


def square(cx, i, z):
    """Where ray i of the cell centred at (cx, 15) meets the cell's side.
    The second cell's points are the first's mirrored about x = 30, so the
    two cells meet on the very same numbers."""
    if cx != 15.0:
        x, y, _ = square(15.0, N // 2 - i, z)
        return (60.0 - x, y, z)
    t = ray(i)
    c, s = math.cos(t), math.sin(t)
    r = CELL / max(abs(c), abs(s))
    # Exact sides and corners: the coordinate on the side it meets is the
    # side's (a ray at 45 deg meets both).
    corner = abs(abs(c) - abs(s)) < 1e-12
    x = CELL * math.copysign(1, c) if corner or abs(c) > abs(s) else r * c
    y = CELL * math.copysign(1, s) if corner or abs(s) > abs(c) else r * s
    return (cx + x, 15.0 + y, z)


def circle(cx, r, i, z):
    t = ray(i)
    return (cx + r * math.cos(t), 15.0 + r * math.sin(t), z)


tris = []


def quad(a, b, c, d):
    """Two triangles of a quad whose corners run counter-clockwise seen
    from outside the solid."""
    tris.append((a, b, c))
    tris.append((a, c, d))


def on_seam(p, q):
    # The two cells meet on x = 30: no wall there.
    return p[0] == 30.0 and q[0] == 30.0


for i in range(N):
    j = i + 1
    # First cell, centre (15, 15): the plate with its hole.
    a = 15.0
    if not on_seam(square(a, i, 0), square(a, j, 0)):
        quad(square(a, i, 0), square(a, j, 0), square(a, j, BASE), square(a, i, BASE))
    quad(circle(a, HOLE, j, 0), circle(a, HOLE, i, 0), circle(a, HOLE, i, BASE), circle(a, HOLE, j, BASE))
    quad(square(a, i, BASE), square(a, j, BASE), circle(a, HOLE, j, BASE), circle(a, HOLE, i, BASE))
    quad(square(a, j, 0), square(a, i, 0), circle(a, HOLE, i, 0), circle(a, HOLE, j, 0))
    # Second cell, centre (45, 15): the plate, the boss on it, the bore
    # through both.
    b = 45.0
    if not on_seam(square(b, i, 0), square(b, j, 0)):
        quad(square(b, i, 0), square(b, j, 0), square(b, j, BASE), square(b, i, BASE))
    quad(square(b, i, BASE), square(b, j, BASE), circle(b, BOSS, j, BASE), circle(b, BOSS, i, BASE))
    quad(square(b, j, 0), square(b, i, 0), circle(b, BORE, i, 0), circle(b, BORE, j, 0))
    quad(circle(b, BOSS, i, BASE), circle(b, BOSS, j, BASE), circle(b, BOSS, j, TOP), circle(b, BOSS, i, TOP))
    quad(circle(b, BOSS, i, TOP), circle(b, BOSS, j, TOP), circle(b, BORE, j, TOP), circle(b, BORE, i, TOP))
    quad(circle(b, BORE, j, 0), circle(b, BORE, i, 0), circle(b, BORE, i, TOP), circle(b, BORE, j, TOP))


def f32(p):
    return tuple(struct.unpack("<f", struct.pack("<f", x + 0.0))[0] for x in p)


tris = [tuple(f32(p) for p in t) for t in tris]

# Closed and consistently oriented: every directed edge once, and its
# reverse once.
edges = {}
for t in tris:
    for k in range(3):
        e = (t[k], t[(k + 1) % 3])
        edges[e] = edges.get(e, 0) + 1
bad = [e for e, n in edges.items() if n != 1 or edges.get((e[1], e[0])) != 1]
assert not bad, f"open or non-manifold at {bad[:3]}"

out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "bracket.stl")
with open(out, "wb") as f:
    f.write(b"bracket for examples/bracket.lmd, mm".ljust(80, b" "))
    f.write(struct.pack("<I", len(tris)))
    for t in tris:
        f.write(struct.pack("<3f", 0.0, 0.0, 0.0))
        for p in t:
            f.write(struct.pack("<3f", *p))
        f.write(b"\0\0")
print(f"{out}: {len(tris)} triangles")

# The 3MF: each distinct corner once, triangles as indices into them; the
# numbers as Python writes the floats (each an f32, so the 3MF's triangles
# are the STL's exactly).
index = {}
for t in tris:
    for p in t:
        index.setdefault(p, len(index))
vertices = "".join(f'<vertex x="{p[0]!r}" y="{p[1]!r}" z="{p[2]!r}"/>\n' for p in index)
triangles = "".join(
    f'<triangle v1="{index[t[0]]}" v2="{index[t[1]]}" v3="{index[t[2]]}"/>\n' for t in tris
)
# Rows m00 m01 m02 / m10 m11 m12 / m20 m21 m22 / m30 m31 m32: a point
# (x, y, z) goes to (30 - y, x, z).
TURN = "0 1 0 -1 0 0 0 0 1 30 0 0"
model = f"""<?xml version="1.0" encoding="UTF-8"?>
<model unit="millimeter" xml:lang="en-US" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">
<metadata name="Title">bracket for examples/bracket_3mf.lmd</metadata>
<resources>
<object id="1" type="model">
<mesh>
<vertices>
{vertices}</vertices>
<triangles>
{triangles}</triangles>
</mesh>
</object>
</resources>
<build>
<item objectid="1" transform="{TURN}"/>
</build>
</model>
"""
CONTENT_TYPES = """<?xml version="1.0" encoding="UTF-8"?>
<Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types"><Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/><Default Extension="model" ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/></Types>
"""
RELS = """<?xml version="1.0" encoding="UTF-8"?>
<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships"><Relationship Target="/3D/3dmodel.model" Id="rel0" Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/></Relationships>
"""
out3 = os.path.join(os.path.dirname(os.path.abspath(__file__)), "bracket.3mf")
with zipfile.ZipFile(out3, "w", zipfile.ZIP_DEFLATED) as z:
    # A fixed date: the same bytes on every run.
    for name, text in [
        ("[Content_Types].xml", CONTENT_TYPES),
        ("_rels/.rels", RELS),
        ("3D/3dmodel.model", model),
    ]:
        info = zipfile.ZipInfo(name, date_time=(2026, 1, 1, 0, 0, 0))
        info.compress_type = zipfile.ZIP_DEFLATED
        z.writestr(info, text)
print(f"{out3}: {len(index)} vertices, {len(tris)} triangles")
