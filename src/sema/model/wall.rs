//! A wall along an open path (`wall NAME { … }`), as checked: the path,
//! how many beads lie side by side and on which side, how its beads start
//! and end and which way they run; and, built on a scan, the scanned part
//! and the top.

use crate::geometry::open_path::OpenPath;
use crate::sema::model::{ScanBase, Top};
use crate::span::Span;
use crate::units::Length;

/// Where a wall lies relative to its path, looking along it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WallSide {
    /// Centred on the path.
    Centre,
    /// On its left: the path is the wall's right face.
    Left,
    /// On its right: the path is the wall's left face.
    Right,
}

/// How each bead of a wall starts and ends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum WallEnds {
    /// The laser switches on at the path's start and off at its end, where
    /// the nozzle starts and stops.
    Stop,
    /// The nozzle runs this far on past each end with the laser off, at the
    /// bead's speed.
    Lead(Length),
}

/// A wall built on a scanned part (`on = scan(…)`, `top = …`): its layers
/// start on the scanned surface under its beads and rise to its top
/// (docs/repair.md, *A wall on a scan*).
#[derive(Clone, Debug)]
pub struct WallOnScan {
    /// The scanned part.
    pub base: ScanBase,
    /// The finished wall's top, above the part's z = 0: any top an
    /// extrusion takes (a height, `plane(…)`, `edges(…)` over the path's
    /// extent, an expression of `x` and `y`, a target mesh or solid).
    pub top: Top,
    /// The `top = …` field.
    pub top_span: Span,
}

/// A wall along an open path.
#[derive(Clone, Debug)]
pub struct OpenWall {
    /// The wall's name.
    pub name: String,
    /// The path, in the part's x and y.
    pub path: OpenPath,
    /// Where each piece of the path is written (a polyline's piece: its end
    /// point), for the path's faults.
    pub pieces: Vec<Span>,
    /// The `along = …` value.
    pub along_span: Span,
    /// Beads side by side.
    pub beads: usize,
    /// Where it lies relative to the path.
    pub side: WallSide,
    /// How each bead starts and ends.
    pub ends: WallEnds,
    /// Every bead runs from the path's start (a travel back between them),
    /// rather than each layer the other way.
    pub one_way: bool,
    /// The block.
    pub span: Span,
}

impl OpenWall {
    /// Each bead's offset from the path (positive: to its left), mm, in
    /// order across the wall from left to right, for beads of `width`
    /// `pitch` apart.
    pub fn offsets(&self, width: f64, pitch: f64) -> Vec<f64> {
        let n = self.beads;
        (0..n)
            .map(|j| {
                let across = (n - 1 - j) as f64 * pitch;
                match self.side {
                    WallSide::Centre => across - (n - 1) as f64 * pitch / 2.0,
                    WallSide::Left => width / 2.0 + across,
                    WallSide::Right => -(width / 2.0) - (j as f64) * pitch,
                }
            })
            .collect()
    }

    /// How far the wall reaches to the path's left and to its right (its
    /// faces), mm, for beads of `width` `pitch` apart.
    pub fn reach(&self, width: f64, pitch: f64) -> [f64; 2] {
        let d = self.offsets(width, pitch);
        let left = d.iter().fold(f64::NEG_INFINITY, |a, &b| a.max(b)) + width / 2.0;
        let right = -d.iter().fold(f64::INFINITY, |a, &b| a.min(b)) + width / 2.0;
        [left.max(0.0), right.max(0.0)]
    }
}
