//! The tera templates that give each program its shape. Built-in copies of
//! `templates/` are compiled into the binary; `--templates DIR` replaces any of them
//! by a file of the same relative name (e.g. `DIR/krl/main.src.tera`).

use std::path::Path;

/// Built-in templates: (name, text).
const BUILTIN: &[(&str, &str)] = &[
    (
        "krl/main.src.tera",
        include_str!("../../templates/krl/main.src.tera"),
    ),
    (
        "krl/main.dat.tera",
        include_str!("../../templates/krl/main.dat.tera"),
    ),
    (
        "krl/module.src.tera",
        include_str!("../../templates/krl/module.src.tera"),
    ),
    (
        "krl/module.dat.tera",
        include_str!("../../templates/krl/module.dat.tera"),
    ),
    (
        "krl/layer.tera",
        include_str!("../../templates/krl/layer.tera"),
    ),
    (
        "rapid/main.mod.tera",
        include_str!("../../templates/rapid/main.mod.tera"),
    ),
    (
        "rapid/module.mod.tera",
        include_str!("../../templates/rapid/module.mod.tera"),
    ),
    (
        "rapid/layer.tera",
        include_str!("../../templates/rapid/layer.tera"),
    ),
    (
        "gcode/header.tera",
        include_str!("../../templates/gcode/header.tera"),
    ),
    (
        "gcode/layer.tera",
        include_str!("../../templates/gcode/layer.tera"),
    ),
    (
        "gcode/footer.tera",
        include_str!("../../templates/gcode/footer.tera"),
    ),
];

/// A loaded template set.
pub struct Templates {
    tera: tera::Tera,
}

impl Templates {
    /// The built-in templates.
    pub fn builtin() -> Result<Self, String> {
        Self::load(None)
    }

    /// The built-in templates, with any file found under `dir` replacing its
    /// built-in namesake.
    ///
    /// A `dir` that is not a directory, that holds none of the templates, or
    /// that holds a `.tera` file lmdc does not use (a misspelt name, a file
    /// outside `krl/`, `rapid/` and `gcode/`) is an error: the built-in templates in
    /// place of a site's own preamble must never pass unnoticed.
    pub fn load(dir: Option<&Path>) -> Result<Self, String> {
        if let Some(d) = dir {
            check_dir(d)?;
        }
        let mut tera = tera::Tera::default();
        tera.autoescape_on(vec![]);
        for (name, text) in BUILTIN {
            let text = match dir.map(|d| d.join(name)) {
                Some(p) if p.is_file() => std::fs::read_to_string(&p)
                    .map_err(|e| format!("cannot read template {}: {e}", p.display()))?,
                _ => text.to_string(),
            };
            tera.add_raw_template(name, &text)
                .map_err(|e| format!("template {name}: {}", error_chain(&e)))?;
        }
        Ok(Templates { tera })
    }

    /// Renders template `name` with `ctx`.
    pub fn render(&self, name: &str, ctx: &tera::Context) -> Result<String, String> {
        self.tera
            .render(name, ctx)
            .map_err(|e| format!("template {name}: {}", error_chain(&e)))
    }
}

/// The names a template directory may hold, for messages.
fn known_names() -> String {
    BUILTIN
        .iter()
        .map(|(n, _)| *n)
        .collect::<Vec<_>>()
        .join(", ")
}

/// Refuses a template directory that is missing, holds no template, or holds a
/// `.tera` file that would be silently ignored.
fn check_dir(dir: &Path) -> Result<(), String> {
    let meta =
        std::fs::metadata(dir).map_err(|e| format!("template directory {}: {e}", dir.display()))?;
    if !meta.is_dir() {
        return Err(format!(
            "template directory {}: not a directory",
            dir.display()
        ));
    }
    let mut found = 0;
    let mut unused = Vec::new();
    for sub in ["", "krl", "gcode"] {
        let d = dir.join(sub);
        let Ok(entries) = std::fs::read_dir(&d) else {
            continue;
        };
        for e in entries.flatten() {
            let name = e.file_name().to_string_lossy().into_owned();
            if !name.ends_with(".tera") {
                continue;
            }
            let rel = if sub.is_empty() {
                name
            } else {
                format!("{sub}/{name}")
            };
            if BUILTIN.iter().any(|(n, _)| *n == rel) {
                found += 1;
            } else {
                unused.push(rel);
            }
        }
    }
    unused.sort();
    if let Some(first) = unused.first() {
        return Err(format!(
            "template directory {}: lmdc has no template called {first}{}; the templates are {}",
            dir.display(),
            if unused.len() > 1 {
                format!(" (nor {})", unused[1..].join(", "))
            } else {
                String::new()
            },
            known_names()
        ));
    }
    if found == 0 {
        return Err(format!(
            "template directory {} holds none of lmdc's templates ({})",
            dir.display(),
            known_names()
        ));
    }
    Ok(())
}

fn error_chain(e: &dyn std::error::Error) -> String {
    let mut s = e.to_string();
    let mut src = e.source();
    while let Some(c) = src {
        s.push_str(": ");
        s.push_str(&c.to_string());
        src = c.source();
    }
    s
}
