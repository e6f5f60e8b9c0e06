//! The pre-defined error field, object 1003h (CiA 301 §7.5.2.3;
//! docs/canopen.md#error-history; the Kollmorgen AKD CANopen manual: "The
//! last 10 Emergency error codes can be read using object 1003").
//!
//! [`ErrorHistory`] holds the last `N` errors a device reported (N = 10 on the
//! AKD, the default). Sub-index 0 is the number of entries; sub-index 1 the
//! newest. Each entry is a `u32`: bits 0–15 the error code, bits 16–31
//! manufacturer-specific additional information ([`ErrorHistoryEntry`]).
//! [`ErrorHistory::read`] and [`ErrorHistory::write`] answer SDO accesses
//! with the value or the [`SdoAbortCode`] CiA 301 prescribes.
//!
//! The **Decision**s taken where CiA 301 leaves a choice
//! (docs/canopen.md#error-history), and an example, are on [`ErrorHistory`].

use byteorder::{ByteOrder, LittleEndian};

use super::{Emcy, EmcyOutcome, ErrorCode, SdoAbortCode};

/// The default capacity of an [`ErrorHistory`], 10 entries as on the AKD
/// (the AKD CANopen manual; docs/canopen.md#error-history).
pub const DEFAULT_ERROR_HISTORY_LEN: usize = 10;

/// One entry of the pre-defined error field 1003h (CiA 301 §7.5.2.3;
/// docs/canopen.md#error-history): the error code in bits 0–15 and
/// manufacturer-specific additional information in bits 16–31.
///
/// ```
/// use motionwire_codec::canopen::{ErrorCode, ErrorHistoryEntry};
///
/// let entry = ErrorHistoryEntry::from_u32(0x0001_4210);
/// assert_eq!(entry.code, ErrorCode::new(0x4210));
/// assert_eq!(entry.additional_info, 0x0001);
/// assert_eq!(entry.to_u32(), 0x0001_4210);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ErrorHistoryEntry {
    /// The emergency error code (bits 0–15).
    pub code: ErrorCode,
    /// Manufacturer-specific additional information (bits 16–31).
    pub additional_info: u16,
}

impl ErrorHistoryEntry {
    /// Return an entry with the given fields.
    #[must_use]
    pub const fn new(code: ErrorCode, additional_info: u16) -> Self {
        ErrorHistoryEntry {
            code,
            additional_info,
        }
    }

    /// Return the entry an EMCY makes: its code, and its manufacturer bytes
    /// 0–1 (frame bytes 3–4), little-endian, as the additional information
    /// (**Decision**, see [`ErrorHistory`]).
    #[must_use]
    pub fn from_emcy(emcy: &Emcy) -> Self {
        ErrorHistoryEntry::new(emcy.code, LittleEndian::read_u16(&emcy.manufacturer[..2]))
    }

    /// Decode the entry's `u32` value.
    #[must_use]
    pub const fn from_u32(value: u32) -> Self {
        ErrorHistoryEntry {
            code: ErrorCode::new(value as u16),
            additional_info: (value >> 16) as u16,
        }
    }

    /// Encode the entry as the `u32` value an SDO read returns.
    #[must_use]
    pub const fn to_u32(self) -> u32 {
        (self.additional_info as u32) << 16 | self.code.get() as u32
    }
}

impl From<u32> for ErrorHistoryEntry {
    fn from(value: u32) -> Self {
        Self::from_u32(value)
    }
}

impl From<ErrorHistoryEntry> for u32 {
    fn from(entry: ErrorHistoryEntry) -> u32 {
        entry.to_u32()
    }
}

