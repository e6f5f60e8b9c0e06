//! What a port's traffic tells of its slaves (docs/ethercat.md#slaves):
//! station addresses, AL states, SII words, sync managers and the mailbox
//! messages they carry. Read from the copies that prove a datagram was
//! delivered: a write's or a read's returned copy with a working counter of
//! at least 1.

use crate::decoder::cia402::DriveState;
use crate::ethercat::register::{self, covered};
use crate::ethercat::{
    Addressing, AlStatus, AlStatusCode, CoeHeader, CoeSdo, CoeService, Command, Datagram, Fmmu,
    MailboxHeader, MailboxType, SyncManager, SyncManagerMode, COE_HEADER_LEN, FMMU_LEN,
    MAILBOX_HEADER_LEN, SYNC_MANAGER_LEN,
};
use crate::profiles::Profile;
use crate::servo::{Command as ServoCommand, Feedback};

use super::coe::{CoeChannel, CoeSdoStep};
use super::config::SlaveConfig;
use super::dc::DcRegisters;
use super::image::{CoeObjects, Plan, CIA402_OBJECTS};
use super::missing::{missed, Missed, Watch};
use super::problem::{ImageError, ImageProblem};
use super::process::{ProcessData, ServoSlaves, ServoWatch};
use super::sii::SiiImage;
use super::slave::SlaveRef;
use crate::can::Timestamp;
use crate::logs::Position;

/// The sync managers a slave has at most (ESC datasheet: 16; the
/// configuration the tests see uses 4).
const SYNC_MANAGERS: usize = 16;
/// A mailbox area is at 0x1000 or above (the ESC's process memory).
const PROCESS_MEMORY: u16 = 0x1000;
/// The SII control word's read command (bit 8) and busy flag (bit 15).
const SII_READ: u16 = 0x0100;
/// The SII control word's busy flag.
const SII_BUSY: u16 = 0x8000;
/// Kollmorgen's EtherCAT vendor id.
const AKD_VENDOR: u32 = 0x0000_006A;
/// The AKD's product code (`AKD` in ASCII).
const AKD_PRODUCT: u32 = 0x0041_4B44;

/// The error counters' registers: 0x0300 to 0x0313.
pub const ERROR_COUNTERS_LEN: usize = 0x14;

/// Which register an AL state meaning was read from or written to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum AlRegister {
    /// AL control 0x0120: the state the master requests (bit 4: error
    /// acknowledge).
    Control,
    /// AL status 0x0130: the state the slave is in (bit 4: error).
    Status,
    /// AL status code 0x0134 read alone.
    StatusCode,
}

impl AlRegister {
    /// Return the register's name as the records write it: `al_control`,
    /// `al_status`, `al_status_code`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            AlRegister::Control => "al_control",
            AlRegister::Status => "al_status",
            AlRegister::StatusCode => "al_status_code",
        }
    }
}

/// A slave's identity words of its SII (ETG.2010 table 2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SiiField {
    /// Words 0x08–0x09: the vendor id.
    Vendor,
    /// Words 0x0A–0x0B: the product code.
    Product,
    /// Words 0x0C–0x0D: the revision.
    Revision,
    /// Words 0x0E–0x0F: the serial number.
    Serial,
}

impl SiiField {
    /// Return the field the double word at `word` is, if it is one.
    #[must_use]
    pub const fn at(word: u32) -> Option<Self> {
        Some(match word {
            0x08 => SiiField::Vendor,
            0x0A => SiiField::Product,
            0x0C => SiiField::Revision,
            0x0E => SiiField::Serial,
            _ => return None,
        })
    }

    /// Return the field's name: `vendor`, `product`, `revision`, `serial`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            SiiField::Vendor => "vendor",
            SiiField::Product => "product",
            SiiField::Revision => "revision",
            SiiField::Serial => "serial",
        }
    }
}

