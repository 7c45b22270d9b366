//! Roller rigs and track curvature against analytic results: a sphere on a
//! roller is a Hertzian contact with both bodies curved along x; the
//! creepages of a roller rig come from the roller's surface speed; a track
//! curvature k adds the turning of the track frame (CONTACT's user guide,
//! "Track and roller geometry" and "Wheelset position and velocity"; its
//! `wr_creep_cref`).

use railcontact_solver::core::cache::KernelCache;
use railcontact_solver::core::hertz::{hertz, HertzLoad};
use railcontact_solver::core::material::{CombinedMaterial, Material};
use railcontact_solver::core::problem::Friction;
use railcontact_solver::wheelrail::{
    load_profile, solve_wheelset, PatchResult, RailMotion, RailPlacement, SearchScratch, Side,
    SplineOptions, TrackData, WheelLoad, WheelRailInput, WheelRailModel, WheelRailPair,
    WheelRailSettings, WheelsetData, WheelsetPosition, WheelsetVelocity,
};

/// Wheel radius \[m\] (`circ_r100.prw` at this nominal radius: a sphere).
const RW: f64 = 0.1;
/// Roller radius \[m\] (CONTACT's test-rollers2.inp: NOMRAD_R 400 mm).
const RR: f64 = 0.4;

/// A sphere of radius 0.1 m (`circ_r100.prw`) over a flat profile
/// (`flat_plane.prr`) whose origin lies at y = 0.2 m, z = 0: on a roller of
/// radius `roller` (a cylinder about y) or a track, with `curvature`.
fn sphere_pair(roller: Option<f64>, curvature_per_m: f64) -> WheelRailPair {
    let load = |n: &str| load_profile(crate::profile_path(n)).unwrap();
    let (rail, wheel) = (load("flat_plane.prr"), load("circ_r100.prw"));
    WheelRailPair::new(
        [&rail, &rail],
        [&wheel, &wheel],
        TrackData {
            placement: RailPlacement::Origin { q_m: 0.2, z_m: 0.0 },
            cant_rad: 0.0,
            deviations: Default::default(),
            roller_radius_m: roller,
            curvature_per_m,
        },
        WheelsetData {
            flange_back_distance_m: 0.3,
            nominal_radius_m: RW,
            flange_back_y_m: Some(-0.05),
        },
        &SplineOptions::default(),
    )
    .unwrap()
}

/// The right wheel at an approach of 0.16 mm (test-rollers2.inp's), rolling
/// at `forward` m/s with pitch rate `pitch`, the rollers turning at
/// `roller_rate`.
fn input(model: WheelRailModel, forward: f64, pitch: f64, roller_rate: f64) -> WheelRailInput {
    WheelRailInput {
        position: WheelsetPosition {
            roll_rad: Some(0.0),
            ..Default::default()
        },
        velocity: WheelsetVelocity {
            pitch_rad_per_s: Some(pitch),
            ..WheelsetVelocity::rolling(forward)
        },
        load: WheelLoad::Approach(0.16e-3),
        sides: vec![Side::Right],
        material: CombinedMaterial::identical(Material {
            shear_modulus_pa: 82e9,
            poisson_ratio: 0.28,
        })
        .unwrap(),
        friction: Friction::coulomb(0.3),
        friction_table: None,
        settings: WheelRailSettings {
            model,
            element_size_m: 2e-4,
            ..WheelRailSettings::default()
        },
        total_longitudinal_force_n: None,
        temperature: None,
        rail_motion: [RailMotion {
            roller_rad_per_s: roller_rate,
            ..RailMotion::default()
        }; 2],
        rail_slices: Default::default(),
    }
}

fn patch(pair: &WheelRailPair, input: &WheelRailInput) -> PatchResult {
    let mut scratch = SearchScratch::default();
    let sol = solve_wheelset(pair, input, KernelCache::global(), &mut scratch).unwrap();
    let patches = &sol.wheels[0].patches;
    assert_eq!(patches.len(), 1);
    patches[0].clone()
}

