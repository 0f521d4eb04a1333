//! The node kinds on the engine: the surface node (file and synthetic sources), the contact node
//! and the friction node (every method and model), run through studies.

#[path = "../../crates/numerics/tests/common/mod.rs"]
mod common;
mod contact_derived;
mod contact_node;
mod friction_high_plasticity;
mod friction_node;
mod friction_ploughing;
mod friction_steps;
mod friction_trust;
#[path = "../nodes_common/mod.rs"]
mod nodes_common;
mod step_sharing;
mod surface_functional_node;
mod surface_node;
mod surface_spectrum_twin;
mod validity;
