//! Which slave a record is about ([`SlaveRef`]).

/// Which slave a meaning is about: its configured station address and its
/// position, as far as the capture has shown them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct SlaveRef {
    /// The configured station address (register 0x0010).
    pub station: Option<u16>,
    /// The position on the ring, from 0.
    pub position: Option<u16>,
}

impl core::fmt::Display for SlaveRef {
    /// `slave 0x1001 (4097) at 1`, `slave 0x1001 (4097)`, `slave at 1`;
    /// `every slave` for neither (a broadcast).
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match (self.station, self.position) {
            (Some(s), Some(p)) => write!(f, "slave {s:#06x} ({s}) at {p}"),
            (Some(s), None) => write!(f, "slave {s:#06x} ({s})"),
            (None, Some(p)) => write!(f, "slave at {p}"),
            (None, None) => f.write_str("every slave"),
        }
    }
}
