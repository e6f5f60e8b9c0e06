//! Error frames as Linux reports them (`linux/can/error.h`; candump `-e`;
//! docs/formats.md#error-frames and the `error_frame` keys of
//! docs/output.md#error-frame).
//!
//! An error frame is a [`CanFrame`] of type [`FrameType::Error`]: its
//! identifier holds the error classes, its 8 data bytes their details.
//! [`ErrorFrame::from_frame`] reads them.
//!
//! ```
//! use motionwire_codec::can::{CanFrame, ControllerStatus, ErrorClasses, ErrorFrame};
//!
//! // candump -e: `20000004#0004000000000000`, a controller problem:
//! // the receiver reached the warning level.
//! let frame = CanFrame::new_error(0x004, &[0, 0x04, 0, 0, 0, 0, 0, 0])?;
//! let error = ErrorFrame::from_frame(&frame)?;
//! assert_eq!(error.classes, ErrorClasses::CONTROLLER);
//! assert_eq!(error.controller(), ControllerStatus::RX_WARNING);
//! assert_eq!(error.classes.names().collect::<Vec<_>>(), ["controller"]);
//! assert_eq!(error.tx_errors(), None); // the counters class is not set
//! assert_eq!(error.to_string(), "error frame: controller (rx_warning)");
//! # Ok::<(), motionwire_codec::Error>(())
//! ```

use crate::error::What;
use core::fmt;

use super::{CanFrame, FrameType};
use crate::{Result, ValueError};

bitflags::bitflags! {
    /// The error classes of an error frame: bits 0–9 of its identifier
    /// (Linux `linux/can/error.h`, `CAN_ERR_TX_TIMEOUT` … `CAN_ERR_CNT`;
    /// docs/formats.md#error-frames). Bits above 9 are kept as they were
    /// received.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
    #[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
    pub struct ErrorClasses: u32 {
        /// TX timeout, by the network device driver (`CAN_ERR_TX_TIMEOUT`).
        const TX_TIMEOUT = 1 << 0;
        /// Lost arbitration, bit in data byte 0 (`CAN_ERR_LOSTARB`).
        const LOST_ARBITRATION = 1 << 1;
        /// Controller problem, status in data byte 1 (`CAN_ERR_CRTL`).
        const CONTROLLER = 1 << 2;
        /// Protocol violation, type and location in data bytes 2 and 3
        /// (`CAN_ERR_PROT`).
        const PROTOCOL = 1 << 3;
        /// Transceiver status in data byte 4 (`CAN_ERR_TRX`).
        const TRANSCEIVER = 1 << 4;
        /// No ACK received on transmission (`CAN_ERR_ACK`).
        const NO_ACK = 1 << 5;
        /// Bus off (`CAN_ERR_BUSOFF`).
        const BUS_OFF = 1 << 6;
        /// Bus error, may flood (`CAN_ERR_BUSERROR`).
        const BUS_ERROR = 1 << 7;
        /// Controller restarted (`CAN_ERR_RESTARTED`).
        const RESTARTED = 1 << 8;
        /// TX and RX error counters valid in data bytes 6 and 7
        /// (`CAN_ERR_CNT`).
        const COUNTERS = 1 << 9;
        // Classes a later kernel may add are kept as they were received.
        const _ = !0;
    }
}

impl ErrorClasses {
    /// Every class with the name `error_classes` writes
    /// (docs/output.md#error-frame), in bit order: the one table that the
    /// names, `Display` and the tests read.
    pub const NAMES: [(ErrorClasses, &'static str); 10] = [
        (ErrorClasses::TX_TIMEOUT, "tx_timeout"),
        (ErrorClasses::LOST_ARBITRATION, "lost_arbitration"),
        (ErrorClasses::CONTROLLER, "controller"),
        (ErrorClasses::PROTOCOL, "protocol"),
        (ErrorClasses::TRANSCEIVER, "transceiver"),
        (ErrorClasses::NO_ACK, "no_ack"),
        (ErrorClasses::BUS_OFF, "bus_off"),
        (ErrorClasses::BUS_ERROR, "bus_error"),
        (ErrorClasses::RESTARTED, "restarted"),
        (ErrorClasses::COUNTERS, "counters"),
    ];

    /// Return the names of the set classes in bit order (`error_classes`
    /// in docs/output.md#error-frame).
    pub fn names(self) -> impl Iterator<Item = &'static str> + Clone {
        Self::NAMES
            .into_iter()
            .filter(move |(class, _)| self.contains(*class))
            .map(|(_, name)| name)
    }
}