/// Something a datagram tells of the slaves (docs/ethercat.md#slaves).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Meaning<'a> {
    /// The master gave the slave at a position its station address
    /// (APWR 0x0010).
    StationAddress {
        /// The slave, with both.
        slave: SlaveRef,
    },
    /// An AL register of one slave, read or written.
    AlState {
        /// The slave.
        slave: SlaveRef,
        /// The register.
        register: AlRegister,
        /// AL control or status as written or read (`None` for the code
        /// read alone).
        status: Option<AlStatus>,
        /// The AL status code, where the datagram covers 0x0134.
        code: Option<AlStatusCode>,
    },
    /// A broadcast read of AL status: the OR of every slave's state, and
    /// how many slaves answered. Never one slave's.
    BroadcastAlStatus {
        /// The ORed status.
        status: AlStatus,
        /// The working counter: the slaves that answered.
        answered: u16,
    },
    /// A double word of a slave's SII read (4 bytes at a word address).
    Sii {
        /// The slave.
        slave: SlaveRef,
        /// The word address.
        word: u32,
        /// The value, little-endian.
        value: u32,
    },
    /// The DL status register 0x0110 of one slave as read: the low byte
    /// (PDI, watchdog, physical link per port in bits 4–7) and the high
    /// byte (loop closed and communication per port, two bits each), each
    /// where the read covers it (TwinCAT reads 0x0111 alone).
    DlStatus {
        /// The slave.
        slave: SlaveRef,
        /// Byte 0x0110.
        low: Option<u8>,
        /// Byte 0x0111.
        high: Option<u8>,
    },
    /// The error counters 0x0300–0x0313 of one slave as read, each byte
    /// where the read covers it (docs/ethercat.md#error-counters).
    ErrorCounters {
        /// The slave.
        slave: SlaveRef,
        /// Bytes 0x0300 to 0x0313.
        bytes: [Option<u8>; ERROR_COUNTERS_LEN],
    },
    /// A mailbox message written to a slave or read from it.
    Mailbox {
        /// The slave.
        slave: SlaveRef,
        /// Written by the master (`true`) or read from the slave.
        written: bool,
        /// Whether the slave took it: a write whose returned copy has
        /// working counter 0 was not accepted (the master repeats it).
        accepted: bool,
        /// Whether the area was guessed (no sync-manager configuration
        /// seen for the slave; docs/ethercat.md#mailbox).
        guessed: bool,
        /// Whether it is a message read again after the master's repeat
        /// request, with the counter of the message read before it: the
        /// same message, counted once (docs/ethercat.md#mailbox-repeat).
        repeated: bool,
        /// The header.
        header: MailboxHeader,
        /// The message's body (after the header), as far as the datagram
        /// holds it.
        body: &'a [u8],
        /// The profile that reads the slave's CoE emergencies: the AKD's
        /// for a slave whose SII says Kollmorgen (vendor 0x6A) AKD (product
        /// 0x414B44), else CiA 301's (docs/ethercat.md#coe).
        profile: Profile,
        /// For a CoE SDO message the slave took (a write with working
        /// counter 1, a read), what it is in the slave's transfer
        /// (docs/ethercat.md#coe-sdo).
        sdo: Option<CoeSdoStep>,
    },
    /// A read of the status byte of a slave's mailbox-in sync manager
    /// (SM1's 0x080D): the master polls it for a message
    /// (docs/ethercat.md#mailbox-repeat).
    MailboxPoll {
        /// The slave.
        slave: SlaveRef,
        /// Bit 3: the mailbox is full, a message waits.
        full: bool,
    },
    /// The mailbox repeat protocol: the master toggles bit 1 of the
    /// mailbox-in sync manager's activate byte (SM1's 0x080E) to ask for
    /// the last message again; the slave acknowledges with the same bit of
    /// its PDI control byte (0x080F) (docs/ethercat.md#mailbox-repeat).
    MailboxRepeat {
        /// The slave.
        slave: SlaveRef,
        /// `false` for the request (written), `true` for the acknowledge
        /// (read, the first that matches the request).
        acknowledged: bool,
    },
    /// The station alias (0x0012) read or written, or DL control's alias
    /// bit (0x0103 bit 0) read or written; a BWR of 0x0103 sets the bit of
    /// every slave and names none (docs/ethercat.md#alias).
    StationAlias {
        /// The slave (neither station nor position for a BWR).
        slave: SlaveRef,
        /// The alias, where the datagram covers 0x0012.
        alias: Option<u16>,
        /// Whether FPxx reach the slave by its alias, where the datagram
        /// covers 0x0103.
        enabled: Option<bool>,
    },
    /// Distributed-clock registers of one slave, read or written
    /// (docs/ethercat.md#dc).
    Dc {
        /// The slave.
        slave: SlaveRef,
        /// Written by the master (`true`) or read.
        written: bool,
        /// The registers the datagram covers.
        registers: DcRegisters,
    },
    /// The cyclic distribution of the reference clock's system time: an
    /// ARMW or FRMW of 0x0910 reads it from the addressed slave and writes
    /// it to every slave after (docs/ethercat.md#dc).
    DcDistribution {
        /// The reference clock: the addressed slave.
        slave: SlaveRef,
        /// Its system time as read (the low 32 bits for a 4-byte datagram).
        system_time: Option<u64>,
        /// The working counter.
        wkc: u16,
    },
}

/// What the port's traffic has shown of one slave.
#[derive(Debug, Clone, Default)]
struct Slave {
    station: Option<u16>,
    position: Option<u16>,
    /// The word address of the last SII read command.
    sii_address: Option<u32>,
    sync_managers: [Option<SyncManager>; SYNC_MANAGERS],
    fmmus: [Option<Fmmu>; SYNC_MANAGERS],
    vendor: Option<u32>,
    product: Option<u32>,
    /// Its SII words as read.
    sii: SiiImage,
    /// What its registers say of its taking part in the cycles.
    watch: Watch,
    /// Its CoE SDO transfers.
    channel: CoeChannel,
    /// The PDO objects its CoE transfers showed.
    coe: CoeObjects,
    /// What a configuration file gives of it.
    given: Option<SlaveConfig>,
    /// How its process data is cut; `None` until needed after a change.
    plan: Option<Plan>,
    /// The last outputs and inputs images cut.
    outputs: Vec<u8>,
    inputs: Vec<u8>,
    /// Its CiA 402 state machine as observed.
    drive: DriveState,
    /// Its servo handshakes, when it is read as a servo.
    servo: Option<ServoWatch>,
    /// Its station alias (0x0012) as read.
    alias: Option<u16>,
    /// DL control's alias bit as last written or read to it alone.
    alias_enabled: Option<bool>,
    /// Its mailbox's repeat protocol.
    repeat: Repeat,
}

