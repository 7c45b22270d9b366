//! Contact tables: the geometric part of the contact search precomputed per
//! profile pair, so that a time step of the Hertz+FASTSIM fast path costs a
//! look-up and a few point evaluations instead of a search.
//!
//! # What is tabulated
//!
//! [`ContactTable::build`] runs the search of [`crate::wheelrail::search`]
//! on a grid of wheelset lateral shift y and roll angle (track frame, yaw 0,
//! wheelset centre at the nominal radius above the top of rail), per side
//! (once when the sides are mirror images). At every node it stores each
//! **potential contact**: each local minimum of the vertical gap (the rail
//! minus the wheel's contact locus) within [`CONTACT_LEVEL_M`] of the
//! node's smallest gap; of two minima whose barrier is below
//! [`PROMINENCE_M`] (rounding, not contacts), the deeper. Per contact:
//!
//! where it lies on the wheel profile (arc length of the fitted profile).
//!
//! Default grid ([`TableSettings::default`]): y from -15 to +15 mm every
//! 0.1 mm and roll from -25 to +25 mrad every 2.5 mrad: 301 x 21 nodes. The
//! roll found from the profiles of S1002/UIC60 is -11.3 mrad at 10 mm shift
//! (CONTACT's `mbench_a22` input has -11.26 mrad) and -15.1 mrad at 15 mm;
//! the rest covers roll inputs away from the quasi-static one. The table
//! only seeds the search (below), so its steps need not resolve the
//! contact positions; 0.1 mm in y puts the onset of a contact within
//! 0.05 mm of shift of a node. Build time: see `crates/solver/tests/validation/wheelrail.rs`.
//!
//! # Look-up
//!
//! [`ContactTable`] interpolates bilinearly between the four nodes around
//! (y, roll). The contacts of the node with the largest weight come first;
//! each is matched at the other nodes with the contact nearest on the
//! wheel profile, within [`MATCH_DISTANCE_M`] of arc length, and its
//! position on the wheel is the weighted mean over the nodes that have it.
//! Contacts of the other nodes
//! left without a match follow (a contact that appears or disappears
//! between the nodes), with the weights of the nodes that have them.
//!
//! Each of these is a **seed**: from it, the vertical gap is evaluated
//! exactly at the actual position (lateral shift, roll **and yaw**: the
//! contact-locus point of that wheel point, [`LocusFrame`], and the rail
//! surface below it) and followed downhill along the wheel profile (in
//! growing steps where the gap falls steeply, sample by sample near the
//! bottom) to its local minimum, refined by a parabola. Seeds that end
//! on the same minimum are one contact; seeds of a contact that does not
//! exist at the actual position end on a neighbour. So the contact
//! position, contact angle (from the rail's sample normals, as the direct
//! search), rolling radius, lead of the contact point and vertical gap are
//! those of the direct search up to how each refines the minimum between
//! samples, and whether a contact exists is decided at the actual
//! position, not at a node. The barrier between neighbouring
//! contacts (the largest vertical gap between them, for grouping) is
//! evaluated the same way. The rigid position (and the roll, when it is
//! not given) follows from these gaps as in the direct search. The roll
//! search starts at the previous step's roll in a co-simulation
//! ([`solve_wheelset_tabulated_warm`]), otherwise at the table's estimate
//! ([`ContactTable::roll_estimate`], from each node's smallest gap); its
//! first roll's contacts come from the look-up, the next rolls' from the
//! contacts of the roll before (the roll moves by micro-radians).
//!
//! The lateral curvature B of the normal undeformed distance (for Hertz)
//! is evaluated at the actual position too, from the vertical gap G(q) at
//! wheel points [`CURVATURE_SPAN_M`] either side of the minimum:
//! B = G''(q) cos^3(angle) / 2, the curvature difference of two curves of
//! slope tan(angle), over the span of the direct path's second difference
//! ([`crate::wheelrail::contact`]). Interpolating B between nodes instead
//! (as this module did first) missed its fast variation at flange roots and
//! flanks: with a roll given 1-3 mrad off the quasi-static one, up to 60 %
//! of B on a tread/flange-root pair. With B from the actual position, no
//! part of the Hertz input comes from the yaw-0 table, so yaw needs no
//! approximation.
//!
//! # Patches
//!
//! Per wheel, as the direct path: potential contacts with a vertical gap
//! below a cap (1.15 times a Hertz estimate of the approach) are grouped,
//! consecutive contacts closer than the merge distance, or whose barrier is
//! below the level, forming one patch at the deepest; the load iteration
//! gives the approach; contacts are grouped again at the approach (the
//! direct path's split of interpenetration that falls apart) and solved
//! again if the patches changed. The direct path merges on the distance
//! between the parts below the level, the tables on the distance between
//! the minima: they differ only for minima about the merge distance apart.
//!
//! Positions outside the table (lateral shift or roll), and models other
//! than Hertz+FASTSIM, are solved with the direct search.

use std::time::Instant;

use crate::core::cache::KernelCache;
use crate::core::cancel::{self, CancelToken};
use crate::core::error::ContactError;
use crate::core::hertz::{hertz, HertzLoad};
use crate::core::memory::{heap_bytes, HeapBytes};
use crate::wheelrail::contact::{
    finish, hertz_patch, load_iteration, normal_per_vertical, solve_pitch, solve_wheelset_warm,
    validate, validate_on, wheel_fastsim, LoadResult, PatchWork, Timing, WarmStart, WheelLoad,
    WheelRailInput, WheelRailModel, WheelRailSolution, WheelResult, CAP_FACTOR,
};
use crate::wheelrail::search::{
    find_roll, parabola_vertex, rail_normal_at, wheel_locus, LocusFrame, LocusPoint, PatchGeometry,
    RollStart, SearchScratch, SearchSettings, SidePose, VerticalGap,
};
use crate::wheelrail::wheelset::{
    CurveSample, PlacedRail, Side, TrackData, WheelRailError, WheelRailPair, SAMPLE_SPACING_M,
};

