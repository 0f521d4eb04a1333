//! The one registry of friction laws: the name a study writes mapped to the law's descriptor.
//! Adding a law: its own file in this folder and one line in [`LAWS`] (ARCHITECTURE.md, "How to
//! add a friction law").

use super::law::LawDescriptor;
use super::{chang_etsion_bogy, full_stick, junction_shear, kogut_etsion, ploughing};

/// Every friction law, in the order documentation lists them. The first is the default model.
pub const LAWS: &[&LawDescriptor] = &[
    &kogut_etsion::LAW,
    &chang_etsion_bogy::LAW,
    &full_stick::LAW,
    &junction_shear::LAW,
    &ploughing::LAW,
];

/// The law a study gets without `model`.
pub fn default_law() -> &'static LawDescriptor {
    LAWS[0]
}

/// The registered law called `name`.
pub fn find_law(name: &str) -> Option<&'static LawDescriptor> {
    LAWS.iter().copied().find(|law| law.name == name)
}

/// The names of the registered laws (for messages and the schema).
pub fn law_names() -> Vec<&'static str> {
    LAWS.iter().map(|law| law.name).collect()
}