/// The pre-defined error field, object 1003h, holding the last `N` errors
/// (CiA 301 §7.5.2.3; docs/canopen.md#error-history).
///
/// Sub-index 0 is the number of entries, sub-index 1 the newest; a new error
/// shifts the older ones down and the oldest falls off when full; reset
/// EMCYs (0x00xx) are not recorded.
///
/// **Decisions** where CiA 301 leaves a choice (docs/canopen.md#error-history):
///
/// - [`ErrorHistory::record`] fills bits 16–31 from the EMCY's
///   manufacturer-specific bytes 0–1 (frame bytes 3–4) read little-endian,
///   so an AKD entry carries the axis and feedback id in bits 16–23
///   (docs/canopen.md#akd).
/// - Sub-indices `count + 1 ..= N` exist but hold no data: reading one is
///   refused with [`SdoAbortCode::NO_DATA_AVAILABLE`]
///   (docs/canopen.md#error-history). Sub-indices above `N` do not exist in the
///   object dictionary: reading or writing one is refused with
///   [`SdoAbortCode::SUB_INDEX_DOES_NOT_EXIST`] (CiA 301 Table 22).
/// - Writing sub-indices 1..=N is refused with
///   [`SdoAbortCode::WRITE_OF_READ_ONLY`]: CiA 301 gives them read-only
///   access.
/// - `N` is 1..=254 (sub-indices 1..=FEh of CiA 301); another `N` fails to
///   compile when the history is created:
///
/// ```compile_fail
/// let history = motionwire_codec::canopen::ErrorHistory::<255>::with_capacity();
/// ```
///
/// ```
/// use motionwire_codec::canopen::{
///     EmcyEvent, EmcyProducer, ErrorCode, ErrorHistory, SdoAbortCode,
/// };
///
/// let mut producer = EmcyProducer::new();
/// let mut history = ErrorHistory::new();
///
/// for event in [
///     EmcyEvent::error(ErrorCode::new(0x4210), [0x01, 0, 0, 0, 0]),
///     EmcyEvent::error(ErrorCode::new(0x8110), [0; 5]),
///     EmcyEvent::reset(ErrorCode::new(0x4210)), // a reset EMCY: not recorded
/// ] {
///     history.record_outcome(&producer.apply(event));
/// }
///
/// assert_eq!(history.read(0), Ok(2));
/// assert_eq!(history.read(1), Ok(0x0000_8110)); // newest
/// assert_eq!(history.read(2), Ok(0x0001_4210)); // axis 1 in bits 16–23
/// assert_eq!(history.read(3), Err(SdoAbortCode::NO_DATA_AVAILABLE));
///
/// assert_eq!(history.write(0, 1), Err(SdoAbortCode::INVALID_VALUE));
/// assert_eq!(history.write(0, 0), Ok(()));
/// assert!(history.is_empty());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ErrorHistory<const N: usize = DEFAULT_ERROR_HISTORY_LEN> {
    /// Newest first in `entries[..count]`; every other slot is zero, so the
    /// derived `PartialEq` compares contents.
    entries: [ErrorHistoryEntry; N],
    /// Sub-index 0, `<= N`.
    count: u8,
}

impl<const N: usize> Default for ErrorHistory<N> {
    fn default() -> Self {
        Self::with_capacity()
    }
}

impl ErrorHistory {
    /// Return an empty history of [`DEFAULT_ERROR_HISTORY_LEN`] (10)
    /// entries — the Kollmorgen AKD's object 1003h holds 10 — written
    /// without naming a capacity, as `HashMap::new` is.
    ///
    /// ```
    /// use motionwire_codec::canopen::ErrorHistory;
    ///
    /// let history = ErrorHistory::new();
    /// assert_eq!(history.len(), 0);
    /// ```
    #[must_use]
    pub const fn new() -> Self {
        Self::with_capacity()
    }
}

impl<const N: usize> ErrorHistory<N> {
    /// The number of entries the history holds, `N`.
    pub const CAPACITY: usize = N;

    /// Fails the build for an `N` outside 1..=254 (CiA 301: sub-indices
    /// 1..=FEh).
    const VALID_CAPACITY: () = assert!(N >= 1 && N <= 254, "object 1003h holds 1..=254 entries");

    const EMPTY: ErrorHistoryEntry = ErrorHistoryEntry::new(ErrorCode::NO_ERROR, 0);