/// Potential contacts are the minima of the vertical gap up to this far
/// above a node's smallest gap \[m\]: far beyond the approach of any wheel
/// load (about 0.1 mm at 100 kN on S1002/UIC60).
pub const CONTACT_LEVEL_M: f64 = 2.0e-3;

/// Minima of the vertical gap whose barrier to a neighbour is lower than
/// this are one contact \[m\].
pub const PROMINENCE_M: f64 = 1.0e-7;

/// Largest distance along the wheel profile between the matched contacts
/// of neighbouring nodes \[m\].
pub const MATCH_DISTANCE_M: f64 = 2.0e-3;

/// Half-span of the second difference for the lateral curvature B, along
/// the wheel profile \[m\]: that of the direct path (10 lateral samples).
pub const CURVATURE_SPAN_M: f64 = 10.0 * SAMPLE_SPACING_M;

/// Grid of a contact table (track frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TableSettings {
    /// Smallest and largest lateral shift \[m\].
    pub lateral_range_m: [f64; 2],
    /// Lateral step \[m\].
    pub lateral_step_m: f64,
    /// Smallest and largest roll angle \[rad\].
    pub roll_range_rad: [f64; 2],
    /// Roll step \[rad\].
    pub roll_step_rad: f64,
}

impl Default for TableSettings {
    /// See the module documentation for the choice.
    fn default() -> Self {
        Self {
            lateral_range_m: [-0.015, 0.015],
            lateral_step_m: 1.0e-4,
            roll_range_rad: [-0.025, 0.025],
            roll_step_rad: 2.5e-3,
        }
    }
}

/// One potential contact of a table node (side frame).
#[derive(Debug, Clone, Copy, PartialEq)]
struct NodeContact {
    /// Arc length of the contact point along the fitted wheel profile [m].
    wheel_t_m: f64,
}

/// A uniform axis of the grid.
#[derive(Debug, Clone, Copy)]
struct Axis {
    first: f64,
    step: f64,
    n: usize,
}

impl Axis {
    fn new(range: [f64; 2], step: f64, key: &str) -> Result<Self, WheelRailError> {
        if !(step > 0.0 && range[0].is_finite() && range[1] > range[0]) {
            return Err(WheelRailError::invalid(
                key,
                format!("range {range:?} with step {step} is not a grid"),
            ));
        }
        let n = ((range[1] - range[0]) / step).round() as usize + 1;
        if !(2..=10_000).contains(&n) {
            return Err(WheelRailError::invalid(key, format!("{n} nodes")));
        }
        Ok(Self {
            first: range[0],
            step,
            n,
        })
    }

    fn value(&self, i: usize) -> f64 {
        self.first + i as f64 * self.step
    }

    /// Lower node and weight of the upper one; `None` outside.
    fn locate(&self, v: f64) -> Option<(usize, f64)> {
        let f = (v - self.first) / self.step;
        let last = (self.n - 1) as f64;
        if !(f >= -1e-9 && f <= last + 1e-9) {
            return None;
        }
        let i = (f.max(0.0) as usize).min(self.n - 2);
        Some((i, (f - i as f64).clamp(0.0, 1.0)))
    }
}

/// A potential contact evaluated at an actual position (side frame).
#[derive(Debug, Clone, Copy)]
struct Evaluated {
    /// Arc length along the wheel profile [m].
    wheel_t_m: f64,
    locus: LocusPoint,
    rail_z_m: f64,
    /// Contact angle [rad] (set once the position is final:
    /// [`Probe::contact_angle`]).
    contact_angle_rad: f64,
    /// Vertical gap [m].
    gap_m: f64,
    /// Lateral curvature of the normal undeformed distance [1/m] (set
    /// once the position is final: [`Probe::curvature`]).
    b_per_m: f64,
    /// Largest vertical gap between this contact and the next (+q) [m].
    barrier_m: f64,
}

/// Contact tables of one profile pair (both sides). Build once per pair
/// ([`ContactTable::build`]); solve with [`solve_wheelset_tabulated`].
#[derive(Debug, Clone)]
pub struct ContactTable {
    pair: WheelRailPair,
    settings: TableSettings,
    lateral: Axis,
    roll: Axis,
    /// Per side, per node (lateral-major): its contacts, increasing q. The
    /// left side's is empty when it is the mirror image of the right's.
    nodes: [Vec<Vec<NodeContact>>; 2],
    /// Per side, per node: the smallest vertical gap with the wheelset
    /// centre at the nominal radius above the top of rail \[m\] (infinite
    /// where the profiles do not overlap): the start of the roll search.
    min_gap_m: [Vec<f64>; 2],
    /// The sides are mirror images: the left side at (y, roll) is the right
    /// side at (-y, -roll).
    mirrored: bool,
    /// Per side, the rail surface.
    rails: [VerticalGap; 2],
    build_s: f64,
}

