//! Atomic output: every file goes to a temporary file in the output directory
//! and is renamed into place only when every program was emitted, so a failed
//! build writes nothing and a reader never sees half a program.

use lmdc::back::Sink;
use std::fs;
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use tempfile::NamedTempFile;

/// Collects temporary files in `dir`; [`AtomicDir::commit`] renames them.
pub struct AtomicDir {
    dir: PathBuf,
    created_dir: bool,
    files: Vec<(String, NamedTempFile)>,
}

impl AtomicDir {
    /// Prepares `dir` (creating it if needed; removed again if nothing is
    /// committed).
    pub fn new(dir: &Path) -> io::Result<Self> {
        let created_dir = !dir.exists();
        fs::create_dir_all(dir)?;
        Ok(AtomicDir {
            dir: dir.to_path_buf(),
            created_dir,
            files: Vec::new(),
        })
    }

    /// Flushes every file to disk and renames it into place. Returns the paths.
    pub fn commit(mut self) -> io::Result<Vec<PathBuf>> {
        let mut out = Vec::new();
        for (name, tmp) in std::mem::take(&mut self.files) {
            // Temporary files are created private (0600); a program is an
            // ordinary file the cell's operators must be able to read.
            #[cfg(unix)]
            {
                use std::os::unix::fs::PermissionsExt;
                tmp.as_file()
                    .set_permissions(fs::Permissions::from_mode(0o644))?;
            }
            tmp.as_file().sync_all()?;
            let path = self.dir.join(&name);
            tmp.persist(&path).map_err(|e| e.error)?;
            out.push(path);
        }
        self.created_dir = false;
        Ok(out)
    }
}

impl Drop for AtomicDir {
    fn drop(&mut self) {
        // Temporary files delete themselves; an output directory this run
        // created for nothing goes too.
        self.files.clear();
        if self.created_dir {
            let _ = fs::remove_dir(&self.dir);
        }
    }
}

/// A buffered writer that reports flush errors when the back end flushes (it
/// must: errors at drop are lost).
struct TempWriter<'a> {
    inner: BufWriter<&'a mut fs::File>,
}

impl Write for TempWriter<'_> {
    fn write(&mut self, b: &[u8]) -> io::Result<usize> {
        self.inner.write(b)
    }
    fn write_all(&mut self, b: &[u8]) -> io::Result<()> {
        self.inner.write_all(b)
    }
    fn flush(&mut self) -> io::Result<()> {
        self.inner.flush()
    }
}

impl Sink for AtomicDir {
    fn create(&mut self, name: &str) -> io::Result<Box<dyn Write + '_>> {
        if name.contains(['/', '\\']) || name.is_empty() || name.starts_with('.') {
            return Err(io::Error::new(
                io::ErrorKind::InvalidInput,
                format!("refusing to write a file called {name:?}"),
            ));
        }
        if self.files.iter().any(|(n, _)| n == name) {
            return Err(io::Error::new(
                io::ErrorKind::AlreadyExists,
                format!("two programs would both be written to {name}: give the machines more distinct names"),
            ));
        }
        let tmp = tempfile::Builder::new()
            .prefix(".lmdc-")
            .suffix(".tmp")
            .tempfile_in(&self.dir)?;
        self.files.push((name.to_string(), tmp));
        let file = self.files.last_mut().expect("just pushed").1.as_file_mut();
        Ok(Box::new(TempWriter {
            inner: BufWriter::with_capacity(1 << 20, file),
        }))
    }
}