    /// Return an empty history of `N` entries (1..=254, checked when the
    /// program is built), e.g. `ErrorHistory::<5>::with_capacity()`.
    #[must_use]
    pub const fn with_capacity() -> Self {
        let () = Self::VALID_CAPACITY;
        ErrorHistory {
            entries: [Self::EMPTY; N],
            count: 0,
        }
    }

    /// Return the number of entries, the value of sub-index 0.
    #[must_use]
    pub const fn len(&self) -> usize {
        self.count as usize
    }

    /// Return whether the history holds no entry.
    #[must_use]
    pub const fn is_empty(&self) -> bool {
        self.count == 0
    }

    /// Return the newest entry, sub-index 1.
    #[must_use]
    pub fn newest(&self) -> Option<ErrorHistoryEntry> {
        self.stored().first().copied()
    }

    /// Return the entry at `sub_index` (1 = newest), or `None` when it holds
    /// no entry.
    #[must_use]
    pub fn entry(&self, sub_index: u8) -> Option<ErrorHistoryEntry> {
        let position = usize::from(sub_index).checked_sub(1)?;
        self.stored().get(position).copied()
    }

    /// Return the entries, newest first.
    #[must_use]
    pub fn iter(
        &self,
    ) -> impl DoubleEndedIterator<Item = ErrorHistoryEntry> + ExactSizeIterator + '_ {
        self.stored().iter().copied()
    }

    /// Add an entry as the newest; the older ones shift down and the oldest
    /// falls off when the history is full. A reset code (0x00xx) is not an
    /// error and is not recorded (docs/canopen.md#error-history): return
    /// whether it was.
    pub fn push(&mut self, entry: ErrorHistoryEntry) -> bool {
        if entry.code.is_reset() {
            return false;
        }
        self.entries.rotate_right(1);
        if let Some(newest) = self.entries.first_mut() {
            *newest = entry;
        }
        if self.len() < N {
            self.count += 1;
        }
        true
    }

    /// Record an EMCY that was sent: its code and, as additional
    /// information, its manufacturer bytes 0–1 (**Decision**, see
    /// [`ErrorHistory`]). Reset EMCYs are not recorded
    /// (docs/canopen.md#error-history); return whether it was.
    pub fn record(&mut self, emcy: &Emcy) -> bool {
        self.push(ErrorHistoryEntry::from_emcy(emcy))
    }

    /// Record the EMCY of a state-machine step, if it sent an error EMCY
    /// (transitions 1 and 3); return whether one was recorded.
    pub fn record_outcome(&mut self, outcome: &EmcyOutcome) -> bool {
        match &outcome.emcy() {
            Some(emcy) => self.record(emcy),
            None => false,
        }
    }

    /// Remove every entry (what writing 0 to sub-index 0 does).
    pub fn clear(&mut self) {
        *self = Self::with_capacity();
    }

    /// Answer an SDO read (upload) of sub-index `sub_index`: sub-index 0 the
    /// count, 1..=count the entries newest first (CiA 301 §7.5.2.3;
    /// docs/canopen.md#error-history).
    ///
    /// # Errors
    ///
    /// [`SdoAbortCode::NO_DATA_AVAILABLE`] for a sub-index in `count + 1 ..=
    /// N`; [`SdoAbortCode::SUB_INDEX_DOES_NOT_EXIST`] above `N`.
    pub fn read(&self, sub_index: u8) -> Result<u32, SdoAbortCode> {
        if sub_index == 0 {
            return Ok(u32::from(self.count));
        }
        if usize::from(sub_index) > N {
            return Err(SdoAbortCode::SUB_INDEX_DOES_NOT_EXIST);
        }
        self.entry(sub_index)
            .map(ErrorHistoryEntry::to_u32)
            .ok_or(SdoAbortCode::NO_DATA_AVAILABLE)
    }

    /// Answer an SDO write (download) of `value` to sub-index `sub_index`:
    /// writing 0 to sub-index 0 clears the history (CiA 301 §7.5.2.3;
    /// docs/canopen.md#error-history).
    ///
    /// # Errors
    ///
    /// [`SdoAbortCode::INVALID_VALUE`] for any other value written to
    /// sub-index 0; [`SdoAbortCode::WRITE_OF_READ_ONLY`] for sub-indices
    /// 1..=N; [`SdoAbortCode::SUB_INDEX_DOES_NOT_EXIST`] above `N`. A refused
    /// write changes nothing.
    pub fn write(&mut self, sub_index: u8, value: u32) -> Result<(), SdoAbortCode> {
        match (sub_index, value) {
            (0, 0) => {
                self.clear();
                Ok(())
            }
            (0, _) => Err(SdoAbortCode::INVALID_VALUE),
            _ if usize::from(sub_index) > N => Err(SdoAbortCode::SUB_INDEX_DOES_NOT_EXIST),
            _ => Err(SdoAbortCode::WRITE_OF_READ_ONLY),
        }
    }

    /// The stored entries, `entries[..count]`, newest first.
    fn stored(&self) -> &[ErrorHistoryEntry] {
        self.entries.get(..self.len()).unwrap_or(&[])
    }
}