/// The nodes of `side` with roll index in `rolls` (lateral-major within
/// each roll), each with its contacts and smallest vertical gap.
fn build_rolls(
    pair: &WheelRailPair,
    side: Side,
    lateral: &Axis,
    roll: &Axis,
    rolls: std::ops::Range<usize>,
) -> Vec<(usize, Vec<NodeContact>, f64)> {
    let z0 = -pair.wheelset().nominal_radius_m;
    let (rail, wheel) = (pair.rail(side), pair.wheel(side));
    let dt = wheel_step_m(wheel.samples());
    let (mut locus0, mut locus) = (Vec::new(), Vec::new());
    let mut gap = VerticalGap::default();
    let mut out = Vec::with_capacity(rolls.len() * lateral.n);
    for ir in rolls {
        if cancel::requested() {
            break;
        }
        // At yaw 0 a lateral shift translates the locus along q.
        let pose = SidePose::new(side, 0.0, z0, roll.value(ir), 0.0);
        wheel_locus(wheel, -z0, &pose, &mut locus0);
        for iy in 0..lateral.n {
            let dq = side.sign() * lateral.value(iy);
            locus.clear();
            locus.extend(locus0.iter().map(|p| LocusPoint {
                q_m: p.q_m + dq,
                ..*p
            }));
            gap.compute(rail, &locus);
            let min_gap_m = gap.min().map_or(f64::INFINITY, |(_, g)| g);
            out.push((iy * roll.n + ir, node_contacts(&gap, &locus, dt), min_gap_m));
        }
    }
    out
}

/// Arc-length step of the (uniform) wheel samples [m].
fn wheel_step_m(samples: &[CurveSample]) -> f64 {
    samples[1].t_m - samples[0].t_m
}

/// Its copy of the pair, its nodes' contacts and gaps, and the rails.
impl HeapBytes for ContactTable {
    fn heap_bytes(&self) -> usize {
        let contacts = self
            .nodes
            .iter()
            .map(|side| {
                side.capacity() * std::mem::size_of::<Vec<NodeContact>>()
                    + side.iter().map(HeapBytes::heap_bytes).sum::<usize>()
            })
            .sum::<usize>();
        contacts + heap_bytes!(self.pair, self.min_gap_m, self.rails)
    }
}

impl ContactTable {
    /// Runs the contact search on the grid of `settings` for `pair` (which
    /// the table keeps a copy of), on all cores.
    pub fn build(pair: &WheelRailPair, settings: &TableSettings) -> Result<Self, WheelRailError> {
        if pair.track().roller_radius_m.is_some() {
            return Err(WheelRailError::invalid(
                "track.roller_radius_m",
                "a contact table is built for a prismatic rail, not a roller rig",
            ));
        }
        let t0 = Instant::now();
        let lateral = Axis::new(
            settings.lateral_range_m,
            settings.lateral_step_m,
            "table.lateral",
        )?;
        let roll = Axis::new(
            settings.roll_range_rad,
            settings.roll_step_rad,
            "table.roll",
        )?;
        let symmetric_grid = |r: [f64; 2]| (r[0] + r[1]).abs() < 1e-12;
        let mirrored = symmetric_grid(settings.lateral_range_m)
            && symmetric_grid(settings.roll_range_rad)
            && pair.rail(Side::Left).samples() == pair.rail(Side::Right).samples()
            && pair.wheel(Side::Left).samples() == pair.wheel(Side::Right).samples();
        let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
        // The build threads stop with the caller's solve (core::cancel).
        let token = CancelToken::current();
        let chunk = roll.n.div_ceil(threads);
        let mut nodes: [Vec<Vec<NodeContact>>; 2] = Default::default();
        let mut min_gap_m: [Vec<f64>; 2] = Default::default();
        for side in Side::BOTH {
            if mirrored && side == Side::Left {
                continue;
            }
            let out = &mut nodes[side.index()];
            out.resize(lateral.n * roll.n, Vec::new());
            let gaps = &mut min_gap_m[side.index()];
            gaps.resize(lateral.n * roll.n, f64::INFINITY);
            let parts = std::thread::scope(|scope| {
                let handles: Vec<_> = (0..roll.n)
                    .step_by(chunk)
                    .map(|first| {
                        let rolls = first..(first + chunk).min(roll.n);
                        let token = token.clone();
                        scope.spawn(move || {
                            let build = || build_rolls(pair, side, &lateral, &roll, rolls);
                            match token {
                                Some(t) => t.scope(build),
                                None => build(),
                            }
                        })
                    })
                    .collect();
                handles
                    .into_iter()
                    .map(|h| h.join().expect("table build thread"))
                    .collect::<Vec<_>>()
            });
            for (k, contacts, gap) in parts.into_iter().flatten() {
                out[k] = contacts;
                gaps[k] = gap;
            }
        }
        if cancel::requested() {
            return Err(WheelRailError::Cancelled);
        }
        let rails = Side::BOTH.map(|s| VerticalGap::rail_surface(pair.rail(s)));
        Ok(Self {
            pair: pair.clone(),
            settings: *settings,
            lateral,
            roll,
            nodes,
            min_gap_m,
            mirrored,
            rails,
            build_s: t0.elapsed().as_secs_f64(),
        })
    }

    /// The profile pair of the table.
    pub fn pair(&self) -> &WheelRailPair {
        &self.pair
    }

    /// The grid.
    pub fn settings(&self) -> &TableSettings {
        &self.settings
    }

    /// Time the build took \[s\].
    pub fn build_time_s(&self) -> f64 {
        self.build_s
    }

    /// Number of nodes (per side).
    pub fn node_count(&self) -> usize {
        self.lateral.n * self.roll.n
    }

    /// True when (lateral shift, roll) lies inside the grid.
    pub fn covers(&self, lateral_m: f64, roll_rad: f64) -> bool {
        self.lateral.locate(lateral_m).is_some() && self.roll.locate(roll_rad).is_some()
    }

