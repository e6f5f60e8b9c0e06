//! A deterministic EtherCAT capture of two CiA 402 drives and one servo of
//! docs/servo.md, as a master's network port shows it, written by the
//! crate's own models; with the ENI file (ETG.2100) that describes the
//! network and a JSON-lines record of what the models did
//! (tests/data/ethercat/README.md, "drives.pcapng").
//!
//! [`write`] writes the three for a number of 1 ms cycles; [`write_files`]
//! writes them to paths. Same cycle count, same bytes.
//!
//! # The network
//!
//! | position | station | device | identity (SII) |
//! |---|---|---|---|
//! | 0 | 0x1001 | servo of docs/servo.md, no mailbox | vendor 0x539, product 0x5E80 |
//! | 1 | 0x1002 | CiA 402 drive A, CoE | vendor 0xE47, product 0x04020001 |
//! | 2 | 0x1003 | CiA 402 drive B, CoE | vendor 0xE47, product 0x04020001 |
//!
//! The identities are fictitious. The master's MAC is 00:01:05:10:20:30;
//! every frame is written as sent and, 40 µs later, as returned (bit 0x02 of
//! the source MAC's first byte set, working counters counted, auto-increment
//! addresses counted on by each of the three slaves, padded to 60 bytes), as
//! scripts/ecat_pcapng.py writes its frames.
//!
//! # Start-up (one exchange every 200 µs)
//!
//! BRD 0x0000; APWR 0x0010 station addresses; AL status reads (FPRD 0x0130,
//! 6 bytes); SII vendor and product words (FPWR 0x0502, FPRD 0x0502, FPRD
//! 0x0508); the drives' mailbox sync managers (FPWR 0x0800, 16 bytes: SM0
//! 0x1000/128 control 0x26, SM1 0x1080/128 control 0x22); INIT → PREOP
//! (FPWR 0x0120, then FPRD 0x0130); the PDO configuration over CoE (drive A
//! with expedited downloads of one sub-index each, drive B with
//! complete-access downloads and a complete-access upload of 0x1A00, as
//! TwinCAT and SOEM do); the process-data sync managers (FPWR 0x0800 + 8n,
//! 8 bytes); the FMMUs (FPWR 0x0600 + 16n); PREOP → SAFEOP → OP.
//!
//! # The process image
//!
//! One LRW at logical 0x00010000, 79 bytes, and a BRD of AL status 0x0130
//! in one frame per cycle:
//!
//! | bytes | what | slave |
//! |---|---|---|
//! | 0–9 | servo command (docs/servo.md#command) | 0x1001 SM0 0x1000 |
//! | 10–16 | controlword 0x6040, target position 0x607A, mode 0x6060 | 0x1002 SM2 0x1100 |
//! | 17–23 | the same | 0x1003 SM2 0x1100 |
//! | 24–63 | servo feedback (docs/servo.md#feedback) | 0x1001 SM1 0x1100 |
//! | 64–70 | statusword 0x6041, position actual 0x6064, mode display 0x6061 | 0x1002 SM3 0x1180 |
//! | 71–77 | the same | 0x1003 SM3 0x1180 |
//! | 78 bit 0 | SM1 status 0x080D bit 3, "mailbox full" | 0x1002 |
//!
//! The sent copy carries this cycle's outputs and, in the inputs part, the
//! inputs the master last received (TwinCAT and SOEM do this); the returned
//! copy carries the slaves' inputs of this cycle. Working counter 9.
//!
//! # The models
//!
//! The servo is [`Drive`], driven by an NC written only against the crate's
//! [`EnableHandshake`], [`ErrorClearHandshake`] and [`ZeroPulseHandshake`]
//! (as examples/nc_loop.rs). The CiA 402 drives run the crate's state
//! machine ([`Cia402State::on_controlword`], [`Cia402State::on_drive_event`])
//! and answer with [`Statusword::with_state`]; their master goes shutdown →
//! switch on → enable operation and then ramps the target position, which
//! the position actual follows; mode 8 (cyclic synchronous position).
//!
//! # Faults ([`Schedule`], in proportion to the cycle count)
//!
//! (a) the servo gets SEW FollowerErr (E09) and the NC clears it and enables
//! again; (e) the zero-pulse handshake; (c) a lost encoder (E01): the NC
//! clears, the drive acknowledges but the error persists, refuses the enable
//! edge, the NC's enable times out, it cancels, clears again (the encoder is
//! back) and arms again; (b) one cycle whose returned copy is lost (the
//! slaves processed it; the master keeps the inputs it had), and one cycle
//! in which the servo takes no part (LRW working counter 6, the servo's
//! inputs returned as sent, the servo model not run); (d) drive A faults:
//! fault reaction active, then fault, with the CoE emergency 0x2310
//! (register 0x03) in its SM1 mailbox, read by the master with an FPRD
//! 0x1080 in a frame of its own between two cycles; the master's fault
//! reset (controlword bit 7 rising) brings it back to operation enabled,
//! and the drive sends the reset emergency 0x0000, read the same way.
//!
//! # The model record
//!
//! One JSON object per line, per thing the models did, in cycle order:
//! `cycle`, `packet` (the pcapng packet number, from 1, of the cycle's
//! returned copy, or of its sent copy where that was lost), `ts` (seconds,
//! of that packet), `slave` (station address; `null` for a lost frame,
//! which concerns no one slave), `kind`, and what the kind
//! says: `cia402_state` (`from`, `to` as [`Cia402State`]'s `Display`,
//! `statusword`), `emcy` (`code`, `register`, `mailbox_packet`: the
//! returned FPRD 0x1080), `servo_enable` (`from`, `to`: [`EnablePhase`]
//! names), `enable_timeout` (`cycles`), `error_clear` and `zero_pulse`
//! (`from`, `to`: [`HandshakePhase`] names; `zero_pulse` to `acknowledged`
//! has `position`), `sew_set` and `sew_cleared` (`fault`, `e_code`),
//! `servo_rdy` (`value`), `act_pos` (`value`, every 1000th cycle),
//! `lost_frame` (`command`), `short_wkc` (`command`, `wkc`, `expected`).
#![allow(dead_code)]

use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::Path;

use motionwire::canopen::{Cia402DriveEvent, Cia402State, Cia402Transition, Statusword};
use motionwire::servo::{
    ActualPosition, Command, Drive, DriveConfig, EnableHandshake, EnablePhase, ErrorClearHandshake,
    Feedback, HandshakePhase, ServoControlWord, ServoErrorWord, ServoFault, ServoStatusWord,
    ZeroPulseHandshake,
};

/// The master's source MAC on the frames it sends.
pub const MASTER_MAC: [u8; 6] = [0x00, 0x01, 0x05, 0x10, 0x20, 0x30];
/// The servo's station address (position 0).
pub const SERVO: u16 = 0x1001;
/// CiA 402 drive A's station address (position 1).
pub const DRIVE_A: u16 = 0x1002;
/// CiA 402 drive B's station address (position 2).
pub const DRIVE_B: u16 = 0x1003;
/// The stations in ring order.
pub const STATIONS: [u16; 3] = [SERVO, DRIVE_A, DRIVE_B];
/// The servo's vendor ID and product code in its SII (fictitious).
pub const SERVO_IDENTITY: (u32, u32) = (0x0000_0539, 0x0000_5E80);
/// The CiA 402 drives' vendor ID and product code in their SII (fictitious).
pub const DRIVE_IDENTITY: (u32, u32) = (0x0000_0E47, 0x0402_0001);
/// The logical address of the process image.
pub const LOGICAL: u32 = 0x0001_0000;
/// The LRW's length: outputs 24, inputs 54, the mailbox bit's byte.
pub const IMAGE_LEN: usize = 79;
/// The LRW's working counter when every slave reads and writes.
pub const LRW_WKC: u16 = 9;
/// The first packet's time: 2026-01-01T00:00:00Z, in nanoseconds.
pub const T0_NS: u64 = 1_767_225_600 * 1_000_000_000;
/// The cycle time.
pub const CYCLE_NS: u64 = 1_000_000;
/// The returned copy's delay after the sent one.
pub const RETURN_NS: u64 = 40_000;
/// The fewest cycles in which every fault of the [`Schedule`] completes.
pub const MIN_CYCLES: u32 = 500;

/// Offsets in the process image.
mod image {
    use core::ops::Range;
    pub const SERVO_OUT: Range<usize> = 0..10;
    pub const A_OUT: Range<usize> = 10..17;
    pub const B_OUT: Range<usize> = 17..24;
    pub const SERVO_IN: Range<usize> = 24..64;
    pub const A_IN: Range<usize> = 64..71;
    pub const B_IN: Range<usize> = 71..78;
    pub const MAILBOX_BIT: usize = 78;
    pub const INPUTS: Range<usize> = 24..79;
}