/// Where a slave's mailbox repeat protocol stands
/// (docs/ethercat.md#mailbox-repeat).
#[derive(Debug, Clone, Copy, Default)]
struct Repeat {
    /// Bit 1 of the mailbox-in sync manager's activate byte as last
    /// written or read.
    request_bit: Option<bool>,
    /// A request waits for its message.
    pending: bool,
    /// The request's acknowledge was said.
    acknowledged: bool,
    /// The last message read: its counter and type.
    last: Option<(u8, MailboxType)>,
}

impl Slave {
    fn reference(&self) -> SlaveRef {
        SlaveRef {
            station: self.station,
            position: self.position,
        }
    }

    /// The mailbox area written (`true`) or read at `ado`, if a configured
    /// sync manager starts there.
    fn mailbox_at(&self, ado: u16) -> Option<(bool, u16)> {
        self.sync_managers
            .iter()
            .flatten()
            .find(|sm| sm.mode() == SyncManagerMode::Mailbox && sm.start == ado)
            .map(|sm| (sm.written_by_master(), sm.len))
    }

    /// The first register of the sync manager the master reads messages
    /// from (SM1 where none is known).
    fn mailbox_in_base(&self) -> u16 {
        let n = self
            .sync_managers
            .iter()
            .position(|sm| {
                sm.is_some_and(|sm| {
                    sm.mode() == SyncManagerMode::Mailbox && !sm.written_by_master()
                })
            })
            .unwrap_or(1);
        register::SYNC_MANAGER_BASE + (n * SYNC_MANAGER_LEN) as u16
    }

    fn has_mailbox(&self) -> bool {
        self.sync_managers
            .iter()
            .flatten()
            .any(|sm| sm.mode() == SyncManagerMode::Mailbox)
    }

    /// The profile its identity names.
    fn profile(&self) -> Profile {
        match (self.vendor, self.product) {
            (Some(AKD_VENDOR), Some(AKD_PRODUCT)) => Profile::Akd,
            _ => Profile::Generic,
        }
    }
}

/// The slaves of one port.
#[derive(Debug, Default)]
pub(super) struct Network {
    slaves: Vec<Slave>,
    /// The slaves a datagram touches, reused.
    touched: Vec<(usize, u16)>,
    /// What the working counter says of each, reused.
    missed: Vec<Missed>,
    /// Problems not taken yet.
    problems: Vec<ImageProblem>,
    /// Problems past [`PROBLEMS_KEPT`].
    problems_dropped: u64,
    /// DL control's alias bit as a BWR of 0x0103 last set it for every
    /// slave.
    alias_broadcast: Option<bool>,
}

/// The problems a network keeps between two takes; more are counted.
pub(super) const PROBLEMS_KEPT: usize = 100;

impl Network {
    /// Take what a configuration file says of the slaves: each is found
    /// by station address or position (added when new), and the capture's
    /// own start-up wins for what it writes.
    pub(super) fn configure(&mut self, slaves: &[SlaveConfig]) {
        for config in slaves {
            let at = match (config.station, config.position) {
                (Some(station), Some(position)) => {
                    let at = self.at_position(position);
                    self.assign(at, station)
                }
                (Some(station), None) => self.at_station(station),
                (None, Some(position)) => self.at_position(position),
                (None, None) => continue,
            };
            let known = &mut self.slaves[at];
            for &(n, fmmu) in &config.fmmus {
                if let Some(slot) = known.fmmus.get_mut(usize::from(n)) {
                    slot.get_or_insert(fmmu);
                }
            }
            for &(n, sm) in &config.sync_managers {
                if let Some(slot) = known.sync_managers.get_mut(usize::from(n)) {
                    slot.get_or_insert(sm);
                }
            }
            known.vendor = known.vendor.or(config.vendor);
            known.product = known.product.or(config.product);
            known.given = Some(config.clone());
            known.plan = None;
        }
    }

