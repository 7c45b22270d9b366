//! Module 1: wheel/rail contact of one wheel on its rail or roller
//! (CONTACT's C1 digit: 0 left rail, 1 right rail, 4 left roller, 5 right
//! roller), from profiles, track and wheelset data, the
//! wheelset's position and velocity, and a vertical force or position; the
//! contact search finds the patches, each solved as a module 3 problem.
//!
//! # How CONTACT's problem maps to the solver's
//!
//! CONTACT solves one half wheelset on one half track; internally a left
//! side is solved as its mirror image, a right side (the "side frame" of
//! [`railcontact_solver::wheelrail::wheelset`] is exactly that mirrored
//! frame). Here the solver's wheelset carries the same rail and wheel
//! profile on both sides and solves only the side of C1
//! (`sides: vec![side]`), with the exact model (Kalker's theory on the
//! planar patch) on square elements of size DX.
//!
//! * Variable rails: a rail slices file (`.slcs`, CONTACT's switches and
//!   crossings; the solver's `wheelrail::slices`, NFEAT <= 1 and
//!   U_INTPOL = 1): the pair's rail is the slices' profile at the
//!   wheelset's position S (placed again when S moves), and each element
//!   of a patch adds the rail's change of height between S and its own
//!   S + x (the solver's `WheelRailInput::rail_slices`). The tangent plane
//!   and contact angle of a patch are those of the slice at S (CONTACT
//!   takes them at the weighted centre of the interpenetration over x and
//!   y: docs/cntc.md, "Variable rails"). The slice profiles are read with
//!   the call (`Call::SetProfileFile`'s `slice_files`). Features, the
//!   approximating spline, perturbations and smoothing are refused.
//! * Out-of-round wheels: a wheel slices file (`.slcw`, the solver's
//!   `wheelrail::slices::WheelSlices`, NFEAT <= 1, TH_INTPOL = 1 or 2,
//!   CONTACT's approximating spline): each slice read, scaled and smoothed
//!   (SMOOTH, ISMOOTH) as a single wheel profile, as CONTACT smooths each
//!   slice; the pair's wheel is the profile the wheel shows the rail at
//!   the pitch PITCH (`cntc_setwheelsetposition`'s sixth value; placed
//!   again when the pitch changes): per interpolation path the lowest
//!   point of the wheel within +-0.2 rad of theta = -PITCH, as CONTACT
//!   searches the wheel's surface over +-0.2 rad (the solver's
//!   `WheelSlices::profile_facing_rail`); each element of a patch then
//!   adds the change of radius between that profile and the wheel's
//!   cross-section at its own angle -PITCH + asin(x / r), and the grid
//!   reaches along x wherever the true wheel comes near the rail (the
//!   solver's `WheelRailPair::with_wheel_slices`). The contact search and
//!   the tangent plane of a patch are those of the profile facing the
//!   rail, at x = 0.
//!   The slice profiles are read with the call, as a rail slices file's.
//!   Features and perturbations are refused.
//! * Profiles: CONTACT's canonical (right-hand) profiles, in metres here.
//!   CONTACT multiplies the numbers read by the scale factor `rparam(1)`
//!   to get millimetres; its default is the unit convention's (1 for
//!   CONTACT's units, 1000 for SI and SIMPACK's). Simpack files are first
//!   taken to millimetres by their own `units.len.f`, MiniProf and plain
//!   files are numbers in millimetres, so a profile lies at
//!   `reader's metres x scale factor`.
//! * Track (Z digit): the gauge point placement (gauge height > 0), gauge
//!   and cant; or the absolute placement (gauge height <= 0), the rail
//!   profile's origin at (RAILY0, RAILZ0) of the track (RAILY0 a track y,
//!   positive for a right rail), rotated by the cant about it and not
//!   shifted to touch the track plane (the solver's `RailPlacement::Origin`, at
//!   q = sign(side) RAILY0 of the side frame). The track curvature CURV (params(6)) is the solver's
//!   `TrackData::curvature_per_m`: the rails turn at -V CURV under the
//!   wheelset (V the forward speed, on a roller the roller's surface speed
//!   at the contact), as CONTACT's `wr_creep_cref`, so the yaw rate VYAW
//!   is relative to the turning track frame.
//! * Roller rigs (C1 = 4, 5): the rail profile lies on a roller of radius
//!   NOMRAD (params(5)) about an axle along y at that distance below the
//!   track plane (the solver's `TrackData::roller_radius_m`), its z an
//!   offset to the radius; the gauge point placement shifts it laterally
//!   only; CANT is ignored (0), as CONTACT does; rail deviations turn and
//!   shift the roller's profile with its axle. The first value of
//!   `cntc_setwheelsetvelocity` is then the rollers' angular velocity
//!   VPITCH_ROL (rad/s, > 0 for forward rolling, < 0 backwards; the solver's
//!   `RailMotion::roller_rad_per_s`) and the wheelset's forward speed is
//!   0, as CONTACT decides when the velocity is set. The roller's surface
//!   curves along x with radius NOMRAD - z at each lateral point, which
//!   the patch gap adds to the wheel's curvature; with yaw the contact
//!   point lies where that gap's minimum along x does (between the wheel's
//!   closest point to a prismatic rail and the roller's top), on the
//!   roller's surface, as CONTACT's. The creepages are relative to
//!   CONTACT's reference speed there, the mean of the two surfaces'
//!   speeds. The first position value is X_WS, which must be 0
//!   (the wheelset over the rollers' top). With F = 1 (FX_WS given) the
//!   wheelset's pitch rate is found relative to the roller's surface
//!   speed. Refused on a roller rig: VPITCH_ROL = 0, X_WS != 0.
//! * Rail deviations (Z = 2, 3): DYRAIL, DZRAIL (track y, z: DYRAIL > 0
//!   towards the track centre for a left rail) and DROLLR turn and shift
//!   the placed rail about its profile's origin (the solver's
//!   `RailDeviation`; the gauge point is found on the rail inclined by the
//!   cant alone, as CONTACT's `wr_set_rail_marker` does). VYRAIL, VZRAIL,
//!   VROLLR move the rail: the solver's `RailMotion`, whose velocity at
//!   the rail's point of each patch (CONTACT's) it takes off the wheel's.
//! * Massless rail (F = 3; Z = 32, 33 set KYRAIL, FYRAIL, KZRAIL, FZRAIL
//!   in force/length and N, DYSTEP0, default 1 mm): the rail deflections
//!   DY_DEFL, DZ_DEFL (track y, z) at which the wheel's force on the rail
//!   balances the springs and the forces prescribed (the solver's
//!   `wheelrail::massless_rail`), added to the deviations DYRAIL, DZRAIL
//!   (the pair's rail is placed with them). Iterated on the rail without
//!   them, from none, or from the last ones with I = 1; with N = 1,
//!   DZ_DEFL = (FZ + FZRAIL) / KZRAIL (0 when KZRAIL = 0) and the
//!   wheelset's height is found at FZ over the deflected rail, as CONTACT
//!   does; N = 0 needs KZRAIL > 0 and keeps Z_WS as given (CONTACT's
//!   iteration moves it a little: docs/cntc.md). Any other F resets the
//!   deflections to zero, as CONTACT does.
//! * FBPOS only places the wheel profile (its y = 0 at FBDIST/2 - FBPOS
//!   from the wheelset centre) and may lie outside the profile, as in
//!   CONTACT; the solver is given the same placement from the profile's
//!   smallest y.
//! * Wheelset (E digit): flange-back distance and position, nominal
//!   radius and the optional tape circle; position s, y, z, roll, yaw,
//!   pitch (a round wheel does not depend on it; an out-of-round wheel
//!   does, above); velocity.
//! * Flexible wheelset deviations (E = 4, 5): the wheel profile's marker
//!   displaced by DXWHL, DYWHL, DZWHL and the wheel turned about it by
//!   DROLLW, DYAWW in wheelset coordinates, as CONTACT's
//!   `wr_set_wheel_marker` places it; DPITCHW turns a round wheel onto
//!   itself. A wheel is a body of revolution: the solver takes the
//!   deflected wheel as a wheelset pose, its axis where the wheel's is
//!   (`FlexedWheel`), and its rigid motion as CONTACT's wheel point velocity:
//!   the wheelset's motion (pitch about the wheelset's axle) plus the
//!   deviations' rates VXWHL .. VPITCHW about the marker. So DYAWW gives no
//!   lateral creepage and DROLLW no spin by themselves (CONTACT's
//!   test-rollers2.inp cases 1b, 1e). The creepages are relative to the
//!   rolling speed of the deflected wheel about its own axle, CONTACT's to
//!   that about the wheelset's: 0.15 % apart with DROLLW = 0.02 rad on a
//!   100 mm wheel. With F = 1 (FX_WS given) the wheelset's pitch rate is
//!   found as without deviations. The solver's
//!   limit of 0.2 rad on a wheel's roll and yaw holds for the deflected
//!   wheel (test-rollers2 case 1b, DYAWW = -0.3 rad, is refused by it).
//! * Load: N = 1 the vertical force FZ (`cntc_setverticalforce`), N = 0 the
//!   wheelset height z_ws (zero at the nominal position, z_tr = -r_nom).
//! * Discretisation (`cntc_setpotcontact`, icp = -1): DX = DS (square
//!   elements), D_SEP the distance below which two regions of contact are
//!   one patch, D_COMB the distance below which they are one region: two
//!   regions between D_COMB and D_SEP apart are CONTACT's blended patch,
//!   sub-patches of one grid whose pressures act on each other reduced by
//!   ((D_SEP - d)/(D_SEP - D_COMB))^0.8 in the normal problem
//!   (`SearchSettings::combine_distance_m`); neighbouring patches
//!   between D_SEP and D_TURN apart (default 2 D_SEP - D_COMB) whose
//!   contact angles differ by at most A_SEP turn their angles towards each
//!   other as CONTACT's do (`SearchSettings::angle_turning`); G_MISS is
//!   stored without effect.
//! * Friction: L = 0 and the falling laws L = 2-5 (exact model), V = 0,
//!   and V = 1 (by contact angle, CONTACT's angles of the right-hand side,
//!   negative at the gauge face) as the solver's friction table.
//! * Steady rolling (T = 3), or the normal problem only (T = 0: the
//!   solver's `ExactTangential::Frictionless`; zero tractions, creep
//!   forces and creepages, the contact area all adhesion, as CONTACT
//!   reports them).
//! * Transient contact (T = 1 shifts, T = 2 transient rolling; the
//!   solver's `ExactTangential::Transient`): each calculation is one time
//!   step, the element keeping the patches' tractions as the next step's
//!   history (`TransientHistory`: P = 0 continues, P = 1 keeps the
//!   pressures only, P = 2 starts from rest, P = 3 repeats the last step;
//!   after a steady calculation, T = 3 or 0, its patches' tractions are
//!   that history, CONTACT's transient start from steady rolling). The grid lies
//!   on CONTACT's super-grid (fixed to the track with T = 1, moving with
//!   the wheelset with T = 2, along the rail profile's arc length from its
//!   origin laterally); the history moves onto it by whole elements. With
//!   T = 1 the velocities are the step's displacements and the creepages
//!   the patch's rigid shift (length, rad; `Outcome::is_shift`); T = 2
//!   rolls DQREL elements a step, a whole number (`rolled_elements`;
//!   larger steps with CONTACT's leading-edge correction, as CONTACT's
//!   module 1 rolls them). MZ is taken about
//!   the super-grid's origin, as CONTACT's. F = 0, M = 0 and L = 0 only
//!   (V = 1 taken). Agreement with CONTACT's reference outputs:
//!   docs/cntc.md.
//! * Materials: M = 0 (Kalker's exact theory on each patch) or M = 3, 2
//!   (CONTACT's modified FASTSIM on each patch, the solver's
//!   `ExactTangential::Fastsim`): the normal problem of each patch exact
//!   as with M = 0, then FASTSIM on the patch's own grid with that
//!   pressure as its traction bound (B = 0, the only bound allowed here;
//!   CONTACT's user guide: B = 2-4 are not available in module 1), Kalker's
//!   three flexibilities of the equivalent ellipse of the loaded elements
//!   (Kik and Piotrowski's, CONTACT's `equiv_ellipse`: CONTACT's module 1
//!   patches are non-Hertzian, IPOTCN = 1), blended (M = 2: the one given
//!   flexibility FLX instead), with the slope reduction k0, alpha_inf,
//!   beta and the friction law at the global slip velocity, as module 3
//!   runs it on a non-Hertzian grid. As in CONTACT's
//!   `panprc`, FASTSIM's tractions do not act back on the pressure; the
//!   load iteration meets FZ with FASTSIM's creep forces included (CONTACT
//!   iterates on the total force in the track frame). M = 5: CONTACT's
//!   modified FaStrip the same way (the solver's `ExactTangential::Fastrip`:
//!   FASTSIM bounded by the static coefficient, then strip theory per grid
//!   row, CONTACT's `modif_fastrip`). V = 1 (friction by contact angle) is
//!   refused with M = 2, 3, 5.
//!
//! # Outcomes
//!
//! Each patch becomes an [`Outcome`] in CONTACT's reporting frame: for a
//! left wheel the grid is mirrored (rows reversed, y negated), and the
//! lateral traction and slip, lateral force, lateral and spin creepage and
//! the spin moment change sign, as CONTACT's getters do. The contact
//! reference point is CONTACT's: the weighted centre of the
//! interpenetration with its mean contact angle, and CONTACT's point for
//! the creepages (the solver's `ReferencePoint::InterpenetrationCentre`).
//! `location` holds every
//! value of `cntc_getcontactlocation`, the rail deflections (18, 19) those
//! of the wheel (zero unless F = 3).

use std::collections::BTreeMap;
use std::sync::Arc;
use std::time::Instant;

use railcontact_solver::core::cache::KernelCache;
use railcontact_solver::core::error::Range;
use railcontact_solver::core::grid::Grid;
use railcontact_solver::core::layer::LayerFields;
use railcontact_solver::core::problem::{Friction, SolverSettings};
use railcontact_solver::core::root::{decreasing_root, RootEnd, RootError, RootSettings};
use railcontact_solver::core::solution::{ElementFields, ElementState};
use railcontact_solver::wheelrail::search::{AngleTurning, ReferencePoint, SearchSettings};
use railcontact_solver::wheelrail::slices::{
    parse_slices_file_along, parse_slices_within, parse_wheel_slices_within, SliceAxis,
    SlicesLimits,
};
use railcontact_solver::wheelrail::{
    is_slices_file, is_wheel_slices_file, nominal_rolling_speed, parse_profile,
    pitch_force_tolerance, solve_on_massless_rail, solve_wheelset_warm, viscoelastic_bodies,
    wheelrail_solver_settings, ExactTangential, FrictionAxis, FrictionTable, LengthUnit,
    LoadOptions, MasslessRail, MasslessRailError, MirrorZ, PairCache, PatchResult, PatchTractions,
    Profile, ProfileChecks, ProfileError, ProfileKind, ProfileSpline, RailDeflection,
    RailDeviation, RailMotion, RailPlacement, RailSlices, SearchScratch, Side, SourceLocation,
    SplineOptions, TrackData, TransientContact, WarmStart, WheelLoad, WheelRailError,
    WheelRailInput, WheelRailModel, WheelRailPair, WheelRailSettings, WheelRailSolution,
    WheelSlices, WheelsetData, WheelsetPosition, WheelsetVelocity, MASSLESS_RAIL_PLACED_TOLERANCE,
    MAX_TRACK_CURVATURE_PER_M,
};

use crate::config::{Config, FrictionLaw, MaterialModel};
use crate::element::MAX_ICP;
use crate::error::{CntcError, Result};
use crate::flags;
use crate::outcome::{DisplacementSource, Location, Outcome};
use crate::subsurface::Blocks;
use crate::units::Units;

/// Millimetres per metre: CONTACT's profile values and their smoothing
/// parameters are in millimetres whatever the unit convention.
const MM: f64 = 1e-3;

/// NOMRADR of the track dimensions set \[m\] (0 when not set: refused by
/// the roller's checks or by the missing track).
fn track_roller_radius(track: &Slot<Track>) -> f64 {
    match track {
        Some(Ok(t)) => t.roller_radius_m,
        _ => 0.0,
    }
}

/// A profile as given (canonical right-hand form, SI), with its smoothing.
#[derive(Debug, Clone)]
struct ProfileInput {
    /// The checked points (metres, CONTACT order); of a variable rail, its
    /// first slice.
    profile: Profile,
    /// Cut-off wavelength of its smoothing spline \[m\] (0: interpolating).
    smoothing_m: f64,
    /// A rail varying along the track (a `.slcs` file): the pair's rail
    /// is its profile at the wheelset's position s.
    slices: Option<Arc<RailSlices>>,
    /// An out-of-round wheel (a `.slcw` file): the pair's wheel is its
    /// profile at theta = -PITCH, `profile` its profile at theta = 0.
    wheel_slices: Option<Arc<WheelSlices>>,
}

impl ProfileInput {
    fn spline(&self) -> Result<ProfileSpline> {
        self.profile
            .spline(&SplineOptions::smoothing(self.smoothing_m))
            .map_err(|e| {
                CntcError::Profile(format!(
                    "profile \"{}\" cannot be fitted: {e}",
                    self.profile.name()
                ))
            })
    }
}

/// A setting that may be missing or may have failed: a failure is kept and
/// refused by every calculation until a good value replaces it (as
/// CONTACT's profile error code).
type Slot<T> = Option<std::result::Result<T, CntcError>>;

/// Reads a slot for the calculation.
fn slot<'a, T>(s: &'a Slot<T>, missing: &str) -> Result<&'a T> {
    match s {
        None => Err(CntcError::Input(missing.to_string())),
        Some(Err(e)) => Err(e.clone()),
        Some(Ok(v)) => Ok(v),
    }
}

/// Track dimensions (Z = 1, 3), SI.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Track {
    placement: Placement,
    cant_rad: f64,
    /// NOMRADR \[m\] (params(5)): the rollers' nominal radius, used
    /// on a roller rig (C1 = 4, 5).
    roller_radius_m: f64,
    /// CURV \[1/m\] (params(6)): the signed track curvature.
    curvature_per_m: f64,
}

/// The rail placement of `cntc_settrackdimensions`, SI.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Placement {
    /// GAUGHT > 0: GAUGHT and GAUGWD.
    GaugePoint { gauge_height_m: f64, gauge_m: f64 },
    /// GAUGHT <= 0: RAILY0 (track y, not mirrored) and RAILZ0.
    Absolute { rail_y_m: f64, rail_z_m: f64 },
}

impl Track {
    /// The solver's track for the rail of `side`: RAILY0 in the side frame;
    /// on a roller (`roller`) of radius NOMRADR, without cant (CONTACT
    /// ignores CANT there).
    fn for_side(&self, side: Side, deviation: &[f64; 6], roller: bool) -> TrackData {
        let placement = match self.placement {
            Placement::GaugePoint {
                gauge_height_m,
                gauge_m,
            } => RailPlacement::GaugePoint {
                gauge_m,
                gauge_height_m,
            },
            Placement::Absolute { rail_y_m, rail_z_m } => RailPlacement::Origin {
                q_m: side.sign() * rail_y_m,
                z_m: rail_z_m,
            },
        };
        let mut deviations = [RailDeviation::default(); 2];
        deviations[side.index()] = RailDeviation {
            dy_m: deviation[0],
            dz_m: deviation[1],
            droll_rad: deviation[2],
        };
        TrackData {
            placement,
            cant_rad: if roller { 0.0 } else { self.cant_rad },
            deviations,
            roller_radius_m: roller.then_some(self.roller_radius_m),
            curvature_per_m: self.curvature_per_m,
        }
    }
}

/// Wheelset dimensions (E = 3, 5), SI.
#[derive(Debug, Clone, Copy, PartialEq)]
struct WheelsetDims {
    flange_back_distance_m: f64,
    flange_back_y_m: f64,
    nominal_radius_m: f64,
    /// Y_TAPE \[m\], when the tape circle computation is on.
    tape_y_m: Option<f64>,
}

/// Discretisation (`cntc_setpotcontact` with icp = -1), SI.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Discretisation {
    dx_m: f64,
    ds_m: f64,
    /// A_SEP \[rad\]: neighbouring patches whose contact angles differ
    /// by more do not turn them (D_TURN).
    angle_sep_rad: f64,
    /// D_SEP \[m\].
    dist_sep_m: f64,
    /// D_COMB \[m\].
    dist_comb_m: f64,
    /// D_TURN \[m\]: neighbouring patches between D_SEP and D_TURN apart
    /// turn their contact angles towards each other.
    dist_turn_m: f64,
}

