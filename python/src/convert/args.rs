//! Scalar arguments whose range PyO3 would report as `OverflowError`
//! (`Tolerance`, `Budget`, `Translation`), and path arguments.

use super::err_for;
use super::value_error;
use dymsum::polytope::MeshPolicy;
use dymsum::sum::Method;
use pyo3::prelude::*;

/// An argument PyO3 would extract as a Rust number, with an integer beyond
/// the number's range reported as a `ValueError` naming the argument (PyO3
/// raises `OverflowError` there, and passes it on unnamed): `what` is the
/// argument's name, `range` what it takes.
pub(crate) fn number_arg<'a, 'py, T>(
    obj: Borrowed<'a, 'py, PyAny>,
    what: &str,
    range: &str,
) -> PyResult<T>
where
    T: for<'b> FromPyObject<'b, 'py, Error = PyErr>,
{
    obj.extract::<T>().map_err(|e: PyErr| {
        let py = obj.py();
        if e.is_instance_of::<pyo3::exceptions::PyOverflowError>(py) {
            value_error(format!("{what} must be {range}, got an integer beyond it"))
        } else {
            e
        }
    })
}

/// A motion check's `tolerance` (a float; its range is checked where it is
/// used).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Tolerance(pub f64);

impl<'a, 'py> FromPyObject<'a, 'py> for Tolerance {
    type Error = PyErr;
    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        number_arg(obj, "tolerance", "a finite number in [2**-38, 1)").map(Tolerance)
    }
}

/// A motion check's work `budget`, in intervals (`None` the default).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Budget(pub u64);

impl<'a, 'py> FromPyObject<'a, 'py> for Budget {
    type Error = PyErr;
    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        number_arg(obj, "budget", "an integer in [1, 2**64)").map(Budget)
    }
}

/// A pose's `translation`: three floats.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Translation(pub [f64; 3]);

impl<'a, 'py> FromPyObject<'a, 'py> for Translation {
    type Error = PyErr;
    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        number_arg(obj, "translation", "three finite floats").map(Translation)
    }
}

pub(crate) fn path_string(path: &Bound<'_, PyAny>) -> PyResult<String> {
    let os = path.py().import("os")?;
    os.call_method1("fspath", (path,))?.extract()
}

/// The mesh policy of a `strict` argument.
pub(crate) fn policy(strict: bool) -> MeshPolicy {
    if strict {
        MeshPolicy::strict()
    } else {
        MeshPolicy::default()
    }
}

/// A static method name (`walk`, `brute`, `hull`).
pub(crate) fn parse_method(method: &str) -> PyResult<Method> {
    method.parse::<Method>().map_err(|e| err_for("method", e))
}
