//! The fixtures fixed to a machine whose table or positioner turns the
//! part (`fixture { machine = NAME }`, docs/collision.md): where each stands
//! from the part changes with every move, so the page draws them at the
//! slider's move. It gets each fixture as declared (in the machine's
//! coordinates, or its tilt axis's body's), the part's frame as its turns
//! ([`PartFrame::turns`]) and the axes at the moves the arm is posed at
//! (every k-th, at most [`super::joints::POSES`]); the viewer brings the
//! fixture into the part's coordinates with the frame at the last posed
//! move at or before the slider's.

use super::encode::FixtureBox;
use crate::ir::{Machine, Program};
use crate::plan::part_frame::{PartFrame, Turn};
use crate::plan::{Move, Plan, Visit};
use serde::Serialize;

/// What the page says about the fixtures that move with the axes.
#[derive(Serialize)]
pub struct Moving<'a> {
    /// Each fixture as declared, its box in its own coordinates.
    pub fixtures: Vec<FixtureBox<'a>>,
    /// Whether each stands on the tilt axis's body (`turns_with = tilt`).
    pub tilts: Vec<bool>,
    /// The tilt axis's turn, then the C axis's (E2's).
    pub turns: [Turn; 2],
    /// The constant after them: rows of `[R | t]`.
    pub then: [[f64; 4]; 3],
    /// The page's moves posed, ascending.
    pub moves: Vec<usize>,
    /// The axes at each (tilt, C; E1, E2), deg.
    pub axes: Vec<[f64; 2]>,
}

/// The axes at the plan's moves wanted.
struct Axes {
    want: std::vec::IntoIter<(usize, usize)>,
    next: Option<(usize, usize)>,
    index: usize,
    moves: Vec<usize>,
    axes: Vec<[f64; 2]>,
}

impl Visit for Axes {
    fn motion(&mut self, m: &Move) {
        while let Some((plan, page)) = self.next.filter(|w| w.0 <= self.index) {
            if plan == self.index {
                self.moves.push(page);
                self.axes.push([m.axes.tilt, m.axes.c]);
            }
            self.next = self.want.next();
        }
        self.index += 1;
    }
}

/// The fixtures of `program` fixed to `machine` where its part's frame
/// moves, with the axes at the plan's moves `want` (`(plan move index,
/// page move index)`, ascending); `None` where there are none.
pub fn of<'a>(
    program: &'a Program,
    machine: &Machine,
    plan: &Plan<'_>,
    want: Vec<(usize, usize)>,
) -> Option<Moving<'a>> {
    let ([t, c], then) = PartFrame::of(machine)?.turns()?;
    let name = machine.name();
    let ours: Vec<_> = (program.fixtures.iter())
        .filter(|f| f.fixed_to(name) == Some(true))
        .collect();
    if ours.is_empty() {
        return None;
    }
    let mut want = want.into_iter();
    let mut a = Axes {
        next: want.next(),
        want,
        index: 0,
        moves: Vec::new(),
        axes: Vec::new(),
    };
    plan.walk(&mut a);
    let m = then.to_homogeneous();
    Some(Moving {
        fixtures: ours.iter().map(|f| FixtureBox::of(f)).collect(),
        tilts: ours.iter().map(|f| f.tilts).collect(),
        turns: [t, c],
        then: std::array::from_fn(|r| std::array::from_fn(|k| m[(r, k)])),
        moves: a.moves,
        axes: a.axes,
    })
}
