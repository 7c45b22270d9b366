//! The leading-edge correction of a transient rolling step (CONTACT's
//! `m_leadedge`; Vollebregt, CONTACT user guide, "leading edge
//! correction"; Kalker 1990 §5.2 for the step's slip).
//!
//! A rolling step of dq = k dx carries the previous tractions k elements
//! upstream ([`crate::core::problem`]), and the slip of the step at an
//! element is S = W + u - u', W the rigid shift over the step, u the
//! displacement difference now and u' that of the material's previous
//! position. That holds for material that was in contact during the whole
//! step. With k > 1 the material now in the last elements of the contact
//! area before its leading edge entered it during the step: it was in
//! contact for a fraction
//!
//! facdt = min(1, (x_e - x) / dq)
//!
//! of the step, x_e the position of the leading edge, and it had the
//! displacement difference of the edge when it entered. Its slip over the
//! step is then
//!
//! S = facdt W + u - u_bnd,
//!
//! u_bnd the displacement difference at the edge at the start of the step
//! (of the previous tractions where they were then, relative to the patch;
//! CONTACT's `subnd`). In the carried field u' (the previous displacement
//! of the material now at each element) that is u' of the element dq
//! behind the edge: the material there was at x_e. CONTACT estimates the
//! edge at the centre of the first element outside the contact area
//! downstream of the last one in contact of each grid row's segment (its
//! `sxbnd` with `facdx` = 1), element e, so the elements e - j, j = 1 ..
//! k - 1, take facdt = j / k and u_bnd = u'(e - k); a step of one element
//! (k = 1) corrects nothing. The correction is CONTACT's, applied where
//! CONTACT applies it, so that steps of several elements give CONTACT's
//! tractions.
//!
//! Where this differs from CONTACT: a segment whose last element in contact
//! is one of the last two of its grid row is not corrected (CONTACT does
//! not correct its last elements either, but gives the elements further
//! back its factor facdt with a zero edge displacement), nor is one whose
//! edge is less than k elements from the row's start (the previous
//! tractions there are no longer on the grid; CONTACT keeps them); oblique
//! rolling steps ([`Carry::Oblique`]) are not corrected (CONTACT's
//! correction assumes rolling along its x axis).

use crate::core::grid::Grid;
use crate::core::problem::Carry;