    /// The smallest vertical gap of `side` at (y, roll), interpolated
    /// linearly in y at roll node `ir` (the wheelset centre at the
    /// nominal radius, yaw 0) \[m\]; `None` outside the lateral range.
    fn node_min_gap(&self, side: Side, lateral_m: f64, ir: usize) -> Option<f64> {
        if self.mirrored && side == Side::Left {
            return self.node_min_gap(Side::Right, -lateral_m, self.roll.n - 1 - ir);
        }
        let (iy, wy) = self.lateral.locate(lateral_m)?;
        let gaps = &self.min_gap_m[side.index()];
        let g0 = gaps[iy * self.roll.n + ir];
        let g1 = gaps[(iy + 1) * self.roll.n + ir];
        Some(g0 + wy * (g1 - g0))
    }

    /// The roll angle at which both wheels touch their rails at lateral
    /// shift `lateral_m` and yaw 0, from the nodes' smallest gaps
    /// (linear between roll nodes) \[rad\]: where the roll search starts.
    /// `None` when the nodes do not bracket it.
    pub fn roll_estimate(&self, lateral_m: f64) -> Option<f64> {
        let d = |ir: usize| -> Option<f64> {
            let v = self.node_min_gap(Side::Left, lateral_m, ir)?
                - self.node_min_gap(Side::Right, lateral_m, ir)?;
            v.is_finite().then_some(v)
        };
        let mut prev = d(0)?;
        for ir in 1..self.roll.n {
            let next = d(ir)?;
            if prev <= 0.0 && next >= 0.0 {
                let w = if next > prev {
                    -prev / (next - prev)
                } else {
                    0.0
                };
                return Some(self.roll.value(ir - 1) + w * self.roll.step);
            }
            prev = next;
        }
        None
    }

    /// The seeds of the potential contacts of `side` at (y, roll),
    /// interpolated (see the module documentation), nearest node's first;
    /// `None` outside the grid.
    fn lookup(&self, side: Side, lateral_m: f64, roll_rad: f64) -> Option<Vec<NodeContact>> {
        if self.mirrored && side == Side::Left {
            return self.lookup(Side::Right, -lateral_m, -roll_rad);
        }
        let (iy, wy) = self.lateral.locate(lateral_m)?;
        let (ir, wr) = self.roll.locate(roll_rad)?;
        let nodes = &self.nodes[side.index()];
        let at = |dy: usize, dr: usize| &nodes[(iy + dy) * self.roll.n + ir + dr];
        let mut corners = [
            (at(0, 0), (1.0 - wy) * (1.0 - wr)),
            (at(1, 0), wy * (1.0 - wr)),
            (at(0, 1), (1.0 - wy) * wr),
            (at(1, 1), wy * wr),
        ];
        corners.sort_by(|a, b| b.1.total_cmp(&a.1));
        let mut used: Vec<Vec<bool>> = corners.iter().map(|c| vec![false; c.0.len()]).collect();
        let mut out = Vec::new();
        // Contacts of the nearest node, matched at the others; then those
        // of the others that found no match.
        for first in 0..corners.len() {
            for (i, c) in corners[first].0.iter().enumerate() {
                if used[first][i] {
                    continue;
                }
                let (mut t, mut w_sum) = (0.0, 0.0);
                for (k, (contacts, w)) in corners.iter().enumerate().skip(first) {
                    let near = |m: &NodeContact| (m.wheel_t_m - c.wheel_t_m).abs();
                    let Some(j) = (0..contacts.len())
                        .filter(|&j| !used[k][j] && near(&contacts[j]) < MATCH_DISTANCE_M)
                        .min_by(|&a, &b| near(&contacts[a]).total_cmp(&near(&contacts[b])))
                    else {
                        continue;
                    };
                    used[k][j] = true;
                    t += w * contacts[j].wheel_t_m;
                    w_sum += w;
                }
                // Contacts of nodes of zero weight only keep their values.
                out.push(NodeContact {
                    wheel_t_m: if w_sum > 0.0 { t / w_sum } else { c.wheel_t_m },
                });
            }
        }
        Some(out)
    }

    /// The potential contacts of `side` at (y, roll), evaluated in `pose`
    /// (which carries the actual yaw and centre height): each seed of the
    /// look-up refined to the local minimum of the vertical gap on the
    /// wheel profile; seeds that end on the same minimum are one contact.
    /// Increasing q. With `near`, the contacts of a nearby pose of the
    /// same position (the roll search's previous roll), those are the
    /// seeds instead of the look-up's.
    fn evaluate(
        &self,
        side: Side,
        lateral_m: f64,
        roll_rad: f64,
        pose: &SidePose,
        near: Option<&[Evaluated]>,
    ) -> Option<Vec<Evaluated>> {
        let probe = Probe::new(self, side, pose);
        let mut out: Vec<Evaluated> = Vec::new();
        let mut add = |t_m: f64| {
            let Some(e) = probe.descend(t_m) else {
                return;
            };
            let same = |o: &Evaluated| (o.wheel_t_m - e.wheel_t_m).abs() < 2.0 * probe.dt;
            if !out.iter().any(same) {
                out.push(e);
            }
        };
        match near {
            Some(near) => near.iter().for_each(|c| add(c.wheel_t_m)),
            None => self
                .lookup(side, lateral_m, roll_rad)?
                .iter()
                .for_each(|c| add(c.wheel_t_m)),
        }
        out.sort_by(|a, b| a.locus.q_m.total_cmp(&b.locus.q_m));
        (!out.is_empty()).then_some(out)
    }
}

/// Point evaluation of the vertical gap of one side in one pose at any
/// point of the wheel profile.
struct Probe<'a> {
    samples: &'a [CurveSample],
    dt: f64,
    frame: LocusFrame,
    rail: &'a VerticalGap,
    rail_samples: &'a [CurveSample],
}

