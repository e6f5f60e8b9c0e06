//! Names of object-dictionary entries: one table for the CiA 301
//! communication objects, the CiA 402 drive objects and the encoder objects
//! of CiA 406 and the Baumer EAM580 (`object` in docs/canopen.md#object-names,
//! signal names in docs/canopen.md#signals).
//!
//! [`OBJECT_NAMES`] is the one place the crate names an object by its index.
//! Each row is an index or an index range with the object area it belongs
//! to ([`ObjectSet`]) and its name as the defining document writes it. An
//! SDO names its object with [`object_name`]: the communication objects
//! 1000h–1FFFh always, a device profile's objects only for a node given that
//! profile (docs/canopen.md#object-names), since the same index means different
//! things in different profiles (6041h is the CiA 402 statusword, 6503h the
//! drive catalogue number of CiA 402 and the alarms of CiA 406). The name is
//! the object's, not a sub-entry's.
//!
//! Where one range holds numbered instances of one object (1400h–15FFh are
//! RPDO 1 to RPDO 512), the row's name has no number and
//! [`object_instance`] gives it.
//!
//! ```
//! use motionwire_codec::canopen::{object_instance, object_name, ObjectSet};
//!
//! // Communication objects are named whatever the profile.
//! assert_eq!(object_name(0x1017, None), Some("Producer heartbeat time"));
//! assert_eq!(object_name(0x1801, Some(ObjectSet::Drive)), Some("TPDO communication parameter"));
//! assert_eq!(object_instance(0x1801, None), Some(2));
//!
//! // Profile objects only with their profile.
//! assert_eq!(object_name(0x6041, Some(ObjectSet::Drive)), Some("Statusword"));
//! assert_eq!(object_name(0x6041, None), None);
//! assert_eq!(object_name(0x6503, Some(ObjectSet::Drive)), Some("Drive catalogue number"));
//! assert_eq!(object_name(0x6503, Some(ObjectSet::Encoder)), Some("Alarms"));
//!
//! // Indices no table names.
//! assert_eq!(object_name(0x1004, None), None);
//! assert_eq!(object_name(0x2000, Some(ObjectSet::Drive)), None);
//! ```

/// Which object-dictionary area an entry belongs to (CiA 301 §7.4.1, the
/// object dictionary's structure; docs/canopen.md#object-names).
///
/// The order of the variants is the order of [`OBJECT_NAMES`].
///
/// With the `serde` feature a set serializes as its variant name.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum ObjectSet {
    /// The communication profile area 1000h–1FFFh: the objects of CiA 301
    /// v4.2.0 and the common CiA 302 objects in 1F00h–1FFFh. Named for every
    /// node.
    Communication,
    /// The CiA 402 drive profile (IEC 61800-7-201), 6000h–67FFh: the objects
    /// of a Kollmorgen AKD or any other CiA 402 drive.
    Drive,
    /// The encoder objects of the Baumer EAM580 (its CANopen manual):
    /// the CiA 406 encoder profile in 6000h–67FFh and the encoder's own
    /// manufacturer-specific objects in 2000h–5FFFh.
    Encoder,
}

impl ObjectSet {
    /// Every set, in the order of [`OBJECT_NAMES`].
    pub const ALL: [ObjectSet; 3] = [
        ObjectSet::Communication,
        ObjectSet::Drive,
        ObjectSet::Encoder,
    ];
}

/// One row of [`OBJECT_NAMES`]: an index or an index range with its name
/// (docs/canopen.md#object-names, docs/canopen.md#signals).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ObjectName {
    /// The first index of the row.
    pub first: u16,
    /// The last index of the row (`first` for a single object).
    pub last: u16,
    /// The area the object belongs to.
    pub set: ObjectSet,
    /// The object's name, as the defining document writes it.
    pub name: &'static str,
    /// Whether each index of the range is one numbered instance of the
    /// object, `first` being instance 1 (1400h is RPDO 1, 1401h RPDO 2);
    /// see [`ObjectName::instance`].
    pub numbered: bool,
}

impl ObjectName {
    /// Return whether `index` lies in this row's range.
    ///
    /// ```
    /// use motionwire_codec::canopen::find_object;
    ///
    /// let row = find_object(0x1200, None).unwrap();
    /// assert!(row.contains(0x127F));
    /// assert!(!row.contains(0x1280));
    /// ```
    #[inline]
    #[must_use]
    pub const fn contains(&self, index: u16) -> bool {
        self.first <= index && index <= self.last
    }

    /// Return the instance number of `index` in a numbered row, 1 for
    /// `first`; `None` when the row is not numbered or `index` lies outside
    /// it.
    ///
    /// ```
    /// use motionwire_codec::canopen::find_object;
    ///
    /// let rpdo_mapping = find_object(0x1600, None).unwrap();
    /// assert_eq!(rpdo_mapping.instance(0x1600), Some(1));
    /// assert_eq!(rpdo_mapping.instance(0x17FF), Some(512));
    /// assert_eq!(find_object(0x1017, None).unwrap().instance(0x1017), None);
    /// ```
    #[inline]
    #[must_use]
    pub const fn instance(&self, index: u16) -> Option<u16> {
        if self.numbered && self.contains(index) {
            Some(index - self.first + 1)
        } else {
            None
        }
    }
}

/// A communication object with one index.
const fn comm(index: u16, name: &'static str) -> ObjectName {
    row(index, index, ObjectSet::Communication, name, false)
}

/// A communication object range whose indices are numbered instances.
const fn comm_numbered(first: u16, last: u16, name: &'static str) -> ObjectName {
    row(first, last, ObjectSet::Communication, name, true)
}

/// A communication object range that is one object spread over several
/// indices.
const fn comm_range(first: u16, last: u16, name: &'static str) -> ObjectName {
    row(first, last, ObjectSet::Communication, name, false)
}

/// A CiA 402 drive object.
const fn drive(index: u16, name: &'static str) -> ObjectName {
    row(index, index, ObjectSet::Drive, name, false)
}

