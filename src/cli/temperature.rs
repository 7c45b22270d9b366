//! `--temperature-csv FILE` of `railcontact solve`: the flash temperatures
//! of a case with `[temperature]` (see [`crate::core::temperature`] for the
//! model and its conventions).
//!
//! One row per element of the grid: its centre, the frictional power
//! density and both bodies' surface temperatures, SI units.

use std::io::Write;
use std::path::Path;

use super::plot::err;
use crate::core::grid::Grid;
use crate::core::temperature::SurfaceTemperatures;

/// The header of the CSV.
pub const CSV_HEADER: &str = "x_m,y_m,heat_flux_w_per_m2,body1_k,body2_k";

/// Writes the CSV of the surface temperatures `t` on `grid` to `path`.
pub fn write_csv(path: &Path, grid: &Grid, t: &SurfaceTemperatures) -> Result<(), String> {
    let file = std::fs::File::create(path).map_err(err)?;
    let mut w = std::io::BufWriter::new(file);
    writeln!(w, "{CSV_HEADER}").map_err(err)?;
    for i in 0..grid.len() {
        writeln!(
            w,
            "{:e},{:e},{:e},{:e},{:e}",
            grid.x_m(i % grid.nx),
            grid.y_m(i / grid.nx),
            t.heat_flux_w_per_m2[i],
            t.body1_k[i],
            t.body2_k[i]
        )
        .map_err(err)?;
    }
    w.flush().map_err(err)
}
