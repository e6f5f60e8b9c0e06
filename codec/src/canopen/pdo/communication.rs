//! The communication parameter of a PDO, objects 1400h–15FFh (RPDO) and
//! 1800h–19FFh (TPDO): its COB-ID, transmission type, inhibit time and
//! event timer (CiA 301 §7.5.2.35, §7.5.2.37; docs/canopen.md#pdo-mappings).

use core::fmt;
use core::time::Duration;

use crate::can::CanId;

/// The COB-ID of a PDO, sub-index 1 of its communication parameter
/// (CiA 301 §7.5.2.35, §7.5.2.37, "COB-ID used by PDO";
/// docs/canopen.md#pdo-mappings): bit 31 set = the PDO is not valid, bit 30 set
/// = no RTR is allowed on it, bit 29 set = a 29-bit identifier. Every bit of
/// the 32 survives a round trip.
///
/// ```
/// use motionwire_codec::canopen::PdoCobId;
///
/// let cob_id = PdoCobId::from_u32(0x4000_0185);
/// assert!(cob_id.is_valid());
/// assert!(!cob_id.rtr_allowed());
/// assert!(!cob_id.is_extended());
/// assert_eq!(cob_id.can_id().map(|id| id.raw()), Some(0x185));
/// assert!(!PdoCobId::from_u32(0x8000_0185).is_valid());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PdoCobId(u32);

impl PdoCobId {
    /// Bit 31: the PDO does not exist / is not valid.
    pub const NOT_VALID: u32 = 1 << 31;
    /// Bit 30: no RTR is allowed on this PDO.
    pub const NO_RTR: u32 = 1 << 30;
    /// Bit 29: the identifier has 29 bits (CAN extended frame).
    pub const EXTENDED: u32 = 1 << 29;

    /// Return the COB-ID held by the object value `raw`.
    #[must_use]
    pub const fn from_u32(raw: u32) -> Self {
        PdoCobId(raw)
    }

    /// Return the COB-ID of a valid PDO on `id` with RTR `rtr_allowed`.
    #[must_use]
    pub const fn new(id: CanId, rtr_allowed: bool) -> Self {
        let mut raw = id.raw();
        if id.is_extended() {
            raw |= Self::EXTENDED;
        }
        if !rtr_allowed {
            raw |= Self::NO_RTR;
        }
        PdoCobId(raw)
    }

    /// Return the object value, every bit as it was.
    #[must_use]
    pub const fn to_u32(self) -> u32 {
        self.0
    }

    /// Return whether bit 31 is clear: the PDO exists and is valid.
    #[must_use]
    pub const fn is_valid(self) -> bool {
        self.0 & Self::NOT_VALID == 0
    }

    /// Return whether bit 30 is clear: RTR is allowed on the PDO.
    #[must_use]
    pub const fn rtr_allowed(self) -> bool {
        self.0 & Self::NO_RTR == 0
    }

    /// Return whether bit 29 is set: the identifier has 29 bits.
    #[must_use]
    pub const fn is_extended(self) -> bool {
        self.0 & Self::EXTENDED != 0
    }

    /// Return the identifier: bits 0–10, or bits 0–28 when bit 29 is set.
    /// With bit 29 clear, bits 11–28 should be 0 (CiA 301); they are ignored
    /// here and kept by [`PdoCobId::to_u32`]. `None` never occurs for the
    /// masked bits but keeps the signature honest about [`CanId`]'s checks.
    #[must_use]
    pub const fn can_id(self) -> Option<CanId> {
        if self.is_extended() {
            CanId::extended(self.0 & 0x1FFF_FFFF)
        } else {
            CanId::standard(self.0 & 0x7FF)
        }
    }
}

impl From<u32> for PdoCobId {
    fn from(raw: u32) -> Self {
        PdoCobId::from_u32(raw)
    }
}

impl From<PdoCobId> for u32 {
    fn from(cob_id: PdoCobId) -> u32 {
        cob_id.to_u32()
    }
}

/// What a [`TransmissionType`] says about when the PDO is sent
/// (CiA 301 §7.5.2.35, §7.5.2.37, "transmission type";
/// docs/canopen.md#pdo-mappings).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum TransmissionKind {
    /// 0: synchronous, acyclic (after a SYNC, when the data changed / an
    /// event occurred).
    SynchronousAcyclic,
    /// 1–240: synchronous, cyclic, every n-th SYNC.
    SynchronousCyclic,
    /// 241–251: reserved.
    Reserved,
    /// 252: RTR only, synchronous (sampled at SYNC, sent on request).
    RtrSynchronous,
    /// 253: RTR only, event-driven (sent on request).
    RtrEventDriven,
    /// 254: event-driven, manufacturer-specific events.
    EventDrivenManufacturer,
    /// 255: event-driven, device-profile / application-profile events.
    EventDrivenProfile,
}