/// What a calculation leaves besides the outcomes: the frames of the
/// solved wheel (side frame: x, q, z; q = y on the right, -y on the left)
/// and each patch's forces and moments for `cntc_getglobalforces`.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct Solved {
    side: Side,
    /// Wheelset axes in the side frame: forward, axle (outwards), down.
    ws_axes: [[f64; 3]; 3],
    /// The wheel's turn from the wheelset's axes, DROLLW and DYAWW
    /// \[rad\] (track frame).
    wheel_turn_rad: [f64; 2],
    /// Rail roll in the side frame \[rad\] (-cant).
    rail_roll_rad: f64,
    /// The loaded wheelset height z_ws (zero at the nominal position) \[m\].
    z_ws_m: f64,
    /// The pitch rate VPITCH found for a prescribed FX_WS (F = 1) \[rad/s\].
    vpitch_found: Option<f64>,
    /// Per patch (side frame): force on the rail, its moment about the rail
    /// profile marker, about the wheel profile marker.
    globals: Vec<[[f64; 3]; 3]>,
}

/// A module 1 result element.
#[derive(Default)]
pub struct WheelRail {
    /// Bounds on the slices files it reads (rail and wheel): none in
    /// process; a server's ([`WheelRail::set_slices_limits`]) on the files
    /// a forwarding library sends it.
    slices_limits: SlicesLimits,
    /// Units, digits, materials, friction, solver parameters (for all its
    /// patches).
    pub config: Config,
    /// The patches of the last calculation (icp = 1..=npatch).
    pub outcomes: Vec<Outcome>,
    /// Cases calculated.
    pub ncase: usize,
    /// Wall time of the calculations since the last reset \[s\].
    pub time_s: f64,
    rail: Slot<ProfileInput>,
    wheel: Slot<ProfileInput>,
    track: Slot<Track>,
    /// Rail deviations (Z = 2, 3), SI: DYRAIL, DZRAIL \[m\], DROLLR
    /// \[rad\], VYRAIL, VZRAIL \[m/s\], VROLLR \[rad/s\] (track frame).
    rail_deviation: [f64; 6],
    /// The massless rail (Z = 32, 33; used with F = 3), SI.
    massless_rail: Option<MasslessRail>,
    /// The rail's deflection found by the last calculation with F = 3
    /// (zero otherwise): the pair's rail is placed with it on top of the
    /// deviations.
    rail_deflection: RailDeflection,
    wheelset: Slot<WheelsetDims>,
    /// s, y, z \[m\], roll, yaw, pitch \[rad\].
    position: [f64; 6],
    /// vs, vy, vz \[m/s\], vroll, vyaw, vpitch \[rad/s\].
    velocity: [f64; 6],
    /// VPITCH_ROL \[rad/s\]: the rollers' angular velocity (C1 = 4, 5).
    roller_rad_per_s: f64,
    /// Flexible wheelset deviations (E = 4, 5), SI: DXWHL, DYWHL, DZWHL
    /// \[m\], DROLLW, DYAWW, DPITCHW \[rad\], VXWHL, VYWHL, VZWHL \[m/s\],
    /// VROLLW, VYAWW, VPITCHW \[rad/s\]; zeros without them.
    flexibility: [f64; 12],
    /// FZ \[N\] (N = 1).
    vertical_force_n: Option<f64>,
    /// FX_WS \[N\] (F = 1): the total force on the rail along the
    /// wheelset's longitudinal axis.
    longitudinal_force_n: Option<f64>,
    discretisation: Option<Discretisation>,
    /// DQREL: transient rolling (T = 2) rolls this many elements a step
    /// (a whole number); steady rolling takes 1.
    dqrel: f64,
    /// The placed profiles, found at the first calculation after a change:
    /// shared with every element of the process that placed the same
    /// profiles on the same track and wheelset ([`PairCache`]).
    pair: Option<Arc<WheelRailPair>>,
    /// The pair before the last change, held until the next one is found,
    /// so that inputs set again to equal values find it in the cache.
    pair_before: Option<Arc<WheelRailPair>>,
    /// The wheelset position s \[m\] the pair was built at (a variable
    /// rail's pair is its profile there).
    pair_track_s_m: Option<f64>,
    /// The pitch angle whose wheel profile an out-of-round wheel's pair
    /// holds \[rad\].
    pair_pitch_rad: Option<f64>,
    scratch: SearchScratch,
    solved: Option<Solved>,
    /// Subsurface blocks for every patch without its own (icp = -1).
    subs_all: Blocks,
    /// Subsurface blocks of one patch (icp >= 1).
    subs_patch: BTreeMap<i32, Blocks>,
    /// The blocks computed below each patch of the last calculation.
    subs_done: Vec<Option<Blocks>>,
    /// The most elements a patch's grid may have (a server's limit;
    /// `None`: the solver's).
    max_grid_elements: Option<usize>,
    /// Transient contact (T = 1, 2): the tractions of the last time steps.
    transient: TransientHistory,
}

/// The history of transient contact (T = 1, 2) of a module 1 element: the
/// tractions of its patch after the last calculation and before it, on
/// their grids (the solver's [`WarmStart::tractions`]). A steady-rolling
/// calculation (T = 3, or T = 0's pressures) leaves its tractions too: a
/// transient step after it starts from that steady state (CONTACT's
/// transient start from steady rolling).
#[derive(Default)]
struct TransientHistory {
    /// After the last calculation (None: no contact, or none yet).
    last: Option<PatchTractions>,
    /// What the last calculation started from.
    before: Option<PatchTractions>,
    /// The wheelset's track position S \[m\] of the last calculation when
    /// it was not transient: its tractions lie on the lattice moving with
    /// the wheelset (as transient rolling's), which a transient shift
    /// (T = 1, whose lattice is fixed to the track) sees moved by S.
    steady_at_s_m: Option<f64>,
}

impl TransientHistory {
    /// The tractions a calculation with CONTACT's P digit `pvtime` and T
    /// digit `tang` starts from: P = 0 the last step's, P = 1 its
    /// pressures only (the tangential tractions zero), P = 2 none (a new
    /// sequence), P = 3 those the last calculation started from (a new
    /// iteration of it).
    fn history(&self, pvtime: i32, tang: i32) -> Option<PatchTractions> {
        let mut t = match pvtime {
            0 => self.last.clone(),
            1 => self.last.clone().map(|mut t| {
                t.traction_pa.iter_mut().for_each(|v| v.fill(0.0));
                t
            }),
            3 => self.before.clone(),
            _ => None,
        }?;
        if let (Some(s), 1, 0 | 1) = (self.steady_at_s_m, tang, pvtime) {
            t.lattice_origin_m[0] += s;
        }
        Some(t)
    }

    /// After a transient calculation that started from `start` and left
    /// `tractions`: they are the last step's, `start` what a following
    /// P = 3 (another iteration of the same step) starts from.
    fn advance(&mut self, start: Option<PatchTractions>, tractions: Option<PatchTractions>) {
        self.last = tractions;
        self.before = start;
        self.steady_at_s_m = None;
    }

    /// After a calculation that was not transient, at the wheelset's track
    /// position `s_m`, that left `tractions` (None: none to start from).
    fn steady(&mut self, tractions: Option<PatchTractions>, s_m: f64) {
        self.last = tractions;
        self.before = None;
        self.steady_at_s_m = Some(s_m);
    }
}

/// The rolling step of transient rolling (T = 2) in elements: DQREL, a
/// whole number of elements (within 1e-6; CONTACT's grid moves on its
/// super-grid, so the history moves by whole elements), at least 1.
/// Steps of several elements take CONTACT's leading-edge correction
/// (`railcontact_solver::core::leading_edge`). A fraction of an element
/// is refused (-40).
fn rolled_elements(dqrel: f64) -> Result<usize> {
    let whole = dqrel.round();
    if !(whole >= 1.0 && (dqrel - whole).abs() <= 1e-6 * whole) {
        return Err(CntcError::NotSupported(format!(
            "DQREL = {dqrel} (cntc_setrollingstepsize) with T = 2 in module 1 is not supported: \
             the patch rolls a whole number of elements a step (DQREL = 1, 2, ...)"
        )));
    }
    Ok(whole as usize)
}

// ---------------------------------------------------------------------
// Small vector helpers (side frame: x, q, z).

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn scale(k: f64, a: [f64; 3]) -> [f64; 3] {
    [k * a[0], k * a[1], k * a[2]]
}

/// Components of `v` along the axes `e` (rows).
fn in_basis(v: [f64; 3], e: &[[f64; 3]; 3]) -> [f64; 3] {
    [dot(v, e[0]), dot(v, e[1]), dot(v, e[2])]
}

/// The vector with components `v` along the axes `e` (rows).
fn of_basis(v: [f64; 3], e: &[[f64; 3]; 3]) -> [f64; 3] {
    add(scale(v[0], e[0]), add(scale(v[1], e[1]), scale(v[2], e[2])))
}

/// The axes `e` (rows) turned by the rotation whose columns, in `e`'s
/// coordinates, are the rows of `r`: R_e R.
fn turned(e: &[[f64; 3]; 3], r: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    [of_basis(r[0], e), of_basis(r[1], e), of_basis(r[2], e)]
}

/// `iparam(k)` (1-based as CONTACT numbers them), or `default`.
fn ip(p: &[i32], k: usize, default: i32) -> i32 {
    p.get(k - 1).copied().unwrap_or(default)
}

/// `rparam(k)` (1-based), or `default`.
fn rp(p: &[f64], k: usize, default: f64) -> f64 {
    p.get(k - 1).copied().unwrap_or(default)
}

/// Checks that every value is finite, naming the call and parameter list.
fn finite(call: &str, names: &[&str], p: &[f64]) -> Result<()> {
    for (i, v) in p.iter().enumerate() {
        if !v.is_finite() {
            let name = names.get(i).copied().unwrap_or("params");
            return Err(CntcError::Input(format!(
                "{call}: {name} (params({})) = {v} is not a finite number",
                i + 1
            )));
        }
    }
    Ok(())
}

/// The arc length \[m\] of the spline where CONTACT's profile coordinate s
/// is zero: at y = 0 when y runs monotonically along the profile, else at
/// the point nearest to the profile origin (CONTACT's rule).
fn arc_origin(spline: &ProfileSpline, origin_z_m: f64) -> f64 {
    let knots = spline.knot_arc_lengths_m();
    let ys: Vec<f64> = knots.iter().map(|t| spline.position(*t)[0]).collect();
    let increasing = ys.windows(2).all(|w| w[1] > w[0]);
    let decreasing = ys.windows(2).all(|w| w[1] < w[0]);
    if increasing || decreasing {
        if let Some(t) = spline.t_at_y(0.0) {
            return t;
        }
    }
    knots
        .iter()
        .map(|t| {
            let p = spline.position(*t);
            (*t, p[0] * p[0] + (p[1] - origin_z_m).powi(2))
        })
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map_or(0.0, |(t, _)| t)
}

/// Whether z of a profile of `kind` points up (CONTACT's z points down):
/// a rail's highest point (smallest z) and a wheel's flange tip (largest
/// z) lie inside the profile, its ends are low on a rail and high on a
/// wheel. Used for `cntc_setprofileinputvalues` with MIRROR_Z = 0.
fn z_points_up(kind: ProfileKind, pts: &[[f64; 2]]) -> bool {
    let n = pts.len();
    if n < 5 {
        return false;
    }
    let outer = (n / 10).max(1);
    let interior = |i: usize| i >= outer && i + outer < n;
    let (mut imin, mut imax) = (0, 0);
    for (i, p) in pts.iter().enumerate() {
        if p[1] < pts[imin][1] {
            imin = i;
        }
        if p[1] > pts[imax][1] {
            imax = i;
        }
    }
    match kind {
        // The top of the rail (smallest z) lies inside; flipped when only
        // the largest z does.
        ProfileKind::Rail => !interior(imin) && interior(imax),
        // The flange tip (largest z) lies inside; flipped when only the
        // smallest z does.
        ProfileKind::Wheel => !interior(imax) && interior(imin),
    }
}

/// CONTACT's smoothing parameters as the solver's cut-off wavelength \[m\]:
/// ISMOOTH = 1, 2 give L_FILT \[mm\] directly (2, CONTACT's third-order
/// B-spline, is taken as the second-order spline of the same wavelength);
/// ISMOOTH = 0, the unweighted spline with parameter LAMBDA, as the user
/// guide relates it to the weighted one: lambda2 = mean(ds) LAMBDA,
/// L_FILT = 2 pi lambda2^(1/4) (ds in mm).
fn smoothing_wavelength_m(ismooth: i32, smooth: f64, points_m: &[[f64; 2]]) -> f64 {
    if smooth <= 0.0 {
        return 0.0;
    }
    if ismooth >= 1 {
        return smooth * MM;
    }
    let n = points_m.len();
    if n < 2 {
        return 0.0;
    }
    let total: f64 = points_m
        .windows(2)
        .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
        .sum();
    let mean_ds_mm = total / MM / (n - 1) as f64;
    2.0 * std::f64::consts::PI * (mean_ds_mm * smooth).powf(0.25) * MM
}

/// The profile smoothed by `wavelength_m` and sampled at its own points,
/// for a pair whose other profile has another smoothing (the pair fits
/// both with one option: then both are given smoothed and interpolated).
fn presmoothed(p: &ProfileInput) -> Result<Profile> {
    if p.smoothing_m <= 0.0 {
        return Ok(p.profile.clone());
    }
    let spline = p.spline()?;
    let pts: Vec<[f64; 2]> = spline
        .knot_arc_lengths_m()
        .iter()
        .map(|t| spline.position(*t))
        .collect();
    Profile::from_points(
        p.profile.name(),
        p.profile.kind(),
        &pts,
        &ProfileChecks::default(),
    )
    .map_err(CntcError::from_profile)
}

/// Reads a profile file as CONTACT does: a relative name is relative to
/// the process's working directory (said in the message when it cannot be
/// read).
fn read_profile_text(
    fname: &str,
    content: std::result::Result<&[u8], &String>,
    options: &LoadOptions,
) -> Result<Profile> {
    const CALL: &str = "cntc_setprofileinputfname";
    let bytes = content.map_err(|why| CntcError::Profile(format!("{CALL}: {why}")))?;
    let name = std::path::Path::new(fname)
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| fname.to_string());
    // Profile files are ASCII; other code pages are tolerated in free text.
    let text = String::from_utf8_lossy(bytes);
    parse_profile(&text, &name, options).map_err(|e| CntcError::Profile(format!("{CALL}: {e}")))
}

/// The bytes of profile file `fname` (a path as the caller gave it), or
/// why they cannot be read (a relative path: with the working directory
/// it is relative to).
pub fn read_profile_file(fname: &str) -> std::result::Result<Vec<u8>, String> {
    let path = std::path::Path::new(fname);
    std::fs::read(path).map_err(|e| {
        let cwd = match std::env::current_dir() {
            Ok(d) if path.is_relative() => {
                format!(" (relative to the working directory {})", d.display())
            }
            _ => String::new(),
        };
        format!("cannot read \"{fname}\": {e}{cwd}")
    })
}

/// A slices file as `cntc_setprofileinputfname` gives it: its name, its
/// bytes (or why they could not be read), its profile files' and the
/// call's parameters.
#[derive(Clone, Copy)]
struct SlicesSource<'a> {
    fname: &'a str,
    content: std::result::Result<&'a [u8], &'a String>,
    slice_files: &'a [SliceFile],
    iparam: &'a [i32],
    rparam: &'a [f64],
}

/// A profile file a rail slices file names: its name as written there,
/// and its bytes or why they could not be read.
pub type SliceFile = (String, std::result::Result<Vec<u8>, String>);

/// The profile files of the rail or wheel slices file `fname` (`.slcs`,
/// `.slcw`; its bytes
/// `content`), each read relative to the slices file's folder
/// ([`read_profile_file`]), so that a server applies the file without the
/// caller's files. Empty for another file, or a slices file that cannot be
/// read or whose lines are malformed (applying it then says why).
pub fn read_slice_files(
    fname: &str,
    content: std::result::Result<&[u8], &String>,
) -> Vec<SliceFile> {
    let axis = if is_slices_file(fname) {
        SliceAxis::Track
    } else {
        SliceAxis::Wheel
    };
    let (true, Ok(bytes)) = (
        is_slices_file(fname) || is_wheel_slices_file(fname),
        content,
    ) else {
        return Vec::new();
    };
    let Ok(file) = parse_slices_file_along(&String::from_utf8_lossy(bytes), fname, axis) else {
        return Vec::new();
    };
    let dir = std::path::Path::new(fname)
        .parent()
        .unwrap_or(std::path::Path::new(""));
    let mut out: Vec<SliceFile> = Vec::with_capacity(file.slices.len());
    for (_, name, _) in file.slices {
        if out.iter().all(|(n, _)| *n != name) {
            let bytes = read_profile_file(&dir.join(&name).to_string_lossy());
            out.push((name, bytes));
        }
    }
    out
}

/// The rows of a per-element field in reverse order (a left wheel's grid
/// mirrored in y), each value times `sign`.
fn mirrored_rows(v: &[f64], nx: usize, ny: usize, sign: f64) -> Vec<f64> {
    if v.len() != nx * ny {
        return v.to_vec();
    }
    (0..ny)
        .rev()
        .flat_map(|iy| v[iy * nx..(iy + 1) * nx].iter().map(move |x| sign * x))
        .collect()
}

fn mirrored<T: Copy>(v: &[T], nx: usize, ny: usize) -> Vec<T> {
    if v.len() != nx * ny {
        return v.to_vec();
    }
    (0..ny)
        .rev()
        .flat_map(|iy| v[iy * nx..(iy + 1) * nx].iter().copied())
        .collect()
}

impl WheelRail {
    /// Bounds the slices files it reads from now on (a server's, on the
    /// files a forwarding library sends with its calls).
    pub fn set_slices_limits(&mut self, limits: SlicesLimits) {
        self.slices_limits = limits;
    }

    fn units(&self) -> Units {
        self.config.units
    }

    /// Forgets the placed profiles (a profile, the track or the wheelset
    /// changed).
    fn invalidate(&mut self) {
        if let Some(pair) = self.pair.take() {
            self.pair_before = Some(pair);
        }
    }

    /// The profile slot of `kind`.
    fn profile_slot(&mut self, kind: ProfileKind) -> &mut Slot<ProfileInput> {
        match kind {
            ProfileKind::Rail => &mut self.rail,
            ProfileKind::Wheel => &mut self.wheel,
        }
    }

    /// Stores `r` (a profile or the error reading it) and returns its error.
    fn store_profile(&mut self, kind: ProfileKind, r: Result<ProfileInput>) -> Result<()> {
        self.invalidate();
        let out = r.as_ref().map(|_| ()).map_err(Clone::clone);
        *self.profile_slot(kind) = Some(r);
        out
    }

    /// CONTACT's scale factor SCALE_YZ: `rparam(1)`, or (when <= 5e-4,
    /// CONTACT's rule) the unit convention's millimetres per length unit.
    fn profile_scale(&self, rparam: &[f64]) -> f64 {
        let s = rp(rparam, 1, 0.0);
        if s.is_finite() && s > 5e-4 {
            s
        } else {
            self.units().length_m() / MM
        }
    }

    /// `cntc_setprofileinputfname`: a rail or wheel profile from file
    /// `fname`, whose bytes the caller read ([`read_profile_file`]).
    pub fn set_profile_file(
        &mut self,
        fname: &str,
        content: std::result::Result<&[u8], &String>,
        slice_files: &[SliceFile],
        iparam: &[i32],
        rparam: &[f64],
    ) -> Result<()> {
        const CALL: &str = "cntc_setprofileinputfname";
        let itype = ip(iparam, 1, -1);
        let kind = match itype {
            0 => ProfileKind::Rail,
            1 => ProfileKind::Wheel,
            // A slices file (.slcs) is a rail's, a .slcw a wheel's.
            _ if is_slices_file(fname) => ProfileKind::Rail,
            _ if is_wheel_slices_file(fname) => ProfileKind::Wheel,
            _ => railcontact_solver::wheelrail::kind_from_extension(fname).ok_or_else(|| {
                CntcError::Profile(format!(
                    "{CALL}: cannot tell a rail from a wheel profile by the extension of \"{fname}\" \
                     (.prr, .ban, .slcs rail; .prw, .whl wheel): give ITYPE = 0 (rail) or 1 (wheel) in iparam(1)"
                ))
            })?,
        };
        let r = self.read_profile(fname, content, slice_files, kind, iparam, rparam);
        self.store_profile(kind, r)
    }

