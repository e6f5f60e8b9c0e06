//! Inflating a BLF file's zlib containers (docs/formats.md#blf): on the
//! reading thread, or on a second thread that inflates the next containers
//! while the reading thread reads the objects of the one before.
//!
//! The second thread gets owned buffers only — a container's compressed
//! bytes and a spare buffer to inflate into — and gives back each result in
//! the order it got the containers, so the reader yields the same records,
//! errors included, in the same order as on one thread.

use std::sync::mpsc::{self, Receiver, SyncSender};
use std::thread::JoinHandle;
use std::vec::Vec;

/// Containers sent ahead to the second thread: one being inflated, the
/// next ones waiting. Each holds at most `MAX_RECORD_LEN` (16 MiB) of
/// compressed and as much inflated data; a writer's containers are far
/// smaller (python-can: 128 KiB inflated).
pub(super) const AHEAD: usize = 3;

/// Inflate the zlib stream `data` into `out` (cleared first): whether it
/// is whole and inflates to exactly `uncompressed` bytes.
pub(super) fn inflate(data: &[u8], uncompressed: usize, out: &mut Vec<u8>) -> bool {
    out.clear();
    append(data, uncompressed, out)
}

/// Inflate `data` at the end of `out`; on failure `out` is as it was.
pub(super) fn append(data: &[u8], uncompressed: usize, out: &mut Vec<u8>) -> bool {
    let before = out.len();
    out.reserve(uncompressed);
    let mut inflater = flate2::Decompress::new(true);
    let status = inflater.decompress_vec(data, out, flate2::FlushDecompress::Finish);
    let whole = matches!(status, Ok(flate2::Status::StreamEnd));
    if !whole || out.len() - before != uncompressed {
        out.truncate(before);
        return false;
    }
    true
}

/// A container for the second thread: its compressed data (the whole body
/// of the `LOG_CONTAINER` object, read from `skip`), its inflated size, and
/// a buffer to inflate into.
struct Job {
    body: Vec<u8>,
    skip: usize,
    uncompressed: usize,
    into: Vec<u8>,
}

/// What the second thread gives back for a [`Job`]: the inflated bytes,
/// or `None` when the container's data is damaged.
type Done = Option<Vec<u8>>;

/// The second thread, with the containers it was given and has not given
/// back.
#[derive(Debug)]
pub(super) struct Inflater {
    jobs: Option<SyncSender<Job>>,
    done: Receiver<Done>,
    thread: Option<JoinHandle<()>>,
    /// Buffers given back, to inflate the next containers into.
    spare: Vec<Vec<u8>>,
}

impl Inflater {
    /// Start the second thread; `None` when the platform cannot start
    /// one (the reader then inflates on its own thread).
    pub(super) fn start() -> Option<Self> {
        let (jobs, queue) = mpsc::sync_channel::<Job>(AHEAD);
        let (results, done) = mpsc::channel::<Done>();
        let thread = std::thread::Builder::new()
            .name("motionwire-blf-inflate".into())
            .spawn(move || {
                for mut job in queue {
                    let data = job.body.get(job.skip..).unwrap_or_default();
                    let ok = inflate(data, job.uncompressed, &mut job.into);
                    if results.send(ok.then_some(job.into)).is_err() {
                        return;
                    }
                }
            })
            .ok()?;
        Some(Inflater {
            jobs: Some(jobs),
            done,
            thread: Some(thread),
            spare: Vec::new(),
        })
    }

    /// Hand the thread a container's body, whose zlib data starts at
    /// `skip`; `false` when the thread is gone.
    pub(super) fn send(&mut self, body: Vec<u8>, skip: usize, uncompressed: usize) -> bool {
        let into = self.spare.pop().unwrap_or_default();
        self.jobs.as_ref().is_some_and(|jobs| {
            jobs.send(Job {
                body,
                skip,
                uncompressed,
                into,
            })
            .is_ok()
        })
    }

    /// Wait for the next container given: its inflated bytes, `Ok(None)`
    /// when its data is damaged; `Err` when the thread is gone.
    pub(super) fn next(&mut self) -> Result<Option<Vec<u8>>, mpsc::RecvError> {
        self.done.recv()
    }

    /// Give back a buffer that was read, for a later container.
    pub(super) fn recycle(&mut self, mut buffer: Vec<u8>) {
        if self.spare.len() < AHEAD {
            buffer.clear();
            self.spare.push(buffer);
        }
    }
}

impl Drop for Inflater {
    /// Stop the thread: it ends when its queue closes, after the container
    /// it is inflating.
    fn drop(&mut self) {
        drop(self.jobs.take());
        if let Some(thread) = self.thread.take() {
            // A thread that panicked has nothing left to give.
            let _ = thread.join();
        }
    }
}
