//! Scripted analog inputs for a LinuxCNC program run in rs274.
//!
//! rs274, LinuxCNC's interpreter run alone, has no HAL: `M66 E<n> L0` reads
//! 0 into `#5399` and prints nothing. So a test that runs a ring's loop
//! replaces, in the program's text, each read with a value it scripts:
//! the program reads segment `j`'s input `height_input + j` once a layer,
//! all in segment order, and uses `#5399` on the next line. This rewrite
//! counts the layers at segment 1's read and takes `#5399` from a table of
//! numbered parameters (`#1000` on) set at the top of the program — one
//! per layer and segment. Nothing else of the program changes.
#![allow(dead_code)]

/// First numbered parameter of the table.
const BASE: usize = 1000;
/// Beyond it LinuxCNC's parameters are the system's.
const LAST: usize = 5000;

/// `ngc` with its `M66 E<first + j> L0` reads answered by `inputs[layer][j]`
/// (the raw input, height / full scale), layer by layer.
pub fn scripted(ngc: &str, first: u16, inputs: &[Vec<f64>]) -> String {
    let segments = inputs.first().map_or(0, Vec::len);
    assert!(segments > 0, "no readings");
    assert!(
        BASE + (inputs.len() + 1) * segments < LAST,
        "too many readings for the parameter table"
    );
    let mut out = String::from("#<_test_layer> = 0\n");
    for (l, layer) in inputs.iter().enumerate() {
        assert_eq!(layer.len(), segments);
        for (j, v) in layer.iter().enumerate() {
            // Layer l is read while the counter says l + 1.
            out.push_str(&format!("#{} = {v:.12}\n", BASE + (l + 1) * segments + j));
        }
    }
    let mut segment: Option<usize> = None;
    let mut reads = 0;
    for line in ngc.lines() {
        let t = line.trim();
        if let Some(e) = t
            .strip_prefix("M66 E")
            .and_then(|r| r.strip_suffix(" L0"))
            .and_then(|e| e.parse::<usize>().ok())
        {
            let j = e
                .checked_sub(first as usize)
                .filter(|j| *j < segments)
                .unwrap_or_else(|| panic!("M66 E{e}: not a segment's input"));
            assert_eq!(
                j,
                segment.map_or(0, |s| (s + 1) % segments),
                "reads in segment order"
            );
            segment = Some(j);
            reads += 1;
            out.push_str(&if j == 0 {
                "#<_test_layer> = [#<_test_layer> + 1]\n".to_string()
            } else {
                format!("(scripted read of E{e})\n")
            });
            continue;
        }
        if line.contains("#5399") {
            let j = segment.expect("#5399 before any M66");
            let at = format!("#[{} + #<_test_layer> * {segments}]", BASE + j);
            out.push_str(&line.replace("#5399", &at));
        } else {
            out.push_str(line);
        }
        out.push('\n');
    }
    assert!(reads > 0, "the program reads no input");
    out
}