    fn read_profile(
        &self,
        fname: &str,
        content: std::result::Result<&[u8], &String>,
        slice_files: &[SliceFile],
        kind: ProfileKind,
        iparam: &[i32],
        rparam: &[f64],
    ) -> Result<ProfileInput> {
        const CALL: &str = "cntc_setprofileinputfname";
        if fname.is_empty() {
            return Err(CntcError::Profile(format!(
                "{CALL}: the file name is empty"
            )));
        }
        let ext = std::path::Path::new(fname)
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase());
        let src = SlicesSource {
            fname,
            content,
            slice_files,
            iparam,
            rparam,
        };
        match (kind, ext.as_deref()) {
            (ProfileKind::Rail, Some("slcs")) => return self.read_rail_slices(&src),
            (ProfileKind::Wheel, Some("slcw")) => return self.read_wheel_slices(&src),
            (ProfileKind::Rail, Some("slcw")) => {
                return Err(CntcError::Profile(format!(
                    "{CALL}: \"{fname}\" is a wheel slices file (.slcw), given as the rail \
                     (ITYPE = 0)"
                )))
            }
            (ProfileKind::Wheel, Some("slcs")) => {
                return Err(CntcError::Profile(format!(
                    "{CALL}: \"{fname}\" is a rail slices file (.slcs), given as the wheel \
                     (ITYPE = 1)"
                )))
            }
            _ => {}
        }
        let profile = self.scaled_profile(fname, content, kind, iparam, rparam)?;
        let smooth = rp(rparam, 2, 0.0);
        if !smooth.is_finite() {
            return Err(CntcError::Profile(format!(
                "{CALL}: SMOOTH (rparam(2)) = {smooth} is not a finite number"
            )));
        }
        let smoothing_m = smoothing_wavelength_m(ip(iparam, 6, 0), smooth, profile.points());
        Ok(ProfileInput {
            profile,
            smoothing_m,
            slices: None,
            wheel_slices: None,
        })
    }

    /// A variable rail from the slices file `fname` (its bytes `content`,
    /// its profile files' `slice_files`): each slice's profile read and
    /// scaled as a single profile is.
    fn read_rail_slices(&self, src: &SlicesSource) -> Result<ProfileInput> {
        const CALL: &str = "cntc_setprofileinputfname";
        let rparam = src.rparam;
        let rail = ProfileKind::Rail;
        let limits = self.slices_limits;
        let slices = self.read_slices(src, rail, &Ok, |t, n, r| {
            parse_slices_within(t, n, r, limits)
        })?;
        let profile = slices
            .profile_at(slices.u_range_m().0)
            .map_err(|e| CntcError::Profile(format!("{CALL}: {e}")))?;
        let smooth = rp(rparam, 2, 0.0);
        if !(smooth.is_finite() && smooth <= 0.0) {
            return Err(CntcError::NotSupported(format!(
                "{CALL}: SMOOTH (rparam(2)) = {smooth}: smoothing a variable rail \
                 (a slices file) is not supported; give 0"
            )));
        }
        Ok(ProfileInput {
            profile,
            smoothing_m: 0.0,
            slices: Some(Arc::new(slices)),
            wheel_slices: None,
        })
    }

    /// An out-of-round wheel from the wheel slices file `fname` (its bytes
    /// `content`, its profile files' `slice_files`): each slice's profile
    /// read, scaled and smoothed (SMOOTH, as a single profile) on its own,
    /// as CONTACT smooths each slice, and the slices' surface built from
    /// the smoothed slices.
    fn read_wheel_slices(&self, src: &SlicesSource) -> Result<ProfileInput> {
        const CALL: &str = "cntc_setprofileinputfname";
        let (iparam, rparam) = (src.iparam, src.rparam);
        let smooth = rp(rparam, 2, 0.0);
        if !smooth.is_finite() {
            return Err(CntcError::Profile(format!(
                "{CALL}: SMOOTH (rparam(2)) = {smooth} is not a finite number"
            )));
        }
        let ismooth = ip(iparam, 6, 0);
        let smoothed = |profile: Profile| {
            let smoothing_m = smoothing_wavelength_m(ismooth, smooth, profile.points());
            presmoothed(&ProfileInput {
                profile,
                smoothing_m,
                slices: None,
                wheel_slices: None,
            })
        };
        let wheel = ProfileKind::Wheel;
        let slices = self.read_slices(src, wheel, &smoothed, |t, n, r| {
            parse_wheel_slices_within(t, n, r, self.slices_limits)
        })?;
        let profile = slices
            .profile_at(0.0)
            .map_err(|e| CntcError::Profile(format!("{CALL}: {e}")))?;
        Ok(ProfileInput {
            profile,
            smoothing_m: 0.0,
            slices: None,
            wheel_slices: Some(Arc::new(slices)),
        })
    }

    /// The slices of the slices file of `src` (its profile files each read
    /// and scaled as a single profile of `kind`, then passed through
    /// `finish`) built by `parse`.
    fn read_slices<T>(
        &self,
        src: &SlicesSource,
        kind: ProfileKind,
        finish: &dyn Fn(Profile) -> Result<Profile>,
        parse: impl FnOnce(
            &str,
            &str,
            &mut dyn FnMut(&str) -> std::result::Result<Profile, ProfileError>,
        ) -> std::result::Result<T, ProfileError>,
    ) -> Result<T> {
        const CALL: &str = "cntc_setprofileinputfname";
        let SlicesSource {
            fname,
            content,
            slice_files,
            iparam,
            rparam,
        } = *src;
        let bytes = content.map_err(|why| CntcError::Profile(format!("{CALL}: {why}")))?;
        let text = String::from_utf8_lossy(bytes);
        let not_given = "not among the files read with the slices file".to_string();
        // Errors of a slice's profile pass through the slices reader as
        // text (it names the slice's line).
        let mut read = |name: &str| {
            let bytes = slice_files
                .iter()
                .find(|(n, _)| n == name)
                .map_or(Err(&not_given), |(_, b)| b.as_deref());
            self.scaled_profile(name, bytes, kind, iparam, rparam)
                .and_then(finish)
                .map_err(|e| ProfileError::Format {
                    at: SourceLocation::new(name, None),
                    message: e.to_string(),
                })
        };
        parse(&text, fname, &mut read).map_err(|e| CntcError::Profile(format!("{CALL}: {e}")))
    }

    /// A profile file read and scaled by SCALE_YZ, as
    /// `cntc_setprofileinputfname` takes it.
    fn scaled_profile(
        &self,
        fname: &str,
        content: std::result::Result<&[u8], &String>,
        kind: ProfileKind,
        iparam: &[i32],
        rparam: &[f64],
    ) -> Result<Profile> {
        const CALL: &str = "cntc_setprofileinputfname";
        let mirror_z = match ip(iparam, 4, 0) {
            0 => MirrorZ::Auto,
            m if m < 0 => MirrorZ::Keep,
            _ => MirrorZ::Flip,
        };
        let sclfac = self.profile_scale(rparam);
        let scaled = (sclfac - 1.0).abs() >= 1e-12;
        let options = LoadOptions {
            kind: Some(kind),
            mirror_y: ip(iparam, 3, 0) >= 1,
            mirror_z,
            // CONTACT reads a two-column table as numbers in millimetres
            // (times the scale factor).
            plain_unit: Some(LengthUnit::Millimetre),
            // The width is checked once scaled.
            checks: ProfileChecks {
                min_width_m: if scaled {
                    0.0
                } else {
                    ProfileChecks::default().min_width_m
                },
                ..ProfileChecks::default()
            },
            ..LoadOptions::default()
        };
        let read = read_profile_text(fname, content, &options)?;
        let profile = if !scaled {
            read
        } else {
            let pts: Vec<[f64; 2]> = read
                .points()
                .iter()
                .map(|p| [p[0] * sclfac, p[1] * sclfac])
                .collect();
            Profile::from_points(read.name(), Some(kind), &pts, &ProfileChecks::default()).map_err(
                |e| {
                    CntcError::Profile(format!(
                        "{CALL}: \"{fname}\" scaled by SCALE_YZ = {sclfac} (rparam(1)): {e}"
                    ))
                },
            )?
        };
        Ok(profile)
    }

    /// `cntc_setprofileinputvalues`: a profile from `npoint` (y, z) pairs.
    pub fn set_profile_values(
        &mut self,
        npoint: usize,
        values: &[f64],
        iparam: &[i32],
        rparam: &[f64],
    ) -> Result<()> {
        const CALL: &str = "cntc_setprofileinputvalues";
        // CONTACT: ITYPE clamped to 0 (rail) or 1 (wheel); a wheel without
        // iparam.
        let kind = if iparam.is_empty() || ip(iparam, 1, 1) >= 1 {
            ProfileKind::Wheel
        } else {
            ProfileKind::Rail
        };
        let r = (|| {
            if values.len() < 2 * npoint {
                return Err(CntcError::Profile(format!(
                    "{CALL}: {npoint} points need {} values, got {}",
                    2 * npoint,
                    values.len()
                )));
            }
            if npoint < 2 {
                return Err(CntcError::Profile(format!(
                    "{CALL}: a profile needs at least 2 points, got NPOINT = {npoint}"
                )));
            }
            let sclfac = self.profile_scale(rparam) * MM;
            let ysign = if ip(iparam, 3, 0) >= 1 { -1.0 } else { 1.0 };
            let mut pts: Vec<[f64; 2]> = values[..2 * npoint]
                .chunks(2)
                .map(|c| [ysign * c[0] * sclfac, c[1] * sclfac])
                .collect();
            if let Some(i) = pts
                .iter()
                .position(|p| !(p[0].is_finite() && p[1].is_finite()))
            {
                return Err(CntcError::Profile(format!(
                    "{CALL}: point {} (values({}), values({})) is not finite",
                    i + 1,
                    2 * i + 1,
                    2 * i + 2
                )));
            }
            let flip = match ip(iparam, 4, 0) {
                0 => z_points_up(kind, &pts),
                m => m > 0,
            };
            if flip {
                pts.iter_mut().for_each(|p| p[1] = -p[1]);
            }
            let profile =
                Profile::from_points("<values>", Some(kind), &pts, &ProfileChecks::default())
                    .map_err(|e| CntcError::Profile(format!("{CALL}: {e}")))?;
            let smooth = rp(rparam, 2, 0.0);
            let smoothing_m = smoothing_wavelength_m(ip(iparam, 6, 0), smooth, profile.points());
            Ok(ProfileInput {
                profile,
                smoothing_m,
                slices: None,
                wheel_slices: None,
            })
        })();
        self.store_profile(kind, r)
    }

    /// `cntc_settrackdimensions`.
    pub fn set_track_dimensions(&mut self, ztrack: i32, p: &[f64]) -> Result<()> {
        const CALL: &str = "cntc_settrackdimensions";
        let (lo, hi) = match ztrack {
            0 => (0, 0),
            1 => (5, 6),
            2 => (6, 6),
            3 => (11, 12),
            32 | 33 => (4, 5),
            z => {
                return Err(CntcError::Input(format!(
                    "{CALL}: method Z = {z} does not exist (0-3, 32, 33)"
                )))
            }
        };
        if p.len() < lo || p.len() > hi {
            return Err(CntcError::Input(format!(
                "{CALL}: method Z = {ztrack} needs {} parameters, got {}",
                if lo == hi {
                    lo.to_string()
                } else {
                    format!("{lo}-{hi}")
                },
                p.len()
            )));
        }
        finite(CALL, &[], p)?;
        let u = self.units();
        if ztrack >= 32 {
            // KYRAIL, KZRAIL [force/length], FYRAIL, FZRAIL [N],
            // DYSTEP0 [length] (default 1 mm).
            let rail = MasslessRail {
                lateral_stiffness_n_per_m: u.per_len(p[0]),
                lateral_force_n: p[1],
                vertical_stiffness_n_per_m: u.per_len(p[2]),
                vertical_force_n: p[3],
                first_lateral_step_m: p.get(4).map_or(1e-3, |v| u.len(*v)),
            };
            let names = ["KYRAIL", "FYRAIL", "KZRAIL", "FZRAIL", "DYSTEP0"];
            let bad = |k: usize, what: &str| {
                Err(CntcError::Input(format!(
                    "{CALL}: Z = {ztrack}: {} = {} (params({})) must be {what}",
                    names[k],
                    p[k],
                    k + 1
                )))
            };
            if rail.lateral_stiffness_n_per_m <= 0.0 {
                return bad(0, "> 0");
            }
            if rail.vertical_stiffness_n_per_m < 0.0 {
                return bad(2, ">= 0");
            }
            if rail.first_lateral_step_m <= 0.0 {
                return bad(4, "> 0");
            }
            self.massless_rail = Some(rail);
            return Ok(());
        }
        if ztrack == 1 || ztrack == 3 {
            let gaught = u.len(p[0]);
            let curv_index = if ztrack == 1 { 6 } else { 12 };
            let curv = if p.len() >= curv_index { p[5] } else { 0.0 };
            let curvature_per_m = u.per_len(curv);
            let roller_radius_m = u.len(p[4]);
            let track = if curvature_per_m.abs() > MAX_TRACK_CURVATURE_PER_M {
                Err(CntcError::Input(format!(
                    "{CALL}: track curvature CURV = {curv} (params(6)) is a curve radius below \
                     {} (the solver's limit)",
                    u.len_out(1.0 / MAX_TRACK_CURVATURE_PER_M)
                )))
            } else if gaught <= 0.0 {
                // Absolute placement: the rail profile's origin at
                // (RAILY0, RAILZ0) of the track.
                Ok(Track {
                    placement: Placement::Absolute {
                        rail_y_m: u.len(p[1]),
                        rail_z_m: u.len(p[2]),
                    },
                    cant_rad: p[3],
                    roller_radius_m,
                    curvature_per_m,
                })
            } else if p[2] <= 0.0 {
                Err(CntcError::Input(format!(
                    "{CALL}: the gauge GAUGWD = {} (params(3)) must be > 0",
                    p[2]
                )))
            } else {
                Ok(Track {
                    placement: Placement::GaugePoint {
                        gauge_height_m: gaught,
                        gauge_m: u.len(p[2]),
                    },
                    cant_rad: p[3],
                    roller_radius_m,
                    curvature_per_m,
                })
            };
            // GAUGSQ (params(2)) is reserved in CONTACT; NOMRAD (params(5))
            // is the roller radius of roller rigs, checked when one is
            // solved.
            self.invalidate();
            let out = track.as_ref().map(|_| ()).map_err(Clone::clone);
            self.track = Some(track);
            out?;
        }
        if ztrack == 2 || ztrack == 3 {
            let ofs = match ztrack {
                2 => 0,
                _ if p.len() >= 12 => 6,
                _ => 5,
            };
            let d = &p[ofs..ofs + 6];
            self.rail_deviation = [
                u.len(d[0]),
                u.len(d[1]),
                d[2],
                u.velocity(d[3]),
                u.velocity(d[4]),
                d[5],
            ];
        }
        Ok(())
    }

    /// `cntc_setwheelsetdimensions`.
    pub fn set_wheelset_dimensions(&mut self, ewheel: i32, p: &[f64]) -> Result<()> {
        const CALL: &str = "cntc_setwheelsetdimensions";
        if !(0..=5).contains(&ewheel) {
            return Err(CntcError::Input(format!(
                "{CALL}: method E = {ewheel} does not exist (0-5)"
            )));
        }
        if ewheel != 3 && ewheel != 5 {
            if !p.is_empty() {
                return Err(CntcError::Input(format!(
                    "{CALL}: method E = {ewheel} needs 0 parameters, got {}",
                    p.len()
                )));
            }
            return Ok(());
        }
        if p.len() < 3 || p.len() > 4 {
            return Err(CntcError::Input(format!(
                "{CALL}: method E = {ewheel} needs 3 or 4 parameters (FBDIST, FBPOS, NOMRAD, \
                 {{YTAPE}}), got {}",
                p.len()
            )));
        }
        finite(CALL, &["FBDIST", "FBPOS", "NOMRAD", "YTAPE"], p)?;
        let u = self.units();
        let dims = if p[0] <= 0.0 {
            Err(CntcError::Input(format!(
                "{CALL}: the flange-back distance FBDIST = {} (params(1)) must be > 0",
                p[0]
            )))
        } else if p[2] <= 0.0 {
            Err(CntcError::Input(format!(
                "{CALL}: the nominal radius NOMRAD = {} (params(3)) must be > 0",
                p[2]
            )))
        } else {
            let tape = p.get(3).map(|y| u.len(*y)).filter(|y| y.abs() < 1.0);
            Ok(WheelsetDims {
                flange_back_distance_m: u.len(p[0]),
                flange_back_y_m: u.len(p[1]),
                nominal_radius_m: u.len(p[2]),
                tape_y_m: tape,
            })
        };
        self.invalidate();
        let out = dims.as_ref().map(|_| ()).map_err(Clone::clone);
        self.wheelset = Some(dims);
        out
    }

    /// `cntc_setwheelsetposition`.
    pub fn set_wheelset_position(&mut self, ewheel: i32, p: &[f64]) -> Result<()> {
        const CALL: &str = "cntc_setwheelsetposition";
        if !(1..=5).contains(&ewheel) {
            return Err(CntcError::Input(format!(
                "{CALL}: method E = {ewheel} does not exist (1-5)"
            )));
        }
        if p.len() != 6 {
            return Err(CntcError::Input(format!(
                "{CALL}: method E = {ewheel} needs 6 parameters (S_WS, Y_WS, Z_WS, ROLL, YAW, \
                 PITCH), got {}",
                p.len()
            )));
        }
        finite(CALL, &["S_WS", "Y_WS", "Z_WS", "ROLL", "YAW", "PITCH"], p)?;
        let u = self.units();
        self.position = [u.len(p[0]), u.len(p[1]), u.len(p[2]), p[3], p[4], p[5]];
        Ok(())
    }

    /// `cntc_setwheelsetvelocity`.
    pub fn set_wheelset_velocity(&mut self, ewheel: i32, p: &[f64]) -> Result<()> {
        const CALL: &str = "cntc_setwheelsetvelocity";
        // CONTACT maps the obsolete E = 1 with 6 values to E = 2.
        let e = if ewheel == 1 && p.len() == 6 {
            2
        } else {
            ewheel
        };
        if e == 1 && p.is_empty() {
            return Ok(());
        }
        if !(2..=5).contains(&e) {
            return Err(CntcError::Input(format!(
                "{CALL}: method E = {ewheel} does not exist for velocities (2-5)"
            )));
        }
        if p.len() != 6 {
            return Err(CntcError::Input(format!(
                "{CALL}: method E = {ewheel} needs 6 parameters (VS, VY, VZ, VROLL, VYAW, \
                 VPITCH), got {}",
                p.len()
            )));
        }
        finite(CALL, &["VS", "VY", "VZ", "VROLL", "VYAW", "VPITCH"], p)?;
        let u = self.units();
        // On a roller rig (C1 = 4, 5 when called, as CONTACT decides) the
        // first value is the rollers' angular velocity VPITCH_ROL and the
        // wheelset's forward speed is zero.
        let (vs, roller) = if self.is_roller() {
            (0.0, p[0])
        } else {
            (p[0], 0.0)
        };
        self.roller_rad_per_s = roller;
        self.velocity = [
            u.velocity(vs),
            u.velocity(p[1]),
            u.velocity(p[2]),
            p[3],
            p[4],
            p[5],
        ];
        Ok(())
    }

    /// `cntc_setwheelsetflexibility`.
    pub fn set_wheelset_flexibility(&mut self, ewheel: i32, p: &[f64]) -> Result<()> {
        const CALL: &str = "cntc_setwheelsetflexibility";
        if !(1..=5).contains(&ewheel) {
            return Err(CntcError::Input(format!(
                "{CALL}: method E = {ewheel} does not exist (1-5)"
            )));
        }
        if ewheel <= 3 {
            // No flexibilities: any values given are not used.
            self.flexibility = [0.0; 12];
            return Ok(());
        }
        if p.len() != 12 {
            return Err(CntcError::Input(format!(
                "{CALL}: method E = {ewheel} needs 12 parameters (DXWHL .. VPITCHW), got {}",
                p.len()
            )));
        }
        finite(
            CALL,
            &[
                "DXWHL", "DYWHL", "DZWHL", "DROLLW", "DYAWW", "DPITCHW", "VXWHL", "VYWHL", "VZWHL",
                "VROLLW", "VYAWW", "VPITCHW",
            ],
            p,
        )?;
        let u = self.units();
        let mut f = [0.0; 12];
        for k in 0..3 {
            f[k] = u.len(p[k]);
            f[k + 3] = p[k + 3];
            f[k + 6] = u.velocity(p[k + 6]);
            f[k + 9] = p[k + 9];
        }
        self.flexibility = f;
        Ok(())
    }

    /// `cntc_setverticalforce` (also sets N = 1).
    pub fn set_vertical_force(&mut self, fz: f64) -> Result<()> {
        if !fz.is_finite() {
            return Err(CntcError::Input(format!(
                "cntc_setverticalforce: FZ = {fz} is not a finite number"
            )));
        }
        self.config.digits.norm = 1;
        self.vertical_force_n = Some(fz);
        Ok(())
    }

    /// `cntc_settangentialforces` of module 1 (icp <= 0): FX_WS, the total
    /// force on the rail along the wheelset's longitudinal axis \[N\] (on
    /// the wheel under SIMPACK's convention), for F = 1; FY is not used.
    pub fn set_longitudinal_force(&mut self, icp: i32, fx: f64) -> Result<()> {
        if icp > 0 {
            return Err(CntcError::Icp(format!(
                "cntc_settangentialforces: icp = {icp}; module 1 takes its total force FX_WS \
                 with icp = -1"
            )));
        }
        if !fx.is_finite() {
            return Err(CntcError::Input(format!(
                "cntc_settangentialforces: FX_WS = {fx} is not a finite number"
            )));
        }
        self.longitudinal_force_n = Some(fx * self.units().body_sign());
        Ok(())
    }

    /// `cntc_setpotcontact` with icp = -1: DX, DS, A_SEP, D_SEP, D_COMB, ...
    pub fn set_discretisation(&mut self, ipotcn: i32, p: &[f64]) -> Result<()> {
        const CALL: &str = "cntc_setpotcontact";
        let ok = match ipotcn {
            -1 => (5..=7).contains(&p.len()),
            0 => (2..=3).contains(&p.len()),
            _ => {
                return Err(CntcError::Discretisation(format!(
                "{CALL}: IPOTCN = {ipotcn} does not exist for a wheel/rail problem (-1: DX, DS, \
                     A_SEP, D_SEP, D_COMB; 0: DX, DS)"
            )))
            }
        };
        if !ok {
            return Err(CntcError::Discretisation(format!(
                "{CALL}: IPOTCN = {ipotcn} needs {} parameters, got {}",
                if ipotcn == -1 { "5, 6 or 7" } else { "2 or 3" },
                p.len()
            )));
        }
        finite(
            CALL,
            &["DX", "DS", "A_SEP", "D_SEP", "D_COMB", "D_TURN", "G_MISS"],
            p,
        )?;
        let u = self.units();
        let old = self.discretisation;
        let d = Discretisation {
            dx_m: u.len(p[0].max(1e-12)),
            ds_m: u.len(p[1].max(1e-12)),
            angle_sep_rad: if ipotcn == -1 {
                p[2].max(0.0)
            } else {
                old.map_or(std::f64::consts::PI, |d| d.angle_sep_rad)
            },
            dist_sep_m: if ipotcn == -1 {
                u.len(p[3].max(0.0))
            } else {
                old.map_or(8.0 * MM, |d| d.dist_sep_m)
            },
            dist_comb_m: if ipotcn == -1 {
                u.len(p[4].max(0.0))
            } else {
                old.map_or(4.0 * MM, |d| d.dist_comb_m)
            },
            dist_turn_m: match (ipotcn, p.get(5)) {
                (-1, Some(&t)) => u.len(t.max(0.0)),
                // CONTACT's default: 2 D_SEP - D_COMB.
                (-1, None) => u.len(2.0 * p[3].max(0.0) - p[4].max(0.0)),
                _ => old.map_or(12.0 * MM, |d| d.dist_turn_m),
            },
        };
        self.discretisation = Some(d);
        Ok(())
    }

    /// `cntc_setrollingstepsize` with icp = -1: DQREL.
    pub fn set_rolling_step(&mut self, _chi: f64, dqrel: f64) -> Result<()> {
        if !dqrel.is_finite() {
            return Err(CntcError::Input(format!(
                "cntc_setrollingstepsize: DQREL = {dqrel} is not a finite number"
            )));
        }
        // Steady rolling takes DQREL = 1; T = 2 checks it at the calculation.
        self.dqrel = dqrel;
        Ok(())
    }

    // -----------------------------------------------------------------
    // Calculation.

    /// `cntc_calculate` of the wheel: `Ok(n)`, n >= 0 contact elements on
    /// the border of the patches' grids.
    pub fn calculate(&mut self, cache: &KernelCache) -> Result<i32> {
        let t0 = Instant::now();
        self.ncase += 1;
        let r = self.calculate_timed(cache);
        self.time_s += t0.elapsed().as_secs_f64();
        if r.is_err() {
            self.outcomes.clear();
            self.solved = None;
            self.subs_done.clear();
        }
        r
    }

    /// Limits each patch's grid to `max` elements (a server's limit).
    pub fn limit_grid_elements(&mut self, max: usize) {
        self.max_grid_elements = Some(max);
    }

    /// What the last calculation left (to send to a library that forwards
    /// its calculations).
    pub fn calculation_result(&self) -> (Vec<Outcome>, Option<Solved>) {
        (self.outcomes.clone(), self.solved.clone())
    }

    /// Takes what a server's calculation left, as [`WheelRail::calculate`]
    /// leaves it, counting the calculation and its `seconds`.
    pub fn accept_calculation(
        &mut self,
        outcomes: Vec<Outcome>,
        solved: Option<Solved>,
        seconds: f64,
    ) {
        self.ncase += 1;
        self.time_s += seconds;
        self.subs_done = vec![None; outcomes.len()];
        self.outcomes = outcomes;
        self.solved = solved;
    }

    /// The side of the C1 digit.
    fn side(&self) -> Result<Side> {
        match self.config.digits.config {
            0 | 4 => Ok(Side::Left),
            1 | 5 => Ok(Side::Right),
            c => Err(CntcError::NotSupported(format!(
                "C1 = {c} (CNTC_ic_config): 0 left rail, 1 right rail, 4 left roller, 5 right \
                 roller"
            ))),
        }
    }

    /// True on a roller rig (C1 = 4, 5).
    fn is_roller(&self) -> bool {
        self.config.digits.config >= 4
    }

    /// What a roller rig needs: NOMRADR > 0, VPITCH_ROL != 0 (> 0 rolling
    /// forwards, < 0 backwards) and the wheelset over the rollers' top
    /// (X_WS = 0).
    fn check_roller(&self, x_ws: f64) -> Result<()> {
        let u = self.units();
        let radius = track_roller_radius(&self.track);
        if radius <= 0.0 {
            return Err(CntcError::Input(format!(
                "NOMRADR = {} (cntc_settrackdimensions params(5)) must be > 0 on a roller rig \
                 (C1 = 4, 5)",
                u.len_out(radius)
            )));
        }
        if self.roller_rad_per_s == 0.0 {
            return Err(CntcError::NotSupported(format!(
                "VPITCH_ROL = {} (cntc_setwheelsetvelocity params(1)): the rollers must turn \
                 (> 0 rolling forwards, < 0 backwards): the creepages are divided by their \
                 surface speed",
                self.roller_rad_per_s
            )));
        }
        if x_ws != 0.0 {
            return Err(CntcError::NotSupported(format!(
                "X_WS = {} (cntc_setwheelsetposition params(1)): the wheelset stands over the \
                 rollers' top (X_WS = 0) only",
                u.len_out(x_ws)
            )));
        }
        Ok(())
    }

    /// Checks the configuration for what this library solves.
    fn check_configuration(&self) -> Result<()> {
        self.config.check_supported()?;
        let d = &self.config.digits;
        if !(0..=3).contains(&d.tang) {
            return Err(CntcError::NotSupported(format!(
                "T = {} (CNTC_ic_tang) in module 1 is not supported: the normal problem only \
                 (T = 0), a shift (T = 1), transient rolling (T = 2) or steady rolling (T = 3)",
                d.tang
            )));
        }
        if d.tang == 1 || d.tang == 2 {
            self.check_transient()?;
        }
        match d.force {
            0 => {}
            1 if d.tang == 0 => {
                return Err(CntcError::Input(
                    "F = 1 (a prescribed total force FX_WS) needs creep forces: T = 3 (T = 0 \
                     solves the normal problem only)"
                        .into(),
                ))
            }
            1 => {
                if d.norm != 1 {
                    return Err(CntcError::Input(
                        "F = 1 (a prescribed total force FX_WS) needs N = 1 (a vertical force: \
                         cntc_setverticalforce)"
                            .into(),
                    ));
                }
                if self.longitudinal_force_n.is_none() {
                    return Err(CntcError::Input(
                        "F = 1 needs the total force FX_WS: cntc_settangentialforces(ire, -1, \
                         fx, 0)"
                            .into(),
                    ));
                }
            }
            // The massless rail: its parameters are checked when solved.
            3 => {}
            f => {
                return Err(CntcError::NotSupported(format!(
                    "F = {f} (CNTC_ic_force) in module 1 is not supported: give the pitch rate \
                     VPITCH (F = 0), the total force FX_WS (F = 1) or use the massless rail \
                     (F = 3)"
                )))
            }
        }
        if d.discns >= 4 {
            return Err(CntcError::NotSupported(format!(
                "D = {} (CNTC_ic_discns): conformal contact in module 1 is not supported; D = 2",
                d.discns
            )));
        }
        if self.config.material.model.fastsim().is_some() {
            let method = match self.config.material.model {
                MaterialModel::ModifiedFastrip(_) => "FaStrip",
                _ => "FASTSIM",
            };
            if d.bound != 0 {
                return Err(CntcError::NotSupported(format!(
                    "B = {} (CNTC_ic_bound) with M = {} in module 1 is not supported: {method} \
                     on a wheel/rail patch takes its exact normal problem's pressure as the \
                     traction bound (B = 0); CONTACT's B = 2-4 are not available in module 1",
                    d.bound, d.mater
                )));
            }
            if d.tang == 3 && self.config.friction_by_angle.is_some() {
                return Err(CntcError::NotSupported(format!(
                    "V = 1 (friction varying with the contact angle) with M = {} in module 1 is \
                     not supported: {method} takes one friction law per patch (V = 0)",
                    d.mater
                )));
            }
        }
        if d.heat == 3 {
            return Err(CntcError::NotSupported(
                "H = 3 (temperatures, cntc_settemperaturedata) in module 1 is not supported".into(),
            ));
        }
        Ok(())
    }

    /// What transient contact (T = 1, 2) takes here: the pitch rate given
    /// (F = 0), Kalker's theory on elastic bodies (M = 0), Coulomb
    /// friction (L = 0; V = 0, or V = 1 by contact angle), with T = 2
    /// a rolling step of whole elements (DQREL = 1, 2, ...,
    /// [`rolled_elements`]).
    fn check_transient(&self) -> Result<()> {
        let d = &self.config.digits;
        let t = d.tang;
        if d.force != 0 {
            return Err(CntcError::NotSupported(format!(
                "F = {} (CNTC_ic_force) with T = {t} in module 1 is not supported: transient \
                 contact takes the pitch rate given (F = 0)",
                d.force
            )));
        }
        if !matches!(self.config.material.model, MaterialModel::Elastic) {
            return Err(CntcError::NotSupported(format!(
                "M = {} (CNTC_ic_mater) with T = {t} in module 1 is not supported: transient \
                 contact takes Kalker's theory on elastic bodies (M = 0)",
                d.mater
            )));
        }
        if d.frclaw != 0 {
            return Err(CntcError::NotSupported(format!(
                "L = {} (CNTC_ic_frclaw) with T = {t} in module 1 is not supported: transient \
                 contact takes Coulomb friction (L = 0)",
                d.frclaw
            )));
        }
        if t == 2 {
            rolled_elements(self.dqrel)?;
        }
        Ok(())
    }

    /// Whether `pair` was placed for the rail of `side`: a rail placed
    /// absolutely sits at RAILY0 of its own side, and the pair placed for
    /// the other side does not serve.
    fn fits(&self, pair: &WheelRailPair, side: Side) -> bool {
        // A variable rail's pair holds its profile at one position s.
        if matches!(&self.rail, Some(Ok(r)) if r.slices.is_some())
            && self.pair_track_s_m != Some(self.position[0])
        {
            return false;
        }
        // An out-of-round wheel's pair holds its profile at one pitch.
        if matches!(&self.wheel, Some(Ok(w)) if w.wheel_slices.is_some())
            && self.pair_pitch_rad != Some(self.position[5])
        {
            return false;
        }
        match &self.track {
            Some(Ok(track)) => {
                *pair.track() == self.placed_track(track, side, self.rail_deflection)
            }
            _ => true,
        }
    }

    /// The profile `p`, or of a variable rail its profile at the wheelset's
    /// position S, or of an out-of-round wheel its profile facing the rail
    /// at PITCH (`WheelSlices::profile_facing_rail`).
    fn at_wheelset<'a>(&self, p: &'a ProfileInput) -> Result<std::borrow::Cow<'a, ProfileInput>> {
        if let Some(slices) = &p.wheel_slices {
            let pitch = self.position[5];
            let radius =
                slot(&self.wheelset, "the wheelset dimensions have not been set")?.nominal_radius_m;
            let profile = slices.profile_facing_rail(pitch, radius).map_err(|e| {
                CntcError::Input(format!(
                    "the wheelset's pitch PITCH = {pitch} (cntc_setwheelsetposition): {e}"
                ))
            })?;
            return Ok(std::borrow::Cow::Owned(ProfileInput {
                profile,
                smoothing_m: p.smoothing_m,
                slices: None,
                wheel_slices: None,
            }));
        }
        let Some(slices) = &p.slices else {
            return Ok(std::borrow::Cow::Borrowed(p));
        };
        let s_m = self.position[0];
        let profile = slices.profile_at(s_m).map_err(|e| {
            CntcError::Input(format!(
                "the wheelset's position S = {} (cntc_setwheelsetposition): {e}",
                self.units().len_out(s_m)
            ))
        })?;
        Ok(std::borrow::Cow::Owned(ProfileInput {
            profile,
            smoothing_m: 0.0,
            slices: None,
            wheel_slices: None,
        }))
    }

    /// The solver's track of the rail of `side`, its deviations and the
    /// massless rail's `deflection` added.
    fn placed_track(&self, track: &Track, side: Side, deflection: RailDeflection) -> TrackData {
        let mut deviation = self.rail_deviation;
        deviation[0] += deflection.lateral_m;
        deviation[1] += deflection.vertical_m;
        track.for_side(side, &deviation, self.is_roller())
    }

    /// The placed profiles, the rail with the massless rail's
    /// `deflection`.
    fn build_pair(&self, side: Side, deflection: RailDeflection) -> Result<Arc<WheelRailPair>> {
        let rail = slot(
            &self.rail,
            "the rail profile has not been set: cntc_setprofileinputfname or \
             cntc_setprofileinputvalues with ITYPE = 0",
        )
        .map_err(|e| CntcError::Profile(e.to_string()))?;
        let rail = &*self.at_wheelset(rail)?;
        let wheel = slot(
            &self.wheel,
            "the wheel profile has not been set: cntc_setprofileinputfname or \
             cntc_setprofileinputvalues with ITYPE = 1",
        )
        .map_err(|e| CntcError::Profile(e.to_string()))?;
        let oor = wheel.wheel_slices.clone();
        let wheel = &*self.at_wheelset(wheel)?;
        let track = slot(
            &self.track,
            "the track dimensions have not been set: cntc_settrackdimensions with Z = 1 or 3",
        )?;
        let dims = slot(
            &self.wheelset,
            "the wheelset dimensions have not been set: cntc_setwheelsetdimensions with E = 3 or 5",
        )?;
        // One spline option for both: the common smoothing, or each
        // smoothed on its own and then interpolated.
        let (rail_p, wheel_p, options) = if rail.smoothing_m == wheel.smoothing_m {
            (
                rail.profile.clone(),
                wheel.profile.clone(),
                SplineOptions::smoothing(rail.smoothing_m),
            )
        } else {
            (
                presmoothed(rail)?,
                presmoothed(wheel)?,
                SplineOptions::interpolating(),
            )
        };
        // The tape circle: the wheel profile shifted so that its point at
        // Y_TAPE lies at the nominal radius (CONTACT's dr_tape).
        let wheel_p = match self.tape_shift(wheel)? {
            0.0 => wheel_p,
            dz => wheel_p.translated(0.0, dz),
        };
        // FBPOS only places the profile (its y = 0 at FBDIST/2 - FBPOS from
        // the wheelset centre) and may lie outside it (test-rollers2.inp:
        // FBPOS = -100 mm on a sphere of y -50..50 mm); the solver takes
        // the back of the flange on the profile: the same placement from
        // the profile's smallest y.
        let (lo, hi) = wheel_p.y_range_m();
        let (fb_distance_m, fb_y_m) = if (lo..=hi).contains(&dims.flange_back_y_m) {
            (dims.flange_back_distance_m, dims.flange_back_y_m)
        } else {
            (
                dims.flange_back_distance_m - 2.0 * (dims.flange_back_y_m - lo),
                lo,
            )
        };
        if fb_distance_m <= 0.0 {
            return Err(CntcError::Input(format!(
                "cntc_setwheelsetdimensions: FBDIST/2 - FBPOS = {} puts the wheel profile \
                 (y from {} to {}) across the wheelset centre",
                self.units()
                    .len_out(0.5 * dims.flange_back_distance_m - dims.flange_back_y_m),
                self.units().len_out(lo),
                self.units().len_out(hi)
            )));
        }
        let pair = PairCache::global()
            .get_or_build(
                [&rail_p, &rail_p],
                [&wheel_p, &wheel_p],
                self.placed_track(track, side, deflection),
                WheelsetData {
                    flange_back_distance_m: fb_distance_m,
                    nominal_radius_m: dims.nominal_radius_m,
                    flange_back_y_m: Some(fb_y_m),
                },
                &options,
            )
            .map_err(CntcError::from_wheelrail)?;
        let Some(oor) = oor else {
            return Ok(pair);
        };
        let pitch = self.position[5];
        let mut out = (*pair).clone();
        for s in [Side::Left, Side::Right] {
            out = out
                .with_wheel_slices(s, oor.clone(), pitch)
                .map_err(CntcError::from_wheelrail)?;
        }
        Ok(Arc::new(out))
    }

    /// CONTACT's dr_tape \[m\]: -z_w(Y_TAPE), 0 without a tape circle or
    /// when Y_TAPE lies outside the profile.
    fn tape_shift(&self, wheel: &ProfileInput) -> Result<f64> {
        let Some(Ok(dims)) = &self.wheelset else {
            return Ok(0.0);
        };
        let Some(y) = dims.tape_y_m else {
            return Ok(0.0);
        };
        let (lo, hi) = wheel.profile.y_range_m();
        if y < lo || y > hi {
            return Ok(0.0);
        }
        Ok(wheel.spline()?.z_at_y(y).map_or(0.0, |z| -z))
    }

    fn calculate_timed(&mut self, cache: &KernelCache) -> Result<i32> {
        self.check_configuration()?;
        let side = self.side()?;
        if self.config.digits.ret >= 2 {
            return Ok(0); // R = 2, 3: check the input only
        }
        let massless = match (self.config.digits.force, self.massless_rail) {
            (3, Some(rail)) => Some(rail),
            (3, None) => {
                return Err(CntcError::Input(
                    "F = 3 (the massless rail) needs its parameters: cntc_settrackdimensions \
                     with Z = 32 or 33"
                        .into(),
                ))
            }
            _ => None,
        };
        if massless.is_none() {
            self.rail_deflection = RailDeflection::default();
        }
        self.place_pair(side)?;
        let input = self.solver_input(side)?;
        if let Some(rail) = massless {
            self.deflect_rail(side, &rail, &input, cache)?;
        }
        let pair = self.pair.as_ref().expect("built above");
        let (input, sol, vpitch_found) = match self.longitudinal_force_n {
            Some(target) if self.config.digits.force == 1 => {
                let [_, _, _, roll, yaw, _] = self.position;
                let nominal_radius_m =
                    slot(&self.wheelset, "the wheelset dimensions have not been set")?
                        .nominal_radius_m;
                let problem = PitchProblem {
                    side,
                    axis: contact_ws_axes(side, roll, yaw)[0],
                    target_n: target,
                    vpitch: self.velocity[5],
                    nominal_radius_m,
                    eps: self.config.solver.eps,
                };
                let found = problem.solve(pair, input, cache, &mut self.scratch)?;
                let s_m = found.input.position.track_s_m;
                self.transient.steady(found.tractions, s_m);
                (found.input, found.solution, Some(found.vpitch))
            }
            _ if matches!(self.config.digits.tang, 1 | 2) => {
                let digits = &self.config.digits;
                let start = self.transient.history(digits.pvtime, digits.tang);
                let mut warm = WarmStart::default();
                warm.tractions[side.index()] = start.clone();
                let sol = solve_wheelset_warm(pair, &input, cache, &mut self.scratch, &mut warm)
                    .map_err(CntcError::from_wheelrail)?;
                self.transient
                    .advance(start, warm.tractions[side.index()].take());
                (input, sol, None)
            }
            _ => {
                let mut warm = WarmStart::default();
                let sol = solve_wheelset_warm(pair, &input, cache, &mut self.scratch, &mut warm)
                    .map_err(CntcError::from_wheelrail)?;
                let tractions = warm.tractions[side.index()].take();
                self.transient.steady(tractions, input.position.track_s_m);
                (input, sol, None)
            }
        };
        if let Some(rail) = massless {
            self.check_balance(side, &rail, &sol)?;
        }
        let ierror = self.finish(side, &input, &sol)?;
        if let Some(sv) = &mut self.solved {
            sv.vpitch_found = vpitch_found;
        }
        Ok(ierror)
    }

    /// Places the profiles when the pair held does not fit.
    fn place_pair(&mut self, side: Side) -> Result<()> {
        if !self.pair.as_ref().is_some_and(|p| self.fits(p, side)) {
            let pair = self.build_pair(side, self.rail_deflection);
            self.pair_before = None;
            self.pair = Some(pair?);
            self.pair_track_s_m = Some(self.position[0]);
            self.pair_pitch_rad = Some(self.position[5]);
        }
        Ok(())
    }

    /// F = 3: the massless rail's deflection for `input`, iterated with the
    /// rail placed at each lateral deflection tried (from the last
    /// deflection with I = 1, else from none), then the pair placed with
    /// it.
    fn deflect_rail(
        &mut self,
        side: Side,
        rail: &MasslessRail,
        input: &WheelRailInput,
        cache: &KernelCache,
    ) -> Result<()> {
        let start = if self.config.digits.iestim >= 1 {
            self.rail_deflection
        } else {
            RailDeflection::default()
        };
        let mut scratch = std::mem::take(&mut self.scratch);
        // A pair that cannot be placed stops the iteration with its own
        // error.
        let mut place_error = None;
        let place = |dy: f64| {
            let d = RailDeflection {
                lateral_m: dy,
                vertical_m: 0.0,
            };
            self.build_pair(side, d).map_err(|e| {
                place_error = Some(e);
                WheelRailError::Cancelled
            })
        };
        let found = solve_on_massless_rail(place, input, rail, start, cache, &mut scratch);
        self.scratch = scratch;
        if let Some(e) = place_error {
            return Err(e);
        }
        let found = found.map_err(|e| match e {
            MasslessRailError::Contact(e) => CntcError::from_wheelrail(e),
            MasslessRailError::Invalid { .. } => CntcError::Input(e.to_string()),
            MasslessRailError::NotConverged { .. } | MasslessRailError::OutOfReach(_) => {
                CntcError::ForceIteration(e.to_string())
            }
        })?;
        self.rail_deflection = found.deflection;
        self.place_pair(side)
    }

    /// F = 3: the balances of the rail's springs with the wheel's force of
    /// `sol`, solved on the rail placed with the deflections, to
    /// [`MASSLESS_RAIL_PLACED_TOLERANCE`] of the force scale (the vertical
    /// one when KZRAIL > 0); the iteration's rail was placed without them.
    fn check_balance(
        &self,
        side: Side,
        rail: &MasslessRail,
        sol: &WheelRailSolution,
    ) -> Result<()> {
        let f = sol
            .wheels
            .iter()
            .find(|w| w.side == side)
            .map_or([0.0; 3], |w| w.force_track_n);
        let [ry, rz] = rail.residuals_n(self.rail_deflection, [f[1], f[2]]);
        let rz = if rail.vertical_stiffness_n_per_m > 0.0 {
            rz
        } else {
            0.0
        };
        let tolerance = MASSLESS_RAIL_PLACED_TOLERANCE * rail.force_scale_n(f[2]);
        if ry.abs().max(rz.abs()) > tolerance {
            return Err(CntcError::ForceIteration(format!(
                "massless rail: on the rail placed with the deflections found (DY_DEFL {} m, \
                 DZ_DEFL {} m) the balances miss by {ry} N (lateral) and {rz} N (vertical), \
                 beyond {tolerance} N: the contact jumps with a shift of the rail here",
                self.rail_deflection.lateral_m, self.rail_deflection.vertical_m
            )));
        }
        Ok(())
    }

    /// The wheel deflected by the flexible wheelset deviations (E = 4, 5)
    /// on the wheelset rolled and yawed by CONTACT's `roll`, `yaw`; `None`
    /// without deviations (all zero: the undeflected wheel, bit for bit).
    fn flexed_wheel(&self, side: Side, roll: f64, yaw: f64) -> Result<Option<FlexedWheel>> {
        if self.flexibility.iter().all(|v| *v == 0.0) {
            return Ok(None);
        }
        let dims = slot(&self.wheelset, "the wheelset dimensions have not been set")?;
        let wheel = slot(&self.wheel, "the wheel profile has not been set")?;
        let pair = self.pair.as_ref().ok_or_else(|| {
            CntcError::Other("the profiles are placed before the deviations".into())
        })?;
        let r_marker = dims.nominal_radius_m + self.tape_shift(wheel)?;
        Ok(Some(FlexedWheel::new(
            side,
            roll,
            yaw,
            pair.wheel(side).axial_offset_m(),
            r_marker,
            &self.flexibility,
        )))
    }

    /// The solver's input of this problem.
    fn solver_input(&self, side: Side) -> Result<WheelRailInput> {
        let d = self.discretisation.ok_or_else(|| {
            CntcError::Discretisation(
                "the discretisation has not been set: cntc_setpotcontact with icp = -1, IPOTCN = -1 \
                 (DX, DS, A_SEP, D_SEP, D_COMB)"
                    .into(),
            )
        })?;
        let u = self.units();
        if (d.dx_m - d.ds_m).abs() > 1e-6 * d.dx_m.max(d.ds_m) {
            return Err(CntcError::NotSupported(format!(
                "DX = {}, DS = {} (cntc_setpotcontact): the patch grids have square elements; give \
                 DX = DS",
                u.len_out(d.dx_m),
                u.len_out(d.ds_m)
            )));
        }
        if !(1e-6..5e-3).contains(&d.dx_m) {
            return Err(CntcError::Discretisation(format!(
                "DX = DS = {} (cntc_setpotcontact) must lie between {} and {}",
                u.len_out(d.dx_m),
                u.len_out(1e-6),
                u.len_out(5e-3)
            )));
        }
        let dims = slot(&self.wheelset, "the wheelset dimensions have not been set")?;
        let [s_ws, y_ws, z_ws, roll, yaw, _pitch] = self.position;
        let [vs, vy, vz, vroll, vyaw, vpitch] = self.velocity;
        let roller = self.is_roller();
        if roller {
            self.check_roller(s_ws)?;
        } else if vs == 0.0 {
            return Err(CntcError::NotSupported(format!(
                "VS_WS = {} (cntc_setwheelsetvelocity): the wheelset must roll (> 0 forwards, \
                 < 0 backwards): the creepages are divided by the rolling speed",
                u.velocity_out(vs)
            )));
        }
        // The reference speed of the friction laws: the forward speed's
        // size, on a roller its surface speed's at the nominal radius.
        let v_ref = if roller {
            self.roller_rad_per_s * track_roller_radius(&self.track)
        } else {
            vs
        }
        .abs();
        let load = if self.config.digits.norm == 1 {
            let fz = self.vertical_force_n.ok_or_else(|| {
                CntcError::Input("N = 1 needs the vertical force: cntc_setverticalforce".into())
            })?;
            if fz <= 0.0 {
                return Err(CntcError::Input(format!(
                    "FZ = {fz} N (cntc_setverticalforce) must be > 0"
                )));
            }
            WheelLoad::VerticalForce(fz)
        } else {
            WheelLoad::CenterHeight(z_ws - dims.nominal_radius_m)
        };
        let material = self.config.material.combined()?;
        let start = self.config.solver.start;
        let (friction, friction_table) = match &self.config.friction_by_angle {
            None => (self.config.friction.friction(v_ref, start), None),
            Some((angles, laws)) => friction_by_angle(angles, laws, v_ref, start)?,
        };
        let o = SolverOrientation::of(roll, yaw, vroll, vyaw, vpitch);
        let mut position = WheelsetPosition {
            lateral_m: y_ws,
            yaw_rad: o.yaw_rad,
            roll_rad: Some(o.roll_rad),
            // X_WS on a roller rig (zero, checked), not a track position.
            track_s_m: if roller { 0.0 } else { s_ws },
        };
        let mut velocity = WheelsetVelocity {
            forward_m_per_s: vs,
            lateral_m_per_s: vy,
            vertical_m_per_s: vz,
            roll_rad_per_s: o.roll_rate,
            yaw_rad_per_s: o.yaw_rate,
            pitch_rad_per_s: Some(o.pitch_rate),
        };
        let mut load = load;
        if let Some(fw) = self.flexed_wheel(side, roll, yaw)? {
            // The deflected wheel as the solver's wheelset: its axis
            // through the wheelset centre moved by center_rel, its rigid
            // motion CONTACT's wheelset motion plus the deviations' rates.
            let s = side.sign();
            let (roll_w, yaw_w) = fw.solver_roll_yaw(side);
            position.lateral_m = y_ws + s * fw.center_rel[1];
            position.roll_rad = Some(roll_w);
            position.yaw_rad = yaw_w;
            if let WheelLoad::CenterHeight(z) = load {
                load = WheelLoad::CenterHeight(z + fw.center_rel[2]);
            }
            let w_ws = add(
                [s * o.roll_rate, 0.0, s * o.yaw_rate],
                scale(o.pitch_rate, fw.ws_axes[1]),
            );
            let [fwd, lat, vert, roll_rate, yaw_rate, pitch] =
                fw.solver_velocity(side, [vs, s * vy, vz], w_ws, &self.flexibility);
            velocity = WheelsetVelocity {
                forward_m_per_s: fwd,
                lateral_m_per_s: lat,
                vertical_m_per_s: vert,
                roll_rad_per_s: roll_rate,
                yaw_rad_per_s: yaw_rate,
                pitch_rad_per_s: Some(pitch),
            };
        }
        // The rail's own motion (Z = 2, 3), taken at the rail's point of
        // each patch by the solver (CONTACT's `wr_creep_cref`).
        let [_, _, _, vy_r, vz_r, vroll_r] = self.rail_deviation;
        let mut rail_motion = [RailMotion::default(); 2];
        rail_motion[side.index()] = RailMotion {
            lateral_m_per_s: vy_r,
            vertical_m_per_s: vz_r,
            roll_rad_per_s: vroll_r,
            roller_rad_per_s: if roller { self.roller_rad_per_s } else { 0.0 },
        };
        let mut rail_slices: [Option<Arc<RailSlices>>; 2] = Default::default();
        if let Some(Ok(rail)) = &self.rail {
            rail_slices[side.index()] = rail.slices.clone();
        }
        let forward_speed = velocity.forward_m_per_s.abs();
        Ok(WheelRailInput {
            position,
            velocity,
            load,
            sides: vec![side],
            material,
            friction,
            friction_table,
            settings: WheelRailSettings {
                model: WheelRailModel::Exact,
                element_size_m: d.dx_m,
                search: SearchSettings {
                    merge_distance_m: d.dist_sep_m,
                    // D_COMB < d <= D_SEP: CONTACT's blended patch.
                    combine_distance_m: Some(d.dist_comb_m),
                    // CONTACT's turning of neighbouring patches' angles.
                    angle_turning: Some(AngleTurning {
                        distance_m: d.dist_turn_m,
                        max_angle_difference_rad: d.angle_sep_rad,
                    }),
                    // CONTACT's reference point: the weighted centre of
                    // the interpenetration, its mean contact angle.
                    reference_point: ReferencePoint::InterpenetrationCentre,
                    ..SearchSettings::default()
                },
                max_grid_elements: self.max_grid_elements.unwrap_or(usize::MAX),
                // CONTACT's elements are DX by DS on every patch.
                min_elements_across: 0,
                exact_tangential: match (self.config.digits.tang, self.config.material.model) {
                    (0, _) => ExactTangential::Frictionless,
                    (1, _) => ExactTangential::Transient(TransientContact::Shift),
                    (2, _) => ExactTangential::Transient(TransientContact::Rolling {
                        rolled_elements: rolled_elements(self.dqrel)?,
                    }),
                    (_, MaterialModel::ModifiedFastsim(material)) => {
                        ExactTangential::Fastsim(material)
                    }
                    (_, MaterialModel::ModifiedFastrip(material)) => {
                        ExactTangential::Fastrip(material)
                    }
                    _ => ExactTangential::Kalker,
                },
                // M = 4: the layer's flexibility in the patches' tangential
                // kernels (the normal problem does not see it), its
                // plasticity in their tangential solvers. M = 1: the
                // viscoelastic bodies in the patches' kernels, rolling at
                // the wheelset's speed (the solver's
                // `wheelrail::viscoelastic_bodies`, which replaces this
                // speed).
                solver: SolverSettings {
                    interfacial_layer: self.config.material.model.layer(),
                    viscoelastic: self.config.material.model.viscoelastic(forward_speed),
                    ..wheelrail_solver_settings()
                },
                ..WheelRailSettings::default()
            },
            total_longitudinal_force_n: None,
            temperature: None,
            rail_motion,
            rail_slices,
        })
    }

    /// The outcomes of a solution and the frames for the getters.
    fn finish(
        &mut self,
        side: Side,
        input: &WheelRailInput,
        sol: &WheelRailSolution,
    ) -> Result<i32> {
        let pair = self.pair.as_ref().expect("solved on it");
        let s = side.sign();
        let dims = *slot(&self.wheelset, "the wheelset dimensions have not been set")?;
        let wheel_in = slot(&self.wheel, "the wheel profile has not been set")?;
        let dr_tape = self.tape_shift(wheel_in)?;
        let Some(wheel) = sol.wheels.iter().find(|w| w.side == side) else {
            return Err(CntcError::Other(format!(
                "the solver returned no result for the {} wheel",
                side.name()
            )));
        };
        // The loaded wheelset (side frame).
        let [_, y_ws, _, roll, yaw, _] = self.position;
        let flexed = self.flexed_wheel(side, roll, yaw)?;
        // The solver's wheelset is the deflected wheel's (its centre
        // center_rel from the wheelset's).
        let shift = flexed.map_or([0.0; 3], |f| f.center_rel);
        let center_z = sol.center_z_m + wheel.vertical_approach_m - shift[2];
        let ws_axes = contact_ws_axes(side, roll, yaw);
        let [_, a, e1] = ws_axes;
        let c = [0.0, s * y_ws, center_z];
        let axial = pair.wheel(side).axial_offset_m();
        let r_marker = dims.nominal_radius_m + dr_tape;
        let (wheel_axes, w_marker, wheel_marker_ws, wheel_angles) = match flexed {
            None => (
                ws_axes,
                add(c, add(scale(axial, a), scale(r_marker, e1))),
                [0.0, s * axial, r_marker, 0.0, 0.0],
                [roll, yaw],
            ),
            Some(f) => {
                let (roll_w, yaw_w) = f.contact_roll_yaw(side);
                let m = f.marker_ws;
                let flex = &self.flexibility;
                (
                    f.axes,
                    add(c, f.marker_rel),
                    [m[0], s * m[1], m[2], flex[3], flex[4]],
                    [roll_w, yaw_w],
                )
            }
        };
        let rail = pair.rail(side);
        let [rq, rz] = rail.to_side(0.0, 0.0);
        let r_marker_pt = [0.0, rq, rz];
        let rail_roll = -rail.inclination_rad();
        // Arc-length origins of the profiles (CONTACT's s = 0).
        let rail_spline = rail.spline();
        let wheel_spline = pair.wheel(side).spline();
        let rail_s0 = arc_origin(rail_spline, 0.0);
        let wheel_s0 = arc_origin(wheel_spline, dr_tape);

        let mut outcomes = Vec::with_capacity(wheel.patches.len());
        let mut globals = Vec::with_capacity(wheel.patches.len());
        let mut border = 0usize;
        for p in &wheel.patches {
            let (mut o, g) = self.patch_outcome(
                p,
                side,
                input,
                PatchFrames {
                    ws_axes,
                    wheel_axes,
                    center: c,
                    w_marker,
                    r_marker: r_marker_pt,
                    rail_roll,
                    wheel_marker_ws,
                    wheel_angles,
                    x_shift_m: shift[0],
                    rail_s0,
                    wheel_s0,
                    rail_spline,
                    wheel_spline,
                    sign: s,
                },
            );
            if o.has_fields() {
                // CONTACT's US of the patch (its getters read the patch's
                // data), computed when a getter asks: u = A p on the
                // patch's grid with the wheel/rail solver's materials (its
                // kernels, a hit of the process cache); the interaction of
                // patches ignored, as CONTACT ignores it.
                // A FASTSIM patch (M = 2, 3): CONTACT's US = FLX(1:2)/K_EFF
                // times the tractions, its normal row from the exact normal
                // problem (B = 0); a frictionless one has no tractions.
                o.displacement_source = Some(match input.settings.exact_tangential {
                    ExactTangential::Fastsim(_) => DisplacementSource::Fastsim {
                        flexibilities_m_per_pa: o.fastsim.map_or([0.0; 2], |a| {
                            let [l1, l2, _] = a.flexibilities_m_per_pa;
                            [l1 / a.slope_factor, l2 / a.slope_factor]
                        }),
                        normal: Some([input.material.body1, input.material.body2]),
                    },
                    ExactTangential::Fastrip(_) => DisplacementSource::WheelRailFastrip,
                    _ => DisplacementSource::Influence {
                        body1: input.material.body1,
                        body2: input.material.body2,
                        layer_flexibility_m_per_pa: input
                            .settings
                            .solver
                            .interfacial_layer
                            .map_or(0.0, |l| l.flexibility_m_per_pa()),
                        // The kernels of the patch's solve.
                        viscoelastic: viscoelastic_bodies(pair, input),
                    },
                });
            }
            border += o.border_elements;
            outcomes.push(o);
            globals.push(g);
        }
        self.outcomes = outcomes;
        self.subs_done = vec![None; self.outcomes.len()];
        self.solved = Some(Solved {
            side,
            ws_axes,
            wheel_turn_rad: [self.flexibility[3], self.flexibility[4]],
            rail_roll_rad: rail_roll,
            z_ws_m: center_z + dims.nominal_radius_m,
            vpitch_found: None,
            globals,
        });
        Ok(border.min(i32::MAX as usize) as i32)
    }

    /// One patch's outcome (CONTACT's reporting frame) and its forces and
    /// moments (side frame).
    fn patch_outcome(
        &self,
        p: &PatchResult,
        side: Side,
        input: &WheelRailInput,
        f: PatchFrames<'_>,
    ) -> (Outcome, [[f64; 3]; 3]) {
        let s = f.sign;
        let left = side == Side::Left;
        let e = input.settings.element_size_m;
        // The contact frame (side frame components): x, s (tangent), n.
        let (st, ct) = p.contact_angle_rad.sin_cos();
        let n = [0.0, st, ct];
        let t = [0.0, ct, -st];
        let ex_c = [1.0, 0.0, 0.0];
        let origin = [p.track_x_m + f.x_shift_m, s * p.track_y_m, p.track_z_m];
        let ft = p.force_track_n;
        let force = [ft[0], s * ft[1], ft[2]];

        // Moments of the tractions about the reference (contact frame),
        // the pressure centre, the grid and its fields.
        let (grid, fields) = match (&p.grid_geometry, &p.solution) {
            (Some(g), Some(sol)) if sol.fields.pressure_pa.len() == g.len() => {
                (*g, Some(&sol.fields))
            }
            (Some(g), _) => (*g, None),
            _ => (
                Grid::new(4, 4, e, e, -2.0 * e, -2.0 * e).unwrap_or(Grid {
                    nx: 4,
                    ny: 4,
                    dx_m: e,
                    dy_m: e,
                    x0_m: -2.0 * e,
                    y0_m: -2.0 * e,
                }),
                None,
            ),
        };
        let (mut ma, mut mb, mut mc) = (0.0, 0.0, p.mz_nm);
        let (mut xc, mut sc) = (0.0, 0.0);
        let mut max_traction: f64 = 0.0;
        if let Some(fl) = fields {
            let da = grid.element_area_m2();
            let (mut sp, mut sxp, mut ssp) = (0.0, 0.0, 0.0);
            mc = 0.0;
            for iy in 0..grid.ny {
                let y = grid.y_m(iy);
                for ix in 0..grid.nx {
                    let x = grid.x_m(ix);
                    let k = grid.index(ix, iy);
                    let (pn, px, py) =
                        (fl.pressure_pa[k], fl.traction_x_pa[k], fl.traction_y_pa[k]);
                    ma += y * pn * da;
                    mb -= x * pn * da;
                    mc += (x * py - y * px) * da;
                    sp += pn;
                    sxp += x * pn;
                    ssp += y * pn;
                    max_traction = max_traction.max(px.hypot(py));
                }
            }
            if sp > 0.0 {
                xc = sxp / sp;
                sc = ssp / sp;
            }
        }
        let m_local = add(add(scale(ma, ex_c), scale(mb, t)), scale(mc, n));
        let m_rail = add(cross(sub(origin, f.r_marker), force), m_local);
        let m_wheel = add(cross(sub(origin, f.w_marker), force), m_local);

        // The outcome, mirrored for a left wheel.
        let (ny, nx) = (grid.ny, grid.nx);
        let out_grid = if left {
            Grid {
                y0_m: -(grid.y0_m + ny as f64 * grid.dy_m),
                ..grid
            }
        } else {
            grid
        };
        let out_fields = fields.map(|fl| {
            if left {
                ElementFields {
                    pressure_pa: mirrored_rows(&fl.pressure_pa, nx, ny, 1.0),
                    traction_x_pa: mirrored_rows(&fl.traction_x_pa, nx, ny, 1.0),
                    traction_y_pa: mirrored_rows(&fl.traction_y_pa, nx, ny, -1.0),
                    slip_x: mirrored_rows(&fl.slip_x, nx, ny, 1.0),
                    slip_y: mirrored_rows(&fl.slip_y, nx, ny, -1.0),
                    state: mirrored(&fl.state, nx, ny),
                    gap_m: mirrored_rows(&fl.gap_m, nx, ny, 1.0),
                }
            } else {
                fl.clone()
            }
        });
        // CONTACT's undeformed distance has its minimum over the grid at 0
        // and its approach PEN is the interpenetration there; the solver's
        // is measured from the wheelset's rigid position, where this wheel
        // may still have a gap (the other wheel touching first).
        let hmin = out_fields
            .as_ref()
            .filter(|f| f.gap_m.len() == out_grid.len())
            .map(|f| f.gap_m.iter().copied().fold(f64::INFINITY, f64::min))
            .filter(|h| h.is_finite())
            .unwrap_or(0.0);
        let mut out_fields = out_fields;
        let frictionless = self.config.digits.tang == 0;
        if let Some(fl) = out_fields.as_mut() {
            fl.gap_m.iter_mut().for_each(|h| *h -= hmin);
            if frictionless {
                // Without friction CONTACT counts the contact area as
                // adhesion (as module 3 does).
                for st in fl.state.iter_mut() {
                    if *st == ElementState::Slip {
                        *st = ElementState::Adhesion;
                    }
                }
            }
        }
        let gap = out_fields
            .as_ref()
            .filter(|f| f.gap_m.len() == out_grid.len())
            .map(|f| f.gap_m.clone())
            .unwrap_or_else(|| vec![0.0; out_grid.len()]);
        // A plastic layer's state (CONTACT's TAUCRT, UPLSX, UPLSY and the
        // plasticity area), mirrored as the fields.
        let layer = p
            .layer
            .as_ref()
            .filter(|l| l.plastic.len() == out_grid.len())
            .map(|l| {
                if left {
                    LayerFields {
                        yield_limit_pa: mirrored_rows(&l.yield_limit_pa, nx, ny, 1.0),
                        plastic_x_m: mirrored_rows(&l.plastic_x_m, nx, ny, 1.0),
                        plastic_y_m: mirrored_rows(&l.plastic_y_m, nx, ny, -1.0),
                        plastic: mirrored(&l.plastic, nx, ny),
                    }
                } else {
                    l.clone()
                }
            });
        let mut o = Outcome::no_contact(out_grid, gap, p.approach_m - hmin);
        if let Some(fl) = out_fields {
            if fl.state.len() == out_grid.len() {
                let plastic = layer.as_ref().map_or(&[][..], |l| &l.plastic);
                o.areas_m2 = Outcome::areas_of(&out_grid, &fl.state, plastic);
            }
            o.border_elements = out_grid.loaded_border_elements(&fl.pressure_pa);
            o.fields = fl;
            o.layer = layer;
        } else {
            o.areas_m2 = Outcome::areas_by_fraction(p.contact_area_m2, p.adhesion_fraction);
        }
        o.friction_coefficient = p.friction_coefficient;
        o.normal_force_n = p.normal_force_n;
        o.fx_n = p.fx_n;
        o.fy_n = s * p.fs_n;
        // Transient contact: CONTACT's spin moment is about the origin of
        // its super-grid (the lattice's), where the reference point lies
        // at (x0, s0).
        let mz = match p.lattice_origin_m {
            Some([x0, s0]) => p.mz_nm + x0 * p.fs_n - s0 * p.fx_n,
            None => p.mz_nm,
        };
        o.mz_nm = s * mz;
        // CONTACT reports zero creepages without a tangential problem.
        o.creepages = if frictionless {
            [0.0; 3]
        } else {
            [p.creepage_long, s * p.creepage_lat, s * p.spin_per_m]
        };
        o.is_shift = self.config.digits.tang == 1;
        o.rolling_speed_m_per_s = p.rolling_speed_m_per_s;
        o.rolling_direction_rad = p.rolling_direction_rad;
        o.max_pressure_pa = p.max_pressure_pa;
        o.max_traction_pa = max_traction;
        o.fastsim = p.fastsim_flexibility;
        o.tgamma_n = if p.rolling_speed_m_per_s > 0.0 {
            p.frictional_power_w / p.rolling_speed_m_per_s
        } else {
            0.0
        };

        // Where the patch lies (CONTACT's reporting frame).
        let delta_tr = -p.contact_angle_rad; // CONTACT's angle, side frame
        let [ex, a, e1] = f.ws_axes;
        let dw = sub(origin, f.w_marker);
        let wheel_pt = in_basis(dw, &f.wheel_axes);
        let n_ws = [dot(n, ex), dot(n, a), dot(n, e1)];
        let delta_ws = (-n_ws[1]).atan2(n_ws[2]);
        let n_w = in_basis(n, &f.wheel_axes);
        let delta_w = (-n_w[1]).atan2(n_w[2]);
        let rail_s = f
            .rail_spline
            .t_at_y(p.rail_y_m)
            .map_or(0.0, |t| t - f.rail_s0);
        let wheel_s = f
            .wheel_spline
            .t_at_y(wheel_pt[1])
            .map_or(0.0, |t| t - f.wheel_s0);
        let pc = add(origin, add(scale(xc, ex_c), scale(sc, t)));
        let dc = sub(origin, f.center);
        o.location = Some(Location {
            track: [origin[0], s * origin[1], origin[2], s * delta_tr],
            rail: [
                origin[0],
                s * p.rail_y_m,
                p.rail_z_m,
                rail_s,
                s * (delta_tr - f.rail_roll),
            ],
            wheel: [
                wheel_pt[0],
                s * wheel_pt[1],
                wheel_pt[2],
                wheel_s,
                s * delta_w,
            ],
            pressure_centre: [pc[0], s * pc[1]],
            wheel_marker_track: [
                f.w_marker[0],
                s * f.w_marker[1],
                f.w_marker[2],
                f.wheel_angles[0],
                f.wheel_angles[1],
            ],
            rail_marker_track: [s * f.r_marker[1], f.r_marker[2], s * f.rail_roll],
            wheelset: [dot(dc, ex), s * dot(dc, a), dot(dc, e1), s * delta_ws],
            wheel_marker_wheelset: f.wheel_marker_ws,
            force_track_n: p.force_track_n,
            rail_deflection_m: [
                self.rail_deflection.lateral_m,
                self.rail_deflection.vertical_m,
            ],
        });
        (o, [force, m_rail, m_wheel])
    }

    // -----------------------------------------------------------------
    // Getters.

    /// `cntc_getgriddiscretization` with icp = -1: DX, DS in the caller's
    /// units.
    pub fn grid_size(&self) -> Result<[f64; 2]> {
        let d = self.discretisation.ok_or_else(|| {
            CntcError::Discretisation(
                "the discretisation has not been set: cntc_setpotcontact with icp = -1".into(),
            )
        })?;
        let u = self.units();
        Ok([u.len_out(d.dx_m), u.len_out(d.ds_m)])
    }

    /// The inputs an input file may leave as they are: the wheelset's
    /// height Z_WS \[m\] (given under N = 0) and pitch rate VPITCH
    /// \[rad/s\] (given under F = 0), as last set.
    pub fn held_z_and_vpitch(&self) -> (f64, f64) {
        (self.position[2], self.velocity[5])
    }

    /// `cntc_getwheelsetposition`: s, y, z, roll, yaw, pitch (caller's units).
    /// After a calculation with a vertical force (N = 1), z is the height
    /// found.
    pub fn wheelset_position(&self) -> Result<[f64; 6]> {
        let u = self.units();
        let [s, y, mut z, roll, yaw, pitch] = self.position;
        if self.config.digits.norm == 1 {
            if let Some(sv) = &self.solved {
                z = sv.z_ws_m;
            }
        }
        Ok([u.len_out(s), u.len_out(y), u.len_out(z), roll, yaw, pitch])
    }

    /// `cntc_getwheelsetvelocity`: vs, vy, vz, vroll, vyaw, vpitch.
    pub fn wheelset_velocity(&self) -> Result<[f64; 6]> {
        let u = self.units();
        let [vs, vy, vz, vr, vyaw, mut vp] = self.velocity;
        if let Some(found) = self.solved.as_ref().and_then(|sv| sv.vpitch_found) {
            vp = found;
        }
        Ok([
            u.velocity_out(vs),
            u.velocity_out(vy),
            u.velocity_out(vz),
            vr,
            vyaw,
            vp,
        ])
    }

    /// `cntc_getglobalforces` of patch `icp` (or all, `None`): the 24
    /// values in the caller's units.
    pub fn global_forces(&self, icp: Option<usize>) -> Result<[f64; 24]> {
        let Some(sv) = &self.solved else {
            return Err(CntcError::Input(
                "cntc_getglobalforces: no results; call cntc_calculate first".into(),
            ));
        };
        let zero = [[0.0; 3]; 3];
        let [f, mr, mw] = match icp {
            None => sv.globals.iter().fold(zero, |acc, g| {
                [add(acc[0], g[0]), add(acc[1], g[1]), add(acc[2], g[2])]
            }),
            // CONTACT: zeros for a patch number beyond the last
            // calculation's.
            Some(k) => sv.globals.get(k.wrapping_sub(1)).copied().unwrap_or(zero),
        };
        let u = self.units();
        let b = u.body_sign();
        let s = sv.side.sign();
        let l = |m: f64| u.len_out(m);
        let (sr, cr) = sv.rail_roll_rad.sin_cos();
        let rail_axes = [[1.0, 0.0, 0.0], [0.0, cr, sr], [0.0, -sr, cr]];
        let f_ws = in_basis(f, &sv.ws_axes);
        let mw_ws = in_basis(mw, &sv.ws_axes);
        // The wheel's axes: the wheelset's, turned by DROLLW and DYAWW.
        let wheel_axes = match sv.wheel_turn_rad {
            [0.0, 0.0] => sv.ws_axes,
            [droll, dyaw] => turned(&sv.ws_axes, &contact_ws_axes(sv.side, droll, dyaw)),
        };
        let f_w = in_basis(f, &wheel_axes);
        let mw_w = in_basis(mw, &wheel_axes);
        let f_r = in_basis(f, &rail_axes);
        let mr_r = in_basis(mr, &rail_axes);
        let mut v = [0.0; 24];
        let block = |v: &mut [f64], fv: [f64; 3], mv: [f64; 3]| {
            v[0] = b * fv[0];
            v[1] = b * s * fv[1];
            v[2] = b * fv[2];
            v[3] = b * s * l(mv[0]);
            v[4] = b * l(mv[1]);
            v[5] = b * s * l(mv[2]);
        };
        block(&mut v[0..6], f, mr);
        block(&mut v[6..12], f_ws, mw_ws);
        block(&mut v[12..18], f_r, mr_r);
        block(&mut v[18..24], f_w, mw_w);
        Ok(v)
    }

    // -----------------------------------------------------------------
    // Subsurface stresses.

    fn check_subs_icp(icp: i32, call: &str) -> Result<()> {
        if icp == -1 || (1..=MAX_ICP).contains(&icp) {
            Ok(())
        } else {
            Err(CntcError::Icp(format!(
                "{call}: icp = {icp}: -1 (every patch) or a contact patch 1 to {MAX_ICP}"
            )))
        }
    }

    /// `subs_addblock` for patch `icp` (-1: every patch without its own).
    pub fn subs_add(
        &mut self,
        icp: i32,
        iblk: i32,
        isubs: i32,
        x: &[f64],
        y: &[f64],
        z: &[f64],
    ) -> Result<()> {
        Self::check_subs_icp(icp, "subs_addblock")?;
        let u = self.units();
        if icp == -1 {
            self.subs_all.add(u, iblk, isubs, x, y, z)
        } else {
            self.subs_patch
                .entry(icp)
                .or_default()
                .add(u, iblk, isubs, x, y, z)
        }
    }

    /// `subs_calculate` for patch `icp` (-1: all).
    pub fn subs_calculate(&mut self, icp: i32) -> Result<()> {
        Self::check_subs_icp(icp, "subs_calculate")?;
        let n = self.outcomes.len();
        if self.subs_done.len() != n {
            self.subs_done = vec![None; n];
        }
        let which: Vec<usize> = if icp == -1 {
            (1..=n).collect()
        } else if (icp as usize) <= n {
            vec![icp as usize]
        } else {
            return Err(CntcError::Icp(format!(
                "subs_calculate: icp = {icp}: the last calculation found {n} contact patch(es)"
            )));
        };
        let material = self.config.material.combined()?;
        for k in which {
            let mut blocks = self
                .subs_patch
                .get(&(k as i32))
                .cloned()
                .unwrap_or_else(|| self.subs_all.clone());
            // The outcome is in CONTACT's reporting frame already (a left
            // wheel's grid mirrored), where the blocks' points are given.
            blocks.calculate_with(&self.outcomes[k - 1], &material, false)?;
            self.subs_done[k - 1] = Some(blocks);
        }
        Ok(())
    }

    /// The blocks computed below patch `icp` (-1: the first patch).
    fn subs_of(&self, icp: i32, call: &str) -> Result<&Blocks> {
        Self::check_subs_icp(icp, call)?;
        let k = if icp == -1 { 1 } else { icp as usize };
        self.subs_done
            .get(k - 1)
            .and_then(|b| b.as_ref())
            .ok_or_else(|| {
                CntcError::Input(format!(
                    "{call}: no subsurface stresses for patch {k}: call subs_calculate after \
                     cntc_calculate"
                ))
            })
    }

    /// `subs_getblocksize` of block `iblk` of patch `icp`.
    pub fn subs_block_size(&self, icp: i32, iblk: i32) -> Result<[usize; 3]> {
        self.subs_of(icp, "subs_getblocksize")?.block_size(iblk)
    }

    /// `subs_getresults`: columns `icol` of block `iblk` of patch `icp`.
    pub fn subs_results(&self, icp: i32, iblk: i32, icol: &[i32]) -> Result<Vec<f64>> {
        self.subs_of(icp, "subs_getresults")?
            .results(self.units(), iblk, icol)
    }

    // -----------------------------------------------------------------
    // Profiles.

    /// `cntc_getprofilevalues`: a profile as a table of values (of a
    /// variable rail, its profile at the wheelset's position S). Tasks -1
    /// (error code), 0 (number of points), 1 (y, z in profile coordinates),
    /// 2 (y, z in track coordinates), 4 (arc length s), 5 (surface
    /// inclination); sampling ISAMPL -1, 0 (the profile's points), 1
    /// (every DS_OUT \[mm\]), 2-100 (points per interval). Lengths in mm
    /// (CONTACT: no unit conversion for profile values).
    pub fn profile_values(&self, itask: i32, iparam: &[i32], rparam: &[f64]) -> Result<Vec<f64>> {
        const CALL: &str = "cntc_getprofilevalues";
        let kind = if ip(iparam, 1, 0) >= 1 {
            ProfileKind::Wheel
        } else {
            ProfileKind::Rail
        };
        let slot = match kind {
            ProfileKind::Rail => &self.rail,
            ProfileKind::Wheel => &self.wheel,
        };
        if itask == -1 {
            return Ok(match slot {
                Some(Ok(_)) => vec![0.0, 0.0],
                None => vec![flags::err::PROFIL as f64, 1.0],
                Some(Err(_)) => vec![flags::err::PROFIL as f64, -1.0],
            });
        }
        let prf = match slot {
            Some(Ok(p)) => p,
            Some(Err(e)) => {
                return Err(CntcError::Profile(format!(
                    "{CALL}: the {kind} profile could not be loaded: {e}"
                )))
            }
            None => {
                return Err(CntcError::Profile(format!(
                    "{CALL}: no {kind} profile has been set"
                )))
            }
        };
        // A variable rail: its profile at the wheelset's position S.
        let prf = &*self.at_wheelset(prf)?;
        match itask {
            0..=2 | 4 | 5 => {}
            3 => {
                return Err(CntcError::NotSupported(format!(
                    "{CALL}: task 3 (gauge point data) is not supported"
                )))
            }
            6..=9 => {
                return Err(CntcError::NotSupported(format!(
                    "{CALL}: task {itask} needs a variable profile (slices files are not supported)"
                )))
            }
            t => {
                return Err(CntcError::Input(format!(
                    "{CALL}: ITASK = {t} does not exist (-1 to 9)"
                )))
            }
        }
        let spline = prf.spline()?;
        let knots = spline.knot_arc_lengths_m();
        let (t0, t1) = (knots[0], knots[knots.len() - 1]);
        let mut isampl = ip(iparam, 2, 0).clamp(-1, 100);
        let ds_out = rp(rparam, 1, 1.0);
        if isampl == 1 && !(ds_out.is_finite() && ds_out >= 1e-4) {
            isampl = 0;
        }
        // Arc lengths of the samples.
        let ts: Vec<f64> = match isampl {
            -1 | 0 => knots.to_vec(),
            1 => {
                let ds = ds_out * MM;
                let n = ((t1 - t0) / ds).floor() as usize + 1;
                (0..n).map(|i| t0 + i as f64 * ds).collect()
            }
            k => {
                let k = k as usize;
                let mut v = vec![t0];
                for w in knots.windows(2) {
                    for j in 1..=k {
                        v.push(w[0] + (w[1] - w[0]) * j as f64 / k as f64);
                    }
                }
                v
            }
        };
        let npnt = ts.len();
        if itask == 0 {
            return Ok(vec![npnt as f64]);
        }
        let pts: Vec<[f64; 2]> = if isampl == -1 && prf.profile.len() == npnt {
            prf.profile.points().to_vec()
        } else {
            ts.iter().map(|t| spline.position(*t)).collect()
        };
        let mm = |v: f64| v / MM;
        match itask {
            1 => Ok(pts
                .iter()
                .map(|p| mm(p[0]))
                .chain(pts.iter().map(|p| mm(p[1])))
                .collect()),
            2 => {
                let track = self.profile_in_track(kind, &pts)?;
                Ok(track
                    .iter()
                    .map(|p| mm(p[0]))
                    .chain(track.iter().map(|p| mm(p[1])))
                    .collect())
            }
            4 => {
                let s0 = arc_origin(&spline, 0.0);
                Ok(ts.iter().map(|t| mm(t - s0)).collect())
            }
            _ => Ok(ts
                .iter()
                .map(|t| {
                    let d = spline.tangent(*t);
                    d[1].atan2(d[0])
                })
                .collect()),
        }
    }

    /// Profile points (y, z) \[m\] of `kind` in track coordinates (y of the
    /// actual side, z down): the rail as placed on the track, the wheel at
    /// the wheelset's position (the height found by the last calculation
    /// with N = 1, else the one given).
    fn profile_in_track(&self, kind: ProfileKind, pts: &[[f64; 2]]) -> Result<Vec<[f64; 2]>> {
        let side = self.side()?;
        let s = side.sign();
        let built;
        let pair = match &self.pair {
            Some(p) if self.fits(p, side) => p,
            _ => {
                built = self.build_pair(side, self.rail_deflection)?;
                &built
            }
        };
        match kind {
            ProfileKind::Rail => {
                let rail = pair.rail(side);
                Ok(pts
                    .iter()
                    .map(|p| {
                        let [q, z] = rail.to_side(p[0], p[1]);
                        [s * q, z]
                    })
                    .collect())
            }
            ProfileKind::Wheel => {
                let dims = slot(&self.wheelset, "the wheelset dimensions have not been set")?;
                let wheel = slot(&self.wheel, "the wheel profile has not been set")?;
                let dr_tape = self.tape_shift(wheel)?;
                let [_, y_ws, z_in, roll, yaw, _] = self.position;
                let z_ws = match (&self.solved, self.config.digits.norm) {
                    (Some(sv), 1) => sv.z_ws_m,
                    _ => z_in,
                };
                let [_, a, e1] = contact_ws_axes(side, roll, yaw);
                let w = add(
                    [0.0, s * y_ws, z_ws - dims.nominal_radius_m],
                    add(
                        scale(pair.wheel(side).axial_offset_m(), a),
                        scale(dims.nominal_radius_m + dr_tape, e1),
                    ),
                );
                Ok(pts
                    .iter()
                    .map(|p| {
                        let q = add(w, add(scale(p[0], a), scale(p[1], e1)));
                        [s * q[1], q[2]]
                    })
                    .collect())
            }
        }
    }
}

