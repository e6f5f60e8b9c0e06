//! Device-specific layouts: how one vendor's device fills the fields that
//! CANopen leaves to the manufacturer, kept apart from the generic codecs
//! (docs/canopen.md#profiles).
//!
//! The generic codecs in [`crate::canopen`] decode every device's frames;
//! a profile gives the manufacturer-specific bytes their meaning for one
//! device family.

pub mod akd;
pub mod baumer;

use crate::canopen::{NodeId, ObjectSet};

/// How a node's device-specific bytes are read: the manufacturer field of
/// its EMCYs (`--profile` in docs/output.md#command) and the profile objects
/// that name its SDO objects and PDO signals (docs/canopen.md#object-names,
/// docs/canopen.md#signals).
///
/// ```
/// use motionwire_codec::profiles::Profile;
///
/// assert_eq!(Profile::from_name("akd"), Some(Profile::Akd));
/// assert_eq!(Profile::Baumer.name(), "baumer");
/// assert_eq!(Profile::from_name("kollmorgen"), None);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum Profile {
    /// CiA 301 only: the manufacturer field as raw bytes.
    #[default]
    Generic,
    /// Kollmorgen AKD, a CiA 402 drive: axis and feedback ids in the EMCY
    /// (docs/canopen.md#akd, [`akd`]); the node is a drive
    /// (docs/canopen.md#cia402).
    Akd,
    /// Baumer EAM580 encoder: alarms, warnings and diagnostic sources
    /// (docs/canopen.md#baumer, [`baumer`]).
    Baumer,
}

impl Profile {
    /// Every profile, in the order `--profile` lists them.
    pub const ALL: [Profile; 3] = [Profile::Generic, Profile::Akd, Profile::Baumer];

    /// Return the profile's name as `--profile` takes it: `generic`, `akd`,
    /// `baumer`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Profile::Generic => "generic",
            Profile::Akd => "akd",
            Profile::Baumer => "baumer",
        }
    }

    /// Return the profile named `name` (as [`name`](Self::name) writes it).
    #[must_use]
    pub fn from_name(name: &str) -> Option<Profile> {
        Profile::ALL.into_iter().find(|p| p.name() == name)
    }

    /// Return the device profile's objects that name a node's SDO objects
    /// and PDO signals (docs/canopen.md#object-names, docs/canopen.md#signals):
    /// CiA 402 for the AKD, the encoder objects for the Baumer EAM580, none for
    /// `generic`.
    #[must_use]
    pub const fn object_set(self) -> Option<ObjectSet> {
        match self {
            Profile::Generic => None,
            Profile::Akd => Some(ObjectSet::Drive),
            Profile::Baumer => Some(ObjectSet::Encoder),
        }
    }

    /// Return whether the profile is a CiA 402 drive's
    /// (docs/canopen.md#cia402).
    #[must_use]
    pub const fn is_drive(self) -> bool {
        matches!(self, Profile::Akd)
    }
}

impl core::fmt::Display for Profile {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(self.name())
    }
}

/// The profile of every node: one for the nodes not named, and one per
/// node named (`--profile 3=akd,5=baumer` in docs/output.md#command).
///
/// ```
/// use motionwire_codec::canopen::NodeId;
/// use motionwire_codec::profiles::{NodeProfiles, Profile};
///
/// let three = NodeId::new(3).unwrap();
/// let profiles = NodeProfiles::new(Profile::Generic).with(three, Profile::Akd);
/// assert_eq!(profiles.of(Some(three)), Profile::Akd);
/// assert_eq!(profiles.of(NodeId::new(4)), Profile::Generic);
/// assert_eq!(profiles.of(None), Profile::Generic);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NodeProfiles {
    /// The profile of the nodes not named.
    default: Profile,
    /// Index 1..=127: the profile a node was given, if it was.
    nodes: [Option<Profile>; 128],
}

impl Default for NodeProfiles {
    fn default() -> Self {
        NodeProfiles::new(Profile::Generic)
    }
}

impl NodeProfiles {
    /// Every node read with `default`.
    #[must_use]
    pub const fn new(default: Profile) -> Self {
        NodeProfiles {
            default,
            nodes: [None; 128],
        }
    }

