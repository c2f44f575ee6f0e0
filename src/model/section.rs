//! Properties of a beam's rectangular section, computed in one place.
//!
//! The section is h × w (height h in the bending plane, width w out of it)
//! [SI: m]; with the material's Young's modulus E [SI: Pa] and density ρ
//! [SI: kg/m³]:
//!
//! | property | formula | unit |
//! |---|---|---|
//! | [`Section::area`] | A = h·w | m² |
//! | [`Section::second_moment`] | I = w·h³/12 | m⁴ |
//! | [`Section::axial_stiffness`] | EA = E·(h·w) | N |
//! | [`Section::bending_stiffness`] | EI = E·w·h³/12 | N m² |
//! | [`Section::mass_per_length`] | ρA = ρ·(h·w) | kg/m |
//! | [`Beam::mass`] | m = ρ·h·w·L | kg |
//!
//! The floating-point order of each expression is part of its contract (a
//! regrouping changes results in the last bits): the element matrices and
//! the analytic references take EA, EI and ρA from here, the centre of mass
//! and the rigid stand-in of a beam its mass.

use super::types::{Beam, Section};

impl Section {
    /// Area A = h·w [SI: m²].
    pub fn area(&self) -> f64 {
        self.height * self.width
    }

    /// Second moment of area about the axis out of the bending plane,
    /// I = w·h³/12 [SI: m⁴].
    pub fn second_moment(&self) -> f64 {
        self.width * self.height.powi(3) / 12.0
    }

    /// Axial stiffness EA [SI: N] for Young's modulus `young` [SI: Pa].
    pub fn axial_stiffness(&self, young: f64) -> f64 {
        young * self.area()
    }

    /// Bending stiffness EI [SI: N m²] for Young's modulus `young` [SI: Pa],
    /// evaluated as E·w·h³/12 (left to right).
    pub fn bending_stiffness(&self, young: f64) -> f64 {
        young * self.width * self.height.powi(3) / 12.0
    }

    /// Mass per length ρA [SI: kg/m] for density `density` [SI: kg/m³].
    pub fn mass_per_length(&self, density: f64) -> f64 {
        density * self.area()
    }
}

impl Beam {
    /// Mass of the whole beam, m = ρ·h·w·L [SI: kg], evaluated left to
    /// right: the centre of mass of the assembly (and so every placed
    /// model) and the rigid stand-in have always grouped it so; ρA·L
    /// differs from it by at most a few ulp.
    pub fn mass(&self) -> f64 {
        self.material.density * self.section.height * self.section.width * self.length
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// EI is E times I, up to the rounding of the different grouping.
    #[test]
    fn the_stiffnesses_are_the_modulus_times_the_geometry() {
        for (h, w) in [(1.0e-3, 5.0e-3), (0.7e-3, 3.3e-3), (2.0, 0.1)] {
            let s = Section {
                height: h,
                width: w,
            };
            let e = 1.23e11;
            let ei = s.bending_stiffness(e);
            assert!(((ei - e * s.second_moment()) / ei).abs() < 4.0 * f64::EPSILON);
            assert_eq!(s.axial_stiffness(e), e * s.area());
            // A rectangle turned by 90° has the other I; its area is the same.
            let t = Section {
                height: w,
                width: h,
            };
            assert_eq!(t.area(), s.area());
            let ratio = s.second_moment() / t.second_moment();
            assert!((ratio / (h * h / (w * w)) - 1.0).abs() < 4.0 * f64::EPSILON);
        }
    }

    /// The beam's mass is its mass per length times its length, up to the
    /// rounding of the grouping.
    #[test]
    fn the_mass_is_the_mass_per_length_times_the_length() {
        let mut beam = crate::model::Model::builtin().beams[0].clone();
        for (h, w, l) in [(1.1e-3, 5.2e-3, 0.03), (0.93e-3, 6.1e-3, 0.017)] {
            beam.section = Section {
                height: h,
                width: w,
            };
            beam.length = l;
            let m = beam.mass();
            let rho_a_l = beam.section.mass_per_length(beam.material.density) * l;
            assert!(((m - rho_a_l) / m).abs() < 4.0 * f64::EPSILON);
        }
    }
}