/// CONTACT's wheelset orientation as the solver's. CONTACT rolls the
/// wheelset about the track's x axis, then yaws it about its own rolled
/// vertical axis (R = Rx(roll) Rz(yaw)); the solver yaws about the track's
/// vertical axis (R = Rz(yaw') Rx(roll')). A wheel is a body of revolution:
/// only its axle's direction counts, so (roll', yaw') are chosen to give
/// CONTACT's axle (-sin yaw, cos yaw cos roll, cos yaw sin roll):
/// sin roll' = cos yaw sin roll, sin yaw' = sin yaw / cos roll'. The
/// rotation rates likewise: CONTACT's angular velocity (roll rate) e_x +
/// (yaw rate) Rx(roll) e_z + (pitch rate) a is the solver's (roll', 0,
/// yaw') + pitch' a with pitch' - pitch = -(yaw rate) sin roll / a_y.
#[derive(Debug, Clone, Copy, PartialEq)]
struct SolverOrientation {
    roll_rad: f64,
    yaw_rad: f64,
    roll_rate: f64,
    yaw_rate: f64,
    pitch_rate: f64,
}

impl SolverOrientation {
    fn of(roll: f64, yaw: f64, vroll: f64, vyaw: f64, vpitch: f64) -> Self {
        let (sr, cr) = roll.sin_cos();
        let (sy, cy) = yaw.sin_cos();
        let a = [-sy, cy * cr, cy * sr];
        let roll_p = (cy * sr).clamp(-1.0, 1.0).asin();
        let yaw_p = (sy / roll_p.cos()).clamp(-1.0, 1.0).asin();
        let d = -vyaw * sr / a[1];
        SolverOrientation {
            roll_rad: roll_p,
            yaw_rad: yaw_p,
            roll_rate: vroll - d * a[0],
            yaw_rate: vyaw * cr - d * a[2],
            pitch_rate: vpitch + d,
        }
    }
}