/// An encoder object.
const fn encoder(index: u16, name: &'static str) -> ObjectName {
    row(index, index, ObjectSet::Encoder, name, false)
}

const fn row(
    first: u16,
    last: u16,
    set: ObjectSet,
    name: &'static str,
    numbered: bool,
) -> ObjectName {
    ObjectName {
        first,
        last,
        set,
        name,
        numbered,
    }
}

/// The names of object-dictionary entries, sorted by (set, first), with no
/// overlapping rows inside a set (checked when the crate compiles and by the
/// tests). Rows of different sets may share indices: the profiles reuse
/// 6000h–67FFh.
///
/// Sources, group by group:
///
/// - **Communication, 1000h–1BFFh, 1FA0h–1FFFh**: CiA 301 v4.2.0, the
///   object dictionary's communication profile area (§7.5), names as CiA
///   writes them (American spelling: "Error behavior object"). Checked
///   against Wireshark's CANopen dissector (`packet-canopen.c`, `obj_dict`)
///   and lely-core's CiA conformance list. 1004h, 100Bh, 100Eh–100Fh and
///   101Ah–101Fh are reserved and unnamed.
/// - **Communication, 102Ah and 1F20h–1F91h**: CiA 302 v4.1.0 (part 2,
///   network management; part 3, configuration and program download), as
///   lely-core's CiA conformance list names them; only the objects whose
///   names two sources agree on (CanFestival's DS-302 profile for 1F20h,
///   1F22h, 1F50h, 1F51h).
/// - **Communication, 1C00h–1C33h**: the sync manager objects of CANopen
///   over EtherCAT (indices the CiA sources above name nothing at):
///   ETG.1000.6 (EtherCAT application layer, the CoE object dictionary)
///   defines 1C00h, the sync manager communication type (sub-index n:
///   SM n-1's type, 1 mailbox out, 2 mailbox in, 3 outputs, 4 inputs),
///   the PDO assignment of SM n at 1C10h + n — 1C12h the outputs'
///   (RxPDOs), 1C13h the inputs' (TxPDOs) on the usual layout — and the
///   synchronization of SM n at 1C30h + n; ETG.1020 (EtherCAT protocol
///   enhancements, synchronization) names 1C32h and 1C33h, the output and
///   input sync manager parameters (sync mode, cycle time, shift times).
///   1C00h is named as ETG.1000.6 names it, the others as ETG.1020 and
///   the ESI files of Beckhoff's devices do; only these indices, not the
///   whole ranges, since what 1C10h + n and 1C30h + n hold depends on the
///   device's sync manager layout.
/// - **Drive**: CiA 402 part 2 (IEC 61800-7-201), the objects of the common
///   entries, device control, the factor group and the operating modes
///   (vl, pp, pv, tq, hm, ip, touch probe); checked against CiA DSP 402
///   v2.0's object headings, CanFestival's DS-402 profile and published
///   drive object lists. 6096h is "Velocity factor" (DSP 402 v2.0 called it
///   "Velocity factor 2"; 6093h–6095h are that edition's objects, kept for
///   drives that still carry them).
/// - **Encoder, 6000h–650Bh**: CiA 406 (encoder profile), checked against
///   CanFestival's DS-406 profile; 6501h is "Singleturn resolution" as the
///   Baumer seed and Baumer's own object lists spell it (CiA 406 names the
///   rotary meaning of the object).
/// - **Encoder, 2100h–2300h**: the object list of the Baumer EAM580 CANopen
///   manual: 2100h "Baudrate" and 2300h "Customer EEPROM" as
///   listed there; 2101h from its section "Changing the node ID" (the node-ID
///   can be changed in object 2101h); 2116h by the name the list gives its
///   sub-index 1, "Diagnostic Injection", where the error injection codes of
///   docs/canopen.md#baumer are written.
pub const OBJECT_NAMES: &[ObjectName] = &[
    // CiA 301 v4.2.0, communication profile area.
    comm(0x1000, "Device type"),
    comm(0x1001, "Error register"),
    comm(0x1002, "Manufacturer status register"),
    comm(0x1003, "Pre-defined error field"),
    comm(0x1005, "COB-ID SYNC message"),
    comm(0x1006, "Communication cycle period"),
    comm(0x1007, "Synchronous window length"),
    comm(0x1008, "Manufacturer device name"),
    comm(0x1009, "Manufacturer hardware version"),
    comm(0x100A, "Manufacturer software version"),
    comm(0x100C, "Guard time"),
    comm(0x100D, "Life time factor"),
    comm(0x1010, "Store parameters"),
    comm(0x1011, "Restore default parameters"),
    comm(0x1012, "COB-ID time stamp object"),
    comm(0x1013, "High resolution time stamp"),
    comm(0x1014, "COB-ID EMCY"),
    comm(0x1015, "Inhibit time EMCY"),
    comm(0x1016, "Consumer heartbeat time"),
    comm(0x1017, "Producer heartbeat time"),
    comm(0x1018, "Identity object"),
    comm(0x1019, "Synchronous counter overflow value"),
    comm(0x1020, "Verify configuration"),
    comm(0x1021, "Store EDS"),
    comm(0x1022, "Store format"),
    comm(0x1023, "OS command"),
    comm(0x1024, "OS command mode"),
    comm(0x1025, "OS debugger interface"),
    comm(0x1026, "OS prompt"),
    comm(0x1027, "Module list"),
    comm(0x1028, "Emergency consumer object"),
    comm(0x1029, "Error behavior object"),
    // CiA 302-2.
    comm(0x102A, "NMT inhibit time"),
    // CiA 301 v4.2.0: SDO and PDO parameters, one index per instance.
    comm_numbered(0x1200, 0x127F, "SDO server parameter"),
    comm_numbered(0x1280, 0x12FF, "SDO client parameter"),
    comm_numbered(0x1400, 0x15FF, "RPDO communication parameter"),
    comm_numbered(0x1600, 0x17FF, "RPDO mapping parameter"),
    comm_numbered(0x1800, 0x19FF, "TPDO communication parameter"),
    comm_numbered(0x1A00, 0x1BFF, "TPDO mapping parameter"),
    // ETG.1000.6 and ETG.1020: the sync manager objects of CoE.
    comm(0x1C00, "Sync manager communication type"),
    comm(0x1C12, "RxPDO assign"),
    comm(0x1C13, "TxPDO assign"),
    comm(0x1C32, "SM output parameter"),
    comm(0x1C33, "SM input parameter"),
    // CiA 302-3: configuration manager and program download.
    comm(0x1F20, "Store DCF"),
    comm(0x1F22, "Concise DCF"),
    comm(0x1F25, "Configuration request"),
    comm(0x1F26, "Expected configuration date"),
    comm(0x1F27, "Expected configuration time"),
    comm(0x1F50, "Program data"),
    comm(0x1F51, "Program control"),
    comm(0x1F56, "Program software identification"),
    comm(0x1F57, "Flash status identification"),
    // CiA 302-2: network management.
    comm(0x1F80, "NMT startup"),
    comm(0x1F81, "NMT slave assignment"),
    comm(0x1F82, "Request NMT"),
    comm(0x1F83, "Request node guarding"),
    comm(0x1F84, "Device type identification"),
    comm(0x1F85, "Vendor identification"),
    comm(0x1F86, "Product code"),
    comm(0x1F87, "Revision number"),
    comm(0x1F88, "Serial number"),
    comm(0x1F89, "Boot time"),
    comm(0x1F8A, "Restore configuration"),
    comm(0x1F90, "NMT flying master timing parameters"),
    // CiA 301 v4.2.0: multiplexed PDOs; each list spans its whole range.
    comm_range(0x1FA0, 0x1FCF, "Object scanner list"),
    comm_range(0x1FD0, 0x1FFF, "Object dispatching list"),
    // CiA 402: common entries and device control.
    drive(0x6007, "Abort connection option code"),
    drive(0x603F, "Error code"),
    drive(0x6040, "Controlword"),
    drive(0x6041, "Statusword"),
    // CiA 402: velocity mode (vl).
    drive(0x6042, "vl target velocity"),
    drive(0x6043, "vl velocity demand"),
    drive(0x6044, "vl velocity actual value"),
    drive(0x6046, "vl velocity min max amount"),
    drive(0x6048, "vl velocity acceleration"),
    drive(0x6049, "vl velocity deceleration"),
    drive(0x604A, "vl velocity quick stop"),
    drive(0x604B, "vl set-point factor"),
    drive(0x604C, "vl dimension factor"),
    // CiA 402: device control, option codes and modes.
    drive(0x605A, "Quick stop option code"),
    drive(0x605B, "Shutdown option code"),
    drive(0x605C, "Disable operation option code"),
    drive(0x605D, "Halt option code"),
    drive(0x605E, "Fault reaction option code"),
    drive(0x6060, "Modes of operation"),
    drive(0x6061, "Modes of operation display"),
    // CiA 402: position control, profile velocity and torque.
    drive(0x6062, "Position demand value"),
    drive(0x6063, "Position actual internal value"),
    drive(0x6064, "Position actual value"),
    drive(0x6065, "Following error window"),
    drive(0x6066, "Following error time out"),
    drive(0x6067, "Position window"),
    drive(0x6068, "Position window time"),
    drive(0x6069, "Velocity sensor actual value"),
    drive(0x606A, "Sensor selection code"),
    drive(0x606B, "Velocity demand value"),
    drive(0x606C, "Velocity actual value"),
    drive(0x606D, "Velocity window"),
    drive(0x606E, "Velocity window time"),
    drive(0x606F, "Velocity threshold"),
    drive(0x6070, "Velocity threshold time"),
    drive(0x6071, "Target torque"),
    drive(0x6072, "Max torque"),
    drive(0x6073, "Max current"),
    drive(0x6074, "Torque demand"),
    drive(0x6075, "Motor rated current"),
    drive(0x6076, "Motor rated torque"),
    drive(0x6077, "Torque actual value"),
    drive(0x6078, "Current actual value"),
    drive(0x6079, "DC link circuit voltage"),
    // CiA 402: profile position.
    drive(0x607A, "Target position"),
    drive(0x607B, "Position range limit"),
    drive(0x607C, "Home offset"),
    drive(0x607D, "Software position limit"),
    drive(0x607E, "Polarity"),
    drive(0x607F, "Max profile velocity"),
    drive(0x6080, "Max motor speed"),
    drive(0x6081, "Profile velocity"),
    drive(0x6082, "End velocity"),
    drive(0x6083, "Profile acceleration"),
    drive(0x6084, "Profile deceleration"),
    drive(0x6085, "Quick stop deceleration"),
    drive(0x6086, "Motion profile type"),
    drive(0x6087, "Torque slope"),
    drive(0x6088, "Torque profile type"),
    // CiA 402: factor group.
    drive(0x6089, "Position notation index"),
    drive(0x608A, "Position dimension index"),
    drive(0x608B, "Velocity notation index"),
    drive(0x608C, "Velocity dimension index"),
    drive(0x608D, "Acceleration notation index"),
    drive(0x608E, "Acceleration dimension index"),
    drive(0x608F, "Position encoder resolution"),
    drive(0x6090, "Velocity encoder resolution"),
    drive(0x6091, "Gear ratio"),
    drive(0x6092, "Feed constant"),
    drive(0x6093, "Position factor"),
    drive(0x6094, "Velocity encoder factor"),
    drive(0x6095, "Velocity factor 1"),
    drive(0x6096, "Velocity factor"),
    drive(0x6097, "Acceleration factor"),
    // CiA 402: homing.
    drive(0x6098, "Homing method"),
    drive(0x6099, "Homing speeds"),
    drive(0x609A, "Homing acceleration"),
    // CiA 402: jerk and SI units.
    drive(0x60A2, "Jerk factor"),
    drive(0x60A3, "Profile jerk use"),
    drive(0x60A4, "Profile jerk"),
    drive(0x60A8, "SI unit position"),
    drive(0x60A9, "SI unit velocity"),
    drive(0x60AA, "SI unit acceleration"),
    drive(0x60AB, "SI unit jerk"),
    // CiA 402: offsets for cyclic synchronous modes.
    drive(0x60B0, "Position offset"),
    drive(0x60B1, "Velocity offset"),
    drive(0x60B2, "Torque offset"),
    // CiA 402: touch probe.
    drive(0x60B8, "Touch probe function"),
    drive(0x60B9, "Touch probe status"),
    drive(0x60BA, "Touch probe 1 positive edge"),
    drive(0x60BB, "Touch probe 1 negative edge"),
    drive(0x60BC, "Touch probe 2 positive edge"),
    drive(0x60BD, "Touch probe 2 negative edge"),
    // CiA 402: interpolated position.
    drive(0x60C0, "Interpolation sub mode select"),
    drive(0x60C1, "Interpolation data record"),
    drive(0x60C2, "Interpolation time period"),
    drive(0x60C3, "Interpolation sync definition"),
    drive(0x60C4, "Interpolation data configuration"),
    drive(0x60C5, "Max acceleration"),
    drive(0x60C6, "Max deceleration"),
    // CiA 402: touch probe source and counters.
    drive(0x60D0, "Touch probe source"),
    drive(0x60D5, "Touch probe 1 positive edge counter"),
    drive(0x60D6, "Touch probe 1 negative edge counter"),
    drive(0x60D7, "Touch probe 2 positive edge counter"),
    drive(0x60D8, "Touch probe 2 negative edge counter"),
    // CiA 402: torque limits, homing methods, additional values.
    drive(0x60E0, "Positive torque limit value"),
    drive(0x60E1, "Negative torque limit value"),
    drive(0x60E3, "Supported homing methods"),
    drive(0x60E4, "Additional position actual value"),
    drive(0x60E5, "Additional velocity actual value"),
    // CiA 402: position control and common entries.
    drive(0x60F2, "Positioning option code"),
    drive(0x60F4, "Following error actual value"),
    drive(0x60F8, "Max slippage"),
    drive(0x60FA, "Control effort"),
    drive(0x60FC, "Position demand internal value"),
    drive(0x60FD, "Digital inputs"),
    drive(0x60FE, "Digital outputs"),
    drive(0x60FF, "Target velocity"),
    // CiA 402: motor and drive data.
    drive(0x6402, "Motor type"),
    drive(0x6403, "Motor catalogue number"),
    drive(0x6404, "Motor manufacturer"),
    drive(0x6405, "http motor catalogue address"),
    drive(0x6406, "Motor calibration date"),
    drive(0x6407, "Motor service period"),
    drive(0x6410, "Motor data"),
    drive(0x6502, "Supported drive modes"),
    drive(0x6503, "Drive catalogue number"),
    drive(0x6504, "Drive manufacturer"),
    drive(0x6505, "http drive catalogue address"),
    drive(0x6510, "Drive data"),
    drive(0x67FE, "Version number"),
    drive(0x67FF, "Single device type"),
    // Baumer EAM580 CANopen manual, object list.
    encoder(0x2100, "Baudrate"),
    encoder(0x2101, "Node ID"),
    encoder(0x2116, "Diagnostic injection"),
    encoder(0x2300, "Customer EEPROM"),
    // CiA 406: encoder profile.
    encoder(0x6000, "Operating parameters"),
    encoder(0x6001, "Measuring units per revolution"),
    encoder(0x6002, "Total measuring range in measuring units"),
    encoder(0x6003, "Preset value"),
    encoder(0x6004, "Position value"),
    encoder(0x6005, "Linear encoder measuring step settings"),
    encoder(0x6008, "High precision position value"),
    encoder(0x6009, "High precision preset value"),
    encoder(0x6030, "Speed value"),
    encoder(0x6040, "Acceleration value"),
    encoder(0x6050, "Jerk value"),
    encoder(0x6200, "Cyclic timer"),
    encoder(0x6500, "Operating status"),
    encoder(0x6501, "Singleturn resolution"),
    encoder(0x6502, "Number of distinguishable revolutions"),
    encoder(0x6503, "Alarms"),
    encoder(0x6504, "Supported alarms"),
    encoder(0x6505, "Warnings"),
    encoder(0x6506, "Supported warnings"),
    encoder(0x6507, "Profile and software version"),
    encoder(0x6508, "Operating time"),
    encoder(0x6509, "Offset value"),
    encoder(0x650A, "Module identification"),
    encoder(0x650B, "Serial number"),
];

