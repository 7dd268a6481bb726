"""Property tests of the flange example from Python (docs/testing.md): a
hypothesis sweep of its outside diameter through `lmdc build --set`, the
plan read back as data (`--emit ir`, `--emit plan`) and validated against
lmdc's published schemas first.

    python3 -m pip install hypothesis pytest jsonschema-rs
    PATH="$PWD/target/release:$PATH" python3 -m pytest -q examples/python

`lmdc` is taken from $LMDC, else from PATH."""

import json
import math
import os
import pathlib
import subprocess
import tempfile

import jsonschema_rs
from hypothesis import given, settings, strategies as st

ROOT = pathlib.Path(__file__).resolve().parents[2]
LMDC = os.environ.get("LMDC", "lmdc")
IR_SCHEMA = jsonschema_rs.validator_for(json.loads((ROOT / "docs/ir.schema.json").read_text()))
PLAN_SCHEMA = jsonschema_rs.validator_for(json.loads((ROOT / "docs/plan.schema.json").read_text()))

BEAD = 3.0  # mm, the flange's bead width
CHORD = 0.02  # mm, what flattening the round outlines may take off


def build(od, out):
    """Builds the flange with outside diameter `od` (mm) into `out`: True when
    it compiled; False when lmdc refused that diameter (and said why, as JSON
    lines with a code)."""
    r = subprocess.run(
        [LMDC, "build", str(ROOT / "examples/flange.lmd"), "-o", out,
         "--emit", "ir", "--emit", "plan", "--set", f"OD={od:.3f} mm",
         "--message-format", "json", "--quiet"],
        capture_output=True, text=True)
    if r.returncode == 1:
        codes = [json.loads(line)["code"] for line in r.stdout.splitlines()]
        assert codes, r.stderr
        return False
    assert r.returncode == 0, r.stdout + r.stderr
    return True


def inside_flange(x, y, od):
    """How far (x, y) lies inside the flange's drawing in plan, mm: a disc of
    `od` with a 30 mm bore and six 9 mm holes on a 60 mm circle from 30°."""
    margin = min(od / 2 - math.hypot(x, y), math.hypot(x, y) - 15)
    for k in range(6):
        a = math.radians(30 + 60 * k)
        margin = min(margin, math.hypot(x - 30 * math.cos(a), y - 30 * math.sin(a)) - 4.5)
    return margin


@settings(max_examples=12, deadline=None)
@given(od=st.floats(min_value=72, max_value=95))
def test_every_deposit_point_lies_inside_the_design_solid(od):
    with tempfile.TemporaryDirectory() as out:
        if not build(od, out):
            return
        ir = json.loads(pathlib.Path(out, "flange.ir.json").read_text())
        IR_SCHEMA.validate(ir)
        for layer in ir["layers"]:
            for path in layer["paths"]:
                pts = path["points"]
                for a, b in zip(pts, pts[1:]):
                    if not a["laser_on"]:
                        continue
                    for p in (a, b):
                        x, y, z = p["pos"]
                        assert z >= 0, p
                        # size = outer: the bead's edge on the drawing's faces
                        assert inside_flange(x, y, od) >= BEAD / 2 - CHORD, (od, p["pos"])


@settings(max_examples=12, deadline=None)
@given(od=st.floats(min_value=72, max_value=95))
def test_the_laser_is_never_on_during_a_travel(od):
    with tempfile.TemporaryDirectory() as out:
        if not build(od, out):
            return
        plans = list(pathlib.Path(out).glob("flange_*.plan.jsonl"))
        assert len(plans) == 2, plans
        for plan in plans:
            deposits = 0
            for line in plan.read_text().splitlines():
                step = json.loads(line)
                PLAN_SCHEMA.validate(step)
                if step["type"] == "move" and step["laser"]:
                    assert step["kind"] == "deposit", (plan.name, step)
                    deposits += 1
            assert deposits > 0, plan.name


def test_the_design_property_can_fail():
    """A drawing 2 mm smaller than the part planned puts the outer contour
    outside it: the check above would see it."""
    with tempfile.TemporaryDirectory() as out:
        assert build(80, out)
        ir = json.loads(pathlib.Path(out, "flange.ir.json").read_text())
        worst = min(inside_flange(p["pos"][0], p["pos"][1], 76)
                    for layer in ir["layers"] for path in layer["paths"]
                    for p in path["points"] if p["laser_on"])
        assert worst < 0
