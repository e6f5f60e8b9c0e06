//! With several files read as one recording (`--joined`), where each
//! file's lines lie in it: the `{"type": "file", …}` records that follow
//! the summary (docs/output.md#several-files).

use crate::logs::Position;
use core::fmt;

/// One file of a recording read from several files, and the lines it holds
/// in the recording's numbering (docs/output.md#several-files).
///
/// `Display` writes the text summary's line, `file NAME  lines 1 to 2000`;
/// `Serialize` writes the JSON record `{"type": "file",
/// "file", "first_line", "last_line"}`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FileSpan {
    /// The file, as it was named.
    pub file: String,
    /// Its first line in the recording.
    pub first_line: u64,
    /// Its last line in the recording.
    pub last_line: u64,
}

impl fmt::Display for FileSpan {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "file {}  lines {} to {}",
            self.file, self.first_line, self.last_line
        )
    }
}

impl serde::Serialize for FileSpan {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let mut map = serializer.serialize_map(Some(4))?;
        map.serialize_entry("type", "file")?;
        map.serialize_entry("file", &self.file)?;
        map.serialize_entry("first_line", &self.first_line)?;
        map.serialize_entry("last_line", &self.last_line)?;
        map.end()
    }
}

/// Several logs read one after the other (docs/output.md#several-files):
/// each a recording of its own, or joined into one recording whose lines
/// are numbered on from one file to the next. It says when a recording
/// begins and ends, which line of the recording a file's line is, and,
/// joined, where each file's lines lie ([`FileSpan`]).
///
/// A reader of the files calls [`begin`](Self::begin) before each file
/// (a fresh decoder and summarizer when it returns `true`: nothing learned
/// from the file before carries over), numbers each position with
/// [`line`](Self::line), and calls [`end`](Self::end) after it (the file's
/// summary, named by the file, when it returns `true`). After the last
/// file, the recording not yet ended is summarized, followed by the
/// [`spans`](Self::spans).
///
/// ```
/// use motionwire::logs::Position;
/// use motionwire::summary::{FileSpan, SeveralFiles};
///
/// // Two rotated logs of one bus, joined: 2000 and 500 lines.
/// let mut files = SeveralFiles::new(2, true);
/// assert!(!files.begin());
/// assert_eq!(files.line(Position::Line(2000)), Position::Line(2000));
/// assert!(!files.end("a.log", 2000));
/// assert!(!files.begin()); // the same recording goes on
/// assert_eq!(files.line(Position::Line(1)), Position::Line(2001));
/// assert!(!files.end("b.log", 500));
/// assert_eq!(
///     files.spans()[1],
///     FileSpan { file: "b.log".into(), first_line: 2001, last_line: 2500 }
/// );
///
/// // The same files apart: two recordings, each summary naming its file.
/// let mut files = SeveralFiles::new(2, false);
/// assert!(!files.begin());
/// assert!(files.end("a.log", 2000));
/// assert!(files.begin()); // a fresh decoder and summarizer
/// assert_eq!(files.line(Position::Line(1)), Position::Line(1));
/// assert!(files.end("b.log", 500));
/// assert!(files.spans().is_empty());
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SeveralFiles {
    count: usize,
    joined: bool,
    /// Files begun so far.
    begun: usize,
    /// The lines of the files before this one, when joined.
    offset: u64,
    spans: Vec<FileSpan>,
}

impl SeveralFiles {
    /// Read `count` files, joined into one recording when `joined` (one
    /// file is one recording either way).
    #[must_use]
    pub fn new(count: usize, joined: bool) -> Self {
        SeveralFiles {
            count,
            joined: joined && count > 1,
            begun: 0,
            offset: 0,
            spans: Vec::new(),
        }
    }

    /// Return whether there are several files: every record then names
    /// its file (docs/output.md#several-files).
    #[must_use]
    pub fn several(&self) -> bool {
        self.count > 1
    }

    /// Return whether several files are one recording (`--joined`).
    #[must_use]
    pub fn joined(&self) -> bool {
        self.joined
    }

    /// Begin the next file; return whether it begins a recording of its
    /// own after another (files apart, every file after the first): the
    /// reader then starts a fresh decoder and summarizer.
    pub fn begin(&mut self) -> bool {
        self.begun += 1;
        self.several() && !self.joined && self.begun > 1
    }

    /// Return the position in the recording of the position `position`
    /// of the current file (docs/formats.md#positions): numbered on from
    /// the lines or records of the files before it when joined, the
    /// file's own else.
    #[must_use]
    pub fn line(&self, position: Position) -> Position {
        match position {
            Position::Line(n) => Position::Line(self.offset + n),
            Position::Record(n) => Position::Record(self.offset + n),
        }
    }

    /// End the current file, named `name`, whose last line or record is
    /// `last`; return whether its recording ends with it (files apart):
    /// its summary is then written, naming the file ([`Summary::file`](super::Summary::file)).
    /// Joined, the file's [`FileSpan`] is kept and the next file's lines
    /// follow its last.
    pub fn end(&mut self, name: &str, last: u64) -> bool {
        if self.joined {
            self.spans.push(FileSpan {
                file: name.to_owned(),
                first_line: self.offset + 1,
                last_line: self.offset + last,
            });
            self.offset += last;
            return false;
        }
        self.several()
    }

    /// Return where each file's lines lie in the recording, with files
    /// joined (empty otherwise): the records that follow its summary.
    #[must_use]
    pub fn spans(&self) -> &[FileSpan] {
        &self.spans
    }

    /// Return the spans ([`spans`](Self::spans)), leaving none.
    #[must_use]
    pub fn take_spans(&mut self) -> Vec<FileSpan> {
        core::mem::take(&mut self.spans)
    }
}