impl TransmissionKind {
    /// Return the kind's name in lower-case words, e.g. `"synchronous_cyclic"`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            TransmissionKind::SynchronousAcyclic => "synchronous_acyclic",
            TransmissionKind::SynchronousCyclic => "synchronous_cyclic",
            TransmissionKind::Reserved => "reserved",
            TransmissionKind::RtrSynchronous => "rtr_synchronous",
            TransmissionKind::RtrEventDriven => "rtr_event_driven",
            TransmissionKind::EventDrivenManufacturer => "event_driven_manufacturer",
            TransmissionKind::EventDrivenProfile => "event_driven_profile",
        }
    }
}

impl fmt::Display for TransmissionKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The transmission type of a PDO, sub-index 2 of its communication
/// parameter (CiA 301 §7.5.2.35, §7.5.2.37; docs/canopen.md#pdo-mappings).
/// Every byte is a transmission type; [`TransmissionType::kind`] says what it
/// means.
///
/// ```
/// use motionwire_codec::canopen::{TransmissionKind, TransmissionType};
///
/// let every_4th_sync = TransmissionType::from_byte(4);
/// assert_eq!(every_4th_sync.kind(), TransmissionKind::SynchronousCyclic);
/// assert_eq!(every_4th_sync.sync_interval(), Some(4));
/// assert_eq!(TransmissionType::from_byte(255).kind(), TransmissionKind::EventDrivenProfile);
/// assert_eq!(TransmissionType::from_byte(241).kind(), TransmissionKind::Reserved);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TransmissionType(u8);

impl TransmissionType {
    /// 0: synchronous, acyclic.
    pub const SYNCHRONOUS_ACYCLIC: TransmissionType = TransmissionType(0);
    /// 254: event-driven, manufacturer-specific.
    pub const EVENT_DRIVEN_MANUFACTURER: TransmissionType = TransmissionType(254);
    /// 255: event-driven, device profile.
    pub const EVENT_DRIVEN_PROFILE: TransmissionType = TransmissionType(255);

    /// Return the transmission type of the object value `byte`.
    #[must_use]
    pub const fn from_byte(byte: u8) -> Self {
        TransmissionType(byte)
    }

    /// Return the object value.
    #[must_use]
    pub const fn to_byte(self) -> u8 {
        self.0
    }

    /// Return what the type means.
    #[must_use]
    pub const fn kind(self) -> TransmissionKind {
        match self.0 {
            0 => TransmissionKind::SynchronousAcyclic,
            1..=240 => TransmissionKind::SynchronousCyclic,
            241..=251 => TransmissionKind::Reserved,
            252 => TransmissionKind::RtrSynchronous,
            253 => TransmissionKind::RtrEventDriven,
            254 => TransmissionKind::EventDrivenManufacturer,
            255 => TransmissionKind::EventDrivenProfile,
        }
    }

    /// Return n for a synchronous cyclic type (sent every n-th SYNC,
    /// 1..=240), else `None`.
    #[must_use]
    pub const fn sync_interval(self) -> Option<u8> {
        match self.0 {
            1..=240 => Some(self.0),
            _ => None,
        }
    }

    /// Return whether the PDO is tied to SYNC (0–240 and 252).
    #[must_use]
    pub const fn is_synchronous(self) -> bool {
        matches!(self.0, 0..=240 | 252)
    }
}

impl From<u8> for TransmissionType {
    fn from(byte: u8) -> Self {
        TransmissionType::from_byte(byte)
    }
}

impl From<TransmissionType> for u8 {
    fn from(transmission_type: TransmissionType) -> u8 {
        transmission_type.to_byte()
    }
}

/// The inhibit time of a PDO, sub-index 3 of its communication parameter:
/// the least time between two transmissions, in multiples of 100 µs
/// (CiA 301 §7.5.2.35; docs/canopen.md#pdo-mappings).
///
/// ```
/// use core::time::Duration;
/// use motionwire_codec::canopen::InhibitTime;
///
/// assert_eq!(InhibitTime::from_raw(25).duration(), Duration::from_micros(2_500));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct InhibitTime(u16);

impl InhibitTime {
    /// Return the inhibit time of the object value `raw` (× 100 µs).
    #[must_use]
    pub const fn from_raw(raw: u16) -> Self {
        InhibitTime(raw)
    }

    /// Return the object value, in units of 100 µs.
    #[must_use]
    pub const fn raw(self) -> u16 {
        self.0
    }

    /// Return the time.
    #[must_use]
    pub const fn duration(self) -> Duration {
        Duration::from_micros(self.0 as u64 * 100)
    }
}

/// The event timer of a PDO, sub-index 5 of its communication parameter:
/// for a TPDO the period of event-driven transmission, for an RPDO the
/// deadline after which a missing PDO is an error; in milliseconds, 0 =
/// not used (CiA 301 §7.5.2.35; docs/canopen.md#pdo-mappings).
///
/// ```
/// use core::time::Duration;
/// use motionwire_codec::canopen::EventTimer;
///
/// assert_eq!(EventTimer::from_raw(10).duration(), Some(Duration::from_millis(10)));
/// assert_eq!(EventTimer::from_raw(0).duration(), None);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct EventTimer(u16);