// Commands (ETG.1000.4; docs/ethercat.md).
const APWR: u8 = 2;
const FPRD: u8 = 4;
const FPWR: u8 = 5;
const BRD: u8 = 7;
const LRW: u8 = 12;

// AL states (register 0x0130).
const INIT: u8 = 1;
const PREOP: u8 = 2;
const SAFEOP: u8 = 4;
const OP: u8 = 8;

// The drives' mailbox.
const MBX_OUT: u16 = 0x1000;
const MBX_IN: u16 = 0x1080;
const MBX_LEN: usize = 128;

/// The cycles at which things happen, in proportion to the cycle count.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Schedule {
    /// The cycles written.
    pub cycles: u32,
    /// The NC's enable timeout and the handshakes' wait, in cycles.
    pub timeout: u32,
    /// The servo starts to move at 250 counts per cycle.
    pub move_at: u32,
    /// (a) SEW FollowerErr (E09) is injected before this cycle.
    pub sew_error: u32,
    /// (e) the NC starts the zero-pulse search at −300 counts per cycle.
    pub home: u32,
    /// (c) the servo loses its encoder (E01) before this cycle…
    pub encoder_lost: u32,
    /// …and gets it back before this one, while the NC waits for ServoEn.
    pub encoder_back: u32,
    /// (b) this cycle's returned copy is lost.
    pub lost_frame: u32,
    /// (b) the servo takes no part in this cycle (LRW working counter 6).
    pub servo_absent: u32,
    /// (d) drive A faults in this cycle.
    pub drive_fault: u32,
    /// Cycles drive A's master waits in fault before the fault reset.
    pub reset_delay: u32,
    /// The servo runs backward from here on.
    pub reverse: u32,
}

impl Schedule {
    /// Return the schedule for `cycles` cycles.
    #[must_use]
    pub fn new(cycles: u32) -> Schedule {
        let at = |permille: u64| (u64::from(cycles) * permille / 1000).max(1) as u32;
        let timeout = (cycles / 40).clamp(20, 500);
        let encoder_lost = at(450);
        Schedule {
            cycles,
            timeout,
            move_at: at(50),
            sew_error: at(150),
            home: at(250),
            encoder_lost,
            encoder_back: encoder_lost + 10 + timeout / 2,
            lost_frame: at(600),
            servo_absent: at(650),
            drive_fault: at(700),
            reset_delay: (cycles / 100).clamp(5, 100),
            reverse: at(800),
        }
    }
}

/// What was written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Written {
    /// Packets in the capture.
    pub packets: u64,
    /// Lines of the model record.
    pub records: u64,
    /// When things happened.
    pub schedule: Schedule,
}

/// Write the capture (pcapng), the model record (JSON lines) and the ENI
/// (XML) of `cycles` cycles to three paths.
pub fn write_files(cycles: u32, capture: &Path, model: &Path, eni: &Path) -> io::Result<Written> {
    let mut capture = BufWriter::with_capacity(1 << 20, File::create(capture)?);
    let mut model = BufWriter::new(File::create(model)?);
    let mut eni = BufWriter::new(File::create(eni)?);
    let written = write(cycles, &mut capture, &mut model, &mut eni)?;
    capture.flush()?;
    model.flush()?;
    eni.flush()?;
    Ok(written)
}

/// Write the capture (pcapng), the model record (JSON lines) and the ENI
/// (XML) of `cycles` cycles. Fewer than [`MIN_CYCLES`] is an error: the
/// faults would not complete.
pub fn write(
    cycles: u32,
    capture: impl Write,
    model: impl Write,
    mut eni: impl Write,
) -> io::Result<Written> {
    if cycles < MIN_CYCLES {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!("at least {MIN_CYCLES} cycles, not {cycles}"),
        ));
    }
    let schedule = Schedule::new(cycles);
    eni.write_all(eni_xml().as_bytes())?;
    let mut run = Run {
        bus: Bus::new(capture)?,
        model: Model {
            out: model,
            lines: 0,
        },
        t: T0_NS,
        counters: [0; 3],
    };
    run.start_up()?;
    run.cycles(schedule)?;
    Ok(Written {
        packets: run.bus.packets,
        records: run.model.lines,
        schedule,
    })
}

// ----------------------------------------------------------------- wire --

/// One datagram as sent and as returned.
#[derive(Debug, Clone, Copy)]
struct Datagram<'a> {
    command: u8,
    /// ADP | ADO << 16, or the logical address.
    address: u32,
    sent: &'a [u8],
    returned: &'a [u8],
    wkc: u16,
}

impl<'a> Datagram<'a> {
    fn fprd(station: u16, ado: u16, zeros: &'a [u8], returned: &'a [u8], wkc: u16) -> Self {
        Datagram {
            command: FPRD,
            address: u32::from(station) | u32::from(ado) << 16,
            sent: &zeros[..returned.len()],
            returned,
            wkc,
        }
    }

    fn fpwr(station: u16, ado: u16, data: &'a [u8]) -> Self {
        Datagram {
            command: FPWR,
            address: u32::from(station) | u32::from(ado) << 16,
            sent: data,
            returned: data,
            wkc: 1,
        }
    }
}

/// Zeros for the sent copies of reads.
static ZEROS: [u8; MBX_LEN] = [0; MBX_LEN];

/// The capture: a pcapng writer and the frames' index counter.
struct Bus<W: Write> {
    out: W,
    packets: u64,
    index: u8,
    frame: Vec<u8>,
    block: Vec<u8>,
}

/// Packet numbers and times of one exchange.
#[derive(Debug, Clone, Copy)]
struct Exchanged {
    sent: u64,
    sent_ns: u64,
    returned: Option<(u64, u64)>,
}

impl Exchanged {
    /// The returned copy's packet and time, or the sent copy's.
    fn last(self) -> (u64, u64) {
        self.returned.unwrap_or((self.sent, self.sent_ns))
    }
}

fn option(block: &mut Vec<u8>, code: u16, value: &[u8]) {
    block.extend_from_slice(&code.to_le_bytes());
    block.extend_from_slice(&(value.len() as u16).to_le_bytes());
    block.extend_from_slice(value);
    block.resize(block.len().next_multiple_of(4), 0);
}

impl<W: Write> Bus<W> {
    /// Write the section header and the one Ethernet interface `eth0` with
    /// nanosecond timestamps.
    fn new(mut out: W) -> io::Result<Self> {
        let mut body = Vec::new();
        body.extend_from_slice(&0x1A2B_3C4Du32.to_le_bytes());
        body.extend_from_slice(&1u16.to_le_bytes());
        body.extend_from_slice(&0u16.to_le_bytes());
        body.extend_from_slice(&(-1i64).to_le_bytes());
        option(&mut body, 4, b"motionwire tests/common/ecat_drives.rs");
        option(&mut body, 0, b"");
        write_block(&mut out, 0x0A0D_0D0A, &body)?;
        body.clear();
        body.extend_from_slice(&1u16.to_le_bytes()); // LINKTYPE_ETHERNET
        body.extend_from_slice(&0u16.to_le_bytes());
        body.extend_from_slice(&0u32.to_le_bytes()); // snaplen: no limit
        option(&mut body, 2, b"eth0");
        option(&mut body, 9, &[9]); // if_tsresol: nanoseconds
        option(&mut body, 0, b"");
        write_block(&mut out, 1, &body)?;
        Ok(Bus {
            out,
            packets: 0,
            index: 0,
            frame: Vec::with_capacity(1536),
            block: Vec::with_capacity(1600),
        })
    }

    /// Write the sent copy of `datagrams` at `t` and, unless `lost`, the
    /// returned copy [`RETURN_NS`] later.
    fn exchange(&mut self, t: u64, datagrams: &[Datagram], lost: bool) -> io::Result<Exchanged> {
        let first = self.index;
        self.index = self.index.wrapping_add(datagrams.len() as u8);
        self.build(datagrams, first, false);
        let sent = self.packet(t)?;
        let returned = if lost {
            None
        } else {
            self.build(datagrams, first, true);
            Some((self.packet(t + RETURN_NS)?, t + RETURN_NS))
        };
        Ok(Exchanged {
            sent,
            sent_ns: t,
            returned,
        })
    }

