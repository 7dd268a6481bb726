//! File names: no two machines may write the same file (the names keep only the
//! letters, digits and `_` of the part's and machine's names, in lower case).

use super::rule::{ProgramCx, ProgramRule};
use crate::diag::{message, Diagnostics};
use crate::ir::{Machine, Program};
use crate::target::names::{gcode_file, KrlNames};
use std::collections::BTreeMap;

/// The files machine `m` writes, given how many moves its plan has.
pub(super) fn files(p: &Program, m: &Machine, moves: u64) -> Vec<String> {
    match m {
        Machine::Robot(r) => {
            let paths = p.layers.iter().map(|l| l.paths.len()).sum();
            let names = KrlNames::new(&p.part, r, p.point_count(), paths);
            let modules = if p.loop_on_machine().is_some() {
                // The loop's one module holds a layer, run once per layer.
                1
            } else {
                (moves as usize).div_ceil(r.max_points_per_module.max(1))
            };
            names.files(modules)
        }
        Machine::Cnc(c) => vec![gcode_file(&p.part, c)],
    }
}

/// `lmd::name-clash`: every file two machines would both write, once per
/// pair of machines. It runs after the plans, whose summaries list the files.
pub(super) struct FileNames;

impl ProgramRule for FileNames {
    fn check(cx: &ProgramCx<'_>, out: &mut Diagnostics) {
        clashes(cx, out);
    }
}

fn clashes(cx: &ProgramCx<'_>, out: &mut Diagnostics) {
    let p = cx.program;
    let mut owner: BTreeMap<String, usize> = BTreeMap::new();
    let mut pairs: BTreeMap<(usize, usize), String> = BTreeMap::new();
    for (m, summary) in cx.plans {
        for f in &summary.files {
            // Case-insensitive file systems (Windows, macOS) see one file.
            match owner.get(&f.to_ascii_lowercase()) {
                Some(&first) if first != *m => {
                    pairs.entry((first, *m)).or_insert_with(|| f.clone());
                }
                Some(_) => {}
                None => {
                    owner.insert(f.to_ascii_lowercase(), *m);
                }
            }
        }
    }
    let ms = &p.machines;
    let o = &p.origins.machines;
    for ((first, second), name) in pairs {
        out.push(message::verify::name_clash(
            ms[first].name(),
            ms[second].name(),
            &name,
            o.get(first).map(|o| o.block),
            o.get(second).map(|o| o.block),
        ));
    }
}
