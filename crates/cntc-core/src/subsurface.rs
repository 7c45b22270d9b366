//! Subsurface stresses (`subs_addblock`, `subs_calculate`,
//! `subs_getblocksize`, `subs_getresults`): blocks of points below a solved
//! patch, per contact problem (module 3) or per wheel/rail problem and
//! patch (module 1).
//!
//! # Blocks
//!
//! A block is a 3D lattice of NX x NY x NZ points, given by CONTACT's
//! option ISUBS (user guide, "Subsurface stresses", and the library's
//! "Calculation of subsurface stresses"):
//!
//! | ISUBS | x, y | z |
//! |---|---|---|
//! | 1 | the centres of all elements of the potential contact area | NZ layers ZL, ZL + DZ, ... (`zparam` = \[NZ, ZL, DZ\]) |
//! | 2 | the centres of columns IXL, IXL + IXINC, ... <= IXH and rows IYL, IYINC, IYH (`xparam` = \[IXL, IXINC, IXH\], `yparam` likewise) | as 1 |
//! | 3 | the centres of the columns IX(1..NPX) and rows IY(1..NPY) (1-based numbers) | as 1 |
//! | 5, 6, 7 | as 1, 2, 3 | the list Z(1..NPZ) |
//! | 9 | the lists X(1..NPX), Y(1..NPY) | the list Z(1..NPZ) |
//!
//! As in CONTACT, coordinate lists are sorted in ascending order; column
//! and row numbers are rounded, non-positive and repeated ones dropped,
//! and those outside the grid (1..MX, 1..MY) ignored when the block is
//! evaluated. Coordinates are the patch's contact frame (x rolling, y
//! lateral, the grid's own coordinates), z the depth into body 1; a
//! negative z is a point of body 2 at depth -z. Points are numbered x
//! fastest, then y, then z.
//!
//! Limits (refused with an error naming the parameter): [`MAX_BLOCKS`]
//! blocks (CONTACT's), [`MAX_LIST`] values per list (CONTACT truncates
//! there), [`MAX_POINTS`] points over all blocks of a problem,
//! coordinates within [`MAX_COORD_M`] of the frame's origin, and
//! [`MAX_DIRECT_PAIRS`] for the direct sum.
//!
//! # Results
//!
//! 21 columns per point (CONTACT's table): 1-3 x, y, z; 4-6 the
//! displacements ux, uy, uz of the body's material; 7-9 the hydrostatic
//! stress (trace / 3), the von Mises stress sqrt(3 J2) and Tresca's
//! sigma_1 - sigma_3; 10-12 the principal stresses sigma_1 >= sigma_2 >=
//! sigma_3; 13-21 the stress tensor column by column: sxx, syx, szx, sxy,
//! syy, szy, sxz, syz, szz. Stresses are tension positive, in the common
//! frame (x, y, z into body 1) for both bodies. Inside SI; `results`
//! converts to the caller's units (lengths and stresses; no body sign:
//! these are not forces on a body).
//!
//! # Computation
//!
//! The element tractions of the solution (uniform per element, acting on
//! body 1, body 2 carrying their opposite) load two elastic half-spaces;
//! the fields are sums of the closed-form influence functions of a
//! uniformly loaded rectangle of [`railcontact_solver::core::subsurface`]
//! (Love 1929; Johnson 1985, §3), each body with its own constants. Two
//! evaluations give the same sums (up to rounding) and the cheaper is
//! used:
//!
//! * points at element centres (ISUBS 1-7, and ISUBS 9 when every x and y
//!   is an element centre): the whole grid per depth by FFT
//!   ([`DepthKernels`]);
//! * any point (ISUBS 9): the direct sum over the loaded elements
//!   ([`element_response`]).
//!
//! A point on the surface (z = 0) exactly on an edge of a loaded element
//! lies on the discontinuity of the piecewise constant load, where some
//! stresses have no value; it is evaluated at a depth of
//! [`EDGE_DEPTH`] x min(dx, dy) instead (the average of the two sides for
//! a jump). CONTACT's bilinear tractions (C3 = 3) are not modelled: the
//! loads are the piecewise constant tractions of the surface solution
//! (C3 = 2).
//!
//! Unlike CONTACT (Revision 2707), a depth z < 0 (body 2) of an ISUBS 1-7
//! block does not change the solution: CONTACT negates the solution's px
//! in place there and does not restore it, so that its later depths and
//! blocks of the same `subs_calculate` (and `cntc_gettractions`
//! afterwards) see -px.

use railcontact_solver::core::fft::ConvolutionPlan;
use railcontact_solver::core::grid::Grid;
use railcontact_solver::core::material::{CombinedMaterial, Material};
use railcontact_solver::core::subsurface::{
    element_response, Body, DepthKernels, StressTensor, SubsurfaceWorkspace,
};

use crate::error::{CntcError, Result};
use crate::outcome::Outcome;
use crate::units::Units;

/// Most blocks per contact problem (CONTACT's MXBLCK).
pub const MAX_BLOCKS: usize = 10;
/// Most values in one list of a block (NZ, NPX, NPY, NPZ; CONTACT's
/// MXSUBS, which CONTACT truncates to and this library refuses beyond).
pub const MAX_LIST: usize = 9999;
/// Most points of all blocks of one contact problem (each point keeps 21
/// values: 168 MB at this limit).
pub const MAX_POINTS: usize = 1_000_000;
/// Most (point, loaded element) pairs of a direct sum (ISUBS = 9 away from
/// element centres): some 45 s of computation (0.2 µs a pair).
pub const MAX_DIRECT_PAIRS: u64 = 200_000_000;
/// Most memory for the FFT kernels of one depth \[bytes\].
pub const MAX_KERNEL_BYTES: usize = 1 << 30;
/// Columns of a block's table.
pub const COLUMNS: usize = 21;
/// The value `subs_getresults` gives for a column outside 1-21 (CONTACT's).
pub const NO_COLUMN: f64 = -999.0;
/// Largest |x|, |y|, |z| of a point \[m\] (a point 1 m from the patch is
/// far outside any wheel/rail contact; larger values are mostly lengths in
/// the wrong unit).
pub const MAX_COORD_M: f64 = 1.0;
/// Depth, relative to min(dx, dy), at which a surface point on an edge of a
/// loaded element is evaluated.
pub const EDGE_DEPTH: f64 = 1e-9;

/// Memory of the FFT kernels of one depth per grid element \[bytes\]: the
/// corner lattice and offset table (4 nx ny x (25 + 27) values) and 27
/// spectra of about 2 nx ny complex values.
const KERNEL_BYTES_PER_ELEMENT: usize = 4 * 52 * 8 + 27 * 2 * 16;
/// The cost of one depth of the FFT evaluation per grid element, in units
/// of one element's response at one point (measured: the corner lattice
/// and the 36 transforms).
const FFT_COST_PER_ELEMENT: u64 = 12;

