//! The kinematics of a case: `[load]`, `[rolling]`, `[extra_rigid_slip]`
//! and `[transient]` with its steps (shifts, rolling steps, prescribed
//! forces).

use serde::Deserialize;

use super::{bad, per_element_values, ranges, CaseFile, GeometryKind, GridSection, Model};
use crate::core::error::Range;
use crate::core::force::PrescribedForce;
use crate::core::frame::{axis_turns, direction, Direction, ROLLING_DIRECTION_KEY};
use crate::core::friclaw::SlipStart;
use crate::core::normal::NormalLoad;
use crate::core::problem::{
    Creepages, ExtraRigidSlip, Kinematics, ShiftStep, CREEPAGE_RANGE, SPIN_RANGE,
};
use crate::problem::CaseError;

/// `[extra_rigid_slip]`: a rigid slip [-] added at each element to the
/// creepages' rigid slip w = (xi - phi y, eta + phi x), CONTACT's `EXRHS`
/// of a rolling case (E = 9): `slip_x` and `slip_y`, each nx * ny values
/// with index iy * nx + ix (x fastest) in [-1, 1]; and a rigid shift
/// \[m\] added at each element to the shift of every transient shift step,
/// `EXRHS` of a shift case: `shift_x_m` and `shift_y_m`, in [-0.01, 0.01]
/// m. One component of a pair may be left out (zeros). Exact model; steady
/// rolling and rolling steps need the slip (a rolling step of dq adds dq
/// times it to the rigid shift), shift steps the shift; the grid's `nx`
/// and `ny` must be given.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExtraRigidSlipSection {
    /// x component per element [-].
    pub slip_x: Option<Vec<f64>>,
    /// y component per element [-].
    pub slip_y: Option<Vec<f64>>,
    /// x component of each shift step's extra shift per element \[m\].
    pub shift_x_m: Option<Vec<f64>>,
    /// y component of each shift step's extra shift per element \[m\].
    pub shift_y_m: Option<Vec<f64>>,
}

/// `[rolling]`: per direction either the creepage or the prescribed total
/// tangential force on body 1 (signs as in [`crate::core::problem`]).
#[derive(Debug, Clone, Copy, Default, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RollingSection {
    /// Longitudinal creepage xi [-] (default 0 unless `force_x_n` is given).
    pub creepage_long: Option<f64>,
    /// Lateral creepage eta [-] (default 0 unless `force_y_n` is given).
    pub creepage_lat: Option<f64>,
    /// Spin creepage phi [1/m] (default 0).
    pub spin_per_m: f64,
    /// Prescribed longitudinal force Fx \[N\], |Fx| < mu Fn, instead of
    /// `creepage_long`.
    pub force_x_n: Option<f64>,
    /// Prescribed lateral force Fy \[N\], |Fy| < mu Fn, instead of
    /// `creepage_lat`.
    pub force_y_n: Option<f64>,
    /// Line contact (`geometry.kind = "line"`): prescribed longitudinal
    /// force per metre Fx' \[N/m\], |Fx'| < mu Fn', instead of
    /// `creepage_long`.
    pub force_x_n_per_m: Option<f64>,
}

impl RollingSection {
    /// Rolling with these creepages.
    pub fn creepages(c: Creepages) -> Self {
        Self {
            creepage_long: Some(c.creepage_long),
            creepage_lat: Some(c.creepage_lat),
            spin_per_m: c.spin_per_m,
            force_x_n: None,
            force_y_n: None,
            force_x_n_per_m: None,
        }
    }

    /// The creepages (0 in the directions of a prescribed force: the start
    /// of its iteration) and the prescribed forces (`force_x_n_per_m` as
    /// Fx: a line contact's totals are per metre); exactly one of creepage
    /// and force per direction.
    pub fn split(&self) -> Result<(Creepages, PrescribedForce), CaseError> {
        let (force_x, fx_key) = match (self.force_x_n, self.force_x_n_per_m) {
            (Some(_), Some(_)) => {
                return Err(bad(
                    "rolling.force_x_n_per_m",
                    "give either `rolling.force_x_n` or `rolling.force_x_n_per_m`, not both",
                ))
            }
            (None, Some(f)) => {
                ranges::TANGENTIAL_FORCE_PER_M.check("rolling.force_x_n_per_m", f)?;
                (Some(f), "force_x_n_per_m")
            }
            (f, None) => (f, "force_x_n"),
        };
        let one = |creep: Option<f64>, force: Option<f64>, ck: &str, fk: &str| match (creep, force)
        {
            (Some(_), Some(_)) => Err(bad(
                format!("rolling.{fk}"),
                format!("give either `rolling.{ck}` or `rolling.{fk}`, not both"),
            )),
            (c, None) => Ok((c.unwrap_or(0.0), None)),
            (None, Some(f)) => {
                if !fk.ends_with("_per_m") {
                    ranges::TANGENTIAL_FORCE.check(&format!("rolling.{fk}"), f)?;
                }
                Ok((0.0, Some(f)))
            }
        };
        let (xi, fx) = one(self.creepage_long, force_x, "creepage_long", fx_key)?;
        let (eta, fy) = one(
            self.creepage_lat,
            self.force_y_n,
            "creepage_lat",
            "force_y_n",
        )?;
        Ok((
            Creepages {
                creepage_long: xi,
                creepage_lat: eta,
                spin_per_m: self.spin_per_m,
            },
            PrescribedForce {
                force_x_n: fx,
                force_y_n: fy,
            },
        ))
    }
}

/// `[load]`: exactly one of `normal_force_n` (`normal_force_n_per_m` for a
/// line contact) and `approach_m`.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoadSection {
    /// Total normal force \[N\], > 0.
    pub normal_force_n: Option<f64>,
    /// Line contact (`geometry.kind = "line"`): normal force per metre of
    /// the cylinders \[N/m\], > 0.
    #[serde(default)]
    pub normal_force_n_per_m: Option<f64>,
    /// Approach of the bodies \[m\], > 0 (line contact: relative to the
    /// surface points 1 m from the load, see [`crate::core::influence`]).
    pub approach_m: Option<f64>,
}

