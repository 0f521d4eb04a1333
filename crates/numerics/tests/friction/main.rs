//! Stage 3: single-asperity laws, statistical integrals and the separation solve, per summit and per spot.

mod friction_asperity_laws;
mod friction_contact_spots;
mod friction_full_stick;
mod friction_gw_summits;
mod friction_integrals;
mod friction_law_registry;
mod friction_per_summit;
mod friction_ploughing;
mod friction_sliding_direction;
mod friction_static_solve;
mod friction_two_bodies;
mod law_support;
mod ploughing_support;