/// Largest change of roll in the roll search over which the contacts of
/// one roll seed those of the next instead of the table's look-up \[rad\]:
/// a tenth of the default roll step, a change of the vertical gaps of
/// about 0.2 mm across the track, ten times less than the level of
/// potential contacts ([`CONTACT_LEVEL_M`]).
const NEAR_ROLL_RAD: f64 = 2.5e-4;

/// Most steps of the descent from a seed along the wheel profile, each
/// way.
const MAX_DESCENT_STEPS: usize = 400;

/// Longest step of the descent from a seed along the wheel profile, in
/// sample spacings (0.4 mm): a valley of the vertical gap narrower than
/// that may be stepped over to a lower point beyond its barrier.
const MAX_STRIDE_SAMPLES: f64 = 8.0;

/// Least fall of the vertical gap over one step of the descent for the
/// next step to be longer \[m\]. On the flat bottom of a tread contact the
/// gap falls by nanometres a sample spacing; strides there would land on
/// another of the ripples of a fitted profile (positions 0.06 mm apart on
/// MBench at the same force), so the descent is sample by sample.
const STRIDE_DROP_M: f64 = 1.0e-6;

impl<'a> Probe<'a> {
    fn new(table: &'a ContactTable, side: Side, pose: &SidePose) -> Self {
        let wheel = table.pair.wheel(side);
        Self {
            samples: wheel.samples(),
            dt: wheel_step_m(wheel.samples()),
            frame: LocusFrame::new(wheel, table.pair.wheelset().nominal_radius_m, pose),
            rail: &table.rails[side.index()],
            rail_samples: table.pair.rail(side).samples(),
        }
    }

    /// The contact evaluated at wheel arc length `t_m`; `None` off the
    /// profiles.
    fn at(&self, t_m: f64) -> Option<Evaluated> {
        let ws = self.samples;
        let f = t_m / self.dt;
        if !(f >= 0.0 && f <= (ws.len() - 1) as f64) {
            return None;
        }
        let k = (f as usize).min(ws.len() - 2);
        let w = f - k as f64;
        let (a, b) = (&ws[k], &ws[k + 1]);
        let mix = |u: f64, v: f64| u + w * (v - u);
        let tan = [
            mix(a.tangent[0], b.tangent[0]),
            mix(a.tangent[1], b.tangent[1]),
        ];
        let norm = tan[0].hypot(tan[1]);
        let locus = self.frame.point(&CurveSample {
            t_m,
            q_m: mix(a.q_m, b.q_m),
            z_m: mix(a.z_m, b.z_m),
            tangent: [tan[0] / norm, tan[1] / norm],
            curvature_per_m: mix(a.curvature_per_m, b.curvature_per_m),
        });
        let rail_z_m = self.rail.rail_z_at(locus.q_m);
        rail_z_m.is_finite().then_some(Evaluated {
            wheel_t_m: t_m,
            locus,
            rail_z_m,
            contact_angle_rad: 0.0,
            gap_m: rail_z_m - locus.z_m,
            b_per_m: 0.0,
            barrier_m: f64::INFINITY,
        })
    }

    /// From the seed `t_m`, downhill along the wheel profile to a local
    /// minimum of the vertical gap at sample resolution (a point whose
    /// neighbours one sample spacing away on either side are not lower),
    /// then to the vertex of the parabola through it and those neighbours.
    /// Downhill steps double from one sample spacing up to
    /// [`MAX_STRIDE_SAMPLES`] while the gap falls by more than
    /// [`STRIDE_DROP_M`] a step, and start again at one where a step would
    /// climb or the gap flattens: a seed far from its minimum (a contact
    /// of a neighbouring node that the actual position lacks) gets there
    /// in a few steps, and near a minimum, where the gap is flat, the
    /// descent goes sample by sample.
    fn descend(&self, t_m: f64) -> Option<Evaluated> {
        let g = |t: f64| self.at(t).map_or(f64::INFINITY, |e| e.gap_m);
        let (mut t, mut g0) = (t_m, g(t_m));
        if !g0.is_finite() {
            return None;
        }
        // The gaps one sample spacing above and below t, when known.
        let (mut above, mut below): (Option<f64>, Option<f64>) = (None, None);
        for dir in [1.0, -1.0] {
            let mut stride = 1.0;
            for _ in 0..MAX_DESCENT_STEPS {
                let known = if dir > 0.0 { above } else { below };
                let g1 = match known {
                    Some(v) if stride == 1.0 => v,
                    _ => g(t + dir * stride * self.dt),
                };
                if g1 >= g0 {
                    if stride == 1.0 {
                        if dir > 0.0 {
                            above = Some(g1);
                        } else {
                            below = Some(g1);
                        }
                        break;
                    }
                    stride = 1.0;
                    continue;
                }
                // The point left behind is a neighbour only after a unit
                // step.
                let behind = (stride == 1.0).then_some(g0);
                (above, below) = if dir > 0.0 {
                    (None, behind)
                } else {
                    (behind, None)
                };
                let drop = g0 - g1;
                (t, g0) = (t + dir * stride * self.dt, g1);
                stride = if drop > STRIDE_DROP_M {
                    (2.0 * stride).min(MAX_STRIDE_SAMPLES)
                } else {
                    1.0
                };
            }
        }
        let lo = below.unwrap_or_else(|| g(t - self.dt));
        let hi = above.unwrap_or_else(|| g(t + self.dt));
        let (f, _) = parabola_vertex(lo, g0, hi, 1.0);
        self.at(t + f * self.dt)
    }

