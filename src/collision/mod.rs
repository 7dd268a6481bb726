//! Nothing the machine carries hits anything (docs/collision.md): the head's
//! solids ([`head`]) against the plate, the fixtures and the part as it grows
//! ([`material`]), at every pose of the plan.

pub mod arm;
pub mod capsule;
pub mod head;
pub mod material;
pub mod sample_tree;
pub mod surface;

pub use crate::geometry::bisect;