impl EventTimer {
    /// Return the event timer of the object value `raw` (ms).
    #[must_use]
    pub const fn from_raw(raw: u16) -> Self {
        EventTimer(raw)
    }

    /// Return the object value in milliseconds.
    #[must_use]
    pub const fn raw(self) -> u16 {
        self.0
    }

    /// Return the period, or `None` when the value is 0 (not used).
    #[must_use]
    pub const fn duration(self) -> Option<Duration> {
        if self.0 == 0 {
            None
        } else {
            Some(Duration::from_millis(self.0 as u64))
        }
    }
}

/// The communication parameter of a PDO, objects 1400h–15FFh (RPDO) and
/// 1800h–19FFh (TPDO) (CiA 301 §7.5.2.35, §7.5.2.37;
/// docs/canopen.md#pdo-mappings). The optional sub-indices are `None` where the
/// device or the file gives none.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PdoCommunication {
    /// Sub-index 1: COB-ID.
    pub cob_id: PdoCobId,
    /// Sub-index 2: transmission type.
    pub transmission_type: Option<TransmissionType>,
    /// Sub-index 3: inhibit time.
    pub inhibit_time: Option<InhibitTime>,
    /// Sub-index 5: event timer.
    pub event_timer: Option<EventTimer>,
    /// Sub-index 6: SYNC start value (TPDO only; 0 = not used).
    pub sync_start: Option<u8>,
}

impl PdoCommunication {
    /// Return the communication parameter with COB-ID `cob_id` and no other
    /// sub-index.
    #[must_use]
    pub const fn new(cob_id: PdoCobId) -> Self {
        PdoCommunication {
            cob_id,
            transmission_type: None,
            inhibit_time: None,
            event_timer: None,
            sync_start: None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cob_id_bits() {
        // CiA 301 Table 71: bit 31 valid, bit 30 RTR, bit 29 frame.
        let table: &[(u32, bool, bool, bool, u32)] = &[
            (0x0000_0181, true, true, false, 0x181),
            (0x8000_0181, false, true, false, 0x181),
            (0x4000_0281, true, false, false, 0x281),
            (0xC000_0381, false, false, false, 0x381),
            (0x2012_3456, true, true, true, 0x0012_3456),
            (0x0000_F981, true, true, false, 0x181), // bits 11–28 ignored for 11-bit
        ];
        for &(raw, valid, rtr, extended, id) in table {
            let cob_id = PdoCobId::from_u32(raw);
            assert_eq!(cob_id.is_valid(), valid, "{raw:#x}");
            assert_eq!(cob_id.rtr_allowed(), rtr, "{raw:#x}");
            assert_eq!(cob_id.is_extended(), extended, "{raw:#x}");
            assert_eq!(cob_id.can_id().map(CanId::raw), Some(id), "{raw:#x}");
            assert_eq!(u32::from(cob_id), raw);
        }
        let id = CanId::standard(0x185).unwrap();
        assert_eq!(PdoCobId::new(id, true).to_u32(), 0x185);
        assert_eq!(PdoCobId::new(id, false).to_u32(), 0x4000_0185);
        let ext = CanId::extended(0x1ABC_DEF0).unwrap();
        assert_eq!(PdoCobId::new(ext, true).to_u32(), 0x3ABC_DEF0);
    }

    #[test]
    fn transmission_types() {
        use TransmissionKind::*;
        let table: &[(u8, TransmissionKind, Option<u8>, bool)] = &[
            (0, SynchronousAcyclic, None, true),
            (1, SynchronousCyclic, Some(1), true),
            (240, SynchronousCyclic, Some(240), true),
            (241, Reserved, None, false),
            (251, Reserved, None, false),
            (252, RtrSynchronous, None, true),
            (253, RtrEventDriven, None, false),
            (254, EventDrivenManufacturer, None, false),
            (255, EventDrivenProfile, None, false),
        ];
        for &(byte, kind, interval, sync) in table {
            let t = TransmissionType::from_byte(byte);
            assert_eq!(t.kind(), kind, "{byte}");
            assert_eq!(t.sync_interval(), interval, "{byte}");
            assert_eq!(t.is_synchronous(), sync, "{byte}");
            assert_eq!(u8::from(t), byte);
        }
        assert_eq!(EventDrivenProfile.to_string(), "event_driven_profile");
    }

    #[test]
    fn times_are_durations() {
        assert_eq!(InhibitTime::from_raw(0).duration(), Duration::ZERO);
        assert_eq!(
            InhibitTime::from_raw(u16::MAX).duration(),
            Duration::from_micros(6_553_500)
        );
        assert_eq!(EventTimer::from_raw(0).duration(), None);
        assert_eq!(
            EventTimer::from_raw(500).duration(),
            Some(Duration::from_millis(500))
        );
    }
}
