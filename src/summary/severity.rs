//! How bad a finding is: [`Severity`] (docs/summary.md#severity), and
//! an EMCY's from its error register and its node's profile.

use core::fmt;

use crate::canopen::Emcy;
use crate::profiles::baumer::BaumerEmcy;
use crate::profiles::Profile;

/// How bad a finding is (docs/summary.md#severity), the worst first:
/// `Fault < Error < Warning < Notice`.
///
/// ```
/// use motionwire::canopen::{Emcy, ErrorCode, ErrorRegister};
/// use motionwire::profiles::Profile;
/// use motionwire::summary::Severity;
///
/// let battery = Emcy::new(ErrorCode::new(0xFF00), ErrorRegister::empty(), [0, 0, 0x10, 0, 0]);
/// assert_eq!(Severity::of_emcy(&battery, Profile::Baumer), Severity::Warning);
/// let sensor = Emcy::new(ErrorCode::new(0x7305), ErrorRegister::GENERIC, [0x21, 0, 0, 0, 0]);
/// assert_eq!(Severity::of_emcy(&sensor, Profile::Akd), Severity::Error);
/// assert!(Severity::Fault < Severity::Error);
/// assert_eq!(Severity::Warning.to_string(), "warning");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Severity {
    /// A device stopped doing its job: a CiA 402 drive entered a fault
    /// state (CiA 402), a controller went bus-off (ISO 11898-1).
    Fault,
    /// A device reports an error (an EMCY whose error register is set,
    /// CiA 301), or was lost (a heartbeat timeout, CiA 301's heartbeat
    /// event).
    Error,
    /// Something went wrong and did not stop anything: an EMCY that reports
    /// no error present, or that the device's profile calls a warning; a
    /// restart; a guarding toggle error; a broken or unanswered SDO
    /// transfer; error-passive.
    Warning,
    /// Worth knowing: an SDO abort (a server refusing a request is part of
    /// the protocol).
    Notice,
}

impl Severity {
    /// Return the name JSON writes: `fault`, `error`, `warning`, `notice`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Severity::Fault => "fault",
            Severity::Error => "error",
            Severity::Warning => "warning",
            Severity::Notice => "notice",
        }
    }

    /// Return whether it is a fault or an error: what a first cause can be.
    #[must_use]
    pub const fn is_fault_or_error(self) -> bool {
        matches!(self, Severity::Fault | Severity::Error)
    }

    /// Return the severity of an EMCY of a node read with `profile`
    /// (docs/summary.md#severity): a reset is a notice; an EMCY the
    /// profile's own table calls a warning (a Baumer diagnostic source
    /// signalled in 6505h only, [`BaumerEmcy::is_warning`]) or that
    /// reports no error present (error register 0,
    /// [`Emcy::reports_no_error`]) is a warning; any other is an error.
    #[must_use]
    pub fn of_emcy(emcy: &Emcy, profile: Profile) -> Severity {
        if emcy.is_reset() {
            return Severity::Notice;
        }
        if profile == Profile::Baumer && BaumerEmcy::from_emcy(emcy).is_warning() {
            return Severity::Warning;
        }
        if emcy.reports_no_error() {
            return Severity::Warning;
        }
        Severity::Error
    }
}

impl fmt::Display for Severity {
    /// The [`name`](Self::name).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}