    /// The contact angle at contact `e` from the rail's sample normals, as
    /// the direct path has it ([`rail_normal_at`]); off the rail samples,
    /// from the rail surface's slope (up to 0.006 rad off on a flange).
    fn contact_angle(&self, e: &Evaluated) -> f64 {
        if let Some((_, n)) = rail_normal_at(self.rail_samples, e.locus.q_m) {
            return n[0].atan2(n[1]);
        }
        let (rail, q) = (self.rail, e.locus.q_m);
        let h = 0.5 * rail.dq_m;
        let slope = (rail.rail_z_at(q + h) - rail.rail_z_at(q - h)) / (2.0 * h);
        // Normal into the rail: (-dz/dq, 1) normalised.
        if slope.is_finite() {
            (-slope).atan2(1.0)
        } else {
            0.0
        }
    }

    /// The lateral curvature B of the normal undeformed distance at contact
    /// `e` [1/m] (module documentation); 0 where the span leaves the
    /// profiles (Hertz then takes its floor on B).
    fn curvature(&self, e: &Evaluated) -> f64 {
        let h = (CURVATURE_SPAN_M / self.dt).round().max(1.0) * self.dt;
        let (Some(a), Some(b)) = (self.at(e.wheel_t_m - h), self.at(e.wheel_t_m + h)) else {
            return 0.0;
        };
        let (qa, q0, qb) = (a.locus.q_m, e.locus.q_m, b.locus.q_m);
        let d2 =
            2.0 * ((b.gap_m - e.gap_m) / (qb - q0) - (e.gap_m - a.gap_m) / (q0 - qa)) / (qb - qa);
        let b_per_m = 0.5 * d2 * e.contact_angle_rad.cos().powi(3);
        if b_per_m.is_finite() {
            b_per_m
        } else {
            0.0
        }
    }

    /// Largest vertical gap between contacts `a` and `b` (wheel samples in
    /// between) [m].
    fn barrier(&self, a: &Evaluated, b: &Evaluated) -> f64 {
        let (ta, tb) = (a.wheel_t_m.min(b.wheel_t_m), a.wheel_t_m.max(b.wheel_t_m));
        let n = ((tb - ta) / self.dt).ceil() as usize;
        (0..=n)
            .filter_map(|k| self.at((ta + k as f64 * self.dt).min(tb)))
            .map(|e| e.gap_m)
            .fold(a.gap_m.max(b.gap_m), f64::max)
    }
}

/// The potential contacts of one node from its vertical gap.
fn node_contacts(gap: &VerticalGap, locus: &[LocusPoint], wheel_dt_m: f64) -> Vec<NodeContact> {
    let n = gap.len();
    let g = |k: usize| gap.gap_m(k);
    let Some((_, gmin)) = gap.min() else {
        return Vec::new();
    };
    // Local minima (strict on the left so that a flat run counts once);
    // of two with too low a barrier between them, the deeper.
    let is_min = |k: usize| {
        g(k) < gmin + CONTACT_LEVEL_M
            && (k == 0 || g(k) < g(k - 1))
            && (k + 1 == n || g(k) <= g(k + 1))
    };
    let mut minima: Vec<usize> = Vec::new();
    // Largest gap since the last minimum kept.
    let mut ridge = f64::NEG_INFINITY;
    for k in 0..n {
        ridge = ridge.max(g(k));
        if !is_min(k) {
            continue;
        }
        match minima.last_mut() {
            Some(last) if ridge - g(*last).max(g(k)) < PROMINENCE_M => {
                if g(k) < g(*last) {
                    *last = k;
                    ridge = g(k);
                }
            }
            _ => {
                minima.push(k);
                ridge = g(k);
            }
        }
    }
    minima
        .iter()
        .map(|&k| {
            // Wheel arc length: along the locus segment below sample k.
            let li = gap.locus_index[k].min(locus.len() - 2);
            let (p, q) = (locus[li], locus[li + 1]);
            let f = ((gap.q_m(k) - p.q_m) / (q.q_m - p.q_m)).clamp(0.0, 1.0);
            NodeContact {
                wheel_t_m: (li as f64 + f) * wheel_dt_m,
            }
        })
        .collect()
}

/// Groups the contacts (increasing q) with a gap below `cap_m` into
/// patches: consecutive ones closer than `merge_m` along q, or with a
/// barrier below `level_m`, form one patch; its deepest contact stands for
/// it. Returns the indices of those.
fn group(contacts: &[Evaluated], cap_m: f64, level_m: f64, merge_m: f64) -> Vec<usize> {
    let mut out: Vec<usize> = Vec::new();
    let mut last: Option<usize> = None;
    // Largest barrier level since the last contact below the cap.
    let mut ridge = f64::NEG_INFINITY;
    for (i, c) in contacts.iter().enumerate() {
        if let Some(j) = i.checked_sub(1) {
            ridge = ridge.max(contacts[j].barrier_m);
        }
        if c.gap_m >= cap_m {
            continue;
        }
        let joined = last.is_some_and(|l| {
            ridge < level_m || (contacts[l].locus.q_m - c.locus.q_m).abs() < merge_m
        });
        match out.last_mut() {
            Some(rep) if joined => {
                if c.gap_m < contacts[*rep].gap_m {
                    *rep = i;
                }
            }
            _ => out.push(i),
        }
        last = Some(i);
        ridge = f64::NEG_INFINITY;
    }
    out
}