    /// Build one copy of the frame in `self.frame`.
    fn build(&mut self, datagrams: &[Datagram], first: u8, returned: bool) {
        let f = &mut self.frame;
        f.clear();
        f.extend_from_slice(&[0xFF; 6]);
        let mut source = MASTER_MAC;
        if returned {
            source[0] |= 0x02;
        }
        f.extend_from_slice(&source);
        f.extend_from_slice(&[0x88, 0xA4]);
        f.extend_from_slice(&[0, 0]); // EtherCAT header, filled in below
        for (i, d) in datagrams.iter().enumerate() {
            let data = if returned { d.returned } else { d.sent };
            let mut address = d.address;
            if returned && matches!(d.command, APWR | BRD) {
                // Every slave counts the ADP of an auto-increment command on.
                let adp = (address as u16).wrapping_add(STATIONS.len() as u16);
                address = (address & 0xFFFF_0000) | u32::from(adp);
            }
            let more = if i + 1 < datagrams.len() { 0x8000 } else { 0 };
            f.push(d.command);
            f.push(first.wrapping_add(i as u8));
            f.extend_from_slice(&address.to_le_bytes());
            f.extend_from_slice(&(data.len() as u16 | more).to_le_bytes());
            f.extend_from_slice(&[0, 0]);
            f.extend_from_slice(data);
            f.extend_from_slice(&(if returned { d.wkc } else { 0 }).to_le_bytes());
        }
        let length = (f.len() - 16) as u16;
        f[14..16].copy_from_slice(&(length | 1 << 12).to_le_bytes());
        if returned && f.len() < 60 {
            f.resize(60, 0);
        }
    }

    /// Write `self.frame` as an enhanced packet block at `t`; return its
    /// packet number.
    fn packet(&mut self, t: u64) -> io::Result<u64> {
        let b = &mut self.block;
        b.clear();
        let len = self.frame.len() as u32;
        b.extend_from_slice(&0u32.to_le_bytes());
        b.extend_from_slice(&((t >> 32) as u32).to_le_bytes());
        b.extend_from_slice(&(t as u32).to_le_bytes());
        b.extend_from_slice(&len.to_le_bytes());
        b.extend_from_slice(&len.to_le_bytes());
        b.extend_from_slice(&self.frame);
        b.resize(b.len().next_multiple_of(4), 0);
        write_block(&mut self.out, 6, b)?;
        self.packets += 1;
        Ok(self.packets)
    }
}

fn write_block(out: &mut impl Write, kind: u32, body: &[u8]) -> io::Result<()> {
    let total = (12 + body.len()) as u32;
    let mut head = [0; 8];
    head[..4].copy_from_slice(&kind.to_le_bytes());
    head[4..].copy_from_slice(&total.to_le_bytes());
    out.write_all(&head)?;
    out.write_all(body)?;
    out.write_all(&total.to_le_bytes())
}

/// One sync manager's 8 bytes (0x0800 + 8n).
fn sm(start: u16, length: u16, control: u8) -> [u8; 8] {
    let [s0, s1] = start.to_le_bytes();
    let [l0, l1] = length.to_le_bytes();
    [s0, s1, l0, l1, control, 0, 1, 0]
}

/// One FMMU's 16 bytes (0x0600 + 16n); `kind` 1 read, 2 write.
fn fmmu(logical: u32, length: u16, bits: (u8, u8), physical: u16, bit: u8, kind: u8) -> [u8; 16] {
    let mut f = [0; 16];
    f[..4].copy_from_slice(&logical.to_le_bytes());
    f[4..6].copy_from_slice(&length.to_le_bytes());
    (f[6], f[7]) = bits;
    f[8..10].copy_from_slice(&physical.to_le_bytes());
    f[10] = bit;
    f[11] = kind;
    f[12] = 1;
    f
}

/// A mailbox message (6-byte header, CoE type 3) padded to the SM's 128
/// bytes.
fn coe_mailbox(counter: u8, coe: &[u8]) -> [u8; MBX_LEN] {
    let mut m = [0; MBX_LEN];
    m[..2].copy_from_slice(&(coe.len() as u16).to_le_bytes());
    m[5] = 3 | (counter & 7) << 4;
    m[6..6 + coe.len()].copy_from_slice(coe);
    m
}

/// The CoE header: number 0, `service` (1 emergency, 2 SDO request, 3 SDO
/// response).
fn coe_header(service: u8) -> [u8; 2] {
    (u16::from(service) << 12).to_le_bytes()
}

/// An SDO message of 10 bytes: CoE header, command, index, sub-index, 4
/// data bytes.
fn sdo(service: u8, command: u8, index: u16, sub: u8, data: [u8; 4]) -> Vec<u8> {
    let mut m = coe_header(service).to_vec();
    m.push(command);
    m.extend_from_slice(&index.to_le_bytes());
    m.push(sub);
    m.extend_from_slice(&data);
    m
}

/// A normal (size-indicated) SDO message with complete access: CoE
/// header, command, index, sub-index 0, the 4-byte size, the data.
fn sdo_complete(service: u8, command: u8, index: u16, data: &[u8]) -> Vec<u8> {
    let mut m = coe_header(service).to_vec();
    m.push(command);
    m.extend_from_slice(&index.to_le_bytes());
    m.push(0);
    m.extend_from_slice(&(data.len() as u32).to_le_bytes());
    m.extend_from_slice(data);
    m
}

/// The complete-access data of a PDO assignment or mapping object:
/// sub-index 0, a padding byte, the entries.
fn complete_data(entries: &[u32], width: usize) -> Vec<u8> {
    let mut d = vec![entries.len() as u8, 0];
    for e in entries {
        d.extend_from_slice(&e.to_le_bytes()[..width]);
    }
    d
}

/// The RxPDO mapping of both drives: controlword, target position, mode.
const RX_MAPPING: [u32; 3] = [0x6040_0010, 0x607A_0020, 0x6060_0008];
/// The TxPDO mapping: statusword, position actual, mode display.
const TX_MAPPING: [u32; 3] = [0x6041_0010, 0x6064_0020, 0x6061_0008];

// ------------------------------------------------------------ start-up --

/// The writers and the clock.
struct Run<C: Write, M: Write> {
    bus: Bus<C>,
    model: Model<M>,
    t: u64,
    /// The last mailbox counter per station (index: station − 0x1001),
    /// 1–7: a request and its response carry the same one.
    counters: [u8; 3],
}

/// The start-up's spacing.
const STEP_NS: u64 = 200_000;

impl<C: Write, M: Write> Run<C, M> {
    fn ex(&mut self, datagrams: &[Datagram]) -> io::Result<Exchanged> {
        let e = self.bus.exchange(self.t, datagrams, false)?;
        self.t += STEP_NS;
        Ok(e)
    }

    fn al_control(&mut self, state: u8) -> io::Result<()> {
        for station in STATIONS {
            self.ex(&[Datagram::fpwr(station, 0x0120, &[state, 0])])?;
        }
        for station in STATIONS {
            self.ex(&[Datagram::fprd(
                station,
                0x0130,
                &ZEROS,
                &[state, 0, 0, 0, 0, 0],
                1,
            )])?;
        }
        Ok(())
    }

