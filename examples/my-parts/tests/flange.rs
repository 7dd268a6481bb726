// my-parts/tests/flange.rs
use proptest::prelude::*;

const SRC: &str = include_str!("../parts/flange.lmd");

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]
    #[test]
    fn every_deposit_is_fed_with_the_laser_on(od in 70.0f64..95.0) {
        let options = lmdc::Options {
            set: vec![format!("OD={od:.2} mm").parse().unwrap()],
            ..Default::default()
        };
        // An OD the part cannot take is lmdc's error, not the property's.
        let Ok(program) = lmdc::compile(SRC, &options) else { return Ok(()) };
        for m in program.machines() {
            m.plan().walk(&mut |mv: &lmdc::plan::Move| {
                if mv.deposits() {
                    let fed = matches!(mv.speed, lmdc::plan::Speed::Feed(v) if v > 0.0);
                    assert!(fed && mv.power > 0.0, "{mv:?}");
                }
            });
        }
    }
}
