//! A slave's CoE SDO transfers followed message by message (ETG.1000.6
//! §5.6.2; docs/ethercat.md#coe-sdo): what each message is in its
//! transfer ([`CoeSdoStep`]), and the transfer it completes
//! ([`CoeTransfer`]). The summary counts and times them from it; the
//! process image keeps the PDO objects they write or read.

use core::time::Duration;

use crate::can::Timestamp;
use crate::ethercat::CoeSdo;

/// The data of a transfer the channel keeps: enough for a PDO object
/// (sub-index 0, its padding and 64 entries of 4 bytes); past it the
/// bytes are counted, not kept.
pub const COE_DATA_KEPT: usize = 2 + 4 * 64;

/// A CoE SDO transfer a message completed.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CoeTransfer {
    /// The object.
    pub index: u16,
    /// The sub-index (the first, with complete access).
    pub sub_index: u8,
    /// An upload (the master reads) or a download.
    pub upload: bool,
    /// Complete access: the object's sub-indices from `sub_index` on.
    pub complete_access: bool,
    /// Whether segments followed the initiate exchange.
    pub segmented: bool,
    /// The data's bytes, as the messages carried them.
    pub size: usize,
    /// From the request that opened it to the message that completed it,
    /// where both have a time.
    pub latency: Option<Duration>,
    /// The data the messages carried: its first [`COE_DATA_KEPT`] bytes
    /// ([`truncated`](Self::truncated) when there were more).
    pub data: Vec<u8>,
}

impl CoeTransfer {
    /// Return whether the transfer carried more bytes than
    /// [`data`](Self::data) keeps ([`COE_DATA_KEPT`]).
    #[must_use]
    pub fn truncated(&self) -> bool {
        self.size > self.data.len()
    }
}

/// What one CoE SDO message is in its slave's transfer.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct CoeSdoStep {
    /// The message opened a transfer (an initiate request).
    pub started: bool,
    /// The transfer the message completed: a download's confirmation
    /// after its last data, an upload's last data.
    pub ended: Option<CoeTransfer>,
    /// An abort, from either side, ended the transfer open.
    pub aborted: bool,
}

/// A transfer in progress.
#[derive(Debug, Clone)]
struct Open {
    index: u16,
    sub_index: u8,
    complete_access: bool,
    upload: bool,
    /// The size the initiate message announced.
    size: Option<usize>,
    /// Bytes carried so far, and the first [`COE_DATA_KEPT`] of them.
    carried: usize,
    data: Vec<u8>,
    /// Segments follow the initiate exchange.
    segmented: bool,
    /// A download's last data is sent: the next confirmation ends it.
    last_sent: bool,
    started: Option<Timestamp>,
}

/// One slave's SDO channel.
#[derive(Debug, Clone, Default)]
pub(super) struct CoeChannel {
    open: Option<Open>,
}

impl CoeChannel {
    /// Read a message: `request` from the master (a write of the master's
    /// mailbox), else the slave's; `timestamp` its packet's time.
    pub(super) fn message(
        &mut self,
        request: bool,
        sdo: &CoeSdo<'_>,
        timestamp: Option<Timestamp>,
    ) -> CoeSdoStep {
        let command = sdo.command();
        let mut step = CoeSdoStep::default();
        if sdo.specifier() == 4 {
            step.aborted = self.open.take().is_some();
            return step;
        }
        match (request, sdo.specifier()) {
            (true, 1) => {
                // Initiate download: expedited, or its size and as much
                // data as the message holds.
                let Some((index, sub_index)) = sdo.multiplexer() else {
                    self.open = None;
                    return step;
                };
                let data = sdo.initiate_data();
                let (size, bytes) = initiate(command, data);
                let mut open = Open {
                    index,
                    sub_index,
                    complete_access: sdo.complete_access(),
                    upload: false,
                    size,
                    carried: 0,
                    data: Vec::new(),
                    segmented: false,
                    last_sent: false,
                    started: timestamp,
                };
                open.carry(bytes);
                open.last_sent = size.map_or(command & 0x02 != 0, |s| open.carried >= s);
                open.segmented = !open.last_sent;
                self.open = Some(open);
                step.started = true;
            }
            (true, 2) => {
                // Initiate upload.
                self.open = sdo.multiplexer().map(|(index, sub_index)| Open {
                    index,
                    sub_index,
                    complete_access: sdo.complete_access(),
                    upload: true,
                    size: None,
                    carried: 0,
                    data: Vec::new(),
                    segmented: false,
                    last_sent: false,
                    started: timestamp,
                });
                step.started = self.open.is_some();
            }
            (true, 0) => {
                // Download segment.
                if let Some(open) = self.open.as_mut().filter(|o| !o.upload) {
                    open.carry(segment(command, sdo.segment_data()));
                    open.last_sent = command & 0x01 != 0;
                }
            }
            // Initiate download response, download segment response.
            (false, 3 | 1) if self.open.as_ref().is_some_and(|o| !o.upload && o.last_sent) => {
                step.ended = self.end(timestamp);
            }
            (false, 2) => {
                // Initiate upload response: expedited, or its size and as
                // much data as the message holds.
                if let Some(open) = self.open.as_mut().filter(|o| o.upload) {
                    let (size, bytes) = initiate(command, sdo.initiate_data());
                    open.size = size;
                    open.carried = 0;
                    open.data.clear();
                    open.carry(bytes);
                    let whole = size.map_or(command & 0x02 != 0, |s| open.carried >= s);
                    open.segmented = !whole;
                    if whole {
                        step.ended = self.end(timestamp);
                    }
                }
            }
            (false, 0) => {
                // Upload segment response.
                if let Some(open) = self.open.as_mut().filter(|o| o.upload) {
                    open.carry(segment(command, sdo.segment_data()));
                    if command & 0x01 != 0 {
                        step.ended = self.end(timestamp);
                    }
                }
            }
            _ => {}
        }
        step
    }

