//! Atomic output of whole sets of files.
//!
//! A machine's program is a set of files (a KRL main program, its data list
//! and its numbered modules; one G-code file), and a set is useless, or
//! dangerous, mixed with another build's: an old main program calling new
//! modules runs a part nobody planned. So a build replaces each machine's set
//! as a whole:
//!
//! 1. every file is written into the staging folder `DIR/.lmdc-staging/` and
//!    flushed to disk; nothing in `DIR` changes while the programs are emitted,
//!    and a failed build only removes the folder;
//! 2. the *journal* `DIR/.lmdc-staging/journal` is written to a temporary name
//!    and renamed into place, flushed: this rename is the commit point. It
//!    lists the files to remove (the previous files of the machines being
//!    rebuilt, newest first, so a KRL main program goes before its modules),
//!    the files to move in (in the order the back end wrote them: modules
//!    before the main program that calls them) and the manifest that results;
//! 3. the removals, then the moves, are carried out (each rebuilt set's main
//!    program is removed first, then the rest side by side: a removal
//!    mostly waits on the disk); then the manifest
//!    `DIR/.lmdc-manifest` is replaced (temporary name, rename) and the staging
//!    folder removed.
//!
//! A build killed before the commit point leaves the previous files untouched,
//! and the next lmdc build into `DIR` deletes its staging folder (rolls back). A
//! build killed after it is finished by the next one (rolls forward: steps
//! that were done are skipped, so finishing twice is harmless). In between
//! the directory never holds files of both builds: every old file of a
//! rebuilt set is removed before the first new one appears, and the main
//! program appears last — what a robot could be given is the old set, the new
//! set, or an incomplete set without its main program.
//!
//! The manifest lists, per part and machine, the files lmdc wrote, so a
//! rebuild that writes fewer KRL modules removes the old extra modules, and
//! only those: a file lmdc did not write into `DIR` is never removed (unless a
//! build writes a file of the same name, which replaces it), and a file
//! another part or machine wrote is never replaced (the build is refused:
//! two parts whose KRL names clash would otherwise overwrite each other). `DIR/.lmdc-lock`
//! keeps two builds out of one directory at the same time; a lock left by a
//! killed build is taken over. Temporary files an older lmdc left
//! (`DIR/.lmdc-*.tmp`) are removed too.

use lmdc::back::Sink;
use serde::{Deserialize, Serialize};
use std::cell::Cell;
use std::collections::HashSet;
use std::fs::{self, File, OpenOptions};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::rc::Rc;

/// The folder new files are written to before they replace the old ones.
pub const STAGING: &str = ".lmdc-staging";
/// The list of the files lmdc wrote into an output directory.
pub const MANIFEST: &str = ".lmdc-manifest";
/// Held while a build writes into an output directory.
pub const LOCK: &str = ".lmdc-lock";
/// Inside [`STAGING`]: the commit record of a build.
const JOURNAL: &str = "journal";

/// Whose files a set is: a part's program for one machine, or its plan
/// (`--emit ir`, no machine).
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct SetKey {
    /// The part's name.
    pub part: String,
    /// The machine's name; `None` for the IR.
    pub machine: Option<String>,
}

/// One set of files in the manifest.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
struct FileSet {
    #[serde(flatten)]
    key: SetKey,
    /// In the order they were written.
    files: Vec<String>,
}

/// `DIR/.lmdc-manifest`: the files lmdc owns in `DIR`.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
struct Manifest {
    format: String,
    version: u32,
    sets: Vec<FileSet>,
}

/// The commit record: what is left to do once it exists.
#[derive(Clone, Debug, Serialize, Deserialize)]
struct Journal {
    format: String,
    version: u32,
    /// Files to remove from the output directory: the first [`Self::serial`]
    /// in this order, then the others side by side.
    remove: Vec<String>,
    /// How many of `remove` go one by one before the rest: each rebuilt
    /// set's main program. A journal without it (an older lmdc's) removes
    /// every file in order.
    #[serde(default = "every_file")]
    serial: usize,
    /// Files to move from the staging folder into the output directory, in
    /// this order.
    moves: Vec<String>,
    /// The manifest once done.
    manifest: Manifest,
}

/// A journal's [`Journal::serial`] where it does not say: every file.
fn every_file() -> usize {
    usize::MAX
}

impl Manifest {
    fn new(sets: Vec<FileSet>) -> Self {
        Manifest {
            format: "lmdc-manifest".into(),
            version: 1,
            sets,
        }
    }

