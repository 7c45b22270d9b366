//! The rolling frame: a problem whose rolling direction chi is not +x,
//! turned so that it rolls in +x (or close to it), and its solution turned
//! back.
//!
//! The exact solver discretises steady rolling and transient rolling steps
//! along the grid's x axis (the upwind difference of the steady operator,
//! the marching sweeps, the traction memory carried by whole elements;
//! see [`crate::core::steady`]). A rolling direction along one of the
//! grid's axes, chi = k pi/2, is therefore solved exactly by turning the
//! problem a quarter turn k times about n: (x', y') = (cos chi x + sin chi
//! y, -sin chi x + cos chi y) maps the grid onto a grid of the same
//! elements (rows and columns exchanged when k is odd), every per-element
//! field onto its element, and every tangential vector (creepages, shifts,
//! tractions, slips, forces) by the same rotation; spin, rotations, the
//! moment about n through the origin and all scalars are unchanged.
//!
//! Any other direction is split as chi = k pi/2 + theta, |theta| <= pi/4
//! ([`direction`]): the problem is turned by the k quarter turns and keeps
//! the oblique rest theta as its rolling direction. Transient rolling steps
//! take it: a step of dq carries the previous tractions, pressures and
//! element states (dq cos theta, dq sin theta) upstream, off the element
//! centres, by bilinear interpolation between the four surrounding
//! elements (the states and a friction law's memory from the nearest
//! element; see [`crate::core::tangential::carry_upstream`]). Steady
//! rolling has no discretisation of d/dq across the grid lines and is
//! refused off the axes, naming the key: its transient rolling steps tend
//! to it. CONTACT likewise takes steady rolling along `CHI` = 0 or pi only
//! (its SteadyGS solver, which resets other directions to 0 with a
//! warning) and interpolates the carried fields of transient rolling steps
//! in any direction (Vollebregt, User guide for CONTACT, §"Tangential
//! quantities in case of rolling").

use std::f64::consts::FRAC_PI_2;

use crate::core::error::{show, ContactError};
use crate::core::grid::Grid;
use crate::core::problem::{ContactProblem, ExtraRigidSlip, Kinematics, ShiftStep};
use crate::core::solution::ContactSolution;

/// Largest distance of a rolling direction to the nearest multiple of
/// pi/2 \[rad\] that counts as that multiple (decimal input of pi).
pub const AXIS_TOLERANCE_RAD: f64 = 1e-6;

/// The key of the rolling direction in errors.
pub const ROLLING_DIRECTION_KEY: &str = "rolling_direction_rad";

/// A rolling direction chi = turns pi/2 + oblique_rad.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Direction {
    /// Quarter turns k, 0 to 3.
    pub turns: u8,
    /// The rest theta \[rad\], |theta| <= pi/4; exactly 0 within
    /// [`AXIS_TOLERANCE_RAD`] of a multiple of pi/2.
    pub oblique_rad: f64,
}

impl Direction {
    /// Whether the direction is along one of the grid's axes.
    pub fn is_axis(&self) -> bool {
        self.oblique_rad == 0.0
    }
}

/// The [`Direction`] of `chi_rad` on a grid that is a line contact
/// (`line`: one row of strips across y, which rolls along x only: chi 0 or
/// pi) or not, or an error naming [`ROLLING_DIRECTION_KEY`]; chi must be
/// finite.
pub fn direction(chi_rad: f64, line: bool) -> Result<Direction, ContactError> {
    if !chi_rad.is_finite() {
        return Err(ContactError::invalid(
            ROLLING_DIRECTION_KEY,
            format!("must be finite, got {}", show(chi_rad)),
        ));
    }
    let k = (chi_rad / FRAC_PI_2).round();
    let rest = chi_rad - k * FRAC_PI_2;
    let oblique_rad = if rest.abs() > AXIS_TOLERANCE_RAD {
        rest
    } else {
        0.0
    };
    let turns = k.rem_euclid(4.0) as u8;
    if line && (turns % 2 == 1 || oblique_rad != 0.0) {
        return Err(ContactError::invalid(
            ROLLING_DIRECTION_KEY,
            format!(
                "a line contact rolls along x (0 or pi), got {}",
                show(chi_rad)
            ),
        ));
    }
    Ok(Direction { turns, oblique_rad })
}

