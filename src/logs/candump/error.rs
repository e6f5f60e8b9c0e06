//! Building the crate's syntax errors for a candump line.

use crate::logs::lex::syntax;
use crate::logs::{LogFormat, SyntaxError};
use crate::Error;

/// The error at 0-based `index` of `line`.
#[cold]
#[inline(never)]
pub(super) fn error(index: usize, reason: SyntaxError) -> Error {
    syntax(LogFormat::Candump, index.saturating_add(1), reason)
}
