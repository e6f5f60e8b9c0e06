//! Where the names of a node's objects come from (`object` in
//! docs/canopen.md#object-names): the node's EDS/DCF first, then the CiA 301
//! communication objects and the device profile's.

use crate::canopen::{object_name, ObjectSet};
use crate::eds::Eds;

/// How a node's objects are named (`object` in docs/canopen.md#object-names):
/// for a node given an EDS or DCF (`--eds`,
/// [`DecoderConfig::eds`](super::DecoderConfig::eds)), the object's
/// `ParameterName` there; else — or where the file does not describe the object
/// — the CiA 301 communication objects 1000h–1FFFh and the device profile's
/// objects (of the node's profile, or CiA 402's for a node whose EDS makes it a
/// drive). The name is the object's, not a sub-entry's.
///
/// ```
/// use motionwire::canopen::{NodeId, ObjectSet};
/// use motionwire::decoder::{Decoder, DecoderConfig, ObjectNames};
/// use motionwire::eds::Eds;
///
/// let eds = "[1000]\nParameterName=Device type\nDataType=0x0007\nAccessType=ro\n\
///            DefaultValue=0x00020192\n\n\
///            [6040]\nParameterName=Control word\nDataType=0x0006\nAccessType=rw\n";
/// let node = NodeId::new(3).unwrap();
/// let eds = Eds::parse(eds, "drive.eds", Some(node)).unwrap();
/// let decoder = Decoder::new(DecoderConfig::new().eds(node, eds).unwrap());
/// let names = decoder.object_names(node);
/// // The file's name first, the profile's (CiA 402: the file says 402) else.
/// assert_eq!(names.name(0x6040), Some("Control word"));
/// assert_eq!(names.name(0x6041), Some("Statusword"));
/// assert_eq!(names.name(0x1018), Some("Identity object"));
/// assert_eq!(ObjectNames::new(None, None).name(0x6040), None);
/// ```
#[derive(Debug, Clone, Copy, Default)]
pub struct ObjectNames<'d> {
    eds: Option<&'d Eds>,
    set: Option<ObjectSet>,
}

impl<'d> ObjectNames<'d> {
    /// Names from `eds` first, then from the communication objects and
    /// `set` (a profile's objects; `None`: the communication objects only).
    #[must_use]
    pub const fn new(eds: Option<&'d Eds>, set: Option<ObjectSet>) -> Self {
        ObjectNames { eds, set }
    }

    /// Return the node's EDS or DCF, if it was given one.
    #[must_use]
    pub const fn eds(&self) -> Option<&'d Eds> {
        self.eds
    }

    /// Return the profile's objects that name what the file does not.
    #[must_use]
    pub const fn object_set(&self) -> Option<ObjectSet> {
        self.set
    }

    /// Return the name of object `index`, where known.
    #[must_use]
    pub fn name(&self, index: u16) -> Option<&'d str> {
        match self.eds.and_then(|eds| eds.object(index)) {
            Some(object) if !object.name.is_empty() => Some(object.name.as_str()),
            _ => object_name(index, self.set),
        }
    }
}