/// A first estimate of the vertical approach that carries `force` on the
/// deepest contact: Hertz on its curvatures.
fn approach_estimate(c: &Evaluated, input: &WheelRailInput, force: f64) -> f64 {
    let cos = c.contact_angle_rad.cos();
    let kx = c.locus.kx_per_m.max(0.1);
    hertz(
        0.5 * kx,
        c.b_per_m.max(0.05 * kx),
        input.material.effective_modulus_pa(),
        HertzLoad::NormalForce {
            normal_force_n: force / cos,
        },
    )
    .map(|h| h.approach_m / cos)
    .unwrap_or(1e-4)
}

/// The patch of contact `c` at the rigid position.
fn patch(
    rail: &PlacedRail,
    track: &TrackData,
    c: &Evaluated,
    pose: &SidePose,
    side: Side,
    input: &WheelRailInput,
    omega: f64,
) -> PatchWork {
    let (sin, cos) = c.contact_angle_rad.sin_cos();
    let geom = PatchGeometry {
        reference_m: [c.locus.q_m, c.rail_z_m],
        x_m: c.locus.x_m,
        normal: [sin, cos],
        contact_angle_rad: c.contact_angle_rad,
        min_vertical_gap_m: c.gap_m,
        rolling_radius_m: c.locus.radius_m,
        wheel_profile_y_m: c.locus.profile_y_m,
        // Hertz needs no lateral samples or grid.
        s_range_m: [0.0, 0.0],
        lateral: Vec::new(),
        rail_index: 0,
        locus_index: 0,
        wheel_drop_m: c.gap_m,
    };
    hertz_patch(
        (rail, track),
        geom,
        c.gap_m * cos,
        c.locus.kx_per_m,
        c.b_per_m,
        pose,
        side,
        input,
        omega,
    )
}

/// One wheel pressed onto its rail, its contacts evaluated at the rigid
/// position (the structure of the direct path's wheel solution); the load
/// iteration of a single patch starts at `start`, a normal force per
/// vertical load, which is returned for the next step.
#[allow(clippy::too_many_arguments)]
fn solve_wheel_tabulated(
    pair: &WheelRailPair,
    contacts: &[Evaluated],
    pose: &SidePose,
    side: Side,
    input: &WheelRailInput,
    omega: f64,
    cache: &KernelCache,
    timing: &mut Timing,
    start: Option<f64>,
) -> Result<(WheelResult, Option<f64>), WheelRailError> {
    let deepest = contacts
        .iter()
        .min_by(|a, b| a.gap_m.total_cmp(&b.gap_m))
        .expect("a side without contacts is solved directly");
    let gmin = deepest.gap_m;
    let mut cap = match input.load {
        WheelLoad::VerticalForce(f) => gmin + CAP_FACTOR * approach_estimate(deepest, input, f),
        // Not reaching the rail: nothing to solve (as the direct path).
        WheelLoad::Approach(d) if d <= gmin => {
            return Ok((finish(pair, side, gmin, d, 0, Vec::new(), &mut None), None))
        }
        // The gap below `d` interpenetrates (as the direct path).
        WheelLoad::Approach(d) => d,
        WheelLoad::CenterHeight(_) => unreachable!("resolved by solve_wheelset_tabulated"),
    };
    let mut fastsim = wheel_fastsim(side)?;
    let merge = input.settings.search.merge_distance_m;
    let mut reps = group(contacts, cap, cap, merge);
    let mut split = false;
    for _ in 0..5 {
        let tg = Instant::now();
        let mut patches: Vec<_> = reps
            .iter()
            .map(|&i| {
                patch(
                    pair.rail(side),
                    pair.track(),
                    &contacts[i],
                    pose,
                    side,
                    input,
                    omega,
                )
            })
            .collect();
        timing.geometry_s += tg.elapsed().as_secs_f64();
        let ts = Instant::now();
        let result = load_iteration(&mut patches, input, cap, &mut fastsim, cache, start).map_err(
            |(patch, source): (usize, ContactError)| WheelRailError::Contact {
                side: side.name(),
                patch,
                source,
            },
        )?;
        timing.solve_s += ts.elapsed().as_secs_f64();
        match result {
            LoadResult::Done { delta, iterations } => {
                let parts = group(contacts, cap, delta, merge);
                if !split && parts != reps {
                    split = true;
                    reps = parts;
                    continue;
                }
                let ratio = normal_per_vertical(&patches, input);
                return Ok((
                    finish(pair, side, gmin, delta, iterations, patches, &mut None),
                    ratio,
                ));
            }
            LoadResult::CapTooSmall => {
                cap = gmin + 2.0 * (cap - gmin);
                reps = group(contacts, cap, cap, merge);
                split = false;
            }
        }
    }
    Err(WheelRailError::LoadNotCarried {
        side: side.name(),
        max_approach_m: cap - gmin,
    })
}

/// Solves the wheel/rail contact of `input` on the table's pair with the
/// contact geometry from `table` (see the module documentation) for the
/// Hertz+FASTSIM model; other models, and positions outside the table, are
/// solved by [`solve_wheelset`](crate::wheelrail::solve_wheelset) with the direct search. The roll search
/// starts at the table's estimate ([`ContactTable::roll_estimate`]).
pub fn solve_wheelset_tabulated(
    table: &ContactTable,
    input: &WheelRailInput,
    cache: &KernelCache,
    scratch: &mut SearchScratch,
) -> Result<WheelRailSolution, WheelRailError> {
    solve_wheelset_tabulated_warm(table, input, cache, scratch, &mut WarmStart::default())
}

