//! A slave's SII (its EEPROM) as far as the capture read it, and the PDOs
//! its categories describe (docs/ethercat.md#sii-pdos).
//!
//! Masters read the SII a few words at a time through registers 0x0502
//! (control and status), 0x0504 (word address) and 0x0508 (data, 4 or 8
//! bytes a read), and only the parts they need: the words read make an
//! image with holes. The category area starts at word 0x40 (ETG.2010
//! §2.3): each category is a type (16 bits) and a size in words, then its
//! data; type 0xFFFF ends the list. Read here: strings (10: a count, then
//! each string as a length byte and its bytes), TxPDO (50) and RxPDO (51):
//! each PDO an 8-byte header (index 16 bits, entry count, sync manager, DC
//! sync, name string index, flags 16 bits) and its entries of 8 bytes
//! (index 16 bits, sub-index, name string index, data type, bit length,
//! flags 16 bits). A category whose header was not read hides every one
//! after it; a PDO of which a byte was not read is left out.

use std::collections::BTreeMap;

use crate::canopen::{DataType, MappingEntry};

use super::config::{PdoConfig, PdoEntryConfig, SlaveConfig};

/// The words of the SII kept per slave: 0x0000–0x3FFF (a 32 KiB EEPROM;
/// the category areas of the devices seen end far below). Words read past
/// it are not kept.
pub(super) const SII_WORDS: u32 = 0x4000;
/// Where the category area starts (word address).
const CATEGORIES: usize = 0x40;
/// The categories read at most, and the end marker.
const MAX_CATEGORIES: usize = 256;
const END: u16 = 0xFFFF;
/// Category types.
const STRINGS: u16 = 10;
const TX_PDO: u16 = 50;
const RX_PDO: u16 = 51;
/// A PDO's header and an entry: 8 bytes each.
const PDO_HEADER: usize = 8;
const PDO_ENTRY: usize = 8;
/// The sync managers a PDO can name (ESC: 16); another value assigns the
/// PDO to none.
const SYNC_MANAGERS: u8 = 16;

/// One slave's SII words as the capture read them: kept by address, so
/// that memory grows with the words read, not with their addresses.
#[derive(Debug, Clone, Default)]
pub(super) struct SiiImage {
    words: BTreeMap<u32, u16>,
}

impl SiiImage {
    /// Keep the bytes read at `word` (whole words; an odd last byte is
    /// dropped). Return whether a word changed.
    pub(super) fn store(&mut self, word: u32, bytes: &[u8]) -> bool {
        let mut changed = false;
        for (k, pair) in bytes.chunks_exact(2).enumerate() {
            let Some(at) = word.checked_add(k as u32).filter(|&w| w < SII_WORDS) else {
                break;
            };
            let value = u16::from_le_bytes([pair[0], pair[1]]);
            changed |= self.words.insert(at, value) != Some(value);
        }
        changed
    }

    fn word(&self, at: usize) -> Option<u16> {
        self.words.get(&u32::try_from(at).ok()?).copied()
    }

    fn byte(&self, at: usize) -> Option<u8> {
        let word = self.word(at / 2)?;
        Some(word.to_le_bytes()[at % 2])
    }

    fn bytes<const N: usize>(&self, at: usize) -> Option<[u8; N]> {
        let mut out = [0; N];
        for (k, b) in out.iter_mut().enumerate() {
            *b = self.byte(at + k)?;
        }
        Some(out)
    }

    /// The PDOs the TxPDO and RxPDO categories describe, as a
    /// configuration: each PDO with its entries (named by the strings
    /// category where the capture read the string), and the assignment
    /// of each sync manager a PDO names, in the SII's order. `None` where
    /// no PDO was read.
    pub(super) fn layout(&self) -> Option<SlaveConfig> {
        let last = match self.words.last_key_value() {
            Some((&last, _)) if last as usize > CATEGORIES => last as usize,
            _ => return None,
        };
        let mut strings = Vec::new();
        let mut pdos = Vec::new();
        let mut at = CATEGORIES;
        for _ in 0..MAX_CATEGORIES {
            let (Some(kind), Some(size)) = (self.word(at), self.word(at + 1)) else {
                break;
            };
            if kind == END {
                break;
            }
            let data = at + 2;
            let end = data + usize::from(size);
            match kind {
                STRINGS => strings = self.strings(data * 2, end * 2),
                TX_PDO | RX_PDO => self.pdos(data * 2, end * 2, &mut pdos),
                _ => {}
            }
            at = end;
            if at > last {
                break;
            }
        }
        if pdos.is_empty() {
            return None;
        }
        let name = |index: u8| -> Option<String> {
            let k = usize::from(index).checked_sub(1)?;
            strings.get(k).cloned().flatten()
        };
        let mut config = SlaveConfig::default();
        for pdo in pdos {
            if pdo.sm < SYNC_MANAGERS {
                match config.assignment.iter_mut().find(|(n, _)| *n == pdo.sm) {
                    Some((_, list)) => list.push(pdo.index),
                    None => config.assignment.push((pdo.sm, vec![pdo.index])),
                }
            }
            config.pdos.push(PdoConfig {
                index: pdo.index,
                entries: pdo
                    .entries
                    .iter()
                    .map(|e| PdoEntryConfig {
                        entry: MappingEntry::new(e.index, e.sub_index, e.bits),
                        name: name(e.name),
                        data_type: DataType::try_from(u16::from(e.data_type)).ok(),
                    })
                    .collect(),
            });
        }
        Some(config)
    }

