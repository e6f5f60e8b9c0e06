//! Which format a log is in, from its first bytes (docs/formats.md#detection):
//! binary magic numbers, and for text the shape of the first lines that are not
//! blank — never the file name.

use crate::logs::candump;
use crate::logs::LogFormat;

/// The most text [`detect`] looks at: enough for the longest headers
/// (PEAK TRC 2.x writes about a dozen comment lines, Vector ASC four).
pub const DETECT_LEN: usize = 64 * 1024;

/// The most lines that are neither blank, comments nor deciding that
/// [`detect`] reads past before the first deciding line (the decision in
/// docs/formats.md#detection): a 17th makes the input
/// [`Detected::Unrecognised`].
pub const DETECT_MAX_UNDECIDED: usize = 16;

/// What the first bytes of a log are.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Detected {
    /// A log of this format.
    Format(LogFormat),
    /// A gzip stream (RFC 1952 magic `1f 8b`): inflate it and detect again
    /// (docs/formats.md#gzip).
    Gzip,
    /// Not enough bytes to decide: read more.
    NeedMore,
    /// The whole input holds nothing but blank and comment lines (`#`,
    /// `;`, `//`), or nothing at all: there is nothing to read, whatever
    /// its format.
    Empty,
    /// None of the formats of docs/formats.md.
    Unrecognised,
}

/// Decide the format of a log from its first bytes (up to
/// [`DETECT_LEN`] are looked at; `complete` says that `head` is the whole
/// input, so that a short text can still be decided).
///
/// - pcap: magic `a1b2c3d4` or `a1b23c4d` (nanoseconds), in either byte
///   order; pcapng: the section header block type `0a0d0d0a`; BLF: `LOGG`;
///   MF4: `MDF     ` or `UnFinMF ` and `4.` at byte 8; gzip: `1f 8b`.
/// - Text (the decision in docs/formats.md#detection: random bytes must never
///   pass for a log), line by line: only a line with a format's own shape
///   decides — a PEAK TRC `;$FILEVERSION=` header or row (`N)` and a time); a
///   Vector ASC header that names the format (`date `, `base `, `Begin
///   Triggerblock`, `internal events logged`, `no internal events
///   logged`) or event line (a decimal time followed by a channel number
///   or `CANFD`); a line that [`candump::parse_line`] reads as a frame
///   (candump log or screen). The first deciding line decides. Blank lines
///   and lines that merely start with a comment character (`#`, `;`, `//`)
///   decide nothing; other lines (a damaged line) decide nothing either,
///   so that a log with a bad first line is still read (and the line
///   reported) — but more than [`DETECT_MAX_UNDECIDED`] of them before the
///   first deciding line, or a NUL byte in any line up to it, make the
///   input [`Detected::Unrecognised`], as does no deciding line in the
///   first [`DETECT_LEN`] bytes (or the whole input); nothing but blank
///   and comment lines, [`Detected::Empty`].
///
/// ```
/// use motionwire::logs::{detect, Detected};
/// use motionwire::logs::LogFormat;
///
/// let candump = b"(1700000000.000500) can0 081#1081110000000000\n";
/// assert_eq!(detect(candump, true), Detected::Format(LogFormat::Candump));
/// let asc = b"date Mon Nov 23 07:35:00.000 am 2026\nbase hex  timestamps absolute\n";
/// assert_eq!(detect(asc, true), Detected::Format(LogFormat::Asc));
/// let trc = b";$FILEVERSION=2.1\n;$STARTTIME=45000.5\n";
/// assert_eq!(detect(trc, true), Detected::Format(LogFormat::Trc));
/// assert_eq!(detect(&[0xd4, 0xc3, 0xb2, 0xa1, 2, 0, 4, 0], false), Detected::Format(LogFormat::Pcap));
/// assert_eq!(detect(b"Hello, world!\n", true), Detected::Unrecognised);
/// // A comment character alone decides nothing.
/// assert_eq!(detect(b";\xe9\x17 \x80\n", true), Detected::Empty);
/// assert_eq!(detect(b"junk\n;\x01\x02\x00\n(1.0) can0 705#05\n", true), Detected::Unrecognised);
/// ```
#[must_use]
pub fn detect(head: &[u8], complete: bool) -> Detected {
    if head.starts_with(&[0x1f, 0x8b]) {
        return Detected::Gzip;
    }
    match head.first_chunk::<4>() {
        Some(
            [0xa1, 0xb2, 0xc3, 0xd4]
            | [0xd4, 0xc3, 0xb2, 0xa1]
            | [0xa1, 0xb2, 0x3c, 0x4d]
            | [0x4d, 0x3c, 0xb2, 0xa1],
        ) => return Detected::Format(LogFormat::Pcap),
        Some([0x0a, 0x0d, 0x0d, 0x0a]) => return Detected::Format(LogFormat::Pcapng),
        Some(b"LOGG") => return Detected::Format(LogFormat::Blf),
        Some(b"MDF " | b"UnFi") if is_mf4(head) => return Detected::Format(LogFormat::Mf4),
        Some(_) => {}
        None if complete || head.len() >= 4 => {}
        None => return Detected::NeedMore,
    }
    let head = head.get(..DETECT_LEN).unwrap_or(head);
    let mut rest = head;
    let mut undecided = 0;
    while !rest.is_empty() {
        let (line, next, whole) = match rest.iter().position(|&b| b == b'\n') {
            Some(i) => (
                rest.get(..i).unwrap_or_default(),
                rest.get(i + 1..).unwrap_or_default(),
                true,
            ),
            None => (rest, &[][..], complete || head.len() == DETECT_LEN),
        };
        rest = next;
        if line.contains(&0) {
            // No text log has a NUL before its first frame: binary data
            // (even in a line cut off here, whatever follows it).
            return Detected::Unrecognised;
        }
        if !whole {
            // The last line may be cut off: decide on it only when it is
            // all there is.
            return Detected::NeedMore;
        }
        match line_shape(line) {
            Some(format) => return Detected::Format(format),
            None if is_blank_or_comment(line) => {}
            // A damaged first line does not hide the log after it; many
            // of them are no log.
            None => {
                undecided += 1;
                if undecided > DETECT_MAX_UNDECIDED {
                    return Detected::Unrecognised;
                }
            }
        }
    }
    if complete || head.len() == DETECT_LEN {
        if undecided > 0 {
            Detected::Unrecognised
        } else {
            Detected::Empty
        }
    } else {
        Detected::NeedMore
    }
}

