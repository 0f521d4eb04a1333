//! The boundary between Python and the computations: the GIL is released while Rust computes,
//! and a panic becomes a Python exception instead of unwinding into the interpreter.

use std::panic::{catch_unwind, AssertUnwindSafe};

use ndarray::Array2;
use numpy::PyReadonlyArray2;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;

/// Runs `f` with the GIL released; a panic inside becomes a `RuntimeError` naming it as a bug.
pub fn compute<T: Send>(py: Python<'_>, f: impl FnOnce() -> PyResult<T> + Send) -> PyResult<T> {
    py.detach(|| catch_unwind(AssertUnwindSafe(f)))
        .unwrap_or_else(|payload| Err(panic_error(payload.as_ref())))
}

/// The exception of a caught panic: its message, marked as an internal error.
pub fn panic_error(payload: &(dyn std::any::Any + Send)) -> PyErr {
    let text = payload
        .downcast_ref::<&str>()
        .map(|s| (*s).to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| String::from("unknown panic"));
    PyRuntimeError::new_err(format!(
        "internal error in asperity (a bug; please report it with the input): {text}"
    ))
}

/// A `ValueError` naming the parameter.
pub fn value_error(parameter: &str, message: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(format!("{parameter}: {message}"))
}

/// An owned copy of a float64 height map argument.
pub fn owned(array: &PyReadonlyArray2<'_, f64>) -> Array2<f64> {
    array.as_array().to_owned()
}
