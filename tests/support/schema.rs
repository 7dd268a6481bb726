//! A JSON Schema validator for the keywords lmdc's schemas use: `type`
//! (one or a list), `const`, `enum`, `required`, `properties`,
//! `additionalProperties: false`, `items`, `minItems`, `maxItems`,
//! `minimum`, `oneOf`, `$ref` to the schema's own `$defs`, `pattern` (only
//! the `^prefix[class]+$` shape docs/diagnostics.schema.json uses). A keyword it
//! does not know fails the validation, so the schema cannot grow past what
//! the test checks. A crate (jsonschema) would pull in a regex engine and an
//! HTTP client for one schema of eight fields.
#![allow(dead_code)]

use serde_json::Value;

/// Keywords that only document.
const NOTES: [&str; 6] = [
    "$schema",
    "$id",
    "title",
    "description",
    "$comment",
    "$defs",
];

/// Every way `v` breaks `schema`, with the JSON path where.
pub fn validate(schema: &Value, v: &Value) -> Vec<String> {
    let mut errors = Vec::new();
    check(schema, v, "$", &mut (schema, &mut errors));
    errors
}

/// The root schema (for `$ref`) and the errors found.
type Cx<'a, 'e> = (&'a Value, &'e mut Vec<String>);

fn type_of(v: &Value) -> &'static str {
    match v {
        Value::Null => "null",
        Value::Bool(_) => "boolean",
        Value::Number(n) if n.is_u64() || n.is_i64() => "integer",
        Value::Number(_) => "number",
        Value::String(_) => "string",
        Value::Array(_) => "array",
        Value::Object(_) => "object",
    }
}

fn is(v: &Value, t: &str) -> bool {
    let have = type_of(v);
    have == t || (t == "number" && have == "integer")
}

fn check(schema: &Value, v: &Value, at: &str, cx: &mut Cx<'_, '_>) {
    let root = cx.0;
    let errors = &mut *cx.1;
    let Some(s) = schema.as_object() else {
        errors.push(format!("{at}: the schema is not an object"));
        return;
    };
    for (key, want) in s {
        match key.as_str() {
            k if NOTES.contains(&k) => {}
            "type" => {
                let ok = match want {
                    Value::String(t) => is(v, t),
                    Value::Array(ts) => ts.iter().any(|t| t.as_str().is_some_and(|t| is(v, t))),
                    _ => false,
                };
                if !ok {
                    errors.push(format!("{at}: {} is not of type {want}", type_of(v)));
                }
            }
            "const" if v != want => errors.push(format!("{at}: {v} is not {want}")),
            "const" => {}
            "enum" => {
                if !want.as_array().is_some_and(|a| a.contains(v)) {
                    errors.push(format!("{at}: {v} is not one of {want}"));
                }
            }
            "required" => {
                for name in want.as_array().into_iter().flatten() {
                    let name = name.as_str().unwrap_or_default();
                    if v.as_object().is_some_and(|o| !o.contains_key(name)) {
                        errors.push(format!("{at}: `{name}` is missing"));
                    }
                }
            }
            "properties" => {
                if let (Some(props), Some(o)) = (want.as_object(), v.as_object()) {
                    for (name, sub) in props {
                        if let Some(x) = o.get(name) {
                            check(sub, x, &format!("{at}.{name}"), &mut (root, &mut *errors));
                        }
                    }
                }
            }
            "additionalProperties" => {
                let known = s.get("properties").and_then(Value::as_object);
                if want != &Value::Bool(false) {
                    errors.push(format!(
                        "{at}: only additionalProperties: false is supported"
                    ));
                } else if let Some(o) = v.as_object() {
                    for name in o.keys() {
                        if !known.is_some_and(|k| k.contains_key(name)) {
                            errors.push(format!("{at}: `{name}` is not allowed"));
                        }
                    }
                }
            }
            "items" => {
                for (i, x) in v.as_array().into_iter().flatten().enumerate() {
                    check(want, x, &format!("{at}[{i}]"), &mut (root, &mut *errors));
                }
            }
            "minItems" | "maxItems" => {
                if let (Some(n), Some(a)) = (want.as_u64(), v.as_array()) {
                    let len = a.len() as u64;
                    if (key == "minItems" && len < n) || (key == "maxItems" && len > n) {
                        errors.push(format!("{at}: {len} items, {key} {n}"));
                    }
                }
            }
            "oneOf" => {
                let passing = want
                    .as_array()
                    .into_iter()
                    .flatten()
                    .filter(|sub| {
                        let mut e = Vec::new();
                        check(sub, v, at, &mut (root, &mut e));
                        e.is_empty()
                    })
                    .count();
                if passing != 1 {
                    errors.push(format!("{at}: {passing} of oneOf's schemas hold, not one"));
                }
            }
            "$ref" => {
                let target = want
                    .as_str()
                    .and_then(|r| r.strip_prefix("#/$defs/"))
                    .and_then(|name| root.get("$defs")?.get(name));
                match target {
                    Some(sub) => check(sub, v, at, &mut (root, &mut *errors)),
                    None => errors.push(format!(
                        "{at}: $ref {want} is not one of the schema's $defs"
                    )),
                }
            }
            "minimum" => {
                if let (Some(min), Some(x)) = (want.as_f64(), v.as_f64()) {
                    if x < min {
                        errors.push(format!("{at}: {x} is below {min}"));
                    }
                }
            }
            "pattern" => {
                if let (Some(p), Some(x)) = (want.as_str(), v.as_str()) {
                    match matches(p, x) {
                        Some(true) => {}
                        Some(false) => errors.push(format!("{at}: `{x}` does not match {p}")),
                        None => errors.push(format!("{at}: pattern {p} is not supported")),
                    }
                }
            }
            other => errors.push(format!("{at}: keyword `{other}` is not supported")),
        }
    }
}

/// `^prefix[class]+$`, the class of single characters and `a-z` ranges.
fn matches(pattern: &str, text: &str) -> Option<bool> {
    let inner = pattern.strip_prefix('^')?.strip_suffix("]+$")?;
    let (prefix, class) = inner.split_once('[')?;
    let class: Vec<char> = class.chars().collect();
    let in_class = |c: char| {
        let mut i = 0;
        while i < class.len() {
            if i + 2 < class.len() && class[i + 1] == '-' {
                if (class[i]..=class[i + 2]).contains(&c) {
                    return true;
                }
                i += 3;
            } else {
                if class[i] == c {
                    return true;
                }
                i += 1;
            }
        }
        false
    };
    let rest = text.strip_prefix(prefix);
    Some(rest.is_some_and(|r| !r.is_empty() && r.chars().all(in_class)))
}

#[test]
fn the_validator_finds_what_it_should() {
    let schema: Value = serde_json::json!({
        "type": "object", "required": ["a"], "additionalProperties": false,
        "properties": {"a": {"type": "integer", "minimum": 1}, "b": {"pattern": "^x::[a-z-]+$"}}
    });
    assert!(validate(&schema, &serde_json::json!({"a": 2, "b": "x::ab-c"})).is_empty());
    assert_eq!(validate(&schema, &serde_json::json!({"a": 0})).len(), 1);
    assert_eq!(
        validate(&schema, &serde_json::json!({"b": "x::A"})).len(),
        2
    );
    assert_eq!(
        validate(&schema, &serde_json::json!({"a": 1, "c": 1})).len(),
        1
    );
    assert_eq!(
        validate(&serde_json::json!({"format": "x"}), &Value::Null).len(),
        1
    );
}
