//! Stage 1: surfaces — height maps, readers, statistics, synthetic generation, summits.

mod height_map;
pub mod io;

pub use height_map::{HeightMap, HeightMapError};
pub mod spectral;
pub mod synthetic;
pub mod twins;
