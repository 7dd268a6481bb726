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
    pub fn load(dir: Option<&Path>) -> Result<Self, String> {
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