    /// Cut a cyclic datagram (LRW, LRD, LWR at `logical`) into each
    /// slave's process data: outputs from `sent` (the sent copy's data,
    /// `None` without one), inputs from `returned`; hand each to `on`
    /// (docs/ethercat.md#process-data).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn process_data(
        &mut self,
        command: Command,
        logical: u32,
        sent: Option<&[u8]>,
        returned: &[u8],
        wkc: u16,
        servos: &ServoSlaves,
        position: Position,
        mut on: impl FnMut(&ProcessData<'_>),
    ) {
        let end = logical.saturating_add(returned.len() as u32);
        let mut touched = core::mem::take(&mut self.touched);
        touched.clear();
        let mut expected: u16 = 0;
        let mut planned = false;
        for i in 0..self.slaves.len() {
            let slave = &mut self.slaves[i];
            if slave.fmmus.iter().all(Option::is_none) {
                continue;
            }
            if slave.plan.is_none() {
                // The layout's sources after the capture's own start-up:
                // a configuration file's, then the SII's.
                let sii = slave.sii.layout();
                let given: Vec<&SlaveConfig> = slave.given.iter().chain(sii.as_ref()).collect();
                let plan = Plan::new(&slave.fmmus, &slave.sync_managers, &slave.coe, &given);
                let reference = slave.reference();
                for error in plan.too_long.clone() {
                    self.problem(position, reference, error);
                }
                self.slaves[i].plan = Some(plan);
                planned = true;
            }
            let Some(plan) = self.slaves[i].plan.as_ref() else {
                continue;
            };
            if plan.touches(logical, end) {
                let share = plan.share(command, logical, end);
                expected = expected.saturating_add(share);
                touched.push((i, share));
            }
        }
        if touched.is_empty() {
            on(&ProcessData {
                slave: None,
                logical,
                wkc,
                expected_wkc: None,
                confirmed: wkc > 0,
                missed: Missed::No,
                outputs: matches!(command, Command::Lrw | Command::Lwr)
                    .then_some(sent.unwrap_or(returned)),
                inputs: matches!(command, Command::Lrw | Command::Lrd).then_some(returned),
                cia402: None,
                servo: None,
                plan: None,
            });
            self.touched = touched;
            return;
        }
        if planned {
            self.overlaps(&touched, position);
        }
        let mut verdicts = core::mem::take(&mut self.missed);
        missed(
            &touched,
            |i| &self.slaves[i].watch,
            expected,
            wkc,
            &mut verdicts,
        );
        for (&(i, _), &missed) in touched.iter().zip(&verdicts) {
            let confirmed = missed.confirmed();
            let slave = &mut self.slaves[i];
            if wkc >= expected {
                slave.watch.whole();
            }
            let reference = slave.reference();
            let Slave {
                plan,
                outputs,
                inputs,
                drive,
                servo,
                ..
            } = slave;
            let Some(plan) = plan.as_ref() else { continue };
            let (held_out, held_in) =
                plan.cut(logical, sent.unwrap_or(returned), returned, outputs, inputs);
            let (out_len, in_len) = plan.lens();
            // An LRD writes no outputs, an LWR reads no inputs: the
            // datagram does not hold that half whatever bytes it has there.
            let outputs = (matches!(command, Command::Lrw | Command::Lwr)
                && out_len > 0
                && held_out == out_len)
                .then_some(&outputs[..]);
            let inputs =
                (matches!(command, Command::Lrw | Command::Lrd) && in_len > 0 && held_in == in_len)
                    .then_some(&inputs[..]);
            let mut cia402 = None;
            if plan.maps_cia402() {
                // The CiA 402 objects of the cycle, without an allocation:
                // a drive maps each at most once or twice.
                let mut picked = [None; 8];
                let mut n = 0;
                let mut pick =
                    |_: &str, signal: Result<crate::canopen::Signal, crate::CodecError>| {
                        if let Ok(signal) = signal {
                            if CIA402_OBJECTS.contains(&signal.entry.index()) && n < picked.len() {
                                picked[n] = Some(signal);
                                n += 1;
                            }
                        }
                    };
                if let Some(image) = outputs {
                    plan.for_each_signal(true, image, &mut pick);
                }
                if let (Some(image), true) = (inputs, confirmed) {
                    plan.for_each_signal(false, image, &mut pick);
                }
                if n > 0 {
                    cia402 = drive.read(picked[..n].iter().flatten());
                }
            }
            let mut servo_reading = None;
            if let Some(mode) = servos.mode(reference.station, (out_len, in_len)) {
                let watch = servo.get_or_insert_with(|| ServoWatch::new(mode));
                if let Some(command) = outputs.and_then(|o| ServoCommand::parse(o).ok()) {
                    let feedback = inputs
                        .filter(|_| confirmed)
                        .and_then(|i| Feedback::parse(i).ok());
                    servo_reading = Some(watch.cycle(&command, feedback.as_ref()));
                }
            }
            on(&ProcessData {
                slave: Some(reference),
                logical,
                wkc,
                expected_wkc: Some(expected),
                confirmed,
                missed,
                outputs,
                inputs,
                cia402,
                servo: servo_reading,
                plan: Some(plan),
            });
        }
        self.touched = touched;
        self.missed = verdicts;
    }

    /// Say the output ranges two slaves of a datagram both map.
    fn overlaps(&mut self, touched: &[(usize, u16)], position: Position) {
        let mut found = Vec::new();
        for (k, &(a, _)) in touched.iter().enumerate() {
            for &(b, _) in &touched[k + 1..] {
                let (Some(pa), Some(pb)) = (&self.slaves[a].plan, &self.slaves[b].plan) else {
                    continue;
                };
                if let Some((start, end)) = pa.output_overlap(pb) {
                    found.push((a, b, start, end));
                }
            }
        }
        for (a, b, start, end) in found {
            let other = self.slaves[b].reference();
            let error = ImageError::OverlappingFmmus { other, start, end };
            self.problem(position, self.slaves[a].reference(), error);
        }
    }

    /// Take the problems said since the last call, and how many more
    /// were not kept.
    pub(super) fn take_problems(&mut self) -> (Vec<ImageProblem>, u64) {
        (
            core::mem::take(&mut self.problems),
            core::mem::take(&mut self.problems_dropped),
        )
    }

    /// Return whether a problem was said since the last take.
    #[inline]
    pub(super) fn has_problems(&self) -> bool {
        !self.problems.is_empty() || self.problems_dropped > 0
    }