/// The fixed part of a transient step's slip without the normal pressure's
/// share: on entry `slip` holds the rigid shift W per element \[m\] (x, y),
/// on return W - u' with the leading-edge correction, facdt W - u_bnd,
/// for the elements that entered the contact area (`pressure` > 0 \[Pa\])
/// during a rolling step of `carry`; `previous` is u' per element \[m\]
/// (x, y): the previous tractions' displacement difference, carried
/// upstream. Without correction (a shift step, one element a step, an
/// oblique step) it is W - u' at every element.
pub fn fixed_slip(
    grid: &Grid,
    carry: Carry,
    pressure: &[f64],
    previous: [&[f64]; 2],
    slip: [&mut [f64]; 2],
) {
    let k = match carry {
        Carry::Whole(k) if k > 1 => k,
        _ => {
            for (s, p) in slip.into_iter().zip(previous) {
                for (s, p) in s.iter_mut().zip(p) {
                    *s -= p;
                }
            }
            return;
        }
    };
    let nx = grid.nx;
    let [sx, sy] = slip;
    let rows = pressure
        .chunks_exact(nx)
        .zip(previous[0].chunks_exact(nx))
        .zip(previous[1].chunks_exact(nx))
        .zip(sx.chunks_exact_mut(nx).zip(sy.chunks_exact_mut(nx)));
    for (((pn, ux), uy), (sx, sy)) in rows {
        // The outside element at the edge of the segment the elements
        // from here on downstream belong to, when it can be corrected.
        let mut edge: Option<usize> = None;
        for ix in (0..nx).rev() {
            let inside = pn[ix] > 0.0;
            if inside && (ix + 1 == nx || pn[ix + 1] <= 0.0) {
                edge = (ix + 2 < nx && ix + 1 >= k).then_some(ix + 1);
            }
            match edge {
                Some(e) if inside && e - ix < k => {
                    let facdt = (e - ix) as f64 / k as f64;
                    sx[ix] = facdt * sx[ix] - ux[e - k];
                    sy[ix] = facdt * sy[ix] - uy[e - k];
                }
                _ => {
                    sx[ix] -= ux[ix];
                    sy[ix] -= uy[ix];
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(nx: usize) -> Grid {
        Grid::new(nx, 4, 1e-3, 1e-3, 0.0, 0.0).expect("valid grid")
    }

    /// One row of `nx` elements repeated over the grid's 4 rows: slip after
    /// [`fixed_slip`] with W = 1 and u' = 10 + ix at element ix.
    fn row_slip(nx: usize, carry: Carry, contact: impl Fn(usize) -> bool) -> Vec<f64> {
        let g = grid(nx);
        let n = g.len();
        let pn: Vec<f64> = (0..n)
            .map(|i| if contact(i % nx) { 1.0 } else { 0.0 })
            .collect();
        let u: Vec<f64> = (0..n).map(|i| 10.0 + (i % nx) as f64).collect();
        let (mut sx, mut sy) = (vec![1.0; n], vec![1.0; n]);
        fixed_slip(&g, carry, &pn, [&u, &u], [&mut sx, &mut sy]);
        assert_eq!(sx, sy);
        assert!(sx.chunks_exact(nx).all(|r| r == &sx[..nx]));
        sx[..nx].to_vec()
    }

    #[test]
    fn steps_of_one_element_and_shifts_are_not_corrected() {
        let plain: Vec<f64> = (0..10).map(|ix| 1.0 - (10.0 + ix as f64)).collect();
        for carry in [Carry::Whole(0), Carry::Whole(1), Carry::Oblique([2.0, 0.5])] {
            assert_eq!(
                row_slip(10, carry, |ix| (2..6).contains(&ix)),
                plain,
                "{carry:?}"
            );
        }
    }

    #[test]
    fn the_last_elements_before_the_edge_take_part_of_the_shift_and_the_edge_displacement() {
        // Contact in 2..6, the edge at element 6's centre; k = 3: element
        // 5 in contact for 1/3 of the step, 4 for 2/3, 3 and 2 all of it;
        // the edge's displacement is u' of element 6 - 3.
        let s = row_slip(10, Carry::Whole(3), |ix| (2..6).contains(&ix));
        let want = [
            1.0 - 10.0,
            1.0 - 11.0,
            1.0 - 12.0,
            1.0 - 13.0,
            2.0 / 3.0 - 13.0,
            1.0 / 3.0 - 13.0,
            1.0 - 16.0,
            1.0 - 17.0,
            1.0 - 18.0,
            1.0 - 19.0,
        ];
        for (ix, (g, w)) in s.iter().zip(want).enumerate() {
            assert!((g - w).abs() < 1e-12, "element {ix}: {g} != {w}");
        }
    }

    #[test]
    fn each_segment_of_a_row_has_its_own_edge_and_the_grid_ends_are_not_corrected() {
        // Segments 1..3 (edge at 3) and 5..9 (last in contact 8, one of
        // the row's last two: not corrected); k = 2.
        let two = |ix| (1..3).contains(&ix) || (5..9).contains(&ix);
        let s = row_slip(10, Carry::Whole(2), two);
        let mut want: Vec<f64> = (0..10).map(|ix| 1.0 - (10.0 + ix as f64)).collect();
        want[2] = 0.5 - 11.0;
        assert_eq!(s, want);
        // With k = 4 the first segment's edge is less than k elements from
        // the row's start: not corrected either; 5..8 (edge at 8) is.
        let two = |ix| (1..3).contains(&ix) || (5..8).contains(&ix);
        let s = row_slip(10, Carry::Whole(4), two);
        let mut want: Vec<f64> = (0..10).map(|ix| 1.0 - (10.0 + ix as f64)).collect();
        for j in 1..=3 {
            want[8 - j] = j as f64 / 4.0 - 14.0;
        }
        assert_eq!(s, want);
    }
}