    /// Return the table with `node` read with `profile`.
    #[must_use]
    pub const fn with(mut self, node: NodeId, profile: Profile) -> Self {
        self.nodes[node.get() as usize] = Some(profile);
        self
    }

    /// Read `node` with `profile` from now on.
    pub fn set(&mut self, node: NodeId, profile: Profile) {
        self.nodes[usize::from(node.get())] = Some(profile);
    }

    /// Read every node not named with [`set`](Self::set) or
    /// [`with`](Self::with) with `profile` from now on.
    pub fn set_default(&mut self, profile: Profile) {
        self.default = profile;
    }

    /// Return the profile of `node`; the default for `None` (a frame that
    /// names no node).
    #[inline]
    #[must_use]
    pub fn of(&self, node: Option<NodeId>) -> Profile {
        node.and_then(|n| self.nodes[usize::from(n.get())])
            .unwrap_or(self.default)
    }

    /// Return the profile of the nodes not named.
    #[must_use]
    pub const fn default_profile(&self) -> Profile {
        self.default
    }
}

/// An EMCY read with a node's profile: `Display` writes it as a person
/// reads it — code, class, description, error register and its flags, and
/// the manufacturer bytes as the profile reads them (raw hex for
/// `generic`; axis and feedback for the AKD, docs/canopen.md#akd; alarms,
/// warnings and diagnostic sources for the Baumer EAM580,
/// docs/canopen.md#baumer).
///
/// ```
/// use motionwire_codec::canopen::{Emcy, ErrorCode, ErrorRegister};
/// use motionwire_codec::profiles::{Profile, ProfiledEmcy};
///
/// let emcy = Emcy::new(ErrorCode::new(0x7305), ErrorRegister::GENERIC, [0x01, 0x00, 0, 0, 0]);
/// let text = ProfiledEmcy::new(&emcy, Profile::Generic).to_string();
/// assert!(text.starts_with("0x7305 "), "{text}");
/// assert!(text.ends_with("  register 0x01 [generic]  manufacturer 0100000000"), "{text}");
/// ```
#[derive(Debug, Clone, Copy)]
pub struct ProfiledEmcy<'a> {
    emcy: &'a crate::canopen::Emcy,
    profile: Profile,
}

impl<'a> ProfiledEmcy<'a> {
    /// Read `emcy` with `profile`.
    #[must_use]
    pub const fn new(emcy: &'a crate::canopen::Emcy, profile: Profile) -> Self {
        ProfiledEmcy { emcy, profile }
    }
}

impl core::fmt::Display for ProfiledEmcy<'_> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        let emcy = self.emcy;
        write!(
            f,
            "{} {}: {}  register 0x{:02X}",
            emcy.code,
            emcy.code.class(),
            emcy.code.description(),
            emcy.register.bits(),
        )?;
        let mut names = emcy.register.names().peekable();
        if names.peek().is_some() {
            f.write_str(" [")?;
            for (i, name) in names.enumerate() {
                if i > 0 {
                    f.write_str(", ")?;
                }
                f.write_str(name)?;
            }
            f.write_str("]")?;
        }
        match self.profile {
            Profile::Generic => {
                f.write_str("  manufacturer ")?;
                for b in emcy.manufacturer {
                    write!(f, "{b:02x}")?;
                }
            }
            Profile::Akd => {
                let field = akd::AkdManufacturerField::new_unchecked(&emcy.manufacturer[..]);
                write!(f, "  axis {}", field.axis_id().get())?;
                match field.feedback_id() {
                    Ok(fb) => match fb.number() {
                        Some(n) => write!(f, ", feedback FB{n}")?,
                        None => f.write_str(", no feedback fault")?,
                    },
                    Err(e) => write!(f, "  error: {e}")?,
                }
            }
            Profile::Baumer => {
                let baumer = baumer::BaumerEmcy::from_emcy(emcy);
                write!(
                    f,
                    "  alarms 0x{:04X} warnings 0x{:04X}",
                    baumer.manufacturer.alarms.bits(),
                    baumer.manufacturer.warnings.bits()
                )?;
                for (i, source) in baumer.sources().enumerate() {
                    f.write_str(if i == 0 { "  sources " } else { ", " })?;
                    f.write_str(source.name())?;
                }
            }
        }
        Ok(())
    }
}