/// `[transient]`: a sequence of shift and rolling steps from the unloaded
/// state (or from a steady rolling state, `steady_start`), each from the
/// tractions of the step before.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TransientSection {
    /// The steps start from the steady rolling state at these creepages
    /// instead of the unloaded state (exact model): that state is solved
    /// first, at the `[load]`, and reported as `steady_start` ahead of
    /// the steps (CONTACT's steady case, T = 3, followed by transient
    /// cases continuing it, T = 2 with P = 0): `creepage_long`,
    /// `creepage_lat`, `spin_per_m`, each default 0, ranges as
    /// `[rolling]`'s (a line contact's `creepage_long` only).
    pub steady_start: Option<Creepages>,
    /// Distance the contact patch rolls in +x in each rolling step \[m\]
    /// (moving coordinates, see [`crate::core::problem`]): a whole number
    /// of elements `grid.window_x_m / grid.nx`, in (0, 1] m. Needed when a
    /// step gives creepages (exact model only).
    pub rolling_step_m: Option<f64>,
    /// The steps, at least one.
    pub steps: Vec<StepSection>,
}

/// One step in `transient.steps`: a shift step (`shift_*`,
/// `rotation_rad`) or a rolling step (creepages, rolling
/// `transient.rolling_step_m` or the step's `rolling_m`), never both. A
/// shift step with `rolling_m` rolls that far by its shift: the potential
/// contact area moves with the bodies, in world-fixed terms (the
/// tractions stay where they are on the bodies). In either kind the
/// tangential forces may be prescribed instead of the shifts or creepages
/// of their directions (exact model): the step is solved for the shifts
/// that give them, reported with the step.
#[derive(Debug, Clone, Copy, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StepSection {
    /// Rigid shift of body 1 relative to body 2 in x during the step \[m\]
    /// (required in a shift step unless `force_x_n` is given, except for
    /// the conformal models, which take 0 only).
    pub shift_x_m: Option<f64>,
    /// Rigid shift in y during the step \[m\] (default 0).
    #[serde(default)]
    pub shift_y_m: f64,
    /// Rigid rotation about the normal axis during the step \[rad\] (default 0).
    #[serde(default)]
    pub rotation_rad: f64,
    /// Normal force in the step \[N\], > 0 (default: the `[load]`).
    pub normal_force_n: Option<f64>,
    /// Line contact: normal force per metre in the step \[N/m\], > 0
    /// (default: the `[load]`).
    #[serde(default)]
    pub normal_force_n_per_m: Option<f64>,
    /// Approach in the step \[m\], > 0 (default: the `[load]`).
    pub approach_m: Option<f64>,
    /// Longitudinal creepage xi of a rolling step [-], in [-1, 1] (default
    /// 0 when another creepage is given).
    pub creepage_long: Option<f64>,
    /// Lateral creepage eta of a rolling step [-], in [-1, 1] (default 0).
    pub creepage_lat: Option<f64>,
    /// Spin creepage phi of a rolling step \[1/m\], in [-1000, 1000]
    /// (default 0).
    pub spin_per_m: Option<f64>,
    /// Prescribed longitudinal force Fx on body 1 in the step \[N\],
    /// |Fx| < mu Fn, instead of `shift_x_m` (a shift step) or
    /// `creepage_long` (a rolling step); exact model.
    #[serde(default)]
    pub force_x_n: Option<f64>,
    /// Prescribed lateral force Fy \[N\], |(Fx, Fy)| < mu Fn, instead of
    /// `shift_y_m` or `creepage_lat` (with `force_x_n` or alone).
    #[serde(default)]
    pub force_y_n: Option<f64>,
    /// Line contact: prescribed longitudinal force per metre Fx' \[N/m\],
    /// |Fx'| < mu Fn', as `force_x_n` otherwise.
    #[serde(default)]
    pub force_x_n_per_m: Option<f64>,
    /// Distance this step rolls \[m\]: a whole number of elements, in
    /// (0, 1] (default: `transient.rolling_step_m` in a step with
    /// creepages, 0 in a shift step). A shift step with `rolling_m` is a
    /// rolling step given by its shift (the creepages are the shifts over
    /// `rolling_m`).
    #[serde(default)]
    pub rolling_m: Option<f64>,
    /// Distance the bodies' undeformed distance travels in +x over the
    /// grid in this shift step \[m\], in [-1, 1] (default 0): world-fixed
    /// steps on a fixed potential contact area, the tractions staying where
    /// they are on the grid. It accumulates over the steps: after steps
    /// with travels t_1..t_k the gap is A (x - s)² + B y², s = t_1 + ... +
    /// t_k (exact model, without `geometry.gap_m`).
    #[serde(default)]
    pub gap_travel_x_m: Option<f64>,
    /// Where this step's iteration on the slip velocities starts
    /// (`"previous"`, `"sticking"`, `"sliding"`, as `friction.start`;
    /// CONTACT's INISLP of each case); default `friction.start`. Needs a
    /// falling law (`friction.law`).
    #[serde(default)]
    pub friction_start: Option<SlipStart>,
}

impl StepSection {
    /// The forces prescribed in the step (`force_x_n_per_m` as Fx when
    /// `line`: a line contact's totals are per metre), checked against
    /// their ranges; `key` names the step.
    fn force(&self, key: &str, line: bool) -> Result<PrescribedForce, CaseError> {
        let force_x_n = match (line, self.force_x_n, self.force_x_n_per_m) {
            (true, Some(_), _) => {
                return Err(bad(
                    format!("{key}.force_x_n"),
                    format!(
                        "a line contact's forces are per metre: give `{key}.force_x_n_per_m` [N/m]"
                    ),
                ))
            }
            (false, _, Some(_)) => {
                return Err(bad(
                    format!("{key}.force_x_n_per_m"),
                    format!(
                        "a force per metre is for `geometry.kind = \"line\"`: give `{key}.force_x_n` [N]"
                    ),
                ))
            }
            (true, None, f) => {
                if let Some(f) = f {
                    ranges::TANGENTIAL_FORCE_PER_M.check(&format!("{key}.force_x_n_per_m"), f)?;
                }
                f
            }
            (false, f, None) => {
                if let Some(f) = f {
                    ranges::TANGENTIAL_FORCE.check(&format!("{key}.force_x_n"), f)?;
                }
                f
            }
        };
        if let Some(f) = self.force_y_n {
            ranges::TANGENTIAL_FORCE.check(&format!("{key}.force_y_n"), f)?;
        }
        Ok(PrescribedForce {
            force_x_n,
            force_y_n: self.force_y_n,
        })
    }

    /// The creepages of a rolling step, None for a shift step; `key` names
    /// the step.
    fn creepages(&self, key: &str) -> Result<Option<Creepages>, CaseError> {
        if self.creepage_long.is_none() && self.creepage_lat.is_none() && self.spin_per_m.is_none()
        {
            return Ok(None);
        }
        let c = Creepages {
            creepage_long: self.creepage_long.unwrap_or(0.0),
            creepage_lat: self.creepage_lat.unwrap_or(0.0),
            spin_per_m: self.spin_per_m.unwrap_or(0.0),
        };
        CREEPAGE_RANGE.check(&format!("{key}.creepage_long"), c.creepage_long)?;
        CREEPAGE_RANGE.check(&format!("{key}.creepage_lat"), c.creepage_lat)?;
        SPIN_RANGE.check(&format!("{key}.spin_per_m"), c.spin_per_m)?;
        Ok(Some(c))
    }
}

