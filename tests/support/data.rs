//! Compiling a source with data files (meshes, scans, sheets) beside it,
//! held in memory.

use lmdc::pipeline::{compile_reading, Compiled};
use std::collections::BTreeMap;
use std::rc::Rc;

/// Compiles `src` with `files` (name → bytes) as the files beside it.
pub fn compile_with_files<K: Into<String>>(
    src: &str,
    files: impl IntoIterator<Item = (K, Vec<u8>)>,
) -> Compiled {
    compile_with_files_and_model(src, files).0
}

/// [`compile_with_files`], with the checked model when it compiles.
pub fn compile_with_files_and_model<K: Into<String>>(
    src: &str,
    files: impl IntoIterator<Item = (K, Vec<u8>)>,
) -> (Compiled, Option<lmdc::sema::model::Model>) {
    let files: BTreeMap<String, Vec<u8>> = files.into_iter().map(|(k, v)| (k.into(), v)).collect();
    let data: lmdc::sema::DataReader = Rc::new(move |p: &str, _| {
        files
            .get(p)
            .cloned()
            .ok_or_else(|| format!("no file `{p}`"))
    });
    compile_reading(src, None, &mut (), data).unwrap()
}
