//! Writing version 2.1: what the reader reads back to the same frames.

use core::fmt::{self, Write};

use super::header::UNIX_EPOCH_DAY;
use super::row::{ERROR_FRAME_CLASSES, FD_LENGTHS, PROT_LOCATION, PROT_TX, PROT_TYPES};
use crate::can::{Direction, FdFlags, FrameType, Iface, LogFrame, Timestamp};

/// Microseconds in a day.
const DAY_MICROS: u64 = 86_400_000_000;
/// The fraction digits of the days written: enough that reading them back
/// gives the same microsecond.
const FRACTION_DIGITS: u32 = 20;
/// The largest day number the reader takes (7 digits).
const MAX_DAYS: u64 = 9_999_999;

/// The start time as written: to the microsecond.
fn written_start(start: Timestamp) -> Timestamp {
    Timestamp::from_nanos(start.secs(), start.micros() * 1_000).unwrap_or(start)
}

/// Write the header of a version 2.1 file whose offsets count from `start`
/// (docs/formats.md#trc): `;$FILEVERSION=2.1`, `;$STARTTIME=` (days since
/// 1899-12-30 to the microsecond, UTC, as the reader takes it) and
/// `;$COLUMNS=N,O,T,B,I,d,R,L,D`, each line ending in `\r\n` as PEAK's tools
/// write. Fails (`fmt::Error`) for a start after the year 29 000, which the
/// 7 digits of days PEAK's readers take cannot hold.
///
/// ```
/// use motionwire::can::Timestamp;
/// use motionwire::logs::trc;
///
/// let mut text = String::new();
/// trc::write_header(&mut text, Timestamp::new(1_700_000_000, 500).unwrap()).unwrap();
/// assert!(text.starts_with(";$FILEVERSION=2.1\r\n;$STARTTIME=45244.925925931712962962"));
/// ```
pub fn write_header(out: &mut impl Write, start: Timestamp) -> fmt::Result {
    let start = written_start(start);
    let micros = start.as_micros();
    let day = u128::from(DAY_MICROS);
    let days = u64::try_from(micros / day)
        .ok()
        .and_then(|d| d.checked_add(UNIX_EPOCH_DAY))
        .filter(|&d| d <= MAX_DAYS)
        .ok_or(fmt::Error)?;
    let fraction = micros % day * 10u128.pow(FRACTION_DIGITS) / day;
    write!(
        out,
        ";$FILEVERSION=2.1\r\n;$STARTTIME={days}.{fraction:020}\r\n;$COLUMNS=N,O,T,B,I,d,R,L,D\r\n"
    )
}

/// Write `frame` as row `number` of a version 2.1 file whose header
/// [`write_header`] wrote with `start`, in PEAK's 2.1 columns
/// `N,O,T,B,I,d,R,L,D`, ending in `\r\n` (docs/formats.md#trc). The reader
/// reads the row back to the same frame.
///
/// Fails (`fmt::Error`) for what a TRC row cannot hold: a frame without a
/// timestamp or from before `start`, an interface name (TRC has bus
/// numbers; no interface is written `-`), CAN FD flags other than BRS and
/// ESI or a CAN FD length that no DLC has, and an error frame that is not
/// of the shape the reader gives PEAK's error frames
/// ([`ERROR_FRAME_CLASSES`], see the module's decisions).
///
/// ```
/// use motionwire::can::{CanFrame, CanId, Direction, Iface, LogFrame, Timestamp};
/// use motionwire::logs::trc;
///
/// let start = Timestamp::new(1_700_000_000, 0).unwrap();
/// let frame = LogFrame::new(CanFrame::new(CanId::standard(0x705).unwrap(), &[5])?)
///     .with_timestamp(Timestamp::new(1_700_000_001, 250).unwrap())
///     .with_iface(Iface::Channel(1))
///     .with_direction(Direction::Rx);
/// let mut text = String::new();
/// trc::write_line(&mut text, 1, start, &frame).unwrap();
/// assert_eq!(text, "      1      1000.250 DT  1     0705 Rx -  1    05\r\n");
/// # Ok::<(), motionwire::Error>(())
/// ```
pub fn write_line(
    out: &mut impl Write,
    number: u64,
    start: Timestamp,
    frame: &LogFrame<'_>,
) -> fmt::Result {
    let since = frame
        .timestamp
        .and_then(|ts| ts.duration_since(written_start(start)))
        .ok_or(fmt::Error)?;
    let millis = since.as_millis();
    let nanos = since.subsec_nanos() % 1_000_000;
    let bus = match frame.iface {
        Some(Iface::Channel(bus)) => Some(bus),
        None => None,
        Some(Iface::Name(_)) => return Err(fmt::Error),
    };
    let direction = match frame.direction {
        Some(Direction::Rx) => "Rx",
        Some(Direction::Tx) => "Tx",
        None => "-",
    };
    let can = &frame.frame;
    let (kind, dlc) = match can.frame_type() {
        FrameType::Data => ("DT", can.dlc()),
        FrameType::Remote { dlc } => ("RR", dlc),
        FrameType::Fd(flags) => {
            let brs = flags.contains(FdFlags::BRS);
            let esi = flags.contains(FdFlags::ESI);
            let len = can.data().len();
            if !FdFlags::BRS.union(FdFlags::ESI).contains(flags)
                || FD_LENGTHS.get(usize::from(can.dlc())) != Some(&(len as u8))
            {
                return Err(fmt::Error);
            }
            let kind = match (brs, esi) {
                (false, false) => "FD",
                (true, false) => "FB",
                (false, true) => "FE",
                (true, true) => "BI",
            };
            (kind, can.dlc())
        }
        FrameType::Error => ("ER", 5),
    };
    write!(out, "{number:>7} {millis:>9}.")?;
    if nanos % 1_000 == 0 {
        write!(out, "{:03}", nanos / 1_000)?;
    } else {
        write!(out, "{nanos:06}")?;
    }
    write!(out, " {kind} ")?;
    match bus {
        Some(bus) => write!(out, "{bus:>2} ")?,
        None => out.write_str(" - ")?,
    }
    match can.frame_type() {
        FrameType::Error => out.write_str("       -")?,
        _ if can.is_extended() => write!(out, "{:08X}", can.id().raw())?,
        _ => write!(out, "    {:04X}", can.id().raw())?,
    }
    write!(out, " {direction:>2} -  {dlc:<4}")?;
    match can.frame_type() {
        FrameType::Error => {
            let data = error_bytes(can.data()).ok_or(fmt::Error)?;
            if can.id().raw() != ERROR_FRAME_CLASSES.bits() {
                return Err(fmt::Error);
            }
            write_bytes(out, &data)?;
        }
        _ => write_bytes(out, can.data())?,
    }
    out.write_str("\r\n")
}

/// PEAK's five error frame bytes (type, direction, position, RX and TX
/// counters) for Linux error frame data of the reader's shape.
fn error_bytes(data: &[u8]) -> Option<[u8; 5]> {
    let &[0, 0, prot, location, 0, 0, tx, rx] = data else {
        return None;
    };
    if prot & !(PROT_TYPES | PROT_TX) != 0 || location & !PROT_LOCATION != 0 {
        return None;
    }
    let kind = match prot & PROT_TYPES {
        0 => 8,
        kind => kind,
    };
    let receiving = u8::from(prot & PROT_TX == 0);
    Some([kind, receiving, location, rx, tx])
}

/// Each byte as two upper-case hex digits, after a space.
fn write_bytes(out: &mut impl Write, data: &[u8]) -> fmt::Result {
    data.iter().try_for_each(|b| write!(out, " {b:02X}"))
}