bitflags::bitflags! {
    /// The controller status of an error frame: data byte 1 when the
    /// `controller` class is set (Linux `CAN_ERR_CRTL_*`;
    /// docs/formats.md#error-frames).
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
    #[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
    pub struct ControllerStatus: u8 {
        /// RX buffer overflow (`CAN_ERR_CRTL_RX_OVERFLOW`, 0x01).
        const RX_OVERFLOW = 0x01;
        /// TX buffer overflow (`CAN_ERR_CRTL_TX_OVERFLOW`, 0x02).
        const TX_OVERFLOW = 0x02;
        /// Reached the warning level for RX errors (`CAN_ERR_CRTL_RX_WARNING`, 0x04).
        const RX_WARNING = 0x04;
        /// Reached the warning level for TX errors (`CAN_ERR_CRTL_TX_WARNING`, 0x08).
        const TX_WARNING = 0x08;
        /// Reached the error-passive level for RX (`CAN_ERR_CRTL_RX_PASSIVE`, 0x10).
        const RX_PASSIVE = 0x10;
        /// Reached the error-passive level for TX (`CAN_ERR_CRTL_TX_PASSIVE`, 0x20).
        const TX_PASSIVE = 0x20;
        /// Recovered to error-active state (`CAN_ERR_CRTL_ACTIVE`, 0x40).
        const ACTIVE = 0x40;
        // Bit 7 is kept as it was received.
        const _ = !0;
    }
}

impl ControllerStatus {
    /// Every status flag with the name `controller` writes
    /// (docs/output.md#error-frame), in bit order.
    pub const NAMES: [(ControllerStatus, &'static str); 7] = [
        (ControllerStatus::RX_OVERFLOW, "rx_overflow"),
        (ControllerStatus::TX_OVERFLOW, "tx_overflow"),
        (ControllerStatus::RX_WARNING, "rx_warning"),
        (ControllerStatus::TX_WARNING, "tx_warning"),
        (ControllerStatus::RX_PASSIVE, "rx_passive"),
        (ControllerStatus::TX_PASSIVE, "tx_passive"),
        (ControllerStatus::ACTIVE, "active"),
    ];

    /// Return the names of the set flags in bit order (`controller`
    /// in docs/output.md#error-frame).
    pub fn names(self) -> impl Iterator<Item = &'static str> + Clone {
        Self::NAMES
            .into_iter()
            .filter(move |(flag, _)| self.contains(*flag))
            .map(|(_, name)| name)
    }

    /// Return whether the controller reports the error-passive level, for
    /// receiving or for sending.
    #[must_use]
    pub fn is_error_passive(self) -> bool {
        self.intersects(ControllerStatus::RX_PASSIVE | ControllerStatus::TX_PASSIVE)
    }
}

/// An error frame read: its classes and the details the data bytes carry
/// (Linux `linux/can/error.h`; docs/formats.md#error-frames).
///
/// A detail is only what its class says is there: [`controller`](Self::controller)
/// is empty unless the `controller` class is set, the counters are `None`
/// unless the `counters` class is set (docs/output.md#error-frame), and a byte
/// that a short frame does not have is `None` or empty, never a guessed zero.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ErrorFrame {
    /// The error classes, bits 0..=28 of the identifier.
    pub classes: ErrorClasses,
    /// The data bytes as received, zero past the frame's length.
    bytes: [u8; 8],
    /// How many data bytes the frame had, 0..=8.
    len: u8,
}