/// The load of a `[load]` or a step named `key`: per metre
/// (`normal_force_n_per_m`) for a line contact, else total
/// (`normal_force_n`); the other force key is refused.
pub(super) fn one_load(
    key: &str,
    force: Option<f64>,
    force_per_m: Option<f64>,
    approach: Option<f64>,
    line: bool,
) -> Result<Option<NormalLoad>, CaseError> {
    match (line, force, force_per_m) {
        (true, Some(_), _) => {
            return Err(bad(
                format!("{key}.normal_force_n"),
                format!("a line contact's load is per metre: give `{key}.normal_force_n_per_m` [N/m]"),
            ))
        }
        (false, _, Some(_)) => {
            return Err(bad(
                format!("{key}.normal_force_n_per_m"),
                format!("a force per metre is for `geometry.kind = \"line\"`: give `{key}.normal_force_n` [N]"),
            ))
        }
        (true, None, Some(f)) => {
            if approach.is_some() {
                return Err(bad(
                    format!("{key}.normal_force_n_per_m"),
                    format!("give either `{key}.normal_force_n_per_m` or `{key}.approach_m`, not both"),
                ));
            }
            ranges::NORMAL_FORCE_PER_M.check(&format!("{key}.normal_force_n_per_m"), f)?;
            return Ok(Some(NormalLoad::NormalForce(f)));
        }
        _ => {}
    }
    match (force, approach) {
        (Some(_), Some(_)) => Err(bad(
            format!("{key}.normal_force_n"),
            format!("give either `{key}.normal_force_n` or `{key}.approach_m`, not both"),
        )),
        (Some(f), None) => {
            ranges::NORMAL_FORCE.check(&format!("{key}.normal_force_n"), f)?;
            Ok(Some(NormalLoad::NormalForce(f)))
        }
        (None, Some(d)) => {
            ranges::APPROACH.check(&format!("{key}.approach_m"), d)?;
            Ok(Some(NormalLoad::Approach(d)))
        }
        (None, None) => Ok(None),
    }
}

/// Refuses what a line contact cannot roll with (lateral creepage, spin,
/// a lateral or total force), and a force per metre on other geometries.
pub(super) fn check_line_rolling(r: &RollingSection, line: bool) -> Result<(), CaseError> {
    if !line {
        if r.force_x_n_per_m.is_some() {
            return Err(bad(
                "rolling.force_x_n_per_m",
                "a force per metre is for `geometry.kind = \"line\"`: give `rolling.force_x_n` [N]",
            ));
        }
        return Ok(());
    }
    refuse_lateral(
        "rolling",
        "rolls",
        &[
            ("creepage_lat", r.creepage_lat.is_some_and(|v| v != 0.0)),
            ("spin_per_m", r.spin_per_m != 0.0),
            ("force_y_n", r.force_y_n.is_some()),
        ],
    )?;
    if r.force_x_n.is_some() {
        return Err(bad(
            "rolling.force_x_n",
            "a line contact's forces are per metre: give `rolling.force_x_n_per_m` [N/m]",
        ));
    }
    Ok(())
}

/// A line contact moves in x only: the first of `lateral` (a key under
/// `section` and whether it is given) that is given is refused, naming
/// it; `moves` is "rolls" or "shifts".
fn refuse_lateral(section: &str, moves: &str, lateral: &[(&str, bool)]) -> Result<(), CaseError> {
    match lateral.iter().find(|(_, given)| *given) {
        Some((key, _)) => Err(bad(
            format!("{section}.{key}"),
            format!("a line contact {moves} in x only: give 0 or leave it out"),
        )),
        None => Ok(()),
    }
}

/// Rejects a model that cannot run on the geometry; the error names `model`.
/// The [`Direction`] of `rolling_direction_rad` (see
/// [`crate::core::frame`]): the exact model rolls in any direction (a line
/// contact 0 or pi), steady rolling along a grid axis (a multiple of pi/2)
/// and transient rolling steps in any; the other models roll in +x; flash
/// temperatures roll in +x.
pub(super) fn rolling_direction(
    file: &CaseFile,
    model: Model,
    line: bool,
) -> Result<Direction, CaseError> {
    let key = ROLLING_DIRECTION_KEY;
    let d = direction(file.rolling_direction_rad, line)?;
    let along_x = d.turns == 0 && d.is_axis();
    // Model fastsim rolls along -x on CONTACT's grid (`[fastsim]` checks
    // the discretisation).
    let minus_x = d.turns == 2 && d.is_axis() && !line;
    if !along_x && model != Model::Exact && !(model == Model::Fastsim && minus_x) {
        return Err(bad(
            key,
            format!(
                "the exact model rolls in other directions than +x (model fastsim along -x on its grid), not {}: leave it 0",
                model.name()
            ),
        ));
    }
    if !along_x && file.temperature.is_some() {
        return Err(bad(
            key,
            "the flash temperatures are computed for rolling in +x: leave it 0 or leave out [temperature]",
        ));
    }
    // Steady rolling (a case's, or the steady start of its steps) rolls
    // along a grid axis.
    let steady = file
        .transient
        .as_ref()
        .is_none_or(|t| t.steady_start.is_some());
    if !d.is_axis() && steady {
        axis_turns(file.rolling_direction_rad, line)?;
    }
    Ok(d)
}

