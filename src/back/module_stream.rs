//! What the robot dialects' module writers share: the body of the module
//! being filled, the layer comment blocks that go before a layer's first
//! motion (in the module that motion goes to), and closing a module into
//! its files through its templates. The dialects (`krl::modules`,
//! `rapid::modules`) write the motion lines themselves.
//!
//! Holding one module in memory bounds memory by the module size, whatever
//! the part's size.

use crate::back::{EmitError, Sink, Templates};
use crate::target::names::KrlNames;
use std::io::Write;

/// Marker the module template's `body` variable is rendered as, where the
/// motion lines go.
const BODY: &str = "\u{1}lmdc-body\u{1}";

/// The files a module is written as: the template holding the motion lines
/// (`{{ body }}`) and its file extension, and optionally a second file
/// beside it (KRL's data list), left out when it renders empty.
#[derive(Clone, Copy, Debug)]
pub struct ModuleFiles {
    /// The template with `{{ body }}`, and the extension of its file.
    pub body: (&'static str, &'static str),
    /// A template without the body, and its file's extension.
    pub beside: Option<(&'static str, &'static str)>,
}

/// The module being filled and the modules written so far.
pub struct ModuleStream<'a> {
    sink: &'a mut dyn Sink,
    t: &'a Templates,
    base: tera::Context,
    names: KrlNames,
    files: ModuleFiles,
    max_lines: usize,
    /// The current module's motion lines, as the dialect wrote them.
    pub body: Vec<u8>,
    /// Motion instructions in the current module.
    pub lines: usize,
    /// A layer comment block waiting for the layer's first motion, and the
    /// layer's number.
    pre: Vec<u8>,
    pre_layer: Option<usize>,
    /// Layer numbers (1-based) whose comment blocks are in this module.
    layers: Option<(usize, usize)>,
    /// The last layer whose comment block was placed (1-based; 0: none yet).
    current: usize,
    /// The layer already under way when this module starts (0: it starts
    /// with a layer's comment block, or before any).
    continues: usize,
    modules: Vec<String>,
    error: Option<EmitError>,
}

impl<'a> ModuleStream<'a> {
    /// A stream of modules named by `names`, each at most `max_lines`
    /// motions, written as `files` says with `base` as the templates'
    /// context.
    pub fn new(
        sink: &'a mut dyn Sink,
        t: &'a Templates,
        base: tera::Context,
        names: KrlNames,
        files: ModuleFiles,
        max_lines: usize,
    ) -> Self {
        ModuleStream {
            sink,
            t,
            base,
            names,
            files,
            max_lines: max_lines.max(1),
            body: Vec::with_capacity(1 << 16),
            lines: 0,
            pre: Vec::new(),
            pre_layer: None,
            layers: None,
            current: 0,
            continues: 0,
            modules: Vec::new(),
            error: None,
        }
    }

    /// The comment block of layer `number` (1-based), as the dialect laid
    /// it out: it goes before the layer's first motion.
    pub fn layer(&mut self, number: usize) -> &mut Vec<u8> {
        self.pre_layer = Some(number);
        &mut self.pre
    }

    /// Places the waiting layer comment block, if any, in the body: the
    /// next motion is its layer's first.
    pub fn place_pre(&mut self) {
        if let Some(number) = self.pre_layer.take() {
            self.body.extend_from_slice(&self.pre);
            self.pre.clear();
            self.layers = Some(match self.layers {
                Some((first, _)) => (first, number),
                None => (number, number),
            });
            self.current = number;
        }
    }

    /// The current module holds as many motions as a module may.
    pub fn full(&self) -> bool {
        self.lines >= self.max_lines
    }

    /// Writes the current module (its last motion ended) and starts the
    /// next. An error is kept for [`Self::finish`].
    pub fn close(&mut self) {
        let name = self.names.module(self.modules.len());
        if self.error.is_none() {
            if let Err(e) = self.write(&name) {
                self.error = Some(e);
            }
        }
        self.modules.push(name);
        self.body.clear();
        self.lines = 0;
        self.layers = None;
        // Mid-layer unless the next motion opens a layer with its block.
        self.continues = if self.pre_layer.is_some() {
            0
        } else {
            self.current
        };
    }

    /// Closes the last module (the dialect ended its last motion): the
    /// module names in call order, or the first error met.
    pub fn finish(mut self) -> Result<Vec<String>, EmitError> {
        self.place_pre();
        if self.lines > 0 || !self.body.is_empty() {
            self.close();
        }
        match self.error {
            Some(e) => Err(e),
            None => Ok(self.modules),
        }
    }

    fn write(&mut self, name: &str) -> Result<(), EmitError> {
        let mut ctx = self.base.clone();
        ctx.insert("name", name);
        ctx.insert("module", &(self.modules.len() + 1));
        ctx.insert("lines", &self.lines);
        let (first, last) = self.layers.unwrap_or((0, 0));
        ctx.insert("first_layer", &first);
        ctx.insert("last_layer", &last);
        ctx.insert("continues", &self.continues);
        ctx.insert("body", BODY);
        let (template, ext) = self.files.body;
        let text = self.t.render(template, &ctx).map_err(EmitError::Template)?;
        let (head, tail) = text.split_once(BODY).ok_or_else(|| {
            EmitError::Template(format!(
                "template {template}: it must contain {{{{ body }}}}"
            ))
        })?;
        let beside = match self.files.beside {
            Some((template, ext)) => Some((
                self.t.render(template, &ctx).map_err(EmitError::Template)?,
                ext,
            )),
            None => None,
        };
        let mut out = self.sink.create(&format!("{name}.{ext}"))?;
        out.write_all(head.as_bytes())?;
        out.write_all(&self.body)?;
        out.write_all(tail.as_bytes())?;
        out.flush()?;
        drop(out);
        if let Some((text, ext)) = beside.filter(|(text, _)| !text.is_empty()) {
            let mut out = self.sink.create(&format!("{name}.{ext}"))?;
            out.write_all(text.as_bytes())?;
            out.flush()?;
        }
        Ok(())
    }
}
