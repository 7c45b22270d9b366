//! The rectangular potential contact grid.
//!
//! Elements are `nx` by `ny` rectangles of size `dx` by `dy` \[m\]. Element (ix, iy)
//! has its centre at x = x0 + (ix + 1/2) dx, y = y0 + (iy + 1/2) dy and is stored
//! at index `iy * nx + ix` (x runs fastest: grid lines along the rolling
//! direction are contiguous). x is the rolling direction; the leading edge of a
//! rolling contact is at large x (see [`crate::core::problem`] for the sign
//! conventions).
//!
//! A grid of one row ([`Grid::line`]) is a line contact: strips of width
//! `dx` across the unit length [`LINE_LENGTH_M`] of two cylinders, solved
//! with the plane-strain coefficients of the half-plane
//! ([`crate::core::influence`]). Its totals are forces per metre. Every
//! other grid has at least [`MIN_ELEMENTS`] rows.

use serde::{Deserialize, Serialize};

use crate::core::error::{require_finite, require_positive, ContactError};
use crate::core::influence::{LINE_LENGTH_M, LINE_REFERENCE_DISTANCE_M};

/// Smallest grid dimension accepted.
pub const MIN_ELEMENTS: usize = 4;
/// Largest number of elements accepted in one direction.
pub const MAX_ELEMENTS_PER_DIRECTION: usize = 2048;

/// A validated potential contact grid (read back from serde only through
/// [`Grid::new`] or [`Grid::line_from`], so a deserialised grid is valid).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "GridFields")]
pub struct Grid {
    /// Elements in x (rolling direction).
    pub nx: usize,
    /// Elements in y (lateral direction).
    pub ny: usize,
    /// Element size in x \[m\].
    pub dx_m: f64,
    /// Element size in y \[m\].
    pub dy_m: f64,
    /// x of the grid's lower-left corner \[m\].
    pub x0_m: f64,
    /// y of the grid's lower-left corner \[m\].
    pub y0_m: f64,
}

/// A grid's fields as serialised, before they are checked.
#[derive(Deserialize)]
struct GridFields {
    nx: usize,
    ny: usize,
    dx_m: f64,
    dy_m: f64,
    x0_m: f64,
    y0_m: f64,
}

impl TryFrom<GridFields> for Grid {
    type Error = ContactError;

    fn try_from(g: GridFields) -> Result<Self, ContactError> {
        if g.ny == 1 {
            let line = Grid::line_from(g.nx, g.dx_m, g.x0_m)?;
            if line.dy_m != g.dy_m || line.y0_m != g.y0_m {
                return Err(ContactError::invalid(
                    "grid.dy_m",
                    "a line-contact grid has the unit length's row",
                ));
            }
            Ok(line)
        } else {
            Grid::new(g.nx, g.ny, g.dx_m, g.dy_m, g.x0_m, g.y0_m)
        }
    }
}

impl Grid {
    /// The first and last columns and rows \[ix0, ix1, iy0, iy1\] of the
    /// elements where `field > 0`, or None when there are none.
    fn loaded_elements(&self, field: &[f64]) -> Option<[usize; 4]> {
        let (mut xmin, mut xmax, mut ymin, mut ymax) = (usize::MAX, 0, usize::MAX, 0);
        for iy in 0..self.ny {
            for ix in 0..self.nx {
                if field[self.index(ix, iy)] > 0.0 {
                    xmin = xmin.min(ix);
                    xmax = xmax.max(ix);
                    ymin = ymin.min(iy);
                    ymax = ymax.max(iy);
                }
            }
        }
        (xmin != usize::MAX).then_some([xmin, xmax, ymin, ymax])
    }

    /// The box \[x0, x1, y0, y1\] \[m\] of the elements where `field > 0`
    /// (the loaded patch), their edges included, or None when there are
    /// none.
    pub fn loaded_box_m(&self, field: &[f64]) -> Option<[f64; 4]> {
        self.loaded_elements(field).map(|[x0, x1, y0, y1]| {
            [
                self.x0_m + x0 as f64 * self.dx_m,
                self.x0_m + (x1 + 1) as f64 * self.dx_m,
                self.y0_m + y0 as f64 * self.dy_m,
                self.y0_m + (y1 + 1) as f64 * self.dy_m,
            ]
        })
    }

    /// Length along x and width along y \[m\] of the bounding box of the
    /// elements where `field > 0` (the loaded patch), or None when there
    /// are none.
    pub fn loaded_extent_m(&self, field: &[f64]) -> Option<[f64; 2]> {
        self.loaded_elements(field).map(|[x0, x1, y0, y1]| {
            [
                (x1 - x0 + 1) as f64 * self.dx_m,
                (y1 - y0 + 1) as f64 * self.dy_m,
            ]
        })
    }

    /// A grid of `nx` x `ny` elements covering `[x0, x0 + nx dx] x [y0, y0 + ny dy]`.
    pub fn new(
        nx: usize,
        ny: usize,
        dx_m: f64,
        dy_m: f64,
        x0_m: f64,
        y0_m: f64,
    ) -> Result<Self, ContactError> {
        for (key, n) in [("grid.nx", nx), ("grid.ny", ny)] {
            if !(MIN_ELEMENTS..=MAX_ELEMENTS_PER_DIRECTION).contains(&n) {
                return Err(ContactError::invalid(
                    key,
                    format!(
                        "must be between {MIN_ELEMENTS} and {MAX_ELEMENTS_PER_DIRECTION}, got {n}"
                    ),
                ));
            }
        }
        require_positive("grid.dx_m", dx_m)?;
        require_positive("grid.dy_m", dy_m)?;
        require_finite("grid.x0_m", x0_m)?;
        require_finite("grid.y0_m", y0_m)?;
        Ok(Self {
            nx,
            ny,
            dx_m,
            dy_m,
            x0_m,
            y0_m,
        })
    }

