//! `Serialize`/`Deserialize` for [`Octets`], which cannot derive them
//! (feature `serde`): octets are their length in bits and their bytes,
//! checked by [`Octets::new`] when read back.

use core::fmt;

use serde::de::{self, SeqAccess, Visitor};
use serde::ser::SerializeStruct;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use super::{Octets, MAX_OCTETS};

impl Serialize for Octets {
    /// `{"bits": n, "bytes": [...]}` with `bits.div_ceil(8)` bytes.
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut s = serializer.serialize_struct("Octets", 2)?;
        s.serialize_field("bits", &self.bits())?;
        s.serialize_field("bytes", self.as_bytes())?;
        s.end()
    }
}

/// The bytes of an [`Octets`] value as read back: at most [`MAX_OCTETS`].
struct Bytes {
    bytes: [u8; MAX_OCTETS],
    len: usize,
}

impl<'de> Deserialize<'de> for Bytes {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Seq;

        impl<'de> Visitor<'de> for Seq {
            type Value = Bytes;

            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a sequence of at most 32 bytes")
            }

            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Bytes, A::Error> {
                let mut out = Bytes {
                    bytes: [0; MAX_OCTETS],
                    len: 0,
                };
                while let Some(byte) = seq.next_element::<u8>()? {
                    match out.bytes.get_mut(out.len) {
                        Some(slot) => *slot = byte,
                        None => return Err(de::Error::invalid_length(MAX_OCTETS + 1, &self)),
                    }
                    out.len += 1;
                }
                Ok(out)
            }
        }

        deserializer.deserialize_seq(Seq)
    }
}

#[derive(Deserialize)]
#[serde(rename = "Octets")]
struct Parts {
    bits: u8,
    bytes: Bytes,
}

impl<'de> Deserialize<'de> for Octets {
    /// `{"bits": n, "bytes": [...]}`, refused unless the bytes are exactly
    /// the `bits.div_ceil(8)` that [`Octets::new`] needs.
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let parts = Parts::deserialize(deserializer)?;
        Octets::new(&parts.bytes.bytes[..parts.bytes.len], parts.bits).ok_or_else(|| {
            de::Error::custom(format_args!(
                "{} bytes do not hold {} bits exactly",
                parts.bytes.len, parts.bits
            ))
        })
    }
}