/// `[extra_rigid_slip]`, checked: exact model, rolling kinematics.
pub(super) fn extra_rigid_slip(
    file: &CaseFile,
    model: Model,
    kinematics: &Kinematics,
    n: [usize; 2],
    grid: GridSection,
) -> Result<Option<ExtraRigidSlip>, CaseError> {
    let Some(e) = &file.extra_rigid_slip else {
        return Ok(None);
    };
    let key = "extra_rigid_slip";
    if model != Model::Exact {
        return Err(bad(
            key,
            format!(
                "an extra rigid slip is solved by the exact model only, not {}",
                model.name()
            ),
        ));
    }
    let line = file.geometry.kind == GeometryKind::Line;
    let elements = if line { n[0] } else { n[0] * n[1] };
    // One pair: both components, zeros for one left out; empty without.
    let pair = |names: [&str; 2], given: [&Option<Vec<f64>>; 2], range: Range| {
        let mut out = [Vec::new(), Vec::new()];
        if given.iter().all(|v| v.is_none()) {
            return Ok(out);
        }
        for (k, (name, v)) in names.into_iter().zip(given).enumerate() {
            out[k] = match v {
                Some(v) => {
                    per_element_values(&format!("{key}.{name}"), v, n, grid, line, range)?;
                    v.clone()
                }
                None => vec![0.0; elements],
            };
        }
        Ok::<_, CaseError>(out)
    };
    let [slip_x, slip_y] = pair(["slip_x", "slip_y"], [&e.slip_x, &e.slip_y], CREEPAGE_RANGE)?;
    let [shift_x_m, shift_y_m] = pair(
        ["shift_x_m", "shift_y_m"],
        [&e.shift_x_m, &e.shift_y_m],
        ranges::SHIFT,
    )?;
    let extra = ExtraRigidSlip {
        slip_x,
        slip_y,
        shift_x_m,
        shift_y_m,
    };
    if !extra.has_slip() && !extra.has_shift() {
        return Err(bad(
            key,
            "give `extra_rigid_slip.slip_x` and/or `slip_y` (rolling), or `shift_x_m` and/or \
             `shift_y_m` (shift steps)",
        ));
    }
    extra.check_kinematics(kinematics)?;
    Ok(Some(extra))
}

/// A transient step as the core solves it: the step and the force
/// prescribed in it (none: the step is solved as given).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TransientStep {
    /// The step; in a direction with a prescribed force its shift is the
    /// iteration's start (0).
    pub step: ShiftStep,
    /// The force prescribed in the step.
    pub force: PrescribedForce,
    /// How far the bodies' undeformed distance travels over the grid in
    /// the step \[m\] (`gap_travel_x_m`, 0 when not given).
    pub gap_travel_x_m: f64,
}

/// The core step of a step section `s` named `key`: a rolling step of
/// the step's `rolling_m` or `rolling_step_m` (`transient.rolling_step_m`)
/// when it gives creepages, else a shift step (rolling its own
/// `rolling_m`, if given); its load defaults to `default_load` (per metre
/// when `line`, a line contact, which shifts and rolls in x only); with
/// the force it prescribes. Checks the ranges and that a step is one kind
/// or the other and gives either the shift (creepage) or the force of a
/// direction, and its `gap_travel_x_m` (only in a shift step of the exact
/// `model` without a gap given per element, `given_gap`), naming the key.
pub fn transient_step(
    key: &str,
    s: &StepSection,
    default_load: NormalLoad,
    rolling_step_m: Option<f64>,
    line: bool,
    model: Model,
    given_gap: bool,
) -> Result<TransientStep, CaseError> {
    let gap_travel_x_m = gap_travel(key, s, model, given_gap)?;
    let load = one_load(
        key,
        s.normal_force_n,
        s.normal_force_n_per_m,
        s.approach_m,
        line,
    )?
    .unwrap_or(default_load);
    if line {
        refuse_lateral(
            key,
            "shifts",
            &[
                ("shift_y_m", s.shift_y_m != 0.0),
                ("rotation_rad", s.rotation_rad != 0.0),
                ("force_y_n", s.force_y_n.is_some()),
            ],
        )?;
    }
    let force = s.force(key, line)?;
    if let Some(dq) = s.rolling_m {
        ranges::ROLLING_STEP.check(&format!("{key}.rolling_m"), dq)?;
    }
    let fx_key = if line { "force_x_n_per_m" } else { "force_x_n" };
    let either = |given: &str, force: &str| {
        bad(
            format!("{key}.{force}"),
            format!("give either `{key}.{given}` or `{key}.{force}`, not both"),
        )
    };
    let step = match s.creepages(key)? {
        Some(c) => {
            if line {
                refuse_lateral(
                    key,
                    "rolls",
                    &[
                        ("creepage_lat", c.creepage_lat != 0.0),
                        ("spin_per_m", c.spin_per_m != 0.0),
                    ],
                )?;
            }
            for (name, given) in [
                ("shift_x_m", s.shift_x_m.is_some()),
                ("shift_y_m", s.shift_y_m != 0.0),
                ("rotation_rad", s.rotation_rad != 0.0),
            ] {
                if given {
                    return Err(bad(
                        format!("{key}.{name}"),
                        "a rolling step (one with creepages) takes no shift: its shift is the \
                         creepages times its rolling distance",
                    ));
                }
            }
            if force.force_x_n.is_some() && s.creepage_long.is_some() {
                return Err(either("creepage_long", fx_key));
            }
            if force.force_y_n.is_some() && s.creepage_lat.is_some() {
                return Err(either("creepage_lat", "force_y_n"));
            }
            let dq = s.rolling_m.or(rolling_step_m).ok_or_else(|| {
                bad(
                    "transient.rolling_step_m",
                    format!(
                        "missing: {key} gives creepages, so it rolls `transient.rolling_step_m` m \
                         (or its own `{key}.rolling_m`)"
                    ),
                )
            })?;
            ShiftStep::rolling(load, dq, &c)
        }
        None => {
            let shift_x_m = match (s.shift_x_m, force.force_x_n) {
                (Some(_), Some(_)) => return Err(either("shift_x_m", fx_key)),
                (Some(x), None) => x,
                (None, Some(_)) => 0.0,
                (None, None) => {
                    return Err(bad(
                        format!("{key}.shift_x_m"),
                        format!(
                            "missing: give the shift (a shift step), `{fx_key}` (a prescribed \
                             force) or creepages (a rolling step)"
                        ),
                    ))
                }
            };
            if force.force_y_n.is_some() && s.shift_y_m != 0.0 {
                return Err(either("shift_y_m", "force_y_n"));
            }
            ShiftStep {
                load,
                shift_x_m,
                shift_y_m: s.shift_y_m,
                rotation_rad: s.rotation_rad,
                rolling_m: s.rolling_m.unwrap_or(0.0),
            }
        }
    };
    check_shift_step(key, &step)?;
    Ok(TransientStep {
        step,
        force,
        gap_travel_x_m,
    })
}

/// The `gap_travel_x_m` of step `s` named `key` (0 when not given),
/// checked: a shift step of the exact `model` whose gap is the quadratic
/// one (`given_gap`: an undeformed distance given per element, which does
/// not travel).
fn gap_travel(key: &str, s: &StepSection, model: Model, given_gap: bool) -> Result<f64, CaseError> {
    let Some(t) = s.gap_travel_x_m else {
        return Ok(0.0);
    };
    let name = format!("{key}.gap_travel_x_m");
    ranges::GAP_TRAVEL.check(&name, t)?;
    let rolls = s.rolling_m.is_some()
        || s.creepage_long.is_some()
        || s.creepage_lat.is_some()
        || s.spin_per_m.is_some();
    let reason = if rolls {
        "is for shift steps on a fixed grid: a rolling step's grid moves with the bodies"
    } else if model != Model::Exact {
        "is solved by the exact model only"
    } else if given_gap {
        "moves the quadratic undeformed distance: not with a gap given per element \
         (`geometry.gap_m`, `geometry.extra_gap_m`)"
    } else {
        return Ok(t);
    };
    Err(bad(name, reason))
}

