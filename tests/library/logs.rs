//! `motionwire::logs`: one way to read any log (docs/formats.md). Every
//! fixture reads through `logs::open` as its format's own reader reads it;
//! gzip is inflated once; the line layer's rules hold (over-long lines,
//! NUL bytes, CRLF); a live stream is known to be drained; any bytes end
//! without a panic, with positions that increase; and memory stays within
//! the documented limits whatever the input claims.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::fs::File;
use std::io::{Cursor, Read, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;

use motionwire::logs::asc;
use motionwire::logs::blf::BlfReader;
use motionwire::logs::candump::{self, LineState, RelativeTimestamps};
use motionwire::logs::pcap::PcapReader;
use motionwire::logs::trc;
use motionwire::logs::{
    self, BinaryError, FormatError, LogError, LogErrorKind, LogFormat, LogReader, Position,
    ReadLog, ReadOptions, MAX_LINE_LEN, MAX_RECORD_LEN,
};
use proptest::prelude::*;

/// The allocator of the `library` test binary (this module's, used by every
/// module's tests): the system's, counting the bytes each thread holds and
/// the most it held, so that a test can see how much memory reading an
/// input took. The counts are per thread, so the other tests running at
/// the same time do not change them.
struct Metered;

thread_local! {
    static HELD: Cell<usize> = const { Cell::new(0) };
    static PEAK: Cell<usize> = const { Cell::new(0) };
}

fn add(n: usize) {
    let _ = HELD.try_with(|held| {
        let now = held.get().saturating_add(n);
        held.set(now);
        let _ = PEAK.try_with(|peak| peak.set(peak.get().max(now)));
    });
}

fn sub(n: usize) {
    let _ = HELD.try_with(|held| held.set(held.get().saturating_sub(n)));
}

// SAFETY: every call goes to the system allocator unchanged; the counting
// touches only this thread's counters, which allocate nothing.
unsafe impl GlobalAlloc for Metered {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = System.alloc(layout);
        if !p.is_null() {
            add(layout.size());
        }
        p
    }

    unsafe fn dealloc(&self, p: *mut u8, layout: Layout) {
        System.dealloc(p, layout);
        sub(layout.size());
    }

    unsafe fn realloc(&self, p: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let q = System.realloc(p, layout, new_size);
        if !q.is_null() {
            sub(layout.size());
            add(new_size);
        }
        q
    }
}

#[global_allocator]
static METERED: Metered = Metered;

/// The most memory this thread held above what it held when `f` began.
fn peak_while<T>(f: impl FnOnce() -> T) -> (T, usize) {
    let base = HELD.with(Cell::get);
    PEAK.with(|peak| peak.set(base));
    let out = f();
    (out, PEAK.with(Cell::get) - base)
}

/// What a reader hands on, owned, for comparing two readers: each event
/// or error with its position.
type Items = Vec<(Position, String)>;

/// Read everything `log` hands on, checking the rules every reader keeps:
/// positions increase, and an error that is not skipped is the last item.
fn drain<L: ReadLog + ?Sized>(log: &mut L) -> Items {
    let mut items: Items = Vec::new();
    let mut ended = false;
    while let Some(next) = log.next_event() {
        assert!(!ended, "an item after an error that ends the input");
        let (position, text) = match next {
            Ok(record) => (Some(record.position), format!("{:?}", record.event)),
            Err(error) => {
                ended = !error.is_skipped();
                (error.position(), format!("error: {}", error.kind()))
            }
        };
        if let Some(position) = position {
            if let Some((last, _)) = items.last() {
                assert!(
                    last.number() < position.number(),
                    "{last:?} then {position:?}"
                );
            }
            items.push((position, text));
        } else {
            assert!(
                ended,
                "only an error that ends the input may lack a position"
            );
        }
    }
    assert!(log.next_event().is_none(), "None after the end");
    items
}

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// Every log fixture and the sample, with its format.
fn fixtures() -> Vec<(PathBuf, LogFormat)> {
    let mut out = Vec::new();
    for dir in ["asc", "trc", "blf", "pcap", "candump_screen", "sdo", "pdo"] {
        for entry in std::fs::read_dir(root().join("tests/fixtures").join(dir)).unwrap() {
            let path = entry.unwrap().path();
            let format = match path.extension().and_then(|e| e.to_str()) {
                Some("asc") => LogFormat::Asc,
                Some("trc") => LogFormat::Trc,
                Some("blf") => LogFormat::Blf,
                Some("pcap") => LogFormat::Pcap,
                Some("pcapng") => LogFormat::Pcapng,
                Some("log" | "txt") => LogFormat::Candump,
                _ => continue,
            };
            out.push((path, format));
        }
    }
    out.push((
        root().join("tests/fixtures/python_can.log"),
        LogFormat::Candump,
    ));
    out.push((root().join("samples/machine.log"), LogFormat::Candump));
    out.sort_by(|a, b| a.0.cmp(&b.0));
    out
}

