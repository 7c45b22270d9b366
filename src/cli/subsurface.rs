//! `--subsurface-csv FILE` and `--subsurface-plot FILE` of `railcontact
//! solve`: the subsurface fields of a case with `[subsurface]` (see
//! [`crate::core::subsurface`] for the frame and signs).
//!
//! The CSV has one row per body, depth and element; the plot shows the
//! von Mises stress of both bodies in the x-n plane through the grid's
//! centre row and the y-n plane through its centre column (body 1 at n > 0,
//! body 2 at n < 0), and of each body at one depth, every map at equal
//! scale.

use std::io::Write;
use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use super::plot::{colormap, colour_bar, err, register_fonts, Format, Frame, FONT, SIZE};
use crate::core::grid::Grid;
use crate::core::subsurface::{Body, BodySubsurface};

/// The header of the CSV (SI units; n = +depth in body 1, -depth in body 2).
pub const CSV_HEADER: &str = "body,x_m,y_m,depth_m,n_m,ux_m,uy_m,un_m,\
sigma_xx_pa,sigma_yy_pa,sigma_nn_pa,sigma_xy_pa,sigma_xn_pa,sigma_yn_pa,\
sigma_1_pa,sigma_2_pa,sigma_3_pa,von_mises_pa,tresca_pa,max_shear_pa,hydrostatic_pa";

/// Writes the CSV of both bodies' fields to `path`.
pub fn write_csv(path: &Path, grid: &Grid, bodies: &[BodySubsurface; 2]) -> Result<(), String> {
    let file = std::fs::File::create(path).map_err(err)?;
    let mut w = std::io::BufWriter::new(file);
    writeln!(w, "{CSV_HEADER}").map_err(err)?;
    let n = grid.len();
    for b in bodies {
        let (id, sign) = match b.body {
            Body::One => (1, 1.0),
            Body::Two => (2, -1.0),
        };
        for (k, &z) in b.depths_m.iter().enumerate() {
            for e in 0..n {
                let i = k * n + e;
                let t = b.stress(i);
                let [s1, s2, s3] = t.principal();
                let u = &b.displacement_m;
                writeln!(
                    w,
                    "{id},{:e},{:e},{z:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{s1:e},{s2:e},{s3:e},{:e},{:e},{:e},{:e}",
                    grid.x_m(e % grid.nx),
                    grid.y_m(e / grid.nx),
                    sign * z,
                    u[0][i],
                    u[1][i],
                    u[2][i],
                    t.xx,
                    t.yy,
                    t.nn,
                    t.xy,
                    t.xn,
                    t.yn,
                    t.von_mises(),
                    s1 - s3,
                    0.5 * (s1 - s3),
                    t.hydrostatic()
                )
                .map_err(err)?;
            }
        }
    }
    w.flush().map_err(err)
}

/// The index of the computed depth closest to `depth_m`, or of the depth
/// of body 1's largest von Mises stress when None.
pub fn plot_depth(grid: &Grid, bodies: &[BodySubsurface; 2], depth_m: Option<f64>) -> usize {
    let depths = &bodies[0].depths_m;
    let want = depth_m.unwrap_or_else(|| bodies[0].summary(grid).max_von_mises.depth_m);
    (0..depths.len())
        .min_by(|&a, &b| {
            (depths[a] - want)
                .abs()
                .total_cmp(&(depths[b] - want).abs())
        })
        .unwrap_or(0)
}

/// Writes the plot of both bodies' von Mises stresses to `path`, the
/// depth maps at computed depth number `depth_index`.
pub fn write_plot(
    path: &Path,
    format: Format,
    grid: &Grid,
    bodies: &[BodySubsurface; 2],
    depth_index: usize,
) -> Result<(), String> {
    register_fonts()?;
    match format {
        Format::Png => {
            let root = BitMapBackend::new(path, SIZE).into_drawing_area();
            draw(&root, grid, bodies, depth_index)?;
            root.present().map_err(err)
        }
        Format::Svg => {
            let root = SVGBackend::new(path, SIZE).into_drawing_area();
            draw(&root, grid, bodies, depth_index)?;
            root.present().map_err(err)
        }
    }
}

/// Cell edges \[mm\] around sorted centres (the outer edges half a spacing
/// out, the first clipped at 0 for depths).
fn edges(centres: &[f64], clip_at_zero: bool) -> Vec<f64> {
    let m = centres.len();
    let mut e = Vec::with_capacity(m + 1);
    let first = if m > 1 {
        centres[0] - 0.5 * (centres[1] - centres[0])
    } else {
        centres[0] - 0.5
    };
    e.push(if clip_at_zero { first.max(0.0) } else { first });
    for k in 1..m {
        e.push(0.5 * (centres[k - 1] + centres[k]));
    }
    let last = if m > 1 {
        centres[m - 1] + 0.5 * (centres[m - 1] - centres[m - 2])
    } else {
        centres[0] + 0.5
    };
    e.push(last);
    e
}