/// Checks a transient step's shifts and rotation against their ranges
/// (its load is checked where it is read); `key` names the step.
pub fn check_shift_step(key: &str, s: &ShiftStep) -> Result<(), CaseError> {
    ranges::SHIFT.check(&format!("{key}.shift_x_m"), s.shift_x_m)?;
    ranges::SHIFT.check(&format!("{key}.shift_y_m"), s.shift_y_m)?;
    ranges::ROTATION.check(&format!("{key}.rotation_rad"), s.rotation_rad)?;
    Ok(())
}

/// The steps of a static compression (conformal models): every shift zero,
/// no rolling, every step with a `normal_force_n`, increasing.
pub(super) fn static_compression(
    model: Model,
    t: &TransientSection,
) -> Result<Vec<ShiftStep>, CaseError> {
    let no_rolling = |key: String| {
        bad(
            key,
            format!(
                "the {} model runs static compression only: no rolling steps",
                model.name()
            ),
        )
    };
    if t.rolling_step_m.is_some() {
        return Err(no_rolling("transient.rolling_step_m".into()));
    }
    let mut out: Vec<ShiftStep> = Vec::with_capacity(t.steps.len());
    let mut previous = 0.0;
    for (k, s) in t.steps.iter().enumerate() {
        let key = format!("transient.steps[{k}]");
        if s.creepages(&key)?.is_some() {
            return Err(no_rolling(format!("{key}.creepage_long")));
        }
        if s.rolling_m.is_some() {
            return Err(no_rolling(format!("{key}.rolling_m")));
        }
        for (name, given) in [
            ("force_x_n", s.force_x_n.is_some()),
            ("force_y_n", s.force_y_n.is_some()),
            ("force_x_n_per_m", s.force_x_n_per_m.is_some()),
        ] {
            if given {
                return Err(bad(
                    format!("{key}.{name}"),
                    format!(
                        "the {} model runs static compression only: no tangential forces",
                        model.name()
                    ),
                ));
            }
        }
        for (name, v) in [
            ("shift_x_m", s.shift_x_m.unwrap_or(0.0)),
            ("shift_y_m", s.shift_y_m),
            ("rotation_rad", s.rotation_rad),
        ] {
            if v != 0.0 {
                return Err(bad(
                    format!("{key}.{name}"),
                    format!(
                        "the {} model runs static compression only: shifts and rotations must be 0, got {v}",
                        model.name()
                    ),
                ));
            }
        }
        if s.approach_m.is_some() {
            return Err(bad(
                format!("{key}.approach_m"),
                format!(
                    "the {} model's load steps are forces: give `normal_force_n` instead",
                    model.name()
                ),
            ));
        }
        let f = s.normal_force_n.ok_or_else(|| {
            bad(
                format!("{key}.normal_force_n"),
                "missing: every static compression step gives its normal force",
            )
        })?;
        ranges::NORMAL_FORCE.check(&format!("{key}.normal_force_n"), f)?;
        if f <= previous {
            return Err(bad(
                format!("{key}.normal_force_n"),
                format!("static compression loads monotonically: {f} N must exceed the previous step's {previous} N"),
            ));
        }
        previous = f;
        out.push(ShiftStep {
            load: NormalLoad::NormalForce(f),
            shift_x_m: 0.0,
            shift_y_m: 0.0,
            rotation_rad: 0.0,
            rolling_m: 0.0,
        });
    }
    Ok(out)
}

/// A case's motion, validated: the kinematics, with the tangential forces
/// that steady rolling or the transient steps prescribe.
pub(super) struct CaseMotion {
    pub(super) kinematics: Kinematics,
    pub(super) prescribed_force: PrescribedForce,
    pub(super) step_forces: Vec<PrescribedForce>,
    pub(super) step_gap_offsets_m: Vec<f64>,
    /// `transient.steady_start`, checked.
    pub(super) steady_start: Option<Creepages>,
    /// Each step's `friction_start` (empty when no step gives one).
    pub(super) step_slip_starts: Vec<Option<SlipStart>>,
}

/// The `[rolling]` or `[transient]` of `file` (neither: frictionless
/// contact), checked against `model`, the case's `[load]` and whether the
/// contact is a line.
pub(super) fn case_motion(
    file: &CaseFile,
    model: Model,
    load: NormalLoad,
    line: bool,
) -> Result<CaseMotion, CaseError> {
    let mut prescribed_force = PrescribedForce::default();
    let mut step_forces = Vec::new();
    let mut step_gap_offsets_m = Vec::new();
    let mut steady_start = None;
    let mut step_slip_starts = Vec::new();
    let kinematics = match (&file.rolling, &file.transient) {
        (Some(_), Some(_)) => {
            return Err(bad(
                "transient",
                "`[rolling]` and `[transient]` exclude each other; give one of them",
            ));
        }
        (Some(rs), None) => {
            let (r, force) = rs.split()?;
            r.check_input()?;
            check_line_rolling(rs, line)?;
            if force.any() && model != Model::Exact {
                let key = if force.force_x_n.is_some() {
                    "rolling.force_x_n"
                } else {
                    "rolling.force_y_n"
                };
                return Err(bad(
                    key,
                    format!(
                        "a prescribed force is solved with the exact model only, not {}{}: give \
                         `rolling.creepage_long`/`creepage_lat`, or `model = \"exact\"`",
                        model.name(),
                        if matches!(model, Model::Hertz | Model::HertzCorrected) {
                            " (it has no tangential forces)"
                        } else {
                            ""
                        }
                    ),
                ));
            }
            prescribed_force = force;
            if model.is_cect() {
                if let NormalLoad::Approach(_) = load {
                    return Err(bad(
                        "load.approach_m",
                        format!(
                            "the {} model rolls at a prescribed normal force: give `load.normal_force_n`",
                            model.name()
                        ),
                    ));
                }
            }
            Kinematics::SteadyRolling(r)
        }
        (None, Some(t)) => {
            if t.steps.is_empty() {
                return Err(bad("transient.steps", "needs at least one step"));
            }
            if let Some(dq) = t.rolling_step_m {
                ranges::ROLLING_STEP.check("transient.rolling_step_m", dq)?;
            }
            if let Some(c) = t.steady_start {
                steady_start = Some(steady_start_creepages(c, model, line)?);
            }
            if t.steps.iter().any(|s| s.friction_start.is_some()) {
                step_slip_starts = t.steps.iter().map(|s| s.friction_start).collect();
            }
            if model.is_cect() {
                Kinematics::Transient(static_compression(model, t)?)
            } else {
                let mut steps = Vec::with_capacity(t.steps.len());
                let mut forces = Vec::with_capacity(t.steps.len());
                let mut offsets = Vec::with_capacity(t.steps.len());
                let mut offset = 0.0;
                for (k, s) in t.steps.iter().enumerate() {
                    let key = format!("transient.steps[{k}]");
                    let given_gap = file.geometry.gap_m.is_some();
                    let t =
                        transient_step(&key, s, load, t.rolling_step_m, line, model, given_gap)?;
                    offset += t.gap_travel_x_m;
                    offsets.push(offset);
                    if t.force.any() && model != Model::Exact {
                        return Err(bad(
                            format!("{key}.force_x_n"),
                            format!(
                                "a prescribed force is solved with the exact model only, not {}",
                                model.name()
                            ),
                        ));
                    }
                    steps.push(t.step);
                    forces.push(t.force);
                }
                if forces.iter().any(PrescribedForce::any) {
                    step_forces = forces;
                }
                if t.steps.iter().any(|s| s.gap_travel_x_m.is_some()) {
                    step_gap_offsets_m = offsets;
                }
                Kinematics::Transient(steps)
            }
        }
        (None, None) => Kinematics::Frictionless,
    };
    Ok(CaseMotion {
        kinematics,
        prescribed_force,
        step_forces,
        step_gap_offsets_m,
        steady_start,
        step_slip_starts,
    })
}

