//! Stage 2: elastic–perfectly-plastic half-space contact of two rough surfaces.