/// F = 1: the pitch rate VPITCH at which the wheel's total force on the
/// rail along the wheelset's longitudinal axis (CONTACT's FX_WS) is the one
/// prescribed, found as the solver finds a wheelset's for a prescribed
/// total longitudinal force ([`decreasing_root`] on the nominal
/// longitudinal creepage xi0 = -(VS + VPITCH r0) / |VS|, each step a solve of
/// the wheel at its vertical force), from the VPITCH given; to within
/// max(EPS, the tangential tolerance) of mu FZ, as CONTACT's EPS mu FZ.
struct PitchProblem {
    side: Side,
    /// The wheelset's longitudinal axis in the side frame.
    axis: [f64; 3],
    target_n: f64,
    /// The caller's VPITCH, the first estimate \[rad/s\].
    vpitch: f64,
    nominal_radius_m: f64,
    eps: f64,
}

impl PitchProblem {
    /// Step limit (as the solver's).
    const MAX_ITERATIONS: usize = 60;

    /// FX_WS of a solution \[N\].
    fn force_n(&self, sol: &WheelRailSolution) -> f64 {
        let s = self.side.sign();
        sol.wheels
            .iter()
            .filter(|w| w.side == self.side)
            .map(|w| {
                let f = w.force_track_n;
                dot([f[0], s * f[1], f[2]], self.axis)
            })
            .sum()
    }

