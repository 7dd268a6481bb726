//! Which of a machine's fields the plan's checks may point at, under the
//! IR's own keys ([`MachineField`]): the one place the language's tables
//! meet the IR's names for them, so the verifier needs no table.

use super::Written;
use crate::ir::{MachineField as K, MachineOrigin};
use crate::sema::schema::collision::HEAD_BLOCK;
use crate::sema::schema::machine::{self as m, gas, limits, positioner as p, powder};
use crate::sema::schema::Field;
use crate::span::Span;

/// Each field a check may name, with its key in the IR.
static KEYS: [(&Field, K); 40] = [
    (&m::NAME, K::Name),
    (&m::MAX_SPEED, K::MaxSpeed),
    (&m::ROTARY_SPEED, K::RotarySpeed),
    (&m::ACCELERATION, K::Acceleration),
    (&m::BLENDING, K::Blending),
    (&m::RAMP, K::Ramp),
    (&m::AXES, K::Axes),
    (&m::FULL_SCALE, K::FullScale),
    (&m::SAFE_HEIGHT, K::SafeHeight),
    (&m::FEED_UNITS, K::FeedUnits),
    (&m::S_DECIMALS, K::SDecimals),
    (&m::S_PER_WATT, K::SPerWatt),
    (&m::TABLE_OUTPUT, K::TableOutput),
    (&m::DIALECT, K::Dialect),
    (&m::HEIGHT_INPUT, K::HeightInput),
    (&m::HEIGHT_DELAY, K::HeightDelay),
    (&m::ARM, K::Arm),
    (&m::CONTROLLER, K::Controller),
    (&m::BASE, K::Base),
    (&m::TOOL, K::Tool),
    (&m::HOME, K::Home),
    (&m::SINGULARITY, K::Singularity),
    (&limits::X, K::Limit('X')),
    (&limits::Y, K::Limit('Y')),
    (&limits::Z, K::Limit('Z')),
    (&limits::A, K::Limit('A')),
    (&limits::B, K::Limit('B')),
    (&limits::C, K::Limit('C')),
    (&gas::PRE_FLOW, K::GasPreFlow),
    (&powder::ARRIVAL, K::PowderArrival),
    (&powder::FULL_SCALE, K::PowderFullScale),
    (&m::POSITIONER_BLOCK, K::Positioner),
    (&p::KEEP, K::PositionerKeep),
    (&p::HOME, K::PositionerHome),
    (&p::FACEPLATE, K::Faceplate),
    (&HEAD_BLOCK, K::Head),
    (&p::TILT_LIMITS, K::TiltLimits),
    (&p::TILT_SPEED, K::TiltSpeed),
    (&p::ROTATE_LIMITS, K::RotateLimits),
    (&p::ROTATE_SPEED, K::RotateSpeed),
];

/// The IR's key for `field`, if a check may point at it.
pub fn key(field: &Field) -> Option<K> {
    KEYS.iter().find(|(f, _)| *f == field).map(|&(_, k)| k)
}

/// Where the machine declared at `block` and the fields its checks name
/// are written.
pub fn origin(block: Span, written: &Written) -> MachineOrigin {
    MachineOrigin {
        block,
        fields: written
            .iter()
            .filter_map(|&(f, at)| key(f).map(|k| (k, at)))
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two fields under one key would make a check point at whichever was
    /// read first.
    #[test]
    fn every_key_names_one_field() {
        let all: Vec<K> = KEYS.iter().map(|&(_, k)| k).collect();
        for (i, k) in all.iter().enumerate() {
            assert!(!all[i + 1..].contains(k), "{k:?} twice");
        }
        assert_eq!(key(&m::MAX_SPEED), Some(K::MaxSpeed));
        assert_eq!(key(&p::TILT_SPEED), Some(K::TiltSpeed));
        assert_eq!(key(&m::KIND), None);
    }
}