/// A sphere of radius Rw on a roller of radius Rr (a cylinder about the
/// lateral axis) is Hertz's problem with the curvatures A = (1/Rw +
/// 1/Rr) / 2 along x and B = 1/(2 Rw) across (as two crossed cylinders,
/// the wheel's lateral curvature added): 92 007 N at 0.16 mm (this
/// crate's `hertz`, steel G 82 GPa, nu 0.28), where the sphere on a plane
/// (A = B) carries 97 185 N, 5.6 % more, so a roller's curvature left out
/// fails the test. The solver's Hertz model reads its curvatures off the
/// sampled profiles and carries 0.06 % more than Hertz on the plane (its
/// fit of the lateral curvature); on the roller it must carry the same
/// 0.06 % more, within 1e-4 (the roller's curvature exact to that). The
/// exact model on its 0.2 mm grid lies within 0.1 % of Hertz: CONTACT's
/// exact results on the same grid lie 0.04 % (test-rollers2.ref_out case 1,
/// the sphere on the plane: 9.722E+04 N) and 0.002 % (its case 6, "2a",
/// a cylinder of 133.3 mm on a roller of 400 mm by 100 mm, A = B = 5 /m:
/// 9.719E+04 N, the library's 97 186.9 N) above Hertz.
#[test]
fn a_sphere_on_a_roller_is_hertz_with_both_curvatures_along_x() {
    let pair = sphere_pair(Some(RR), 0.0);
    let rate = 1.0;
    let pitch = -rate * RR / RW;
    let e_star = input(WheelRailModel::Exact, 0.0, pitch, rate)
        .material
        .effective_modulus_pa();
    let a = 0.5 * (1.0 / RW + 1.0 / RR);
    let b = 0.5 / RW;
    let reference = hertz(
        a,
        b,
        e_star,
        HertzLoad::Approach {
            approach_m: 0.16e-3,
        },
    )
    .unwrap();
    let on_track = hertz(
        b,
        b,
        e_star,
        HertzLoad::Approach {
            approach_m: 0.16e-3,
        },
    )
    .unwrap();
    assert!(
        (reference.normal_force_n / on_track.normal_force_n - 1.0).abs() > 0.05,
        "the roller must matter"
    );
    let h = patch(
        &pair,
        &input(WheelRailModel::HertzFastsim, 0.0, pitch, rate),
    );
    let fh = h.normal_force_n;
    let track = sphere_pair(None, 0.0);
    let ht = patch(
        &track,
        &input(WheelRailModel::HertzFastsim, 10.0, -100.0, 0.0),
    );
    let (ratio, ratio_track) = (
        fh / reference.normal_force_n,
        ht.normal_force_n / on_track.normal_force_n,
    );
    assert!(
        (ratio - ratio_track).abs() < 1e-4 && (ratio_track - 1.0).abs() < 1e-3,
        "Hertz model {fh} N against Hertz {} N ({ratio}); on the plane {ratio_track}",
        reference.normal_force_n
    );
    let x = patch(&pair, &input(WheelRailModel::Exact, 0.0, pitch, rate));
    let fx = x.normal_force_n;
    assert!(
        (fx / reference.normal_force_n - 1.0).abs() < 1e-3,
        "exact {fx} N, Hertz {} N",
        reference.normal_force_n
    );
}

/// On a roller the creepages are relative to the roller's surface: with
/// the wheel's pitch rate w = -(1 + c) W Rr / Rw (W the roller's rate) and
/// the contact at both nominal radii, the surfaces move at -W Rr (roller)
/// and -(1 + c) W Rr (wheel), CONTACT's reference speed is their mean
/// (2 + c) W Rr / 2, and the longitudinal creepage (roller - wheel) / V is
/// c / (1 + c / 2); the rolling speed reported is that mean. The wheelset
/// itself stands still (forward speed 0).
#[test]
fn a_rollers_creepage_is_relative_to_its_surface() {
    let pair = sphere_pair(Some(RR), 0.0);
    let w = 2.5;
    for c in [0.0, 1e-3, -2e-3] {
        let pitch = -(1.0 + c) * w * RR / RW;
        let p = patch(&pair, &input(WheelRailModel::HertzFastsim, 0.0, pitch, w));
        // The contact point lies 0.08 mm (half the approach) into the
        // roller's surface: its radius and the wheel's differ by 1e-4 of
        // the radii, which is the tolerance on c.
        let expected = c / (1.0 + 0.5 * c);
        assert!(
            (p.creepage_long - expected).abs() < 1e-6,
            "c = {c}: {} against {expected}",
            p.creepage_long
        );
        let speed = 0.5 * (2.0 + c) * w * RR;
        assert!(
            (p.rolling_speed_m_per_s / speed - 1.0).abs() < 1e-3,
            "{} against {speed}",
            p.rolling_speed_m_per_s
        );
        assert!(p.creepage_lat.abs() < 1e-12 && p.spin_per_m.abs() < 1e-9);
    }
}