/// What the format's own reader makes of the file: the buffer iterators of
/// the text formats (candump with the relative timestamps its first frames
/// say, docs/formats.md#candump-relative-times), the readers of the binary
/// ones.
fn own_reader(path: &Path, format: LogFormat) -> Items {
    let text = std::fs::read(path).unwrap();
    match format {
        LogFormat::Candump => {
            let relative = candump::detect_relative_timestamps(&text, true).unwrap();
            candump::lines_from(&text, LineState::new(relative))
                .filter_map(|(n, parsed)| match parsed {
                    Ok(None) => None,
                    Ok(Some(frame)) => {
                        Some((n, format!("{:?}", motionwire::can::LogEvent::Frame(frame))))
                    }
                    Err(e) => Some((n, format!("error: {e}"))),
                })
                .collect()
        }
        LogFormat::Asc => text_items(asc::lines(&text)),
        LogFormat::Trc => text_items(trc::lines(&text)),
        LogFormat::Blf => drain(&mut BlfReader::new(File::open(path).unwrap()).unwrap()),
        LogFormat::Pcap | LogFormat::Pcapng => {
            drain(&mut PcapReader::new(File::open(path).unwrap()).unwrap())
        }
        other => panic!("no reader for {other}"),
    }
}

fn text_items<'a>(
    lines: impl Iterator<
        Item = (
            Position,
            Result<Option<motionwire::can::LogEvent<'a>>, FormatError>,
        ),
    >,
) -> Items {
    lines
        .filter_map(|(position, parsed)| match parsed {
            Ok(None) => None,
            Ok(Some(event)) => Some((position, format!("{event:?}"))),
            Err(e) => Some((position, format!("error: {e}"))),
        })
        .collect()
}

#[test]
fn every_fixture_reads_through_open_as_its_own_reader_reads_it() {
    let fixtures = fixtures();
    assert!(fixtures.len() > 30, "{} fixtures", fixtures.len());
    for (path, format) in fixtures {
        let mut log = logs::open(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert_eq!(log.format(), format, "{}", path.display());
        assert!(!log.is_gzip());
        let ours = drain(&mut log);
        let theirs = own_reader(&path, format);
        assert!(!ours.is_empty(), "{}", path.display());
        assert_eq!(ours, theirs, "{}", path.display());
        let skipped = ours.iter().filter(|(_, t)| t.starts_with("error")).count();
        if matches!(format, LogFormat::Candump | LogFormat::Asc | LogFormat::Trc) {
            assert_eq!(log.skipped(), skipped as u64, "{}", path.display());
        }
        assert_eq!(
            log.bytes_read(),
            std::fs::metadata(&path).unwrap().len(),
            "{}",
            path.display()
        );
        // Every record skipped is said by its kind.
        let by_kind: u64 = log.other_kinds().iter().map(|kind| kind.count).sum();
        assert_eq!(by_kind, log.other_records(), "{}", path.display());
    }
}

fn gzip(bytes: &[u8]) -> Vec<u8> {
    let mut gz = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::default());
    gz.write_all(bytes).unwrap();
    gz.finish().unwrap()
}

