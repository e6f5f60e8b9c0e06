//! How a summary writes a time and a bus in JSON: [`Ts`] and [`Iface`],
//! which the records, the findings and the verdict share.

use serde::ser::Error as _;
use serde::{Serialize, Serializer};

use crate::can::BusName;
use crate::can::Timestamp;

/// A time as a JSON number with six or nine decimals.
pub(super) struct Ts(pub(super) Timestamp);

impl Serialize for Ts {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let text = self.0.seconds().to_string();
        serde_json::value::RawValue::from_string(text)
            .map_err(S::Error::custom)?
            .serialize(serializer)
    }
}

/// The `iface` of docs/output.md#common-keys: the name, the channel as a
/// string, or null.
pub(super) struct Iface<'a>(pub(super) &'a BusName);

impl Serialize for Iface<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self.0 {
            BusName::Unnamed => serializer.serialize_none(),
            BusName::Channel(n) => serializer.collect_str(n),
            BusName::Name(name) => serializer.serialize_str(name),
        }
    }
}
