//! Stage 2: the contact solver against closed forms and its stability.

mod contact_precision;
mod contact_stability;
mod contact_tolerance;
mod contact_validation;
