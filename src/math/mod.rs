//! Mathematical tools the physics is written with: special functions
//! (Bessel, Fresnel) and quadrature (Gauss–Legendre, adaptive
//! Gauss–Kronrod).

pub mod quadrature;
pub mod special;
