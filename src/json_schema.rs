//! The JSON Schemas of what lmdc writes as data: docs/ir.schema.json (the
//! IR, `--emit ir`) and docs/report.schema.json (`lmdc report --json`, one
//! object a machine). They are derived from the types that serialise the
//! data (schemars, behind the `json-schema` feature that only CI turns on,
//! so neither the build nor `cargo test` compiles it), with the serialising side's view (`for_serialize`: a field skipped
//! when empty is optional, every other field required) and strict objects
//! (no property the type does not have), so a schema cannot fall behind the
//! code: the test below fails when a file in docs/ is stale, and
//! `LMDC_UPDATE_DOCS=1 cargo test --release --lib --features json-schema
//! json_schema` rewrites it.
//! tests/schemas.rs validates every example's output against the files
//! with an independent validator (Python's jsonschema).

use schemars::generate::SchemaSettings;
use schemars::JsonSchema;
use serde_json::{Map, Value};
use std::collections::BTreeSet;

/// The schema of `T` as lmdc writes it, titled, described and closed.
fn schema_of<T: JsonSchema>(id: &str, title: &str, description: &str) -> String {
    let schema = SchemaSettings::draft2020_12()
        .for_serialize()
        .into_generator()
        .into_root_schema_for::<T>();
    let mut root = schema.to_value();
    close(&mut root);
    let obj = root.as_object_mut().expect("a root schema is an object");
    obj.insert("$id".into(), id.into());
    obj.insert("title".into(), title.into());
    obj.insert("description".into(), description.into());
    let mut text = serde_json::to_string_pretty(&root).expect("a schema serialises");
    text.push('\n');
    text
}

/// Closes every object schema that lists its properties, so that a field the
/// type does not have is an error, not silently allowed. A tagged enum's
/// variant adds its tag to a referenced type's fields (`properties` beside a
/// `$ref`): that variant is closed with `unevaluatedProperties`, which sees
/// the referenced fields too, and the referenced type is left open (closed
/// on its own, it would refuse the tag).
fn close(root: &mut Value) {
    let mut extended = BTreeSet::new();
    walk(root, &mut |o| {
        if let (true, Some(Value::String(r))) = (o.contains_key("properties"), o.get("$ref")) {
            if let Some(name) = r.strip_prefix("#/$defs/") {
                extended.insert(name.to_string());
            }
        }
    });
    if let Some(Value::Object(defs)) = root.get_mut("$defs") {
        for (name, def) in defs.iter_mut() {
            if let (true, Some(o)) = (extended.contains(name), def.as_object_mut()) {
                o.insert("x-extended".into(), true.into());
            }
        }
    }
    walk(root, &mut |o| {
        if o.remove("x-extended").is_some() || !o.contains_key("properties") {
            return;
        }
        let key = if o.contains_key("$ref") {
            "unevaluatedProperties"
        } else {
            "additionalProperties"
        };
        o.entry(key).or_insert(false.into());
    });
}

/// Calls `f` on every object in `v`, depth first.
fn walk(v: &mut Value, f: &mut dyn FnMut(&mut Map<String, Value>)) {
    match v {
        Value::Object(o) => {
            for x in o.values_mut() {
                walk(x, f);
            }
            f(o);
        }
        Value::Array(a) => a.iter_mut().for_each(|x| walk(x, f)),
        _ => {}
    }
}

/// The IR's schema (docs/ir.schema.json).
pub fn ir() -> String {
    schema_of::<crate::ir::Program>(
        "https://lmdc.dev/schema/ir.schema.json",
        "lmdc IR",
        "The plan lmdc compiled, as `lmdc build --emit ir` writes it \
         (docs/ir.md explains the fields; `version` says which of them a plan has).",
    )
}

/// The report's schema (docs/report.schema.json).
pub fn report() -> String {
    schema_of::<crate::report::Report>(
        "https://lmdc.dev/schema/report.schema.json",
        "lmdc report",
        "One machine's report, as `lmdc report --json` writes it: one object a \
         machine, one line each (with `--message-format json` the diagnostics' \
         lines come in the same stream, told apart by `type`).",
    )
}

#[cfg(test)]
mod tests {
    /// Compares `want` with the file at `path`, or rewrites it when
    /// `LMDC_UPDATE_DOCS` is set.
    fn fresh(path: &str, want: String) {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(path);
        if std::env::var_os("LMDC_UPDATE_DOCS").is_some() {
            std::fs::write(&path, want).unwrap();
            return;
        }
        let got = std::fs::read_to_string(&path).unwrap_or_default();
        assert!(
            got == want,
            "{} is stale: the types changed. Rewrite it with \
             `LMDC_UPDATE_DOCS=1 cargo test --release --lib --features json-schema json_schema` and review the diff",
            path.display()
        );
    }

    #[test]
    fn ir_schema_is_fresh() {
        fresh("docs/ir.schema.json", super::ir());
    }

    #[test]
    fn report_schema_is_fresh() {
        fresh("docs/report.schema.json", super::report());
    }

    #[test]
    fn objects_are_closed() {
        let schema: serde_json::Value = serde_json::from_str(&super::ir()).unwrap();
        let points = &schema["$defs"]["Point"];
        assert_eq!(points["additionalProperties"], false, "{points}");
        assert!(points["properties"]["pos"].is_object(), "{points}");
    }
}
