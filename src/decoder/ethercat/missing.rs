//! Which slave a short working counter leaves out (docs/ethercat.md#wkc):
//! the count is a sum and names no one, so the session looks for other
//! evidence in the capture — a slave's AL status out of operation, a rise
//! of its lost-link counters or a change of its links — and else for the
//! one set of slaves whose shares add up to the shortfall.

use crate::ethercat::{AlState, AlStatus};

/// The slaves of one datagram whose shares of a short working counter
/// are searched for the one set that explains it.
const SHARE_SEARCH: usize = 16;
/// The lost-link counters 0x0310–0x0313 in the error counters' bytes.
const LOST_LINKS: core::ops::Range<usize> = 0x10..0x14;

/// What names a slave as one that missed a cycle.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Evidence {
    /// Its last AL status read has the error bit, or a state below SAFEOP.
    AlStatus,
    /// One of its lost-link counters (0x0310–0x0313) rose since its last
    /// cycle with a whole count.
    LostLink,
    /// Its DL status links (0x0110 bits 4–7) changed since its last cycle
    /// with a whole count.
    DlStatus,
    /// Its share is the shortfall, or part of the one set of shares that
    /// adds up to it.
    Share,
}

impl Evidence {
    /// Return the evidence's name as the records write it: `al_status`,
    /// `lost_link`, `dl_status`, `share`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Evidence::AlStatus => "al_status",
            Evidence::LostLink => "lost_link",
            Evidence::DlStatus => "dl_status",
            Evidence::Share => "share",
        }
    }

    /// Return the evidence in words, as the text writes it.
    #[must_use]
    pub const fn text(self) -> &'static str {
        match self {
            Evidence::AlStatus => "its AL status",
            Evidence::LostLink => "its lost-link counter",
            Evidence::DlStatus => "its DL status",
            Evidence::Share => "its share of the count",
        }
    }
}

impl core::fmt::Display for Evidence {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(self.name())
    }
}

/// What a cycle's working counter says of one slave's part in it
/// (docs/ethercat.md#wkc).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Missed {
    /// The count is the expected one (or none is known, or the slave has
    /// no share of it).
    #[default]
    No,
    /// The count is short, and the evidence names other slaves: this one
    /// took part, its inputs are confirmed.
    Others,
    /// The count is short and this slave is named by the evidence: its
    /// inputs are unconfirmed.
    Named(Evidence),
    /// The count is short and names no slave: every slave's inputs are
    /// unconfirmed.
    Unknown,
}

impl Missed {
    /// Return whether the slave's inputs are confirmed.
    #[must_use]
    pub const fn confirmed(self) -> bool {
        matches!(self, Missed::No | Missed::Others)
    }

    /// Return whether the count was short.
    #[must_use]
    pub const fn short(self) -> bool {
        !matches!(self, Missed::No)
    }
}

/// What one slave's registers read in the capture say of its taking part.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Watch {
    /// Its last AL status is out of operation.
    al_out: bool,
    /// Its links as last read.
    links: Option<u8>,
    /// Its lost-link counters as last read.
    lost_links: [Option<u8>; 4],
    /// A link event since its last whole cycle.
    event: Option<Evidence>,
}

impl Watch {
    /// An AL status read.
    pub(super) fn al_status(&mut self, status: AlStatus) {
        self.al_out = status.error()
            || matches!(
                status.state(),
                Some(AlState::Init | AlState::PreOp | AlState::Boot)
            );
    }

    /// A DL status read of byte 0x0110.
    pub(super) fn dl_status(&mut self, low: u8) {
        let links = low >> 4;
        if self.links.is_some_and(|before| before != links) {
            self.event = Some(Evidence::DlStatus);
        }
        self.links = Some(links);
    }

    /// An error-counters read (`bytes` from 0x0300, each where read): a
    /// lost-link counter that rose is an event, one that fell a reset.
    pub(super) fn error_counters(&mut self, bytes: &[Option<u8>]) {
        let lost = bytes.get(LOST_LINKS).unwrap_or(&[]);
        for (kept, now) in self.lost_links.iter_mut().zip(lost) {
            if let (Some(before), Some(now)) = (*kept, *now) {
                if now > before {
                    self.event = Some(Evidence::LostLink);
                }
            }
            if now.is_some() {
                *kept = *now;
            }
        }
    }

    /// What names the slave now, if anything.
    fn named(&self) -> Option<Evidence> {
        if self.al_out {
            Some(Evidence::AlStatus)
        } else {
            self.event
        }
    }

    /// A cycle whose count was whole: link events before it are spent.
    pub(super) fn whole(&mut self) {
        self.event = None;
    }
}