/// The quarter turns k (0 to 3) of a rolling direction `chi_rad` = k pi/2
/// on `grid`, or an error naming [`ROLLING_DIRECTION_KEY`]: chi must be
/// finite and within [`AXIS_TOLERANCE_RAD`] of a multiple of pi/2, and a
/// line contact (one row of strips across y) rolls along x only (k 0 or 2).
/// This is the rule of steady rolling; transient problems take any
/// [`direction`].
pub fn quarter_turns(chi_rad: f64, grid: &Grid) -> Result<u8, ContactError> {
    axis_turns(chi_rad, grid.is_line())
}

/// [`quarter_turns`] on a grid that is a line contact (`line`) or not.
pub fn axis_turns(chi_rad: f64, line: bool) -> Result<u8, ContactError> {
    let d = direction(chi_rad, line)?;
    if !d.is_axis() {
        return Err(ContactError::invalid(
            ROLLING_DIRECTION_KEY,
            format!(
                "must be a multiple of pi/2 (within {AXIS_TOLERANCE_RAD:e} rad) in steady rolling: \
                 it rolls along a grid axis, 0 = +x, pi/2 = +y, pi = -x, 3 pi/2 = -y (transient \
                 rolling steps take any direction and tend to steady rolling); got {}",
                show(chi_rad)
            ),
        ));
    }
    Ok(d.turns)
}

/// The map between a problem's frame (the user's) and the solver's
/// rolling frame, in which the patch rolls in +x.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RollingFrame {
    /// Quarter turns k about n, chi = k pi/2.
    turns: u8,
    /// The problem's grid.
    user: Grid,
    /// The same elements in the rolling frame.
    rolling: Grid,
}

impl RollingFrame {
    /// The frame of `problem`'s rolling direction and grid.
    pub fn of(problem: &ContactProblem) -> Result<Self, ContactError> {
        let d = direction(problem.rolling_direction_rad, problem.grid.is_line())?;
        Ok(Self::new(d.turns, problem.grid))
    }

    /// The frame of `turns` quarter turns of `user`.
    pub fn new(turns: u8, user: Grid) -> Self {
        let g = user;
        let (x1, y1) = (g.x0_m + g.nx as f64 * g.dx_m, g.y0_m + g.ny as f64 * g.dy_m);
        let rolling = match turns {
            0 => g,
            // (x', y') = (y, -x)
            1 => Grid {
                nx: g.ny,
                ny: g.nx,
                dx_m: g.dy_m,
                dy_m: g.dx_m,
                x0_m: g.y0_m,
                y0_m: -x1,
            },
            // (x', y') = (-x, -y)
            2 => Grid {
                x0_m: -x1,
                y0_m: -y1,
                ..g
            },
            // (x', y') = (-y, x)
            _ => Grid {
                nx: g.ny,
                ny: g.nx,
                dx_m: g.dy_m,
                dy_m: g.dx_m,
                x0_m: -y1,
                y0_m: g.x0_m,
            },
        };
        Self {
            turns,
            user,
            rolling,
        }
    }

    /// Whether the patch rolls in +x already (chi = 0): nothing to turn.
    pub fn is_identity(&self) -> bool {
        self.turns == 0
    }

    /// The quarter turns k, chi = k pi/2.
    pub fn turns(&self) -> u8 {
        self.turns
    }

    /// The problem's grid.
    pub fn user_grid(&self) -> Grid {
        self.user
    }

    /// The grid in the rolling frame.
    pub fn rolling_grid(&self) -> Grid {
        self.rolling
    }

    /// (cos chi, sin chi).
    fn cos_sin(&self) -> (f64, f64) {
        match self.turns {
            0 => (1.0, 0.0),
            1 => (0.0, 1.0),
            2 => (-1.0, 0.0),
            _ => (0.0, -1.0),
        }
    }

    /// A tangential vector of the problem's frame in the rolling frame.
    pub fn to_rolling(&self, [vx, vy]: [f64; 2]) -> [f64; 2] {
        let (c, s) = self.cos_sin();
        [c * vx + s * vy, -s * vx + c * vy]
    }

    /// A tangential vector of the rolling frame in the problem's frame.
    pub fn to_user(&self, [vx, vy]: [f64; 2]) -> [f64; 2] {
        let (c, s) = self.cos_sin();
        [c * vx - s * vy, s * vx + c * vy]
    }

