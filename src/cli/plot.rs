//! `--plot FILE`: pressure map, traction-magnitude map with the slip area
//! hatched and the adhesion/slip boundary drawn, and a centre-line plot of
//! p_n, mu p_n, p_x (and p_y) along x. PNG or SVG.
//!
//! Text is drawn with the DejaVu Sans font bundled in `assets/fonts/`
//! (license beside it), so plots render on headless machines without system
//! fonts.

use std::ops::Range;
use std::path::Path;
use std::sync::Once;

use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::{register_font, FontStyle};

use crate::core::grid::Grid;
use crate::core::solution::{ContactSolution, ElementState};
use crate::core::temperature::SurfaceTemperatures;

/// Output format of a plot.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Raster image.
    Png,
    /// Vector image.
    Svg,
}

/// Size of the image \[px\].
pub const SIZE: (u32, u32) = (1400, 1000);

/// Font family name of the bundled font.
pub(crate) const FONT: &str = "sans-serif";
static FONT_BYTES: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");

/// Registers the bundled font (once).
pub(crate) fn register_fonts() -> Result<(), String> {
    static ONCE: Once = Once::new();
    let mut result = Ok(());
    ONCE.call_once(|| {
        result = register_font(FONT, FontStyle::Normal, FONT_BYTES)
            .map_err(|_| "the bundled font is not a valid TTF".to_string());
    });
    result
}

/// What a plot shows besides the fields: the case's title, its kinetic
/// friction coefficient and whether x is the rolling direction.
#[derive(Debug, Clone, Copy)]
pub struct PlotCase<'a> {
    /// Describes the case (the plot's title).
    pub title: &'a str,
    /// Kinetic friction coefficient (0: no mu p_n line).
    pub mu: f64,
    /// Steady rolling: the x axis is labelled as the rolling direction.
    pub rolling: bool,
    /// The flash temperatures (a case with `[temperature]`): both bodies'
    /// surface temperatures along the centre line, on a second axis \[K\].
    pub temperature: Option<&'a SurfaceTemperatures>,
}

impl PlotCase<'_> {
    fn x_desc(&self) -> &'static str {
        if self.rolling {
            "x (rolling) [mm]"
        } else {
            "x [mm]"
        }
    }
}

/// Writes the plot of `solution` on `grid` to `path`. The maps are at equal
/// scale in x and y.
pub fn write_plot(
    path: &Path,
    format: Format,
    grid: &Grid,
    solution: &ContactSolution,
    case: PlotCase,
) -> Result<(), String> {
    register_fonts()?;
    match format {
        Format::Png => {
            let root = BitMapBackend::new(path, SIZE).into_drawing_area();
            draw(&root, grid, solution, case)?;
            root.present().map_err(|e| e.to_string())
        }
        Format::Svg => {
            let root = SVGBackend::new(path, SIZE).into_drawing_area();
            draw(&root, grid, solution, case)?;
            root.present().map_err(|e| e.to_string())
        }
    }
}

/// A perceptually ordered colour map (viridis-like) for t in [0, 1].
pub(crate) fn colormap(t: f64) -> RGBColor {
    const STOPS: [(f64, f64, f64); 6] = [
        (68.0, 1.0, 84.0),
        (65.0, 68.0, 135.0),
        (42.0, 120.0, 142.0),
        (34.0, 168.0, 132.0),
        (122.0, 209.0, 81.0),
        (253.0, 231.0, 37.0),
    ];
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let s = t * (STOPS.len() - 1) as f64;
    let i = (s.floor() as usize).min(STOPS.len() - 2);
    let f = s - i as f64;
    let (a, b) = (STOPS[i], STOPS[i + 1]);
    let mix = |u: f64, v: f64| (u + (v - u) * f).round() as u8;
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

pub(crate) fn err<E: std::fmt::Display>(e: E) -> String {
    e.to_string()
}

fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    grid: &Grid,
    sol: &ContactSolution,
    case: PlotCase,
) -> Result<(), String> {
    root.fill(&WHITE).map_err(err)?;
    let root = root
        .titled(&format!("railcontact — {}", case.title), (FONT, 24))
        .map_err(err)?;
    let (w, h) = root.dim_in_pixel();
    let (top, bottom) = root.split_vertically(h * 56 / 100);
    let (left, right) = top.split_horizontally(w / 2);
    let f = &sol.fields;
    let traction: Vec<f64> = f
        .traction_x_pa
        .iter()
        .zip(&f.traction_y_pa)
        .map(|(x, y)| x.hypot(*y))
        .collect();
    let x_desc = case.x_desc();
    map(
        &left,
        grid,
        &f.pressure_pa,
        "pressure p_n [MPa]",
        None,
        x_desc,
    )?;
    if traction.iter().any(|&t| t > 0.0) {
        let caption = "traction |p_t| [MPa], slip hatched, adhesion/slip boundary red";
        map(&right, grid, &traction, caption, Some(&f.state), x_desc)?;
    } else {
        let note = if case.mu > 0.0 {
            "no tangential traction: no creepage or shift"
        } else {
            "no tangential traction: frictionless"
        };
        panel_note(&right, "traction |p_t| [MPa]", 17, note)?;
    }
    centre_line(&bottom, grid, sol, case)?;
    Ok(())
}