/// docs/formats.md#gzip: a gzip-compressed log is the log inside it, whatever
/// its format; inflated once only.
#[test]
fn gzip_is_inflated_once() {
    for (name, format) in [
        ("samples/machine.log", LogFormat::Candump),
        ("tests/fixtures/pcap/multi.pcapng", LogFormat::Pcapng),
        ("tests/fixtures/blf/python_can.blf", LogFormat::Blf),
        ("tests/fixtures/trc/python_can_v2_1.trc", LogFormat::Trc),
    ] {
        let plain = std::fs::read(root().join(name)).unwrap();
        let mut log = logs::read(Cursor::new(gzip(&plain))).unwrap();
        assert!(log.is_gzip(), "{name}");
        assert_eq!(log.format(), format, "{name}");
        let inflated = drain(&mut log);
        assert_eq!(log.bytes_read(), plain.len() as u64, "{name}");
        assert_eq!(
            inflated,
            drain(&mut logs::read(Cursor::new(plain)).unwrap()),
            "{name}"
        );
    }
    let twice = gzip(&gzip(b"(1700000000.000500) can0 081#00\n"));
    let error = logs::read(Cursor::new(twice)).unwrap_err();
    assert!(matches!(error.kind(), LogErrorKind::Unrecognised));
    assert_eq!(error.position(), None);
    assert_eq!(
        error.to_string(),
        "unrecognised log format: expected a candump log or screen output, Vector ASC or BLF, \
         PEAK TRC, pcap or pcapng, ASAM MDF 4 (gzip-compressed or not)"
    );
}

/// A gzip stream cut short ends the reading with an I/O error after the
/// lines before the cut.
#[test]
fn a_cut_gzip_stream_is_an_io_error_at_the_end() {
    let mut text = Vec::new();
    for i in 0..2000 {
        writeln!(text, "(1700000000.{i:06}) can0 705#05").unwrap();
    }
    let gz = gzip(&text);
    let mut log = logs::read(Cursor::new(gz[..gz.len() - 20].to_vec())).unwrap();
    let items = drain(&mut log);
    let (position, last) = items.last().unwrap();
    assert!(last.starts_with("error: read error"), "{last}");
    assert_eq!(*position, Position::Line(items.len() as u64));
    assert!(items.len() > 1000);
}

/// An input of nothing but blank and comment lines is an empty candump
/// log; anything that is no log is one error; a damaged binary header is
/// one error too.
#[test]
fn empty_unrecognised_and_damaged_inputs() {
    let mut log = logs::read(&b"\n# a comment\n\r\n"[..]).unwrap();
    assert_eq!(log.format(), LogFormat::Candump);
    assert!(drain(&mut log).is_empty());
    let mut log = logs::read(&b""[..]).unwrap();
    assert!(log.next_event().is_none());

    for garbage in [&b"Hello, world!\n"[..], b"{\"line\": 1}\n", &[0xFF; 100]] {
        let error = logs::read(garbage).unwrap_err();
        assert!(
            matches!(error.kind(), LogErrorKind::Unrecognised),
            "{error}"
        );
    }

    let mut blf = std::fs::read(root().join("tests/fixtures/blf/python_can.blf")).unwrap();
    blf[4..8].copy_from_slice(&8u32.to_le_bytes());
    let error = logs::read(Cursor::new(blf)).unwrap_err();
    assert!(!error.is_skipped());
    assert!(
        matches!(
            error.kind(),
            LogErrorKind::Damaged(FormatError::Binary {
                format: LogFormat::Blf,
                reason: BinaryError::BadLength { length: 8 },
                ..
            })
        ),
        "{error}"
    );

    // A forced format reads what detection would refuse.
    let mut log = ReadOptions::new()
        .format(LogFormat::Candump)
        .read(&b"Hello, world!\n(1.0) can0 705#05\n"[..])
        .unwrap();
    let items = drain(&mut log);
    assert_eq!(items.len(), 2);
    assert!(items[0].1.starts_with("error: candump line"), "{items:?}");
    assert_eq!(items[1].0, Position::Line(2));
}

fn log_text(n: usize, end: &str) -> String {
    (0..n)
        .map(|i| format!("(1700000000.{i:06}) can0 705#05{end}"))
        .collect()
}