    /// The strings of a strings category over bytes `[from, to)`: each
    /// where the capture read it and every length byte before it.
    fn strings(&self, from: usize, to: usize) -> Vec<Option<String>> {
        let mut out = Vec::new();
        let Some(count) = self.byte(from) else {
            return out;
        };
        let mut at = from + 1;
        for _ in 0..count {
            let Some(len) = self.byte(at) else {
                break;
            };
            let len = usize::from(len);
            if at + 1 + len > to {
                break;
            }
            let text: Option<Vec<u8>> = (at + 1..at + 1 + len).map(|b| self.byte(b)).collect();
            // ETG.2010 strings are ASCII; other bytes are read as Latin-1.
            out.push(text.map(|t| t.iter().map(|&b| char::from(b)).collect()));
            at += 1 + len;
        }
        out
    }

    /// The PDOs of a TxPDO or RxPDO category over bytes `[from, to)`.
    fn pdos(&self, from: usize, to: usize, out: &mut Vec<SiiPdo>) {
        let mut at = from;
        while at + PDO_HEADER <= to {
            // Without its header, the PDO's length and all after it are
            // unknown.
            let Some(h) = self.bytes::<PDO_HEADER>(at) else {
                return;
            };
            let count = usize::from(h[2]);
            let end = at + PDO_HEADER + count * PDO_ENTRY;
            if end > to {
                return;
            }
            let entries: Option<Vec<SiiEntry>> = (0..count)
                .map(|k| {
                    let e = self.bytes::<PDO_ENTRY>(at + PDO_HEADER + k * PDO_ENTRY)?;
                    Some(SiiEntry {
                        index: u16::from_le_bytes([e[0], e[1]]),
                        sub_index: e[2],
                        name: e[3],
                        data_type: e[4],
                        bits: e[5],
                    })
                })
                .collect();
            if let Some(entries) = entries {
                out.push(SiiPdo {
                    index: u16::from_le_bytes([h[0], h[1]]),
                    sm: h[3],
                    entries,
                });
            }
            at = end;
        }
    }
}

/// A PDO of the SII.
#[derive(Debug)]
struct SiiPdo {
    index: u16,
    sm: u8,
    entries: Vec<SiiEntry>,
}

/// An entry of a PDO of the SII.
#[derive(Debug)]
struct SiiEntry {
    index: u16,
    sub_index: u8,
    name: u8,
    data_type: u8,
    bits: u8,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An SII with a strings category (`Out`, `Channel 1`) and an RxPDO
    /// category: 0x1600 on SM 0 with 0x7000:01 (BOOLEAN, 1 bit, named
    /// string 1) and a 7-bit gap.
    fn bytes() -> Vec<u8> {
        let mut b = vec![0u8; CATEGORIES * 2];
        let strings: &[u8] = &[
            2, 3, b'O', b'u', b't', 9, b'C', b'h', b'a', b'n', b'n', b'e', b'l', b' ', b'1', 0,
        ];
        b.extend(STRINGS.to_le_bytes());
        b.extend(((strings.len() / 2) as u16).to_le_bytes());
        b.extend(strings);
        let pdo: &[u8] = &[
            0x00, 0x16, 2, 0, 0, 2, 0, 0, // 0x1600, 2 entries, SM 0, name 2
            0x00, 0x70, 1, 1, 1, 1, 0, 0, // 0x7000:01, name 1, BOOLEAN, 1 bit
            0x00, 0x00, 0, 0, 0, 7, 0, 0, // a gap of 7 bits
        ];
        b.extend(RX_PDO.to_le_bytes());
        b.extend(((pdo.len() / 2) as u16).to_le_bytes());
        b.extend(pdo);
        b.extend(END.to_le_bytes());
        b.extend([0xFF, 0xFF]);
        b
    }

    fn image(bytes: &[u8], skip: impl Fn(usize) -> bool) -> SiiImage {
        let mut sii = SiiImage::default();
        for (w, pair) in bytes.chunks(2).enumerate() {
            if !skip(w) {
                sii.store(w as u32, pair);
            }
        }
        sii
    }

    #[test]
    fn rx_pdo_category_with_names() {
        let config = image(&bytes(), |_| false).layout().unwrap();
        assert_eq!(config.assignment, [(0, vec![0x1600])]);
        let pdo = &config.pdos[0];
        assert_eq!(pdo.index, 0x1600);
        assert_eq!(pdo.entries[0].entry, MappingEntry::new(0x7000, 1, 1));
        assert_eq!(pdo.entries[0].name.as_deref(), Some("Out"));
        assert_eq!(pdo.entries[0].data_type, Some(DataType::Boolean));
        assert_eq!(pdo.entries[1].entry, MappingEntry::new(0, 0, 7));
        assert_eq!(pdo.entries[1].name, None);
    }

    /// A string not read leaves its entry unnamed; a string after it
    /// whose length byte was read is still found.
    #[test]
    fn holes() {
        let bytes = bytes();
        // Word 0x43 holds "ut" of the first string.
        let config = image(&bytes, |w| w == 0x43).layout().unwrap();
        assert_eq!(config.pdos[0].entries[0].name, None);
        // A missing PDO entry drops the PDO; a missing category header
        // hides the PDOs.
        let entry = 0x42 + 8 + 2 + 4;
        assert!(image(&bytes, |w| w == entry).layout().is_none());
        assert!(image(&bytes, |w| w == 0x40).layout().is_none());
        // Nothing past the kept words, nothing odd.
        let mut sii = SiiImage::default();
        assert!(!sii.store(SII_WORDS, &[1, 2]));
        assert!(!sii.store(u32::MAX, &[1, 2, 3]));
        assert!(sii.words.is_empty());
        assert!(sii.layout().is_none());
    }
}