impl<'a, const N: usize> IntoIterator for &'a ErrorHistory<N> {
    type Item = ErrorHistoryEntry;
    type IntoIter = core::iter::Copied<core::slice::Iter<'a, ErrorHistoryEntry>>;

    /// Iterate over the entries, newest first.
    fn into_iter(self) -> Self::IntoIter {
        self.stored().iter().copied()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::canopen::{EmcyEvent, EmcyProducer, ErrorRegister};

    fn entry(code: u16, info: u16) -> ErrorHistoryEntry {
        ErrorHistoryEntry::new(ErrorCode::new(code), info)
    }

    /// A history holding `codes`, pushed oldest first.
    fn history_of<const N: usize>(codes: &[u16]) -> ErrorHistory<N> {
        let mut history = ErrorHistory::<N>::with_capacity();
        for &code in codes {
            assert!(history.push(entry(code, 0)));
        }
        history
    }

    #[test]
    fn reads_answer_count_entries_or_abort() {
        // 0x2310 then 0x3210 then 0x4210 (with additional info 0x0201).
        let mut history: ErrorHistory = history_of(&[0x2310, 0x3210]);
        assert!(history.push(entry(0x4210, 0x0201)));
        let table: [(u8, Result<u32, SdoAbortCode>); 8] = [
            (0, Ok(3)),
            (1, Ok(0x0201_4210)),
            (2, Ok(0x0000_3210)),
            (3, Ok(0x0000_2310)),
            (4, Err(SdoAbortCode::NO_DATA_AVAILABLE)),
            (10, Err(SdoAbortCode::NO_DATA_AVAILABLE)),
            (11, Err(SdoAbortCode::SUB_INDEX_DOES_NOT_EXIST)),
            (255, Err(SdoAbortCode::SUB_INDEX_DOES_NOT_EXIST)),
        ];
        for (sub_index, expected) in table {
            assert_eq!(history.read(sub_index), expected, "sub-index {sub_index}");
        }
    }

    #[test]
    fn reads_of_an_empty_history() {
        let history = ErrorHistory::new();
        assert_eq!(history.read(0), Ok(0));
        for sub_index in 1..=10 {
            assert_eq!(
                history.read(sub_index),
                Err(SdoAbortCode::NO_DATA_AVAILABLE)
            );
        }
        assert_eq!(history.newest(), None);
        assert_eq!(history.iter().count(), 0);
    }

    #[test]
    fn writes_clear_or_abort() {
        // (sub-index, value, result, count afterwards) on a 3-entry history.
        let table: [(u8, u32, Result<(), SdoAbortCode>, u32); 9] = [
            (0, 1, Err(SdoAbortCode::INVALID_VALUE), 3),
            (0, 3, Err(SdoAbortCode::INVALID_VALUE), 3),
            (0, 0xFF, Err(SdoAbortCode::INVALID_VALUE), 3),
            (0, 0x0100, Err(SdoAbortCode::INVALID_VALUE), 3),
            (1, 0, Err(SdoAbortCode::WRITE_OF_READ_ONLY), 3),
            (3, 0x1000, Err(SdoAbortCode::WRITE_OF_READ_ONLY), 3),
            (10, 0, Err(SdoAbortCode::WRITE_OF_READ_ONLY), 3),
            (11, 0, Err(SdoAbortCode::SUB_INDEX_DOES_NOT_EXIST), 3),
            (0, 0, Ok(()), 0),
        ];
        for (sub_index, value, expected, count) in table {
            let mut history: ErrorHistory = history_of(&[0x2310, 0x3210, 0x4210]);
            let before = history;
            assert_eq!(
                history.write(sub_index, value),
                expected,
                "{sub_index}, {value:#x}"
            );
            assert_eq!(history.read(0), Ok(count));
            if expected.is_err() {
                assert_eq!(history, before, "a refused write changes nothing");
            }
        }
    }

    #[test]
    fn clearing_empties_every_sub_index() {
        let mut history: ErrorHistory = history_of(&[0x2310, 0x3210]);
        assert_eq!(history.write(0, 0), Ok(()));
        assert!(history.is_empty());
        assert_eq!(history.read(1), Err(SdoAbortCode::NO_DATA_AVAILABLE));
        assert_eq!(history, ErrorHistory::new());
        // A cleared history fills again from sub-index 1.
        history.push(entry(0x5000, 0));
        assert_eq!(history.read(1), Ok(0x5000));
    }

    #[test]
    fn a_new_error_shifts_older_ones_down_and_the_oldest_falls_off_n_10() {
        let codes: Vec<u16> = (1..=12).map(|n| 0x1000 + n).collect();
        let mut history = ErrorHistory::new();
        for (pushed, &code) in codes.iter().enumerate() {
            history.push(entry(code, 0));
            assert_eq!(history.read(0), Ok((pushed as u32 + 1).min(10)));
            assert_eq!(history.read(1), Ok(u32::from(code)));
        }
        // Newest 0x100C at sub-index 1 … 0x1003 at sub-index 10; 0x1001 and
        // 0x1002 fell off.
        let expected: Vec<u32> = (3..=12).rev().map(|n| 0x1000 + n).collect();
        let read: Vec<u32> = (1..=10).map(|s| history.read(s).unwrap()).collect();
        assert_eq!(read, expected);
        assert_eq!(
            history.read(11),
            Err(SdoAbortCode::SUB_INDEX_DOES_NOT_EXIST)
        );
    }

    #[test]
    fn a_new_error_shifts_older_ones_down_and_the_oldest_falls_off_n_3() {
        let steps: [(u16, [Option<u16>; 3]); 5] = [
            (0x2310, [Some(0x2310), None, None]),
            (0x3210, [Some(0x3210), Some(0x2310), None]),
            (0x4210, [Some(0x4210), Some(0x3210), Some(0x2310)]),
            (0x8110, [Some(0x8110), Some(0x4210), Some(0x3210)]),
            (0x2310, [Some(0x2310), Some(0x8110), Some(0x4210)]),
        ];
        let mut history = ErrorHistory::<3>::with_capacity();
        for (code, expected) in steps {
            history.push(entry(code, 0));
            for (sub_index, want) in (1..=3).zip(expected) {
                let want = want.map(u32::from).ok_or(SdoAbortCode::NO_DATA_AVAILABLE);
                assert_eq!(
                    history.read(sub_index),
                    want,
                    "after {code:#06x}, {sub_index}"
                );
            }
        }
        assert_eq!(history.read(4), Err(SdoAbortCode::SUB_INDEX_DOES_NOT_EXIST));
    }

    #[test]
    fn the_same_code_twice_is_two_entries() {
        let history: ErrorHistory = history_of(&[0x8110, 0x8110]);
        assert_eq!(history.read(0), Ok(2));
    }

    #[test]
    fn a_history_of_one() {
        let history: ErrorHistory<1> = history_of(&[0x2310, 0x3210]);
        assert_eq!(history.read(0), Ok(1));
        assert_eq!(history.read(1), Ok(0x3210));
        assert_eq!(history.read(2), Err(SdoAbortCode::SUB_INDEX_DOES_NOT_EXIST));
    }

    #[test]
    fn reset_emcys_are_not_recorded() {
        let mut history: ErrorHistory = history_of(&[0x4210]);
        for raw in [0x0000, 0x0001, 0x00FF] {
            let reset = Emcy::new(ErrorCode::new(raw), ErrorRegister::GENERIC, [7; 5]);
            assert!(!history.record(&reset));
            assert!(!history.push(entry(raw, 1)));
        }
        assert_eq!(history.read(0), Ok(1));
        assert_eq!(history.read(1), Ok(0x4210));
    }

    #[test]
    fn record_takes_additional_info_from_manufacturer_bytes_0_and_1() {
        let mut history = ErrorHistory::new();
        // AKD: axis 1, feedback 2 in byte 3 of the frame (docs/canopen.md#akd).
        let emcy = Emcy::new(
            ErrorCode::new(0x7305),
            ErrorRegister::GENERIC,
            [0x21, 0xAB, 1, 2, 3],
        );
        assert!(history.record(&emcy));
        assert_eq!(history.read(1), Ok(0xAB21_7305));
        assert_eq!(history.newest(), Some(entry(0x7305, 0xAB21)));
    }

    #[test]
    fn record_outcome_records_only_error_emcys() {
        let mut producer = EmcyProducer::new();
        let mut history = ErrorHistory::new();
        // (event, recorded?)
        let table = [
            (EmcyEvent::Initialised, false),
            (
                EmcyEvent::error(ErrorCode::new(0x4210), [1, 0, 0, 0, 0]),
                true,
            ),
            (
                EmcyEvent::error(ErrorCode::new(0x4210), [1, 0, 0, 0, 0]),
                false,
            ),
            (EmcyEvent::error(ErrorCode::new(0x3210), [0; 5]), true),
            (EmcyEvent::reset(ErrorCode::new(0x4210)), false),
            (EmcyEvent::AllErrorsReset, false),
            (EmcyEvent::error(ErrorCode::new(0x0000), [0; 5]), false),
        ];
        for (event, recorded) in table {
            let outcome = producer.apply(event);
            assert_eq!(history.record_outcome(&outcome), recorded, "{event:?}");
        }
        let entries: Vec<u32> = history.iter().map(u32::from).collect();
        assert_eq!(entries, [0x0000_3210, 0x0001_4210]);
    }

    #[test]
    fn iteration_is_newest_first() {
        let history = history_of::<4>(&[0x1001, 0x1002, 0x1003]);
        let codes: Vec<u16> = history.iter().map(|e| e.code.get()).collect();
        assert_eq!(codes, [0x1003, 0x1002, 0x1001]);
        let codes: Vec<u16> = (&history).into_iter().map(|e| e.code.get()).collect();
        assert_eq!(codes, [0x1003, 0x1002, 0x1001]);
        assert_eq!(history.iter().len(), 3);
        assert_eq!(history.entry(0), None);
        assert_eq!(history.entry(3), Some(entry(0x1001, 0)));
        assert_eq!(history.entry(4), None);
    }

    #[test]
    fn entry_u32_layout() {
        let table = [
            (0x0000_8110, 0x8110, 0x0000),
            (0x0001_4210, 0x4210, 0x0001),
            (0xFFFF_FF00, 0xFF00, 0xFFFF),
            (0x1234_5678, 0x5678, 0x1234),
        ];
        for (value, code, info) in table {
            assert_eq!(ErrorHistoryEntry::from_u32(value), entry(code, info));
            assert_eq!(entry(code, info).to_u32(), value);
        }
    }

    #[test]
    fn capacity() {
        assert_eq!(ErrorHistory::<DEFAULT_ERROR_HISTORY_LEN>::CAPACITY, 10);
        assert_eq!(ErrorHistory::<254>::CAPACITY, 254);
        let full = history_of::<254>(&[0x1000; 300]);
        assert_eq!(full.read(0), Ok(254));
        assert_eq!(full.read(254), Ok(0x1000));
        assert_eq!(full.read(255), Err(SdoAbortCode::SUB_INDEX_DOES_NOT_EXIST));
    }
}

#[cfg(test)]
mod proptests {
    use proptest::prelude::*;

