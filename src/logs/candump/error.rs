//! Building the crate's syntax errors for a candump line.

use crate::logs::lex::syntax;
use crate::logs::FormatError;
use crate::logs::{LogFormat, SyntaxError};

/// The error at 0-based `index` of `line`.
#[cold]
#[inline(never)]
pub(super) fn error(index: usize, reason: SyntaxError) -> FormatError {
    syntax(LogFormat::Candump, index.saturating_add(1), reason)
}