impl ErrorFrame {
    /// Read an error frame; any other kind of frame is a
    /// [`ValueError`].
    pub fn from_frame<D: AsRef<[u8]>>(frame: &CanFrame<D>) -> Result<Self, ValueError> {
        if frame.frame_type() != FrameType::Error {
            return Err(ValueError {
                what: What::CanFrameType,
                found: frame.id().raw(),
                expected: "an error frame (CAN_ERR_FLAG)",
            });
        }
        let data = frame.data();
        let mut bytes = [0; 8];
        for (to, from) in bytes.iter_mut().zip(data) {
            *to = *from;
        }
        Ok(ErrorFrame {
            classes: ErrorClasses::from_bits_retain(frame.id().raw()),
            bytes,
            // An error frame has at most 8 bytes (`CanFrame`'s invariant).
            len: data.len().min(8) as u8,
        })
    }

    fn byte(&self, index: usize, class: ErrorClasses) -> Option<u8> {
        if self.classes.contains(class) && index < usize::from(self.len) {
            self.bytes.get(index).copied()
        } else {
            None
        }
    }

    /// Return the data bytes as received.
    #[must_use]
    pub fn data(&self) -> &[u8] {
        self.bytes.get(..usize::from(self.len)).unwrap_or_default()
    }

    /// Return the bit in which arbitration was lost (data byte 0), when the
    /// `lost_arbitration` class is set.
    #[must_use]
    pub fn lost_arbitration_bit(&self) -> Option<u8> {
        self.byte(0, ErrorClasses::LOST_ARBITRATION)
    }

    /// Return the controller status (data byte 1); empty unless the
    /// `controller` class is set.
    #[must_use]
    pub fn controller(&self) -> ControllerStatus {
        self.byte(1, ErrorClasses::CONTROLLER).map_or(
            ControllerStatus::empty(),
            ControllerStatus::from_bits_retain,
        )
    }

    /// Return the protocol error type and location (data bytes 2 and 3,
    /// Linux `CAN_ERR_PROT_*` and `CAN_ERR_PROT_LOC_*`), when the `protocol`
    /// class is set.
    #[must_use]
    pub fn protocol(&self) -> Option<(u8, u8)> {
        Some((
            self.byte(2, ErrorClasses::PROTOCOL)?,
            self.byte(3, ErrorClasses::PROTOCOL)?,
        ))
    }

    /// Return the transceiver status (data byte 4, Linux `CAN_ERR_TRX_*`),
    /// when the `transceiver` class is set.
    #[must_use]
    pub fn transceiver(&self) -> Option<u8> {
        self.byte(4, ErrorClasses::TRANSCEIVER)
    }

    /// Return the TX error counter (data byte 6), when the `counters` class
    /// is set.
    #[must_use]
    pub fn tx_errors(&self) -> Option<u8> {
        self.byte(6, ErrorClasses::COUNTERS)
    }

    /// Return the RX error counter (data byte 7), when the `counters` class
    /// is set.
    #[must_use]
    pub fn rx_errors(&self) -> Option<u8> {
        self.byte(7, ErrorClasses::COUNTERS)
    }

    /// Return whether the frame reports bus-off (`bus_off` in
    /// docs/summary.md#bus).
    #[must_use]
    pub fn is_bus_off(&self) -> bool {
        self.classes.contains(ErrorClasses::BUS_OFF)
    }

    /// Return whether the frame reports the error-passive level
    /// (`error_passive` in docs/summary.md#bus).
    #[must_use]
    pub fn is_error_passive(&self) -> bool {
        self.controller().is_error_passive()
    }
}

