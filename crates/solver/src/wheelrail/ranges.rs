//! The documented ranges of a wheel/rail case's numbers, and the one check
//! of them that the command line (case files) and the service (requests)
//! both run, so that a value is refused the same way, naming the same key
//! (`position.lateral_m`, `wheelset.nominal_radius_m`), whichever way it
//! came. A value that fits once read in other units is said to be likely
//! in millimetres.

use crate::core::error::{show, ContactError, Range, UnitHint};
use crate::wheelrail::contact::WheelLoad;
use crate::wheelrail::wheelset::{
    RailPlacement, Side, TrackData, WheelsetData, WheelsetPosition, WheelsetVelocity,
};

/// `position.lateral_m` \[m\] (flange contact is at about 8 mm).
pub const LATERAL: Range = Range::symmetric(0.02, "m").hint(UnitHint::Millimetre);
/// `position.yaw_rad` \[rad\].
pub const YAW: Range = Range::symmetric(0.05, "rad");
/// `position.roll_rad` \[rad\].
pub const ROLL: Range = Range::symmetric(0.05, "rad");
/// The magnitude of `velocity.forward_m_per_s` \[m/s\], of either sign
/// ([`check_forward_speed`]): > 0 rolls forwards (along the track's +x),
/// < 0 backwards (towards -x: a reversing vehicle, a push-pull train, a
/// roller rig run backwards). 0 and speeds below 1 m/s are excluded:
/// creepages are velocities divided by the rolling speed.
pub const FORWARD_SPEED: Range = Range::closed(1.0, 150.0, "m/s");

/// The forward speed's two ranges as messages write them.
pub fn describe_forward_speed() -> String {
    let (lo, hi) = (FORWARD_SPEED.min, FORWARD_SPEED.max);
    format!(
        "[{}, {}] m/s (rolling backwards) or {}",
        show(-hi),
        show(-lo),
        FORWARD_SPEED.describe()
    )
}

/// `v` if its magnitude is in [`FORWARD_SPEED`] (either sign), else an
/// error naming `key` that states both ranges and why 0 is excluded.
pub fn check_forward_speed(key: &str, v: f64) -> Result<f64, ContactError> {
    if FORWARD_SPEED.contains(v.abs()) {
        return Ok(v);
    }
    Err(ContactError::invalid(
        key,
        format!(
            "must be in {}, got {} (creepages are divided by the rolling speed: it cannot be \
             about 0)",
            describe_forward_speed(),
            show(v)
        ),
    ))
}
/// `velocity.lateral_m_per_s`, `velocity.vertical_m_per_s` \[m/s\].
pub const TRANSVERSE_SPEED: Range = Range::symmetric(5.0, "m/s");
/// `velocity.roll_rad_per_s`, `velocity.yaw_rad_per_s` \[rad/s\].
pub const TURN_RATE: Range = Range::symmetric(5.0, "rad/s");
/// `velocity.pitch_rad_per_s` \[rad/s\] (free rolling: -V/r0).
pub const PITCH_RATE: Range = Range::symmetric(1000.0, "rad/s");
/// `load.vertical_force_n` \[N\] (total on both wheels).
pub const VERTICAL_FORCE: Range = Range::closed(1e2, 1e6, "N");
/// `load.approach_m` \[m\].
pub const APPROACH: Range = Range::positive(2e-3, "m").hint(UnitHint::Millimetre);
/// `load.total_longitudinal_force_n` \[N\] (its reach is checked against
/// saturation when solved).
pub const TOTAL_LONGITUDINAL_FORCE: Range = Range::symmetric(1e6, "N");
/// `load.center_z_m` \[m\]: z points down, so the centre of a wheelset on
/// its rails is at about minus the wheel radius.
pub const CENTER_Z: Range = Range::closed(-1.5, 0.0, "m");

/// `track.gauge_m` \[m\].
pub const GAUGE: Range = Range::closed(0.3, 3.0, "m").hint(UnitHint::Millimetre);
/// `track.gauge_height_m` \[m\]: depth below the top of the rail.
pub const GAUGE_HEIGHT: Range = Range::closed(0.0, 0.05, "m").hint(UnitHint::Millimetre);
/// `track.rail_origin_y_m` \[m\]: the right rail profile's origin (the
/// left's mirrored), absolute placement.
pub const RAIL_ORIGIN_Y: Range = Range::symmetric(3.0, "m").hint(UnitHint::Millimetre);
/// `track.rail_origin_z_m` \[m\] (z down).
pub const RAIL_ORIGIN_Z: Range = Range::symmetric(0.5, "m").hint(UnitHint::Millimetre);
/// `track.cant_rad` \[rad\]: rail inclination (1:40 is 0.025).
pub const CANT: Range = Range::symmetric(0.2, "rad");
/// `track.rail_deviation_left.dy_m`, `.dz_m` (and `_right`) \[m\]: a
/// rail's shift from its placement.
pub const RAIL_DEVIATION_SHIFT: Range = Range::symmetric(0.05, "m").hint(UnitHint::Millimetre);
/// `track.rail_deviation_left.droll_rad` (and `_right`) \[rad\]: a
/// rail's roll from its placement, the range of a rail inclination.
pub const RAIL_DEVIATION_ROLL: Range = CANT;
/// `wheelset.flange_back_distance_m` \[m\].
pub const FLANGE_BACK_DISTANCE: Range = Range::closed(0.2, 3.0, "m").hint(UnitHint::Millimetre);
/// `wheelset.nominal_radius_m` \[m\].
pub const NOMINAL_RADIUS: Range = Range::closed(0.05, 2.0, "m").hint(UnitHint::Millimetre);
/// `wheelset.flange_back_y_m` \[m\] (the profile's y of the back of the
/// flange; -0.070 for S1002).
pub const FLANGE_BACK_Y: Range = Range::symmetric(0.5, "m").hint(UnitHint::Millimetre);