/// A panel with nothing to plot: its caption (font size `caption_px`) and
/// a centred note that says why.
pub(crate) fn panel_note<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    caption: &str,
    caption_px: u32,
    note: &str,
) -> Result<(), String> {
    let area = area.titled(caption, (FONT, caption_px)).map_err(err)?;
    let (w, h) = area.dim_in_pixel();
    area.draw(&Text::new(
        note,
        ((w / 2) as i32, (h / 2) as i32),
        TextStyle::from((FONT, 17).into_font())
            .color(&BLACK.mix(0.7))
            .pos(Pos::new(HPos::Center, VPos::Center)),
    ))
    .map_err(err)
}

/// One colour map of `values` [Pa] on the grid, with a colour bar; with
/// `states`, slip elements are hatched and the adhesion/slip boundary drawn.
/// The margin and label areas of a chart \[px\], so that its axes can be
/// put at equal scale.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Frame {
    /// Margin on every side.
    pub margin: u32,
    /// Height of the x labels' area below the plot.
    pub x_labels: u32,
    /// Width of the y labels' area left of the plot.
    pub y_labels: u32,
}

impl Frame {
    /// Ranges at equal scale (the same length per pixel on both axes) that
    /// hold `x` and `y` in a plot of `px` pixels: the axis with less length
    /// per pixel is widened about its centre.
    pub(crate) fn ranges(
        &self,
        (w, h): (u32, u32),
        x: Range<f64>,
        y: Range<f64>,
    ) -> (Range<f64>, Range<f64>) {
        let pw = w.saturating_sub(2 * self.margin + self.y_labels).max(1) as f64;
        let ph = h.saturating_sub(2 * self.margin + self.x_labels).max(1) as f64;
        let per_px = ((x.end - x.start) / pw).max((y.end - y.start) / ph);
        let widen = |r: Range<f64>, px: f64| {
            let half = 0.5 * per_px * px;
            let mid = 0.5 * (r.start + r.end);
            (mid - half)..(mid + half)
        };
        (widen(x, pw), widen(y, ph))
    }

    /// A chart on `area` (its caption drawn already, e.g. by `titled`) at
    /// equal scale holding `x` and `y`.
    pub(crate) fn equal_scale<'a, DB: DrawingBackend>(
        &self,
        area: &'a DrawingArea<DB, Shift>,
        x: Range<f64>,
        y: Range<f64>,
    ) -> ChartResult<'a, DB> {
        let (xr, yr) = self.ranges(area.dim_in_pixel(), x, y);
        self.chart(area, xr, yr)
    }

    /// A chart on `area` with this frame's margin and label areas.
    pub(crate) fn chart<'a, DB: DrawingBackend>(
        &self,
        area: &'a DrawingArea<DB, Shift>,
        x: Range<f64>,
        y: Range<f64>,
    ) -> ChartResult<'a, DB> {
        ChartBuilder::on(area)
            .margin(self.margin)
            .x_label_area_size(self.x_labels)
            .y_label_area_size(self.y_labels)
            .build_cartesian_2d(x, y)
    }
}

