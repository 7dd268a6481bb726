use lmdc::pipeline::compile;

#[test]
fn twisted_duct_compiles() {
    let src = std::fs::read_to_string("examples/twisted_duct.lmd").unwrap();
    let c = compile(&src, &mut ());
    let text = lmdc::diag::render(&c.diagnostics, "twisted_duct.lmd", &src, false);
    eprintln!("{text}");
    let p = c.program.expect("compiles");
    let ir = p.ir();
    eprintln!(
        "layers {} points {} limits {:?}",
        ir.layers.len(),
        ir.point_count(),
        ir.limits
    );
}

#[test]
fn tight_prints() {
    let src = std::fs::read_to_string("/tmp/tight.lmd").unwrap();
    let c = compile(&src, &mut ());
    eprintln!(
        "{}",
        lmdc::diag::render(&c.diagnostics, "tight.lmd", &src, false)
    );
}