/// The blocks of one contact problem and their results.
#[derive(Debug, Clone, Default)]
pub struct Blocks {
    /// The blocks as given (at most [`MAX_BLOCKS`]).
    pub specs: Vec<BlockSpec>,
    /// The results of the last `subs_calculate`, one per block: block k
    /// has results when k < `results.len()` (blocks added since have none).
    pub results: Vec<BlockResult>,
    /// The materials for [`Blocks::calculate`] (see [`Blocks::set_material`]).
    pub material: Option<CombinedMaterial>,
}

/// One block as `subs_addblock` gives it, checked and normalised.
#[derive(Debug, Clone, PartialEq)]
pub struct BlockSpec {
    /// ISUBS: 1-3, 5-7, 9.
    pub isubs: i32,
    /// x parameters: ISUBS 1, 5: none; 2, 6: \[IXL, IXINC, IXH\] (rounded,
    /// IXL, IXINC >= 1); 3, 7: the column numbers (1-based, ascending,
    /// unique, positive); 9: the coordinates \[m\], ascending.
    pub x: Vec<f64>,
    /// y parameters, as `x`.
    pub y: Vec<f64>,
    /// z parameters: ISUBS 1-3: \[NZ, ZL \[m\], DZ \[m\]\] (NZ rounded, >= 1);
    /// 5-7, 9: the depths \[m\], ascending.
    pub z: Vec<f64>,
}

/// The points and their results: 21 columns per point (CONTACT's table).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct BlockResult {
    /// Points in x, y, z.
    pub n: [usize; 3],
    /// Rows of 21 SI values: x, y, z, ux, uy, uz, sighyd, sigvm, sigtr,
    /// sigma1-3, sxx, syx, szx, sxy, syy, szy, sxz, syz, szz.
    pub table: Vec<[f64; COLUMNS]>,
}

fn input(msg: String) -> CntcError {
    CntcError::Input(msg)
}

/// Checks that every value of `p` (`name`) is finite.
fn finite(isubs: i32, name: &str, p: &[f64]) -> Result<()> {
    match p.iter().position(|v| !v.is_finite()) {
        Some(i) => Err(input(format!(
            "ISUBS = {isubs} (subs_addblock): {name}({}) = {} is not finite",
            i + 1,
            p[i]
        ))),
        None => Ok(()),
    }
}

/// A list of 1 to [`MAX_LIST`] values of `name` (NP`axis`).
fn list_len(isubs: i32, axis: char, name: &str, p: &[f64]) -> Result<()> {
    if p.is_empty() || p.len() > MAX_LIST {
        return Err(input(format!(
            "ISUBS = {isubs} (subs_addblock) needs NP{axis} = 1 to {MAX_LIST} values {name}, got {}",
            p.len()
        )));
    }
    finite(isubs, name, p)
}

/// ISUBS 2, 6: \[IXL, IXINC, IXH\] of `axis` (X or Y).
fn range_params(isubs: i32, axis: char, p: &[f64]) -> Result<Vec<f64>> {
    let (l, i, h) = (
        format!("I{axis}L"),
        format!("I{axis}INC"),
        format!("I{axis}H"),
    );
    if p.len() != 3 {
        return Err(input(format!(
            "ISUBS = {isubs} (subs_addblock) needs NP{axis} = 3 parameters [{l}, {i}, {h}], got {}",
            p.len()
        )));
    }
    finite(isubs, &format!("[{l}, {i}, {h}]"), p)?;
    let (lo, inc, hi) = (p[0].round().max(1.0), p[1].round().max(1.0), p[2].round());
    if hi < lo {
        return Err(input(format!(
            "ISUBS = {isubs} (subs_addblock): {l} = {lo} > {h} = {hi} selects no {}",
            if axis == 'X' { "column" } else { "row" }
        )));
    }
    Ok(vec![lo, inc, hi])
}

/// ISUBS 3, 7: the column (row) numbers I`axis`: rounded, ascending,
/// unique, positive.
fn index_list(isubs: i32, axis: char, p: &[f64]) -> Result<Vec<f64>> {
    let name = format!("I{axis}");
    list_len(isubs, axis, &name, p)?;
    let mut v: Vec<f64> = p.iter().map(|x| x.round()).filter(|&x| x >= 1.0).collect();
    v.sort_by(f64::total_cmp);
    v.dedup();
    if v.is_empty() {
        return Err(input(format!(
            "ISUBS = {isubs} (subs_addblock): no positive {} number in {name}",
            if axis == 'X' { "column" } else { "row" }
        )));
    }
    Ok(v)
}

/// Checks that the length `v_m` \[m\] (`name`, given as `given`) is within
/// [`MAX_COORD_M`].
fn coordinate(units: Units, isubs: i32, name: &str, given: f64, v_m: f64) -> Result<()> {
    if v_m.abs() > MAX_COORD_M {
        return Err(input(format!(
            "ISUBS = {isubs} (subs_addblock): {name} = {given} is {v_m} m from the origin of \
             the contact frame, at most {MAX_COORD_M} m (lengths in {})",
            if units.length_m() == 1.0 { "m" } else { "mm" }
        )));
    }
    Ok(())
}

/// ISUBS 9 (x, y) and 5-7, 9 (z): coordinates in `units`, to SI, ascending.
fn length_list(units: Units, isubs: i32, axis: char, p: &[f64]) -> Result<Vec<f64>> {
    list_len(isubs, axis, &format!("{axis}"), p)?;
    let mut v = Vec::with_capacity(p.len());
    for (i, &x) in p.iter().enumerate() {
        let m = units.len(x);
        coordinate(units, isubs, &format!("{axis}({})", i + 1), x, m)?;
        v.push(m);
    }
    v.sort_by(f64::total_cmp);
    Ok(v)
}

/// ISUBS 1-3: \[NZ, ZL, DZ\].
fn layers(units: Units, isubs: i32, p: &[f64]) -> Result<Vec<f64>> {
    if p.len() != 3 {
        return Err(input(format!(
            "ISUBS = {isubs} (subs_addblock) needs NPZ = 3 parameters [NZ, ZL, DZ], got {}",
            p.len()
        )));
    }
    finite(isubs, "[NZ, ZL, DZ]", p)?;
    // CONTACT takes at least one layer.
    let nz = p[0].round().max(1.0);
    if nz > MAX_LIST as f64 {
        return Err(input(format!(
            "ISUBS = {isubs} (subs_addblock): NZ = {nz} layers, at most {MAX_LIST}"
        )));
    }
    if nz > 1.0 && p[2] <= 0.0 {
        return Err(input(format!(
            "ISUBS = {isubs} (subs_addblock): DZ = {} must be > 0 for NZ = {nz} layers",
            p[2]
        )));
    }
    let (zl, dz) = (units.len(p[1]), units.len(p[2]));
    coordinate(units, isubs, "ZL", p[1], zl)?;
    let last = p[1] + (nz - 1.0) * p[2];
    coordinate(units, isubs, "ZL + (NZ - 1) DZ", last, units.len(last))?;
    Ok(vec![nz, zl, dz])
}

