//! Wheel/rail geometry from real profiles: profile files, the profile
//! frame, and smooth interpolation of profiles.
//!
//! * [`profile`]: the checked in-memory [`Profile`], loading
//!   ([`load_profile`]) and the checks;
//! * [`readers`]: the Simpack, MiniProf and plain text formats and how each
//!   is mapped to the profile frame;
//! * [`spline`]: the smoothing spline [`ProfileSpline`] giving position,
//!   inclination and curvature at any arc length, and z at a given y;
//! * [`wheelset`]: track and wheelset data, the placed profiles
//!   ([`WheelRailPair`]), wheelset position and velocity, and the frames;
//! * [`pair_cache`]: placed pairs shared by content while they are used
//!   ([`PairCache`]);
//! * [`search`]: contact locus, rigid position (roll), contact patches and
//!   their planar geometry, each about its contact reference point (the
//!   smallest gap, or CONTACT's weighted centre of the interpenetration:
//!   [`ReferencePoint`]);
//! * [`contact`]: creepages, the per-patch contact problems and the load
//!   iteration ([`solve_wheelset`]);
//! * [`massless_rail`]: CONTACT's massless rail model, the rail's
//!   deflection that balances the contact force ([`solve_on_massless_rail`]);
//! * [`ranges`]: the documented ranges of a case's numbers and their one
//!   check ([`ranges::check_motion`], [`ranges::check_geometry`]), which
//!   the command line and the service both run;
//! * [`plausibility`]: warnings about answers no elastic contact gives
//!   and forces inconsistent with the kinematics given, naming the input
//!   at fault ([`check_plausibility`]);
//! * [`temperature`]: flash temperatures of the wheel and rail per patch
//!   ([`WheelRailThermal`], [`PatchTemperatures`]);
//! * [`table`]: contact tables per profile pair for the Hertz+FASTSIM fast
//!   path ([`ContactTable`], [`solve_wheelset_tabulated`]).
//!
//! # Profile frame and conventions (used by every reader and the spline)
//!
//! * **Units**: metres, radians; field names carry their unit.
//! * **Axes**: a profile is a curve in the (y, z) plane of the track frame
//!   of [`crate::conformal::geometry`]: x along the track (the rolling
//!   direction), y lateral, z vertical pointing **down**, into the rail;
//!   (x, y, z) right-handed.
//! * **Side**: profiles are those of the **right-hand** rail and wheel, seen
//!   in the direction of travel: +y points to the **field side** (away from
//!   the track centre), -y to the **gauge side** (towards the track
//!   centre). So a rail has its gauge face at its -y end and its field side
//!   at +y; a wheel has its flange on the -y side and its outer (field)
//!   face at +y. The left-hand profiles are the mirror images
//!   ([`Profile::mirrored_y`]). This is CONTACT's convention; Simpack's
//!   `mirror.y` flag and [`LoadOptions::mirror_y`] bring files into it.
//! * **Origin**: kept as in the file, after the format's own shifts; the
//!   track/wheelset set-up places the profiles. For the test files:
//!   `MBench_UIC60_v3.prr` (already canted 1:40) has y = 0, z = 0 at the
//!   top of the rail, its gauge face near y = -43 mm;
//!   `MBench_S1002_v3.prw` has its origin on the tape circle (y = 0, z = 0),
//!   70 mm from the back of the flange, which lies at y = -70 mm; MiniProf
//!   wheels (`.whl`) have y = 0 at the back of the flange and z = 0 at the
//!   height of the tape circle, which lies at y = +70 mm (use
//!   [`Profile::translated`] to put the origin on the tape circle);
//!   MiniProf rails have the instrument's origin near the top of the rail.
//! * **Point order** (CONTACT's): rails in increasing y (gauge face to
//!   field side), wheels in decreasing y (field face to flange back). Then,
//!   walking along the profile, the material lies on the right-hand side
//!   when the plane is drawn with y to the right and z downwards. Readers
//!   reverse the order when needed; profiles of unknown kind (plain files)
//!   keep the file's order.
//! * **Slopes and curvature** ([`spline`]): the inclination is
//!   `atan(dz/dy)`, positive where the surface descends towards +y, made
//!   continuous through vertical parts; the curvature is positive where
//!   the body is convex (rail crown, wheel tread bulging towards the rail)
//!   and negative where it is concave (flange root, hollow tread, groove).
//!   Both circles of the test bank, `circ_r100.prr` (a rail crown of
//!   lateral radius 100 mm) and `circ_r10.prw` (a wheel of lateral radius
//!   10 mm, "-10 mm" in CONTACT's sign convention for wheels), are convex:
//!   curvature +10/m and +100/m.
//! * **Checks**: see [`Profile::from_points`] and [`ProfileChecks`]: close
//!   points are merged, small spikes and pairs of points out of order are
//!   repaired (with warnings), larger ones and gaps are errors that name the
//!   file and line.

pub mod builtin;
pub mod contact;
pub mod friction;
pub mod grid_sizing;
pub mod massless_rail;
pub mod pair_cache;
pub mod plausibility;
pub mod profile;
pub mod ranges;
pub mod readers;
pub mod search;
pub mod slices;
pub mod spline;
pub mod table;
pub mod temperature;
pub mod wheelset;

pub use contact::{
    nominal_rolling_speed, pitch_force_tolerance, solve_wheelset, solve_wheelset_warm,
    viscoelastic_bodies, wheelrail_solver_settings, ExactTangential, PatchResult, PatchTractions,
    RailMotion, TransientContact, WarmStart, WheelLoad, WheelRailInput, WheelRailModel,
    WheelRailSettings, WheelRailSolution, WheelResult, VISCOELASTIC_SETTINGS_KEY,
};
pub use friction::{FrictionAxis, FrictionTable};
pub use grid_sizing::{GridSizing, GRID_COARSENINGS, RECHECK_ANGLE_RAD, RECHECK_AREA_RATIO};
pub use massless_rail::{
    rail_deflection, solve_on_massless_rail, Deflected, MasslessRail, MasslessRailError,
    RailContact, RailDeflection, RailLoad, MASSLESS_RAIL_PLACED_TOLERANCE,
};
pub use pair_cache::{PairCache, PairCacheStats};
pub use plausibility::{check_plausibility, PlausibilityWarning, WarningKind};
pub use profile::{
    detect_format, kind_from_extension, load_profile, load_profile_with, parse_profile, CheckKind,
    LengthUnit, LoadOptions, MiniProfVariant, MirrorZ, Profile, ProfileChecks, ProfileError,
    ProfileFormat, ProfileKind, ProfileWarning, SourceLocation,
};
pub use readers::{parse_miniprof, parse_plain, parse_simpack};
pub use search::{ReferencePoint, SearchScratch, SearchSettings};
pub use slices::{
    is_slices_file, is_wheel_slices_file, load_slices, load_wheel_slices, parse_slices,
    parse_wheel_slices, RailSlices, SliceInterpolation, WheelSlices,
};
pub use spline::{
    ProfileSpline, SplineError, SplineOptions, SplinePoint, DEFAULT_SMOOTHING_WAVELENGTH_M,
};
pub use table::{
    solve_wheelset_tabulated, solve_wheelset_tabulated_warm, ContactTable, TableSettings,
};
pub use temperature::{PatchTemperatures, WheelRailThermal};
pub use wheelset::{
    RailDeviation, RailPlacement, Side, TrackData, WheelRailError, WheelRailPair, WheelSlicesAt,
    WheelsetData, WheelsetPosition, WheelsetVelocity, MAX_TRACK_CURVATURE_PER_M,
};