    /// Keep a problem (at most [`PROBLEMS_KEPT`] between two takes).
    fn problem(&mut self, position: Position, slave: SlaveRef, error: ImageError) {
        if self.problems.len() < PROBLEMS_KEPT {
            self.problems.push(ImageProblem {
                position,
                slave,
                error,
            });
        } else {
            self.problems_dropped += 1;
        }
    }
    /// the slaves; `sent_adp` is the ADP it was sent with (a
    /// position-addressed datagram's position is its negation).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn datagram<'a>(
        &mut self,
        position: Position,
        timestamp: Option<Timestamp>,
        returned: bool,
        datagram: &Datagram<'a>,
        sent_adp: Option<u16>,
        mut on: impl FnMut(Meaning<'a>),
    ) {
        // Only a copy that came back proves what the slaves did.
        if !returned {
            return;
        }
        let command = datagram.command();
        let wkc = datagram.working_counter();
        let ado = datagram.ado();
        let data = datagram.data();
        if command == Command::Brd {
            if let (Some(bytes), true) = (covered(ado, data, register::AL_STATUS, 2), wkc >= 1) {
                on(Meaning::BroadcastAlStatus {
                    status: AlStatus(u16::from_le_bytes([bytes[0], bytes[1]])),
                    answered: wkc,
                });
            }
            return;
        }
        if command == Command::Bwr && wkc >= 1 {
            if let Some(b) = covered(ado, data, register::DL_CONTROL_ALIAS, 1) {
                let enabled = b[0] & 0x01 != 0;
                self.alias_broadcast = Some(enabled);
                for slave in &mut self.slaves {
                    slave.alias_enabled = None;
                }
                on(Meaning::StationAlias {
                    slave: SlaveRef::default(),
                    alias: None,
                    enabled: Some(enabled),
                });
            }
            return;
        }
        if wkc == 0 {
            // An empty mailbox: what a repeat brings after it is news.
            if command == Command::Fprd {
                if let Some(at) = self.addressed(datagram.adp()) {
                    let known = &mut self.slaves[at];
                    if known.mailbox_at(ado).is_some_and(|(writes, _)| !writes) {
                        known.repeat.last = None;
                    }
                }
            }
            if !is_mailbox_write(command) {
                return;
            }
        }
        let slave = match command.addressing() {
            Addressing::Position => match sent_adp {
                Some(adp) => self.at_position(0u16.wrapping_sub(adp)),
                None => return,
            },
            Addressing::Station => match self.addressed(datagram.adp()) {
                Some(at) => at,
                None => self.at_station(datagram.adp()),
            },
            _ => return,
        };
        // A register is taken from a copy that proves it was delivered;
        // a mailbox write is recorded either way (refused when not).
        let delivered = wkc >= 1;
        let writes = command.writes() && delivered;
        let reads = command.reads() && delivered;
        // Station address: written by position.
        if writes && command.addressing() == Addressing::Position {
            if let Some(bytes) = covered(ado, data, register::STATION_ADDRESS, 2) {
                let station = u16::from_le_bytes([bytes[0], bytes[1]]);
                let at = self.assign(slave, station);
                on(Meaning::StationAddress {
                    slave: self.slaves[at].reference(),
                });
            }
        }
        let reference = self.slaves[slave].reference();
        if delivered {
            self.registers(slave, command, ado, data, wkc, &mut on);
        }
        if writes {
            if let Some(bytes) = covered(ado, data, register::AL_CONTROL, 2) {
                on(Meaning::AlState {
                    slave: reference,
                    register: AlRegister::Control,
                    status: Some(AlStatus(u16::from_le_bytes([bytes[0], bytes[1]]))),
                    code: None,
                });
            }
            self.sync_manager_writes(slave, ado, data);
            // The SII command: read, with the word address.
            if let (Some(control), Some(address)) = (
                covered(ado, data, register::SII_CONTROL, 2),
                covered(ado, data, register::SII_ADDRESS, 4),
            ) {
                if u16::from_le_bytes([control[0], control[1]]) & SII_READ != 0 {
                    self.slaves[slave].sii_address = Some(u32::from_le_bytes([
                        address[0], address[1], address[2], address[3],
                    ]));
                }
            }
        }
        if reads && !writes {
            let status = covered(ado, data, register::AL_STATUS, 2)
                .map(|b| AlStatus(u16::from_le_bytes([b[0], b[1]])));
            let code = covered(ado, data, register::AL_STATUS_CODE, 2)
                .map(|b| AlStatusCode(u16::from_le_bytes([b[0], b[1]])));
            if let Some(status) = status {
                self.slaves[slave].watch.al_status(status);
            }
            if status.is_some() || code.is_some() {
                on(Meaning::AlState {
                    slave: reference,
                    register: if status.is_some() {
                        AlRegister::Status
                    } else {
                        AlRegister::StatusCode
                    },
                    status,
                    code,
                });
            }
            self.sii_read(slave, ado, data, &mut on);
            let low = covered(ado, data, register::DL_STATUS, 1).map(|b| b[0]);
            let high = covered(ado, data, register::DL_STATUS + 1, 1).map(|b| b[0]);
            if let Some(low) = low {
                self.slaves[slave].watch.dl_status(low);
            }
            if low.is_some() || high.is_some() {
                on(Meaning::DlStatus {
                    slave: reference,
                    low,
                    high,
                });
            }
            let mut bytes = [None; ERROR_COUNTERS_LEN];
            for (i, byte) in bytes.iter_mut().enumerate() {
                *byte = covered(ado, data, register::RX_ERROR_COUNTERS + i as u16, 1).map(|b| b[0]);
            }
            if bytes.iter().any(Option::is_some) {
                self.slaves[slave].watch.error_counters(&bytes);
                on(Meaning::ErrorCounters {
                    slave: reference,
                    bytes,
                });
            }
        }
        if command.addressing() == Addressing::Station
            && (command == Command::Fpwr || command == Command::Fprd)
        {
            if let Some(mut meaning) =
                self.mailbox(position, slave, command == Command::Fpwr, datagram)
            {
                if let Meaning::Mailbox {
                    written,
                    accepted: true,
                    repeated: false,
                    header,
                    body,
                    ref mut sdo,
                    ..
                } = meaning
                {
                    *sdo = self.coe_message(slave, written, header, body, timestamp);
                    if let Some(error) = self.slaves[slave].coe.oversized.take() {
                        let reference = self.slaves[slave].reference();
                        self.problem(position, reference, error);
                    }
                }
                on(meaning);
            }
        }
    }