/// Return whether `a` comes strictly before `b` in the table: an earlier
/// set, or the same set and a range that ends before `b` starts.
const fn strictly_before(a: &ObjectName, b: &ObjectName) -> bool {
    let (set_a, set_b) = (a.set as u8, b.set as u8);
    set_a < set_b || (set_a == set_b && a.last < b.first)
}

/// Return whether every row is a well-formed range (`first <= last`) and
/// the rows are sorted by (set, first) without overlaps inside a set.
const fn is_well_formed(rows: &[ObjectName]) -> bool {
    let mut i = 0;
    while i < rows.len() {
        if rows[i].first > rows[i].last {
            return false;
        }
        if i > 0 && !strictly_before(&rows[i - 1], &rows[i]) {
            return false;
        }
        i += 1;
    }
    true
}

// The binary search below relies on this; a mis-sorted edit fails the build.
const _: () = assert!(is_well_formed(OBJECT_NAMES), "OBJECT_NAMES is unsorted");

/// Where each set's rows start in the sorted table, and where the last
/// set's end: `SET_STARTS[s]..SET_STARTS[s + 1]` are the rows of the set of
/// number `s`. Worked out when the crate compiles, so that a look-up is one
/// binary search instead of three.
const SET_STARTS: [usize; ObjectSet::ALL.len() + 1] = {
    let mut starts = [OBJECT_NAMES.len(); ObjectSet::ALL.len() + 1];
    let mut s = ObjectSet::ALL.len();
    while s > 0 {
        s -= 1;
        // The first row of set `s` or of a later one (the table is sorted).
        let mut i = 0;
        while i < OBJECT_NAMES.len() && (OBJECT_NAMES[i].set as usize) < s {
            i += 1;
        }
        starts[s] = i;
    }
    starts
};