    /// Complete the open transfer.
    fn end(&mut self, now: Option<Timestamp>) -> Option<CoeTransfer> {
        let open = self.open.take()?;
        let latency = open
            .started
            .zip(now)
            .map(|(start, end)| end.as_duration().saturating_sub(start.as_duration()));
        Some(CoeTransfer {
            index: open.index,
            sub_index: open.sub_index,
            upload: open.upload,
            complete_access: open.complete_access,
            segmented: open.segmented,
            size: open.carried,
            latency,
            data: open.data,
        })
    }
}

impl Open {
    /// Take a message's data: counted, and kept up to [`COE_DATA_KEPT`]
    /// bytes, no more than the announced size.
    fn carry(&mut self, bytes: &[u8]) {
        let wanted = match self.size {
            Some(size) => size.saturating_sub(self.carried).min(bytes.len()),
            None => bytes.len(),
        };
        let room = COE_DATA_KEPT.saturating_sub(self.data.len()).min(wanted);
        self.data.extend_from_slice(&bytes[..room]);
        self.carried += wanted;
    }
}

/// An initiate message's size and data: expedited, its 4 bytes less the
/// unused count when the size is indicated; else the size and the bytes
/// after it.
fn initiate(command: u8, data: &[u8]) -> (Option<usize>, &[u8]) {
    let expedited = command & 0x02 != 0;
    let sized = command & 0x01 != 0;
    if expedited {
        let n = if sized {
            usize::from((command >> 2) & 0x03)
        } else {
            0
        };
        let len = (4 - n).min(data.len());
        return (Some(len), &data[..len]);
    }
    match data.get(..4) {
        Some(b) if sized => (
            Some(u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize),
            &data[4..],
        ),
        Some(_) => (None, &data[4..]),
        None => (None, &data[..0]),
    }
}

/// A segment's data: all the bytes after the command byte when the
/// mailbox holds more than the 7 of CiA 301's segment, else 7 less the
/// unused count in bits 1–3.
fn segment(command: u8, data: &[u8]) -> &[u8] {
    if data.len() > 7 {
        return data;
    }
    let unused = usize::from((command >> 1) & 0x07);
    &data[..data.len().min(7 - unused.min(7))]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(ms: u32) -> Option<Timestamp> {
        Timestamp::new(1, ms * 1000)
    }

    fn step(channel: &mut CoeChannel, request: bool, bytes: &[u8], ms: u32) -> CoeSdoStep {
        channel.message(request, &CoeSdo::parse(bytes).unwrap(), at(ms))
    }

    #[test]
    fn a_segmented_upload_counts_more_than_it_keeps() {
        let mut channel = CoeChannel::default();
        assert!(step(&mut channel, true, &[0x40, 0x08, 0x10, 0, 0, 0, 0, 0], 0).started);
        // Normal response: 300 bytes announced, 4 carried.
        let mut response = vec![0x41, 0x08, 0x10, 0, 0x2C, 0x01, 0, 0];
        response.extend([b'a'; 4]);
        assert_eq!(
            step(&mut channel, false, &response, 1),
            CoeSdoStep::default()
        );
        // One CoE segment with the other 296 bytes, the last.
        assert_eq!(
            step(&mut channel, true, &[0x60, 0, 0, 0, 0, 0, 0, 0], 2),
            CoeSdoStep::default()
        );
        let mut segment = vec![0x01];
        segment.extend([b'b'; 296]);
        let ended = step(&mut channel, false, &segment, 5).ended.unwrap();
        assert_eq!(
            (ended.index, ended.upload, ended.segmented),
            (0x1008, true, true)
        );
        assert_eq!(ended.size, 300);
        assert_eq!(ended.latency, Some(Duration::from_millis(5)));
        assert_eq!(ended.data.len(), COE_DATA_KEPT);
        assert!(ended.data.starts_with(b"aaaab"));
        assert!(ended.truncated());
    }

    #[test]
    fn a_download_ends_with_its_confirmation_and_an_abort_with_nothing() {
        let mut channel = CoeChannel::default();
        // Expedited download of one byte, confirmed.
        assert!(step(&mut channel, true, &[0x2F, 0x60, 0x60, 0, 8, 0, 0, 0], 10).started);
        let ended = step(&mut channel, false, &[0x60, 0x60, 0x60, 0, 0, 0, 0, 0], 11)
            .ended
            .unwrap();
        assert_eq!(
            (ended.size, ended.upload, ended.segmented),
            (1, false, false)
        );
        assert_eq!(ended.data, [8]);
        assert!(!ended.truncated());
        // A confirmation with nothing open completes nothing.
        assert_eq!(
            step(&mut channel, false, &[0x60, 0x60, 0x60, 0, 0, 0, 0, 0], 12),
            CoeSdoStep::default()
        );
        // An abort ends the transfer open, from either side.
        step(&mut channel, true, &[0x40, 0x41, 0x60, 0, 0, 0, 0, 0], 13);
        let abort = [0x80, 0x41, 0x60, 0, 0x00, 0x00, 0x02, 0x06];
        assert!(step(&mut channel, true, &abort, 14).aborted);
        assert!(!step(&mut channel, false, &abort, 15).aborted);
    }
}