    /// A delivered mailbox message: a CoE SDO message steps the slave's
    /// transfer; a completed transfer of a PDO object teaches the slave's
    /// process image. Return the step.
    fn coe_message(
        &mut self,
        slave: usize,
        written: bool,
        header: MailboxHeader,
        body: &[u8],
        timestamp: Option<Timestamp>,
    ) -> Option<CoeSdoStep> {
        if header.mailbox_type != MailboxType::Coe {
            return None;
        }
        let coe = CoeHeader::parse(body).ok()?;
        // A request is the master's whatever its service, an answer the
        // slave's: real slaves abort in a message of the request service.
        let request = match coe.service {
            CoeService::SdoRequest | CoeService::SdoResponse => written,
            _ => return None,
        };
        let sdo = CoeSdo::parse(&body[COE_HEADER_LEN..]).ok()?;
        let known = &mut self.slaves[slave];
        let step = known.channel.message(request, &sdo, timestamp);
        if let Some(transfer) = &step.ended {
            if known.coe.transfer(transfer, &transfer.data) {
                known.plan = None;
            }
        }
        Some(step)
    }

    /// The slave an FPxx at `adp` reaches: the one of that station
    /// address, else the one whose enabled alias it is
    /// (docs/ethercat.md#alias).
    fn addressed(&self, adp: u16) -> Option<usize> {
        let broadcast = self.alias_broadcast;
        self.slaves
            .iter()
            .position(|s| s.station == Some(adp))
            .or_else(|| {
                self.slaves.iter().position(|s| {
                    s.alias == Some(adp) && s.alias_enabled.or(broadcast) == Some(true)
                })
            })
    }

    /// The station address of the slave an FPxx at `adp` reaches
    /// ([`addressed`](Self::addressed)); `adp` where no slave known by
    /// its station address answers to it.
    pub(super) fn station_reached(&self, adp: u16) -> u16 {
        self.addressed(adp)
            .and_then(|at| self.slaves[at].station)
            .unwrap_or(adp)
    }

    /// The registers of docs/ethercat.md#alias, #dc and #mailbox-repeat a
    /// delivered datagram covers.
    fn registers<'a>(
        &mut self,
        slave: usize,
        command: Command,
        ado: u16,
        data: &[u8],
        wkc: u16,
        on: &mut impl FnMut(Meaning<'a>),
    ) {
        let reads = command.reads();
        let writes = command.writes();
        let reference = self.slaves[slave].reference();
        if matches!(command, Command::Armw | Command::Frmw) {
            // The reference clock's time, every cycle: its own kind.
            if covered(ado, data, register::SYSTEM_TIME, 4).is_some() {
                let system_time = DcRegisters::covered(ado, data, true).and_then(|d| d.system_time);
                on(Meaning::DcDistribution {
                    slave: reference,
                    system_time,
                    wkc,
                });
            }
            return;
        }
        let alias = covered(ado, data, register::STATION_ALIAS, 2)
            .map(|b| u16::from_le_bytes([b[0], b[1]]));
        let enabled = covered(ado, data, register::DL_CONTROL_ALIAS, 1).map(|b| b[0] & 0x01 != 0);
        if alias.is_some() || enabled.is_some() {
            let known = &mut self.slaves[slave];
            known.alias = alias.or(known.alias);
            known.alias_enabled = enabled.or(known.alias_enabled);
            on(Meaning::StationAlias {
                slave: reference,
                alias,
                enabled,
            });
        }
        if let Some(registers) = DcRegisters::covered(ado, data, reads) {
            on(Meaning::Dc {
                slave: reference,
                written: !reads,
                registers,
            });
        }
        // The mailbox-in sync manager's status, activate and PDI control.
        let known = &mut self.slaves[slave];
        let base = known.mailbox_in_base();
        let status = base + register::SYNC_MANAGER_STATUS;
        let request_bit =
            covered(ado, data, base + register::SYNC_MANAGER_ACTIVATE, 1).map(|b| b[0] & 0x02 != 0);
        if writes && !reads {
            if let Some(bit) = request_bit {
                // A request writes the byte (SOEM with the status before
                // it); a write of the whole sync manager configures it.
                let toggled =
                    ado >= status && known.repeat.request_bit.is_some_and(|before| before != bit);
                known.repeat.request_bit = Some(bit);
                if toggled {
                    known.repeat.pending = true;
                    known.repeat.acknowledged = false;
                    on(Meaning::MailboxRepeat {
                        slave: reference,
                        acknowledged: false,
                    });
                }
            }
        } else if reads {
            known.repeat.request_bit = request_bit.or(known.repeat.request_bit);
            let ack = covered(ado, data, base + register::SYNC_MANAGER_PDI_CONTROL, 1)
                .map(|b| b[0] & 0x02 != 0);
            let repeat = &mut known.repeat;
            if repeat.pending && !repeat.acknowledged && ack.is_some() && ack == repeat.request_bit
            {
                repeat.acknowledged = true;
                on(Meaning::MailboxRepeat {
                    slave: reference,
                    acknowledged: true,
                });
            }
            // A poll reads the status byte, with at most the two after it.
            if ado == status && data.len() <= 3 {
                if let Some(b) = data.first() {
                    on(Meaning::MailboxPoll {
                        slave: reference,
                        full: b & 0x08 != 0,
                    });
                }
            }
        }
    }