    /// The manifest of `dir`; empty when there is none (a directory no lmdc
    /// with manifests wrote into) or it cannot be read (then lmdc owns no
    /// file there, which errs on the side of keeping files).
    fn read(dir: &Path) -> Manifest {
        fs::read(dir.join(MANIFEST))
            .ok()
            .and_then(|b| serde_json::from_slice::<Manifest>(&b).ok())
            .filter(|m| m.format == "lmdc-manifest" && m.version == 1)
            .unwrap_or_else(|| Manifest::new(Vec::new()))
    }
}

/// Collects a build's files in the staging folder of `dir`;
/// [`AtomicDir::commit`] puts them in place (see the module's documentation).
pub struct AtomicDir {
    dir: PathBuf,
    staging: PathBuf,
    /// `dir` did not exist: removed again if nothing is committed.
    created_dir: bool,
    /// Files written, in order.
    files: Vec<String>,
    names: HashSet<String>,
    /// How many files have been created, for [`AtomicDir::counter`].
    count: Rc<Cell<usize>>,
    /// `(set, number of files written when it ended)`.
    sets: Vec<(SetKey, usize)>,
    /// How many of `files` are flushed to disk.
    flushed: usize,
    /// The journal is written: the staging folder must stay until done.
    journaled: bool,
    _lock: DirLock,
}

impl AtomicDir {
    /// Prepares `dir` (creating it if needed; removed again if nothing is
    /// committed): takes its lock, finishes or undoes a build that was killed
    /// there, and makes an empty staging folder.
    pub fn new(dir: &Path) -> io::Result<Self> {
        let created_dir = !dir.exists();
        fs::create_dir_all(dir)?;
        let lock = match DirLock::take(dir) {
            Ok(l) => l,
            Err(e) => {
                if created_dir {
                    let _ = fs::remove_dir(dir);
                }
                return Err(e);
            }
        };
        recover_locked(dir)?;
        let staging = dir.join(STAGING);
        fs::create_dir(&staging)?;
        Ok(AtomicDir {
            dir: dir.to_path_buf(),
            staging,
            created_dir,
            files: Vec::new(),
            names: HashSet::new(),
            count: Rc::new(Cell::new(0)),
            sets: Vec::new(),
            flushed: 0,
            journaled: false,
            _lock: lock,
        })
    }

    /// A counter of the files created so far, readable while a back end holds
    /// the sink (to tell where one machine's files end).
    pub fn counter(&self) -> Rc<Cell<usize>> {
        Rc::clone(&self.count)
    }

    /// The files created since the previous call (or the start) are the set
    /// `key`. Files not given a set when the build commits form a set of
    /// their own, keyed by the last set's part and no machine.
    pub fn end_set(&mut self, key: SetKey, files_so_far: usize) {
        self.sets.push((key, files_so_far.min(self.files.len())));
    }

    /// Flushes the files written so far to disk (the staging folder only:
    /// nothing in the directory changes). A build flushes while the last
    /// checks run; [`Self::commit`] flushes what is left.
    pub fn flush(&mut self) -> io::Result<()> {
        if self.flushed < self.files.len() && !sync_filesystem(&self.staging)? {
            for name in &self.files[self.flushed..] {
                // Reopened to flush: a build of thousands of modules cannot
                // keep them all open.
                OpenOptions::new()
                    .write(true)
                    .open(self.staging.join(name))?
                    .sync_all()?;
            }
        }
        self.flushed = self.files.len();
        sync_dir(&self.staging)
    }

