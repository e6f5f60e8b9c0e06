//! The INI layer of CiA 306 files: sections, keys and values with the line
//! each stands on, borrowed from the text.
//!
//! CiA 306 writes an EDS or DCF as INI text: `[section]` headers,
//! `key=value` lines, comments from `;`. Section names and keys are
//! compared without regard to ASCII case. A `;` that starts a line, or that
//! follows white space, starts a comment (as python-canopen's
//! `RawConfigParser(inline_comment_prefixes=(';',))` reads it: `a;b` is a
//! value, `a ;b` the value `a`). A section or key written twice is an
//! error, as it is for python-canopen (Python's `configparser` in strict
//! mode).

use std::fmt;

/// One `key=value` line.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct IniEntry<'a> {
    /// The key, trimmed.
    pub key: &'a str,
    /// The value, trimmed, without an inline comment.
    pub value: &'a str,
    /// The 1-based line number.
    pub line: usize,
}

/// One `[section]` with its entries in file order.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct IniSection<'a> {
    /// The name between the brackets, trimmed.
    pub name: &'a str,
    /// The 1-based line number of the header.
    pub line: usize,
    /// The entries, in file order.
    pub entries: Vec<IniEntry<'a>>,
}

impl<'a> IniSection<'a> {
    /// Return the entry of `key` (ASCII case ignored).
    #[must_use]
    pub fn entry(&self, key: &str) -> Option<&IniEntry<'a>> {
        self.entries
            .iter()
            .find(|entry| entry.key.eq_ignore_ascii_case(key))
    }

    /// Return the value of `key` (ASCII case ignored).
    #[must_use]
    pub fn get(&self, key: &str) -> Option<&'a str> {
        self.entry(key).map(|entry| entry.value)
    }
}

/// Why a line of INI text is malformed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum IniErrorKind {
    /// `[` without a closing `]`.
    UnclosedSection,
    /// Something other than a comment after a section's `]`.
    TextAfterSection,
    /// A line that is neither a section, a `key=value` nor a comment.
    ExpectedKeyValue,
    /// A `key=value` line before the first section.
    KeyOutsideSection,
    /// An empty key (`=value`) or section name (`[]`).
    EmptyName,
    /// A section written a second time.
    DuplicateSection {
        /// The line of the first header.
        first_line: usize,
    },
    /// A key written a second time in one section.
    DuplicateKey {
        /// The line of the first one.
        first_line: usize,
    },
}

impl fmt::Display for IniErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            IniErrorKind::UnclosedSection => f.write_str("expected ']' to close the section name"),
            IniErrorKind::TextAfterSection => {
                f.write_str("expected the end of the line or a comment after ']'")
            }
            IniErrorKind::ExpectedKeyValue => {
                f.write_str("expected a [section], a key=value line or a ; comment")
            }
            IniErrorKind::KeyOutsideSection => {
                f.write_str("expected a [section] before the first key=value line")
            }
            IniErrorKind::EmptyName => f.write_str("expected a name, found nothing"),
            IniErrorKind::DuplicateSection { first_line } => {
                write!(f, "section already written at line {first_line}")
            }
            IniErrorKind::DuplicateKey { first_line } => {
                write!(f, "key already written at line {first_line}")
            }
        }
    }
}

/// A malformed line of INI text.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct IniError {
    /// The 1-based line number.
    pub line: usize,
    /// The section the line is in (or the header that repeats one).
    pub section: Option<String>,
    /// The key, for a repeated key.
    pub key: Option<String>,
    /// What is wrong.
    pub kind: IniErrorKind,
}

/// INI text read into sections, borrowing from the text (CiA 306).
///
/// ```
/// use motionwire::eds::IniFile;
///
/// let ini = IniFile::parse("; comment\n[1A00]\nParameterName=TPDO 1 mapping ; note\nsubnumber = 2\n")?;
/// let section = ini.section("1a00").unwrap();
/// assert_eq!(section.get("parametername"), Some("TPDO 1 mapping"));
/// assert_eq!(section.entry("SubNumber").unwrap().line, 4);
/// # Ok::<(), motionwire::eds::IniError>(())
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct IniFile<'a> {
    sections: Vec<IniSection<'a>>,
}

