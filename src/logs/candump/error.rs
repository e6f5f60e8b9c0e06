//! Building the crate's syntax errors for a candump line.

use super::*;

/// The error at 0-based `index` of `line`.
#[cold]
#[inline(never)]
pub(super) fn error(index: usize, reason: SyntaxError) -> Error {
    Error::Syntax {
        format: LogFormat::Candump,
        column: index.saturating_add(1),
        reason,
    }
}

/// What stands at `index` of `line`.
#[inline]
pub(super) fn found(line: &[u8], index: usize) -> Found {
    match line.get(index) {
        Some(&b) => Found::Byte(b),
        None => Found::EndOfLine,
    }
}
