//! The examples as test inputs: an example file with some of its text
//! replaced, each replacement checked to apply (so a test never silently
//! compiles the unedited file).
#![allow(dead_code)]

/// Every example's `.lmd` file (`examples/*.lmd`), sorted.
pub fn files() -> Vec<std::path::PathBuf> {
    let mut files: Vec<_> = std::fs::read_dir("examples")
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "lmd"))
        .collect();
    files.sort();
    files
}

/// `examples/<name>` with each `(from, to)` of `edits` replaced once.
pub fn edited(name: &str, edits: &[(&str, &str)]) -> String {
    let mut src = std::fs::read_to_string(format!("examples/{name}")).unwrap();
    for (from, to) in edits {
        assert!(src.contains(from), "{name} has no `{from}`");
        src = src.replacen(from, to, 1);
    }
    src
}

/// The seed 000 duct, edited.
pub fn duct(edits: &[(&str, &str)]) -> String {
    edited("twisted_duct.lmd", edits)
}

/// The seed 001 sprocket tooth, edited.
pub fn tooth(edits: &[(&str, &str)]) -> String {
    edited("sprocket_tooth.lmd", edits)
}

/// Compiles the .lmd file `path` (its text `src`) as `lmdc build` does:
/// the data files it names (sheets, meshes) read beside it.
pub fn compile_file(path: &std::path::Path, src: &str) -> lmdc::pipeline::Compiled {
    let dir = path
        .parent()
        .map(std::path::Path::to_path_buf)
        .unwrap_or_default();
    let data: lmdc::sema::DataReader =
        std::rc::Rc::new(move |p: &str, _| std::fs::read(dir.join(p)).map_err(|e| e.to_string()));
    lmdc::pipeline::compile_reading(src, None, &mut (), data)
        .expect("no machine named")
        .0
}
