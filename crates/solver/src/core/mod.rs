//! The numeric core: one frictional contact patch on the elastic half-space.
//! No network, no async, no logging: it counts and times, and returns that in
//! its results.

pub mod cache;
pub mod cancel;
pub mod coupling;
pub mod creep;
pub mod error;
pub mod fastrip;
pub mod fastsim;
pub mod fastsim_grid;
pub mod fft;
pub mod force;
pub mod frame;
pub mod friclaw;
pub mod grid;
pub mod hertz;
pub mod influence;
pub mod kikpiotrowski;
pub mod layer;
pub mod leading_edge;
pub mod material;
pub mod memory;
pub mod normal;
pub mod numerical_influence;
pub mod polach;
mod predict;
pub mod problem;
pub mod root;
pub mod sensitivity;
mod simd;
pub mod solution;
pub mod solve;
pub mod steady;
pub mod strip;
pub mod subsurface;
pub mod tangential;
pub mod temperature;
pub mod viscoelastic;
