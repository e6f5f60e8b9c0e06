//! The EMCY a summary points at: [`EmcySeen`], and what its node's profile
//! reads in it: [`ProfileReading`].

use core::fmt;

use crate::can::Timestamp;
use crate::canopen::{Emcy, ErrorCode, ErrorRegister};
use crate::profiles::akd::AkdManufacturerField;
use crate::profiles::baumer::BaumerEmcy;
use crate::profiles::Profile;

/// An EMCY the summary points at: where it was seen, its code, its error
/// register and manufacturer bytes (`first_error` in docs/summary.md#emcy,
/// `active_error`; the JSON keeps the line, time and code).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct EmcySeen {
    /// The line (or record number) it was read on.
    pub line: u64,
    /// Its time, where the log has one.
    pub timestamp: Option<Timestamp>,
    /// Its error code.
    pub code: ErrorCode,
    /// Its error register (1001h).
    pub register: ErrorRegister,
    /// Its manufacturer-specific bytes 3–7, which a node's profile reads
    /// (docs/canopen.md#profiles).
    pub manufacturer: [u8; 5],
}

impl EmcySeen {
    /// Return the EMCY itself.
    #[must_use]
    pub fn emcy(&self) -> Emcy {
        Emcy::new(self.code, self.register, self.manufacturer)
    }

    /// Return what a node's `profile` reads in it
    /// ([`ProfileReading::of`], docs/summary.md#profiles).
    #[must_use]
    pub fn reading(&self, profile: Profile) -> ProfileReading {
        ProfileReading::of(&self.emcy(), profile)
    }
}

/// What a node's profile reads in an EMCY's manufacturer bytes, as the
/// findings, the verdict and the report say it (docs/summary.md#profiles):
/// an AKD's axis and feedback (docs/canopen.md#akd), a Baumer encoder's
/// diagnostic sources and whether its table makes them a warning or an
/// error (docs/canopen.md#baumer).
///
/// `Display` writes the words that follow the EMCY's description in a
/// sentence: ` on axis 1, feedback 2`, ` (source: Battery monitoring
/// warning, a warning)`; nothing for a generic node.
///
/// ```
/// use motionwire::canopen::{Emcy, ErrorCode, ErrorRegister};
/// use motionwire::profiles::Profile;
/// use motionwire::summary::ProfileReading;
///
/// let sensor = Emcy::new(ErrorCode::new(0x7305), ErrorRegister::GENERIC, [0x21, 0, 0, 0, 0]);
/// assert_eq!(ProfileReading::of(&sensor, Profile::Akd).to_string(), " on axis 1, feedback 2");
/// let battery = Emcy::new(ErrorCode::new(0xFF00), ErrorRegister::empty(), [0, 0, 0x10, 0, 0]);
/// assert_eq!(
///     ProfileReading::of(&battery, Profile::Baumer).to_string(),
///     " (source: Battery monitoring warning, a warning)"
/// );
/// assert_eq!(ProfileReading::of(&battery, Profile::Generic).to_string(), "");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum ProfileReading {
    /// A generic node: its profile reads nothing.
    Generic,
    /// A Kollmorgen AKD (docs/canopen.md#akd).
    Akd {
        /// The axis, when the drive gives one.
        axis: Option<u8>,
        /// The feedback the error is on, when it names one.
        feedback: Option<u8>,
    },
    /// A Baumer EAM580 encoder: the EMCY as its table reads it
    /// (docs/canopen.md#baumer).
    Baumer(BaumerEmcy),
}

impl ProfileReading {
    /// Return what `profile` reads in `emcy`.
    #[must_use]
    pub fn of(emcy: &Emcy, profile: Profile) -> ProfileReading {
        match profile {
            Profile::Generic => ProfileReading::Generic,
            Profile::Akd => {
                let field = AkdManufacturerField::new_unchecked(&emcy.manufacturer[..]);
                let axis = field.axis_id();
                ProfileReading::Akd {
                    axis: axis.is_given().then(|| axis.get()),
                    feedback: field.feedback_id().ok().and_then(|fb| fb.number()),
                }
            }
            Profile::Baumer => ProfileReading::Baumer(BaumerEmcy::from_emcy(emcy)),
        }
    }
}

impl fmt::Display for ProfileReading {
    /// ` on axis 1, feedback 2` (AKD); ` (source: Temperature monitoring,
    /// an error)`, ` (sources: A, B, a warning)` (Baumer: the class is the
    /// table's, [`BaumerEmcy::is_warning`]); nothing where the profile
    /// reads nothing, nor for a Baumer reset.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            ProfileReading::Generic => Ok(()),
            ProfileReading::Akd { axis, feedback } => match (axis, feedback) {
                (Some(axis), Some(fb)) => write!(f, " on axis {axis}, feedback {fb}"),
                (None, Some(fb)) => write!(f, " on feedback {fb}"),
                (Some(axis), None) => write!(f, " on axis {axis}"),
                (None, None) => Ok(()),
            },
            ProfileReading::Baumer(emcy) => {
                let mut names: Vec<&str> = emcy.sources().map(|s| s.source()).collect();
                names.dedup();
                if names.is_empty() || emcy.code.is_reset() {
                    return Ok(());
                }
                let plural = if names.len() == 1 { "" } else { "s" };
                let class = if emcy.is_warning() {
                    "a warning"
                } else {
                    "an error"
                };
                write!(f, " (source{plural}: {}, {class})", names.join(", "))
            }
        }
    }
}
