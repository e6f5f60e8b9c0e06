//! `Serialize`/`Deserialize` for the PDO mapping, which cannot derive them
//! (feature `serde`): a mapping is the sequence of its entries, checked by
//! [`PdoMapping::push`] when read back.

use core::fmt;

use serde::de::{self, SeqAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use super::{MappingEntry, PdoMapping};

impl Serialize for PdoMapping {
    /// The sequence of the entries in mapping order.
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_seq(self.entries())
    }
}

impl<'de> Deserialize<'de> for PdoMapping {
    /// A sequence of entries that [`PdoMapping::push`] accepts.
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Entries;

        impl<'de> Visitor<'de> for Entries {
            type Value = PdoMapping;

            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a sequence of at most 64 PDO mapping entries of 512 bits in all")
            }

            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<PdoMapping, A::Error> {
                let mut mapping = PdoMapping::new();
                while let Some(entry) = seq.next_element::<MappingEntry>()? {
                    mapping.push(entry).map_err(de::Error::custom)?;
                }
                Ok(mapping)
            }
        }

        deserializer.deserialize_seq(Entries)
    }
}