    use super::*;
    use crate::canopen::EmcyProducer;
    use crate::strategies::emcy_producer::{emcy_events, produced_emcy};

    /// Record `emcys` in a history of `N` and check it against a plain list.
    fn check_records<const N: usize>(emcys: &[Emcy]) -> Result<(), TestCaseError> {
        let mut history = ErrorHistory::<N>::with_capacity();
        let mut model: Vec<u32> = Vec::new(); // newest first
        for (i, emcy) in emcys.iter().enumerate() {
            let recorded = history.record(emcy);
            prop_assert_eq!(recorded, !emcy.is_reset());
            if recorded {
                let info = u16::from_le_bytes([emcy.manufacturer[0], emcy.manufacturer[1]]);
                model.insert(0, u32::from(info) << 16 | u32::from(emcy.code.get()));
                model.truncate(N);
            }
            prop_assert!(history.len() <= N);
            prop_assert_eq!(history.read(0), Ok(model.len() as u32));
            // Sub-index 1 is always the newest non-reset code recorded.
            let newest = emcys[..=i].iter().rev().find(|e| !e.is_reset());
            match newest {
                Some(newest) => {
                    prop_assert_eq!(history.read(1).map(|v| v as u16), Ok(newest.code.get()))
                }
                None => prop_assert_eq!(history.read(1), Err(SdoAbortCode::NO_DATA_AVAILABLE)),
            }
            prop_assert_eq!(
                history.iter().map(u32::from).collect::<Vec<_>>(),
                model.clone()
            );
        }
        Ok(())
    }