    /// The slave at `position`, added when new.
    fn at_position(&mut self, position: u16) -> usize {
        match self
            .slaves
            .iter()
            .position(|s| s.position == Some(position))
        {
            Some(at) => at,
            None => {
                self.slaves.push(Slave {
                    position: Some(position),
                    ..Slave::default()
                });
                self.slaves.len() - 1
            }
        }
    }

    /// The slave of station address `station`, added when new.
    fn at_station(&mut self, station: u16) -> usize {
        match self.slaves.iter().position(|s| s.station == Some(station)) {
            Some(at) => at,
            None => {
                self.slaves.push(Slave {
                    station: Some(station),
                    ..Slave::default()
                });
                self.slaves.len() - 1
            }
        }
    }

    /// Give the slave at `at` (known by position) the station address
    /// `station`: a slave known by that station alone is the same one,
    /// and another that had it loses it. Return the slave's index.
    fn assign(&mut self, at: usize, station: u16) -> usize {
        for (i, other) in self.slaves.iter_mut().enumerate() {
            if i != at && other.station == Some(station) {
                other.station = None;
            }
        }
        self.slaves[at].station = Some(station);
        at
    }

    /// Keep the sync-manager and FMMU configuration a write covers.
    fn sync_manager_writes(&mut self, slave: usize, ado: u16, data: &[u8]) {
        let known = &mut self.slaves[slave];
        for n in 0..SYNC_MANAGERS {
            let base = register::SYNC_MANAGER_BASE + (n * SYNC_MANAGER_LEN) as u16;
            if let Some(b) = covered(ado, data, base, SYNC_MANAGER_LEN) {
                let mut bytes = [0; SYNC_MANAGER_LEN];
                bytes.copy_from_slice(b);
                let sm = SyncManager::from_bytes(bytes);
                if sm.mode() == SyncManagerMode::Mailbox && !sm.written_by_master() {
                    known.repeat.request_bit = Some(sm.activate & 0x02 != 0);
                }
                known.sync_managers[n] = Some(sm);
                known.plan = None;
            }
            let base = register::FMMU_BASE + (n * FMMU_LEN) as u16;
            if let Some(b) = covered(ado, data, base, FMMU_LEN) {
                let mut bytes = [0; FMMU_LEN];
                bytes.copy_from_slice(b);
                known.fmmus[n] = Some(Fmmu::from_bytes(bytes));
                known.plan = None;
            }
        }
    }

    /// The SII double words a read of the data register gives, with the
    /// interface idle (and, when the read covers it, the address read
    /// back): 4 bytes, or 8 (two double words) as TwinCAT reads them.
    fn sii_read<'a>(
        &mut self,
        slave: usize,
        ado: u16,
        data: &[u8],
        on: &mut impl FnMut(Meaning<'a>),
    ) {
        let Some(value) = covered(ado, data, register::SII_DATA, 4) else {
            return;
        };
        let control =
            covered(ado, data, register::SII_CONTROL, 2).map(|b| u16::from_le_bytes([b[0], b[1]]));
        if control.is_some_and(|c| c & SII_BUSY != 0) {
            return;
        }
        let word = match covered(ado, data, register::SII_ADDRESS, 4) {
            Some(b) => u32::from_le_bytes([b[0], b[1], b[2], b[3]]),
            None => match self.slaves[slave].sii_address {
                Some(word) => word,
                None => return,
            },
        };
        let second = covered(ado, data, register::SII_DATA + 4, 4);
        for (word, bytes) in [(Some(word), Some(value)), (word.checked_add(2), second)] {
            let (Some(word), Some(b)) = (word, bytes) else {
                continue;
            };
            let value = u32::from_le_bytes([b[0], b[1], b[2], b[3]]);
            let known = &mut self.slaves[slave];
            if known.sii.store(word, b) {
                known.plan = None;
            }
            match SiiField::at(word) {
                Some(SiiField::Vendor) => known.vendor = Some(value),
                Some(SiiField::Product) => known.product = Some(value),
                _ => {}
            }
            on(Meaning::Sii {
                slave: known.reference(),
                word,
                value,
            });
        }
    }

