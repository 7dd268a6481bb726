//! The staging folder's writer thread: the back ends format the programs,
//! this thread creates and fills their files meanwhile.
//!
//! Creating a file is a metadata operation that waits on the filesystem
//! (0.17 ms each on ext4 here: 0.6 s of the dense duct's 1.4 s of emitting
//! KRL went into creating its 3 608 files), so the formatting thread hands
//! whole buffers over and goes on, and the second core creates and writes
//! them. Files are created one after another in the order the back end
//! opened them, exactly as before; only who waits for the disk changed.

use std::fs::{File, OpenOptions};
use std::io::{self, Write};
use std::path::PathBuf;
use std::sync::mpsc::{sync_channel, Receiver, SyncSender};
use std::sync::{Arc, Mutex, PoisonError};
use std::thread::JoinHandle;

/// How many bytes a file's writer gathers before it hands them over.
const CHUNK: usize = 1 << 20;
/// How many hand-overs may wait for the thread. The memory a build holds
/// beyond its own is bounded by `(DEPTH + 2) × CHUNK`: waiting, being
/// written, and being filled.
const DEPTH: usize = 16;

/// What the formatting thread asks of the writer thread, in order.
enum Job {
    /// Create this file (a plain name in the staging folder); what follows
    /// goes into it.
    Open(String),
    /// The next bytes of the open file.
    Data(Vec<u8>),
    /// The open file is complete.
    Close,
}

/// The first error the thread met; it stops there.
type Failure = Arc<Mutex<Option<io::Error>>>;

/// The writer thread of one staging folder and the way to it.
pub(super) struct Writer {
    jobs: Option<SyncSender<Job>>,
    thread: Option<JoinHandle<()>>,
    failure: Failure,
}

impl Writer {
    /// Starts a thread that creates and fills files in `staging`.
    pub(super) fn start(staging: PathBuf) -> io::Result<Writer> {
        let (jobs, queue) = sync_channel(DEPTH);
        let failure = Failure::default();
        let stored = Arc::clone(&failure);
        let thread = std::thread::Builder::new()
            .name("lmdc-writer".into())
            .spawn(move || run(&staging, queue, &stored))?;
        Ok(Writer {
            jobs: Some(jobs),
            thread: Some(thread),
            failure,
        })
    }

    /// A writer for a new file `name`: what is written to it reaches the
    /// file on this thread, in order.
    pub(super) fn create(&self, name: &str) -> io::Result<FileWriter<'_>> {
        self.send(Job::Open(name.to_string()))?;
        Ok(FileWriter {
            writer: self,
            buf: Vec::new(),
        })
    }

    /// Waits until every file handed over is written (not flushed to disk)
    /// and stops the thread: the first error it met, if any.
    pub(super) fn finish(&mut self) -> io::Result<()> {
        // Closing the queue ends the thread's loop once it is empty.
        self.jobs = None;
        if let Some(t) = self.thread.take() {
            if t.join().is_err() {
                return Err(io::Error::other("the staging folder's writer failed"));
            }
        }
        match self.take_failure() {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }

    fn send(&self, job: Job) -> io::Result<()> {
        let sent = match &self.jobs {
            Some(jobs) => jobs.send(job).is_ok(),
            None => false,
        };
        if sent {
            return Ok(());
        }
        // The thread stopped, and it stores why before it lets go of the
        // queue: the send could only fail after that.
        Err(self
            .take_failure()
            .unwrap_or_else(|| io::Error::other("the staging folder's writer stopped")))
    }

    fn take_failure(&self) -> Option<io::Error> {
        self.failure
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .take()
    }
}

impl Drop for Writer {
    fn drop(&mut self) {
        // A failed build's staging folder is removed after this: no file may
        // be created in it afterwards.
        let _ = self.finish();
    }
}