/// Return the rows of `set`, a contiguous run of the sorted table.
#[inline]
fn rows_of(set: ObjectSet) -> &'static [ObjectName] {
    let s = set as usize;
    OBJECT_NAMES
        .get(SET_STARTS[s]..SET_STARTS[s + 1])
        .unwrap_or(&[])
}

/// Return the row of `set` whose range holds `index`, by binary search.
fn find_in(set: ObjectSet, index: u16) -> Option<&'static ObjectName> {
    let rows = rows_of(set);
    // The rows of a set do not overlap, so their `last`s ascend too: the
    // first row that ends at or after `index` is the only candidate.
    let at = rows.partition_point(|row| row.last < index);
    rows.get(at).filter(|row| row.first <= index)
}

/// Return the row of [`OBJECT_NAMES`] that names object `index`: a
/// communication object always, a profile object only when `profile` names
/// its set (docs/canopen.md#object-names).
///
/// The look-up is a binary search of the sorted table.
///
/// ```
/// use motionwire_codec::canopen::{find_object, ObjectSet};
///
/// let row = find_object(0x6061, Some(ObjectSet::Drive)).unwrap();
/// assert_eq!((row.first, row.name), (0x6061, "Modes of operation display"));
/// assert_eq!(row.set, ObjectSet::Drive);
/// assert!(find_object(0x6061, Some(ObjectSet::Encoder)).is_none());
/// ```
#[must_use]
pub fn find_object(index: u16, profile: Option<ObjectSet>) -> Option<&'static ObjectName> {
    find_in(ObjectSet::Communication, index).or_else(|| match profile {
        Some(set) if set != ObjectSet::Communication => find_in(set, index),
        _ => None,
    })
}