    /// The solution at the pitch rate found.
    fn solve(
        &self,
        pair: &WheelRailPair,
        input: WheelRailInput,
        cache: &KernelCache,
        scratch: &mut SearchScratch,
    ) -> Result<PitchFound> {
        // The speed of the nominal creepage: on a roller rig the roller's
        // surface speed at its nominal radius (the wheelset stands).
        let v = nominal_rolling_speed(pair, &input);
        let r0 = self.nominal_radius_m;
        // The solver's pitch rate is VPITCH plus a term of the roll and yaw
        // rates (SolverOrientation), which does not depend on VPITCH.
        let offset = input.velocity.pitch_rad_per_s.unwrap_or(0.0) - self.vpitch;
        // xi0 = -(V + VPITCH r0) / |V| (the solver's nominal creepage,
        // either way of rolling).
        let vpitch_of = |xi0: f64| -(v + xi0 * v.abs()) / r0;
        let xi_start = -(v + self.vpitch * r0) / v.abs();
        let xi_start = if (-0.5..=0.5).contains(&xi_start) {
            xi_start
        } else {
            0.0
        };
        // Each solve cold (the root is the same whatever the order of
        // solves), keeping its tractions for a transient step after it.
        let at = |xi0: f64, scratch: &mut SearchScratch| -> Result<_> {
            let mut inp = input.clone();
            inp.velocity.pitch_rad_per_s = Some(vpitch_of(xi0) + offset);
            let mut warm = WarmStart::default();
            let sol = solve_wheelset_warm(pair, &inp, cache, scratch, &mut warm)
                .map_err(CntcError::from_wheelrail)?;
            let tractions = warm.tractions[self.side.index()].take();
            Ok((self.force_n(&sol) - self.target_n, (inp, sol, tractions)))
        };
        let (r0_force, first) = at(xi_start, scratch)?;
        let patches = || first.1.wheels.iter().flat_map(|w| &w.patches);
        let normal: f64 = patches().map(|p| p.normal_force_n).sum();
        let limit: f64 = patches()
            .map(|p| p.friction_coefficient * p.normal_force_n)
            .sum();
        if self.target_n.abs() >= limit {
            return Err(CntcError::ForceIteration(format!(
                "FX_WS = {} N is at or beyond saturation mu FN = {} N (FN = {} N): no pitch \
                 rate gives it",
                self.target_n, limit, normal
            )));
        }
        // Kalker's linear slope of the wheel's patches, as the solver's.
        let g = input.material.shear_modulus_pa;
        let area: f64 = patches().map(|p| p.contact_area_m2).sum();
        let settings = RootSettings {
            tolerance: self.eps.max(pitch_force_tolerance(&input.settings)) * limit,
            max_iterations: Self::MAX_ITERATIONS,
            slope: -g * area / std::f64::consts::PI * 4.0,
        };
        let root = decreasing_root(
            xi_start,
            r0_force,
            first,
            settings,
            Range::closed(-1.0, 1.0, ""),
            |xi0| at(xi0, scratch),
        )
        .map_err(|e| match e {
            RootError::Eval(e) => e,
            RootError::OutOfRange { next } => CntcError::ForceIteration(format!(
                "FX_WS = {} N is out of reach with this motion: the nominal longitudinal \
                 creepage would leave [-1, 1] (last {next})",
                self.target_n
            )),
        })?;
        if root.end != RootEnd::Converged {
            return Err(CntcError::ForceIteration(format!(
                "FX_WS = {} N not reached in {} solves ({:?}): the last gave {} N",
                self.target_n,
                root.evaluations,
                root.end,
                root.residual + self.target_n
            )));
        }
        let (input, sol, tractions) = root.state;
        Ok(PitchFound {
            input,
            solution: sol,
            vpitch: vpitch_of(root.x),
            tractions,
        })
    }
}

