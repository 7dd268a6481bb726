//! The `fixture NAME { shape = …  at = […]  machine = … }` statements: the
//! clamps and fixtures on the plate, in the part's coordinates, which every
//! machine's head keeps its gap from, or fixed to one machine in its own
//! coordinates (docs/collision.md): a box, a cylinder, or a mesh read as
//! the part's is.

use crate::diag::{message, Diagnostics};
use crate::ir::{Fixture, FixtureShape, Machine, MachineOrigin};
use crate::sema::eval::unknown_name;
use crate::sema::eval::Env;
use crate::sema::fields::{self, Fields};
use crate::sema::schema::collision::{self as c, BOX, CYLINDER, FIXTURE, MAX_SIZE_MM};
use crate::sema::schema::solid;
use crate::sema::solid::mesh as mesh_reader;
use crate::sema::statement::{shape_error, Statements};
use crate::sema::value::Value;
use crate::span::Span;
use crate::units::Dim;
use std::collections::BTreeMap;

/// Every fixture that is written right, with where it is placed (its
/// `at`, else its name): what a collision with it points at.
pub fn read<'a>(
    env: &mut Env<'a>,
    st: &Statements<'a>,
    machines: &[(Machine, MachineOrigin)],
    diags: &mut Diagnostics,
) -> Vec<(Fixture, Span)> {
    let mut out = Vec::new();
    let mut seen = BTreeMap::new();
    for s in st.get("fixture") {
        let (Some(n), crate::syntax::ast::Body::Block(stmts, _)) = (&s.name, &s.body) else {
            diags.push(shape_error(s, "fixture NAME { … }", FIXTURE.syntax));
            continue;
        };
        if let Some(&prev) = seen.get(n.node.as_str()) {
            diags.push(message::collision::duplicate_fixture(&n.node, n.span, prev));
            continue;
        }
        seen.insert(n.node.as_str(), n.span);
        let f = Fields::block(
            env,
            stmts,
            &FIXTURE,
            format!("fixture `{}`", n.node),
            s.span,
            diags,
        );
        let shape = shape(&f, env.data.as_ref(), diags);
        let placed = f.span(&c::AT).unwrap_or(n.span);
        let at = at(&f, diags);
        let machine = machine(&f, (st, machines), &n.node, diags);
        let tilts = machine
            .as_ref()
            .and_then(|m| tilts(&f, m.as_deref(), machines, diags));
        if let (Some(shape), Some(at), Some(machine), Some(tilts)) = (shape, at, machine, tilts) {
            let fixture = Fixture {
                name: n.node.clone(),
                shape,
                at,
                machine,
                tilts,
                registration: None,
            };
            out.push((fixture, placed));
        }
    }
    out
}

/// `shape = box(size = […]) | cylinder(length, diameter) | mesh(file, …)`.
fn shape(
    f: &Fields<'_>,
    data: Option<&crate::sema::DataReader>,
    diags: &mut Diagnostics,
) -> Option<FixtureShape> {
    let v = f.value(&c::SHAPE, diags)?;
    let Value::Call(call) = &v.value else {
        diags.push(message::collision::not_a_shape(v.span, &v.value.describe()));
        return None;
    };
    if call.func == BOX.name {
        let a = Fields::call(call, &BOX, diags);
        let v = a.value(&c::SIZE, diags)?;
        let size = three(v, c::SIZE.key, diags)?;
        if let Some(bad) = size.iter().find(|s| !(*s > &0.0 && **s <= MAX_SIZE_MM)) {
            diags.push(message::collision::bad_size(v.span, *bad, MAX_SIZE_MM));
            return None;
        }
        return Some(FixtureShape::Box { size });
    }
    if call.func == CYLINDER.name {
        let a = Fields::call(call, &CYLINDER, diags);
        let out = |q: f64, at| message::collision::bad_size(at, q, MAX_SIZE_MM);
        let length = a.bounded(&c::LENGTH, out, diags);
        let diameter = a.bounded(&c::DIAMETER, out, diags);
        return Some(FixtureShape::Cylinder {
            diameter: diameter?.0,
            length: length?.0,
        });
    }
    if call.func == solid::MESH.name {
        return mesh(call, v.span, data, diags);
    }
    diags.push(message::collision::not_a_shape(v.span, &v.value.describe()));
    None
}

