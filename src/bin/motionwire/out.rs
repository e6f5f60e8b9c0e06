//! Standard output of `motionwire decode`, written on a thread of its own
//! where that pays.
//!
//! Records are built into a block in memory. Into a pipe or a file
//! (`motionwire decode --json LOG | jq …`, `> out.json`), with a second
//! core, a full block is handed to a writer thread, which copies it into
//! the pipe or the page cache while the next one is built; the thread
//! starts with the first full block, so an output that never fills one (a
//! summary) is written on the caller's thread, at [`Out::flush`] or
//! [`Out::finish`]. To a terminal or `/dev/null`, where the write costs
//! little or the order beside standard error matters, smaller blocks are
//! written on the caller's thread. Blocks are written in the order they
//! are built; at most [`IN_FLIGHT`] wait, so the memory used does not grow
//! with the output.

use std::io::{self, Write};
use std::sync::mpsc::{self, Receiver, SyncSender};
use std::thread::{self, JoinHandle};

/// How many bytes of records are built before they are handed to the
/// writer thread: each hand-over wakes it.
const BLOCK: usize = 1 << 20;

/// How many bytes of records are built before they are written on the
/// caller's thread: a block that stays in the core's cache.
const DIRECT_BLOCK: usize = 1 << 16;

/// How many full blocks may wait for the writer thread.
const IN_FLIGHT: usize = 2;

/// What the writer thread is asked to do.
enum Job {
    /// Write the block, then give it back to be filled again.
    Write(Vec<u8>),
    /// Flush standard output, then say so.
    Flush,
}

/// The writer thread and the ways to it.
struct Writer {
    jobs: SyncSender<Job>,
    /// Blocks written, given back to be filled again.
    spare: Receiver<Vec<u8>>,
    /// A flush done.
    flushed: Receiver<()>,
    thread: JoinHandle<io::Result<()>>,
}

/// Standard output: the block being built, and the writer thread once a
/// block was full.
pub struct Out {
    block: Vec<u8>,
    /// The block's length at which it is written out or handed over.
    full: usize,
    /// Full blocks go to a writer thread.
    apart: bool,
    writer: Option<Writer>,
}

impl Out {
    pub fn new() -> Self {
        let apart = writes_apart();
        let full = if apart { BLOCK } else { DIRECT_BLOCK };
        Out {
            block: Vec::with_capacity(full + full / 16),
            full,
            apart,
            writer: None,
        }
    }

    /// The block being built, for a writer that appends to a `Vec` (the
    /// JSON records); [`Out::wrote`] after each record.
    #[inline]
    pub fn block(&mut self) -> &mut Vec<u8> {
        &mut self.block
    }

    /// A record was appended to [`Out::block`]: hand the block over when
    /// it is full.
    #[inline]
    pub fn wrote(&mut self) -> io::Result<()> {
        if self.block.len() >= self.full {
            self.hand_over()?;
        }
        Ok(())
    }

    /// Hand the block to the writer thread (started now if it was not) and
    /// take an empty one; or write it here.
    #[cold]
    fn hand_over(&mut self) -> io::Result<()> {
        if !self.apart {
            io::stdout().lock().write_all(&self.block)?;
            self.block.clear();
            return Ok(());
        }
        let writer = match &mut self.writer {
            Some(writer) => writer,
            None => self.writer.insert(Writer::start()?),
        };
        let next = writer
            .spare
            .try_recv()
            .unwrap_or_else(|_| Vec::with_capacity(self.block.capacity()));
        let full = std::mem::replace(&mut self.block, next);
        if writer.jobs.send(Job::Write(full)).is_err() {
            return Err(self.stopped());
        }
        Ok(())
    }