/// `transient.steady_start`'s creepages `c`, checked against their
/// ranges (a line contact rolls with longitudinal creepage only) and
/// `model` (exact only).
fn steady_start_creepages(c: Creepages, model: Model, line: bool) -> Result<Creepages, CaseError> {
    const KEY: &str = "transient.steady_start";
    if model != Model::Exact {
        return Err(bad(
            KEY,
            format!(
                "a steady rolling start is solved with the exact model only, not {}",
                model.name()
            ),
        ));
    }
    c.check_input()
        .map_err(|e| e.with_key_prefix("rolling", KEY))?;
    if line {
        refuse_lateral(
            KEY,
            "rolls",
            &[
                ("creepage_lat", c.creepage_lat != 0.0),
                ("spin_per_m", c.spin_per_m != 0.0),
            ],
        )?;
    }
    Ok(c)
}

#[cfg(test)]
mod prescribed_force_tests {
    use crate::problem::case::*;

    fn case(model: &str, rolling: &str) -> Result<Case, CaseError> {
        Case::from_toml(&format!(
            "model = \"{model}\"\n[material]\nshear_modulus_pa = 81.0e9\npoisson_ratio = 0.3\n\
             [friction]\ncoefficient = 0.3\n[geometry]\nkind = \"quadratic\"\na_per_m = 1.0\n\
             b_per_m = 1.0\n[load]\nnormal_force_n = 1e4\n[rolling]\n{rolling}\n"
        ))
    }

    fn message(r: Result<Case, CaseError>) -> String {
        match r {
            Err(CaseError::BadInput(m)) => m,
            other => panic!("expected bad input, got {other:?}"),
        }
    }

    #[test]
    fn a_force_replaces_the_creepage_of_its_direction() {
        let c = case(
            "exact",
            "force_x_n = -500.0\ncreepage_lat = 2e-4\nspin_per_m = 0.1",
        )
        .unwrap();
        assert_eq!(c.prescribed_force.force_x_n, Some(-500.0));
        assert_eq!(c.prescribed_force.force_y_n, None);
        // The iteration starts from creepage 0; the other ones are kept.
        assert_eq!(
            c.kinematics,
            Kinematics::SteadyRolling(Creepages {
                creepage_long: 0.0,
                creepage_lat: 2e-4,
                spin_per_m: 0.1
            })
        );
        let c = case("exact", "force_x_n = -500.0\nforce_y_n = 100.0").unwrap();
        assert_eq!(c.prescribed_force.force_y_n, Some(100.0));
    }

    #[test]
    fn both_keys_of_a_direction_and_other_models_are_refused_naming_the_keys() {
        for (creep, force) in [
            ("creepage_long", "force_x_n"),
            ("creepage_lat", "force_y_n"),
        ] {
            let m = message(case("exact", &format!("{creep} = 1e-3\n{force} = -10.0")));
            assert!(
                m.contains(&format!("`rolling.{force}`"))
                    && m.contains(&format!("`rolling.{creep}`")),
                "{m}"
            );
        }
        let m = message(case("exact", "force_y_n = 1e300"));
        assert!(m.contains("rolling.force_y_n"), "{m}");
        let m = message(case("hertz", "force_x_n = -10.0"));
        assert!(
            m.contains("rolling.force_x_n") && m.contains("no tangential forces"),
            "{m}"
        );
        let m = message(case("fastsim", "force_y_n = -10.0"));
        assert!(
            m.contains("rolling.force_y_n") && m.contains("exact model only"),
            "{m}"
        );
    }
}

#[cfg(test)]
mod step_force_tests {
    use crate::problem::case::*;
    use crate::problem::ExactRun;

    /// A transient exact case (0.5 mm elements on 16 x 16) with `steps`.
    fn case(steps: &str) -> Result<Case, CaseError> {
        Case::from_toml(&format!(
            "model = \"exact\"\n[material]\nshear_modulus_pa = 81.0e9\npoisson_ratio = 0.3\n\
             [friction]\ncoefficient = 0.3\n[geometry]\nkind = \"quadratic\"\na_per_m = 1.0\n\
             b_per_m = 1.0\n[load]\nnormal_force_n = 1e4\n[grid]\nnx = 16\nny = 16\n\
             window_x_m = 8e-3\nwindow_y_m = 8e-3\n[transient]\nrolling_step_m = 5e-4\n\
             steps = [{steps}]\n"
        ))
    }

    fn message(r: Result<Case, CaseError>) -> String {
        match r {
            Err(CaseError::BadInput(m)) => m,
            other => panic!("expected bad input, got {other:?}"),
        }
    }