    /// Flushes every file to disk and replaces, for each set written, the
    /// files the previous build of that set wrote by the new ones. Returns
    /// the paths written.
    pub fn commit(mut self) -> io::Result<Vec<PathBuf>> {
        self.flush()?;

        // The sets this build writes, with their files.
        let mut new_sets: Vec<FileSet> = Vec::new();
        let mut start = 0;
        for (key, end) in std::mem::take(&mut self.sets) {
            let files = self.files[start..end.max(start)].to_vec();
            start = end.max(start);
            match new_sets.iter_mut().find(|s| s.key == key) {
                Some(s) => s.files.extend(files),
                None => new_sets.push(FileSet { key, files }),
            }
        }
        if start < self.files.len() {
            let part = new_sets
                .last()
                .map(|s| s.key.part.clone())
                .unwrap_or_default();
            new_sets.push(FileSet {
                key: SetKey {
                    part,
                    machine: None,
                },
                files: self.files[start..].to_vec(),
            });
        }
        let written: HashSet<&str> = self.files.iter().map(String::as_str).collect();

        let old = Manifest::read(&self.dir);
        // A file another part or machine wrote is not replaced by this
        // build's: their names clash (a KRL name cut to its 24 characters),
        // and one part's programs would silently become another's.
        let clash = old
            .sets
            .iter()
            .filter(|s| !new_sets.iter().any(|n| n.key == s.key))
            .find_map(|s| {
                s.files
                    .iter()
                    .find(|f| written.contains(f.as_str()))
                    .map(|f| (s, f))
            });
        if let Some((set, file)) = clash {
            let this = new_sets
                .iter()
                .find(|n| n.files.contains(file))
                .map(|n| &n.key);
            return Err(io::Error::other(clash_message(file, &set.key, this)));
        }
        // Old sets rebuilt now go; the others stay. Each set's main program
        // goes first, so no set is ever left with its main program and not
        // every module it calls; the rest go side by side.
        let mut remove: Vec<String> = Vec::new();
        let mut rest: Vec<String> = Vec::new();
        let mut kept: Vec<FileSet> = Vec::new();
        for set in old.sets {
            if new_sets.iter().any(|n| n.key == set.key) {
                let (main, modules) = main_program(&set.files);
                // Plain names only (as below), so `serial` counts them.
                remove.extend(main.iter().rev().filter(|f| is_plain_name(f)).cloned());
                rest.extend(modules.iter().rev().cloned());
            } else if !set.files.is_empty() {
                kept.push(set);
            }
        }
        let serial = remove.len();
        remove.append(&mut rest);
        // Any other file about to be replaced goes first too, so that the
        // directory never shows an old file beside a new one.
        let mut removed: HashSet<String> = remove.iter().cloned().collect();
        for f in self.files.iter().rev() {
            if !removed.contains(f) && self.dir.join(f).exists() {
                removed.insert(f.clone());
                remove.push(f.clone());
            }
        }
        // A manifest edited by hand must not make lmdc remove anything but
        // plain files in the directory itself.
        remove.retain(|f| is_plain_name(f));
        kept.extend(new_sets);
        let journal = Journal {
            format: "lmdc-journal".into(),
            version: 1,
            remove,
            serial,
            moves: self.files.clone(),
            manifest: Manifest::new(kept),
        };
        let text = serde_json::to_vec_pretty(&journal).map_err(io::Error::other)?;
        write_durably(&self.staging, JOURNAL, &text)?;
        self.journaled = true;
        finish(&self.dir, &journal)?;
        self.created_dir = false;
        Ok(self.files.iter().map(|f| self.dir.join(f)).collect())
    }
}

/// Why `file`, which `owner`'s build wrote, is not replaced by this build's
/// (`this`: the set writing it).
fn clash_message(file: &str, owner: &SetKey, this: Option<&SetKey>) -> String {
    let who = |k: &SetKey| match &k.machine {
        Some(m) => format!("part `{}` on `{m}`", k.part),
        None => format!("part `{}`", k.part),
    };
    let this = this.map_or("this build".to_string(), |k| {
        format!("this build's {}", who(k))
    });
    format!(
        "{file} holds the programs of {}, and {this} would replace them under the same name \
         (a KRL name keeps 24 characters, the part's name shortened first); nothing was \
         written: build into another folder, or give the parts names that differ sooner",
        who(owner)
    )
}

impl Drop for AtomicDir {
    fn drop(&mut self) {
        // A build that failed before its commit point leaves nothing: its
        // staging folder goes, and an output directory it created for
        // nothing. After the commit point the staging folder is kept for the
        // next build to finish the job.
        if !self.journaled {
            let _ = fs::remove_dir_all(&self.staging);
            if self.created_dir {
                let _ = fs::remove_file(self.dir.join(LOCK));
                let _ = fs::remove_dir(&self.dir);
            }
        }
    }
}

/// Finishes or undoes whatever a killed build left in `dir` (see the module's
/// documentation). Takes the directory's lock while it works; does nothing
/// when `dir` does not exist.
pub fn recover(dir: &Path) -> io::Result<()> {
    if !dir.is_dir() {
        return Ok(());
    }
    let _lock = DirLock::take(dir)?;
    recover_locked(dir)
}