/// CRLF files read as LF files, in every text format.
#[test]
fn crlf_reads_as_lf() {
    let asc = "date Mon Nov 23 07:35:00.000 am 2026\nbase hex  timestamps absolute\n\
               internal events logged\nBegin Triggerblock Mon Nov 23 07:35:00.000 am 2026\n   \
               0.012345 1  123             Rx   d 2 11 22\nEnd TriggerBlock\n";
    let trc = ";$FILEVERSION=1.1\n;$STARTTIME=44548.6028595139\n1)  17535.4  Tx  \
               00000100  2  00 01\n2)  17540.3  Warng  FFFFFFFF  4  00 00 00 08  BUSHEAVY\n";
    for text in [log_text(5, "\n"), asc.to_owned(), trc.to_owned()] {
        let crlf = text.replace('\n', "\r\n");
        let lf_items = drain(&mut logs::read(Cursor::new(text.clone())).unwrap());
        let crlf_items = drain(&mut logs::read(Cursor::new(crlf)).unwrap());
        assert!(!lf_items.is_empty());
        assert!(
            lf_items.iter().all(|(_, t)| !t.starts_with("error")),
            "{lf_items:?}"
        );
        assert_eq!(lf_items, crlf_items);
    }
}

/// A NUL byte is a byte of its line, never a line end: the line is
/// malformed, with the column of the NUL, and the next line is read.
#[test]
fn a_nul_byte_makes_its_line_malformed() {
    let text = b"(1700000000.000500) can0 081#00\n(1700000000.000550) can0 7\x0005#05\n\
                 (1700000000.000600) can0 705#05\n";
    let items = drain(&mut logs::read(&text[..]).unwrap());
    assert_eq!(items.len(), 3);
    assert_eq!(items[1].0, Position::Line(2));
    assert_eq!(
        items[1].1,
        "error: candump line, column 27: expected a CAN identifier of 3 or 8 hex digits \
         followed by '#' or white space, found byte 0x00"
    );
    assert_eq!(items[2].0, Position::Line(3));
    for format in [LogFormat::Asc, LogFormat::Trc] {
        let mut log = ReadOptions::new()
            .format(format)
            .read(&b"   1.0 1  1\x0023  Rx   d 1 05\nX\n"[..])
            .unwrap();
        let items = drain(&mut log);
        assert_eq!(items.len(), 2, "{format}");
        assert_eq!(items[0].0, Position::Line(1));
        assert!(items[0].1.starts_with("error"), "{format}: {items:?}");
        assert_eq!(items[1].0, Position::Line(2));
    }
}

/// An input whose bytes are made as they are read: `head`, then `len`
/// bytes of `fill`, then `tail`.
struct Made {
    head: Cursor<Vec<u8>>,
    fill: u8,
    len: u64,
    tail: Cursor<Vec<u8>>,
}

impl Read for Made {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.head.read(buf)?;
        if n > 0 {
            return Ok(n);
        }
        if self.len > 0 {
            let n = buf
                .len()
                .min(usize::try_from(self.len).unwrap_or(usize::MAX));
            buf[..n].fill(self.fill);
            self.len -= n as u64;
            return Ok(n);
        }
        self.tail.read(buf)
    }
}

/// docs/formats.md#memory, bounded memory: a line of 100 MB is one error at its
/// line, skipped unread, and the lines after it are read; the reader never
/// holds more than a line of `MAX_LINE_LEN` and its blocks.
#[test]
fn a_100_mb_line_is_one_error_and_memory_stays_bounded() {
    let input = Made {
        head: Cursor::new(b"(1700000000.000500) can0 081#00\n".to_vec()),
        fill: b'x',
        len: 100_000_000,
        tail: Cursor::new(b"\n(1700000000.000600) can0 705#05\n".to_vec()),
    };
    let (items, peak) = peak_while(|| drain(&mut logs::read(input).unwrap()));
    let positions: Vec<_> = items.iter().map(|(p, _)| *p).collect();
    assert_eq!(
        positions,
        [Position::Line(1), Position::Line(2), Position::Line(3)]
    );
    assert_eq!(
        items[1].1,
        "error: line longer than 1 MiB: not a log line, skipped"
    );
    assert!(peak < MAX_LINE_LEN + (512 << 10), "{peak} bytes held");

    // The same in a file that ends inside the line.
    let input = Made {
        head: Cursor::new(b"(1700000000.000500) can0 081#00\n".to_vec()),
        fill: b'x',
        len: 5 << 20,
        tail: Cursor::new(Vec::new()),
    };
    let mut log = logs::read(input).unwrap();
    let items = drain(&mut log);
    assert_eq!(items.len(), 2);
    assert_eq!(items[1].0, Position::Line(2));
    assert_eq!(log.skipped(), 1);
}