    /// A line-contact grid of `nx` strips of width `window_x_m / nx`
    /// centred on the origin ([`Grid::line_from`]).
    pub fn line(nx: usize, window_x_m: f64) -> Result<Self, ContactError> {
        require_positive("grid.window_x_m", window_x_m)?;
        Self::line_from(nx, window_x_m / nx as f64, -0.5 * window_x_m)
    }

    /// A line-contact grid of `nx` strips of width `dx_m` from x = `x0_m`:
    /// one row standing for [`LINE_LENGTH_M`] of the cylinders (y in
    /// [-1/2, 1/2] m). The window `nx dx_m` must not exceed the reference
    /// distance of the displacements ([`LINE_REFERENCE_DISTANCE_M`], 1 m),
    /// which keeps the plane-strain operator positive definite.
    pub fn line_from(nx: usize, dx_m: f64, x0_m: f64) -> Result<Self, ContactError> {
        let g = Self::new(
            nx,
            MIN_ELEMENTS,
            dx_m,
            LINE_LENGTH_M,
            x0_m,
            -0.5 * LINE_LENGTH_M,
        )?;
        let window = nx as f64 * dx_m;
        if window > LINE_REFERENCE_DISTANCE_M {
            return Err(ContactError::invalid(
                "grid.window_x_m",
                format!(
                    "a line contact's window must be at most {LINE_REFERENCE_DISTANCE_M} m, got {window} m"
                ),
            ));
        }
        Ok(Self { ny: 1, ..g })
    }

    /// Whether this is a line-contact grid (one row, [`Grid::line`]).
    #[inline]
    pub fn is_line(&self) -> bool {
        self.ny == 1
    }

    /// A grid centred on the origin covering `window_x_m` by `window_y_m`.
    pub fn centered(
        nx: usize,
        ny: usize,
        window_x_m: f64,
        window_y_m: f64,
    ) -> Result<Self, ContactError> {
        require_positive("grid.window_x_m", window_x_m)?;
        require_positive("grid.window_y_m", window_y_m)?;
        Self::new(
            nx,
            ny,
            window_x_m / nx as f64,
            window_y_m / ny as f64,
            -0.5 * window_x_m,
            -0.5 * window_y_m,
        )
    }

    /// Number of elements.
    #[inline]
    pub fn len(&self) -> usize {
        self.nx * self.ny
    }

    /// Always false: a grid has at least `MIN_ELEMENTS` elements.
    #[inline]
    pub fn is_empty(&self) -> bool {
        false
    }

    /// Element area \[m²\].
    #[inline]
    pub fn element_area_m2(&self) -> f64 {
        self.dx_m * self.dy_m
    }

    /// x of the centre of column `ix` \[m\].
    #[inline]
    pub fn x_m(&self, ix: usize) -> f64 {
        self.x0_m + (ix as f64 + 0.5) * self.dx_m
    }

    /// y of the centre of row `iy` \[m\].
    #[inline]
    pub fn y_m(&self, iy: usize) -> f64 {
        self.y0_m + (iy as f64 + 0.5) * self.dy_m
    }

    /// Flat index of element (ix, iy).
    #[inline]
    pub fn index(&self, ix: usize, iy: usize) -> usize {
        iy * self.nx + ix
    }

    /// True when element (ix, iy) lies on the outer ring of the grid (for
    /// a line contact: the first or last strip).
    #[inline]
    pub fn on_border(&self, ix: usize, iy: usize) -> bool {
        ix == 0 || ix + 1 == self.nx || (!self.is_line() && (iy == 0 || iy + 1 == self.ny))
    }

    /// The number of border elements ([`Grid::on_border`]) where
    /// `field > 0`: the loaded elements at the border of a patch that
    /// outgrew the grid.
    pub fn loaded_border_elements(&self, field: &[f64]) -> usize {
        (0..self.ny)
            .flat_map(|iy| (0..self.nx).map(move |ix| (ix, iy)))
            .filter(|&(ix, iy)| self.on_border(ix, iy) && field[self.index(ix, iy)] > 0.0)
            .count()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centred_grid_is_symmetric() {
        let g = Grid::centered(10, 4, 2.0e-3, 1.0e-3).unwrap();
        assert!((g.x_m(0) + g.x_m(9)).abs() < 1e-18);
        assert!((g.y_m(0) + g.y_m(3)).abs() < 1e-18);
        assert_eq!(g.index(3, 2), 23);
    }

    #[test]
    fn rejects_tiny_or_bad_grids() {
        assert!(Grid::centered(2, 10, 1.0, 1.0).is_err());
        assert!(Grid::centered(10, 10, f64::NAN, 1.0).is_err());
        assert!(Grid::new(10, 10, 0.0, 1.0, 0.0, 0.0).is_err());
    }
}