    fn start_up(&mut self) -> io::Result<()> {
        // Count the slaves: every ESC answers the broadcast read of its
        // type register.
        self.ex(&[Datagram {
            command: BRD,
            address: 0,
            sent: &[0],
            returned: &[0x11],
            wkc: 3,
        }])?;
        for (position, station) in STATIONS.into_iter().enumerate() {
            let adp = (position as u16).wrapping_neg();
            self.ex(&[Datagram {
                command: APWR,
                address: u32::from(adp) | 0x0010 << 16,
                sent: &station.to_le_bytes(),
                returned: &station.to_le_bytes(),
                wkc: 1,
            }])?;
        }
        for station in STATIONS {
            self.ex(&[Datagram::fprd(
                station,
                0x0130,
                &ZEROS,
                &[INIT, 0, 0, 0, 0, 0],
                1,
            )])?;
        }
        // SII identity: vendor (word 0x08), product (word 0x0A).
        for station in STATIONS {
            let (vendor, product) = if station == SERVO {
                SERVO_IDENTITY
            } else {
                DRIVE_IDENTITY
            };
            for (word, value) in [(0x08u16, vendor), (0x0A, product)] {
                let mut request = [0x00, 0x01, 0, 0, 0, 0];
                request[2..4].copy_from_slice(&word.to_le_bytes());
                self.ex(&[Datagram::fpwr(station, 0x0502, &request)])?;
                self.ex(&[Datagram::fprd(station, 0x0502, &ZEROS, &[0, 0], 1)])?;
                self.ex(&[Datagram::fprd(
                    station,
                    0x0508,
                    &ZEROS,
                    &value.to_le_bytes(),
                    1,
                )])?;
            }
        }
        // The drives' mailbox sync managers, before PREOP.
        let mut mailbox_sms = [0; 16];
        mailbox_sms[..8].copy_from_slice(&sm(MBX_OUT, MBX_LEN as u16, 0x26));
        mailbox_sms[8..].copy_from_slice(&sm(MBX_IN, MBX_LEN as u16, 0x22));
        for station in [DRIVE_A, DRIVE_B] {
            self.ex(&[Datagram::fpwr(station, 0x0800, &mailbox_sms)])?;
        }
        self.al_control(PREOP)?;

        // Drive A: expedited downloads, one sub-index each.
        let a: [(u16, u8, u32, u8); 16] = [
            (0x1C12, 0, 0, 1),
            (0x1600, 0, 0, 1),
            (0x1600, 1, RX_MAPPING[0], 4),
            (0x1600, 2, RX_MAPPING[1], 4),
            (0x1600, 3, RX_MAPPING[2], 4),
            (0x1600, 0, 3, 1),
            (0x1C12, 1, 0x1600, 2),
            (0x1C12, 0, 1, 1),
            (0x1C13, 0, 0, 1),
            (0x1A00, 0, 0, 1),
            (0x1A00, 1, TX_MAPPING[0], 4),
            (0x1A00, 2, TX_MAPPING[1], 4),
            (0x1A00, 3, TX_MAPPING[2], 4),
            (0x1A00, 0, 3, 1),
            (0x1C13, 1, 0x1A00, 2),
            (0x1C13, 0, 1, 1),
        ];
        for (n, (index, sub, value, size)) in a.into_iter().enumerate() {
            // 0x2F, 0x2B, 0x23: expedited, size indicated, 1/2/4 bytes.
            let command = 0x23 | (4 - size) << 2;
            let request = sdo(2, command, index, sub, value.to_le_bytes());
            let response = sdo(3, 0x60, index, sub, [0; 4]);
            self.sdo_exchange(DRIVE_A, &request, &response, n == 0)?;
        }
        // Drive B: complete-access downloads (command 0x31: initiate
        // download, complete access, size indicated, not expedited), then a
        // complete-access upload of 0x1A00 read back.
        let b: [(u16, Vec<u8>); 6] = [
            (0x1C12, complete_data(&[], 1)),
            (0x1600, complete_data(&RX_MAPPING, 4)),
            (0x1C12, complete_data(&[0x1600], 2)),
            (0x1C13, complete_data(&[], 1)),
            (0x1A00, complete_data(&TX_MAPPING, 4)),
            (0x1C13, complete_data(&[0x1A00], 2)),
        ];
        for (n, (index, data)) in b.iter().enumerate() {
            let request = sdo_complete(2, 0x31, *index, data);
            let response = sdo(3, 0x60, *index, 0, [0; 4]);
            self.sdo_exchange(DRIVE_B, &request, &response, n == 0)?;
        }
        // Upload request 0x50 (complete access); response 0x51: normal,
        // size indicated, complete access.
        let request = sdo(2, 0x50, 0x1A00, 0, [0; 4]);
        let response = sdo_complete(3, 0x51, 0x1A00, &complete_data(&TX_MAPPING, 4));
        self.sdo_exchange(DRIVE_B, &request, &response, false)?;

        // Process-data sync managers, one FPWR each.
        for (station, sms) in [
            (
                SERVO,
                [(0u16, sm(0x1000, 10, 0x64)), (1, sm(0x1100, 40, 0x20))],
            ),
            (
                DRIVE_A,
                [(2, sm(0x1100, 7, 0x64)), (3, sm(0x1180, 7, 0x20))],
            ),
            (
                DRIVE_B,
                [(2, sm(0x1100, 7, 0x64)), (3, sm(0x1180, 7, 0x20))],
            ),
        ] {
            for (n, bytes) in sms {
                self.ex(&[Datagram::fpwr(station, 0x0800 + 8 * n, &bytes)])?;
            }
        }
        // FMMUs: outputs from 0x00010000, inputs from 0x00010018, and drive
        // A's SM1 status bit ("mailbox full") at 0x0001004E bit 0.
        let full = (0, 7);
        for (station, fmmus) in [
            (
                SERVO,
                vec![
                    fmmu(LOGICAL, 10, full, 0x1000, 0, 2),
                    fmmu(LOGICAL + 24, 40, full, 0x1100, 0, 1),
                ],
            ),
            (
                DRIVE_A,
                vec![
                    fmmu(LOGICAL + 10, 7, full, 0x1100, 0, 2),
                    fmmu(LOGICAL + 64, 7, full, 0x1180, 0, 1),
                    fmmu(LOGICAL + 78, 1, (0, 0), 0x080D, 3, 1),
                ],
            ),
            (
                DRIVE_B,
                vec![
                    fmmu(LOGICAL + 17, 7, full, 0x1100, 0, 2),
                    fmmu(LOGICAL + 71, 7, full, 0x1180, 0, 1),
                ],
            ),
        ] {
            for (n, bytes) in fmmus.iter().enumerate() {
                self.ex(&[Datagram::fpwr(station, 0x0600 + 16 * n as u16, bytes)])?;
            }
        }
        self.al_control(SAFEOP)?;
        self.al_control(OP)
    }

    /// One SDO transfer: the request written to SM0, the response read
    /// from SM1 (after an empty read with working counter 0 when `early`).
    fn sdo_exchange(
        &mut self,
        station: u16,
        request: &[u8],
        response: &[u8],
        early: bool,
    ) -> io::Result<()> {
        let slot = usize::from(station - SERVO);
        self.counters[slot] = self.counters[slot] % 7 + 1;
        let counter = self.counters[slot];
        let written = coe_mailbox(counter, request);
        self.ex(&[Datagram::fpwr(station, MBX_OUT, &written)])?;
        if early {
            self.ex(&[Datagram::fprd(station, MBX_IN, &ZEROS, &ZEROS, 0)])?;
        }
        let read = coe_mailbox(counter, response);
        self.ex(&[Datagram::fprd(station, MBX_IN, &ZEROS, &read, 1)])?;
        Ok(())
    }
}

// --------------------------------------------------------------- cycles --

/// What the NC is doing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Goal {
    /// Enable the drive, then run.
    Enable,
    /// Run at the NC's speed.
    Run,
    /// Clear the drive's errors, then enable again.
    Clear,
    /// Search the zero pulse at this set point, then run.
    Home(i32),
}

/// The NC of the servo, written against the crate's three handshakes only
/// (examples/nc_loop.rs): it never writes an SE value or a request bit by
/// hand.
struct Nc {
    goal: Goal,
    speed: i32,
    scw: ServoControlWord,
    enable: EnableHandshake,
    clear: ErrorClearHandshake,
    zero: ZeroPulseHandshake,
    timeout: u32,
}

impl Nc {
    /// One NC cycle: read the newest feedback, decide, return the command
    /// and whether the enable timed out.
    fn cycle(&mut self, feedback: &Feedback) -> (Command, bool) {
        let status = feedback.status;
        (self.enable, self.scw) = self.enable.step(self.scw, status);
        (self.clear, self.scw) = self.clear.step(self.scw, status);
        (self.zero, self.scw) = self.zero.step(self.scw, status);
        let mut timed_out = false;
        if self.enable.phase() == EnablePhase::Enabling
            && self.enable.cycles_in_phase() > self.timeout
        {
            // The drive refused the edge: withdraw it, clear what is in
            // the way and arm again.
            timed_out = true;
            self.enable = self.enable.cancel();
            if feedback.errors.is_empty() {
                self.enable = self.enable.start();
            } else {
                self.goal = Goal::Clear;
                self.clear = self.clear.start();
            }
        }
        if self.clear.phase() == HandshakePhase::Requested
            && self.clear.cycles_in_phase() > self.timeout
        {
            self.clear = self.clear.cancel();
        }
        if self.zero.phase() == HandshakePhase::Requested
            && self.zero.cycles_in_phase() > self.timeout
        {
            self.zero = self.zero.cancel();
        }
        // An error while the axis runs stops it and starts a clear; while
        // enabling, the NC waits for its timeout instead.
        if !feedback.errors.is_empty() && matches!(self.goal, Goal::Run | Goal::Home(_)) {
            self.goal = Goal::Clear;
            self.clear = self.clear.start();
            if self.enable.phase() != EnablePhase::Dropped {
                self.enable = self.enable.cancel();
            }
        }
        let setpoint = match self.goal {
            Goal::Enable => {
                self.enable = self.enable.start();
                if self.enable.is_enabled() {
                    self.goal = Goal::Run;
                }
                0
            }
            Goal::Clear => {
                // The ack says the drive cleared; enable again (a cause
                // that persists shows as a refused edge).
                if self.clear.phase() == HandshakePhase::Done {
                    self.goal = Goal::Enable;
                    self.enable = self.enable.start();
                }
                0
            }
            Goal::Run => self.speed,
            Goal::Home(speed) => {
                if matches!(
                    self.zero.phase(),
                    HandshakePhase::Idle | HandshakePhase::Done
                ) {
                    self.goal = Goal::Run;
                }
                speed
            }
        };
        self.scw = self
            .zero
            .apply(self.clear.apply(self.enable.apply(self.scw)));
        (Command::new(setpoint, self.scw, 0), timed_out)
    }
}

