//! Equilibration of the iteration matrix: one symmetric scale D (powers
//! of two, so that scaling rounds nothing) that gives every coordinate a
//! unit diagonal, d_i = 1/√|a_ii|, and every constraint row and column
//! (zero diagonal) a largest entry of one against the scaled coordinates.
//!
//! Why: the blocks of [M/(βh²) + K, C_qᵀ; C_q, 0] differ in scale by the
//! units. A MEMS proof mass of 1.9e-9 kg with an inertia of 1.24e-17 kg m²
//! sits beside constraint rows of order one, and a pivot test relative to
//! its column then rejects the matrix as singular, while the same assembly
//! ten times larger passes. A row-and-column equilibration by largest
//! entries (Ruiz) does not help: the constraint entries are a rotation's
//! largest, and its inertia stays 1e-17 of them. On D·A·D the coordinate
//! block has unit diagonal (the mass matrix is positive definite, so its
//! entries are then at most one), and the pivots, the test and the solve's
//! rounding do not depend on the units: A x = b is solved as
//! (D A D) y = D b, x = D y. Where D·A·D fails the pivot test and A does
//! not (a 150 m rigid arm welded to a 200 µm one: nonsense units the model
//! warns about), A is factored as assembled.

/// The symmetric scale of a square matrix.
#[derive(Debug, Clone)]
pub struct Equilibration {
    /// d_i, a power of two.
    pub scale: Vec<f64>,
    diagonal: Vec<f64>,
    largest: Vec<f64>,
}

impl Equilibration {
    /// Unit scales for an n × n matrix.
    pub fn new(n: usize) -> Self {
        Equilibration {
            scale: vec![1.0; n],
            diagonal: vec![0.0; n],
            largest: vec![0.0; n],
        }
    }

    /// The scales of the matrix whose entries `visit` passes, one
    /// `(row, column, value)` at a time (repeats add up). A row whose
    /// diagonal and entries are all zero keeps the scale 1.
    pub fn compute(&mut self, visit: impl Fn(&mut dyn FnMut(usize, usize, f64))) {
        let diagonal = &mut self.diagonal;
        diagonal.fill(0.0);
        visit(&mut |i, j, v| {
            if i == j {
                diagonal[i] += v;
            }
        });
        for (d, &a) in self.scale.iter_mut().zip(&self.diagonal) {
            *d = power_of_two(1.0 / a.abs().sqrt());
        }
        // The constraints' rows and columns: their largest entry against
        // the scaled coordinates is one.
        let largest = &mut self.largest;
        largest.fill(0.0);
        let (d, diagonal) = (&self.scale, &self.diagonal);
        visit(&mut |i, j, v| {
            let (k, other) = match (diagonal[i] == 0.0, diagonal[j] == 0.0) {
                (true, false) => (i, j),
                (false, true) => (j, i),
                _ => return,
            };
            largest[k] = largest[k].max((v * d[other]).abs());
        });
        for ((d, &a), &m) in self.scale.iter_mut().zip(&self.diagonal).zip(&self.largest) {
            if a == 0.0 {
                *d = power_of_two(1.0 / m);
            }
        }
    }

    /// D = I: the matrix factored as assembled.
    pub fn reset(&mut self) {
        self.scale.fill(1.0);
    }

    /// b ← D b (the right-hand side of the scaled system; also the
    /// scaled solution back to the unknowns).
    pub fn apply(&self, b: &mut [f64]) {
        b.iter_mut().zip(&self.scale).for_each(|(b, d)| *b *= d);
    }
}

/// The power of two nearest `x` (1 for zero, infinite or NaN).
fn power_of_two(x: f64) -> f64 {
    if x > 0.0 && x.is_finite() {
        x.log2().round().exp2()
    } else {
        1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_badly_scaled_saddle_point_matrix_is_balanced_exactly() {
        // [m 0 1; 0 j L; 1 L 0] with m = 1.9e-9 kg, j = 1.24e-17 kg m²,
        // a lever L = 1e-5 m: after scaling the coordinates' diagonal and
        // the constraint's largest entry are within a factor 2 of 1, and
        // the scales are powers of two.
        let a = [[1.9e-9, 0.0, 1.0], [0.0, 1.24e-17, 1e-5], [1.0, 1e-5, 0.0]];
        let mut e = Equilibration::new(3);
        e.compute(|f| {
            for (i, row) in a.iter().enumerate() {
                for (j, &v) in row.iter().enumerate() {
                    if v != 0.0 {
                        f(i, j, v);
                    }
                }
            }
        });
        let scaled = |i: usize, j: usize| (e.scale[i] * a[i][j] * e.scale[j]).abs();
        for i in 0..2 {
            assert!((0.5..=2.0).contains(&scaled(i, i)), "{}", scaled(i, i));
        }
        let constraint = scaled(2, 0).max(scaled(2, 1));
        assert!((0.5..=2.0).contains(&constraint), "{constraint}");
        for s in &e.scale {
            assert_eq!(*s, s.log2().round().exp2(), "a power of two");
        }
    }
}
