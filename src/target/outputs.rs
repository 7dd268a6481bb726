//! How each control numbers its digital and analog outputs: what an
//! output number in a machine block may be.

/// How a machine's control numbers its outputs.
#[derive(Clone, Copy, Debug)]
pub struct Outputs {
    /// Digital outputs `lo..=hi`.
    pub digital: (usize, usize),
    /// Analog outputs `lo..=hi`.
    pub analog: (usize, usize),
}

/// KUKA: `$OUT[1..4096]`, `$ANOUT[1..32]`.
pub const KUKA: Outputs = Outputs {
    digital: (1, 4096),
    analog: (1, 32),
};

/// LinuxCNC: `motion.digital-out-NN` and `motion.analog-out-NN`, 00–63.
pub const LINUXCNC: Outputs = Outputs {
    digital: (0, 63),
    analog: (0, 63),
};

/// Another G-code control, through the lines the machine block gives.
pub const OTHER_CNC: Outputs = Outputs {
    digital: (0, 9999),
    analog: (0, 9999),
};
