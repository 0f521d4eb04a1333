//! Stage 2: the contact solver against closed forms and its stability, the contact node.

mod contact_node;
mod contact_stability;
mod contact_validation;