/// Return the name of object `index`: communication objects (1000h–1FFFh)
/// always, profile objects only when `profile` names their set; `None` for
/// an index no row names (`object` in docs/canopen.md#object-names,
/// docs/canopen.md#signals).
///
/// The name is the object's, not a sub-entry's; a numbered range's name has
/// no number (see [`object_instance`]).
///
/// ```
/// use motionwire_codec::canopen::{object_name, ObjectSet};
///
/// assert_eq!(object_name(0x1003, None), Some("Pre-defined error field"));
/// assert_eq!(object_name(0x6040, Some(ObjectSet::Drive)), Some("Controlword"));
/// assert_eq!(object_name(0x6004, Some(ObjectSet::Encoder)), Some("Position value"));
/// assert_eq!(object_name(0x6004, None), None);
/// ```
#[inline]
#[must_use]
pub fn object_name(index: u16, profile: Option<ObjectSet>) -> Option<&'static str> {
    find_object(index, profile).map(|row| row.name)
}

/// Return the instance number of object `index` in a numbered range, 1 for
/// the range's first index (RPDO 1 at 1400h, SDO server 1 at 1200h, TPDO
/// 512 at 19FFh); `None` for an object that is not one of numbered
/// instances or that no row names (CiA 301 §7.5.2.35–§7.5.2.38).
///
/// ```
/// use motionwire_codec::canopen::object_instance;
///
/// assert_eq!(object_instance(0x1400, None), Some(1));
/// assert_eq!(object_instance(0x1A03, None), Some(4));
/// assert_eq!(object_instance(0x1018, None), None);
/// ```
#[inline]
#[must_use]
pub fn object_instance(index: u16, profile: Option<ObjectSet>) -> Option<u16> {
    find_object(index, profile).and_then(|row| row.instance(index))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::profiles::baumer::{Alarms, Warnings, INJECTION_OBJECT_INDEX};

    /// The profile argument that makes `set`'s rows reachable.
    fn profile_for(set: ObjectSet) -> Option<ObjectSet> {
        match set {
            ObjectSet::Communication => None,
            other => Some(other),
        }
    }

    /// The row a linear scan finds: the oracle for the binary search.
    fn scan(set: ObjectSet, index: u16) -> Option<&'static ObjectName> {
        OBJECT_NAMES
            .iter()
            .find(|row| row.set == set && row.contains(index))
    }

    #[test]
    fn the_table_is_sorted_by_set_then_index_without_overlaps() {
        assert!(is_well_formed(OBJECT_NAMES));
        for pair in OBJECT_NAMES.windows(2) {
            let (a, b) = (&pair[0], &pair[1]);
            assert!(a.first <= a.last, "{a:?} is an empty range");
            assert!(
                a.set < b.set || (a.set == b.set && a.last < b.first),
                "{a:?} then {b:?} is unsorted or overlapping"
            );
        }
    }

    #[test]
    fn the_sortedness_check_refuses_bad_tables() {
        let a = comm(0x1000, "a");
        let b = comm(0x1001, "b");
        let d = drive(0x6040, "d");
        assert!(is_well_formed(&[a, b, d]));
        assert!(!is_well_formed(&[b, a]), "unsorted");
        assert!(!is_well_formed(&[a, a]), "duplicated");
        assert!(!is_well_formed(&[d, a]), "sets out of order");
        assert!(
            !is_well_formed(&[comm_range(0x1000, 0x1010, "x"), b]),
            "overlapping"
        );
        assert!(!is_well_formed(&[comm_range(0x1001, 0x1000, "x")]), "empty");
    }

    #[test]
    fn every_set_is_in_the_table_and_within_its_area() {
        for set in ObjectSet::ALL {
            assert!(!rows_of(set).is_empty(), "{set:?} has no rows");
            assert!(rows_of(set).iter().all(|row| row.set == set));
        }
        let total: usize = ObjectSet::ALL.iter().map(|&set| rows_of(set).len()).sum();
        assert_eq!(total, OBJECT_NAMES.len());
        for row in OBJECT_NAMES {
            let area = match row.set {
                ObjectSet::Communication => 0x1000..=0x1FFF,
                ObjectSet::Drive => 0x6000..=0x67FF,
                // CiA 406 in 6000h–67FFh, the encoder's own objects in the
                // manufacturer-specific area 2000h–5FFFh.
                ObjectSet::Encoder => 0x2000..=0x67FF,
            };
            assert!(
                area.contains(&row.first) && area.contains(&row.last),
                "{row:?} lies outside its set's area"
            );
        }
    }

    #[test]
    fn every_row_is_reachable_at_both_ends() {
        for row in OBJECT_NAMES {
            let profile = profile_for(row.set);
            for index in [row.first, row.last] {
                assert_eq!(find_object(index, profile), Some(row), "{index:#06x}");
                assert_eq!(object_name(index, profile), Some(row.name));
            }
        }
    }

    #[test]
    fn names_are_trimmed_and_not_empty() {
        for row in OBJECT_NAMES {
            assert!(!row.name.is_empty());
            assert_eq!(row.name.trim(), row.name, "{row:?}");
            assert!(!row.name.contains("  "), "{row:?}");
        }
    }

    #[test]
    fn range_boundaries() {
        // (index, name) just inside and just outside the numbered ranges.
        let cases: &[(u16, Option<&str>)] = &[
            (0x11FF, None),
            (0x1200, Some("SDO server parameter")),
            (0x127F, Some("SDO server parameter")),
            (0x1280, Some("SDO client parameter")),
            (0x12FF, Some("SDO client parameter")),
            (0x1300, None),
            (0x13FF, None),
            (0x1400, Some("RPDO communication parameter")),
            (0x15FF, Some("RPDO communication parameter")),
            (0x1600, Some("RPDO mapping parameter")),
            (0x17FF, Some("RPDO mapping parameter")),
            (0x1800, Some("TPDO communication parameter")),
            (0x19FF, Some("TPDO communication parameter")),
            (0x1A00, Some("TPDO mapping parameter")),
            (0x1BFF, Some("TPDO mapping parameter")),
            (0x1C00, Some("Sync manager communication type")),
            (0x1C01, None),
            (0x1C11, None),
            (0x1C12, Some("RxPDO assign")),
            (0x1C13, Some("TxPDO assign")),
            (0x1C14, None),
            (0x1C32, Some("SM output parameter")),
            (0x1C33, Some("SM input parameter")),
            (0x1C34, None),
            (0x1F9F, None),
            (0x1FA0, Some("Object scanner list")),
            (0x1FCF, Some("Object scanner list")),
            (0x1FD0, Some("Object dispatching list")),
            (0x1FFF, Some("Object dispatching list")),
            (0x2000, None),
        ];
        for &(index, name) in cases {
            assert_eq!(object_name(index, None), name, "{index:#06x}");
        }
    }

    #[test]
    fn instances_count_from_one_in_numbered_ranges_only() {
        let cases: &[(u16, Option<u16>)] = &[
            (0x1200, Some(1)),
            (0x127F, Some(128)),
            (0x1280, Some(1)),
            (0x12FF, Some(128)),
            (0x1400, Some(1)),
            (0x1403, Some(4)),
            (0x15FF, Some(512)),
            (0x1600, Some(1)),
            (0x17FF, Some(512)),
            (0x1800, Some(1)),
            (0x1801, Some(2)),
            (0x19FF, Some(512)),
            (0x1A00, Some(1)),
            (0x1BFF, Some(512)),
            // One object, not instances: a list over several indices.
            (0x1FA0, None),
            (0x1FD5, None),
            // Single objects and unknown indices.
            (0x1017, None),
            (0x1300, None),
            (0x6040, None),
        ];
        for &(index, instance) in cases {
            assert_eq!(object_instance(index, None), instance, "{index:#06x}");
        }
        let row = find_object(0x1400, None).unwrap();
        assert_eq!(row.instance(0x1600), None, "outside the row");
    }

    #[test]
    fn unknown_indices_are_none() {
        for index in [
            0x0000, 0x0FFF, 0x1004, 0x100B, 0x100E, 0x101A, 0x102B, 0x1F00, 0x1F21, 0x1F91, 0x2000,
            0x5FFF, 0x6045, 0x6800, 0xFFFF,
        ] {
            for profile in [None, Some(ObjectSet::Drive), Some(ObjectSet::Encoder)] {
                assert_eq!(
                    object_name(index, profile),
                    None,
                    "{index:#06x} {profile:?}"
                );
            }
        }
        assert_eq!(object_name(0x2100, Some(ObjectSet::Drive)), None);
        assert_eq!(object_name(0x6510, Some(ObjectSet::Encoder)), None);
    }

    #[test]
    fn profile_objects_need_their_profile() {
        // (index, (without a profile, drive, encoder))
        type Names = (
            Option<&'static str>,
            Option<&'static str>,
            Option<&'static str>,
        );
        const OPERATING: &str = "Operating parameters";
        const REVOLUTIONS: &str = "Number of distinguishable revolutions";
        let cases: &[(u16, Names)] = &[
            (0x6000, (None, None, Some(OPERATING))),
            (0x603F, (None, Some("Error code"), None)),
            (
                0x6040,
                (None, Some("Controlword"), Some("Acceleration value")),
            ),
            (0x6041, (None, Some("Statusword"), None)),
            (0x6060, (None, Some("Modes of operation"), None)),
            (0x6064, (None, Some("Position actual value"), None)),
            (
                0x6502,
                (None, Some("Supported drive modes"), Some(REVOLUTIONS)),
            ),
            (
                0x6503,
                (None, Some("Drive catalogue number"), Some("Alarms")),
            ),
            (
                0x6505,
                (None, Some("http drive catalogue address"), Some("Warnings")),
            ),
            (0x2116, (None, None, Some("Diagnostic injection"))),
        ];
        for &(index, (none, drive, encoder)) in cases {
            assert_eq!(object_name(index, None), none, "{index:#06x}");
            assert_eq!(object_name(index, Some(ObjectSet::Communication)), none);
            assert_eq!(
                object_name(index, Some(ObjectSet::Drive)),
                drive,
                "{index:#06x}"
            );
            assert_eq!(
                object_name(index, Some(ObjectSet::Encoder)),
                encoder,
                "{index:#06x}"
            );
        }
    }

    #[test]
    fn communication_objects_are_named_whatever_the_profile() {
        for row in rows_of(ObjectSet::Communication) {
            for profile in [
                None,
                Some(ObjectSet::Communication),
                Some(ObjectSet::Drive),
                Some(ObjectSet::Encoder),
            ] {
                assert_eq!(object_name(row.first, profile), Some(row.name));
            }
        }
    }

    #[test]
    fn names_the_docs_and_the_brief_use() {
        // The examples of docs/canopen.md#signals and the CiA 301 names of
        // docs/canopen.md#emcy.
        assert_eq!(object_name(0x1000, None), Some("Device type"));
        assert_eq!(object_name(0x1001, None), Some("Error register"));
        assert_eq!(object_name(0x1003, None), Some("Pre-defined error field"));
        assert_eq!(object_name(0x100C, None), Some("Guard time"));
        assert_eq!(object_name(0x100D, None), Some("Life time factor"));
        assert_eq!(object_name(0x1016, None), Some("Consumer heartbeat time"));
        assert_eq!(object_name(0x1017, None), Some("Producer heartbeat time"));
        assert_eq!(object_name(0x1018, None), Some("Identity object"));
        assert_eq!(object_name(0x1F80, None), Some("NMT startup"));
        let drive = Some(ObjectSet::Drive);
        assert_eq!(object_name(0x6040, drive), Some("Controlword"));
        assert_eq!(object_name(0x6041, drive), Some("Statusword"));
        assert_eq!(
            object_name(0x6061, drive),
            Some("Modes of operation display")
        );
        assert_eq!(object_name(0x60FF, drive), Some("Target velocity"));
    }

    #[test]
    fn the_baumer_profile_indices_name_their_objects() {
        // baumer.rs keeps the indices its EMCY and injection codes refer to;
        // the names are this table's.
        let encoder = Some(ObjectSet::Encoder);
        assert_eq!(object_name(Alarms::OBJECT_INDEX, encoder), Some("Alarms"));
        assert_eq!(
            object_name(Warnings::OBJECT_INDEX, encoder),
            Some("Warnings")
        );
        assert_eq!(
            object_name(INJECTION_OBJECT_INDEX, encoder),
            Some("Diagnostic injection")
        );
    }

    #[test]
    fn every_index_and_profile_agrees_with_a_linear_scan() {
        // Exhaustive: all 65,536 indices with every profile argument.
        let profiles = [
            None,
            Some(ObjectSet::Communication),
            Some(ObjectSet::Drive),
            Some(ObjectSet::Encoder),
        ];
        for index in 0..=u16::MAX {
            for profile in profiles {
                let expected = scan(ObjectSet::Communication, index)
                    .or_else(|| profile.and_then(|set| scan(set, index)));
                assert_eq!(find_object(index, profile), expected, "{index:#06x}");
                assert_eq!(object_name(index, profile), expected.map(|row| row.name));
                let instance = expected
                    .filter(|row| row.numbered)
                    .map(|row| index - row.first + 1);
                assert_eq!(object_instance(index, profile), instance, "{index:#06x}");
            }
        }
    }
}

