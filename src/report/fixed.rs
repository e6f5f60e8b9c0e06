//! Coordinates written with a fixed number of decimals from an integer:
//! the page has hundreds of thousands of them, and Rust's `{:.2}` formats
//! a float exactly (Grisu with a Dragon fallback), a large share of a
//! drives log's report (BENCHMARKS.md, "Coordinates written from
//! integers").

use core::fmt;

/// `x` with `D` decimals (1 to 3), rounded half away from zero: what
/// `{:.D$}` writes, but for an exact half of the last decimal, which
/// `{:.D$}` may round the other way; `-0.00` is written `0.00`.
#[derive(Debug, Clone, Copy)]
pub(super) struct Fixed<const D: usize>(pub(super) f64);

const POW10: [u64; 4] = [1, 10, 100, 1000];

impl<const D: usize> fmt::Display for Fixed<D> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let scale = POW10[D];
        let scaled = (self.0 * scale as f64).round();
        // Beyond 2^53 (and for NaN and the infinities) the float's own
        // formatting says it.
        if !scaled.is_finite() || scaled.abs() >= 9.0e15 {
            return write!(f, "{:.*}", D, self.0);
        }
        let negative = scaled < 0.0;
        let mut n = scaled.abs() as u64;
        let mut buf = [0u8; 24];
        let mut i = buf.len();
        for _ in 0..D {
            i -= 1;
            buf[i] = b'0' + (n % 10) as u8;
            n /= 10;
        }
        i -= 1;
        buf[i] = b'.';
        loop {
            i -= 1;
            buf[i] = b'0' + (n % 10) as u8;
            n /= 10;
            if n == 0 {
                break;
            }
        }
        if negative {
            i -= 1;
            buf[i] = b'-';
        }
        f.write_str(core::str::from_utf8(&buf[i..]).unwrap_or_default())
    }
}

#[cfg(test)]
mod tests {
    use super::Fixed;
    use proptest::prelude::*;

    fn check<const D: usize>(x: f64) -> Result<(), TestCaseError> {
        let ours = Fixed::<D>(x).to_string();
        let std = format!("{x:.D$}");
        let scaled = x * 10f64.powi(D as i32);
        let near_half = (scaled.abs().fract() - 0.5).abs() < 1e-6;
        if !near_half && std != format!("-{}", "0.".to_owned() + &"0".repeat(D)) {
            prop_assert_eq!(&ours, &std, "{} with {} decimals", x, D);
        }
        // Within half a last decimal, whatever the case.
        let back: f64 = ours.parse().unwrap();
        prop_assert!((back - x).abs() <= 0.5 / 10f64.powi(D as i32) + 1e-9 * x.abs().max(1.0));
        Ok(())
    }

    proptest! {
        /// On the page's coordinates (−10 000 to 1 000 000 pixels, any
        /// fraction) and on any float, `Fixed` writes what `{:.D$}` does but
        /// for an exact half.
        #[test]
        fn as_std_writes_it(x in prop_oneof![-1.0e4..1.0e6f64, -1.0e15..1.0e15f64, any::<f64>()]) {
            check::<1>(x)?;
            check::<2>(x)?;
            check::<3>(x)?;
        }
    }

    #[test]
    fn examples() {
        assert_eq!(Fixed::<2>(123.456).to_string(), "123.46");
        assert_eq!(Fixed::<2>(5.0).to_string(), "5.00");
        assert_eq!(Fixed::<1>(-0.04).to_string(), "0.0");
        assert_eq!(Fixed::<3>(-12.0005).to_string(), "-12.001");
        assert_eq!(Fixed::<2>(f64::NAN).to_string(), "NaN");
        assert_eq!(Fixed::<2>(1e300).to_string(), format!("{:.2}", 1e300));
    }
}