/// A CiA 402 drive's application: the crate's state machine, answering
/// the controlword with the statusword; the position actual follows the
/// target while operation is enabled.
struct Cia402Drive {
    state: Cia402State,
    previous: Option<u16>,
    position: i32,
    mode: i8,
    fault: bool,
}

impl Cia402Drive {
    fn new() -> Self {
        Cia402Drive {
            state: Cia402Transition::T0.to(),
            previous: None,
            position: 0,
            mode: 0,
            fault: false,
        }
    }

    /// One cycle: the outputs (controlword, target, mode) in, the inputs
    /// (statusword, position actual, mode display) out.
    fn cycle(&mut self, outputs: &[u8]) -> [u8; 7] {
        let controlword = u16::from_le_bytes([outputs[0], outputs[1]]);
        let target = i32::from_le_bytes([outputs[2], outputs[3], outputs[4], outputs[5]]);
        self.mode = outputs[6] as i8;
        let event = if self.fault {
            self.fault = false;
            Some(Cia402DriveEvent::Fault)
        } else {
            match self.state {
                Cia402State::NotReadyToSwitchOn => Some(Cia402DriveEvent::InitializationComplete),
                Cia402State::FaultReactionActive => Some(Cia402DriveEvent::FaultReactionComplete),
                _ => None,
            }
        };
        if let Some(t) = event.and_then(|e| self.state.on_drive_event(e)) {
            self.state = t.to();
        } else if let (_, Some(t)) = self.state.on_controlword(controlword, self.previous) {
            self.state = t.to();
        }
        self.previous = Some(controlword);
        if self.state == Cia402State::OperationEnabled {
            self.position = target;
        }
        let mut inputs = [0; 7];
        let statusword = Statusword::REMOTE.with_state(self.state).bits();
        inputs[..2].copy_from_slice(&statusword.to_le_bytes());
        inputs[2..6].copy_from_slice(&self.position.to_le_bytes());
        inputs[6] = self.mode as u8;
        inputs
    }
}

/// The master's side of a CiA 402 drive: shutdown → switch on → enable
/// operation, then a target ramp; a fault reset after a while in fault.
struct Cia402Master {
    controlword: u16,
    target: i32,
    step: i32,
    in_fault: u32,
    reset_delay: u32,
}

impl Cia402Master {
    /// This cycle's outputs from the inputs last received.
    fn outputs(&mut self, inputs: &[u8]) -> [u8; 7] {
        let statusword = u16::from_le_bytes([inputs[0], inputs[1]]);
        let actual = i32::from_le_bytes([inputs[2], inputs[3], inputs[4], inputs[5]]);
        let state = Cia402State::from_statusword(statusword);
        self.in_fault = if state == Some(Cia402State::Fault) {
            self.in_fault + 1
        } else {
            0
        };
        self.controlword = match state {
            Some(Cia402State::SwitchOnDisabled) => 0x0006,
            Some(Cia402State::ReadyToSwitchOn) => 0x0007,
            Some(Cia402State::SwitchedOn | Cia402State::OperationEnabled) => 0x000F,
            // Bit 7 rises once the fault has been seen for a while.
            Some(Cia402State::Fault) if self.in_fault > self.reset_delay => 0x0080,
            Some(Cia402State::Fault | Cia402State::FaultReactionActive) => {
                self.controlword & !0x0080
            }
            _ => 0x0000,
        };
        self.target = if state == Some(Cia402State::OperationEnabled) {
            self.target.wrapping_add(self.step)
        } else {
            actual
        };
        let mut outputs = [0; 7];
        outputs[..2].copy_from_slice(&self.controlword.to_le_bytes());
        outputs[2..6].copy_from_slice(&self.target.to_le_bytes());
        outputs[6] = 8; // cyclic synchronous position
        outputs
    }
}

/// The model record's writer.
struct Model<M: Write> {
    out: M,
    lines: u64,
}

impl<M: Write> Model<M> {
    fn record(
        &mut self,
        cycle: u32,
        (packet, ns): (u64, u64),
        slave: impl Into<Option<u16>>,
        kind: &str,
        rest: std::fmt::Arguments,
    ) -> io::Result<()> {
        self.lines += 1;
        let (s, ns_part) = (ns / 1_000_000_000, ns % 1_000_000_000);
        match slave.into() {
            Some(slave) => writeln!(
                self.out,
                r#"{{"cycle":{cycle},"packet":{packet},"ts":{s}.{ns_part:09},"slave":{slave},"kind":"{kind}"{rest}}}"#,
            ),
            None => writeln!(
                self.out,
                r#"{{"cycle":{cycle},"packet":{packet},"ts":{s}.{ns_part:09},"slave":null,"kind":"{kind}"{rest}}}"#,
            ),
        }
    }
}

/// The servo's facts the record follows between cycles.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct ServoSeen {
    enable: EnablePhase,
    clear: HandshakePhase,
    zero: HandshakePhase,
    ready: bool,
    errors: ServoErrorWord,
}

/// A pending CoE emergency in drive A's SM1 mailbox: code, register.
type Emergency = (u16, u8);