/// One row of [`OBJECT_DATA_TYPES`]: the data type of sub-indices
/// `first_sub..=last_sub` of object `index` in `set`. (An object's CiA 301
/// object type — VAR, ARRAY, RECORD — is another thing, the EDS reader's
/// `eds::ObjectType`.)
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ObjectDataType {
    /// The object area.
    pub set: ObjectSet,
    /// The object index.
    pub index: u16,
    /// The first sub-index the type applies to.
    pub first_sub: u8,
    /// The last sub-index the type applies to.
    pub last_sub: u8,
    /// The CiA 301 data type of those entries.
    pub data_type: crate::canopen::DataType,
}

macro_rules! types {
    ($($set:ident $index:literal $first:literal..=$last:literal => $ty:ident;)*) => {
        &[$(ObjectDataType {
            set: ObjectSet::$set,
            index: $index,
            first_sub: $first,
            last_sub: $last,
            data_type: crate::canopen::DataType::$ty,
        },)*]
    };
}

/// The data types of the objects a PDO commonly maps, for decoding a PDO
/// without an EDS (docs/canopen.md#signals: the type from the EDS, else from
/// the profile's table): the CiA 402 drive objects of process data (CiA 402-2's
/// object descriptions) and the CiA 406 encoder objects (CiA 406's object
/// descriptions), plus the communication objects a PDO may carry. Sorted by
/// (set, index); records list their sub-entries.
pub const OBJECT_DATA_TYPES: &[ObjectDataType] = types! {
    Communication 0x1001 0..=0 => Unsigned8;
    Communication 0x1002 0..=0 => Unsigned32;
    Drive 0x603F 0..=0 => Unsigned16;
    Drive 0x6040 0..=0 => Unsigned16;
    Drive 0x6041 0..=0 => Unsigned16;
    Drive 0x6042 0..=0 => Integer16;
    Drive 0x6043 0..=0 => Integer16;
    Drive 0x6044 0..=0 => Integer16;
    Drive 0x605A 0..=0 => Integer16;
    Drive 0x605B 0..=0 => Integer16;
    Drive 0x605C 0..=0 => Integer16;
    Drive 0x605D 0..=0 => Integer16;
    Drive 0x605E 0..=0 => Integer16;
    Drive 0x6060 0..=0 => Integer8;
    Drive 0x6061 0..=0 => Integer8;
    Drive 0x6062 0..=0 => Integer32;
    Drive 0x6063 0..=0 => Integer32;
    Drive 0x6064 0..=0 => Integer32;
    Drive 0x6065 0..=0 => Unsigned32;
    Drive 0x6066 0..=0 => Unsigned16;
    Drive 0x6067 0..=0 => Unsigned32;
    Drive 0x6068 0..=0 => Unsigned16;
    Drive 0x6069 0..=0 => Integer32;
    Drive 0x606B 0..=0 => Integer32;
    Drive 0x606C 0..=0 => Integer32;
    Drive 0x606D 0..=0 => Unsigned16;
    Drive 0x606E 0..=0 => Unsigned16;
    Drive 0x606F 0..=0 => Unsigned16;
    Drive 0x6070 0..=0 => Unsigned16;
    Drive 0x6071 0..=0 => Integer16;
    Drive 0x6072 0..=0 => Unsigned16;
    Drive 0x6073 0..=0 => Unsigned16;
    Drive 0x6074 0..=0 => Integer16;
    Drive 0x6075 0..=0 => Unsigned32;
    Drive 0x6076 0..=0 => Unsigned32;
    Drive 0x6077 0..=0 => Integer16;
    Drive 0x6078 0..=0 => Integer16;
    Drive 0x6079 0..=0 => Unsigned32;
    Drive 0x607A 0..=0 => Integer32;
    Drive 0x607C 0..=0 => Integer32;
    Drive 0x607D 1..=2 => Integer32;
    Drive 0x607E 0..=0 => Unsigned8;
    Drive 0x607F 0..=0 => Unsigned32;
    Drive 0x6080 0..=0 => Unsigned32;
    Drive 0x6081 0..=0 => Unsigned32;
    Drive 0x6082 0..=0 => Unsigned32;
    Drive 0x6083 0..=0 => Unsigned32;
    Drive 0x6084 0..=0 => Unsigned32;
    Drive 0x6085 0..=0 => Unsigned32;
    Drive 0x6086 0..=0 => Integer16;
    Drive 0x6087 0..=0 => Unsigned32;
    Drive 0x6088 0..=0 => Integer16;
    Drive 0x6098 0..=0 => Integer8;
    Drive 0x6099 1..=2 => Unsigned32;
    Drive 0x609A 0..=0 => Unsigned32;
    Drive 0x60B0 0..=0 => Integer32;
    Drive 0x60B1 0..=0 => Integer32;
    Drive 0x60B2 0..=0 => Integer16;
    Drive 0x60B8 0..=0 => Unsigned16;
    Drive 0x60B9 0..=0 => Unsigned16;
    Drive 0x60BA 0..=0 => Integer32;
    Drive 0x60BB 0..=0 => Integer32;
    Drive 0x60BC 0..=0 => Integer32;
    Drive 0x60BD 0..=0 => Integer32;
    Drive 0x60F4 0..=0 => Integer32;
    Drive 0x60FA 0..=0 => Integer32;
    Drive 0x60FC 0..=0 => Integer32;
    Drive 0x60FD 0..=0 => Unsigned32;
    Drive 0x60FE 1..=2 => Unsigned32;
    Drive 0x60FF 0..=0 => Integer32;
    Drive 0x6502 0..=0 => Unsigned32;
    Encoder 0x6000 0..=0 => Unsigned16;
    Encoder 0x6003 0..=0 => Unsigned32;
    Encoder 0x6004 0..=0 => Unsigned32;
    Encoder 0x6030 1..=1 => Integer16;
    Encoder 0x6500 0..=0 => Unsigned16;
    Encoder 0x6501 0..=0 => Unsigned32;
    Encoder 0x6502 0..=0 => Unsigned16;
    Encoder 0x6503 0..=0 => Unsigned16;
    Encoder 0x6504 0..=0 => Unsigned16;
    Encoder 0x6505 0..=0 => Unsigned16;
    Encoder 0x6506 0..=0 => Unsigned16;
    Encoder 0x6508 0..=0 => Unsigned32;
    Encoder 0x6509 0..=0 => Integer32;
};