/// What a cycle's count says of each slave it touched: `touched` holds
/// each slave (a number `watch` looks up) and its share; `out` gets one
/// verdict per slave, in the same order.
pub(super) fn missed<'w>(
    touched: &[(usize, u16)],
    watch: impl Fn(usize) -> &'w Watch,
    expected: u16,
    wkc: u16,
    out: &mut Vec<Missed>,
) {
    out.clear();
    out.resize(touched.len(), Missed::No);
    if wkc >= expected {
        return;
    }
    let short = u32::from(expected - wkc);
    // The slaves the capture's registers name, when their shares can
    // explain the shortfall.
    let named: u32 = touched
        .iter()
        .filter(|&&(i, share)| share > 0 && watch(i).named().is_some())
        .map(|&(_, share)| u32::from(share))
        .sum();
    let set = if named > 0 && named >= short {
        None
    } else {
        match unique_set(touched, short) {
            Some(set) => Some(set),
            None => {
                for (&(_, share), missed) in touched.iter().zip(out.iter_mut()) {
                    if share > 0 {
                        *missed = Missed::Unknown;
                    }
                }
                return;
            }
        }
    };
    for (k, (&(i, share), missed)) in touched.iter().zip(out.iter_mut()).enumerate() {
        if share == 0 {
            continue;
        }
        *missed = match set {
            None => watch(i).named().map_or(Missed::Others, Missed::Named),
            Some(set) if set & (1 << k) != 0 => Missed::Named(Evidence::Share),
            Some(_) => Missed::Others,
        };
    }
}

/// The one set of slaves (a bit per place in `touched`) whose shares add
/// up to `short`, when exactly one does.
fn unique_set(touched: &[(usize, u16)], short: u32) -> Option<u32> {
    if touched.len() > SHARE_SEARCH {
        return None;
    }
    let mut found = None;
    for set in 1u32..(1 << touched.len()) {
        let sum: u32 = touched
            .iter()
            .enumerate()
            .filter(|(k, _)| set & (1 << k) != 0)
            .map(|(_, &(_, share))| u32::from(share))
            .sum();
        if sum == short {
            if found.is_some() {
                return None;
            }
            found = Some(set);
        }
    }
    found
}

#[cfg(test)]
mod tests {
    use super::*;

    fn watch(status: u16) -> Watch {
        let mut w = Watch::default();
        w.al_status(AlStatus(status));
        w
    }

    /// The verdicts of a cycle over slaves given as (share, watch).
    fn verdicts(touched: &[(u16, &Watch)], expected: u16, wkc: u16) -> Vec<Missed> {
        let places: Vec<(usize, u16)> = touched
            .iter()
            .enumerate()
            .map(|(k, &(share, _))| (k, share))
            .collect();
        let mut out = Vec::new();
        missed(&places, |k| touched[k].1, expected, wkc, &mut out);
        out
    }

    #[test]
    fn al_status_names_the_slave_among_equal_shares() {
        let (op, fault) = (watch(0x08), watch(0x14));
        let touched = [(3, &op), (3, &fault), (3, &op)];
        assert_eq!(
            verdicts(&touched, 9, 6),
            [
                Missed::Others,
                Missed::Named(Evidence::AlStatus),
                Missed::Others
            ]
        );
        // Equal shares and nothing read: no one is named.
        let touched = [(3, &op), (3, &op), (3, &op)];
        assert_eq!(verdicts(&touched, 9, 6), [Missed::Unknown; 3]);
        // A shortfall the named slave cannot explain alone.
        let touched = [(3, &op), (1, &fault), (3, &op)];
        assert_eq!(verdicts(&touched, 7, 3), [Missed::Unknown; 3]);
        // SAFEOP without error is no evidence; the unique share is.
        let touched = [(2, &watch(0x04)), (1, &op)];
        assert_eq!(
            verdicts(&touched, 3, 1),
            [Missed::Named(Evidence::Share), Missed::Others]
        );
        assert_eq!(verdicts(&touched, 3, 3), [Missed::No; 2]);
    }

    #[test]
    fn link_events_last_until_a_whole_cycle() {
        let op = watch(0x08);
        let mut lost = watch(0x08);
        let mut counters = [None; 0x14];
        counters[0x11] = Some(0);
        lost.error_counters(&counters);
        assert_eq!(lost.named(), None);
        counters[0x11] = Some(2);
        lost.error_counters(&counters);
        assert_eq!(lost.named(), Some(Evidence::LostLink));
        let touched = [(3, &op), (3, &lost)];
        assert_eq!(
            verdicts(&touched, 6, 3),
            [Missed::Others, Missed::Named(Evidence::LostLink)]
        );
        lost.whole();
        assert_eq!(lost.named(), None);
        // A reset (a fall) is no event; a link change is.
        counters[0x11] = Some(0);
        lost.error_counters(&counters);
        assert_eq!(lost.named(), None);
        lost.dl_status(0x30);
        lost.dl_status(0x10);
        assert_eq!(lost.named(), Some(Evidence::DlStatus));
    }
}
