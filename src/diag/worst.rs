//! The worst offender of a rule: every rule of the verifier reports each kind
//! of violation once, with how often it happens and the case farthest beyond
//! the limit, so one run shows everything to fix without a million lines of
//! output. It lives with the diagnostics because it is what their messages
//! summarise. Where it happens is the rule's own kind of place (the
//! verifier's: a move of the plan); a message only prints it.

/// The violation farthest beyond its limit, and how many there are; `At`
/// says where it happens.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Worst<At> {
    /// How many violations.
    pub count: u64,
    /// The worst value.
    pub value: f64,
    /// The limit it passes.
    pub limit: f64,
    /// Where it happens.
    pub at: At,
}

impl<At> Worst<At> {
    /// Records `value` beyond `limit` at `at` into `slot`, keeping the worst.
    #[cold]
    pub fn hit(slot: &mut Option<Self>, value: f64, limit: f64, at: At) {
        match slot {
            Some(w) => {
                w.count += 1;
                if (value - limit).abs() > (w.value - w.limit).abs() {
                    w.value = value;
                    w.limit = limit;
                    w.at = at;
                }
            }
            None => {
                *slot = Some(Worst {
                    count: 1,
                    value,
                    limit,
                    at,
                })
            }
        }
    }
}

/// `"s"` unless `n` is 1.
pub(crate) fn plural(n: u64) -> &'static str {
    if n == 1 {
        ""
    } else {
        "s"
    }
}