impl BlockSpec {
    /// Checks and normalises `subs_addblock`'s parameters (in `units`).
    pub fn new(units: Units, isubs: i32, x: &[f64], y: &[f64], z: &[f64]) -> Result<Self> {
        let (x, y) = match isubs {
            1 | 5 => (Vec::new(), Vec::new()),
            2 | 6 => (range_params(isubs, 'X', x)?, range_params(isubs, 'Y', y)?),
            3 | 7 => (index_list(isubs, 'X', x)?, index_list(isubs, 'Y', y)?),
            9 => (
                length_list(units, isubs, 'X', x)?,
                length_list(units, isubs, 'Y', y)?,
            ),
            _ => {
                return Err(input(format!(
                    "ISUBS = {isubs} (subs_addblock): the options are 1-3, 5-7 and 9"
                )))
            }
        };
        let z = if isubs <= 3 {
            layers(units, isubs, z)?
        } else {
            length_list(units, isubs, 'Z', z)?
        };
        let spec = BlockSpec { isubs, x, y, z };
        if isubs == 9 {
            let n = spec.x.len() * spec.y.len() * spec.z.len();
            if n > MAX_POINTS {
                return Err(input(format!(
                    "ISUBS = 9 (subs_addblock): NPX x NPY x NPZ = {} x {} x {} = {n} points, \
                     at most {MAX_POINTS}",
                    spec.x.len(),
                    spec.y.len(),
                    spec.z.len()
                )));
            }
        }
        Ok(spec)
    }

    /// Checks the shape of a spec built outside [`BlockSpec::new`] (its
    /// fields are public), so that evaluating it cannot fail on an index.
    fn check_shape(&self, iblk: usize) -> Result<()> {
        let all = |v: &[f64], ok: &dyn Fn(f64) -> bool| !v.is_empty() && v.iter().all(|&x| ok(x));
        let index = |x: f64| x >= 1.0 && x.fract() == 0.0;
        let coord = |x: f64| x.abs() <= MAX_COORD_M;
        let (x, y, z) = (&self.x[..], &self.y[..], &self.z[..]);
        let xy = match self.isubs {
            1 | 5 => true,
            2 | 6 => x.len() == 3 && y.len() == 3 && all(x, &index) && all(y, &index),
            3 | 7 => all(x, &index) && all(y, &index),
            9 => all(x, &coord) && all(y, &coord),
            _ => false,
        };
        let z_ok = if (1..=3).contains(&self.isubs) {
            z.len() == 3
                && index(z[0])
                && z[0] <= MAX_LIST as f64
                && coord(z[1])
                && coord(z[1] + (z[0] - 1.0) * z[2])
        } else {
            all(z, &coord)
        };
        let n = [x.len(), y.len(), z.len()];
        if xy && z_ok && n.iter().all(|&k| k <= MAX_LIST) {
            Ok(())
        } else {
            Err(input(format!(
                "block {iblk}: ISUBS = {} with {} x, {} y and {} z parameters is not a block of \
                 subs_addblock",
                self.isubs, n[0], n[1], n[2]
            )))
        }
    }

    /// The depths of the block \[m\] (signed: negative in body 2).
    fn depths(&self) -> Vec<f64> {
        if self.isubs <= 3 {
            let (nz, zl, dz) = (self.z[0] as usize, self.z[1], self.z[2]);
            (0..nz).map(|k| zl + k as f64 * dz).collect()
        } else {
            self.z.clone()
        }
    }

    /// The points of the block on `grid`; `iblk` names the block.
    fn layout(&self, grid: &Grid, iblk: usize) -> Result<Layout> {
        self.check_shape(iblk)?;
        let z = self.depths();
        let (cols, rows): (Vec<usize>, Vec<usize>) = match self.isubs {
            1 | 5 => ((0..grid.nx).collect(), (0..grid.ny).collect()),
            2 | 6 => (
                range_indices(&self.x, grid.nx, self.isubs, iblk, 'X')?,
                range_indices(&self.y, grid.ny, self.isubs, iblk, 'Y')?,
            ),
            3 | 7 => (
                listed_indices(&self.x, grid.nx, self.isubs, iblk, 'X')?,
                listed_indices(&self.y, grid.ny, self.isubs, iblk, 'Y')?,
            ),
            _ => {
                // ISUBS 9: element centres when every x and y is one.
                let cols = centre_indices(&self.x, grid.x0_m, grid.dx_m, grid.nx);
                let rows = centre_indices(&self.y, grid.y0_m, grid.dy_m, grid.ny);
                return Ok(Layout {
                    x: self.x.clone(),
                    y: self.y.clone(),
                    z,
                    centres: cols.zip(rows),
                });
            }
        };
        Ok(Layout {
            x: cols.iter().map(|&i| grid.x_m(i)).collect(),
            y: rows.iter().map(|&i| grid.y_m(i)).collect(),
            z,
            centres: Some((cols, rows)),
        })
    }
}

/// The 0-based element numbers of \[IXL, IXINC, IXH\] within 1..=`n`.
fn range_indices(p: &[f64], n: usize, isubs: i32, iblk: usize, axis: char) -> Result<Vec<usize>> {
    let (lo, inc, hi) = (p[0], p[1], p[2].min(n as f64));
    if lo > hi {
        return Err(input(format!(
            "block {iblk}, ISUBS = {isubs}: I{axis}L = {lo} lies outside the potential contact \
             area's {} = {n} {}",
            if axis == 'X' { "MX" } else { "MY" },
            if axis == 'X' { "columns" } else { "rows" }
        )));
    }
    let (lo, inc, hi) = (lo as usize, inc.min(n as f64) as usize, hi as usize);
    Ok((lo..=hi).step_by(inc.max(1)).map(|i| i - 1).collect())
}

/// The 0-based element numbers of the listed ones within 1..=`n`.
fn listed_indices(p: &[f64], n: usize, isubs: i32, iblk: usize, axis: char) -> Result<Vec<usize>> {
    let v: Vec<usize> = p
        .iter()
        .filter(|&&i| i <= n as f64)
        .map(|&i| i as usize - 1)
        .collect();
    if v.is_empty() {
        return Err(input(format!(
            "block {iblk}, ISUBS = {isubs}: no number in I{axis} lies in the potential contact \
             area's {} 1 to {n}",
            if axis == 'X' { "columns" } else { "rows" }
        )));
    }
    Ok(v)
}

/// The element numbers whose centres are the coordinates `v` (within 1e-9
/// of the element size), or None when one is not a centre.
fn centre_indices(v: &[f64], x0: f64, d: f64, n: usize) -> Option<Vec<usize>> {
    v.iter()
        .map(|&x| {
            let t = (x - x0) / d - 0.5;
            let i = t.round();
            (i >= 0.0 && i < n as f64 && (t - i).abs() <= 1e-9).then_some(i as usize)
        })
        .collect()
}

/// The points of one block: coordinates \[m\] as reported and, when every
/// point is an element centre, the element columns and rows.
struct Layout {
    x: Vec<f64>,
    y: Vec<f64>,
    z: Vec<f64>,
    centres: Option<(Vec<usize>, Vec<usize>)>,
}

impl Layout {
    fn len(&self) -> usize {
        self.x.len() * self.y.len() * self.z.len()
    }
}