/// [`solve_wheelset_tabulated`] in a co-simulation: the roll search starts
/// at the previous step's roll and each wheel's load iteration at its
/// previous normal force per vertical load (`warm`, which the solve
/// updates; the same solves from the same warm start give the same bits).
/// Positions solved with the direct search use and update `warm` as
/// [`solve_wheelset_warm`] does.
pub fn solve_wheelset_tabulated_warm(
    table: &ContactTable,
    input: &WheelRailInput,
    cache: &KernelCache,
    scratch: &mut SearchScratch,
    warm: &mut WarmStart,
) -> Result<WheelRailSolution, WheelRailError> {
    validate(input)?;
    validate_on(table.pair(), input)?;
    if input.settings.model != WheelRailModel::HertzFastsim {
        return solve_wheelset_warm(&table.pair, input, cache, scratch, warm);
    }
    let t0 = Instant::now();
    let pair = &table.pair;
    let p = &input.position;
    let z0 = -pair.wheelset().nominal_radius_m;
    // The contacts of both sides at `roll`, from the look-up or from
    // those at a nearby roll.
    let at = |roll: f64, near: Option<&[Vec<Evaluated>; 2]>| -> Option<[Vec<Evaluated>; 2]> {
        let eval = |side: Side| {
            let pose = SidePose::new(side, p.lateral_m, z0, roll, p.yaw_rad);
            let near = near.map(|n| n[side.index()].as_slice());
            table.evaluate(side, p.lateral_m, roll, &pose, near)
        };
        Some([eval(Side::Left)?, eval(Side::Right)?])
    };
    let min_gap = |c: &[Evaluated]| c.iter().map(|e| e.gap_m).fold(f64::INFINITY, f64::min);
    // The roll search: its first roll's contacts come from the look-up,
    // the next ones' from the last roll's (the roll moves by less than
    // NEAR_ROLL_RAD); `last` holds the last roll evaluated and its
    // contacts, `first` the roll of the look-up.
    let mut last: Option<(f64, [Vec<Evaluated>; 2])> = None;
    let mut first: Option<f64> = None;
    let mut search = |r: f64| -> Result<f64, WheelRailError> {
        let near = match (&last, first) {
            (Some((_, c)), Some(r0)) if (r - r0).abs() <= NEAR_ROLL_RAD => Some(c),
            _ => {
                first = Some(r);
                None
            }
        };
        let c = at(r, near).ok_or_else(|| WheelRailError::invalid("table", "outside"))?;
        let d = min_gap(&c[0]) - min_gap(&c[1]);
        last = Some((r, c));
        Ok(d)
    };
    let mut roll_slope_m_per_rad = None;
    let roll = match p.roll_rad {
        Some(r) => search(r).ok().map(|_| r),
        None => {
            let start = match warm.roll_rad {
                Some(_) => warm.roll_start(),
                None => RollStart {
                    roll_rad: table.roll_estimate(p.lateral_m).unwrap_or(0.0),
                    ..RollStart::default()
                },
            };
            find_roll(
                |r, _| Ok((search(r)?, true)),
                pair.track().rail_spacing_m(),
                SearchSettings::default().roll_tolerance_m,
                p.lateral_m,
                start,
            )
            .ok()
            .map(|found| {
                roll_slope_m_per_rad = Some(found.slope_m_per_rad);
                found.roll_rad
            })
        }
    };
    let contacts = roll.and_then(|r| match last.take() {
        Some((lr, c)) if lr == r => Some(c),
        _ => at(r, None),
    });
    let (Some(roll), Some(mut contacts)) = (roll, contacts) else {
        return solve_wheelset_warm(pair, input, cache, scratch, warm);
    };
    // Translating the wheelset in z shifts every vertical gap equally.
    let dz = min_gap(&contacts[0]).min(min_gap(&contacts[1]));
    let center_z_m = z0 + dz;
    for side in Side::BOTH {
        let pose = SidePose::new(side, p.lateral_m, z0, roll, p.yaw_rad);
        let probe = Probe::new(table, side, &pose);
        let c = &mut contacts[side.index()];
        for i in 0..c.len() {
            if i + 1 < c.len() {
                c[i].barrier_m = probe.barrier(&c[i], &c[i + 1]) - dz;
            }
            c[i].contact_angle_rad = probe.contact_angle(&c[i]);
            c[i].b_per_m = probe.curvature(&c[i]);
            c[i].gap_m -= dz;
            c[i].locus.z_m += dz;
        }
    }
    let search_s = t0.elapsed().as_secs_f64();
    let mut timing = Timing {
        search_s,
        ..Timing::default()
    };
    let resolved = input.with_load_resolved(center_z_m);
    let input = &*resolved;
    // Each solve of the wheels starts from the last one's, the first from
    // the warm start's last three steps ([`extrapolated_start`]).
    let mut start = warm.first_ratios();
    let mut normal_per_vertical = warm.normal_per_vertical;
    let (omega, wheels, pitch_control) = solve_pitch(pair, input, |omega| {
        let mut wheels = Vec::with_capacity(input.sides.len());
        for &side in &input.sides {
            let pose = SidePose::new(side, p.lateral_m, center_z_m, roll, p.yaw_rad);
            let i = side.index();
            let (wheel, ratio) = solve_wheel_tabulated(
                pair,
                &contacts[i],
                &pose,
                side,
                input,
                omega,
                cache,
                &mut timing,
                start[i],
            )?;
            normal_per_vertical[i] = ratio;
            start[i] = ratio;
            wheels.push(wheel);
        }
        Ok(wheels)
    })?;
    warm.advance(
        roll,
        roll_slope_m_per_rad,
        None,
        normal_per_vertical,
        [None, None],
    );
    Ok(WheelRailSolution {
        center_z_m,
        roll_rad: roll,
        pitch_rad_per_s: omega,
        pitch_control,
        wheels,
        timing,
    })
}