impl<C: Write, M: Write> Run<C, M> {
    fn cycles(&mut self, s: Schedule) -> io::Result<()> {
        let mut drive = Drive::new(DriveConfig::default());
        let mut nc = Nc {
            goal: Goal::Enable,
            speed: 0,
            scw: ServoControlWord::NORMAL,
            enable: EnableHandshake::new(),
            clear: ErrorClearHandshake::new(),
            zero: ZeroPulseHandshake::new(),
            timeout: s.timeout,
        };
        let mut drives = [Cia402Drive::new(), Cia402Drive::new()];
        let mut masters = [
            Cia402Master {
                controlword: 0,
                target: 0,
                step: 100,
                in_fault: 0,
                reset_delay: s.reset_delay,
            },
            Cia402Master {
                controlword: 0,
                target: 0,
                step: -70,
                in_fault: 0,
                reset_delay: s.reset_delay,
            },
        ];
        let mut slave_counter = [self.counters[1], self.counters[2]];
        let mut mailbox: Option<Emergency> = None;
        // What the master has: the inputs of the last returned frame.
        let mut master_image = [0u8; IMAGE_LEN];
        let mut servo_out = Feedback::from_bytes(&[0; 40]);
        let mut seen = ServoSeen {
            enable: nc.enable.phase(),
            clear: nc.clear.phase(),
            zero: nc.zero.phase(),
            ready: false,
            errors: ServoErrorWord::empty(),
        };
        let mut sent = [0u8; IMAGE_LEN];
        let brd_zero = [0u8; 2];
        let brd_op = [OP, 0];
        self.t = (self.t / CYCLE_NS + 1) * CYCLE_NS;

        for cycle in 1..=s.cycles {
            let t = self.t;
            self.t += CYCLE_NS;
            // What happens to the machine.
            match cycle {
                c if c == s.move_at => nc.speed = 250,
                c if c == s.sew_error => drive.inject(ServoFault::FollowerErr),
                c if c == s.home => {
                    nc.goal = Goal::Home(-300);
                    nc.zero = nc.zero.start();
                    nc.speed = 400;
                }
                c if c == s.encoder_lost => drive.lose_encoder(),
                c if c == s.encoder_back => drive.restore_encoder(),
                c if c == s.drive_fault => drives[0].fault = true,
                c if c == s.reverse => nc.speed = -200,
                _ => {}
            }
            let servo_present = cycle != s.servo_absent;
            let lost = cycle == s.lost_frame;

            // The master: outputs from what it last received.
            let nc_feedback =
                Feedback::from_bytes(master_image[image::SERVO_IN].try_into().expect("40 bytes"));
            let (command, timed_out) = nc.cycle(&nc_feedback);
            sent[image::SERVO_OUT].copy_from_slice(&command.to_bytes());
            sent[image::A_OUT].copy_from_slice(&masters[0].outputs(&master_image[image::A_IN]));
            sent[image::B_OUT].copy_from_slice(&masters[1].outputs(&master_image[image::B_IN]));
            sent[image::INPUTS].copy_from_slice(&master_image[image::INPUTS]);

            // The slaves.
            let mut returned = sent;
            if servo_present {
                let received =
                    Command::from_bytes(sent[image::SERVO_OUT].try_into().expect("10 bytes"));
                servo_out = drive.cycle(&received);
                returned[image::SERVO_IN].copy_from_slice(&servo_out.to_bytes());
            }
            let states = [drives[0].state, drives[1].state];
            returned[image::A_IN].copy_from_slice(&drives[0].cycle(&sent[image::A_OUT]));
            returned[image::B_IN].copy_from_slice(&drives[1].cycle(&sent[image::B_OUT]));
            if drives[0].state == Cia402State::FaultReactionActive && states[0] != drives[0].state {
                mailbox = Some((0x2310, 0x03));
            } else if states[0] == Cia402State::Fault && drives[0].state != Cia402State::Fault {
                mailbox = Some((0x0000, 0x00));
            }
            returned[image::MAILBOX_BIT] = u8::from(mailbox.is_some());
            let wkc = if servo_present { LRW_WKC } else { LRW_WKC - 3 };
            let frame = [
                Datagram {
                    command: LRW,
                    address: LOGICAL,
                    sent: &sent,
                    returned: &returned,
                    wkc,
                },
                Datagram {
                    command: BRD,
                    address: 0x0130 << 16,
                    sent: &brd_zero,
                    returned: &brd_op,
                    wkc: 3,
                },
            ];
            let exchanged = self.bus.exchange(t, &frame, lost)?;
            let at = exchanged.last();
            if !lost {
                master_image[image::INPUTS].copy_from_slice(&returned[image::INPUTS]);
            }

            // The record.
            if lost {
                self.model.record(
                    cycle,
                    at,
                    None,
                    "lost_frame",
                    format_args!(r#","command":"LRW""#),
                )?;
            }
            if !servo_present {
                self.model.record(
                    cycle,
                    at,
                    SERVO,
                    "short_wkc",
                    format_args!(r#","command":"LRW","wkc":{wkc},"expected":{LRW_WKC}"#),
                )?;
            }
            if timed_out {
                self.model.record(
                    cycle,
                    at,
                    SERVO,
                    "enable_timeout",
                    format_args!(r#","cycles":{}"#, s.timeout),
                )?;
            }
            let now = ServoSeen {
                enable: nc.enable.phase(),
                clear: nc.clear.phase(),
                zero: nc.zero.phase(),
                ready: servo_out.status.contains(ServoStatusWord::SERVO_RDY),
                errors: servo_out.errors,
            };
            self.servo_record(cycle, at, seen, now, &servo_out)?;
            seen = now;
            if cycle % 1000 == 0 {
                self.model.record(
                    cycle,
                    at,
                    SERVO,
                    "act_pos",
                    format_args!(r#","value":{}"#, drive.position()),
                )?;
            }
            for (n, station) in [DRIVE_A, DRIVE_B].into_iter().enumerate() {
                if states[n] != drives[n].state {
                    let inputs = if n == 0 { image::A_IN } else { image::B_IN };
                    let statusword =
                        u16::from_le_bytes([returned[inputs.start], returned[inputs.start + 1]]);
                    self.model.record(
                        cycle,
                        at,
                        station,
                        "cia402_state",
                        format_args!(
                            r#","from":"{}","to":"{}","statusword":{statusword}"#,
                            states[n], drives[n].state
                        ),
                    )?;
                }
            }

            // The master saw drive A's mailbox full: it reads the message
            // in a frame of its own before the next cycle.
            if let Some((code, register)) = mailbox.filter(|_| !lost) {
                slave_counter[0] = slave_counter[0] % 7 + 1;
                let mut emcy = coe_header(1).to_vec();
                emcy.extend_from_slice(&code.to_le_bytes());
                emcy.push(register);
                emcy.extend_from_slice(&[0; 5]);
                let message = coe_mailbox(slave_counter[0], &emcy);
                let read = self.bus.exchange(
                    t + CYCLE_NS / 2,
                    &[Datagram::fprd(DRIVE_A, MBX_IN, &ZEROS, &message, 1)],
                    false,
                )?;
                mailbox = None;
                self.model.record(
                    cycle,
                    at,
                    DRIVE_A,
                    "emcy",
                    format_args!(
                        r#","code":{code},"register":{register},"mailbox_packet":{}"#,
                        read.last().0
                    ),
                )?;
            }
        }
        Ok(())
    }

    /// Record what changed in the servo and its NC in this cycle.
    fn servo_record(
        &mut self,
        cycle: u32,
        at: (u64, u64),
        before: ServoSeen,
        now: ServoSeen,
        feedback: &Feedback,
    ) -> io::Result<()> {
        let m = &mut self.model;
        if before.enable != now.enable {
            m.record(
                cycle,
                at,
                SERVO,
                "servo_enable",
                format_args!(r#","from":"{}","to":"{}""#, before.enable, now.enable),
            )?;
        }
        if before.clear != now.clear {
            m.record(
                cycle,
                at,
                SERVO,
                "error_clear",
                format_args!(r#","from":"{}","to":"{}""#, before.clear, now.clear),
            )?;
        }
        if before.zero != now.zero {
            let position = match feedback.actual_position() {
                ActualPosition::Incremental {
                    zero_pulse_position,
                    ..
                } if now.zero == HandshakePhase::Acknowledged => {
                    format!(r#","position":{zero_pulse_position}"#)
                }
                _ => String::new(),
            };
            m.record(
                cycle,
                at,
                SERVO,
                "zero_pulse",
                format_args!(r#","from":"{}","to":"{}"{position}"#, before.zero, now.zero),
            )?;
        }
        for fault in ServoFault::ALL {
            if fault == ServoFault::ServoErrors {
                continue;
            }
            let was = before.errors.contains(fault.flag());
            let is = now.errors.contains(fault.flag());
            if was != is {
                let e_code = fault.e_code().map_or(String::new(), |c| c.to_string());
                m.record(
                    cycle,
                    at,
                    SERVO,
                    if is { "sew_set" } else { "sew_cleared" },
                    format_args!(r#","fault":"{}","e_code":"{e_code}""#, fault.name()),
                )?;
            }
        }
        if before.ready != now.ready {
            m.record(
                cycle,
                at,
                SERVO,
                "servo_rdy",
                format_args!(r#","value":{}"#, now.ready),
            )?;
        }
        Ok(())
    }
}

// ------------------------------------------------------------------ ENI --

/// One slave's InitCmd: an FPWR of `data` at `ado`, or (`data` empty) an
/// FPRD of `length` bytes that must show `validate`, in `transitions`.
struct InitCmd<'a> {
    transitions: &'a [&'a str],
    comment: &'a str,
    station: u16,
    ado: u16,
    data: &'a [u8],
    validate: Option<(&'a [u8], &'a [u8])>,
}

impl InitCmd<'_> {
    fn write(&self, out: &mut String) {
        use std::fmt::Write as _;
        out.push_str("        <InitCmd>\n");
        for t in self.transitions {
            let _ = writeln!(out, "          <Transition>{t}</Transition>");
        }
        let _ = writeln!(
            out,
            "          <Comment><![CDATA[{}]]></Comment>",
            self.comment
        );
        out.push_str("          <Requires>cycle</Requires>\n");
        let command = if self.validate.is_some() { FPRD } else { FPWR };
        let _ = writeln!(out, "          <Cmd>{command}</Cmd>");
        let _ = writeln!(out, "          <Adp>{}</Adp>", self.station);
        let _ = writeln!(out, "          <Ado>{}</Ado>", self.ado);
        match self.validate {
            None => {
                let _ = writeln!(out, "          <Data>{}</Data>", hex(self.data));
            }
            Some((value, _)) => {
                let _ = writeln!(out, "          <DataLength>{}</DataLength>", value.len());
            }
        }
        out.push_str("          <Cnt>1</Cnt>\n          <Retries>3</Retries>\n");
        if let Some((value, mask)) = self.validate {
            let _ = writeln!(
                out,
                "          <Validate>\n            <Data>{}</Data>\n            <DataMask>{}</DataMask>\n            <Timeout>5000</Timeout>\n          </Validate>",
                hex(value),
                hex(mask)
            );
        }
        out.push_str("        </InitCmd>\n");
    }
}

/// The InitCmds that request AL `state` and wait for it.
fn al_init_cmds(out: &mut String, transition: &str, name: &str, station: u16, state: u8) {
    let transitions = [transition];
    InitCmd {
        transitions: &transitions,
        comment: &format!("request {name} state"),
        station,
        ado: 0x0120,
        data: &[state, 0],
        validate: None,
    }
    .write(out);
    InitCmd {
        transitions: &transitions,
        comment: &format!("check {name} state"),
        station,
        ado: 0x0130,
        data: &[],
        validate: Some((&[state, 0], &[0x1F, 0])),
    }
    .write(out);
}

/// An InitCmd writing `data` at `ado` of `station`.
fn write_cmd(
    out: &mut String,
    transition: &str,
    comment: &str,
    station: u16,
    ado: u16,
    data: &[u8],
) {
    InitCmd {
        transitions: &[transition],
        comment,
        station,
        ado,
        data,
        validate: None,
    }
    .write(out);
}

fn hex(data: &[u8]) -> String {
    data.iter().map(|b| format!("{b:02x}")).collect()
}

/// A PDO's ENI element: `kind` RxPdo or TxPdo, on `sm`, with its entries
/// (index, sub-index, bits, name, data type).
fn pdo(
    out: &mut String,
    kind: &str,
    sm: u8,
    index: u16,
    name: &str,
    entries: &[(u16, u8, u8, &str, &str)],
) {
    use std::fmt::Write as _;
    let _ = writeln!(
        out,
        "        <{kind} Fixed=\"true\" Mandatory=\"true\" Sm=\"{sm}\">"
    );
    let _ = writeln!(out, "          <Index>#x{index:04x}</Index>");
    let _ = writeln!(out, "          <Name><![CDATA[{name}]]></Name>");
    for (index, sub, bits, name, data_type) in entries {
        let _ = writeln!(
            out,
            "          <Entry>\n            <Index>#x{index:04x}</Index>\n            <SubIndex>{sub}</SubIndex>\n            <BitLen>{bits}</BitLen>\n            <Name><![CDATA[{name}]]></Name>\n            <DataType>{data_type}</DataType>\n          </Entry>"
        );
    }
    let _ = writeln!(out, "        </{kind}>");
}

/// The servo's fixed PDOs, as its SII would give them: command and
/// feedback of docs/servo.md in manufacturer-specific objects.
const SERVO_RX: [(u16, u8, u8, &str, &str); 3] = [
    (0x7000, 1, 32, "SSP", "DINT"),
    (0x7000, 2, 32, "SCW", "UDINT"),
    (0x7000, 3, 16, "Extra data code", "INT"),
];
const SERVO_TX: [(u16, u8, u8, &str, &str); 9] = [
    (0x6000, 1, 64, "ActPos", "LINT"),
    (0x6000, 2, 32, "SSW", "UDINT"),
    (0x6000, 3, 32, "SEW", "UDINT"),
    (0x6000, 4, 32, "Message code", "DINT"),
    (0x6000, 5, 32, "Message data", "REAL"),
    (0x6000, 6, 32, "Extra data 1", "REAL"),
    (0x6000, 7, 32, "Extra data 2", "REAL"),
    (0x6000, 8, 32, "Extra data 3", "REAL"),
    (0x6000, 9, 32, "Extra data 4", "REAL"),
];
const DRIVE_RX: [(u16, u8, u8, &str, &str); 3] = [
    (0x6040, 0, 16, "Controlword", "UINT"),
    (0x607A, 0, 32, "Target position", "DINT"),
    (0x6060, 0, 8, "Modes of operation", "SINT"),
];
const DRIVE_TX: [(u16, u8, u8, &str, &str); 3] = [
    (0x6041, 0, 16, "Statusword", "UINT"),
    (0x6064, 0, 32, "Position actual value", "DINT"),
    (0x6061, 0, 8, "Modes of operation display", "SINT"),
];

/// A sync manager in the ENI: number, type, size, start, control byte,
/// the PDO assigned to it.
type SmConfig = (u8, &'static str, u16, u16, u8, Option<u16>);
/// The servo's sync managers (no mailbox).
const SERVO_SMS: [SmConfig; 2] = [
    (0, "Outputs", 10, 0x1000, 0x64, Some(0x1600)),
    (1, "Inputs", 40, 0x1100, 0x20, Some(0x1A00)),
];
/// The CiA 402 drives' sync managers.
const DRIVE_SMS: [SmConfig; 4] = [
    (0, "MBoxOut", MBX_LEN as u16, MBX_OUT, 0x26, None),
    (1, "MBoxIn", MBX_LEN as u16, MBX_IN, 0x22, None),
    (2, "Outputs", 7, 0x1100, 0x64, Some(0x1600)),
    (3, "Inputs", 7, 0x1180, 0x20, Some(0x1A00)),
];

/// Where the LRW's data sits in TwinCAT's process images: after the
/// Ethernet header, the EtherCAT header and the datagram header.
const IMAGE_OFFSET: usize = 26;

/// The ENI of the network (ETG.2100 `EtherCATConfig`, as TwinCAT exports
/// it; numbers in decimal, object indices and identities as `#x…`).
#[must_use]
pub fn eni_xml() -> String {
    use std::fmt::Write as _;
    let mut x = String::with_capacity(32 * 1024);
    x.push_str("<?xml version=\"1.0\" encoding=\"ISO-8859-1\"?>\n");
    x.push_str("<EtherCATConfig xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" xsi:noNamespaceSchemaLocation=\"EtherCATConfig.xsd\" Version=\"1.3\">\n");
    x.push_str("  <Config>\n    <Master>\n      <Info>\n");
    x.push_str("        <Name><![CDATA[Device 1 (EtherCAT)]]></Name>\n");
    x.push_str("        <Destination>ffffffffffff</Destination>\n");
    let _ = writeln!(x, "        <Source>{}</Source>", hex(&MASTER_MAC));
    x.push_str("        <EtherType>a488</EtherType>\n      </Info>\n");
    x.push_str("      <MailboxStates>\n        <StartAddr>");
    let _ = write!(x, "{}", LOGICAL + IMAGE_LEN as u32 - 1);
    x.push_str("</StartAddr>\n        <Count>1</Count>\n      </MailboxStates>\n    </Master>\n");

    let outputs_start = [0usize, 10, 17];
    let inputs_start = [24usize, 64, 71];
    for (position, station) in STATIONS.into_iter().enumerate() {
        let servo = station == SERVO;
        let (vendor, product) = if servo {
            SERVO_IDENTITY
        } else {
            DRIVE_IDENTITY
        };
        let name = match station {
            SERVO => "Servo 1 (SE80)",
            DRIVE_A => "Drive 2 (CiA 402)",
            _ => "Drive 3 (CiA 402)",
        };
        let (out_len, in_len) = if servo { (10usize, 40usize) } else { (7, 7) };
        x.push_str("    <Slave>\n      <Info>\n");
        let _ = writeln!(x, "        <Name><![CDATA[{name}]]></Name>");
        let _ = writeln!(x, "        <PhysAddr>{station}</PhysAddr>");
        let _ = writeln!(
            x,
            "        <AutoIncAddr>{}</AutoIncAddr>",
            (position as u16).wrapping_neg()
        );
        x.push_str("        <Physics>YY</Physics>\n");
        let _ = writeln!(x, "        <VendorId>#x{vendor:08x}</VendorId>");
        let _ = writeln!(x, "        <ProductCode>#x{product:08x}</ProductCode>");
        x.push_str("        <RevisionNo>#x00000001</RevisionNo>\n        <SerialNo>#x00000000</SerialNo>\n");
        x.push_str("      </Info>\n      <ProcessData>\n");
        let _ = writeln!(
            x,
            "        <Send>\n          <BitStart>{}</BitStart>\n          <BitLength>{}</BitLength>\n        </Send>",
            (IMAGE_OFFSET + outputs_start[position]) * 8,
            out_len * 8
        );
        let _ = writeln!(
            x,
            "        <Recv>\n          <BitStart>{}</BitStart>\n          <BitLength>{}</BitLength>\n        </Recv>",
            (IMAGE_OFFSET + inputs_start[position]) * 8,
            in_len * 8
        );
        let sms: &[SmConfig] = if servo { &SERVO_SMS } else { &DRIVE_SMS };
        for &(n, kind, size, start, control, pdo) in sms {
            let _ = writeln!(x, "        <Sm{n}>\n          <Type>{kind}</Type>\n          <DefaultSize>{size}</DefaultSize>\n          <StartAddress>#x{start:04x}</StartAddress>\n          <ControlByte>#x{control:02x}</ControlByte>\n          <Enable>true</Enable>");
            if let Some(pdo) = pdo {
                let _ = writeln!(x, "          <Pdo>#x{pdo:04x}</Pdo>");
            }
            let _ = writeln!(x, "        </Sm{n}>");
        }
        let (rx_sm, tx_sm) = if servo { (0, 1) } else { (2, 3) };
        if servo {
            pdo(&mut x, "RxPdo", rx_sm, 0x1600, "Command", &SERVO_RX);
            pdo(&mut x, "TxPdo", tx_sm, 0x1A00, "Feedback", &SERVO_TX);
        } else {
            pdo(&mut x, "RxPdo", rx_sm, 0x1600, "Outputs", &DRIVE_RX);
            pdo(&mut x, "TxPdo", tx_sm, 0x1A00, "Inputs", &DRIVE_TX);
        }
        x.push_str("      </ProcessData>\n");

        // InitCmds: the station address, the sync managers and FMMUs, the
        // AL state requests.
        x.push_str("      <InitCmds>\n");
        {
            let _ = writeln!(
                x,
                "        <InitCmd>\n          <Transition>IP</Transition>\n          <Comment><![CDATA[set physical address]]></Comment>\n          <Requires>cycle</Requires>\n          <Cmd>{APWR}</Cmd>\n          <Adp>{}</Adp>\n          <Ado>16</Ado>\n          <Data>{}</Data>\n          <Cnt>1</Cnt>\n          <Retries>3</Retries>\n        </InitCmd>",
                (position as u16).wrapping_neg(),
                hex(&station.to_le_bytes())
            );
        }
        if !servo {
            let mut mailbox_sms = sm(MBX_OUT, MBX_LEN as u16, 0x26).to_vec();
            mailbox_sms.extend_from_slice(&sm(MBX_IN, MBX_LEN as u16, 0x22));
            write_cmd(
                &mut x,
                "IP",
                "set sm 0 and 1 (mailbox)",
                station,
                0x0800,
                &mailbox_sms,
            );
        }
        al_init_cmds(&mut x, "IP", "pre-op", station, PREOP);
        for &(n, _, size, start, control, pdo) in sms {
            if pdo.is_some() {
                write_cmd(
                    &mut x,
                    "PS",
                    &format!("set sm {n}"),
                    station,
                    0x0800 + 8 * u16::from(n),
                    &sm(start, size, control),
                );
            }
        }
        let mut fmmus = vec![
            fmmu(
                LOGICAL + outputs_start[position] as u32,
                out_len as u16,
                (0, 7),
                if servo { 0x1000 } else { 0x1100 },
                0,
                2,
            ),
            fmmu(
                LOGICAL + inputs_start[position] as u32,
                in_len as u16,
                (0, 7),
                if servo { 0x1100 } else { 0x1180 },
                0,
                1,
            ),
        ];
        if station == DRIVE_A {
            fmmus.push(fmmu(LOGICAL + 78, 1, (0, 0), 0x080D, 3, 1));
        }
        for (n, bytes) in fmmus.iter().enumerate() {
            write_cmd(
                &mut x,
                "PS",
                &format!("set fmmu {n}"),
                station,
                0x0600 + 16 * n as u16,
                bytes,
            );
        }
        al_init_cmds(&mut x, "PS", "safe-op", station, SAFEOP);
        al_init_cmds(&mut x, "SO", "op", station, OP);
        x.push_str("      </InitCmds>\n");

        if !servo {
            x.push_str("      <Mailbox DataLinkLayer=\"true\">\n");
            let _ = writeln!(x, "        <Send>\n          <Start>{MBX_OUT}</Start>\n          <Length>{MBX_LEN}</Length>\n        </Send>");
            let _ = write!(x, "        <Recv>\n          <Start>{MBX_IN}</Start>\n          <Length>{MBX_LEN}</Length>\n");
            if station == DRIVE_A {
                let _ = writeln!(
                    x,
                    "          <StatusBitAddr>{}</StatusBitAddr>",
                    (IMAGE_OFFSET + 78) * 8
                );
            } else {
                x.push_str("          <PollTime>20</PollTime>\n");
            }
            x.push_str("        </Recv>\n        <Protocol>CoE</Protocol>\n");
            let complete = station == DRIVE_B;
            let _ = writeln!(x, "        <CoE>\n          <InitCmds>");
            let mut coe = |comment: String, index: u16, sub: u8, data: Vec<u8>| {
                let ca = if complete {
                    " CompleteAccess=\"true\""
                } else {
                    ""
                };
                let _ = writeln!(
                    x,
                    "            <InitCmd Fixed=\"true\"{ca}>\n              <Transition>PS</Transition>\n              <Comment><![CDATA[{comment}]]></Comment>\n              <Timeout>0</Timeout>\n              <Ccs>1</Ccs>\n              <Index>#x{index:04x}</Index>\n              <SubIndex>{sub}</SubIndex>\n              <Data>{}</Data>\n            </InitCmd>",
                    hex(&data)
                );
            };
            for (assign, pdo_index, mapping, what) in [
                (0x1C12u16, 0x1600u16, RX_MAPPING, "RxPDO"),
                (0x1C13, 0x1A00, TX_MAPPING, "TxPDO"),
            ] {
                if complete {
                    coe(
                        format!("clear sm pdos (#x{assign:04x})"),
                        assign,
                        0,
                        complete_data(&[], 1),
                    );
                    coe(
                        format!("download pdo #x{pdo_index:04x} entries"),
                        pdo_index,
                        0,
                        complete_data(&mapping, 4),
                    );
                    coe(
                        format!("download pdo #x{assign:04x} index"),
                        assign,
                        0,
                        complete_data(&[u32::from(pdo_index)], 2),
                    );
                } else {
                    coe(
                        format!("clear sm pdos (#x{assign:04x})"),
                        assign,
                        0,
                        vec![0],
                    );
                    coe(
                        format!("clear pdo #x{pdo_index:04x} entries"),
                        pdo_index,
                        0,
                        vec![0],
                    );
                    for (n, entry) in mapping.iter().enumerate() {
                        coe(
                            format!("download pdo #x{pdo_index:04x} entry"),
                            pdo_index,
                            n as u8 + 1,
                            entry.to_le_bytes().to_vec(),
                        );
                    }
                    coe(
                        format!("download pdo #x{pdo_index:04x} entry count"),
                        pdo_index,
                        0,
                        vec![3],
                    );
                    coe(
                        format!("download pdo #x{assign:04x} index ({what})"),
                        assign,
                        1,
                        pdo_index.to_le_bytes().to_vec(),
                    );
                    coe(
                        format!("download pdo #x{assign:04x} count"),
                        assign,
                        0,
                        vec![1],
                    );
                }
            }
            x.push_str("          </InitCmds>\n        </CoE>\n      </Mailbox>\n");
        }
        x.push_str("    </Slave>\n");
    }

    // The cyclic frame: the LRW and the BRD of AL status.
    let brd_offset = IMAGE_OFFSET + IMAGE_LEN + 2 + 10;
    let _ = writeln!(
        x,
        "    <Cyclic>\n      <CycleTime>1000</CycleTime>\n      <Frame>\n        <Cmd>\n          <State>SAFEOP</State>\n          <State>OP</State>\n          <Comment><![CDATA[cyclic process data]]></Comment>\n          <Cmd>{LRW}</Cmd>\n          <Addr>{LOGICAL}</Addr>\n          <DataLength>{IMAGE_LEN}</DataLength>\n          <Cnt>{LRW_WKC}</Cnt>\n          <InputOffs>{IMAGE_OFFSET}</InputOffs>\n          <OutputOffs>{IMAGE_OFFSET}</OutputOffs>\n        </Cmd>\n        <Cmd>\n          <State>PREOP</State>\n          <State>SAFEOP</State>\n          <State>OP</State>\n          <Comment><![CDATA[AL status]]></Comment>\n          <Cmd>{BRD}</Cmd>\n          <Adp>0</Adp>\n          <Ado>304</Ado>\n          <DataLength>2</DataLength>\n          <Cnt>3</Cnt>\n          <InputOffs>{brd_offset}</InputOffs>\n          <OutputOffs>{brd_offset}</OutputOffs>\n        </Cmd>\n      </Frame>\n    </Cyclic>"
    );

    // The process image: every variable, at its bit in the images.
    let image_size = brd_offset + 2;
    x.push_str("    <ProcessImage>\n");
    for (section, tx) in [("Inputs", true), ("Outputs", false)] {
        let _ = writeln!(
            x,
            "      <{section}>\n        <ByteSize>{image_size}</ByteSize>"
        );
        for (position, station) in STATIONS.into_iter().enumerate() {
            let name = match station {
                SERVO => "Servo 1 (SE80)",
                DRIVE_A => "Drive 2 (CiA 402)",
                _ => "Drive 3 (CiA 402)",
            };
            let entries: &[(u16, u8, u8, &str, &str)] = match (station == SERVO, tx) {
                (true, true) => &SERVO_TX,
                (true, false) => &SERVO_RX,
                (false, true) => &DRIVE_TX,
                (false, false) => &DRIVE_RX,
            };
            let start = if tx {
                inputs_start[position]
            } else {
                outputs_start[position]
            };
            let mut bit = (IMAGE_OFFSET + start) * 8;
            for (_, _, bits, entry, data_type) in entries {
                let _ = writeln!(
                    x,
                    "        <Variable>\n          <Name>{name}.{section}.{entry}</Name>\n          <DataType>{data_type}</DataType>\n          <BitSize>{bits}</BitSize>\n          <BitOffs>{bit}</BitOffs>\n        </Variable>"
                );
                bit += usize::from(*bits);
            }
        }
        if tx {
            let _ = writeln!(
                x,
                "        <Variable>\n          <Name>Drive 2 (CiA 402).InfoData.MailboxFull</Name>\n          <DataType>BOOL</DataType>\n          <BitSize>1</BitSize>\n          <BitOffs>{}</BitOffs>\n        </Variable>",
                (IMAGE_OFFSET + 78) * 8
            );
        }
        let _ = writeln!(x, "      </{section}>");
    }
    x.push_str("    </ProcessImage>\n  </Config>\n</EtherCATConfig>\n");
    x
}
