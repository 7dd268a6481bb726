//! Every `machine NAME { … }` statement: names given once, each block read by
//! [`machine::read`](crate::sema::machine::read) on its own, so one machine's
//! mistakes do not hide another's.

use crate::diag::{message, Diagnostics};
use crate::ir::{Machine, MachineOrigin};
use crate::sema::eval::Env;
use crate::sema::machine;
use crate::sema::schema::machine::NAME;
use crate::sema::statement::{shape_error, Statements};
use crate::span::Span;
use crate::syntax::ast::Body;
use std::collections::BTreeMap;

/// The machines that are right, with where they and their fields are written.
pub fn read<'a>(
    env: &mut Env<'a>,
    st: &Statements<'a>,
    diags: &mut Diagnostics,
) -> Vec<(Machine, MachineOrigin)> {
    let mut machines = Vec::new();
    let mut seen: BTreeMap<&str, Span> = BTreeMap::new();
    for s in st.get("machine") {
        let (Some(n), Body::Block(stmts, _)) = (&s.name, &s.body) else {
            diags.push(shape_error(
                s,
                "machine NAME { … }",
                "machine kr60 { kind = robot … }",
            ));
            continue;
        };
        match seen.get(n.node.as_str()) {
            Some(&prev) => diags.push(message::machine::duplicate_machine(&n.node, n.span, prev)),
            None => {
                seen.insert(&n.node, n.span);
            }
        }
        if let Some((m, mut fields)) = machine::read(env, &n.node, stmts, s.span, diags) {
            fields.push((&NAME, n.span));
            machines.push((m, machine::origin::origin(s.span, &fields)));
        }
    }
    if st.get("machine").is_empty() {
        diags.push(message::machine::no_machine());
    }
    machines
}