/// Return the data type of entry `index`.`subindex` for a node read with
/// `profile` (communication objects always; profile objects only with their
/// set), from [`OBJECT_DATA_TYPES`]; `None` where the table has none.
///
/// ```
/// use motionwire_codec::canopen::{object_data_type, DataType, ObjectSet};
///
/// assert_eq!(object_data_type(0x6041, 0, Some(ObjectSet::Drive)), Some(DataType::Unsigned16));
/// assert_eq!(object_data_type(0x6064, 0, Some(ObjectSet::Drive)), Some(DataType::Integer32));
/// assert_eq!(object_data_type(0x6041, 0, None), None);
/// assert_eq!(object_data_type(0x6004, 0, Some(ObjectSet::Encoder)), Some(DataType::Unsigned32));
/// ```
#[must_use]
pub fn object_data_type(
    index: u16,
    subindex: u8,
    profile: Option<ObjectSet>,
) -> Option<crate::canopen::DataType> {
    let find = |set: ObjectSet| {
        let start = OBJECT_DATA_TYPES.partition_point(|t| (t.set, t.index) < (set, index));
        OBJECT_DATA_TYPES[start..]
            .iter()
            .take_while(|t| t.set == set && t.index == index)
            .find(|t| (t.first_sub..=t.last_sub).contains(&subindex))
            .map(|t| t.data_type)
    };
    find(ObjectSet::Communication).or_else(|| profile.and_then(find))
}

#[cfg(test)]
mod type_tests {
    use super::*;

    #[test]
    fn types_are_sorted_and_name_known_objects() {
        for pair in OBJECT_DATA_TYPES.windows(2) {
            assert!(
                (pair[0].set, pair[0].index) < (pair[1].set, pair[1].index),
                "{pair:?}"
            );
        }
        for row in OBJECT_DATA_TYPES {
            assert!(
                object_name(row.index, Some(row.set)).is_some(),
                "{:04X}h has a type but no name",
                row.index
            );
            for sub in row.first_sub..=row.last_sub {
                assert_eq!(
                    object_data_type(row.index, sub, Some(row.set)),
                    Some(row.data_type)
                );
            }
        }
        assert_eq!(object_data_type(0x607D, 0, Some(ObjectSet::Drive)), None);
    }
}
