//! M, K and C_q as compressed sparse rows for numpy and scipy.

use ancf::linalg::Triplets;
use ancf::system::Linearization;
use ancf::System;
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

/// A compressed-sparse-row matrix (repeated entries summed, explicit
/// zeros dropped, column indices ascending within a row).
pub struct Csr {
    pub shape: (usize, usize),
    pub data: Vec<f64>,
    pub indices: Vec<i64>,
    pub indptr: Vec<i64>,
}

impl Csr {
    pub fn from_triplets(t: &Triplets) -> Csr {
        let mut entries: Vec<(usize, usize, f64)> = t.entries().collect();
        entries.sort_by_key(|&(i, j, _)| (i, j));
        let mut summed: Vec<(usize, usize, f64)> = Vec::with_capacity(entries.len());
        for (i, j, v) in entries {
            match summed.last_mut() {
                Some(last) if last.0 == i && last.1 == j => last.2 += v,
                _ => summed.push((i, j, v)),
            }
        }
        summed.retain(|e| e.2 != 0.0);
        let mut indptr = vec![0i64; t.nrows() + 1];
        for &(i, _, _) in &summed {
            indptr[i + 1] += 1;
        }
        for r in 0..t.nrows() {
            indptr[r + 1] += indptr[r];
        }
        Csr {
            shape: (t.nrows(), t.ncols()),
            data: summed.iter().map(|e| e.2).collect(),
            indices: summed.iter().map(|e| e.1 as i64).collect(),
            indptr,
        }
    }

    /// (data, indices, indptr, shape), or a scipy.sparse.csr_matrix.
    fn to_python<'py>(&self, py: Python<'py>, scipy: bool) -> PyResult<Bound<'py, PyAny>> {
        let parts = (
            PyArray1::from_slice(py, &self.data),
            PyArray1::from_slice(py, &self.indices),
            PyArray1::from_slice(py, &self.indptr),
        );
        if scipy {
            let csr = py.import("scipy.sparse")?.getattr("csr_matrix")?;
            let kwargs = PyDict::new(py);
            kwargs.set_item("shape", self.shape)?;
            csr.call((parts,), Some(&kwargs))
        } else {
            Ok(PyTuple::new(
                py,
                [
                    parts.0.into_any(),
                    parts.1.into_any(),
                    parts.2.into_any(),
                    self.shape.into_pyobject(py)?.into_any(),
                ],
            )?
            .into_any())
        }
    }
}

/// The three matrices of a linearization.
pub struct Matrices {
    pub m: Csr,
    pub k: Csr,
    pub cq: Csr,
}

/// M, K and C_q of `system` linearized at `at`.
pub fn assemble(system: &System, at: &Linearization) -> Matrices {
    let n = system.ndof();
    let mut m = Triplets::new(n, n);
    system.mass().add_into(&mut m);
    let mut k = Triplets::new(n, n);
    system.add_tangent_stiffness(at, &mut k);
    let mut cq = Triplets::new(system.constraint_count(), n);
    system.add_constraint_jacobian(at.q, &mut cq);
    Matrices {
        m: Csr::from_triplets(&m),
        k: Csr::from_triplets(&k),
        cq: Csr::from_triplets(&cq),
    }
}

impl Matrices {
    /// {"M": ..., "K": ..., "C_q": ...}.
    pub fn to_python<'py>(&self, py: Python<'py>, scipy: bool) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        d.set_item("M", self.m.to_python(py, scipy)?)?;
        d.set_item("K", self.k.to_python(py, scipy)?)?;
        d.set_item("C_q", self.cq.to_python(py, scipy)?)?;
        Ok(d)
    }
}
