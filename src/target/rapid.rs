//! ABB IRC5 and OmniCore controllers (RobotWare 6 and 7) as lmdc writes
//! RAPID for them (docs/rapid.md).

/// The RAPID name of an output: the signal's own name, or by number
/// `do<n>` (`analog`: `ao<n>`).
pub fn signal(s: &crate::ir::Signal, analog: bool) -> String {
    match s {
        crate::ir::Signal::Number(n) => format!("{}{n}", if analog { "ao" } else { "do" }),
        crate::ir::Signal::Name(name) => name.clone(),
    }
}

/// Longest RAPID name (modules, routines, data).
pub const MAX_NAME: usize = 32;

/// Highest TCP speed lmdc writes in a `speeddata`, mm/s: ABB's largest
/// predefined speed, `v7000`.
pub const V_TCP_MAX: f64 = 7000.0;

/// Decimals of x, y, z (mm) and of the external axes (deg) in a
/// `robtarget`.
pub const POS_DECIMALS: usize = 3;
/// Decimals of a quaternion's components: a unit quaternion to within
/// 10⁻⁵, as the controller wants it.
pub const QUAT_DECIMALS: usize = 6;
/// Decimals of a `speeddata`'s `v_tcp`, mm/s.
pub const SPEED_DECIMALS: usize = 3;
/// Decimals of an analog output (fraction of full scale).
pub const AO_DECIMALS: usize = 4;

/// RAPID's reserved words a name made of the part and machine could be.
pub const RESERVED: &[&str] = &[
    "ALIAS",
    "AND",
    "BACKWARD",
    "CASE",
    "CONNECT",
    "CONST",
    "DEFAULT",
    "DIV",
    "DO",
    "ELSE",
    "ELSEIF",
    "ENDFOR",
    "ENDFUNC",
    "ENDIF",
    "ENDMODULE",
    "ENDPROC",
    "ENDRECORD",
    "ENDTEST",
    "ENDTRAP",
    "ENDWHILE",
    "ERROR",
    "EXIT",
    "FALSE",
    "FOR",
    "FROM",
    "FUNC",
    "GOTO",
    "IF",
    "INOUT",
    "LOCAL",
    "MOD",
    "MODULE",
    "NOSTEPIN",
    "NOT",
    "NOVIEW",
    "OR",
    "PERS",
    "PROC",
    "RAISE",
    "READONLY",
    "RECORD",
    "RETRY",
    "RETURN",
    "STEP",
    "SYSMODULE",
    "TEST",
    "THEN",
    "TO",
    "TRAP",
    "TRUE",
    "TRYNEXT",
    "UNDO",
    "VAR",
    "VIEWONLY",
    "WHILE",
    "WITH",
    "XOR",
    "MAIN",
];