/// A loaded element: its centre \[m\] and tractions (q_x, q_y, p_n) on body
/// 1 \[Pa\].
#[derive(Clone, Copy)]
struct Loaded {
    x: f64,
    y: f64,
    q: [f64; 3],
}

/// The loaded half-spaces below one solution.
struct Field<'a> {
    grid: Grid,
    material: &'a CombinedMaterial,
    /// Tractions on body 1 (q_x, q_y, p_n) per element \[Pa\].
    tractions: [Vec<f64>; 3],
    loaded: Vec<Loaded>,
    /// FFT plan and the transformed tractions per body, made on first use.
    plan: Option<ConvolutionPlan>,
    workspaces: [Option<SubsurfaceWorkspace>; 2],
    /// One depth's nine fields (six stresses, three displacements).
    out: Vec<Vec<f64>>,
    /// Which evaluation to use (tests force one).
    engine: Engine,
}

/// The evaluation of a block.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Engine {
    /// The cheaper one.
    Auto,
    /// The direct sum.
    #[cfg_attr(not(test), allow(dead_code))]
    Direct,
    /// FFT where the points are element centres.
    #[cfg_attr(not(test), allow(dead_code))]
    Fft,
}

impl<'a> Field<'a> {
    fn new(outcome: &Outcome, material: &'a CombinedMaterial, mirror_y: bool) -> Result<Self> {
        let g = outcome.grid;
        let f = &outcome.fields;
        let n = g.len();
        let size_ok = |d: f64| d.is_finite() && d > 0.0;
        if n == 0
            || !size_ok(g.dx_m)
            || !size_ok(g.dy_m)
            || !g.x0_m.is_finite()
            || !g.y0_m.is_finite()
        {
            return Err(CntcError::Discretisation(format!(
                "subs_calculate: the solution's grid of {} x {} elements of {} x {} m is not a \
                 potential contact area",
                g.nx, g.ny, g.dx_m, g.dy_m
            )));
        }
        for (name, v) in [
            ("pressures", &f.pressure_pa),
            ("tractions px", &f.traction_x_pa),
            ("tractions py", &f.traction_y_pa),
        ] {
            if v.len() != n {
                return Err(CntcError::NotSupported(format!(
                    "subs_calculate needs the element tractions of the solution on its \
                     {} x {} grid; this solution has {} {name} (FASTSIM's strips have none)",
                    g.nx,
                    g.ny,
                    v.len()
                )));
            }
            if v.iter().any(|x| !x.is_finite()) {
                return Err(input(format!(
                    "subs_calculate: the solution's {name} are not finite"
                )));
            }
        }
        let (grid, tractions) = if mirror_y {
            // CONTACT's left-side mirroring: y -> -y, rows reversed, py
            // negated.
            let grid = Grid {
                y0_m: -(g.y0_m + g.ny as f64 * g.dy_m),
                ..g
            };
            let flip = |v: &[f64], s: f64| {
                let mut m = vec![0.0; n];
                for iy in 0..g.ny {
                    for ix in 0..g.nx {
                        m[g.index(ix, g.ny - 1 - iy)] = s * v[g.index(ix, iy)];
                    }
                }
                m
            };
            (
                grid,
                [
                    flip(&f.traction_x_pa, 1.0),
                    flip(&f.traction_y_pa, -1.0),
                    flip(&f.pressure_pa, 1.0),
                ],
            )
        } else {
            (
                g,
                [
                    f.traction_x_pa.clone(),
                    f.traction_y_pa.clone(),
                    f.pressure_pa.clone(),
                ],
            )
        };
        let mut loaded = Vec::new();
        for iy in 0..grid.ny {
            for ix in 0..grid.nx {
                let i = grid.index(ix, iy);
                let q = [tractions[0][i], tractions[1][i], tractions[2][i]];
                if q != [0.0; 3] {
                    loaded.push(Loaded {
                        x: grid.x_m(ix),
                        y: grid.y_m(iy),
                        q,
                    });
                }
            }
        }
        Ok(Field {
            grid,
            material,
            tractions,
            loaded,
            plan: None,
            workspaces: [None, None],
            out: Vec::new(),
            engine: Engine::Auto,
        })
    }

    /// The body and its constants at signed depth `z`.
    fn body(&self, z: f64) -> (Body, &Material) {
        if z < 0.0 {
            (Body::Two, &self.material.body2)
        } else {
            (Body::One, &self.material.body1)
        }
    }

    /// Stresses (xx, yy, nn, xy, xn, yn) and displacements at (x, y, z) by
    /// the direct sum over the loaded elements.
    fn point(&self, x: f64, y: f64, z: f64) -> ([f64; 6], [f64; 3]) {
        let r = self.point_at(x, y, z, z.abs());
        if r.0.iter().chain(&r.1).all(|v| v.is_finite()) {
            return r;
        }
        // On an edge of a loaded element at the surface.
        let h = EDGE_DEPTH * self.grid.dx_m.min(self.grid.dy_m);
        self.point_at(x, y, z, h)
    }

    fn point_at(&self, x: f64, y: f64, z: f64, depth: f64) -> ([f64; 6], [f64; 3]) {
        let (body, m) = self.body(z);
        let two = body == Body::Two;
        let (dx, dy) = (self.grid.dx_m, self.grid.dy_m);
        let (mut s, mut u) = ([0.0; 6], [0.0; 3]);
        for e in &self.loaded {
            let r = element_response(x - e.x, y - e.y, depth, dx, dy, m);
            // Body 2 carries (-q_x, -q_y) and, in its frame (x, y, -n),
            // the same pressure.
            let q = if two { [-e.q[0], -e.q[1], e.q[2]] } else { e.q };
            for (load, &ql) in q.iter().enumerate() {
                if ql == 0.0 {
                    continue;
                }
                for (c, sc) in s.iter_mut().enumerate() {
                    *sc += ql * r.stress[load][c];
                }
                for (c, uc) in u.iter_mut().enumerate() {
                    *uc += ql * r.displacement[load][c];
                }
            }
        }
        if two {
            // Body 2's frame has z = -n.
            s[4] = -s[4];
            s[5] = -s[5];
            u[2] = -u[2];
        }
        (s, u)
    }

    /// The nine fields at signed depth `z` on the whole grid, by FFT, into
    /// `self.out`.
    fn depth_fields(&mut self, z: f64) {
        let n = self.grid.len();
        let (nx, ny) = (self.grid.nx, self.grid.ny);
        let plan: &ConvolutionPlan = self
            .plan
            .get_or_insert_with(|| ConvolutionPlan::new(nx, ny));
        let (body, m) = if z < 0.0 {
            (Body::Two, self.material.body2)
        } else {
            (Body::One, self.material.body1)
        };
        let b = usize::from(body == Body::Two);
        let tractions = &self.tractions;
        let ws = self.workspaces[b].get_or_insert_with(|| {
            let mut ws = SubsurfaceWorkspace::new(plan);
            ws.load(plan, body, [&tractions[0], &tractions[1], &tractions[2]]);
            ws
        });
        let kernels = DepthKernels::new(plan, &self.grid, &m, z.abs());
        if self.out.len() != 9 {
            self.out = vec![vec![0.0; n]; 9];
        }
        let [o0, o1, o2, o3, o4, o5, o6, o7, o8] = &mut self.out[..] else {
            unreachable!("nine fields")
        };
        kernels.apply(plan, ws, [o0, o1, o2, o3, o4, o5, o6, o7, o8]);
    }