/// A BLF header followed by `object`.
fn blf_with(object: &[u8]) -> Vec<u8> {
    let mut file = std::fs::read(root().join("tests/fixtures/blf/python_can.blf")).unwrap();
    file.truncate(144);
    file.extend_from_slice(object);
    file
}

/// A `LOG_CONTAINER` object header claiming `size` bytes, compression
/// `method` and `inflated` bytes inside, followed by `data`.
fn container(size: u32, method: u16, inflated: u32, data: &[u8]) -> Vec<u8> {
    let mut out = Vec::new();
    out.extend_from_slice(b"LOBJ");
    out.extend_from_slice(&16u16.to_le_bytes());
    out.extend_from_slice(&1u16.to_le_bytes());
    out.extend_from_slice(&size.to_le_bytes());
    out.extend_from_slice(&10u32.to_le_bytes());
    out.extend_from_slice(&method.to_le_bytes());
    out.extend_from_slice(&[0; 6]);
    out.extend_from_slice(&inflated.to_le_bytes());
    out.extend_from_slice(&[0; 4]);
    out.extend_from_slice(data);
    out
}

fn damage(log: &mut LogReader) -> BinaryError {
    let mut reason = None;
    while let Some(next) = log.next_event() {
        if let Err(error) = next {
            match error.kind() {
                LogErrorKind::Damaged(FormatError::Binary { reason: r, .. }) => reason = Some(*r),
                other => panic!("{other}"),
            }
        }
    }
    reason.expect("the damage is said")
}

/// Bounded memory in BLF: a container that claims 4 GB, or 4 GB inside
/// it, is refused before anything is allocated; one that inflates to more
/// than it claims stops at `MAX_RECORD_LEN`.
#[test]
fn a_blf_container_claiming_4_gb_allocates_nothing() {
    let limit = MAX_RECORD_LEN as u64;
    for (object, length) in [
        (container(u32::MAX, 2, 100, &[0; 16]), u64::from(u32::MAX)),
        (container(48, 2, u32::MAX, &[0; 16]), u64::from(u32::MAX)),
    ] {
        let ((reason, _), peak) = peak_while(|| {
            let mut log = logs::read(Cursor::new(blf_with(&object))).unwrap();
            (damage(&mut log), log.other_records())
        });
        assert_eq!(reason, BinaryError::TooLarge { length, limit });
        assert!(peak < 1 << 20, "{peak} bytes held");
    }

    // A zlib bomb: 64 MiB of zeros in 64 KiB, claiming 16 MiB inflated.
    let mut z = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::best());
    let zeros = vec![0u8; 1 << 20];
    for _ in 0..64 {
        z.write_all(&zeros).unwrap();
    }
    let bomb = z.finish().unwrap();
    drop(zeros);
    let object = container(32 + bomb.len() as u32, 2, MAX_RECORD_LEN as u32, &bomb);
    let file = blf_with(&object);
    let (reason, peak) = peak_while(|| damage(&mut logs::read(Cursor::new(file)).unwrap()));
    assert_eq!(reason, BinaryError::Decompression);
    assert!(peak < MAX_RECORD_LEN + (1 << 20), "{peak} bytes held");
}

/// A live stream's chunks, one per read, each shorter than asked: what a
/// pipe from `candump -L` gives. Counts the reads.
struct Pipe {
    chunks: Vec<&'static [u8]>,
    reads: Arc<AtomicUsize>,
}

impl Read for Pipe {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        self.reads.fetch_add(1, Ordering::Relaxed);
        if self.chunks.is_empty() {
            return Ok(0);
        }
        let chunk = self.chunks.remove(0);
        buf[..chunk.len()].copy_from_slice(chunk);
        Ok(chunk.len())
    }
}

