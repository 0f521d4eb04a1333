//! The compiled part of the `asperity` Python package (`asperity._native`): thin PyO3 bindings
//! of the study runner (`asperity::study_run`) and of the numerics. Arguments arrive checked
//! for type and shape by the Python layer (`asperity/__init__.py`); values are checked here or by
//! the numerics, whose typed errors become `ValueError`s naming the parameter. Every computation
//! runs with the GIL released and behind [`guard::compute`], so a Rust panic becomes a Python
//! `RuntimeError`, never an abort.

#![deny(unsafe_code)]

mod contact;
mod friction;
mod guard;
mod laws;
mod row;
mod spectrum_twin;
mod study;
mod surface;
mod topography;
mod units;

use pyo3::prelude::*;

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("StudyError", m.py().get_type::<study::StudyError>())?;
    m.add("TOOL_VERSION", asperity::TOOL_VERSION)?;
    study::register(m)?;
    topography::register(m)?;
    surface::register(m)?;
    spectrum_twin::register(m)?;
    contact::register(m)?;
    friction::register(m)?;
    laws::register(m)?;
    units::register(m)?;
    Ok(())
}