impl<'a> IniFile<'a> {
    /// Read `text`. A UTF-8 byte-order mark at the start is skipped; lines
    /// end in `\n` or `\r\n`.
    pub fn parse(text: &'a str) -> Result<Self, IniError> {
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        let mut sections: Vec<IniSection<'a>> = Vec::new();
        // Lower-cased section name → position, for the duplicate check.
        let mut seen: std::collections::HashMap<String, usize> = std::collections::HashMap::new();
        for (number, raw) in text.split('\n').enumerate() {
            let line = number + 1;
            let trimmed = raw.trim();
            if trimmed.is_empty() || trimmed.starts_with(';') {
                continue;
            }
            let error = |sections: &[IniSection<'a>], kind| IniError {
                line,
                section: sections.last().map(|s| s.name.to_owned()),
                key: None,
                kind,
            };
            if let Some(rest) = trimmed.strip_prefix('[') {
                // A broken section header belongs to no section: the error
                // names its line, not the section before it.
                let Some(close) = rest.find(']') else {
                    return Err(error(&[], IniErrorKind::UnclosedSection));
                };
                let after = strip_comment(&rest[close + 1..]);
                if !after.is_empty() {
                    return Err(error(&[], IniErrorKind::TextAfterSection));
                }
                let name = rest[..close].trim();
                if name.is_empty() {
                    return Err(error(&[], IniErrorKind::EmptyName));
                }
                let lower = name.to_ascii_lowercase();
                if let Some(&at) = seen.get(&lower) {
                    return Err(IniError {
                        line,
                        section: Some(name.to_owned()),
                        key: None,
                        kind: IniErrorKind::DuplicateSection {
                            first_line: sections[at].line,
                        },
                    });
                }
                seen.insert(lower, sections.len());
                sections.push(IniSection {
                    name,
                    line,
                    entries: Vec::new(),
                });
                continue;
            }
            let Some((key, value)) = trimmed.split_once('=') else {
                return Err(error(&sections, IniErrorKind::ExpectedKeyValue));
            };
            let key = key.trim();
            if key.is_empty() {
                return Err(error(&sections, IniErrorKind::EmptyName));
            }
            let Some(section) = sections.last_mut() else {
                return Err(error(&sections, IniErrorKind::KeyOutsideSection));
            };
            if let Some(first) = section.entry(key) {
                return Err(IniError {
                    line,
                    section: Some(section.name.to_owned()),
                    key: Some(key.to_owned()),
                    kind: IniErrorKind::DuplicateKey {
                        first_line: first.line,
                    },
                });
            }
            section.entries.push(IniEntry {
                key,
                value: strip_comment(value),
                line,
            });
        }
        Ok(IniFile { sections })
    }

    /// Return the sections in file order.
    #[must_use]
    pub fn sections(&self) -> &[IniSection<'a>] {
        &self.sections
    }

    /// Return the section `name` (ASCII case ignored).
    #[must_use]
    pub fn section(&self, name: &str) -> Option<&IniSection<'a>> {
        self.sections
            .iter()
            .find(|section| section.name.eq_ignore_ascii_case(name))
    }
}

/// Return `text` without a comment (`;` at its start or after white space),
/// trimmed.
fn strip_comment(text: &str) -> &str {
    let bytes = text.as_bytes();
    let mut end = bytes.len();
    for (i, &b) in bytes.iter().enumerate() {
        if b == b';' && (i == 0 || bytes[i - 1].is_ascii_whitespace()) {
            end = i;
            break;
        }
    }
    text[..end].trim()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn comments_and_case() {
        let text = "\u{feff}[FileInfo]\r\nFileName=x.eds\r\n\r\n; whole line\r\n[1000] ; trailing\r\nParameterName=Device type\r\nDefaultValue=0x00020192 ;402\r\nDescription=a;b\r\n";
        let ini = IniFile::parse(text).unwrap();
        assert_eq!(ini.sections().len(), 2);
        let s = ini.section("1000").unwrap();
        assert_eq!(s.line, 5);
        assert_eq!(s.get("PARAMETERNAME"), Some("Device type"));
        assert_eq!(s.get("defaultvalue"), Some("0x00020192"));
        assert_eq!(s.get("Description"), Some("a;b"));
        assert_eq!(s.entry("DefaultValue").unwrap().line, 7);
        assert_eq!(s.get("missing"), None);
    }

    #[test]
    fn errors_name_line_section_key() {
        // (text, line, section, key, kind)
        type Case = (
            &'static str,
            usize,
            Option<&'static str>,
            Option<&'static str>,
            IniErrorKind,
        );
        let cases: &[Case] = &[
            ("[1000\n", 1, None, None, IniErrorKind::UnclosedSection),
            ("[1000] x\n", 1, None, None, IniErrorKind::TextAfterSection),
            (
                "[1000]\nno equals\n",
                2,
                Some("1000"),
                None,
                IniErrorKind::ExpectedKeyValue,
            ),
            ("a=b\n", 1, None, None, IniErrorKind::KeyOutsideSection),
            ("[]\n", 1, None, None, IniErrorKind::EmptyName),
            (
                "[1000]\n=5\n",
                2,
                Some("1000"),
                None,
                IniErrorKind::EmptyName,
            ),
            (
                "[1000]\n[1001]\n[1000]\n",
                3,
                Some("1000"),
                None,
                IniErrorKind::DuplicateSection { first_line: 1 },
            ),
            (
                "[1000]\nDataType=7\ndatatype=5\n",
                3,
                Some("1000"),
                Some("datatype"),
                IniErrorKind::DuplicateKey { first_line: 2 },
            ),
        ];
        for &(text, line, section, key, kind) in cases {
            let e = IniFile::parse(text).unwrap_err();
            assert_eq!(e.line, line, "{text:?}");
            assert_eq!(e.section.as_deref(), section, "{text:?}");
            assert_eq!(e.key.as_deref(), key, "{text:?}");
            assert_eq!(e.kind, kind, "{text:?}");
        }
    }
}
