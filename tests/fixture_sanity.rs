use crate::support::fixture;
use fixture::*;

#[test]
fn fixture_passes_the_checks() {
    let p = bent_tube(
        4,
        12,
        30.0,
        vec![
            lmdc::ir::Machine::Robot(robot()),
            lmdc::ir::Machine::Cnc(cnc5()),
        ],
    );
    assert_eq!(p.point_count(), 4 * 13 + 3);
    lmdc::verify::verify(p, lmdc::verify::Select::All).expect("fixture is valid IR");
}
