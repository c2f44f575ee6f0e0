//! The mechanics of the assembly's parts, each written in the global
//! coordinates q [SI: m for positions, – for slopes, rad for angles]:
//!
//! - [`element`] — the planar ANCF cable element: Hermite shape functions,
//!   mass matrix, axial strain and curvature energy, their gradients and
//!   Hessians [SI: N, N/m];
//! - [`element_state`] — an element's state as its displacement from its
//!   straight reference (the precise linearization's r' and r'');
//! - [`cable_force`] — the element's elastic force, point by point in
//!   arrays [SI: N];
//! - [`anchor`] — a material point of a beam, rigid body, point mass or
//!   the ground, its position and Jacobian in q;
//! - [`pair`] — two anchors, the geometry joints, springs and contacts
//!   act between;
//! - [`joint`] — pin, weld and slider constraints C(q) = 0 with their
//!   Jacobians and Hessians;
//! - [`spring`] — translational and torsional springs and dampers
//!   [SI: N/m, N m/rad], the force-element trait;
//! - [`load`] — point loads and their time functions [SI: N];
//! - [`contact`] — unilateral contacts (pin in slot, point on line) and
//!   their normal-force laws [SI: N/m^n].
//!
//! The system ([`crate::system`]) assembles them; nothing here knows the
//! assembly.

pub mod anchor;
pub mod cable_force;
pub mod contact;
pub mod element;
pub mod element_state;
pub mod joint;
pub mod load;
pub mod pair;
pub mod spring;