/// `mesh(file, units, turn)`: the file's triangles scaled to mm and
/// turned, about the fixture's origin (its `at` moves it), sampled for the
/// collision checks ([`crate::collision::surface`]). The surface need not
/// be closed: only its faces are kept clear of.
fn mesh(
    call: &crate::sema::value::Call,
    at: Span,
    data: Option<&crate::sema::DataReader>,
    diags: &mut Diagnostics,
) -> Option<FixtureShape> {
    let f = Fields::call(call, &solid::MESH, diags);
    if let Some(place) = f.span(&solid::mesh::AT) {
        diags.push(message::collision::mesh_fixture_at(place));
        return None;
    }
    let file = f.text(&solid::mesh::FILE, diags);
    let units = f.word_or_default(&solid::mesh::UNITS, diags);
    let turn = mesh_reader::triple(&f, &solid::mesh::TURN, Dim::ANGLE, diags);
    let ((path, file_at), units, turn) = (file?, units?, turn?);
    let (tris, scale, file_unit) = mesh_reader::load(&f, (&path, file_at), data, diags)?;
    if tris.len() > crate::collision::surface::MAX_TRIANGLES {
        diags.push(message::collision::mesh_fixture_too_big(
            &path,
            tris.len(),
            crate::collision::surface::MAX_TRIANGLES,
            file_at,
        ));
        return None;
    }
    let [rx, ry, rz] = turn.0;
    let rot = nalgebra::Rotation3::from_euler_angles(rx, ry, rz);
    let placed: Vec<[[f64; 3]; 3]> = tris
        .iter()
        .map(|t| {
            t.map(|c| {
                let p = nalgebra::Vector3::new(f64::from(c[0]), f64::from(c[1]), f64::from(c[2]));
                let q = rot * (p * scale);
                [q.x, q.y, q.z]
            })
        })
        .collect();
    drop(tris);
    let mut min = [f64::INFINITY; 3];
    let mut max = [f64::NEG_INFINITY; 3];
    for c in placed.iter().flatten() {
        for k in 0..3 {
            min[k] = min[k].min(c[k]);
            max[k] = max[k].max(c[k]);
        }
    }
    let size = [0, 1, 2].map(|k| max[k] - min[k]);
    if size.iter().any(|s| s.is_nan() || *s > MAX_SIZE_MM) {
        diags.push(message::collision::mesh_fixture_size(
            &path,
            size,
            MAX_SIZE_MM,
            at,
        ));
        return None;
    }
    let surface = crate::collision::surface::sample(&placed);
    Some(FixtureShape::Mesh {
        file: path,
        units: file_unit.unwrap_or(units).to_string(),
        turn: turn.0.map(f64::to_degrees),
        min,
        max,
        tolerance: surface.tolerance,
        samples: crate::ir::MeshSamples(std::sync::Arc::new(surface.samples)),
    })
}