/// In a curve of curvature k the rails turn about the track's z axis at
/// -V k relative to the track frame (CONTACT's `wr_creep_cref`): the rail
/// point at track y moves forwards at V k y, and the rail turns at -V k.
/// At free rolling (the sphere on the plane, contact at the nominal radius)
/// the wheelset moves at V, the wheel's point at 0 and the rail's at V k y:
/// the reference speed is (V (1 - k y) + V) / 2, so the longitudinal
/// creepage is k y / (1 - k y / 2) and the spin -k / (1 - k y / 2) for the
/// right wheel (CONTACT's library gives 0.002002 and -1.001e-5 /mm for
/// k = 1e-5 /mm at y = 200 mm; `crates/cntc/tests/rollers.rs`). The same
/// curvature on the left wheel (its side frame mirrored) changes sign with
/// y.
#[test]
fn a_track_curvature_turns_the_rails_under_the_wheelset() {
    let v = 10.0;
    for k in [0.01, -0.004] {
        let pair = sphere_pair(None, k);
        let mut inp = input(WheelRailModel::HertzFastsim, v, -v / RW, 0.0);
        let straight = patch(&sphere_pair(None, 0.0), &inp);
        assert!(straight.creepage_long.abs() < 1e-6 && straight.spin_per_m.abs() < 1e-9);
        for side in Side::BOTH {
            inp.sides = vec![side];
            let p = patch(&pair, &inp);
            let y = p.track_y_m;
            assert!((y.abs() - 0.2).abs() < 1e-9, "{y}");
            let d = 1.0 - 0.5 * k * y;
            let xi = k * y / d;
            // The straight track's creepage (below 1e-6: the contact
            // point's radius) shifts the reference speed by half of it:
            // cross terms below 1e-8.
            assert!(
                (p.creepage_long - straight.creepage_long - xi).abs() < 1e-8,
                "{side:?} k {k}: {} against {xi}",
                p.creepage_long
            );
            // The side frame's spin: -s k / d, exactly -s V k over the
            // reference speed reported.
            let phi = -side.sign() * k / d;
            assert!(
                (p.spin_per_m - phi).abs() < 1e-8
                    && (p.spin_per_m + side.sign() * v * k / p.rolling_speed_m_per_s).abs() < 1e-15,
                "{side:?} k {k}: spin {} against {phi}",
                p.spin_per_m
            );
        }
    }
}

