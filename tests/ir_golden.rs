//! Golden IR: a small duct's full plan as JSON, floats rounded to 6 decimals so
//! the snapshot is stable across libm versions. Review every diff.

#[path = "support/duct.rs"]
mod duct;

use serde_json::Value;

fn round(v: &mut Value) {
    match v {
        Value::Number(n) if n.is_f64() => {
            let x = (n.as_f64().unwrap() * 1e6).round() / 1e6;
            // -0 and 0 print alike
            let x = if x == 0.0 { 0.0 } else { x };
            *v = serde_json::json!(x);
        }
        Value::Array(a) => a.iter_mut().for_each(round),
        Value::Object(o) => o.values_mut().for_each(round),
        _ => {}
    }
}

#[test]
fn small_duct_ir() {
    let mut d = duct::Duct::seed();
    d.radius = 60.0;
    d.diameter = 12.0;
    d.side = 12.0;
    d.bend_deg = 3.0;
    d.points = 8;
    let src = d.source();
    let c = lmdc::pipeline::compile(&src, &mut ());
    let p = c.program.expect("compiles");
    assert_eq!(
        p.ir().layers.len(),
        3,
        "a three-layer plan keeps the golden short"
    );
    // Through the text form, as a reader of `--emit ir` sees it (f32 values print short).
    let mut v: Value = serde_json::from_str(&serde_json::to_string(p.ir()).unwrap()).unwrap();
    round(&mut v);
    insta::assert_snapshot!(serde_json::to_string_pretty(&v).unwrap());
}