    #[test]
    fn a_step_force_replaces_the_shift_or_creepage_of_its_direction() {
        let c = case(
            "{ shift_x_m = 1e-6 }, { force_x_n = -300.0, shift_y_m = 1e-7 }, \
             { force_y_n = 200.0, creepage_long = 1e-3 }, { force_x_n = -100.0, rolling_m = 1e-3 }",
        )
        .unwrap();
        let x = |f: f64| PrescribedForce {
            force_x_n: Some(f),
            force_y_n: None,
        };
        assert_eq!(
            c.step_forces,
            [
                PrescribedForce::default(),
                x(-300.0),
                PrescribedForce {
                    force_x_n: None,
                    force_y_n: Some(200.0)
                },
                x(-100.0)
            ]
        );
        let Kinematics::Transient(steps) = &c.kinematics else {
            panic!("{:?}", c.kinematics)
        };
        // The prescribed directions start from 0; a rolling step rolls
        // `transient.rolling_step_m` or its own `rolling_m`.
        let shifts: Vec<[f64; 3]> = steps
            .iter()
            .map(|s| [s.shift_x_m, s.shift_y_m, s.rolling_m])
            .collect();
        assert_eq!(
            shifts,
            [
                [1e-6, 0.0, 0.0],
                [0.0, 1e-7, 0.0],
                [1e-3 * 5e-4, 0.0, 5e-4],
                [0.0, 0.0, 1e-3]
            ]
        );
        assert!(case("{ shift_x_m = 1e-6 }").unwrap().step_forces.is_empty());
        // Travel accumulates over the steps.
        let c = case(
            "{ shift_x_m = 0.0, gap_travel_x_m = -1e-3 }, { shift_x_m = 0.0 }, \
             { shift_x_m = 0.0, gap_travel_x_m = 5e-4 }",
        )
        .unwrap();
        assert_eq!(c.step_gap_offsets_m, [-1e-3, -1e-3, -5e-4]);
        assert!(case("{ shift_x_m = 1e-6 }")
            .unwrap()
            .step_gap_offsets_m
            .is_empty());
    }

    #[test]
    fn conflicting_step_keys_are_refused_naming_them() {
        for (steps, keys) in [
            (
                "{ shift_x_m = 1e-6, force_x_n = 10.0 }",
                &[
                    "transient.steps[0].force_x_n",
                    "transient.steps[0].shift_x_m",
                ][..],
            ),
            (
                "{ shift_x_m = 0.0, shift_y_m = 1e-6, force_y_n = 10.0 }",
                &["transient.steps[0].force_y_n"],
            ),
            (
                "{ creepage_long = 1e-3, force_x_n = 10.0 }",
                &["transient.steps[0].force_x_n", "creepage_long"],
            ),
            (
                "{ force_x_n = 10.0, force_y_n = 10.0, shift_y_m = 1e-7 }",
                &["transient.steps[0].force_y_n", "shift_y_m"],
            ),
            (
                "{ force_x_n_per_m = 10.0 }",
                &["transient.steps[0].force_x_n_per_m", "line"],
            ),
            ("{ force_x_n = 1e300 }", &["transient.steps[0].force_x_n"]),
            ("{ force_x_n = nan }", &["transient.steps[0].force_x_n"]),
            (
                "{ shift_x_m = 0.0 }, { force_x_n = 1.0, rolling_m = -1e-4 }",
                &["transient.steps[1].rolling_m"],
            ),
            (
                "{ rolling_m = 5e-4 }",
                &["transient.steps[0].shift_x_m", "force_x_n"],
            ),
            (
                "{ shift_x_m = 0.0 }, { creepage_long = 1e-3, gap_travel_x_m = 5e-4 }",
                &["transient.steps[1].gap_travel_x_m", "rolling step"],
            ),
            (
                "{ shift_x_m = 0.0, gap_travel_x_m = 2.0 }",
                &["transient.steps[0].gap_travel_x_m"],
            ),
        ] {
            let m = message(case(steps));
            for k in keys {
                assert!(m.contains(k), "{steps}: {m}");
            }
        }
    }

    #[test]
    fn bodies_travelling_off_the_grid_are_told_how_far_they_went() {
        // A patch of radius 3.2 mm on a window of 8 mm: 1.5 mm of travel
        // puts it on the grid's border.
        let c = case("{ shift_x_m = 0.0 }, { shift_x_m = 0.0, gap_travel_x_m = 1.5e-3 }").unwrap();
        let m = ExactRun::solve(&c).err().unwrap().to_string();
        assert!(
            m.contains("grid.window_x_m")
                && m.contains("transient.steps[1]")
                && m.contains("0.0015 m"),
            "{m}"
        );
    }

    #[test]
    fn step_forces_are_solved_and_reported_per_step() {
        // The Fx of a forward step, prescribed, gives back its shift.
        let forward = case("{ shift_x_m = 0.0 }, { shift_x_m = 2e-6 }").unwrap();
        let run = ExactRun::solve(&forward).unwrap();
        let fx = run.last().totals.fx_n;
        let c = case(&format!("{{ shift_x_m = 0.0 }}, {{ force_x_n = {fx:e} }}")).unwrap();
        let run = ExactRun::solve(&c).unwrap();
        let report = run.report(&c, false);
        let steps = report.steps.as_ref().unwrap();
        assert_eq!(steps[0].force_control, None);
        let f = steps[1].force_control.unwrap();
        assert!((f.shift_x_m - 2e-6).abs() < 1e-6 * 2e-6, "{f:?}");
        assert_eq!((f.creepage_long, f.rolling_m), (None, 0.0));
        let text = report.human();
        assert!(
            text.contains("step 2 prescribed force: shift x, y"),
            "{text}"
        );
        // Saturation names the step (beyond mu Fn = 3000 N: at exactly
        // 3000 N the refusal hinges on the last bit of the computed Fn).
        let c = case("{ shift_x_m = 0.0 }, { force_x_n = -3010.0 }").unwrap();
        let e = ExactRun::solve(&c).err().unwrap().to_string();
        assert!(e.contains("transient.steps[1].force_x_n"), "{e}");
    }
}

#[cfg(test)]
mod rolling_frame_tests {
    use crate::problem::case::tests::bad_key;

    use crate::core::solution::SolveStatus;
    use crate::problem::case::*;

    /// An exact steady-rolling case on a 24 x 20 grid with `extra` lines.
    fn rolling_case(extra: &str) -> String {
        format!(
            r#"
model = "exact"
{extra}
[material]
shear_modulus_pa = 80.0e9
poisson_ratio = 0.25
[friction]
coefficient = 0.3
[geometry]
kind = "quadratic"
a_per_m = 1.0
b_per_m = 0.6
[load]
normal_force_n = 10000.0
[rolling]
creepage_long = 3e-4
creepage_lat = -1e-4
spin_per_m = 0.5
[grid]
nx = 24
ny = 20
window_x_m = 12e-3
window_y_m = 14e-3
"#
        )
    }