    /// Write out everything so far: on return it is on standard output.
    pub fn flush(&mut self) -> io::Result<()> {
        if self.writer.is_none() {
            let mut stdout = io::stdout().lock();
            stdout.write_all(&self.block)?;
            self.block.clear();
            return stdout.flush();
        }
        if !self.block.is_empty() {
            self.hand_over()?;
        }
        let Some(writer) = &self.writer else {
            return Ok(());
        };
        if writer.jobs.send(Job::Flush).is_err() || writer.flushed.recv().is_err() {
            return Err(self.stopped());
        }
        Ok(())
    }

    /// Write out everything and end the writer thread, with the first error
    /// it met.
    pub fn finish(mut self) -> io::Result<()> {
        self.flush()?;
        match self.writer.take() {
            Some(writer) => writer.join(),
            None => Ok(()),
        }
    }

    /// The writer thread stopped: its error.
    #[cold]
    fn stopped(&mut self) -> io::Error {
        match self.writer.take() {
            Some(writer) => match writer.join() {
                Err(error) => error,
                Ok(()) => io::Error::other("standard output's writer stopped"),
            },
            None => io::Error::other("standard output's writer stopped"),
        }
    }
}

impl Write for Out {
    #[inline]
    fn write(&mut self, bytes: &[u8]) -> io::Result<usize> {
        self.write_all(bytes)?;
        Ok(bytes.len())
    }

    #[inline]
    fn write_all(&mut self, bytes: &[u8]) -> io::Result<()> {
        self.block.extend_from_slice(bytes);
        self.wrote()
    }

    fn flush(&mut self) -> io::Result<()> {
        Out::flush(self)
    }
}

impl Drop for Out {
    /// On an early return (an error said elsewhere), what was built is
    /// still written, as a `BufWriter` would; errors are not said twice.
    fn drop(&mut self) {
        if self.writer.is_some() || !self.block.is_empty() {
            let _ = self.flush();
        }
        if let Some(writer) = self.writer.take() {
            let _ = writer.join();
        }
    }
}

/// Whether standard output is a pipe or a file, and a second core can
/// copy into it.
#[cfg(unix)]
fn writes_apart() -> bool {
    use std::os::fd::AsFd;
    use std::os::unix::fs::FileTypeExt;

    let cores = thread::available_parallelism().map_or(1, usize::from);
    let Ok(fd) = io::stdout().as_fd().try_clone_to_owned() else {
        return false;
    };
    let Ok(metadata) = std::fs::File::from(fd).metadata() else {
        return false;
    };
    let kind = metadata.file_type();
    cores > 1 && (kind.is_fifo() || kind.is_file())
}

/// Elsewhere, standard output is written on the caller's thread.
#[cfg(not(unix))]
fn writes_apart() -> bool {
    false
}

impl Writer {
    fn start() -> io::Result<Self> {
        let (jobs, queue) = mpsc::sync_channel::<Job>(IN_FLIGHT);
        let (give_back, spare) = mpsc::sync_channel(IN_FLIGHT + 1);
        let (say_flushed, flushed) = mpsc::sync_channel(1);
        let thread =
            thread::Builder::new()
                .name("stdout".into())
                .spawn(move || -> io::Result<()> {
                    let stdout = io::stdout();
                    for job in queue {
                        match job {
                            Job::Write(mut block) => {
                                stdout.lock().write_all(&block)?;
                                block.clear();
                                // Full: the block is dropped instead.
                                let _ = give_back.try_send(block);
                            }
                            Job::Flush => {
                                stdout.lock().flush()?;
                                if say_flushed.send(()).is_err() {
                                    break;
                                }
                            }
                        }
                    }
                    stdout.lock().flush()
                })?;
        Ok(Writer {
            jobs,
            spare,
            flushed,
            thread,
        })
    }

    /// Close the queue and wait for the thread: its first error.
    fn join(self) -> io::Result<()> {
        let Writer { jobs, thread, .. } = self;
        drop(jobs);
        thread
            .join()
            .unwrap_or_else(|_| Err(io::Error::other("standard output's writer panicked")))
    }
}
