//! Mathematical tools the physics is written with: special functions
//! (Bessel, Fresnel), quadrature (Gauss–Legendre, adaptive Gauss–Kronrod)
//! and the long inverse DFT of piston sequences split over threads
//! ([`fft`]).

pub mod fft;
pub mod quadrature;
pub mod special;