    /// The problem's index of the element (`jx`, `jy`) of the rolling grid.
    fn user_index(&self, jx: usize, jy: usize) -> usize {
        let (nx, ny) = (self.user.nx, self.user.ny);
        let (ix, iy) = match self.turns {
            0 => (jx, jy),
            1 => (nx - 1 - jy, jx),
            2 => (nx - 1 - jx, ny - 1 - jy),
            _ => (jy, ny - 1 - jx),
        };
        iy * nx + ix
    }

    /// `to[j] = from[user_index(j)]`: a per-element field of the problem's
    /// grid on the rolling grid.
    pub fn field_to_rolling<T: Copy>(&self, from: &[T], to: &mut [T]) {
        if self.is_identity() {
            to.copy_from_slice(from);
            return;
        }
        let r = self.rolling;
        for jy in 0..r.ny {
            for jx in 0..r.nx {
                to[r.index(jx, jy)] = from[self.user_index(jx, jy)];
            }
        }
    }

    /// The inverse of [`RollingFrame::field_to_rolling`].
    pub fn field_to_user<T: Copy>(&self, from: &[T], to: &mut [T]) {
        let r = self.rolling;
        for jy in 0..r.ny {
            for jx in 0..r.nx {
                to[self.user_index(jx, jy)] = from[r.index(jx, jy)];
            }
        }
    }

    /// A per-element vector field (`x`, `y`) of the problem's grid on the
    /// rolling grid, turned.
    pub fn vectors_to_rolling(&self, x: &[f64], y: &[f64]) -> [Vec<f64>; 2] {
        self.turn_vectors(x, y, true)
    }

    /// A per-element vector field (`x`, `y`) of the rolling grid on the
    /// problem's grid, turned back.
    fn vectors_to_user(&self, x: &[f64], y: &[f64]) -> [Vec<f64>; 2] {
        self.turn_vectors(x, y, false)
    }

    /// [`RollingFrame::vectors_to_rolling`] (`to_rolling`) or
    /// [`RollingFrame::vectors_to_user`].
    fn turn_vectors(&self, x: &[f64], y: &[f64], to_rolling: bool) -> [Vec<f64>; 2] {
        let mut out = [vec![0.0; x.len()], vec![0.0; y.len()]];
        let r = self.rolling;
        for jy in 0..r.ny {
            for jx in 0..r.nx {
                let (i, j) = (self.user_index(jx, jy), r.index(jx, jy));
                let (from, to) = if to_rolling { (i, j) } else { (j, i) };
                let v = [x[from], y[from]];
                let [a, b] = if to_rolling {
                    self.to_rolling(v)
                } else {
                    self.to_user(v)
                };
                out[0][to] = a;
                out[1][to] = b;
            }
        }
        out
    }

    /// A step of the problem's frame in the rolling frame.
    pub fn step(&self, s: &ShiftStep) -> ShiftStep {
        let [shift_x_m, shift_y_m] = self.to_rolling([s.shift_x_m, s.shift_y_m]);
        ShiftStep {
            shift_x_m,
            shift_y_m,
            ..*s
        }
    }

    /// `p` (of this frame's grid and direction) in the rolling frame: its
    /// rolling direction the oblique rest of `p`'s ([`Direction`]), 0 along
    /// an axis.
    pub fn problem(&self, p: &ContactProblem) -> ContactProblem {
        let mut gap_m = vec![0.0; p.gap_m.len()];
        self.field_to_rolling(&p.gap_m, &mut gap_m);
        let kinematics = match &p.kinematics {
            Kinematics::Frictionless => Kinematics::Frictionless,
            Kinematics::SteadyRolling(c) => {
                let [xi, eta] = self.to_rolling([c.creepage_long, c.creepage_lat]);
                Kinematics::SteadyRolling(crate::core::problem::Creepages {
                    creepage_long: xi,
                    creepage_lat: eta,
                    spin_per_m: c.spin_per_m,
                })
            }
            Kinematics::Transient(steps) => {
                Kinematics::Transient(steps.iter().map(|s| self.step(s)).collect())
            }
        };
        let extra_rigid_slip = p.extra_rigid_slip.as_ref().map(|e| {
            let turn = |x: &[f64], y: &[f64]| match x.is_empty() {
                true => [Vec::new(), Vec::new()],
                false => self.vectors_to_rolling(x, y),
            };
            let [slip_x, slip_y] = turn(&e.slip_x, &e.slip_y);
            let [shift_x_m, shift_y_m] = turn(&e.shift_x_m, &e.shift_y_m);
            ExtraRigidSlip {
                slip_x,
                slip_y,
                shift_x_m,
                shift_y_m,
            }
        });
        ContactProblem {
            material: p.material,
            friction: p.friction,
            grid: self.rolling,
            gap_m,
            load: p.load,
            kinematics,
            settings: p.settings,
            rolling_direction_rad: direction(p.rolling_direction_rad, p.grid.is_line())
                .map_or(0.0, |d| d.oblique_rad),
            extra_rigid_slip,
            numerical_influence: p.numerical_influence.clone(),
        }
    }