    /// The table of `layout`, by the cheaper of the two evaluations.
    fn block(&mut self, layout: &Layout, isubs: i32, iblk: usize) -> Result<Vec<[f64; COLUMNS]>> {
        let npts = layout.len() as u64;
        let direct = npts * self.loaded.len() as u64;
        let fft_ok = KERNEL_BYTES_PER_ELEMENT.saturating_mul(self.grid.len()) <= MAX_KERNEL_BYTES;
        let fft_cost = layout.z.len() as u64 * self.grid.len() as u64 * FFT_COST_PER_ELEMENT;
        let use_fft = match self.engine {
            Engine::Auto => fft_ok && fft_cost < direct,
            e => e == Engine::Fft,
        };
        let mut table = Vec::with_capacity(layout.len());
        match &layout.centres {
            Some((cols, rows)) if use_fft => {
                for &z in &layout.z {
                    self.depth_fields(z);
                    for (&iy, &y) in rows.iter().zip(&layout.y) {
                        for (&ix, &x) in cols.iter().zip(&layout.x) {
                            let i = self.grid.index(ix, iy);
                            let o = &self.out;
                            let s = [o[0][i], o[1][i], o[2][i], o[3][i], o[4][i], o[5][i]];
                            table.push(row(x, y, z, s, [o[6][i], o[7][i], o[8][i]]));
                        }
                    }
                }
            }
            Some(_) if direct <= MAX_DIRECT_PAIRS => self.direct(layout, &mut table),
            None if direct <= MAX_DIRECT_PAIRS => self.direct(layout, &mut table),
            _ => {
                let why = if layout.centres.is_some() {
                    "the grid is too large for the FFT's kernels (MAX_KERNEL_BYTES)"
                } else {
                    "use fewer points, or element centres (ISUBS = 1-7)"
                };
                return Err(CntcError::NotSupported(format!(
                    "block {iblk}, ISUBS = {isubs}: {npts} points below {} loaded elements need \
                     {direct} element evaluations, this library does at most \
                     {MAX_DIRECT_PAIRS}: {why}",
                    self.loaded.len()
                )));
            }
        }
        Ok(table)
    }

    fn direct(&self, layout: &Layout, table: &mut Vec<[f64; COLUMNS]>) {
        for &z in &layout.z {
            for &y in &layout.y {
                for &x in &layout.x {
                    let (s, u) = self.point(x, y, z);
                    table.push(row(x, y, z, s, u));
                }
            }
        }
    }
}

/// One row of the table from the stresses (xx, yy, nn, xy, xn, yn) and the
/// displacements.
fn row(x: f64, y: f64, z: f64, s: [f64; 6], u: [f64; 3]) -> [f64; COLUMNS] {
    let t = StressTensor {
        xx: s[0],
        yy: s[1],
        nn: s[2],
        xy: s[3],
        xn: s[4],
        yn: s[5],
    };
    let [s1, s2, s3] = t.principal();
    [
        x,
        y,
        z,
        u[0],
        u[1],
        u[2],
        t.hydrostatic(),
        t.von_mises(),
        s1 - s3,
        s1,
        s2,
        s3,
        t.xx,
        t.xy,
        t.xn,
        t.xy,
        t.yy,
        t.yn,
        t.xn,
        t.yn,
        t.nn,
    ]
}

impl Blocks {
    /// `subs_addblock`: block `iblk` (1-based) with CONTACT's ISUBS and its
    /// parameters in `units`. `iblk` = NBLOCK + 1 appends; a lower number
    /// discards that block and the ones after it first; 0 clears all
    /// blocks (the other arguments are then ignored). An invalid block
    /// leaves the blocks as they were.
    pub fn add(
        &mut self,
        units: Units,
        iblk: i32,
        isubs: i32,
        x: &[f64],
        y: &[f64],
        z: &[f64],
    ) -> Result<()> {
        let n = self.specs.len();
        let top = (n + 1).min(MAX_BLOCKS);
        if iblk < 0 || iblk as usize > top {
            return Err(input(format!(
                "IBLK = {iblk} (subs_addblock): must be 0 (clear the blocks) to {top} \
                 (NBLOCK + 1: this problem has {n} block(s), at most {MAX_BLOCKS})"
            )));
        }
        if iblk == 0 {
            self.specs.clear();
            self.results.clear();
            return Ok(());
        }
        let spec = BlockSpec::new(units, isubs, x, y, z)?;
        let k = iblk as usize - 1;
        self.specs.truncate(k);
        self.results.truncate(k);
        self.specs.push(spec);
        Ok(())
    }

    /// The materials [`Blocks::calculate`] uses.
    pub fn set_material(&mut self, material: &CombinedMaterial) {
        self.material = Some(*material);
    }

    /// `subs_calculate` below `outcome`, with the materials of
    /// [`Blocks::set_material`].
    pub fn calculate(&mut self, outcome: &Outcome) -> Result<()> {
        let material = self.material.ok_or_else(|| {
            CntcError::Other(
                "subs_calculate: the materials of the problem were not passed to the \
                 subsurface calculation (Blocks::set_material or Blocks::calculate_with)"
                    .into(),
            )
        })?;
        self.calculate_with(outcome, &material, false)
    }

    /// `subs_calculate` below `outcome` (tractions on body 1) with
    /// `material` (CONTACT uses the materials set at `subs_calculate`).
    /// `mirror_y`: the outcome is a left wheel's patch in a mirrored
    /// (right-side) frame while the points are in CONTACT's reporting
    /// frame: the outcome is first mirrored (y -> -y, rows reversed, py
    /// negated), as CONTACT does; false when the outcome is in the
    /// reporting frame already (module 3, and module 1's outcomes here).
    /// All blocks are evaluated or none: on an error the previous results
    /// are kept.
    pub fn calculate_with(
        &mut self,
        outcome: &Outcome,
        material: &CombinedMaterial,
        mirror_y: bool,
    ) -> Result<()> {
        if self.specs.is_empty() {
            self.results.clear();
            return Ok(());
        }
        let mut field = Field::new(outcome, material, mirror_y)?;
        let layouts = self
            .specs
            .iter()
            .enumerate()
            .map(|(k, s)| s.layout(&field.grid, k + 1))
            .collect::<Result<Vec<_>>>()?;
        let total: usize = layouts.iter().map(Layout::len).sum();
        if total > MAX_POINTS {
            return Err(input(format!(
                "subs_calculate: the {} block(s) hold {total} points (NX x NY x NZ summed), \
                 at most {MAX_POINTS}",
                layouts.len()
            )));
        }
        let mut results = Vec::with_capacity(layouts.len());
        for (k, (l, s)) in layouts.iter().zip(&self.specs).enumerate() {
            results.push(BlockResult {
                n: [l.x.len(), l.y.len(), l.z.len()],
                table: field.block(l, s.isubs, k + 1)?,
            });
        }
        self.results = results;
        Ok(())
    }