/// What [`PitchProblem::solve`] found.
struct PitchFound {
    /// The input at the pitch rate found.
    input: WheelRailInput,
    solution: WheelRailSolution,
    /// VPITCH \[rad/s\].
    vpitch: f64,
    /// The wheel's tractions, the history of a transient step after it.
    tractions: Option<PatchTractions>,
}

/// CONTACT's wheelset axes (forward, axle, down) in the side frame of
/// `side` for roll and yaw of the actual track frame: the columns of
/// Rx(s roll) Rz(s yaw).
fn contact_ws_axes(side: Side, roll: f64, yaw: f64) -> [[f64; 3]; 3] {
    let s = side.sign();
    let (sr, cr) = (s * roll).sin_cos();
    let (sy, cy) = (s * yaw).sin_cos();
    [
        [cy, sy * cr, sy * sr],
        [-sy, cy * cr, cy * sr],
        [0.0, -sr, cr],
    ]
}

/// The frames a patch's location is computed in (side frame).
struct PatchFrames<'a> {
    ws_axes: [[f64; 3]; 3],
    /// The wheel profile's axes (the wheelset's turned by DROLLW, DYAWW).
    wheel_axes: [[f64; 3]; 3],
    center: [f64; 3],
    w_marker: [f64; 3],
    r_marker: [f64; 3],
    rail_roll: f64,
    /// The wheel marker in wheelset coordinates (CONTACT's reporting
    /// frame): x, y, z \[m\], roll, yaw \[rad\].
    wheel_marker_ws: [f64; 5],
    /// The wheel marker's roll and yaw in the track \[rad\].
    wheel_angles: [f64; 2],
    /// The solver's x of the wheel (the wheel's axis placed at x = 0)
    /// less the track's \[m\]: added to the solver's x.
    x_shift_m: f64,
    rail_s0: f64,
    wheel_s0: f64,
    rail_spline: &'a ProfileSpline,
    wheel_spline: &'a ProfileSpline,
    sign: f64,
}

/// The wheel of one side in the side frame with CONTACT's flexible
/// wheelset deviations (`wr_set_wheel_marker`): its profile marker at
/// (DXWHL, FBDIST/2 - FBPOS + DYWHL, r_nom + dr_tape + DZWHL) of the
/// wheelset (DYWHL a wheelset y: mirrored on the left), its axes the
/// wheelset's turned by Rx(DROLLW) Rz(DYAWW) about the marker (DPITCHW
/// turns a round wheel onto itself). The solver takes the wheel as a
/// wheelset pose: the wheel's axis through `center_rel` with the
/// profile's y = 0 at `axial` along it, as an undeflected wheel's axis runs
/// through the wheelset centre.
#[derive(Debug, Clone, Copy)]
struct FlexedWheel {
    /// Wheelset axes (rows: forward, axle outwards, down), CONTACT's.
    ws_axes: [[f64; 3]; 3],
    /// The wheel's axes, likewise.
    axes: [[f64; 3]; 3],
    /// The profile marker relative to the wheelset centre \[m\].
    marker_rel: [f64; 3],
    /// The marker in wheelset coordinates (side frame) \[m\].
    marker_ws: [f64; 3],
    /// The point of the wheel's axis `axial` inside the profile's y = 0,
    /// relative to the wheelset centre \[m\]: the solver's wheelset centre.
    center_rel: [f64; 3],
}

impl FlexedWheel {
    /// `flex` as stored (SI); `axial` the profile's y = 0 from the
    /// wheelset centre, `r_marker` the marker's radius \[m\].
    fn new(side: Side, roll: f64, yaw: f64, axial: f64, r_marker: f64, flex: &[f64; 12]) -> Self {
        let s = side.sign();
        let ws_axes = contact_ws_axes(side, roll, yaw);
        // The deviation's rotation in wheelset coordinates has the same
        // form, Rx(s droll) Rz(s dyaw): its columns in the rows.
        let rf = contact_ws_axes(side, flex[3], flex[4]);
        let axes = turned(&ws_axes, &rf);
        let marker_ws = [flex[0], axial + s * flex[1], r_marker + flex[2]];
        let marker_rel = of_basis(marker_ws, &ws_axes);
        let axis_point = sub(marker_rel, scale(r_marker, axes[2]));
        Self {
            ws_axes,
            axes,
            marker_rel,
            marker_ws,
            center_rel: sub(axis_point, scale(axial, axes[1])),
        }
    }

    /// The solver's track-frame roll and yaw of the wheel's axle: its
    /// axle (-sin yaw cos roll, cos yaw cos roll, sin roll) in the side
    /// frame.
    fn solver_roll_yaw(&self, side: Side) -> (f64, f64) {
        let a = self.axes[1];
        let roll = a[2].clamp(-1.0, 1.0).asin();
        let yaw = (-a[0] / roll.cos()).clamp(-1.0, 1.0).asin();
        (side.sign() * roll, side.sign() * yaw)
    }

    /// CONTACT's roll and yaw (track frame) of the wheel marker: Euler
    /// angles of Rx(roll) Rz(yaw), from its axle.
    fn contact_roll_yaw(&self, side: Side) -> (f64, f64) {
        let a = self.axes[1];
        let yaw = (-a[0]).clamp(-1.0, 1.0).asin();
        (side.sign() * a[2].atan2(a[1]), side.sign() * yaw)
    }

    /// The solver's velocity of the wheel (its centre's [forward, lateral,
    /// vertical] \[m/s\] in the track frame, roll, yaw and pitch rates
    /// \[rad/s\]) for the wheelset's velocity `v_ws` (side frame, at its
    /// centre) and angular velocity `w_ws` (side frame) and the
    /// deviations' rates: CONTACT's velocity of a wheel point,
    /// v_ws + w_ws x (Q - c_ws) + R_ws (v_w + w_w x (Q_ws - m)) (its
    /// `wr_creep_cref`), as the solver's rigid motion about the wheel's
    /// own axle.
    fn solver_velocity(
        &self,
        side: Side,
        v_ws: [f64; 3],
        w_ws: [f64; 3],
        flex: &[f64; 12],
    ) -> [f64; 6] {
        let s = side.sign();
        let v_w = of_basis([flex[6], s * flex[7], flex[8]], &self.ws_axes);
        let w_w = of_basis([s * flex[9], flex[11], s * flex[10]], &self.ws_axes);
        let w = add(w_ws, w_w);
        let v = add(
            add(v_ws, cross(w_ws, self.center_rel)),
            add(v_w, cross(w_w, sub(self.center_rel, self.marker_rel))),
        );
        let a = self.axes[1];
        let pitch = w[1] / a[1];
        let rest = sub(w, scale(pitch, a));
        [v[0], s * v[1], v[2], s * rest[0], s * rest[2], pitch]
    }
}