/// A chart with real axes, or the drawing area's error.
pub(crate) type ChartResult<'a, DB> = Result<
    ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>,
>;

fn map<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    grid: &Grid,
    values: &[f64],
    caption: &str,
    states: Option<&[ElementState]>,
    x_desc: &str,
) -> Result<(), String> {
    let (w, _) = area.dim_in_pixel();
    let (main, bar) = area.split_horizontally(w.saturating_sub(115));
    let vmax = values.iter().cloned().fold(0.0_f64, f64::max);
    let scale = if vmax > 0.0 { vmax } else { 1.0 };
    let (x0, y0) = (grid.x0_m * 1e3, grid.y0_m * 1e3);
    let (dx, dy) = (grid.dx_m * 1e3, grid.dy_m * 1e3);
    let (x1, y1) = (x0 + dx * grid.nx as f64, y0 + dy * grid.ny as f64);
    let main = main.titled(caption, (FONT, 17)).map_err(err)?;
    let frame = Frame {
        margin: 10,
        x_labels: 45,
        y_labels: 60,
    };
    let mut chart = frame.equal_scale(&main, x0..x1, y0..y1).map_err(err)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(x_desc)
        .y_desc("y [mm]")
        .label_style((FONT, 14))
        .axis_desc_style((FONT, 15))
        .draw()
        .map_err(err)?;
    let cell = |ix: usize, iy: usize| {
        let xa = x0 + dx * ix as f64;
        let ya = y0 + dy * iy as f64;
        [(xa, ya), (xa + dx, ya + dy)]
    };
    chart
        .draw_series(
            (0..grid.ny)
                .flat_map(|iy| (0..grid.nx).map(move |ix| (ix, iy)))
                .map(|(ix, iy)| {
                    let v = values[grid.index(ix, iy)];
                    Rectangle::new(cell(ix, iy), colormap(v / scale).filled())
                }),
        )
        .map_err(err)?;
    if let Some(st) = states {
        // Hatch the slip elements.
        let hatch = BLACK.mix(0.55).stroke_width(1);
        chart
            .draw_series(
                (0..grid.ny)
                    .flat_map(|iy| (0..grid.nx).map(move |ix| (ix, iy)))
                    .filter(|&(ix, iy)| st[grid.index(ix, iy)] == ElementState::Slip)
                    .map(|(ix, iy)| {
                        let [(xa, ya), (xb, yb)] = cell(ix, iy);
                        PathElement::new(vec![(xa, ya), (xb, yb)], hatch)
                    }),
            )
            .map_err(err)?;
        // Boundaries: contact edge (white) and adhesion/slip (red).
        let mut contact_edges = Vec::new();
        let mut adh_slip_edges = Vec::new();
        let at = |ix: isize, iy: isize| {
            if ix < 0 || iy < 0 || ix >= grid.nx as isize || iy >= grid.ny as isize {
                ElementState::Exterior
            } else {
                st[grid.index(ix as usize, iy as usize)]
            }
        };
        for iy in 0..=grid.ny as isize {
            for ix in 0..=grid.nx as isize {
                let here = at(ix, iy);
                // Edge to the left neighbour (vertical line at x of column ix) and below (horizontal).
                for (nb, line) in [
                    (
                        at(ix - 1, iy),
                        [
                            (x0 + dx * ix as f64, y0 + dy * iy as f64),
                            (x0 + dx * ix as f64, y0 + dy * (iy + 1) as f64),
                        ],
                    ),
                    (
                        at(ix, iy - 1),
                        [
                            (x0 + dx * ix as f64, y0 + dy * iy as f64),
                            (x0 + dx * (ix + 1) as f64, y0 + dy * iy as f64),
                        ],
                    ),
                ] {
                    use ElementState::*;
                    match (here, nb) {
                        (Adhesion, Slip) | (Slip, Adhesion) => adh_slip_edges.push(line),
                        (Exterior, Adhesion | Slip) | (Adhesion | Slip, Exterior) => {
                            contact_edges.push(line)
                        }
                        _ => {}
                    }
                }
            }
        }
        chart
            .draw_series(
                contact_edges
                    .into_iter()
                    .map(|l| PathElement::new(l.to_vec(), WHITE.stroke_width(2))),
            )
            .map_err(err)?;
        chart
            .draw_series(
                adh_slip_edges
                    .into_iter()
                    .map(|l| PathElement::new(l.to_vec(), RED.stroke_width(3))),
            )
            .map_err(err)?;
    }
    colour_bar(&bar, vmax)
}