    /// `subs_getblocksize` of block `iblk`.
    pub fn block_size(&self, iblk: i32) -> Result<[usize; 3]> {
        self.result(iblk).map(|r| r.n)
    }

    /// `subs_getresults`: the columns `icol` (1-21) of block `iblk`, column
    /// after column, in the caller's units; a column number outside 1-21
    /// gives [`NO_COLUMN`] (CONTACT's -999) for every point.
    pub fn results(&self, units: Units, iblk: i32, icol: &[i32]) -> Result<Vec<f64>> {
        let r = self.result(iblk)?;
        let n = r.table.len();
        if n.saturating_mul(icol.len()) > MAX_POINTS * COLUMNS {
            return Err(input(format!(
                "NCOL = {} (subs_getresults): {n} points x {} columns exceed {} values",
                icol.len(),
                icol.len(),
                MAX_POINTS * COLUMNS
            )));
        }
        let mut out = Vec::with_capacity(n * icol.len());
        for &c in icol {
            match c {
                1..=6 => out.extend(r.table.iter().map(|t| units.len_out(t[c as usize - 1]))),
                7..=21 => out.extend(r.table.iter().map(|t| units.stress_out(t[c as usize - 1]))),
                _ => out.extend(std::iter::repeat_n(NO_COLUMN, n)),
            }
        }
        Ok(out)
    }

