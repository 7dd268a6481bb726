//! How a message names a robot's axes, moves and configuration: in the words
//! of the controller its program is written for (`controller = …`), so a
//! message about an ABB robot speaks of "axis 5", `MoveL` and `confdata`
//! where one about a KUKA robot speaks of A5, `LIN` and Status.

use crate::ir::Controller;

/// The words of a robot's maker, built from its IR robot
/// ([`Words::of`]) and handed to the messages about its arm.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Words {
    /// KUKA's (KRL): axes A1–A6, `LIN` and `PTP`, Status and Turn.
    #[default]
    Kuka,
    /// ABB's (RAPID): axes 1–6, `MoveL`, `MoveJ` from home and `MoveAbsJ`
    /// back, `confdata`.
    Abb,
}

impl Words {
    /// The words of a robot whose controller is `c`.
    pub fn of(c: Controller) -> Words {
        match c {
            Controller::Kuka => Words::Kuka,
            Controller::Abb => Words::Abb,
        }
    }

    /// Axis `i` (0-based) as a name: `A5`, `axis 5`.
    pub fn axis(self, i: usize) -> String {
        match self {
            Words::Kuka => format!("A{}", i + 1),
            Words::Abb => format!("axis {}", i + 1),
        }
    }

    /// Axis `i` (0-based) introduced as an axis: `axis A5`, `axis 5`.
    pub fn an_axis(self, i: usize) -> String {
        match self {
            Words::Kuka => format!("axis A{}", i + 1),
            Words::Abb => format!("axis {}", i + 1),
        }
    }

    /// The six axes' names, first to last, after "axis": `A1 to A6`, `1 to
    /// 6`.
    pub fn six_axes(self) -> &'static str {
        match self {
            Words::Kuka => "A1 to A6",
            Words::Abb => "1 to 6",
        }
    }

    /// The linear move: `LIN`, `MoveL`.
    pub fn lin(self) -> &'static str {
        match self {
            Words::Kuka => "LIN",
            Words::Abb => "MoveL",
        }
    }

    /// The joint move from home to the plan's first pose: `PTP`, `MoveJ`
    /// (docs/rapid.md: `main` goes home with `MoveAbsJ`, the first motion
    /// module moves on from there with `MoveJ`).
    pub fn leave_home(self) -> &'static str {
        match self {
            Words::Kuka => "PTP",
            Words::Abb => "MoveJ",
        }
    }

    /// The joint move back home: `PTP`, `MoveAbsJ`.
    pub fn back_home(self) -> &'static str {
        match self {
            Words::Kuka => "PTP",
            Words::Abb => "MoveAbsJ",
        }
    }

    /// Both joint moves, from home and back: `both PTPs`, `the MoveJ from
    /// home and the MoveAbsJ back`.
    pub fn home_moves(self) -> &'static str {
        match self {
            Words::Kuka => "both PTPs",
            Words::Abb => "the MoveJ from home and the MoveAbsJ back",
        }
    }

    /// The analog output `s` as the program writes it: `$ANOUT[2]`, `ao2`
    /// or the signal's name.
    pub fn analog_out(self, s: &crate::ir::Signal) -> String {
        match self {
            Words::Kuka => format!("$ANOUT[{s}]"),
            Words::Abb => crate::target::rapid::signal(s, true),
        }
    }

    /// The analog outputs as a kind: `$ANOUT`, or the signal `s`'s name.
    pub fn analog_outs(self, s: &crate::ir::Signal) -> String {
        match self {
            Words::Kuka => "$ANOUT".to_string(),
            Words::Abb => crate::target::rapid::signal(s, true),
        }
    }

    /// The arm's home on its controller: `$H_POS`, its home `jointtarget`.
    pub fn home(self) -> &'static str {
        match self {
            Words::Kuka => "`$H_POS`",
            Words::Abb => "its home `jointtarget`",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// KUKA's names stay as they were; ABB's are its manuals'.
    #[test]
    fn each_maker_names_axes_and_moves_its_way() {
        assert_eq!(Words::of(Controller::Kuka), Words::Kuka);
        assert_eq!(Words::of(Controller::Abb), Words::Abb);
        let k = Words::Kuka;
        assert_eq!(
            (k.axis(4), k.an_axis(0), k.six_axes()),
            ("A5".into(), "axis A1".into(), "A1 to A6")
        );
        assert_eq!(
            (k.lin(), k.leave_home(), k.back_home()),
            ("LIN", "PTP", "PTP")
        );
        let a = Words::Abb;
        assert_eq!(
            (a.axis(4), a.an_axis(0), a.six_axes()),
            ("axis 5".into(), "axis 1".into(), "1 to 6")
        );
        assert_eq!(
            (a.lin(), a.leave_home(), a.back_home()),
            ("MoveL", "MoveJ", "MoveAbsJ")
        );
        let named = crate::ir::Signal::Name("aoLaserPower".into());
        let numbered = crate::ir::Signal::Number(2);
        assert_eq!(k.analog_out(&numbered), "$ANOUT[2]");
        assert_eq!(a.analog_out(&numbered), "ao2");
        assert_eq!(a.analog_out(&named), "aoLaserPower");
    }
}
