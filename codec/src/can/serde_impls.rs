//! `Serialize` and `Deserialize` for the frame vocabulary (feature
//! `serde`). Deserializing checks every invariant the constructors check,
//! so no invalid frame can be made this way.

use core::fmt;

use serde::de::{self, SeqAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use super::{
    CanFrame, CanId, ErrorClasses, ErrorFrame, FdFlags, FrameData, FrameType, Timestamp, FD_MAX_LEN,
};

/// A [`CanId`] as written: the number and whether it is extended.
#[derive(Serialize, Deserialize)]
#[serde(rename = "CanId")]
struct RawId {
    raw: u32,
    extended: bool,
}

impl Serialize for CanId {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        RawId {
            raw: self.raw(),
            extended: self.is_extended(),
        }
        .serialize(serializer)
    }
}

impl<'de> Deserialize<'de> for CanId {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let raw = RawId::deserialize(deserializer)?;
        let id = if raw.extended {
            CanId::extended(raw.raw)
        } else {
            CanId::standard(raw.raw)
        };
        id.ok_or_else(|| {
            de::Error::invalid_value(
                de::Unexpected::Unsigned(u64::from(raw.raw)),
                &if raw.extended {
                    "an extended identifier, at most 0x1FFFFFFF"
                } else {
                    "a standard identifier, at most 0x7FF"
                },
            )
        })
    }
}

impl Serialize for FdFlags {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_u8(self.bits())
    }
}

impl<'de> Deserialize<'de> for FdFlags {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let bits = u8::deserialize(deserializer)?;
        FdFlags::new(bits).ok_or_else(|| {
            de::Error::invalid_value(
                de::Unexpected::Unsigned(u64::from(bits)),
                &"a nibble, 0..=15",
            )
        })
    }
}

impl Serialize for FrameData {
    /// The sequence of the data bytes.
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_seq(self.as_slice())
    }
}

impl<'de> Deserialize<'de> for FrameData {
    /// A sequence of at most 64 bytes.
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Bytes;

        impl<'de> Visitor<'de> for Bytes {
            type Value = FrameData;

            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a sequence of at most 64 bytes")
            }

            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<FrameData, A::Error> {
                let mut bytes = [0; FD_MAX_LEN];
                let mut len = 0;
                while let Some(byte) = seq.next_element::<u8>()? {
                    match bytes.get_mut(len) {
                        Some(slot) => *slot = byte,
                        None => return Err(de::Error::invalid_length(FD_MAX_LEN + 1, &self)),
                    }
                    len += 1;
                }
                FrameData::new(bytes.get(..len).unwrap_or_default()).map_err(de::Error::custom)
            }
        }

        deserializer.deserialize_seq(Bytes)
    }
}

/// A [`CanFrame`] as written: its parts, checked when read back.
#[derive(Serialize, Deserialize)]
#[serde(rename = "CanFrame")]
struct Parts {
    id: CanId,
    frame_type: FrameType,
    data: FrameData,
}

impl Serialize for CanFrame {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        Parts {
            id: self.id(),
            frame_type: self.frame_type(),
            data: FrameData::new(self.data()).map_err(serde::ser::Error::custom)?,
        }
        .serialize(serializer)
    }
}

impl<'de> Deserialize<'de> for CanFrame {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let parts = Parts::deserialize(deserializer)?;
        CanFrame::with_type(parts.id, parts.frame_type, parts.data.as_slice())
            .map_err(de::Error::custom)
    }
}

/// An [`ErrorFrame`] as written: its classes and data bytes.
#[derive(Serialize, Deserialize)]
#[serde(rename = "ErrorFrame")]
struct ErrorParts {
    classes: ErrorClasses,
    data: FrameData,
}

impl Serialize for ErrorFrame {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        ErrorParts {
            classes: self.classes,
            data: FrameData::new(self.data()).map_err(serde::ser::Error::custom)?,
        }
        .serialize(serializer)
    }
}

impl<'de> Deserialize<'de> for ErrorFrame {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let parts = ErrorParts::deserialize(deserializer)?;
        let frame = CanFrame::new_error(parts.classes.bits(), parts.data.as_slice())
            .map_err(de::Error::custom)?;
        ErrorFrame::from_frame(&frame).map_err(de::Error::custom)
    }
}

impl Serialize for Timestamp {
    /// Seconds and nanoseconds, as `core::time::Duration` is written.
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        self.as_duration().serialize(serializer)
    }
}

impl<'de> Deserialize<'de> for Timestamp {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        core::time::Duration::deserialize(deserializer).map(Timestamp::from_duration)
    }
}
