//! Writing a register's set flags by name, the one way every `Display` of a
//! flag word does it.

use core::fmt;

/// Write `names` joined by `sep`; return whether any was written.
pub(crate) fn write_joined<'a>(
    f: &mut fmt::Formatter<'_>,
    names: impl IntoIterator<Item = &'a str>,
    sep: &str,
) -> Result<bool, fmt::Error> {
    let mut any = false;
    for name in names {
        if any {
            f.write_str(sep)?;
        }
        f.write_str(name)?;
        any = true;
    }
    Ok(any)
}

/// Write a flag word as `{hex} [name|name]`: the value, then the names of
/// its set flags (`Display` of the servo words and the error register).
pub(crate) fn write_word<'a>(
    f: &mut fmt::Formatter<'_>,
    hex: fmt::Arguments<'_>,
    names: impl IntoIterator<Item = &'a str>,
) -> fmt::Result {
    f.write_fmt(hex)?;
    f.write_str(" [")?;
    write_joined(f, names, "|")?;
    f.write_str("]")
}