fn recover_locked(dir: &Path) -> io::Result<()> {
    let staging = dir.join(STAGING);
    match fs::read(staging.join(JOURNAL)) {
        Ok(bytes) => {
            let journal: Journal = serde_json::from_slice(&bytes).map_err(|e| {
                io::Error::other(format!(
                    "the journal of an interrupted build, {}, cannot be read ({e}); \
                     remove {} to give up that build",
                    staging.join(JOURNAL).display(),
                    staging.display()
                ))
            })?;
            finish(dir, &journal)?;
        }
        Err(e) if e.kind() == io::ErrorKind::NotFound => {
            if staging.exists() {
                fs::remove_dir_all(&staging)?;
            }
        }
        Err(e) => return Err(e),
    }
    // Temporary files: a manifest being replaced when the build was killed,
    // and those of lmdc versions before the staging folder.
    for e in fs::read_dir(dir)?.flatten() {
        let name = e.file_name();
        let name = name.to_string_lossy();
        if name.starts_with(".lmdc-") && name.ends_with(".tmp") {
            let _ = fs::remove_file(e.path());
        }
    }
    Ok(())
}

/// A set's files, in the order written, split into its main program (the
/// last file written and the others of its name: a KRL main program's
/// `.src` and `.dat`) and what it calls, written before it.
fn main_program(files: &[String]) -> (&[String], &[String]) {
    let stem = |f: &str| f.rsplit_once('.').map_or(f, |(s, _)| s).to_string();
    let Some(last) = files.last().map(|f| stem(f)) else {
        return (&[], &[]);
    };
    let k = files
        .iter()
        .rposition(|f| stem(f) != last)
        .map_or(0, |k| k + 1);
    let (modules, main) = files.split_at(k);
    (main, modules)
}

/// How many threads remove files side by side: a removal waits on the
/// disk far more than it computes (on the dense duct's 3608 files, a
/// second and more of waiting each 1000 one by one, a tenth of a second
/// with four at a time).
const REMOVERS: usize = 4;

/// Carries out a journal; each step is skipped when already done, so a
/// journal can be finished again after a kill.
fn finish(dir: &Path, journal: &Journal) -> io::Result<()> {
    let staging = dir.join(STAGING);
    let moves: HashSet<&str> = journal.moves.iter().map(String::as_str).collect();
    let remove = |f: &String| -> io::Result<()> {
        // A file that has already been moved in is the new one: keep it.
        if moves.contains(f.as_str()) && !staging.join(f).exists() {
            return Ok(());
        }
        match fs::remove_file(dir.join(f)) {
            Err(e) if e.kind() != io::ErrorKind::NotFound => Err(e),
            _ => Ok(()),
        }
    };
    let (first, rest) = journal
        .remove
        .split_at(journal.serial.min(journal.remove.len()));
    first.iter().try_for_each(remove)?;
    std::thread::scope(|s| {
        let workers: Vec<_> = (0..REMOVERS)
            .map(|t| {
                let remove = &remove;
                s.spawn(move || rest.iter().skip(t).step_by(REMOVERS).try_for_each(remove))
            })
            .collect();
        workers.into_iter().try_for_each(|w| {
            w.join()
                .unwrap_or_else(|_| Err(io::Error::other("a removal failed")))
        })
    })?;
    sync_dir(dir)?;
    for f in &journal.moves {
        let from = staging.join(f);
        if from.exists() {
            fs::rename(&from, dir.join(f))?;
        }
    }
    sync_dir(dir)?;
    let text = serde_json::to_vec_pretty(&journal.manifest).map_err(io::Error::other)?;
    write_durably(dir, MANIFEST, &text)?;
    fs::remove_dir_all(&staging)?;
    sync_dir(dir)
}

/// Writes `dir/name` whole or not at all: a temporary file, flushed, renamed.
fn write_durably(dir: &Path, name: &str, bytes: &[u8]) -> io::Result<()> {
    let tmp = dir.join(format!(".lmdc-{name}.tmp"));
    let mut f = File::create(&tmp)?;
    f.write_all(bytes)?;
    f.sync_all()?;
    drop(f);
    fs::rename(&tmp, dir.join(name))?;
    sync_dir(dir)
}

/// Flushes everything written to the filesystem that holds `dir` to disk,
/// the staged files among it, in one call (Linux's syncfs: a dense part's
/// 3 600 files cost 3 600 fsyncs otherwise, seconds of system time, and
/// a file's fsync on ext4 flushes the journal anyway). `false` where the
/// system has no such call: the caller flushes file by file.
fn sync_filesystem(dir: &Path) -> io::Result<bool> {
    #[cfg(target_os = "linux")]
    {
        use std::os::fd::AsRawFd;
        let d = File::open(dir)?;
        // SAFETY: syncfs reads nothing but the descriptor, open until the
        // end of this block.
        if unsafe { libc::syncfs(d.as_raw_fd()) } == 0 {
            return Ok(true);
        }
        let e = io::Error::last_os_error();
        if e.raw_os_error() == Some(libc::ENOSYS) {
            return Ok(false);
        }
        Err(e)
    }
    #[cfg(not(target_os = "linux"))]
    {
        let _ = dir;
        Ok(false)
    }
}