    fn result(&self, iblk: i32) -> Result<&BlockResult> {
        let n = self.specs.len();
        if iblk < 1 || iblk as usize > n {
            return Err(input(format!(
                "IBLK = {iblk}: this problem has {n} subsurface block(s) (subs_addblock)"
            )));
        }
        self.results.get(iblk as usize - 1).ok_or_else(|| {
            input(format!(
                "IBLK = {iblk}: the block has no results yet (subs_calculate after subs_addblock)"
            ))
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use railcontact_solver::core::material::Material;

    const STEEL: Material = Material {
        shear_modulus_pa: 82.0e9,
        poisson_ratio: 0.28,
    };

    fn steel() -> CombinedMaterial {
        CombinedMaterial::identical(STEEL).expect("steel")
    }

    /// A Hertz circle of radius `a` on an n x n grid of 2.4 a, pressure p0
    /// sqrt(1 - r²/a²) at the element centres and tractions `mu` times it.
    fn hertz_outcome(n: usize, a: f64, p0: f64, mu: [f64; 2]) -> Outcome {
        let d = 2.4 * a / n as f64;
        let h = -0.5 * n as f64 * d;
        let grid = Grid::new(n, n, d, d, h, h).expect("grid");
        let mut o = Outcome::no_contact(grid, vec![0.0; grid.len()], 0.0);
        for iy in 0..n {
            for ix in 0..n {
                let (x, y) = (grid.x_m(ix), grid.y_m(iy));
                let r2 = (x * x + y * y) / (a * a);
                let p = if r2 < 1.0 {
                    p0 * (1.0 - r2).sqrt()
                } else {
                    0.0
                };
                let i = grid.index(ix, iy);
                o.fields.pressure_pa[i] = p;
                o.fields.traction_x_pa[i] = mu[0] * p;
                o.fields.traction_y_pa[i] = mu[1] * p;
            }
        }
        o
    }

    fn err(r: Result<impl std::fmt::Debug>) -> String {
        r.expect_err("an error").to_string()
    }

    #[test]
    fn add_checks_and_names_contacts_parameters() {
        let u = Units::Contact;
        let mut b = Blocks::default();
        assert!(err(b.add(u, 2, 9, &[0.0], &[0.0], &[0.0])).contains("IBLK = 2"));
        assert!(err(b.add(u, -1, 9, &[0.0], &[0.0], &[0.0])).contains("IBLK = -1"));
        assert!(err(b.add(u, 1, 4, &[], &[], &[1.0])).contains("ISUBS = 4"));
        assert!(
            err(b.add(u, 1, 2, &[1.0, 1.0], &[1.0, 1.0, 3.0], &[1.0, 0.0, 1.0]))
                .contains("NPX = 3")
        );
        assert!(err(b.add(u, 1, 6, &[1.0, 1.0, 3.0], &[1.0], &[1.0])).contains("NPY = 3"));
        assert!(err(b.add(u, 1, 1, &[], &[], &[1.0, 0.0])).contains("NPZ = 3"));
        assert!(err(b.add(
            u,
            1,
            2,
            &[5.0, 1.0, 3.0],
            &[1.0, 1.0, 3.0],
            &[1.0, 0.0, 1.0]
        ))
        .contains("IXL = 5 > IXH = 3"));
        assert!(err(b.add(u, 1, 3, &[0.0, -2.0], &[1.0], &[1.0, 0.0, 1.0])).contains("IX"));
        assert!(err(b.add(u, 1, 9, &[], &[0.0], &[0.0])).contains("NPX = 1 to 9999"));
        assert!(err(b.add(u, 1, 5, &[], &[], &[])).contains("NPZ = 1 to 9999"));
        assert!(err(b.add(u, 1, 9, &[0.0], &[f64::NAN], &[0.0])).contains("Y(1) = NaN"));
        assert!(err(b.add(u, 1, 1, &[], &[], &[3.0, 0.0, 0.0])).contains("DZ = 0"));
        assert!(err(b.add(u, 1, 1, &[], &[], &[1e5, 0.0, 1.0])).contains("at most 9999"));
        let many: Vec<f64> = (0..101).map(f64::from).collect();
        assert!(err(b.add(u, 1, 9, &many, &many, &many)).contains("at most 1000000"));
        assert!(err(b.add(u, 1, 9, &vec![0.0; 10_000], &[0.0], &[0.0])).contains("NPX = 1 to 9999"));
        assert!(b.specs.is_empty());

        // Blocks 1..10, then no 11th.
        for k in 1..=10 {
            b.add(u, k, 5, &[-999.0], &[-999.0], &[0.1 * k as f64])
                .unwrap();
        }
        assert!(err(b.add(u, 11, 5, &[], &[], &[0.0])).contains("at most 10"));
        // Re-using number 3 discards 3..10; an invalid block changes nothing.
        b.add(u, 3, 9, &[0.2, -0.1], &[0.0], &[0.3, 0.1]).unwrap();
        assert_eq!(b.specs.len(), 3);
        assert!(b.add(u, 2, 8, &[], &[], &[0.0]).is_err());
        assert_eq!(b.specs.len(), 3);
        // Coordinates to SI, sorted.
        let s = &b.specs[2];
        assert_eq!(s.isubs, 9);
        assert!((s.x[0] + 1e-4).abs() < 1e-18 && (s.x[1] - 2e-4).abs() < 1e-18);
        assert!((s.z[0] - 1e-4).abs() < 1e-18 && (s.z[1] - 3e-4).abs() < 1e-18);
        // Column numbers: rounded, positive, unique, ascending.
        b.add(u, 4, 7, &[7.2, 0.0, 2.0, 2.4, -1.0], &[3.0], &[0.5])
            .unwrap();
        assert_eq!(b.specs[3].x, vec![2.0, 7.0]);
        b.add(
            u,
            5,
            2,
            &[0.0, -3.0, 6.0],
            &[2.0, 2.0, 2.0],
            &[0.0, 1.0, 1.0],
        )
        .unwrap();
        assert_eq!(b.specs[4].x, vec![1.0, 1.0, 6.0]);
        assert_eq!(b.specs[4].z, vec![1.0, 1e-3, 1e-3]);
        // 0 clears.
        b.add(u, 0, 0, &[], &[], &[]).unwrap();
        assert!(b.specs.is_empty());
        assert!(err(b.block_size(1)).contains("IBLK = 1"));
    }

    #[test]
    fn blocks_expand_like_contacts_selections() {
        let u = Units::Si;
        let o = hertz_outcome(7, 1e-3, 1e9, [0.0, 0.0]);
        let g = o.grid;
        let mut b = Blocks::default();
        b.add(u, 1, 1, &[], &[], &[3.0, 1e-4, 2e-4]).unwrap();
        b.add(
            u,
            2,
            2,
            &[2.0, 2.0, 99.0],
            &[3.0, 9.0, 3.0],
            &[1.0, 0.0, 1.0],
        )
        .unwrap();
        b.add(u, 3, 7, &[9.0, 1.0, 7.0], &[7.0, 2.0], &[2e-4, -1e-4])
            .unwrap();
        b.add(u, 4, 9, &[g.x_m(3), 0.3e-3], &[0.1e-3], &[0.0])
            .unwrap();
        assert!(err(b.block_size(1)).contains("no results"));
        b.calculate_with(&o, &steel(), false).unwrap();
        assert_eq!(b.block_size(1).unwrap(), [7, 7, 3]);
        assert_eq!(b.block_size(2).unwrap(), [3, 1, 1]);
        assert_eq!(b.block_size(3).unwrap(), [2, 2, 2]);
        assert_eq!(b.block_size(4).unwrap(), [2, 1, 1]);
        let t = &b.results[0].table;
        // x fastest, then y, then z.
        assert_eq!((t[1][0], t[1][1], t[1][2]), (g.x_m(1), g.y_m(0), 1e-4));
        assert_eq!((t[7][0], t[7][1]), (g.x_m(0), g.y_m(1)));
        assert!((t[49][2] - 3e-4).abs() < 1e-18);
        let t = &b.results[1].table;
        let xs: Vec<f64> = t.iter().map(|r| r[0]).collect();
        assert_eq!(xs, vec![g.x_m(1), g.x_m(3), g.x_m(5)]);
        assert_eq!(t[0][1], g.y_m(2));
        let t = &b.results[2].table;
        assert_eq!(
            (t[0][0], t[1][0], t[2][1], t[0][2]),
            (g.x_m(0), g.x_m(6), g.y_m(6), -1e-4)
        );
        // Columns outside the grid: an error naming the block.
        b.add(u, 5, 3, &[8.0], &[1.0], &[1.0, 0.0, 1.0]).unwrap();
        let e = err(b.calculate_with(&o, &steel(), false));
        assert!(e.contains("block 5, ISUBS = 3") && e.contains("IX"), "{e}");
        // The earlier results stay.
        assert_eq!(b.results.len(), 4);
        b.add(u, 5, 6, &[1.0, 1.0, 1.0], &[8.0, 1.0, 9.0], &[0.0])
            .unwrap();
        let e = err(b.calculate_with(&o, &steel(), false));
        assert!(e.contains("IYL = 8") && e.contains("MY = 7"), "{e}");
    }

    /// The FFT and the direct sum give the same table at element centres,
    /// in both bodies.
    #[test]
    fn fft_and_direct_sums_agree() {
        let (a, p0) = (1e-3, 1e9);
        let o = hertz_outcome(9, a, p0, [0.3, -0.2]);
        let g = o.grid;
        let m = CombinedMaterial::new(
            STEEL,
            Material {
                shear_modulus_pa: 40e9,
                poisson_ratio: 0.35,
            },
        )
        .unwrap();
        let spec = BlockSpec::new(
            Units::Si,
            9,
            &[g.x_m(0), g.x_m(4), g.x_m(5)],
            &[g.y_m(2), g.y_m(4)],
            &[-0.4 * a, 0.0, 0.3 * a, 2.0 * a],
        )
        .unwrap();
        let l = spec.layout(&g, 1).unwrap();
        assert!(l.centres.is_some());
        let mut f = Field::new(&o, &m, false).unwrap();
        f.engine = Engine::Direct;
        let direct = f.block(&l, 9, 1).unwrap();
        f.engine = Engine::Fft;
        let fft = f.block(&l, 9, 1).unwrap();
        let umax = direct
            .iter()
            .fold(0.0f64, |m, r| m.max(r[3].abs()).max(r[5].abs()));
        for (d, f) in direct.iter().zip(&fft) {
            for c in 3..COLUMNS {
                let scale = if c < 6 { umax } else { p0 };
                assert!(
                    (d[c] - f[c]).abs() < 1e-9 * scale,
                    "col {} at {:?}: {} vs {}",
                    c + 1,
                    &d[..3],
                    d[c],
                    f[c]
                );
            }
        }
    }

    /// At the surface below a loaded element: szz = -p, szx = -qx, szy = -qy
    /// (tension positive), in both bodies (the traction is continuous).
    #[test]
    fn surface_stresses_are_the_tractions() {
        let (a, p0) = (1e-3, 1e9);
        let o = hertz_outcome(9, a, p0, [0.3, -0.2]);
        let g = o.grid;
        let i = g.index(4, 5);
        let (p, qx, qy) = (
            o.fields.pressure_pa[i],
            o.fields.traction_x_pa[i],
            o.fields.traction_y_pa[i],
        );
        let mut b = Blocks::default();
        let h = 1e-9 * a;
        b.add(
            Units::Si,
            1,
            9,
            &[g.x_m(4) + 0.1 * g.dx_m],
            &[g.y_m(5)],
            &[-h, 0.0, h],
        )
        .unwrap();
        b.calculate_with(&o, &steel(), false).unwrap();
        for r in &b.results[0].table {
            assert!((r[20] + p).abs() < 1e-5 * p0, "szz {} vs -{p}", r[20]);
            assert!(
                (r[14] + qx).abs() < 1e-5 * p0 && (r[18] + qx).abs() < 1e-5 * p0,
                "szx {} vs -{qx}",
                r[14]
            );
            assert!(
                (r[17] + qy).abs() < 1e-5 * p0 && (r[19] + qy).abs() < 1e-5 * p0,
                "szy {} vs -{qy}",
                r[17]
            );
            // Symmetric tensor, ordered principal stresses, invariants.
            assert_eq!((r[13], r[14], r[17]), (r[15], r[18], r[19]));
            assert!(r[9] >= r[10] && r[10] >= r[11]);
            assert!((r[8] - (r[9] - r[11])).abs() < 1e-6 * p0);
            assert!((r[6] - (r[12] + r[16] + r[20]) / 3.0).abs() < 1e-6 * p0);
        }
        // Under the load both bodies move toward each other: body 1 in +z,
        // body 2 in -z.
        let t = &b.results[0].table;
        assert!(t[0][5] < 0.0 && t[2][5] > 0.0);
    }

    /// A surface point on an element edge (where the piecewise constant
    /// load jumps) still gets finite values: those just below.
    #[test]
    fn surface_points_on_element_edges_are_finite() {
        let o = hertz_outcome(9, 1e-3, 1e9, [0.3, 0.1]);
        let g = o.grid;
        let (xe, ye) = (g.x0_m + 4.0 * g.dx_m, g.y0_m + 5.0 * g.dy_m);
        let mut b = Blocks::default();
        b.add(Units::Si, 1, 9, &[xe, g.x_m(4)], &[ye, g.y_m(4)], &[0.0])
            .unwrap();
        b.calculate_with(&o, &steel(), false).unwrap();
        for r in &b.results[0].table {
            assert!(r.iter().all(|v| v.is_finite()), "{r:?}");
        }
    }

    /// CONTACT's left-side mirroring: the points at y in the mirrored
    /// frame see the field at -y, with the y-odd components negated.
    #[test]
    fn mirrored_points_see_the_field_at_minus_y() {
        let o = hertz_outcome(9, 1e-3, 1e9, [0.3, 0.2]);
        let (x, y, z) = (0.13e-3, 0.41e-3, [0.2e-3, -0.3e-3]);
        let mut b = Blocks::default();
        b.add(Units::Si, 1, 9, &[x], &[y], &z).unwrap();
        b.calculate_with(&o, &steel(), true).unwrap();
        let mirrored = b.results[0].table.clone();
        b.add(Units::Si, 1, 9, &[x], &[-y], &z).unwrap();
        b.calculate_with(&o, &steel(), false).unwrap();
        // Odd in y: uy, syx, szy and their transposes.
        let odd = [4, 13, 15, 17, 19];
        for (m, r) in mirrored.iter().zip(&b.results[0].table) {
            for c in 3..COLUMNS {
                let want = if odd.contains(&c) { -r[c] } else { r[c] };
                assert!(
                    (m[c] - want).abs() <= 1e-9 * (1.0 + want.abs()) * 1e9,
                    "col {}",
                    c + 1
                );
            }
        }
    }

    #[test]
    fn results_convert_units_and_fill_unknown_columns() {
        let o = hertz_outcome(7, 1e-3, 1e9, [0.0, 0.0]);
        let mut b = Blocks::default();
        b.add(Units::Contact, 1, 9, &[0.0], &[0.0], &[0.0, 0.5])
            .unwrap();
        b.calculate_with(&o, &steel(), false).unwrap();
        let t = b.results[0].table.clone();
        let v = b.results(Units::Contact, 1, &[3, 0, 21, 4, 22]).unwrap();
        assert_eq!(v.len(), 10);
        assert_eq!(&v[..2], &[0.0, 0.5]);
        assert_eq!(&v[2..4], &[NO_COLUMN; 2]);
        assert!((v[4] - t[0][20] * 1e-6).abs() < 1e-9 && (v[5] - t[1][20] * 1e-6).abs() < 1e-9);
        assert!((v[6] - t[0][3] * 1e3).abs() < 1e-15);
        assert_eq!(&v[8..], &[NO_COLUMN; 2]);
        assert!(err(b.results(Units::Si, 2, &[1])).contains("IBLK = 2"));
        // The pressure at the centre element.
        let p = o.fields.pressure_pa[o.grid.index(3, 3)];
        assert!((v[4] + p * 1e-6).abs() < 1e-6 * p * 1e-6);
    }

    #[test]
    fn calculate_needs_materials_and_tractions() {
        let o = hertz_outcome(7, 1e-3, 1e9, [0.0, 0.0]);
        let mut b = Blocks::default();
        b.add(Units::Si, 1, 5, &[], &[], &[1e-4]).unwrap();
        assert!(err(b.calculate(&o)).contains("materials"));
        b.set_material(&steel());
        b.calculate(&o).unwrap();
        let mut strips = o.clone();
        strips.fields.pressure_pa.clear();
        assert!(matches!(
            b.calculate(&strips),
            Err(CntcError::NotSupported(_))
        ));
        let mut bad = o.clone();
        bad.fields.traction_x_pa[3] = f64::NAN;
        assert!(err(b.calculate(&bad)).contains("not finite"));
        // Without load: zero stresses.
        let none = Outcome::no_contact(o.grid, vec![0.0; o.grid.len()], 0.0);
        b.calculate(&none).unwrap();
        assert!(b.results[0]
            .table
            .iter()
            .all(|r| r[3..].iter().all(|&v| v == 0.0)));
    }

    #[test]
    fn sizes_and_coordinates_are_bounded() {
        let u = Units::Contact;
        let mut b = Blocks::default();
        let e = err(b.add(u, 1, 9, &[0.0], &[2000.0], &[0.0]));
        assert!(
            e.contains("Y(1) = 2000") && e.contains("at most 1 m"),
            "{e}"
        );
        let e = err(b.add(u, 1, 1, &[], &[], &[12.0, 0.0, 100.0]));
        assert!(e.contains("ZL + (NZ - 1) DZ = 1100"), "{e}");
        // A spec built by hand is checked before it is evaluated.
        b.specs.push(BlockSpec {
            isubs: 2,
            x: vec![1.0],
            y: vec![],
            z: vec![],
        });
        let o = hertz_outcome(7, 1e-3, 1e9, [0.0, 0.0]);
        let e = err(b.calculate_with(&o, &steel(), false));
        assert!(
            e.contains("block 1: ISUBS = 2 with 1 x, 0 y and 0 z"),
            "{e}"
        );
        // Too many points for the direct sum: refused before computing.
        let big = hertz_outcome(100, 1e-3, 1e9, [0.0, 0.0]);
        let loaded = big.fields.pressure_pa.iter().filter(|&&p| p > 0.0).count();
        let v: Vec<f64> = (0..100).map(|k| 1e-5 * k as f64 + 1e-7).collect();
        let mut b = Blocks::default();
        b.add(Units::Si, 1, 9, &v, &v, &[1e-4; 30]).unwrap();
        assert!(300_000 * loaded as u64 > MAX_DIRECT_PAIRS);
        let e = err(b.calculate_with(&big, &steel(), false));
        assert!(
            e.contains("at most 200000000") && e.contains("ISUBS = 1-7"),
            "{e}"
        );
        // Too many points over all blocks.
        for k in 1..=4 {
            b.add(Units::Si, k, 5, &[], &[], &vec![1e-4; 9999]).unwrap();
        }
        let e = err(b.calculate_with(&big, &steel(), false));
        assert!(e.contains("at most 1000000"), "{e}");
    }
}