/// docs/output.md#live, live use: the reader says it is drained as soon as it
/// has handed on every event of what arrived, before it waits for more —
/// comment lines and `candump -e` explanation lines after the last event
/// included.
#[test]
fn a_live_stream_is_drained_after_each_chunk() {
    let reads = Arc::new(AtomicUsize::new(0));
    let pipe = Pipe {
        chunks: vec![
            b"(1700000000.000500) can0 705#05\n",
            b"(1700000000.000600) can0 705#05\n# a comment\n\n",
            b"(1700000000.000700) can0 20000004#0004000000000000\n",
            b"  can0  20000004   [8]  00 04 00 00 00 00 00 00   ERRORFRAME\n\
              \tcontroller-problem{rx-error-warning}\n",
            b"(1700000000.000800) can0 7X5#05\n",
        ],
        reads: reads.clone(),
    };
    let mut log = logs::read(pipe).unwrap();
    for chunk in 1..=5 {
        let next = log.next_event().unwrap();
        assert_eq!(next.is_err(), chunk == 5);
        assert!(log.drained(), "chunk {chunk}");
        // Nothing was asked of the pipe beyond the chunk of the event.
        assert_eq!(reads.load(Ordering::Relaxed), chunk, "chunk {chunk}");
    }
    assert!(log.next_event().is_none());
}

/// A file read in full blocks is not drained while it has more lines.
#[test]
fn a_file_read_in_full_blocks_is_not_drained() {
    let text = log_text(20_000, "\n");
    let mut log = ReadOptions::new()
        .format(LogFormat::Candump)
        .read(Cursor::new(text))
        .unwrap();
    let mut drained_at = Vec::new();
    while let Some(next) = log.next_event() {
        let number = next.unwrap().position.number();
        if log.drained() {
            drained_at.push(number);
        }
    }
    // Only the first block (the bytes detection read) and the last one.
    assert!(drained_at.len() <= 2, "{drained_at:?}");
}

/// docs/formats.md#candump-relative-times: screen output without timestamps
/// longer than what the relative-timestamp decision looks at reads whole (it
/// once waited for 64 timestamped frames that never came and dropped the held
/// lines).
#[test]
fn a_long_log_without_timestamps_reads_whole() {
    let text: String = (0..20_000)
        .map(|i| format!("  can0  705   [1]  {:02X}\n", i % 256))
        .collect();
    assert!(text.len() > 300_000);
    let mut log = logs::read(Cursor::new(text)).unwrap();
    let items = drain(&mut log);
    assert_eq!(items.len(), 20_000);
    assert!(items.iter().all(|(_, t)| !t.starts_with("error")));
}

/// docs/formats.md#candump-relative-times: relative timestamps decided from the
/// first frames, or given.
#[test]
fn relative_timestamps_detected_or_given() {
    let text = "(000.000000) can0 705#05\n(000.250000) can0 705#05\n(000.100000) can0 705#05\n";
    let times = |options: ReadOptions| -> Vec<u128> {
        let mut log = options.read(Cursor::new(text)).unwrap();
        let mut out = Vec::new();
        while let Some(next) = log.next_event() {
            let ts = next.unwrap().event.timestamp().unwrap();
            out.push(ts.as_duration().as_millis());
        }
        out
    };
    assert_eq!(times(ReadOptions::new()), [0, 250, 350]);
    assert_eq!(
        times(ReadOptions::new().relative_timestamps(RelativeTimestamps::Zero)),
        [0, 250, 100]
    );
    let mut reader = candump::CandumpReader::new(text.as_bytes());
    assert_eq!(reader.relative_timestamps(), None);
    reader.next_event();
    assert_eq!(
        reader.relative_timestamps(),
        Some(RelativeTimestamps::Delta)
    );
}

/// Every record of a damaged binary log after the damage is lost, the
/// records before it are read; a BLF object whose content is bad is
/// skipped alone.
#[test]
fn damage_in_a_binary_log() {
    let pcap = std::fs::read(root().join("tests/fixtures/pcap/can.pcap")).unwrap();
    let whole = drain(&mut logs::read(Cursor::new(pcap.clone())).unwrap());
    let mut cut = pcap.clone();
    cut.truncate(pcap.len() - 3);
    let items = drain(&mut logs::read(Cursor::new(cut)).unwrap());
    let (position, last) = items.last().unwrap();
    assert!(last.starts_with("error: pcap file, byte"), "{last}");
    assert_eq!(*position, Position::Record(whole.len() as u64));
    assert_eq!(items[..items.len() - 1], whole[..whole.len() - 1]);
}