/// V = 1: friction by contact angle as the solver's friction table. The
/// angles are CONTACT's, of the right-hand side (the wheel's contact angle
/// in CONTACT's internal frame, negative at the gauge face); the solver's
/// are positive towards the gauge face: negated. One law's shape holds over
/// the table (the solver scales it to each static coefficient).
fn friction_by_angle(
    angles: &[f64],
    laws: &[FrictionLaw],
    vs: f64,
    start: railcontact_solver::core::friclaw::SlipStart,
) -> Result<(Friction, Option<FrictionTable>)> {
    let first = laws
        .first()
        .ok_or_else(|| CntcError::Friction("V = 1 (cntc_setfrictionmethod) without rows".into()))?;
    let ratio = |l: &FrictionLaw| {
        let f = l.friction(vs, start);
        f.kinetic_coefficient / f.static_coefficient
    };
    let r0 = ratio(first);
    for l in laws {
        let same_kind = std::mem::discriminant(l) == std::mem::discriminant(first);
        if !same_kind || (ratio(l) - r0).abs() > 1e-9 * r0.abs().max(1.0) {
            return Err(CntcError::NotSupported(
                "V = 1 (cntc_setfrictionmethod) with friction laws of different shapes per row: \
                 the rows must share the law and its kinetic/static ratio"
                    .into(),
            ));
        }
    }
    let mut rows: Vec<(f64, f64)> = angles
        .iter()
        .zip(laws)
        .map(|(a, l)| (-a, l.static_coefficient()))
        .collect();
    rows.sort_by(|a, b| a.0.total_cmp(&b.0));
    let table = FrictionTable {
        axis: FrictionAxis::ContactAngle,
        positions: rows.iter().map(|r| r.0).collect(),
        track_s_m: Vec::new(),
        coefficients: rows.iter().map(|r| r.1).collect(),
    };
    Ok((first.friction(vs, start), Some(table)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn z_orientation_of_values() {
        // A rail crown with z down: top (smallest z) inside.
        let rail: Vec<[f64; 2]> = (0..21)
            .map(|i| {
                let y = (i as f64 - 10.0) * 1e-3;
                [y, 2e3 * y * y]
            })
            .collect();
        assert!(!z_points_up(ProfileKind::Rail, &rail));
        let up: Vec<[f64; 2]> = rail.iter().map(|p| [p[0], -p[1]]).collect();
        assert!(z_points_up(ProfileKind::Rail, &up));
    }

    /// `cntc_setprofileinputfname` of `path` with CONTACT's defaults.
    fn set_file(w: &mut WheelRail, path: &str) {
        let content = read_profile_file(path);
        w.set_profile_file(path, content.as_deref(), &[], &[-1, 0, 0], &[1.0, 0.0])
            .unwrap();
    }

    /// The Manchester benchmark's profile files in the repository (the
    /// library reads profiles from files): rail, wheel.
    fn mbench_files() -> (std::path::PathBuf, std::path::PathBuf) {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../solver/profiles");
        (
            dir.join("MBench_UIC60_v3.prr"),
            dir.join("MBench_S1002_v3.prw"),
        )
    }

    /// A wheel/rail problem set up as CONTACT's `python_mbench.py` sets
    /// it up (CONTACT's units), on side `c1` (0 left, 1 right).
    fn mbench(c1: i32) -> WheelRail {
        let (rail, wheel) = mbench_files();
        let mut w = WheelRail::default();
        for (code, value) in [
            (flags::IF_UNITS, flags::UN_CNTC),
            (flags::IC_CONFIG, c1),
            (flags::IC_TANG, 3),
            (flags::IC_PVTIME, 2),
            (flags::IC_NORM, 1),
            (flags::IC_DISCNS, 2),
        ] {
            assert_eq!(w.config.set_flag(1, code, value), None);
        }
        w.config
            .set_material(0, &[0.28, 0.28, 82000.0, 82000.0])
            .unwrap();
        w.config.set_friction(1, 0, &[0.3, 0.3]).unwrap();
        w.set_vertical_force(10000.0).unwrap();
        let pi = std::f64::consts::PI;
        w.set_discretisation(-1, &[0.2, 0.2, pi / 2.0, 8.0, 4.0])
            .unwrap();
        w.set_rolling_step(0.0, 1.0).unwrap();
        let track = [14.0, 0.0, 1435.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
        w.set_track_dimensions(3, &track).unwrap();
        let rail = rail.to_str().expect("utf-8 path");
        set_file(&mut w, rail);
        w.set_wheelset_dimensions(3, &[1360.0, -70.0, 460.0])
            .unwrap();
        let wheel = wheel.to_str().expect("utf-8 path");
        set_file(&mut w, wheel);
        w.set_wheelset_flexibility(1, &[0.0; 12]).unwrap();
        w
    }

    fn close(what: &str, ours: f64, contact: f64, tol: f64) {
        assert!(
            (ours - contact).abs() <= tol,
            "{what}: ours {ours}, CONTACT's {contact} (tolerance {tol})"
        );
    }

    /// A patch solved with FASTSIM (M = 3) gives its displacement
    /// differences as CONTACT's: UX, UY its flexibilities L1/k, L2/k times
    /// the tractions; UN the exact normal problem's, as with M = 0. One
    /// solved with FaStrip (M = 5) refuses them.
    #[test]
    fn displacements_of_fastsim_patches_are_the_flexibilities_times_the_tractions() {
        let cache = KernelCache::default();
        let mut w = mbench(1);
        w.set_wheelset_position(2, &[0.0, 2.5, 0.0, -0.0001457, 0.006, 0.0])
            .unwrap();
        w.set_wheelset_velocity(2, &[2000.0, 0.0, 0.0, 0.0, 0.0, -4.3455627])
            .unwrap();
        w.calculate(&cache).unwrap();
        let exact_un = w.outcomes[0].displacements_m().unwrap()[2].clone();
        w.config
            .set_material(3, &[0.28, 0.28, 82000.0, 82000.0, 1.0, 1.0, 0.0])
            .unwrap();
        w.calculate(&cache).unwrap();
        let o = &w.outcomes[0];
        let a = o.fastsim.expect("FASTSIM's flexibilities");
        let [ux, uy, un] = o.displacements_m().unwrap();
        let f = &o.fields;
        for i in 0..o.grid.len() {
            let l = a.flexibilities_m_per_pa.map(|l| l / a.slope_factor);
            assert_eq!(ux[i], l[0] * f.traction_x_pa[i], "{i}");
            assert_eq!(uy[i], l[1] * f.traction_y_pa[i], "{i}");
        }
        assert!(f.traction_x_pa.iter().any(|p| *p != 0.0));
        // The same normal problem as M = 0's (FASTSIM's tractions do not
        // act back on the pressure; identical bodies do not couple).
        let scale = exact_un.iter().fold(0.0f64, |m, u| m.max(u.abs()));
        assert_eq!(un.len(), exact_un.len());
        for (a, b) in un.iter().zip(&exact_un) {
            assert!((a - b).abs() < 2e-3 * scale, "{a} {b}");
        }
        // FaStrip (M = 5): refused, naming M = 5.
        w.config
            .set_material(5, &[0.28, 0.28, 82000.0, 82000.0, 1.0, 1.0, 0.0])
            .unwrap();
        w.calculate(&cache).unwrap();
        let e = w.outcomes[0].displacements_m().unwrap_err();
        assert_eq!(e.ierror(), crate::flags::err::NOT_SUPPORTED, "{e}");
        assert!(e.detail().contains("M = 5"), "{e}");
    }

    /// Elements that place the same profiles on the same track share one
    /// placed pair, also after their inputs are set again to equal values
    /// (a simulator that sets the track every step); another track gets
    /// its own.
    #[test]
    fn elements_with_equal_profiles_share_their_placed_pair() {
        let cache = KernelCache::default();
        let solve = |w: &mut WheelRail| {
            w.set_wheelset_position(2, &[0.0, 2.5, 0.0, -0.0001457, 0.006, 0.0])
                .unwrap();
            w.set_wheelset_velocity(2, &[2000.0, 0.0, 0.0, 0.0, 0.0, -4.3455627])
                .unwrap();
            w.calculate(&cache).unwrap();
            w.pair.clone().expect("placed")
        };
        let (mut a, mut b) = (mbench(1), mbench(1));
        let pa = solve(&mut a);
        assert!(Arc::ptr_eq(&pa, &solve(&mut b)));
        // One element alone on its track (gauge 1436 mm): set again to
        // equal values, it keeps its pair although no one else holds it.
        let track = [14.0, 0.0, 1436.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
        b.set_track_dimensions(3, &track).unwrap();
        let pb = solve(&mut b);
        assert!(!Arc::ptr_eq(&pa, &pb));
        let held = Arc::downgrade(&pb);
        drop(pb);
        b.set_track_dimensions(3, &track).unwrap();
        let again = solve(&mut b);
        assert!(Arc::ptr_eq(&held.upgrade().expect("kept"), &again));
        let wider = [14.0, 0.0, 1437.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
        b.set_track_dimensions(3, &wider).unwrap();
        assert!(!Arc::ptr_eq(&again, &solve(&mut b)));
        // The replaced pair is freed once the new one is found.
        drop(again);
        assert!(held.upgrade().is_none());
    }

    /// CONTACT's library, python_mbench.py case 6 of the right wheel
    /// (iwhe = 2: y = 2.5 mm, yaw 6 mrad, tread contact); CONTACT read the
    /// rail from `MBench_UIC60_v3.ban` mirrored, the same profile as the
    /// built-in `.prr` used here.
    #[test]
    fn right_wheel_tread_matches_contact() {
        let mut w = mbench(1);
        w.set_wheelset_position(2, &[0.0, 2.5, 0.0, -0.0001457, 0.006, 0.0])
            .unwrap();
        w.set_wheelset_velocity(2, &[2000.0, 0.0, 0.0, 0.0, 0.0, -4.3455627])
            .unwrap();
        let cache = KernelCache::default();
        assert_eq!(w.calculate(&cache).unwrap(), 0);
        assert_eq!(w.outcomes.len(), 1);
        let u = w.config.units;
        let o = &w.outcomes[0];
        let [fn_, fx, fs, _] = crate::getters::contact_forces(o, u);
        close("FN", fn_, 9786.708448251455, 10.0);
        close("FX", fx, -456.2094255489085, 10.0);
        close("FS", fs, -2900.11251343709, 10.0);
        let [cksi, ceta, cphi] = crate::getters::creepages(o, u);
        close("CKSI", cksi, 0.000960668303628454, 1e-5);
        close("CETA", ceta, 0.006025246165910956, 1e-5);
        close("CPHI", cphi, 0.00018659783767993346, 2e-6);
        close("PEN", u.len_out(o.approach_m), 0.024613233222704107, 2e-4);
        let g = w.global_forces(None).unwrap();
        close("FX_TR", g[0], -456.2094255489085, 10.0);
        close("FY_TR", g[1], -2047.031651446247, 10.0);
        close("FZ_TR", g[2], 9999.99881298233, 1.0);
        close("MX_R_TR", g[3], -199219.16215762054, 500.0);
        let loc = crate::element::location_values(o, u);
        close("YCP_TR", loc[1], 740.4619949606438, 0.1);
        close("DELTCP_TR", loc[3], -0.08617430578329278, 1e-3);
        close("YW_TR", loc[21], 752.5535140797225, 1e-3);
        close("ZW_TR", loc[22], 0.02516892142710958, 1e-3);
        // z_ws puts the wheel marker there: z_ws - r + 750 cos(yaw) sin(roll)
        // + 460 cos(roll).
        let pos = w.wheelset_position().unwrap();
        let (roll, yaw) = (-0.0001457f64, 0.006f64);
        let zw = pos[2] - 460.0 + 750.0 * yaw.cos() * roll.sin() + 460.0 * roll.cos();
        close("Z_WS", zw, loc[22], 1e-9);
    }

    /// CONTACT's library, python_mbench.py case 14 of the right wheel
    /// (y = 6.5 mm, yaw 15.6 mrad): flange contact.
    #[test]
    fn right_wheel_flange_matches_contact() {
        let mut w = mbench(1);
        w.set_wheelset_position(2, &[0.0, 6.5, 0.0, -0.004376, 0.0156, 0.0])
            .unwrap();
        w.set_wheelset_velocity(2, &[2000.0, 0.0, 0.0, 0.0, 0.0, -4.2748834])
            .unwrap();
        let cache = KernelCache::default();
        w.calculate(&cache).unwrap();
        assert_eq!(w.outcomes.len(), 1);
        let u = w.config.units;
        let o = &w.outcomes[0];
        let [fn_, fx, fs, _] = crate::getters::contact_forces(o, u);
        close("FN", fn_, 15440.061402268091, 50.0);
        close("FX", fx, -1986.6680261296483, 40.0);
        close("FS", fs, -4170.188764096686, 40.0);
        let g = w.global_forces(None).unwrap();
        close("FY_TR", g[1], 12481.440988735432, 50.0);
        close("FZ_TR", g[2], 9999.980063916239, 1.0);
        close("MX_R_TR", g[3], -550303.8316066253, 2000.0);
        let loc = crate::element::location_values(o, u);
        close("DELTCP_TR", loc[3], -1.159126112966055, 2e-3);
        close("ZCP_TR", loc[2], 10.365437584972096, 0.05);
    }

    /// CONTACT's library, python_mbench.py case 5 of the left wheel
    /// (iwhe = 1: y = 2 mm, yaw 4.8 mrad): a left wheel is reported in the
    /// track frame (y < 0) with its lateral force and creepages mirrored.
    #[test]
    fn left_wheel_is_mirrored_as_contact_reports_it() {
        let mut w = mbench(0);
        w.set_wheelset_position(2, &[0.0, 2.0, 0.0, -0.0001128, 0.0048, 0.0])
            .unwrap();
        w.set_wheelset_velocity(2, &[2000.0, 0.0, 0.0, 0.0, 0.0, -4.3459197])
            .unwrap();
        let cache = KernelCache::default();
        w.calculate(&cache).unwrap();
        let u = w.config.units;
        let o = &w.outcomes[0];
        let [fn_, fx, fs, _] = crate::getters::contact_forces(o, u);
        close("FN", fn_, 10040.715121559264, 10.0);
        close("FX", fx, 546.2665948836895, 10.0);
        close("FS", fs, -2961.0836757778825, 10.0);
        let [_, ceta, _] = crate::getters::creepages(o, u);
        close("CETA", ceta, 0.004798401609212832, 1e-5);
        let g = w.global_forces(None).unwrap();
        close("FY_TR", g[1], -3095.7975364776526, 10.0);
        close("MX_R_TR", g[3], 40032.761166105505, 200.0);
        close("MZ_R_TR", g[5], -13235.98784802425, 200.0);
        let loc = crate::element::location_values(o, u);
        close("YCP_TR", loc[1], -756.5055572557221, 0.3);
        close("YR_TR", loc[25], -760.5325577483475, 1e-3);
        // The grid is mirrored: its rows run the other way round.
        let p = crate::getters::potcontact(o, u);
        assert!(p[3] < 0.0 && p[3] + (p[1] - 1.0) * p[5] > 0.0, "{p:?}");
    }

    /// The same case by vertical position (N = 0), in SI and SIMPACK's
    /// units, and with the wheel given by values: the same forces.
    #[test]
    fn position_units_and_values_give_the_same_forces() {
        let cache = KernelCache::default();
        let case = |w: &mut WheelRail, l: f64, v: f64| {
            w.set_wheelset_position(2, &[0.0, 2.5 * l, 0.0, -0.0001457, 0.006, 0.0])
                .unwrap();
            w.set_wheelset_velocity(2, &[2000.0 * v, 0.0, 0.0, 0.0, 0.0, -4.3455627])
                .unwrap();
        };
        let mut w = mbench(1);
        case(&mut w, 1.0, 1.0);
        w.calculate(&cache).unwrap();
        let g = w.global_forces(None).unwrap();
        let z = w.wheelset_position().unwrap()[2];

        // N = 0 at the height found: the vertical force comes back.
        assert_eq!(w.config.set_flag(1, flags::IC_NORM, 0), None);
        w.set_wheelset_position(2, &[0.0, 2.5, z, -0.0001457, 0.006, 0.0])
            .unwrap();
        w.calculate(&cache).unwrap();
        let g0 = w.global_forces(None).unwrap();
        close("FZ_TR at the height found", g0[2], g[2], 2.0);
        close("FY_TR at the height found", g0[1], g[1], 2.0);

        // SI (profiles in mm: SCALE_YZ = 1) and SIMPACK's convention
        // (forces on the wheel).
        for (units, body) in [(flags::UN_SI, 1.0), (flags::UN_SPCK, -1.0)] {
            let mut si = WheelRail::default();
            si.config.set_flag(1, flags::IF_UNITS, units);
            si.config.set_flag(1, flags::IC_CONFIG, 1);
            si.config
                .set_material(0, &[0.28, 0.28, 82e9, 82e9])
                .unwrap();
            si.config.set_friction(1, 0, &[0.3, 0.3]).unwrap();
            si.set_vertical_force(10000.0).unwrap();
            si.set_discretisation(-1, &[2e-4, 2e-4, std::f64::consts::FRAC_PI_2, 8e-3, 4e-3])
                .unwrap();
            let track = [0.014, 0.0, 1.435, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
            si.set_track_dimensions(3, &track).unwrap();
            si.set_wheelset_dimensions(3, &[1.360, -0.070, 0.460])
                .unwrap();
            let (rail, wheel) = mbench_files();
            for f in [rail, wheel] {
                let f = f.to_str().expect("utf-8 path").to_string();
                set_file(&mut si, &f);
            }
            case(&mut si, 1e-3, 1e-3);
            si.calculate(&cache).unwrap();
            let gs = si.global_forces(None).unwrap();
            close("FY_TR (SI)", gs[1], body * g[1], 1e-6 * g[1].abs());
            close("MX_R_TR (SI)", gs[3] * 1e3, body * g[3], 1e-6 * g[3].abs());
            let u = si.config.units;
            let loc = crate::element::location_values(&si.outcomes[0], u);
            let loc_mm = crate::element::location_values(&w.outcomes[0], w.config.units);
            close("YCP_TR (SI)", loc[1] * 1e3, loc_mm[1], 1e-6);
        }

        // The wheel by values (mm, CONTACT's order) instead of the file.
        let (_, wheel) = mbench_files();
        let text = std::fs::read_to_string(wheel).unwrap();
        let prof = railcontact_solver::wheelrail::parse_profile(
            &text,
            "MBench_S1002_v3.prw",
            &LoadOptions::default(),
        )
        .unwrap();
        let values: Vec<f64> = prof
            .points()
            .iter()
            .flat_map(|p| [p[0] * 1e3, p[1] * 1e3])
            .collect();
        let mut wv = mbench(1);
        wv.set_profile_values(prof.len(), &values, &[1], &[])
            .unwrap();
        case(&mut wv, 1.0, 1.0);
        wv.calculate(&cache).unwrap();
        let gv = wv.global_forces(None).unwrap();
        close("FY_TR (values)", gv[1], g[1], 1e-6 * g[1].abs());
    }

    /// V = 1: friction by contact angle (CONTACT's angles, negative
    /// towards the gauge face): a constant table is Coulomb's law; 0.2 at
    /// the flange lowers its creep forces.
    #[test]
    fn friction_by_contact_angle() {
        let cache = KernelCache::default();
        let solve = |params: &[f64], imeth: i32| {
            let mut w = mbench(1);
            w.config.set_friction(1, imeth, params).unwrap();
            w.set_wheelset_position(2, &[0.0, 6.5, 0.0, -0.004376, 0.0156, 0.0])
                .unwrap();
            w.set_wheelset_velocity(2, &[2000.0, 0.0, 0.0, 0.0, 0.0, -4.2748834])
                .unwrap();
            w.calculate(&cache).unwrap();
            w.global_forces(None).unwrap()
        };
        let coulomb = solve(&[0.3, 0.3], 0);
        let pi = std::f64::consts::PI;
        let table = [
            2.0,
            -20.0 * pi / 180.0,
            0.3,
            0.3,
            -10.0 * pi / 180.0,
            0.3,
            0.3,
        ];
        let constant = solve(&table, 10);
        close("FX_TR, constant table", constant[0], coulomb[0], 1e-6);
        let table = [
            2.0,
            -20.0 * pi / 180.0,
            0.2,
            0.2,
            -10.0 * pi / 180.0,
            0.3,
            0.3,
        ];
        let low = solve(&table, 10);
        // The flange (66 degrees) takes the table's end value 0.2.
        assert!(
            low[0].abs() < 0.85 * coulomb[0].abs(),
            "{} {}",
            low[0],
            coulomb[0]
        );
    }

    #[test]
    fn unsupported_settings_are_refused_naming_the_parameter() {
        let mut w = mbench(1);
        let e = w
            .set_wheelset_flexibility(
                4,
                &[
                    0.1,
                    f64::NAN,
                    0.0,
                    0.0,
                    0.0,
                    0.0,
                    0.0,
                    0.0,
                    0.0,
                    0.0,
                    0.0,
                    0.0,
                ],
            )
            .unwrap_err();
        assert!(e.to_string().contains("DYWHL"), "{e}");
        w.set_wheelset_flexibility(4, &[0.1; 12]).unwrap();
        w.set_wheelset_position(1, &[0.0; 6]).unwrap();
        w.set_wheelset_velocity(2, &[2000.0, 0.0, 0.0, 0.0, 0.0, -4.3])
            .unwrap();
        let cache = KernelCache::default();
        w.set_wheelset_flexibility(5, &[0.0; 12]).unwrap();
        // Transient rolling rolls whole elements a step (DQREL = 1, 2, ...).
        assert_eq!(w.config.set_flag(1, flags::IC_TANG, 2), None);
        w.set_rolling_step(0.0, 2.5).unwrap();
        let e = w.calculate(&cache).unwrap_err();
        assert!(e.to_string().contains("DQREL = 2.5"), "{e}");
        assert_eq!(e.ierror(), -40);
        w.set_rolling_step(0.0, 1.0).unwrap();
        // M = 3 and M = 2 take the exact pressure as their bound (B = 0)
        // only, and with T = 1, 2 are refused (Kalker's theory, M = 0).
        for (m, mat) in [
            (3, vec![0.28, 0.28, 82000.0, 82000.0, 1.0, 1.0, 0.0]),
            (2, vec![0.28, 0.28, 82000.0, 82000.0, 5e-5, 1.0, 1.0, 1.0]),
        ] {
            assert_eq!(w.config.set_flag(1, flags::IC_TANG, 3), None);
            w.config.set_material(m, &mat).unwrap();
            assert_eq!(w.config.set_flag(1, flags::IC_BOUND, 2), None);
            let e = w.calculate(&cache).unwrap_err();
            assert!(
                e.to_string()
                    .contains(&format!("B = 2 (CNTC_ic_bound) with M = {m}")),
                "{e}"
            );
            assert_eq!(e.ierror(), -40);
            assert_eq!(w.config.set_flag(1, flags::IC_BOUND, 0), None);
            assert_eq!(w.config.set_flag(1, flags::IC_TANG, 1), None);
            let e = w.calculate(&cache).unwrap_err();
            assert!(
                e.to_string()
                    .contains(&format!("M = {m} (CNTC_ic_mater) with T = 1")),
                "{e}"
            );
            assert_eq!(e.ierror(), -40);
        }
        assert_eq!(w.config.set_flag(1, flags::IC_TANG, 3), None);
        // T = 0 has no creep forces to prescribe.
        assert_eq!(w.config.set_flag(1, flags::IC_TANG, 0), None);
        assert_eq!(w.config.set_flag(1, flags::IC_FORCE, 1), None);
        let e = w.calculate(&cache).unwrap_err();
        assert!(e.to_string().contains("T = 3"), "{e}");
        assert_eq!(w.config.set_flag(1, flags::IC_FORCE, 0), None);
        let e = w
            .set_track_dimensions(1, &[-1.0, 0.0, 0.0, 0.0, 0.0, 1e-3])
            .unwrap_err();
        assert!(e.to_string().contains("CURV"), "{e}");
        let missing = read_profile_file("no-such-file.prr");
        let e = w
            .set_profile_file("no-such-file.prr", missing.as_deref(), &[], &[], &[])
            .unwrap_err();
        assert_eq!(e.ierror(), flags::err::PROFIL);
        assert!(w.calculate(&cache).is_err());
    }

    /// A server's bounds on the slices files a library sends it: the UK
    /// crossing nose's 10 slices are refused under a limit of 5 slices,
    /// and under one of 1000 surface points (10 slices of their points),
    /// naming the limit; within bounds it is read.
    #[test]
    fn slices_files_are_read_within_the_limits_set() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../solver/profiles");
        let path = dir.join("uk_crossing_nose.slcs");
        let path = path.to_str().unwrap();
        let content = read_profile_file(path);
        let files = read_slice_files(path, content.as_deref());
        let read = |limits: SlicesLimits| {
            let mut w = WheelRail::default();
            w.set_slices_limits(limits);
            w.set_profile_file(
                path,
                content.as_deref(),
                &files,
                &[0, 0, 0, -1],
                &[1000.0, 0.0],
            )
        };
        let few_slices = SlicesLimits {
            max_slices: 5,
            ..SlicesLimits::NONE
        };
        let few_points = SlicesLimits {
            max_surface_points: 1000,
            ..SlicesLimits::NONE
        };
        for limits in [few_slices, few_points] {
            let e = read(limits).unwrap_err();
            assert!(e.to_string().contains("more than the limit"), "{e}");
        }
        read(SlicesLimits::NONE).unwrap();
    }

    /// The sphere of test-rollers2.inp on its plane placed absolutely at
    /// RAILY0 = 200 mm (CONTACT's units), on side `c1`.
    fn sphere_on_plane(c1: i32) -> WheelRail {
        let mut w = mbench(c1);
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../solver/profiles");
        w.set_track_dimensions(
            3,
            &[-1.0, 200.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        )
        .unwrap();
        set_file(&mut w, dir.join("flat_plane.prr").to_str().unwrap());
        w.set_wheelset_dimensions(3, &[200.0, -100.0, 100.0])
            .unwrap();
        set_file(&mut w, dir.join("circ_r100.prw").to_str().unwrap());
        w.set_wheelset_position(2, &[0.0; 6]).unwrap();
        w.set_wheelset_velocity(2, &[100.0, 0.0, 0.0, 0.0, 0.0, -1.0])
            .unwrap();
        w.set_vertical_force(5e4).unwrap();
        w
    }

    /// RAILY0 is a track y: the plane at +200 mm lies under the right wheel
    /// (at +200 mm), not under the left one (at -200 mm), and the pair
    /// placed for the right side is not used for the left.
    #[test]
    fn an_absolute_rail_is_placed_on_its_own_side() {
        let cache = KernelCache::default();
        let mut w = sphere_on_plane(1);
        w.calculate(&cache).unwrap();
        let track_y = |w: &WheelRail| w.outcomes[0].location.as_ref().unwrap().track[1];
        close("YCP_TR", track_y(&w), 0.2, 1e-9);
        assert_eq!(w.config.set_flag(1, flags::IC_CONFIG, 0), None);
        assert!(w.calculate(&cache).is_err());
        let mut left = sphere_on_plane(0);
        left.calculate(&cache).unwrap_err();
        left.set_track_dimensions(1, &[-1.0, -200.0, 0.0, 0.0, 0.0])
            .unwrap();
        left.calculate(&cache).unwrap();
        close("YCP_TR", track_y(&left), -0.2, 1e-9);
    }

    #[test]
    fn profile_values_give_the_points_in_mm() {
        let w = mbench(1);
        let n = w.profile_values(0, &[0, 0], &[]).unwrap()[0] as usize;
        let v = w.profile_values(1, &[0, 0], &[]).unwrap();
        assert_eq!(v.len(), 2 * n);
        // The rail's points run from the gauge side to the field side.
        assert!(v[0] < v[n - 1], "y from {} to {}", v[0], v[n - 1]);
        let s = w.profile_values(4, &[1, 1], &[0.5]).unwrap();
        assert!(s.windows(2).all(|p| (p[1] - p[0] - 0.5).abs() < 1e-9));
        // The rail on the right side of the track lies near y = 760 mm.
        let t = w.profile_values(2, &[0, 0], &[]).unwrap();
        assert!(t[..n].iter().all(|y| (700.0..800.0).contains(y)));
        assert_eq!(w.profile_values(-1, &[1], &[]).unwrap(), vec![0.0, 0.0]);
    }

    #[test]
    fn orientation_gives_contacts_axle() {
        let (roll, yaw) = (0.011, 0.024);
        let o = SolverOrientation::of(roll, yaw, 0.0, 0.0, -4.0);
        let ours = [
            -o.yaw_rad.sin() * o.roll_rad.cos(),
            o.yaw_rad.cos() * o.roll_rad.cos(),
            o.roll_rad.sin(),
        ];
        let axes = contact_ws_axes(Side::Right, roll, yaw);
        for k in 0..3 {
            assert!(
                (ours[k] - axes[1][k]).abs() < 1e-15,
                "{ours:?} {:?}",
                axes[1]
            );
        }
        // Right-handed: forward x axle = down.
        let z = cross(axes[0], axes[1]);
        for k in 0..3 {
            assert!((z[k] - axes[2][k]).abs() < 1e-15);
        }
    }

    #[test]
    fn rows_mirror() {
        let v = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0];
        assert_eq!(
            mirrored_rows(&v, 2, 3, -1.0),
            vec![-5.0, -6.0, -3.0, -4.0, -1.0, -2.0]
        );
    }
}