impl fmt::Display for ErrorFrame {
    /// `error frame: controller|counters (rx_passive) tx 130 rx 0`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("error frame: ")?;
        if !crate::names::write_joined(f, self.classes.names(), "|")? {
            f.write_str("no class")?;
        }
        let controller = self.controller();
        if !controller.is_empty() {
            f.write_str(" (")?;
            crate::names::write_joined(f, controller.names(), "|")?;
            f.write_str(")")?;
        }
        if let (Some(tx), Some(rx)) = (self.tx_errors(), self.rx_errors()) {
            write!(f, " tx {tx} rx {rx}")?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::can::CanId;

    /// The classes of `linux/can/error.h` and docs/formats.md#error-frames,
    /// written out.
    const CLASSES: [(u32, &str); 10] = [
        (0x001, "tx_timeout"),
        (0x002, "lost_arbitration"),
        (0x004, "controller"),
        (0x008, "protocol"),
        (0x010, "transceiver"),
        (0x020, "no_ack"),
        (0x040, "bus_off"),
        (0x080, "bus_error"),
        (0x100, "restarted"),
        (0x200, "counters"),
    ];

    /// The controller status flags of docs/formats.md#error-frames, written
    /// out.
    const CONTROLLER: [(u8, &str); 7] = [
        (0x01, "rx_overflow"),
        (0x02, "tx_overflow"),
        (0x04, "rx_warning"),
        (0x08, "tx_warning"),
        (0x10, "rx_passive"),
        (0x20, "tx_passive"),
        (0x40, "active"),
    ];

    #[test]
    fn class_bits_and_names_are_the_spec_table() {
        for ((flag, name), (bit, spec_name)) in ErrorClasses::NAMES.into_iter().zip(CLASSES) {
            assert_eq!((flag.bits(), name), (bit, spec_name));
        }
        let all = ErrorClasses::from_bits_retain(0x3FF);
        let expected: Vec<_> = CLASSES.iter().map(|(_, n)| *n).collect();
        assert_eq!(all.names().collect::<Vec<_>>(), expected);
    }

    #[test]
    fn controller_bits_and_names_are_the_spec_table() {
        for ((flag, name), (bit, spec_name)) in ControllerStatus::NAMES.into_iter().zip(CONTROLLER)
        {
            assert_eq!((flag.bits(), name), (bit, spec_name));
        }
    }

    #[test]
    fn details_only_where_their_class_says() {
        // Bus error + protocol + counters, controller byte set but its
        // class not: the controller status stays empty.
        let frame = CanFrame::new_error(0x288, &[0, 0x10, 0x08, 0x19, 0, 0, 0x80, 0x05]).unwrap();
        let error = ErrorFrame::from_frame(&frame).unwrap();
        assert_eq!(
            error.classes.names().collect::<Vec<_>>(),
            ["protocol", "bus_error", "counters"]
        );
        assert!(error.controller().is_empty());
        assert_eq!(error.protocol(), Some((0x08, 0x19)));
        assert_eq!(
            (error.tx_errors(), error.rx_errors()),
            (Some(0x80), Some(5))
        );
        assert_eq!(error.lost_arbitration_bit(), None);
        assert_eq!(error.transceiver(), None);
        assert!(!error.is_bus_off() && !error.is_error_passive());
        assert_eq!(
            error.to_string(),
            "error frame: protocol|bus_error|counters tx 128 rx 5"
        );
    }

    #[test]
    fn bus_off_and_passive() {
        let frame = CanFrame::new_error(0x044, &[0, 0x20, 0, 0, 0, 0, 0, 0]).unwrap();
        let error = ErrorFrame::from_frame(&frame).unwrap();
        assert!(error.is_bus_off() && error.is_error_passive());
        assert_eq!(
            error.to_string(),
            "error frame: controller|bus_off (tx_passive)"
        );
    }

    #[test]
    fn short_frames_report_nothing_they_do_not_have() {
        let frame = CanFrame::new_error(0x206, &[7]).unwrap();
        let error = ErrorFrame::from_frame(&frame).unwrap();
        assert_eq!(error.lost_arbitration_bit(), Some(7));
        assert!(error.controller().is_empty());
        assert_eq!((error.tx_errors(), error.rx_errors()), (None, None));
        assert_eq!(error.data(), [7]);
    }

    #[test]
    fn other_frames_are_refused() {
        let frame = CanFrame::new(CanId::standard(0x81).unwrap(), &[]).unwrap();
        assert!(matches!(
            ErrorFrame::from_frame(&frame),
            Err(ValueError {
                what: What::CanFrameType,
                ..
            })
        ));
    }
}