/// The rollers of a roller rig as [`check_motion`] takes them.
#[derive(Debug, Clone, Copy)]
pub struct Rollers {
    /// Nominal radius \[m\] (`track.roller_radius_m`).
    pub radius_m: f64,
    /// Angular velocity \[rad/s\], > 0 rolling forwards (the rollers'
    /// top moving towards -x), < 0 backwards (`track.roller_rad_per_s`).
    pub rad_per_s: f64,
}

/// Case files' key of the rollers' angular velocity.
const ROLLER_RATE_KEY: &str = "track.roller_rad_per_s";

/// Checks a motion and load against their ranges; the error names the
/// key as a case file and a request both spell it. On a roller rig
/// (`rollers`) the rolling speed checked is the rollers' surface speed
/// (with the wheelset's forward speed, usually 0), named by the rollers'
/// rate.
pub fn check_motion(
    position: &WheelsetPosition,
    velocity: &WheelsetVelocity,
    load: &WheelLoad,
    total_longitudinal_force_n: Option<f64>,
    rollers: Option<Rollers>,
) -> Result<(), ContactError> {
    LATERAL.check("position.lateral_m", position.lateral_m)?;
    YAW.check("position.yaw_rad", position.yaw_rad)?;
    if let Some(r) = position.roll_rad {
        ROLL.check("position.roll_rad", r)?;
    }
    if !position.track_s_m.is_finite() {
        return Err(ContactError::invalid(
            "position.track_s_m",
            format!("must be finite, got {}", position.track_s_m),
        ));
    }
    match rollers {
        None => check_forward_speed("velocity.forward_m_per_s", velocity.forward_m_per_s)?,
        Some(r) => {
            let speed = velocity.forward_m_per_s + r.radius_m * r.rad_per_s;
            check_forward_speed(ROLLER_RATE_KEY, speed).map_err(|e| match e {
                ContactError::InvalidInput { key, reason } => ContactError::InvalidInput {
                    key,
                    reason: format!(
                        "the rollers' surface speed (track.roller_radius_m x \
                         track.roller_rad_per_s, with velocity.forward_m_per_s) {reason}"
                    ),
                },
                e => e,
            })?
        }
    };
    TRANSVERSE_SPEED.check("velocity.lateral_m_per_s", velocity.lateral_m_per_s)?;
    TRANSVERSE_SPEED.check("velocity.vertical_m_per_s", velocity.vertical_m_per_s)?;
    TURN_RATE.check("velocity.roll_rad_per_s", velocity.roll_rad_per_s)?;
    TURN_RATE.check("velocity.yaw_rad_per_s", velocity.yaw_rad_per_s)?;
    if let Some(w) = velocity.pitch_rad_per_s {
        PITCH_RATE.check("velocity.pitch_rad_per_s", w)?;
    }
    if let Some(f) = total_longitudinal_force_n {
        TOTAL_LONGITUDINAL_FORCE
            .check(crate::wheelrail::contact::TOTAL_LONGITUDINAL_FORCE_KEY, f)?;
    }
    match *load {
        WheelLoad::VerticalForce(f) => VERTICAL_FORCE.check("load.vertical_force_n", f),
        WheelLoad::Approach(d) => APPROACH.check("load.approach_m", d),
        WheelLoad::CenterHeight(z) => CENTER_Z.check("load.center_z_m", z),
    }?;
    Ok(())
}

/// Checks a track and wheelset against their ranges, naming the key.
pub fn check_geometry(track: &TrackData, wheelset: &WheelsetData) -> Result<(), ContactError> {
    check_track(track)?;
    check_wheelset(wheelset)
}