    #[test]
    fn a_hertz_gap_given_per_element_is_the_quadratic_case_bit_for_bit() {
        // CONTACT's IBASE = 9 (user guide §"Non-Hertzian geometry
        // specification"): the values h(x_I) at the element centres.
        let quadratic = Case::from_toml(&rolling_case("")).unwrap();
        let h = quadratic.problem().unwrap().gap_m;
        let list: Vec<String> = h.iter().map(|v| format!("{v:?}")).collect();
        let text = rolling_case("").replace(
            "b_per_m = 0.6\n",
            &format!("b_per_m = 0.6\ngap_m = [{}]\n", list.join(", ")),
        );
        let given = Case::from_toml(&text).unwrap();
        assert_eq!(given.problem().unwrap().gap_m, h);
        let a = crate::core::solve::solve(&quadratic.problem().unwrap()).unwrap();
        let b = crate::core::solve::solve(&given.problem().unwrap()).unwrap();
        assert_eq!(a[0].info.status, SolveStatus::Converged);
        assert_eq!(format!("{:?}", a[0].totals), format!("{:?}", b[0].totals));
        assert_eq!(a[0].fields, b[0].fields);
    }

    #[test]
    fn a_rolling_direction_and_an_extra_slip_reach_the_problem() {
        let n = 24 * 20;
        let slip = |v: f64| vec![format!("{v:?}"); n].join(", ");
        let text = rolling_case(&format!(
            "rolling_direction_rad = 3.141592653589793\n[extra_rigid_slip]\nslip_x = [{}]\n",
            slip(1e-4)
        ));
        let p = Case::from_toml(&text).unwrap().problem().unwrap();
        assert_eq!(p.rolling_direction_rad, std::f64::consts::PI);
        let e = p.extra_rigid_slip.unwrap();
        assert_eq!(e.slip_x, vec![1e-4; n]);
        assert_eq!(e.slip_y, vec![0.0; n]);
    }

    #[test]
    fn bad_gaps_directions_and_slips_are_refused_naming_the_key() {
        let n = 24 * 20;
        let list = |k: usize, v: &str| vec![v; k].join(", ");
        let slip = |extra: &str| format!("[extra_rigid_slip]\n{extra}\n");
        for (text, key) in [
            (
                rolling_case("").replace(
                    "b_per_m = 0.6\n",
                    &format!("b_per_m = 0.6\ngap_m = [{}]\n", list(7, "0.0")),
                ),
                "`geometry.gap_m`",
            ),
            (
                rolling_case("").replace(
                    "b_per_m = 0.6\n",
                    &format!("b_per_m = 0.6\ngap_m = [nan, {}]\n", list(n - 1, "0.0")),
                ),
                "`geometry.gap_m[0]`",
            ),
            (
                rolling_case("rolling_direction_rad = nan"),
                "`rolling_direction_rad`",
            ),
            (
                rolling_case("rolling_direction_rad = 0.3"),
                "`rolling_direction_rad`",
            ),
            (
                rolling_case("rolling_direction_rad = 3.141592653589793")
                    .replace("model = \"exact\"", "model = \"fastsim\""),
                "`rolling_direction_rad`",
            ),
            (
                rolling_case(&slip(&format!("slip_y = [{}]", list(n + 1, "0.0")))),
                "`extra_rigid_slip.slip_y`",
            ),
            (
                rolling_case(&slip(&format!("slip_x = [inf, {}]", list(n - 1, "0.0")))),
                "`extra_rigid_slip.slip_x[0]`",
            ),
            (rolling_case(&slip("")), "`extra_rigid_slip`"),
            (
                rolling_case(&slip(&format!("shift_x_m = [{}]", list(n, "0.0")))),
                "`extra_rigid_slip.shift_x_m`",
            ),
            (
                rolling_case(&slip(&format!("shift_y_m = [{}]", list(n, "0.5")))),
                "`extra_rigid_slip.shift_y_m[0]`",
            ),
            (
                rolling_case(&slip(&format!("slip_x = [{}]", list(n, "0.0"))))
                    .replace("nx = 24\n", ""),
                "`extra_rigid_slip.slip_x`",
            ),
        ] {
            let m = bad_key(&text);
            assert!(m.contains(key), "{key}: {m}");
        }
    }

    #[test]
    fn rolling_along_y_steps_whole_elements_in_y() {
        // dx = 0.5 mm, dy = 0.7 mm: rolling in +y, a step of 0.5 mm is no
        // whole number of elements, one of 0.7 mm is.
        let text = |dq: f64| {
            rolling_case("rolling_direction_rad = 1.5707963267948966").replace(
                "[rolling]\ncreepage_long = 3e-4\ncreepage_lat = -1e-4\nspin_per_m = 0.5\n",
                &format!(
                    "[transient]\nrolling_step_m = {dq:?}\nsteps = [{{ creepage_lat = 3e-4 }}]\n"
                ),
            )
        };
        let m = bad_key(&text(0.5e-3));
        assert!(
            m.contains("`transient.rolling_step_m`") && m.contains("window_y_m"),
            "{m}"
        );
        assert!(Case::from_toml(&text(0.7e-3)).is_ok());
    }

    #[test]
    fn transient_steps_roll_any_distance_off_the_axes() {
        // chi = 0.5 rad: a step of 0.37 mm is 0.57 dx along x and 0.26 dy
        // along y (dx = 0.5 mm, dy = 0.7 mm), carried by interpolation;
        // steady rolling at 0.5 rad is refused.
        let text = |dq: f64| {
            rolling_case("rolling_direction_rad = 0.5").replace(
                "[rolling]\ncreepage_long = 3e-4\ncreepage_lat = -1e-4\nspin_per_m = 0.5\n",
                &format!(
                    "[transient]\nrolling_step_m = {dq:?}\nsteps = [{{ creepage_long = 3e-4 }}, \
                     {{ creepage_long = 3e-4 }}]\n"
                ),
            )
        };
        let run = |dq: f64| crate::problem::ExactRun::solve(&Case::from_toml(&text(dq)).unwrap());
        assert_eq!(run(0.37e-3).ok().unwrap().solutions.len(), 2);
        let m = run(0.1).err().unwrap().to_string();
        assert!(m.contains("transient.steps[0].rolling_m"), "{m}");
        let m = bad_key(&rolling_case("rolling_direction_rad = 0.5"));
        assert!(
            m.contains("`rolling_direction_rad`") && m.contains("steady"),
            "{m}"
        );
    }
}
