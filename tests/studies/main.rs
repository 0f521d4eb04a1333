//! The shipped studies on their reduced grids, and the report.

mod report;
mod shipped_studies;