    /// A mailbox message, where an FPWR or FPRD starts at a mailbox area
    /// (or, with no sync manager seen, looks like one).
    fn mailbox<'a>(
        &mut self,
        position: Position,
        slave: usize,
        written: bool,
        datagram: &Datagram<'a>,
    ) -> Option<Meaning<'a>> {
        let data = datagram.data();
        let ado = datagram.ado();
        let wkc = datagram.working_counter();
        if data.len() < MAILBOX_HEADER_LEN {
            // A probe, or the area's last byte.
            return None;
        }
        let header = MailboxHeader::parse(data).ok()?;
        let room = data.len() - MAILBOX_HEADER_LEN;
        let plausible = header.length > 0
            && usize::from(header.length) <= room
            && !matches!(header.mailbox_type, MailboxType::Reserved(_));
        let area = self.slaves[slave].mailbox_at(ado);
        if let Some((master_writes, len)) = area {
            let room = len.saturating_sub(MAILBOX_HEADER_LEN as u16);
            if master_writes == written && header.length > room && (written || wkc >= 1) {
                let reference = self.slaves[slave].reference();
                let error = ImageError::MailboxPastSyncManager {
                    length: header.length,
                    room,
                };
                self.problem(position, reference, error);
            }
        }
        let known = &self.slaves[slave];
        let guessed = match area {
            Some((master_writes, _)) if master_writes == written => false,
            Some(_) => return None,
            None if !known.has_mailbox() && ado >= PROCESS_MEMORY && plausible && wkc >= 1 => true,
            None => return None,
        };
        if !written && wkc == 0 {
            // Read from an empty mailbox: no message.
            return None;
        }
        if !plausible && !guessed && header.length == 0 {
            return None;
        }
        let end = (MAILBOX_HEADER_LEN + usize::from(header.length)).min(data.len());
        let mut repeated = false;
        if !written {
            let repeat = &mut self.slaves[slave].repeat;
            let this = (header.counter, header.mailbox_type);
            repeated = repeat.pending && repeat.last == Some(this);
            repeat.pending = false;
            repeat.last = Some(this);
        }
        let known = &self.slaves[slave];
        Some(Meaning::Mailbox {
            slave: known.reference(),
            written,
            accepted: wkc >= 1,
            guessed,
            repeated,
            header,
            body: &data[MAILBOX_HEADER_LEN..end],
            profile: known.profile(),
            sdo: None,
        })
    }
}

/// A write that may carry a mailbox message, recorded even when refused.
const fn is_mailbox_write(command: Command) -> bool {
    matches!(command, Command::Fpwr)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A slave whose 2 output bytes (SM2 at 0x1100) and 2 input bytes
    /// (SM3 at 0x1180) share logical 0x0000–0x0001, as a master maps them
    /// when inputs and outputs overlap.
    fn overlapped() -> Network {
        let fmmu = |physical, kind| Fmmu {
            logical: 0,
            len: 2,
            logical_start_bit: 0,
            logical_end_bit: 7,
            physical,
            physical_start_bit: 0,
            kind,
            active: true,
        };
        let sm = |start, control| SyncManager {
            start,
            len: 2,
            control,
            status: 0,
            activate: 1,
        };
        let mut network = Network::default();
        network.configure(&[SlaveConfig {
            station: Some(0x1001),
            fmmus: vec![(0, fmmu(0x1100, 2)), (1, fmmu(0x1180, 1))],
            sync_managers: vec![(2, sm(0x1100, 0x64)), (3, sm(0x1180, 0x20))],
            ..SlaveConfig::default()
        }]);
        network
    }

    /// The images one datagram gives: outputs and inputs, as hex.
    fn cut(command: Command, sent: &[u8], returned: &[u8], wkc: u16) -> (String, String) {
        let mut network = overlapped();
        let mut images = None;
        network.process_data(
            command,
            0,
            Some(sent),
            returned,
            wkc,
            &ServoSlaves::default(),
            Position::Record(1),
            |data| {
                let hex =
                    |b: Option<&[u8]>| b.map_or_else(|| "-".to_owned(), |b| format!("{b:02x?}"));
                images = Some((hex(data.outputs), hex(data.inputs)));
            },
        );
        images.expect("one record")
    }

    /// An LRW carries both halves: the outputs the master sent, the
    /// inputs the slave put in their place.
    #[test]
    fn lrw_gives_outputs_sent_and_inputs_returned() {
        assert_eq!(
            cut(Command::Lrw, &[0x11, 0x22], &[0x33, 0x44], 3),
            ("[11, 22]".to_owned(), "[33, 44]".to_owned())
        );
    }

    /// An LRD writes nothing: its sent bytes are no outputs of the slave.
    /// An LWR reads nothing: its returned bytes are the master's outputs,
    /// not the slave's inputs.
    #[test]
    fn lrd_gives_no_outputs_and_lwr_no_inputs() {
        assert_eq!(
            cut(Command::Lrd, &[0, 0], &[0x33, 0x44], 1),
            ("-".to_owned(), "[33, 44]".to_owned())
        );
        assert_eq!(
            cut(Command::Lwr, &[0x11, 0x22], &[0x11, 0x22], 1),
            ("[11, 22]".to_owned(), "-".to_owned())
        );
    }
}
