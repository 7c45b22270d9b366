//! Conformal contact (CECT): laterally curved contact patches after
//! Blanco-Lorenzo, Santamaria, Vadillo & Correa, "A contact mechanics study
//! of 3D frictional conformal contact", Tribology International 2018.
//! Built on the planar core: the same grids, kernels and solvers, with the
//! geometry measured along local normals and the influence coefficients
//! combined by the orientation difference of the elements.

pub mod frictional;
pub mod geometry;
pub mod operator;
pub mod solve;