/// Checks a track against its ranges, naming the key.
pub fn check_track(track: &TrackData) -> Result<(), ContactError> {
    match track.placement {
        RailPlacement::GaugePoint {
            gauge_m,
            gauge_height_m,
        } => {
            GAUGE.check("track.gauge_m", gauge_m)?;
            GAUGE_HEIGHT.check("track.gauge_height_m", gauge_height_m)?;
        }
        RailPlacement::Origin { q_m, z_m } => {
            RAIL_ORIGIN_Y.check("track.rail_origin_y_m", q_m)?;
            RAIL_ORIGIN_Z.check("track.rail_origin_z_m", z_m)?;
        }
    }
    CANT.check("track.cant_rad", track.cant_rad)?;
    for side in Side::BOTH {
        let d = &track.deviations[side.index()];
        let key = |field: &str| format!("track.rail_deviation_{}.{field}", side.name());
        RAIL_DEVIATION_SHIFT.check(&key("dy_m"), d.dy_m)?;
        RAIL_DEVIATION_SHIFT.check(&key("dz_m"), d.dz_m)?;
        RAIL_DEVIATION_ROLL.check(&key("droll_rad"), d.droll_rad)?;
    }
    Ok(())
}

/// Checks a wheelset's dimensions against their ranges, naming the key.
pub fn check_wheelset(wheelset: &WheelsetData) -> Result<(), ContactError> {
    FLANGE_BACK_DISTANCE.check(
        "wheelset.flange_back_distance_m",
        wheelset.flange_back_distance_m,
    )?;
    NOMINAL_RADIUS.check("wheelset.nominal_radius_m", wheelset.nominal_radius_m)?;
    if let Some(y) = wheelset.flange_back_y_m {
        FLANGE_BACK_Y.check("wheelset.flange_back_y_m", y)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The three: a lateral shift, a radius and a roll given in
    /// millimetres or beyond reason, each named with its key and value.
    #[test]
    fn values_out_of_range_name_their_key_and_a_likely_unit() {
        let position = WheelsetPosition {
            lateral_m: 6.5,
            yaw_rad: 0.0,
            roll_rad: None,
            track_s_m: 0.0,
        };
        let velocity = WheelsetVelocity {
            forward_m_per_s: 2.0,
            lateral_m_per_s: 0.0,
            vertical_m_per_s: 0.0,
            roll_rad_per_s: 0.0,
            yaw_rad_per_s: 0.0,
            pitch_rad_per_s: None,
        };
        let load = WheelLoad::VerticalForce(1e4);
        let e = check_motion(&position, &velocity, &load, None, None)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("position.lateral_m") && e.contains("6.5") && e.contains("0.0065 m"),
            "{e}"
        );
        let rolled = WheelsetPosition {
            lateral_m: 0.0,
            roll_rad: Some(-0.25),
            ..position
        };
        let e = check_motion(&rolled, &velocity, &load, None, None)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("position.roll_rad") && e.contains("-0.25"),
            "{e}"
        );
        let track = TrackData::gauge_point(1.435, 0.014, 0.0);
        let wheelset = WheelsetData {
            flange_back_distance_m: 1.36,
            nominal_radius_m: 460.0,
            flange_back_y_m: Some(-0.07),
        };
        let e = check_geometry(&track, &wheelset).unwrap_err().to_string();
        assert!(
            e.contains("wheelset.nominal_radius_m") && e.contains("0.46 m"),
            "{e}"
        );
    }

    /// Rolling backwards is a speed in [-150, -1] m/s, on a track and on
    /// a roller rig; about 0 either way is refused naming the key and
    /// saying why.
    #[test]
    fn forward_speed_takes_either_sign_but_not_about_zero() {
        let position = WheelsetPosition {
            lateral_m: 0.0,
            yaw_rad: 0.0,
            roll_rad: None,
            track_s_m: 0.0,
        };
        let load = WheelLoad::VerticalForce(1e4);
        let check = |v: f64, rollers: Option<Rollers>| {
            let velocity = WheelsetVelocity::rolling(v);
            check_motion(&position, &velocity, &load, None, rollers)
        };
        for v in [-150.0, -20.0, -1.0, 1.0, 150.0] {
            check(v, None).unwrap();
        }
        for v in [-150.5, -0.5, 0.0, 0.5, 151.0, f64::NAN] {
            let e = check(v, None).unwrap_err().to_string();
            assert!(
                e.contains("velocity.forward_m_per_s")
                    && e.contains("[-150, -1] m/s (rolling backwards) or [1, 150] m/s")
                    && e.contains("divided by the rolling speed"),
                "{v}: {e}"
            );
        }
        let rollers = |rad_per_s| {
            Some(Rollers {
                radius_m: 0.4,
                rad_per_s,
            })
        };
        check(0.0, rollers(-50.0)).unwrap();
        let e = check(0.0, rollers(-1.0)).unwrap_err().to_string();
        assert!(
            e.contains(ROLLER_RATE_KEY) && e.contains("surface speed"),
            "{e}"
        );
    }
}
