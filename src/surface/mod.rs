//! Stage 1: surfaces — height maps, readers, statistics, synthetic generation, summits.

mod height_map;

pub use height_map::{HeightMap, HeightMapError};