/// A roller rig's rate without a roller, a track without a forward speed,
/// rollers standing still (either way of rolling is solved, none is not),
/// the conformal model on a roller and a bad roller radius or curvature
/// are refused naming their keys.
#[test]
fn bad_roller_and_curvature_inputs_are_refused_naming_their_keys() {
    let err = |pair: &WheelRailPair, inp: &WheelRailInput| {
        let mut scratch = SearchScratch::default();
        solve_wheelset(pair, inp, KernelCache::global(), &mut scratch)
            .unwrap_err()
            .to_string()
    };
    let track = sphere_pair(None, 0.0);
    let e = err(
        &track,
        &input(WheelRailModel::HertzFastsim, 10.0, -100.0, 1.0),
    );
    assert!(e.contains("rail_motion.roller_rad_per_s"), "{e}");
    // On a track the wheelset must move (forwards or backwards).
    let e = err(
        &track,
        &input(WheelRailModel::HertzFastsim, 0.0, -100.0, 0.0),
    );
    assert!(e.contains("velocity.forward_m_per_s"), "{e}");
    let rig = sphere_pair(Some(RR), 0.0);
    let e = err(&rig, &input(WheelRailModel::HertzFastsim, 0.0, -4.0, 0.0));
    assert!(e.contains("rail_motion.roller_rad_per_s"), "{e}");
    let e = err(&rig, &input(WheelRailModel::Cect, 0.0, -4.0, 1.0));
    assert!(e.contains("model"), "{e}");
    let load = |n: &str| load_profile(crate::profile_path(n)).unwrap();
    let (rail, wheel) = (load("flat_plane.prr"), load("circ_r100.prw"));
    let place = |roller: Option<f64>, cant: f64, k: f64| {
        WheelRailPair::new(
            [&rail, &rail],
            [&wheel, &wheel],
            TrackData {
                placement: RailPlacement::Origin { q_m: 0.2, z_m: 0.0 },
                cant_rad: cant,
                deviations: Default::default(),
                roller_radius_m: roller,
                curvature_per_m: k,
            },
            *track.wheelset(),
            &SplineOptions::default(),
        )
        .map(|_| ())
        .unwrap_err()
        .to_string()
    };
    for (roller, cant, k, key) in [
        (Some(-0.4), 0.0, 0.0, "track.roller_radius_m"),
        (Some(f64::NAN), 0.0, 0.0, "track.roller_radius_m"),
        (Some(0.4), 0.025, 0.0, "track.cant_rad"),
        (None, 0.0, f64::INFINITY, "track.curvature_per_m"),
        (None, 0.0, 0.5, "track.curvature_per_m"),
    ] {
        let e = place(roller, cant, k);
        assert!(e.contains(key), "{key}: {e}");
    }
}

/// A roller rig run backwards (the rollers' rate and the wheel's pitch
/// rate of opposite sign: CONTACT's test-rollers2 case "2d" rolls so) is
/// the mirror image in x of the forward run: xi of opposite sign (the
/// roller's velocity relative to the wheel's over a positive speed, as
/// CONTACT defines it), Fx of opposite sign, the same normal and lateral
/// forces, for the exact model (rolling direction pi) and Hertz+FASTSIM
/// (its mirror image solved).
#[test]
fn a_roller_rig_run_backwards_is_the_mirror_image_of_the_forward_run() {
    let pair = sphere_pair(Some(RR), 0.0);
    let w = 2.5;
    let pitch = -(1.0 + 1e-3) * w * RR / RW;
    for model in [WheelRailModel::HertzFastsim, WheelRailModel::Exact] {
        // A yaw rate gives spin, whose lateral force turns over with the
        // rolling direction: the direction left out fails on the forces.
        let mut forwards = input(model, 0.0, pitch, w);
        forwards.velocity.lateral_m_per_s = 2e-3;
        forwards.velocity.yaw_rad_per_s = 0.5;
        let mut backwards = input(model, 0.0, -pitch, -w);
        backwards.velocity.lateral_m_per_s = 2e-3;
        backwards.velocity.yaw_rad_per_s = -0.5;
        let (a, b) = (patch(&pair, &forwards), patch(&pair, &backwards));
        assert!(
            a.fx_n.abs() > 100.0 && a.fs_n.abs() > 100.0,
            "{model:?}: {a:?}"
        );
        assert!(a.spin_per_m.abs() > 0.1, "{model:?}: spin {}", a.spin_per_m);
        assert!(
            (a.creepage_long + b.creepage_long).abs() < 1e-12,
            "{model:?}: xi {} and {}",
            a.creepage_long,
            b.creepage_long
        );
        let scale = a.normal_force_n;
        for (what, x, y) in [
            ("Fn", a.normal_force_n, b.normal_force_n),
            ("Fx", a.fx_n, -b.fx_n),
            ("Fs", a.fs_n, b.fs_n),
        ] {
            assert!(
                (x - y).abs() < 1e-9 * scale,
                "{model:?} {what}: forwards {x}, backwards mirrored {y}"
            );
        }
        assert_eq!(
            (a.rolling_direction_rad, b.rolling_direction_rad),
            (0.0, std::f64::consts::PI)
        );
    }
}