    /// A solution of the rolling frame in the problem's frame (`gap_m` the
    /// problem's undeformed distance).
    pub fn solution(&self, s: ContactSolution, gap_m: &[f64]) -> ContactSolution {
        let f = &s.fields;
        let n = f.pressure_pa.len();
        let mut pressure_pa = vec![0.0; n];
        self.field_to_user(&f.pressure_pa, &mut pressure_pa);
        let mut state = f.state.clone();
        self.field_to_user(&f.state, &mut state);
        let [traction_x_pa, traction_y_pa] =
            self.vectors_to_user(&f.traction_x_pa, &f.traction_y_pa);
        let [slip_x, slip_y] = self.vectors_to_user(&f.slip_x, &f.slip_y);
        let mut totals = s.totals;
        [totals.fx_n, totals.fy_n] = self.to_user([totals.fx_n, totals.fy_n]);
        if self.turns % 2 == 1 {
            std::mem::swap(&mut totals.patch_length_m, &mut totals.patch_width_m);
        }
        ContactSolution {
            totals,
            info: s.info,
            fields: crate::core::solution::ElementFields {
                pressure_pa,
                traction_x_pa,
                traction_y_pa,
                slip_x,
                slip_y,
                state,
                gap_m: gap_m.to_vec(),
            },
        }
    }

    /// An error of the rolling frame in the problem's frame: a patch at the
    /// border of the rolling grid's x is at the border of the problem's y
    /// when the frame turns by an odd number of quarters.
    pub fn error(&self, e: ContactError) -> ContactError {
        match e {
            ContactError::GridTooSmall { key, detail } if self.turns % 2 == 1 => {
                ContactError::GridTooSmall {
                    key: if key == "grid.window_x_m" {
                        "grid.window_y_m"
                    } else {
                        "grid.window_x_m"
                    },
                    detail: format!(
                        "{detail} (in the rolling frame, x along the rolling direction)"
                    ),
                }
            }
            e => e,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_turn_maps_each_element_centre_onto_its_rotated_position() {
        let g = Grid::new(7, 5, 2e-4, 3e-4, -8e-4, -5e-4).unwrap();
        for turns in 0..4u8 {
            let f = RollingFrame::new(turns, g);
            let r = f.rolling_grid();
            assert_eq!(r.len(), g.len());
            for jy in 0..r.ny {
                for jx in 0..r.nx {
                    let i = f.user_index(jx, jy);
                    let (ix, iy) = (i % g.nx, i / g.nx);
                    let [xr, yr] = f.to_rolling([g.x_m(ix), g.y_m(iy)]);
                    assert!((r.x_m(jx) - xr).abs() < 1e-15, "turns {turns}");
                    assert!((r.y_m(jy) - yr).abs() < 1e-15, "turns {turns}");
                }
            }
            let v = [0.3, -1.7];
            assert_eq!(f.to_user(f.to_rolling(v)), v);
        }
    }

    #[test]
    fn directions_off_the_axes_and_non_finite_ones_are_refused_naming_the_key() {
        let g = Grid::centered(8, 8, 1e-3, 1e-3).unwrap();
        assert_eq!(quarter_turns(std::f64::consts::PI, &g), Ok(2));
        assert_eq!(quarter_turns(-FRAC_PI_2, &g), Ok(3));
        // pi in eight decimals, 3.6e-9 rad short.
        assert_eq!(quarter_turns(std::f64::consts::PI - 3.6e-9, &g), Ok(2));
        for chi in [0.3, f64::NAN, f64::INFINITY] {
            let e = quarter_turns(chi, &g).unwrap_err();
            assert_eq!(e.key(), Some(ROLLING_DIRECTION_KEY), "{chi}");
        }
        let line = Grid::line(16, 1e-3).unwrap();
        assert_eq!(quarter_turns(std::f64::consts::PI, &line), Ok(2));
        assert!(quarter_turns(FRAC_PI_2, &line).is_err());
    }
}
