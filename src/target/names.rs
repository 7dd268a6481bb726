//! The names of the files each machine's program is written to. The back ends
//! name their files with these functions and the verifier checks with the same
//! ones that no two machines would write the same file.

use super::kuka;
use crate::ir::{Cnc, Robot};

/// Longest G-code program name stem: Sinumerik 840D program names have at most
/// 24 characters.
pub const GCODE_MAX_NAME: usize = 24;

/// A file-name-safe identifier from `text`: letters, digits and `_`, starting with
/// a letter, lower case, at most `max` characters.
pub fn identifier(text: &str, max: usize) -> String {
    let mut s: String = text
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '_'
            }
        })
        .collect();
    if !s.starts_with(|c: char| c.is_ascii_alphabetic()) {
        s.insert(0, 'p');
    }
    s.truncate(max);
    s
}

/// The stem of a program's file name: `identifier(part_machine)`, at most `max`
/// characters. The part's name is shortened first; a machine name too long to
/// keep whole keeps its start and gets a hash of the whole name, so two
/// machines of one part keep distinct names.
pub fn program_stem(part: &str, machine: &str, max: usize) -> String {
    windows_safe(&stem(part, machine, max))
}

fn stem(part: &str, machine: &str, max: usize) -> String {
    let mut full = identifier(&format!("{part}_{machine}"), usize::MAX);
    if full.len() <= max {
        return full;
    }
    // identifier() maps char for char, so the tail is "_" + the machine's name.
    let tail = machine.chars().count() + 1;
    if tail + 1 < max {
        return format!("{}{}", &full[..max - tail], &full[full.len() - tail..]);
    }
    // `p_` + the machine's start + `_` + 4 hex digits of its whole name.
    const HASHED: usize = 1 + 1 + 1 + 4;
    if max <= HASHED {
        full.truncate(max);
        return full;
    }
    let head: String = full[full.len() - tail + 1..]
        .chars()
        .take(max - HASHED)
        .collect();
    format!(
        "{}_{head}_{:04x}",
        &full[..1],
        fnv1a(machine.as_bytes()) & 0xffff
    )
}

// Windows refuses to create or open a file whose name, up to its first dot,
// is a device name, in any case and with any extension: a program copied to a
// Windows controller or share could not be opened.

/// Device names Windows reserves, upper case.
const RESERVED: &[&str] = &[
    "CON", "PRN", "AUX", "NUL", "CONIN$", "CONOUT$", "COM0", "COM1", "COM2", "COM3", "COM4",
    "COM5", "COM6", "COM7", "COM8", "COM9", "COM¹", "COM²", "COM³", "LPT0", "LPT1", "LPT2", "LPT3",
    "LPT4", "LPT5", "LPT6", "LPT7", "LPT8", "LPT9", "LPT¹", "LPT²", "LPT³",
];

/// Whether Windows reserves `name` (a whole file name or a stem): its part
/// before the first dot, without the trailing spaces and dots Windows
/// ignores, is a device name in any case.
pub fn is_windows_reserved(name: &str) -> bool {
    let base = name.split('.').next().unwrap_or("");
    let base = base.trim_end_matches([' ', '.']);
    RESERVED.iter().any(|r| r.eq_ignore_ascii_case(base))
}

/// `stem` made safe to use as a file name on Windows: a reserved device name
/// (see [`is_windows_reserved`]) gets `_` after its device part (`con` →
/// `con_`, `LPT1` → `LPT1_`, `nul.x` → `nul_.x`); any other stem is returned
/// unchanged. Apply it to the stem every file of a program is named from
/// (and, for KRL, the `DEF` name, which must equal the file's): `con_.src`,
/// `con__m0001.src` then stay distinct from any other part's files. The
/// result is one character longer only for a stem of at most 7 characters,
/// so it fits any name length limit of 8 or more.
pub fn windows_safe(stem: &str) -> String {
    if !is_windows_reserved(stem) {
        return stem.to_string();
    }
    let end = stem
        .split('.')
        .next()
        .unwrap_or("")
        .trim_end_matches([' ', '.'])
        .len();
    format!("{}_{}", &stem[..end], &stem[end..])
}

/// 32-bit FNV-1a: a stable hash, the same on every machine and release.
fn fnv1a(bytes: &[u8]) -> u32 {
    bytes.iter().fold(0x811c_9dc5, |h: u32, &b| {
        (h ^ u32::from(b)).wrapping_mul(0x0100_0193)
    })
}

/// The file name of the G-code program for `cnc`:
/// `identifier(part_machine).extension`, the stem at most [`GCODE_MAX_NAME`]
/// characters.
pub fn gcode_file(part: &str, cnc: &Cnc) -> String {
    format!(
        "{}.{}",
        program_stem(part, &cnc.name, GCODE_MAX_NAME),
        cnc.dialect.extension
    )
}

