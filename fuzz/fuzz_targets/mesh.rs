//! Fuzz target: any bytes as the mesh file of a small part — an STL, binary
//! or ASCII, or a 3MF package — end in a plan or diagnostics, within the
//! budgets (issue 39: a 3MF's ZIP bomb, a part in the wrong unit): never a
//! panic, a hang or a runaway allocation. Run with `cargo fuzz run mesh`.
#![no_main]

use libfuzzer_sys::fuzz_target;
use lmdc::pipeline::compile_reading;

const SOURCE: &str = "part p
bead b { width = 3 mm  model = measured(height = 1 mm, speed = 10 mm/s) }
extrude e { profile = mesh(file = \"part.bin\")  size = outer  bead = b }
slicing planar { offset = auto  contours = 1  infill = raster(angle = 0 deg, rotate = 90 deg) }
process { speed = 10 mm/s  power = 1800 W  powder = 12 g/min }
machine m { kind = cnc  axes = 3  dialect = linuxcnc  max_speed = 50 mm/s }
";

fuzz_target!(|data: &[u8]| {
    let bytes = data.to_vec();
    let reader: lmdc::sema::DataReader = std::rc::Rc::new(move |_: &str, kind| {
        // The cap every reader is held to, as the command line's.
        lmdc::sema::data::read_capped(&bytes[..], kind)
    });
    for name in ["part.stl", "part.3mf"] {
        let src = SOURCE.replace("part.bin", name);
        if let Ok((c, _)) = compile_reading(&src, None, &mut (), reader.clone()) {
            let _ = lmdc::diag::render(&c.diagnostics, "fuzz.lmd", &src, false);
        }
    }
});
