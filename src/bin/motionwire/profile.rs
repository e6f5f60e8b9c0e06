//! Which device profile reads each node's EMCY manufacturer bytes
//! (`--profile`, SPEC §6.1).

use motionwire::canopen::NodeId;

use crate::args::{Profile, ProfileChoice};

/// The profile of each node, from the `--profile` items.
#[derive(Debug, Clone)]
pub struct Profiles([Profile; 128]);

impl Profiles {
    /// Build the table; later items win over earlier ones.
    pub fn new(choices: &[ProfileChoice]) -> Self {
        let default = choices
            .iter()
            .rev()
            .find_map(|c| match c {
                ProfileChoice::Default(p) => Some(*p),
                ProfileChoice::Node(..) => None,
            })
            .unwrap_or(Profile::Generic);
        let mut table = [default; 128];
        for choice in choices {
            if let ProfileChoice::Node(node, profile) = choice {
                table[usize::from(node.get())] = *profile;
            }
        }
        Profiles(table)
    }

    /// The profile of `node` (the default for frames without a node).
    pub fn of(&self, node: Option<NodeId>) -> Profile {
        self.0[node.map_or(0, |n| usize::from(n.get()))]
    }
}