/// One coloured rectangle: its corners \[mm\] and value \[Pa\].
type Cell = ([(f64, f64); 2], f64);

fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    grid: &Grid,
    bodies: &[BodySubsurface; 2],
    depth_index: usize,
) -> Result<(), String> {
    root.fill(&WHITE).map_err(err)?;
    let root = root
        .titled(
            "railcontact — von Mises stress below the surface",
            (FONT, 24),
        )
        .map_err(err)?;
    let panels = root.split_evenly((2, 2));
    let n = grid.len();
    let depths = &bodies[0].depths_m;
    let mut order: Vec<usize> = (0..depths.len()).collect();
    order.sort_by(|&a, &b| depths[a].total_cmp(&depths[b]));
    let sorted: Vec<f64> = order.iter().map(|&k| depths[k] * 1e3).collect();
    let de = edges(&sorted, true);
    let xe: Vec<f64> = (0..=grid.nx)
        .map(|i| (grid.x0_m + grid.dx_m * i as f64) * 1e3)
        .collect();
    let ye: Vec<f64> = (0..=grid.ny)
        .map(|i| (grid.y0_m + grid.dy_m * i as f64) * 1e3)
        .collect();
    let (iy0, ix0) = (grid.ny / 2, grid.nx / 2);
    // Mid-planes: both bodies, n = +depth (body 1), -depth (body 2).
    let plane = |along_x: bool| -> Vec<Cell> {
        let mut cells = Vec::new();
        for b in bodies {
            let s = if b.body == Body::One { 1.0 } else { -1.0 };
            for (j, &k) in order.iter().enumerate() {
                let (na, nb) = (s * de[j], s * de[j + 1]);
                let m = if along_x { grid.nx } else { grid.ny };
                for i in 0..m {
                    let e = if along_x {
                        grid.index(i, iy0)
                    } else {
                        grid.index(ix0, i)
                    };
                    let (a, c) = if along_x {
                        (xe[i], xe[i + 1])
                    } else {
                        (ye[i], ye[i + 1])
                    };
                    cells.push(([(a, na), (c, nb)], b.stress(k * n + e).von_mises()));
                }
            }
        }
        cells
    };
    let at_depth = |b: &BodySubsurface| -> Vec<Cell> {
        (0..n)
            .map(|e| {
                let (ix, iy) = (e % grid.nx, e / grid.nx);
                (
                    [(xe[ix], ye[iy]), (xe[ix + 1], ye[iy + 1])],
                    b.stress(depth_index * n + e).von_mises(),
                )
            })
            .collect()
    };
    let dmax = de[de.len() - 1];
    let z = depths[depth_index] * 1e3;
    panel(
        &panels[0],
        &plane(true),
        &format!("x-n plane at y = {:.3} mm [MPa]", grid.y_m(iy0) * 1e3),
        ("x [mm]", "n [mm] (body 1 > 0, body 2 < 0)"),
        (xe[0]..xe[grid.nx], -dmax..dmax),
    )?;
    panel(
        &panels[1],
        &plane(false),
        &format!("y-n plane at x = {:.3} mm [MPa]", grid.x_m(ix0) * 1e3),
        ("y [mm]", "n [mm] (body 1 > 0, body 2 < 0)"),
        (ye[0]..ye[grid.ny], -dmax..dmax),
    )?;
    for (p, b) in panels[2..].iter().zip(bodies) {
        let id = if b.body == Body::One { 1 } else { 2 };
        panel(
            p,
            &at_depth(b),
            &format!("body {id} at depth {z:.3} mm [MPa]"),
            ("x [mm]", "y [mm]"),
            (xe[0]..xe[grid.nx], ye[0]..ye[grid.ny]),
        )?;
    }
    Ok(())
}

/// One colour map of rectangular cells with a colour bar, at equal scale.
fn panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    cells: &[Cell],
    caption: &str,
    (x_desc, y_desc): (&str, &str),
    (xr, yr): (std::ops::Range<f64>, std::ops::Range<f64>),
) -> Result<(), String> {
    let (w, _) = area.dim_in_pixel();
    let (main, bar) = area.split_horizontally(w.saturating_sub(110));
    let vmax = cells.iter().map(|c| c.1).fold(0.0_f64, f64::max);
    let scale = if vmax > 0.0 { vmax } else { 1.0 };
    let main = main.titled(caption, (FONT, 17)).map_err(err)?;
    let frame = Frame {
        margin: 10,
        x_labels: 40,
        y_labels: 60,
    };
    let mut chart = frame.equal_scale(&main, xr, yr).map_err(err)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .label_style((FONT, 13))
        .axis_desc_style((FONT, 14))
        .draw()
        .map_err(err)?;
    chart
        .draw_series(
            cells
                .iter()
                .map(|&(r, v)| Rectangle::new(r, colormap(v / scale).filled())),
        )
        .map_err(err)?;
    colour_bar(&bar, vmax)
}
