//! ABB's configuration data of a solution (`confdata`: `cf1, cf4, cf6,
//! cfx` of a `robtarget`), from the same solutions the verifier checks.

use super::{Joints, Solver};

impl Solver {
    /// ABB's `[cf1, cf4, cf6, cfx]` of the solution `j` (controller's axis
    /// angles, deg): the quadrants of axes 1, 4 and 6 (0 for 0°..90°, −1 for
    /// −90°..0°, …), and `cfx` = 4·(wrist centre behind axis 1) + 2·(wrist
    /// centre behind the lower arm) + (axis 5 negative).
    pub fn confdata(&self, j: &Joints) -> [i32; 4] {
        let quadrant = |a: f64| (a / 90.0).floor() as i32;
        let s = self.status(j);
        let cfx = 4 * i32::from(s & 1) + 2 * i32::from((s >> 1) & 1) + i32::from(j[4] < 0.0);
        [quadrant(j[0]), quadrant(j[3]), quadrant(j[5]), cfx]
    }
}