pub(crate) fn colour_bar<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    vmax_pa: f64,
) -> Result<(), String> {
    let top = if vmax_pa > 0.0 { vmax_pa * 1e-6 } else { 1.0 };
    let mut chart = ChartBuilder::on(area)
        .margin_top(40)
        .margin_bottom(55)
        .margin_right(10)
        .y_label_area_size(70)
        .build_cartesian_2d(0.0..1.0, 0.0..top)
        .map_err(err)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .y_desc("MPa")
        .label_style((FONT, 13))
        .axis_desc_style((FONT, 14))
        .draw()
        .map_err(err)?;
    let n = 100;
    chart
        .draw_series((0..n).map(|i| {
            let a = top * i as f64 / n as f64;
            let b = top * (i + 1) as f64 / n as f64;
            Rectangle::new(
                [(0.0, a), (1.0, b)],
                colormap((i as f64 + 0.5) / n as f64).filled(),
            )
        }))
        .map_err(err)?;
    Ok(())
}

/// The row whose centre is closest to y = 0.
fn centre_row(grid: &Grid) -> usize {
    (0..grid.ny)
        .min_by(|&a, &b| grid.y_m(a).abs().total_cmp(&grid.y_m(b).abs()))
        .unwrap_or(0)
}

fn centre_line<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    grid: &Grid,
    sol: &ContactSolution,
    case: PlotCase,
) -> Result<(), String> {
    let mu = case.mu;
    let f = &sol.fields;
    let iy = centre_row(grid);
    let xs: Vec<f64> = (0..grid.nx).map(|ix| grid.x_m(ix) * 1e3).collect();
    let row = |v: &[f64]| -> Vec<(f64, f64)> {
        (0..grid.nx)
            .map(|ix| (xs[ix], v[grid.index(ix, iy)] * 1e-6))
            .collect()
    };
    let pn = row(&f.pressure_pa);
    let px = row(&f.traction_x_pa);
    let py = row(&f.traction_y_pa);
    let mupn: Vec<(f64, f64)> = pn.iter().map(|&(x, p)| (x, mu * p)).collect();
    let scale = pn
        .iter()
        .chain(&px)
        .map(|&(_, v)| v.abs())
        .fold(0.0_f64, f64::max);
    let show_py = py.iter().any(|&(_, v)| v.abs() > 1e-3 * scale);
    // Both bounds +-mu p_n, whichever sign the tractions have.
    let all = pn
        .iter()
        .chain(&px)
        .chain(&py)
        .map(|&(_, v)| v)
        .chain(mupn.iter().flat_map(|&(_, v)| [v, -v]));
    let (lo, hi) = all.fold((0.0_f64, 0.0_f64), |(a, b), v| (a.min(v), b.max(v)));
    let pad = 0.08 * (hi - lo).max(1e-9);
    let (x0, x1) = (
        grid.x0_m * 1e3,
        (grid.x0_m + grid.dx_m * grid.nx as f64) * 1e3,
    );
    // Temperatures on the right axis (drawn only for a case with them).
    let temperatures = case.temperature.map(|t| {
        let k = |v: &[f64]| -> Vec<(f64, f64)> {
            (0..grid.nx)
                .map(|ix| (xs[ix], v[grid.index(ix, iy)]))
                .collect()
        };
        (k(&t.body1_k), k(&t.body2_k))
    });
    let (tlo, thi) = temperatures
        .iter()
        .flat_map(|(a, b)| a.iter().chain(b))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &(_, v)| {
            (a.min(v), b.max(v))
        });
    let (tlo, thi) = if tlo <= thi { (tlo, thi) } else { (0.0, 1.0) };
    let tpad = 0.08 * (thi - tlo).max(1e-9);
    let mut chart = ChartBuilder::on(area)
        .caption(
            format!("centre line y = {:.3} mm", grid.y_m(iy) * 1e3),
            (FONT, 17),
        )
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .right_y_label_area_size(if case.temperature.is_some() { 70 } else { 0 })
        .build_cartesian_2d(x0..x1, (lo - pad)..(hi + pad))
        .map_err(err)?
        .set_secondary_coord(x0..x1, (tlo - tpad)..(thi + tpad));
    chart
        .configure_mesh()
        .x_desc(case.x_desc())
        .y_desc("traction [MPa]")
        .label_style((FONT, 14))
        .axis_desc_style((FONT, 15))
        .light_line_style(BLACK.mix(0.05))
        .draw()
        .map_err(err)?;
    chart
        .draw_series(LineSeries::new(vec![(x0, 0.0), (x1, 0.0)], BLACK.mix(0.4)))
        .map_err(err)?;
    let blue = RGBColor(31, 119, 180);
    let orange = RGBColor(255, 127, 14);
    let green = RGBColor(44, 160, 44);
    chart
        .draw_series(LineSeries::new(pn, blue.stroke_width(2)))
        .map_err(err)?
        .label("p_n")
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 25, y)], blue.stroke_width(2)));
    if mu > 0.0 {
        chart
            .draw_series(DashedLineSeries::new(
                mupn.clone(),
                6,
                4,
                blue.stroke_width(1),
            ))
            .map_err(err)?
            .label(format!("mu p_n (mu = {mu})"))
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 25, y)], blue.stroke_width(1))
            });
        let neg: Vec<(f64, f64)> = mupn.iter().map(|&(x, v)| (x, -v)).collect();
        chart
            .draw_series(DashedLineSeries::new(neg, 6, 4, blue.stroke_width(1)))
            .map_err(err)?
            .label("-mu p_n")
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 25, y)], blue.mix(0.5)));
    }
    chart
        .draw_series(LineSeries::new(px, orange.stroke_width(2)))
        .map_err(err)?
        .label("p_x")
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 25, y)], orange.stroke_width(2)));
    if show_py {
        chart
            .draw_series(LineSeries::new(py, green.stroke_width(2)))
            .map_err(err)?
            .label("p_y")
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 25, y)], green.stroke_width(2))
            });
    }
    if let Some((t1, t2)) = temperatures {
        chart
            .configure_secondary_axes()
            .y_desc("surface temperature [K]")
            .label_style((FONT, 14))
            .axis_desc_style((FONT, 15))
            .draw()
            .map_err(err)?;
        let red = RGBColor(214, 39, 40);
        chart
            .draw_secondary_series(LineSeries::new(t1, red.stroke_width(2)))
            .map_err(err)?
            .label("T body 1 [K]")
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 25, y)], red.stroke_width(2)));
        chart
            .draw_secondary_series(DashedLineSeries::new(t2, 6, 4, red.stroke_width(2)))
            .map_err(err)?
            .label("T body 2 [K]")
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 25, y)], red.mix(0.6)));
    }
    chart
        .configure_series_labels()
        .label_font((FONT, 14))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.5))
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(err)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_ranges_are_at_equal_scale_and_hold_the_data() {
        let frame = Frame {
            margin: 10,
            x_labels: 40,
            y_labels: 60,
        };
        // 400 x 300 px leaves a 320 x 240 px plot.
        for (x, y) in [(-4.0..4.0, -1.0..1.0), (0.0..1.0, -30.0..5.0)] {
            let (xr, yr) = frame.ranges((400, 300), x.clone(), y.clone());
            let (px, py) = ((xr.end - xr.start) / 320.0, (yr.end - yr.start) / 240.0);
            assert!((px - py).abs() < 1e-12 * px, "{px} mm/px against {py}");
            assert!(xr.start <= x.start && xr.end >= x.end);
            assert!(yr.start <= y.start && yr.end >= y.end);
            // Centred about the data; the tighter axis is not widened.
            assert!((xr.start + xr.end - x.start - x.end).abs() < 1e-12);
            assert!((yr.start + yr.end - y.start - y.end).abs() < 1e-12);
            let len = |r: &Range<f64>| r.end - r.start;
            let same = |a: &Range<f64>, b: &Range<f64>| (len(a) - len(b)).abs() < 1e-12;
            assert!(same(&xr, &x) || same(&yr, &y));
        }
    }
}