/// How a robot's program is split into files.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct KrlNames {
    /// The main program's name (`<stem>.src`, `<stem>.dat`).
    pub stem: String,
    /// Digits of the module numbers.
    pub digits: usize,
}

impl KrlNames {
    /// The names for `robot`'s program of a part with `points` IR points in
    /// `paths` paths. The module numbers get enough digits for an upper bound of
    /// the module count (every point one LIN, at most three more per path and
    /// one at the end), at least 3; the stem is short enough that every module
    /// name is a valid KRL name too.
    pub fn new(part: &str, robot: &Robot, points: usize, paths: usize) -> Self {
        let lines = points + 3 * paths + 1;
        let modules = lines.div_ceil(robot.max_points_per_module.max(1));
        let digits = modules.to_string().len().max(3);
        let s = program_stem(part, &robot.name, kuka::MAX_NAME - 2 - digits);
        let stem = if kuka::RESERVED.contains(&s.to_ascii_uppercase().as_str()) {
            format!("p{s}")
        } else {
            s
        };
        KrlNames { stem, digits }
    }

    /// The name of module number `i` (0-based): `<stem>_m<NNN>`.
    pub fn module(&self, i: usize) -> String {
        format!("{}_m{:0width$}", self.stem, i + 1, width = self.digits)
    }

    /// Every file of a program of `modules` modules: the main `.src`/`.dat`,
    /// then each module's.
    pub fn files(&self, modules: usize) -> Vec<String> {
        let mut out = vec![format!("{}.src", self.stem), format!("{}.dat", self.stem)];
        for i in 0..modules {
            let m = self.module(i);
            out.push(format!("{m}.src"));
            out.push(format!("{m}.dat"));
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stems_keep_the_machine() {
        assert_eq!(program_stem("bent tube", "mill5", 24), "bent_tube_mill5");
        let s = program_stem("a very long part name indeed", "mill5", 24);
        assert_eq!(s.len(), 24);
        assert!(s.ends_with("_mill5"), "{s}");
        assert_eq!(program_stem("42", "m", 24), "p42_m");
        let s = program_stem("x", "a machine with a very long name", 24);
        assert_eq!(s.len(), 24);
        assert!(program_stem("part", "kr60", 19).len() <= 19);
    }

    #[test]
    fn long_machine_names_stay_distinct() {
        let a = program_stem("bracket", "cnc_with_a_rather_long_name_1", 24);
        let b = program_stem("bracket", "cnc_with_a_rather_long_name_2", 24);
        assert_ne!(a, b);
        for s in [&a, &b] {
            assert_eq!(s.len(), 24, "{s}");
            assert!(s.starts_with("b_cnc_with_a_rath"), "{s}");
        }
        let k = program_stem("very_long_part_name", "a_seventeen_chars", 19);
        assert!(k.len() <= 19 && k.contains("a_seventeen"), "{k}");
    }

    #[test]
    fn device_names_are_renamed_in_any_case() {
        for (stem, want) in [
            ("CON", "CON_"),
            ("con", "con_"),
            ("Prn", "Prn_"),
            ("aux", "aux_"),
            ("NUL", "NUL_"),
            ("com1", "com1_"),
            ("COM9", "COM9_"),
            ("lpt1", "lpt1_"),
            ("LpT9", "LpT9_"),
            ("com0", "com0_"),
            ("COM¹", "COM¹_"),
            ("conin$", "conin$_"),
            ("con.src", "con_.src"),
            ("nul.tar.gz", "nul_.tar.gz"),
        ] {
            assert_eq!(windows_safe(stem), want, "{stem}");
            assert!(!is_windows_reserved(&windows_safe(stem)), "{stem}");
            assert!(!is_windows_reserved(&format!("{}.src", windows_safe(stem))));
        }
    }

    #[test]
    fn other_names_are_kept() {
        for stem in [
            "console",
            "con_kr60",
            "com10",
            "lpt",
            "com",
            "nul_m0001",
            "auxiliary",
            "icon",
            "p_con",
            "",
            "twisted_duct_kr60",
        ] {
            assert_eq!(windows_safe(stem), stem);
        }
    }

    #[test]
    fn the_names_a_program_is_written_as() {
        // A part `con` with a machine `x` has the stem `con_x` (safe); a stem
        // that is all device name is not, nor are its files.
        let stem = windows_safe("con");
        for ext in [".src", ".dat", ".ngc"] {
            assert!(is_windows_reserved(&format!("con{ext}")));
            assert!(!is_windows_reserved(&format!("{stem}{ext}")));
        }
        assert!(!is_windows_reserved(&format!("{stem}_m0001.src")));
    }
}
