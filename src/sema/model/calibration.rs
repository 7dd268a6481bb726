//! A calibration build (`calibration { … }`): coupons laid on a plate to
//! measure a bead, each at its own speed, power and powder feed.

use crate::span::Span;
use crate::units::{Length, MassFlow, Power, Speed};

/// The coupons of a calibration file, laid out on its plate.
#[derive(Clone, Debug)]
pub struct Calibration {
    /// The bead measured (its name).
    pub bead: String,
    /// Its declared width: a track's, a wall's; the pads' tracks overlap by it.
    pub width: Length,
    /// How far a wall's layers are apart; the height every coupon is planned at.
    pub layer_height: Length,
    /// What each coupon is.
    pub kind: CouponKind,
    /// Each coupon's length, along x.
    pub length: Length,
    /// The coupons, in the order they are laid.
    pub coupons: Vec<Coupon>,
    /// Where the block is written.
    pub span: Span,
}

/// What a coupon is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CouponKind {
    /// A single track.
    Track,
    /// The same track laid `layers` times, one on the other.
    Wall {
        /// How many layers.
        layers: usize,
    },
    /// `tracks` overlapped tracks `offset` apart, in one layer.
    Pad {
        /// How many tracks.
        tracks: usize,
        /// Centre to centre.
        offset: Length,
    },
}

impl CouponKind {
    /// Its name in the sheet and the program comments: no comma, no
    /// bracket (a CSV cell, a G-code comment).
    pub fn name(self) -> String {
        match self {
            CouponKind::Track => "track".into(),
            CouponKind::Wall { layers } => format!("wall of {layers} layers"),
            CouponKind::Pad { tracks, offset } => {
                format!(
                    "pad of {tracks} tracks {} mm apart",
                    crate::units::short(offset.0)
                )
            }
        }
    }

    /// How many layers a coupon of this kind has.
    pub fn layers(self) -> usize {
        match self {
            CouponKind::Wall { layers } => layers,
            _ => 1,
        }
    }

    /// How many tracks each of its layers has.
    pub fn tracks(self) -> usize {
        match self {
            CouponKind::Pad { tracks, .. } => tracks,
            _ => 1,
        }
    }

    /// The distance between its tracks' centre lines (0 for one track).
    pub fn offset(self) -> Length {
        match self {
            CouponKind::Pad { offset, .. } => offset,
            _ => Length(0.0),
        }
    }

    /// How wide a coupon of a bead `width` wide is, across its tracks.
    pub fn footprint(self, width: Length) -> Length {
        Length(width.0 + (self.tracks() - 1) as f64 * self.offset().0)
    }
}

/// One coupon: its parameters and where it lies.
#[derive(Clone, Debug, PartialEq)]
pub struct Coupon {
    /// `c01`, `c02`, … in the order laid.
    pub id: String,
    /// Its scan speed.
    pub speed: Speed,
    /// Its laser power.
    pub power: Power,
    /// Its powder feed.
    pub powder: MassFlow,
    /// The start of its first track's centre line on the plate, mm; the
    /// tracks run along +x, a pad's next ones `offset` further along +y.
    pub start: [f64; 2],
}