    proptest! {
        #[test]
        fn records_match_a_list_n_10(emcys in proptest::collection::vec(produced_emcy(), 0..40)) {
            check_records::<10>(&emcys)?;
        }

        #[test]
        fn records_match_a_list_n_3(emcys in proptest::collection::vec(produced_emcy(), 0..20)) {
            check_records::<3>(&emcys)?;
        }

        #[test]
        fn any_access_answers_without_panic(
            emcys in proptest::collection::vec(produced_emcy(), 0..15),
            accesses in proptest::collection::vec((any::<u8>(), any::<u32>(), any::<bool>()), 0..20),
        ) {
            let mut history = ErrorHistory::<10>::with_capacity();
            for emcy in &emcys {
                history.record(emcy);
            }
            for (sub_index, value, is_write) in accesses {
                let count = history.len();
                if is_write {
                    let result = history.write(sub_index, value);
                    prop_assert_eq!(result.is_ok(), sub_index == 0 && value == 0);
                    prop_assert_eq!(history.len(), if result.is_ok() { 0 } else { count });
                } else {
                    let result = history.read(sub_index);
                    let sub = usize::from(sub_index);
                    match result {
                        Ok(_) => prop_assert!(sub <= count),
                        Err(abort) if sub > 10 => prop_assert_eq!(abort, SdoAbortCode::SUB_INDEX_DOES_NOT_EXIST),
                        Err(abort) => prop_assert_eq!(abort, SdoAbortCode::NO_DATA_AVAILABLE),
                    }
                }
            }
        }

        /// Fed from the state machine, sub-index 1 is the code of the last
        /// error EMCY sent.
        #[test]
        fn fed_by_the_state_machine(events in emcy_events(48)) {
            let mut producer = EmcyProducer::<4>::with_capacity();
            let mut history = ErrorHistory::<5>::with_capacity();
            let mut last_error = None;
            for event in events {
                let outcome = producer.apply(event);
                history.record_outcome(&outcome);
                if let Some(emcy) = outcome.emcy().filter(|e| !e.is_reset()) {
                    last_error = Some(u32::from(emcy.code.get()));
                }
                prop_assert_eq!(history.read(1).ok().map(|v| v & 0xFFFF), last_error);
            }
        }
    }
}