/// Flushes a directory's entries (renames, removals) to disk, where the
/// system allows it.
fn sync_dir(dir: &Path) -> io::Result<()> {
    #[cfg(unix)]
    {
        File::open(dir)?.sync_all()
    }
    #[cfg(not(unix))]
    {
        let _ = dir;
        Ok(())
    }
}

/// A name the sink may write: a bare file name that is no hidden file (so no
/// program can overwrite the manifest, the lock or the staging folder).
fn is_plain_name(name: &str) -> bool {
    !(name.is_empty() || name.contains(['/', '\\']) || name.starts_with('.'))
}

/// `DIR/.lmdc-lock`, holding the process id of the build writing into `DIR`.
struct DirLock {
    path: PathBuf,
}

impl DirLock {
    fn take(dir: &Path) -> io::Result<Self> {
        let path = dir.join(LOCK);
        for _ in 0..2 {
            match OpenOptions::new().write(true).create_new(true).open(&path) {
                Ok(mut f) => {
                    writeln!(f, "{}", std::process::id())?;
                    return Ok(DirLock { path });
                }
                Err(e) if e.kind() == io::ErrorKind::AlreadyExists => {
                    let holder = fs::read_to_string(&path)
                        .ok()
                        .and_then(|s| s.trim().parse::<u32>().ok());
                    if let Some(pid) = holder.filter(|&p| is_running_lmdc(p)) {
                        return Err(io::Error::new(
                            io::ErrorKind::WouldBlock,
                            format!(
                                "another lmdc (process {pid}) is writing into {}; if it is not, remove {}",
                                dir.display(),
                                path.display()
                            ),
                        ));
                    }
                    // Left by a build that was killed: take it over.
                    let _ = fs::remove_file(&path);
                }
                Err(e) => return Err(e),
            }
        }
        Err(io::Error::new(
            io::ErrorKind::WouldBlock,
            format!("cannot take the lock {}", path.display()),
        ))
    }
}

impl Drop for DirLock {
    fn drop(&mut self) {
        let _ = fs::remove_file(&self.path);
    }
}

/// Whether process `pid` is an lmdc still running. Known on Linux (`/proc`);
/// elsewhere a lock is taken to be left by a killed build.
fn is_running_lmdc(pid: u32) -> bool {
    if pid == std::process::id() {
        return false;
    }
    match fs::read_to_string(format!("/proc/{pid}/comm")) {
        Ok(comm) => comm.contains("lmdc"),
        Err(_) => false,
    }
}

/// A buffered writer that reports flush errors when the back end flushes (it
/// must: errors at drop are lost).
struct StagedWriter {
    inner: BufWriter<File>,
}