/// The thread: carries the jobs out in order until the queue closes or one
/// fails.
fn run(staging: &std::path::Path, queue: Receiver<Job>, failure: &Failure) {
    let mut file: Option<File> = None;
    for job in queue {
        let done = match job {
            Job::Open(name) => OpenOptions::new()
                .write(true)
                .create_new(true)
                .open(staging.join(name))
                .map(|f| file = Some(f)),
            Job::Data(bytes) => match file.as_mut() {
                Some(f) => f.write_all(&bytes),
                None => Err(io::Error::other("bytes for no file")),
            },
            Job::Close => {
                file = None;
                Ok(())
            }
        };
        if let Err(e) = done {
            *failure.lock().unwrap_or_else(PoisonError::into_inner) = Some(e);
            // Returning drops the queue: the next hand-over fails and
            // reports `e`.
            return;
        }
    }
}

/// A file being written: gathers the back end's bytes and hands them to the
/// thread a chunk at a time. `flush` hands over what it holds and reports
/// an error the thread met by then; one met later is reported when the
/// staging folder is flushed, before anything is committed.
pub(super) struct FileWriter<'a> {
    writer: &'a Writer,
    buf: Vec<u8>,
}

impl FileWriter<'_> {
    fn hand_over(&mut self) -> io::Result<()> {
        if self.buf.is_empty() {
            return Ok(());
        }
        let bytes = std::mem::take(&mut self.buf);
        self.writer.send(Job::Data(bytes))
    }
}

impl Write for FileWriter<'_> {
    fn write(&mut self, b: &[u8]) -> io::Result<usize> {
        self.write_all(b)?;
        Ok(b.len())
    }

    fn write_all(&mut self, b: &[u8]) -> io::Result<()> {
        if self.buf.capacity() == 0 {
            self.buf.reserve(CHUNK);
        }
        self.buf.extend_from_slice(b);
        if self.buf.len() >= CHUNK {
            self.hand_over()?;
        }
        Ok(())
    }

    fn flush(&mut self) -> io::Result<()> {
        self.hand_over()
    }
}

impl Drop for FileWriter<'_> {
    fn drop(&mut self) {
        // Errors here are the thread's, and it keeps them for
        // `Writer::finish`.
        let _ = self.hand_over();
        let _ = self.writer.send(Job::Close);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tmp(tag: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("lmdc-writer-{tag}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn files_come_out_whole_and_in_order() {
        let d = tmp("order");
        let mut w = Writer::start(d.clone()).unwrap();
        // Larger than a chunk, to cross hand-overs, and small ones.
        let big: Vec<u8> = (0..3 * CHUNK + 17).map(|i| (i % 251) as u8).collect();
        for (name, bytes) in [("a.src", &big[..]), ("b.dat", b"DEFDAT b\n"), ("c", b"")] {
            let mut f = w.create(name).unwrap();
            for piece in bytes.chunks(4093) {
                f.write_all(piece).unwrap();
            }
            f.flush().unwrap();
        }
        w.finish().unwrap();
        assert_eq!(std::fs::read(d.join("a.src")).unwrap(), big);
        assert_eq!(std::fs::read(d.join("b.dat")).unwrap(), b"DEFDAT b\n");
        assert_eq!(std::fs::read(d.join("c")).unwrap(), b"");
        let _ = std::fs::remove_dir_all(&d);
    }

    #[test]
    fn a_failure_is_reported_not_lost() {
        let d = tmp("fail");
        let mut w = Writer::start(d.join("missing")).unwrap();
        let mut f = w.create("a.src").unwrap();
        // The thread fails to create the file; a later hand-over or the
        // finish reports why.
        let written = (0..64).try_for_each(|_| {
            f.write_all(&vec![b'x'; CHUNK])?;
            f.flush()
        });
        drop(f);
        let finished = w.finish();
        let e = written.err().or(finished.err()).expect("an error");
        assert_eq!(e.kind(), io::ErrorKind::NotFound, "{e}");
        let _ = std::fs::remove_dir_all(&d);
    }
}