/// Whether `head` starts as an MDF 4 file does (docs/formats.md#mf4): `MDF
/// ` or `UnFinMF `, then the version `4.` at byte 8.
pub(crate) fn is_mf4(head: &[u8]) -> bool {
    let magic = head.get(..8);
    (magic == Some(b"MDF     ") || magic == Some(b"UnFinMF ")) && head.get(8..10) == Some(b"4.")
}

fn trim_start(line: &[u8]) -> &[u8] {
    let start = line
        .iter()
        .position(|&b| b != b' ' && b != b'\t')
        .unwrap_or(line.len());
    line.get(start..).unwrap_or_default()
}

/// A blank line, or one that starts with a comment character of one of the
/// text formats: `#` (candump), `;` (PEAK TRC), `//` (Vector ASC).
fn is_blank_or_comment(line: &[u8]) -> bool {
    match trim_start(line) {
        [] | [b'\r', ..] | [b'#' | b';', ..] | [b'/', b'/', ..] => true,
        // A UTF-8 byte order mark before anything else.
        [0xEF, 0xBB, 0xBF, rest @ ..] => is_blank_or_comment(rest),
        _ => false,
    }
}

/// The format a single line belongs to, if it has that format's own shape.
fn line_shape(line: &[u8]) -> Option<LogFormat> {
    let text = trim_start(line);
    let text = text.strip_prefix(&[0xEF, 0xBB, 0xBF]).unwrap_or(text);
    const ASC_HEADERS: [&[u8]; 5] = [
        b"date ",
        b"base ",
        b"Begin Triggerblock",
        b"internal events logged",
        b"no internal events logged",
    ];
    if text.starts_with(b";$FILEVERSION=") {
        return Some(LogFormat::Trc);
    }
    if ASC_HEADERS.iter().any(|h| text.starts_with(h)) {
        return Some(LogFormat::Asc);
    }
    let digits = text.iter().take_while(|b| b.is_ascii_digit()).count();
    if digits > 0 {
        let after = text.get(digits..).unwrap_or_default();
        // TRC 1.x row: `   1)      1059.900 …` (1.0: `1)  1059 …`): the
        // message number, `)`, then the time offset.
        if let [b')', rest @ ..] = after {
            let time = trim_start(rest);
            if time.len() < rest.len() && time.first().is_some_and(u8::is_ascii_digit) {
                return Some(LogFormat::Trc);
            }
        }
        // ASC event: `   0.012345 1  123 …`, `   0.0123 CANFD   1 …`.
        if let [b'.', frac @ ..] = after {
            let frac_digits = frac.iter().take_while(|b| b.is_ascii_digit()).count();
            let field = trim_start(frac.get(frac_digits..).unwrap_or_default());
            let separated = frac
                .get(frac_digits)
                .is_some_and(|&b| b == b' ' || b == b'\t');
            if frac_digits > 0
                && separated
                && (field.first().is_some_and(u8::is_ascii_digit) || field.starts_with(b"CANFD"))
            {
                return Some(LogFormat::Asc);
            }
        }
    }
    match candump::parse_line(line) {
        Ok(Some(_)) => Some(LogFormat::Candump),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn binary_magics() {
        for (head, format) in [
            (&[0xa1, 0xb2, 0xc3, 0xd4][..], LogFormat::Pcap),
            (&[0xd4, 0xc3, 0xb2, 0xa1], LogFormat::Pcap),
            (&[0xa1, 0xb2, 0x3c, 0x4d], LogFormat::Pcap),
            (&[0x4d, 0x3c, 0xb2, 0xa1], LogFormat::Pcap),
            (&[0x0a, 0x0d, 0x0d, 0x0a], LogFormat::Pcapng),
            (b"LOGG", LogFormat::Blf),
        ] {
            assert_eq!(detect(head, false), Detected::Format(format));
        }
        assert_eq!(detect(&[0x1f, 0x8b, 8, 0], false), Detected::Gzip);
        assert_eq!(detect(&[0x1f, 0x8b], false), Detected::Gzip);
        assert_eq!(detect(&[0xa1], false), Detected::NeedMore);
    }

    /// docs/formats.md#mf4: `MDF     ` or `UnFinMF `, then `4.` at byte 8; MDF
    /// 3 and other text starting so are no MF4.
    #[test]
    fn mf4_magic() {
        for head in [&b"MDF     4.10    "[..], b"UnFinMF 4.11    ", b"MDF     4."] {
            assert_eq!(detect(head, false), Detected::Format(LogFormat::Mf4));
        }
        assert_eq!(detect(b"MDF     3.30    ", true), Detected::Unrecognised);
        assert_eq!(detect(b"MDF 4.10\n", true), Detected::Unrecognised);
    }

    #[test]
    fn text_shapes() {
        let rows: &[(&str, Detected)] = &[
            (
                "(1700000000.000500) can0 081#1081110000000000\n",
                Detected::Format(LogFormat::Candump),
            ),
            (
                "\n# comment\n  can0  081   [8]  10 81 11 00 00 00 00 00\n",
                Detected::Format(LogFormat::Candump),
            ),
            (
                " (2026-11-22 10:11:12.000000)  can0  081   [1]  10\n",
                Detected::Format(LogFormat::Candump),
            ),
            (
                "date Sam Sep 30 15:06:13.191 2017\nbase hex  timestamps absolute\n",
                Detected::Format(LogFormat::Asc),
            ),
            (
                "   0.012345 1  123             Rx   d 8 11 22 33 44 55 66 77 88\n",
                Detected::Format(LogFormat::Asc),
            ),
            (
                "   0.012345 CANFD   1 Rx 123  1 0 8 8 11 22 33 44 55 66 77 88\n",
                Detected::Format(LogFormat::Asc),
            ),
            (
                ";$FILEVERSION=1.1\n;$STARTTIME=43008.920986006946\n",
                Detected::Format(LogFormat::Trc),
            ),
            (
                "     1)      1059.900 DT 0300 Rx 7 00 00 00 00 04 00 00\n",
                Detected::Format(LogFormat::Trc),
            ),
            // A comment line alone decides nothing: any text may start
            // with `;` or `//`.
            (";anything\n", Detected::Empty),
            ("// a comment\n", Detected::Empty),
            (
                ";##########\n;   Start time: 1\n     1)      1059.900 DT 0300 Rx 7 00 00 00 00 04 00 00\n",
                Detected::Format(LogFormat::Trc),
            ),
            ("1) x\n", Detected::Unrecognised),
            ("Hello, world!\n", Detected::Unrecognised),
            ("# only a comment\n\n", Detected::Empty),
            ("", Detected::Empty),
            ("{\"line\": 1}\n", Detected::Unrecognised),
        ];
        for (text, want) in rows {
            assert_eq!(detect(text.as_bytes(), true), *want, "{text:?}");
        }
    }

    #[test]
    fn a_cut_off_line_waits_for_more() {
        assert_eq!(
            detect(b"(1700000000.000500) can0 08", false),
            Detected::NeedMore
        );
        assert_eq!(detect(b"# comment\n", false), Detected::NeedMore);
        assert_eq!(
            detect(b"(1700000000.000500) can0 081#10\n(17", false),
            Detected::Format(LogFormat::Candump)
        );
    }

    #[test]
    fn any_bytes_decide_without_panicking() {
        use proptest::prelude::*;
        proptest!(|(bytes in proptest::collection::vec(any::<u8>(), 0..300), complete in any::<bool>())| {
            let _ = detect(&bytes, complete);
        });
    }

    /// The decision in docs/formats.md#detection: up to 16 lines that decide
    /// nothing are read past, the 17th makes the input unrecognised; a NUL byte
    /// before the deciding line too.
    #[test]
    fn sixteen_undecided_lines_at_most_and_no_nul() {
        let frame = "(1700000000.000500) can0 081#10\n";
        for junk in [0, 1, 16, 17] {
            let mut text = "junk line\n# comment\n\n".repeat(junk);
            text.push_str(frame);
            let want = if junk <= DETECT_MAX_UNDECIDED {
                Detected::Format(LogFormat::Candump)
            } else {
                Detected::Unrecognised
            };
            assert_eq!(detect(text.as_bytes(), true), want, "{junk} junk lines");
        }
        // Comment lines do not count.
        let mut text = "; a comment\n".repeat(100);
        text.push_str(frame);
        assert_eq!(
            detect(text.as_bytes(), true),
            Detected::Format(LogFormat::Candump)
        );
        for text in [&b"# \x00\n(1.0) can0 705#05\n"[..], b"\x00", b"ab\x00cd"] {
            assert_eq!(detect(text, true), Detected::Unrecognised, "{text:?}");
        }
        // A NUL in a cut-off line already decides.
        assert_eq!(detect(b"abc\x00", false), Detected::Unrecognised);
    }

    /// One MiB of random bytes (a fixed seed) is no log, though some of its
    /// lines start with `;`.
    #[test]
    fn random_bytes_are_no_log() {
        let mut state = 0x2545_F491_4F6C_DD1Du64;
        let mut bytes = vec![0u8; 1 << 20];
        for b in &mut bytes {
            // xorshift64*
            state ^= state >> 12;
            state ^= state << 25;
            state ^= state >> 27;
            *b = (state.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 56) as u8;
        }
        assert_eq!(detect(&bytes, true), Detected::Unrecognised);
        // The same bytes without any NUL, from every line start.
        let no_nul: Vec<u8> = bytes.iter().map(|&b| b.max(1)).collect();
        let mut at = 0;
        while let Some(i) = no_nul[at..].iter().position(|&b| b == b'\n') {
            assert_ne!(
                detect(&no_nul[at..], true),
                Detected::Format(LogFormat::Trc),
                "from byte {at}"
            );
            assert!(
                !matches!(detect(&no_nul[at..], true), Detected::Format(_)),
                "from byte {at}"
            );
            at += i + 1;
            if at > 64 * 1024 {
                break;
            }
        }
    }
}