/// `machine = NAME`: a machine of the file (`Some(None)` without it);
/// `None` where it is written wrong or places nothing.
fn machine(
    f: &Fields<'_>,
    (st, machines): (&Statements<'_>, &[(Machine, MachineOrigin)]),
    fixture: &str,
    diags: &mut Diagnostics,
) -> Option<Option<String>> {
    let Some(v) = f.value(&c::MACHINE, diags) else {
        return (!f.has(&c::MACHINE)).then_some(None);
    };
    let Value::Symbol(name) = &v.value else {
        diags.push(message::collision::fixture_machine_not_a_name(
            v.span,
            &v.value.describe(),
        ));
        return None;
    };
    let declared: Vec<&str> = (st.get("machine").iter())
        .filter_map(|s| s.name.as_ref().map(|n| n.node.as_str()))
        .collect();
    if !declared.contains(&name.as_str()) {
        diags.push(unknown_name(name, v.span, "machine", &declared));
        return None;
    }
    match machines.iter().find(|(m, _)| m.name() == name) {
        Some((Machine::Robot(r), _)) if r.base.value.is_none() => {
            diags.push(message::collision::fixture_unplaced(fixture, name, v.span));
            None
        }
        _ => Some(Some(name.clone())),
    }
}

/// `turns_with = nothing | tilt`: whether the fixture turns with the tilt
/// axis of `machine` (the machine it is fixed to, if any), which must have
/// one to turn with.
fn tilts(
    f: &Fields<'_>,
    machine: Option<&str>,
    machines: &[(Machine, MachineOrigin)],
    diags: &mut Diagnostics,
) -> Option<bool> {
    let word = f.word_or_default(&c::TURNS_WITH, diags)?;
    if word != "tilt" {
        return Some(false);
    }
    let at = f.span(&c::TURNS_WITH).unwrap_or_default();
    let Some(name) = machine else {
        diags.push(message::collision::tilts_without_machine(at));
        return None;
    };
    let tilting = match machines.iter().find(|(m, _)| m.name() == name) {
        // Fewer than five axes: no rotary axes, whatever the kinematics.
        Some((Machine::Cnc(c), _)) => c.axes >= 5 && c.kinematics.is_table(),
        Some((Machine::Robot(r), _)) => r.positioner.is_some(),
        // A machine refused on its own: nothing more to say.
        None => return None,
    };
    if !tilting {
        diags.push(message::collision::nothing_tilts(name, at));
        return None;
    }
    Some(true)
}

/// `at = [x, y, z]` (default the origin).
fn at(f: &Fields<'_>, diags: &mut Diagnostics) -> Option<[f64; 3]> {
    match f.value(&c::AT, diags) {
        None if f.has(&c::AT) => None,
        None => Some([0.0; 3]),
        Some(v) => three(v, c::AT.key, diags),
    }
}

/// Three lengths `[x, y, z]`.
fn three(v: &crate::sema::value::Spanned, key: &str, diags: &mut Diagnostics) -> Option<[f64; 3]> {
    let items = match &v.value {
        Value::List(items) if items.len() == 3 => items,
        other => {
            diags.push(message::collision::not_three(
                key,
                v.span,
                &other.describe(),
            ));
            return None;
        }
    };
    let mut out = [0.0; 3];
    let mut ok = true;
    for (o, it) in out.iter_mut().zip(items) {
        match fields::quantity(it, Dim::LENGTH, key, diags) {
            Some(q) => *o = q,
            None => ok = false,
        }
    }
    ok.then_some(out)
}

/// The scanned part an extrusion is built on, as an obstacle: its
/// estimated surface (docs/repair.md) as samples, each a sphere holding the
/// surface over a block of cells, at most [`crate::collision::surface::MAX_SAMPLES`]
/// of them; its box from the lowest surface to the highest (the travels
/// rise over it, the arm's links keep their gap from it).
pub fn scanned(scan: &crate::sema::model::ScanBase) -> Fixture {
    let samples = scan.surface.samples(crate::collision::surface::MAX_SAMPLES);
    let (mut min, mut max) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for s in &samples {
        for k in 0..3 {
            min[k] = min[k].min(s[k] - s[3]);
            max[k] = max[k].max(s[k] + s[3]);
        }
    }
    let tolerance = samples.iter().map(|s| s[3]).fold(0.0, f64::max);
    Fixture {
        name: crate::ir::SCANNED_PART.to_string(),
        shape: FixtureShape::Mesh {
            file: scan.path.clone(),
            units: "mm".into(),
            turn: [0.0; 3],
            min,
            max,
            tolerance,
            samples: crate::ir::MeshSamples(std::sync::Arc::new(samples)),
        },
        at: [0.0; 3],
        machine: None,
        tilts: false,
        registration: scan.registration.as_deref().cloned(),
    }
}