impl Write for StagedWriter {
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
        if !is_plain_name(name) {
            return Err(io::Error::new(
                io::ErrorKind::InvalidInput,
                format!("refusing to write a file called {name:?}"),
            ));
        }
        if !self.names.insert(name.to_string()) {
            return Err(io::Error::new(
                io::ErrorKind::AlreadyExists,
                format!("two programs would both be written to {name}: give the machines more distinct names"),
            ));
        }
        let file = OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(self.staging.join(name))?;
        self.files.push(name.to_string());
        self.count.set(self.files.len());
        Ok(Box::new(StagedWriter {
            inner: BufWriter::with_capacity(1 << 20, file),
        }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tmp(tag: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("lmdc-sink-{}-{tag}", std::process::id()));
        let _ = fs::remove_dir_all(&d);
        d
    }

    fn key(machine: &str) -> SetKey {
        SetKey {
            part: "p".into(),
            machine: Some(machine.into()),
        }
    }

    fn build(dir: &Path, sets: &[(&str, &[(&str, &str)])]) {
        let mut s = AtomicDir::new(dir).unwrap();
        for (machine, files) in sets {
            for (name, text) in *files {
                let mut w = s.create(name).unwrap();
                w.write_all(text.as_bytes()).unwrap();
                w.flush().unwrap();
            }
            let n = s.counter().get();
            s.end_set(key(machine), n);
        }
        s.commit().unwrap();
    }

    fn listing(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn a_rebuild_replaces_only_its_own_set() {
        let d = tmp("sets");
        build(
            &d,
            &[
                (
                    "r",
                    &[
                        ("p_r_m1.src", "1"),
                        ("p_r_m2.src", "2"),
                        ("p_r.src", "main"),
                    ],
                ),
                ("c", &[("p_c.ngc", "g")]),
            ],
        );
        fs::write(d.join("notes.txt"), "mine").unwrap();
        // The robot again, with one module fewer: the old second module goes,
        // the CNC's program and the user's file stay.
        build(&d, &[("r", &[("p_r_m1.src", "1b"), ("p_r.src", "main b")])]);
        assert_eq!(
            listing(&d),
            [
                ".lmdc-manifest",
                "notes.txt",
                "p_c.ngc",
                "p_r.src",
                "p_r_m1.src"
            ]
        );
        assert_eq!(fs::read_to_string(d.join("p_r_m1.src")).unwrap(), "1b");
        assert_eq!(fs::read_to_string(d.join("p_c.ngc")).unwrap(), "g");
        fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn a_failed_build_leaves_nothing() {
        let d = tmp("failed");
        {
            let mut s = AtomicDir::new(&d).unwrap();
            s.create("a.src").unwrap().write_all(b"x").unwrap();
        }
        assert!(!d.exists(), "{:?}", listing(&d));
        build(&d, &[("r", &[("a.src", "1")])]);
        {
            let mut s = AtomicDir::new(&d).unwrap();
            s.create("a.src").unwrap().write_all(b"2").unwrap();
        }
        assert_eq!(listing(&d), [".lmdc-manifest", "a.src"]);
        assert_eq!(fs::read_to_string(d.join("a.src")).unwrap(), "1");
        fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn an_interrupted_commit_is_finished_by_the_next_build() {
        let d = tmp("journal");
        build(
            &d,
            &[(
                "r",
                &[("m1.src", "old 1"), ("m2.src", "old 2"), ("p.src", "old")],
            )],
        );
        // A build killed after its commit point, half-way through the moves:
        // the old files are gone, the first new one is in place.
        let staging = d.join(STAGING);
        fs::create_dir(&staging).unwrap();
        fs::write(staging.join("p.src"), "new").unwrap();
        fs::write(d.join("m1.src"), "new 1").unwrap();
        let journal = Journal {
            format: "lmdc-journal".into(),
            version: 1,
            remove: vec!["p.src".into(), "m2.src".into(), "m1.src".into()],
            serial: 1,
            moves: vec!["m1.src".into(), "p.src".into()],
            manifest: Manifest::new(vec![FileSet {
                key: key("r"),
                files: vec!["m1.src".into(), "p.src".into()],
            }]),
        };
        fs::write(staging.join(JOURNAL), serde_json::to_vec(&journal).unwrap()).unwrap();
        fs::remove_file(d.join("p.src")).unwrap();
        fs::remove_file(d.join("m2.src")).unwrap();
        fs::write(d.join(".lmdc-x1y2.tmp"), "left by an old lmdc").unwrap();
        fs::write(d.join(LOCK), "4000000000\n").unwrap();
        recover(&d).unwrap();
        assert_eq!(listing(&d), [".lmdc-manifest", "m1.src", "p.src"]);
        assert_eq!(fs::read_to_string(d.join("m1.src")).unwrap(), "new 1");
        assert_eq!(fs::read_to_string(d.join("p.src")).unwrap(), "new");
        assert_eq!(Manifest::read(&d), journal.manifest);
        fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn a_sets_main_program_is_its_last_name() {
        let names = |v: &[&str]| v.iter().map(|s| s.to_string()).collect::<Vec<_>>();
        let krl = names(&["p_m1.src", "p_m1.dat", "p.src", "p.dat"]);
        let (main, modules) = main_program(&krl);
        assert_eq!((main, modules), (&krl[2..], &krl[..2]));
        let one = names(&["p.ngc"]);
        assert_eq!(main_program(&one), (&one[..], &[][..]));
        assert_eq!(main_program(&[]), (&[][..], &[][..]));
    }

    #[test]
    fn hidden_names_are_refused() {
        let d = tmp("names");
        let mut s = AtomicDir::new(&d).unwrap();
        for bad in [".lmdc-manifest", "../x", "a/b", ""] {
            assert!(s.create(bad).is_err(), "{bad:?}");
        }
        drop(s);
        assert!(!d.exists());
    }
}
