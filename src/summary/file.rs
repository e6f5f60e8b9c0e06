//! With several files read as one recording (`--joined`), where each
//! file's lines lie in it: the `{"type": "file", …}` records that follow
//! the summary (docs/output.md#several-files).

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