fn text_fragment() -> impl Strategy<Value = Vec<u8>> {
    prop_oneof![
        Just(b"(1700000000.000500) can0 081#1081110000000000\n".to_vec()),
        Just(b"  can0  705   [1]  05\n".to_vec()),
        Just(b"(000.100000) can0 705#05\r\n".to_vec()),
        Just(b"   0.012345 1  123             Rx   d 2 11 22\n".to_vec()),
        Just(b"base dec  timestamps relative\n".to_vec()),
        Just(b";$FILEVERSION=2.1\n".to_vec()),
        Just(b"     1)      1059.900 DT 0300 Rx 7 00 00 00 00 04 00 00\n".to_vec()),
        Just(b"# comment\n\n".to_vec()),
        Just(b"\tcontroller-problem{rx-error-warning}\n".to_vec()),
        proptest::collection::vec(any::<u8>(), 0..40),
    ]
}

fn any_input() -> impl Strategy<Value = Vec<u8>> {
    let fixtures: Vec<Vec<u8>> = [
        "tests/fixtures/blf/python_can.blf",
        "tests/fixtures/pcap/multi.pcapng",
        "tests/fixtures/pcap/can_be.pcap",
        "tests/fixtures/trc/handmade_v2_1.trc",
    ]
    .iter()
    .map(|name| std::fs::read(root().join(name)).unwrap())
    .collect();
    prop_oneof![
        proptest::collection::vec(any::<u8>(), 0..600),
        proptest::collection::vec(text_fragment(), 0..30).prop_map(|parts| parts.concat()),
        // A fixture, cut and with some bytes changed.
        (
            proptest::sample::select(fixtures),
            any::<proptest::sample::Index>(),
            proptest::collection::vec((any::<proptest::sample::Index>(), any::<u8>()), 0..8),
        )
            .prop_map(|(mut file, cut, changes)| {
                for (at, byte) in changes {
                    let i = at.index(file.len());
                    file[i] = byte;
                }
                file.truncate(cut.index(file.len() + 1));
                file
            }),
    ]
}

proptest! {
    /// Any bytes, read as detected or as any format: no panic, an end,
    /// positions that increase, and nothing after an error that ends the
    /// input (`drain` checks it).
    #[test]
    fn any_bytes_read_to_an_end(
        bytes in any_input(),
        gzipped in any::<bool>(),
        format in proptest::option::of(proptest::sample::select(LogFormat::ALL.to_vec())),
    ) {
        let input = if gzipped { gzip(&bytes) } else { bytes };
        let mut options = ReadOptions::new();
        if let Some(format) = format {
            options = options.format(format);
        }
        match options.read(Cursor::new(input)) {
            Ok(mut log) => {
                let items = drain(&mut log);
                let errors = items
                    .iter()
                    .filter(|(p, t)| t.starts_with("error") && matches!(p, Position::Line(_)))
                    .count() as u64;
                prop_assert!(log.skipped() <= errors);
            }
            Err(error) => prop_assert!(!error.is_skipped()),
        }
    }
}

/// `LogError`'s words: the position, then the reason.
#[test]
fn errors_say_where_and_why() {
    let error = LogError::new(Some(Position::Line(3)), LogErrorKind::OverlongLine);
    assert_eq!(
        error.to_string(),
        "line 3: line longer than 1 MiB: not a log line, skipped"
    );
    assert!(error.is_skipped());
    let io = LogError::from(std::io::Error::other("gone"));
    assert_eq!(io.to_string(), "read error: gone");
    assert!(!io.is_skipped());
    assert!(std::error::Error::source(&io).is_some());
}

/// A reader can move to another thread (`read` takes `Send` inputs).
#[test]
fn a_log_reader_is_send() {
    fn send<T: Send>(_: &T) {}
    let log = logs::read(&b"(1.0) can0 705#05\n"[..]).unwrap();
    send(&log);
    let handle = std::thread::spawn(move || {
        let mut log = log;
        drain(&mut log).len()
    });
    assert_eq!(handle.join().unwrap(), 1);
}
