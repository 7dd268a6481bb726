//! File names every system can open.
//!
//! Windows refuses to create or open a file whose name, up to its first dot,
//! is a device name (`CON`, `PRN`, `AUX`, `NUL`, `COM0`–`COM9`, `LPT0`–`LPT9`,
//! `COM¹²³`, `LPT¹²³`, `CONIN$`, `CONOUT$`), in any case and with any
//! extension: `con.src` and `Nul.dat` cannot be written, and a program
//! copied to a Windows controller or share from Linux cannot be opened. A
//! part called `con` must therefore not become `con.src`.

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

#[cfg(test)]
mod tests {
    use super::*;

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
