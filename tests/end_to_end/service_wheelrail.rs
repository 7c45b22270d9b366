//! End-to-end tests of the wheel/rail part of the gRPC service: profile
//! pairs (built-in, from file contents, idempotent ids, list/get/delete,
//! persistence across a restart), SolveWheelRail against the library bit
//! for bit, batches, flash temperatures per patch, the plausibility
//! warnings of answers no elastic contact gives, and the errors of each
//! kind of bad input. The real
//! server runs on an ephemeral loopback port with its store in a temporary
//! directory; profiles come from `crates/solver/profiles`.

use crate::support;

use std::path::Path;

use railcontact::conformal::geometry::RigidSlipSurface;
use railcontact::core::cache::KernelCache;
use railcontact::core::friclaw::{FallingShape, SlipStart, SlipVelocityLaw};
use railcontact::core::problem::Friction;
use railcontact::core::temperature::ThermalBody;
use railcontact::service::config::ServeConfig;
use railcontact::service::pb;
use railcontact::service::server::RunningServer;
use railcontact::service::wheelrail::query_of;
use railcontact::wheelrail::builtin::{mbench_a22_input, MBENCH_TRACK, MBENCH_WHEELSET};
use railcontact::wheelrail::{
    check_plausibility, load_profile, load_profile_with, pitch_force_tolerance, solve_wheelset,
    solve_wheelset_tabulated, solve_wheelset_warm, ContactTable, FrictionAxis, FrictionTable,
    LoadOptions, RailPlacement, SearchScratch, Side, SplineOptions, TableSettings, TrackData,
    WarmStart, WheelRailInput, WheelRailModel, WheelRailPair, WheelRailSolution, WheelRailThermal,
    WheelsetData,
};
use tonic::Code;

use crate::common;
use common::Client;

const BUILTIN: &str = "mbench_s1002_uic60";

pub(crate) fn profile_path(name: &str) -> String {
    common::profile_path(name)
}

pub(crate) async fn server_in(dir: &Path) -> (RunningServer, Client) {
    common::serve(ServeConfig {
        data_dir: dir.to_path_buf(),
        ..ServeConfig::default()
    })
    .await
}

pub(crate) fn file_source(name: &str, mirror_y: bool) -> pb::ProfileSource {
    pb::ProfileSource {
        source: Some(pb::profile_source::Source::File(pb::ProfileFile {
            format: pb::ProfileFormat::Unspecified as i32,
            content: std::fs::read_to_string(profile_path(name)).unwrap(),
            file_name: name.into(),
            ..Default::default()
        })),
        mirror_y,
    }
}

fn track(t: TrackData) -> pb::TrackSpec {
    let RailPlacement::GaugePoint {
        gauge_m,
        gauge_height_m,
    } = t.placement
    else {
        panic!("the wire places rails by the gauge point only: {t:?}")
    };
    pb::TrackSpec {
        gauge_m,
        gauge_height_m,
        cant_rad: t.cant_rad,
        ..Default::default()
    }
}

pub(crate) fn wheelset(w: WheelsetData) -> pb::WheelsetSpec {
    pb::WheelsetSpec {
        flange_back_distance_m: w.flange_back_distance_m,
        nominal_radius_m: w.nominal_radius_m,
        flange_back_y_m: w.flange_back_y_m,
    }
}

const WORN_TRACK: TrackData = TrackData::gauge_point(1.435, 0.014, 0.025);

const WORN_WHEELSET: WheelsetData = WheelsetData {
    flange_back_distance_m: 1.360,
    nominal_radius_m: 0.46,
    flange_back_y_m: None,
};

/// Measured worn profiles: MiniProf wheel, MiniProf rail measured from the
/// gauge side (mirrored), rails inclined 1:40.
fn worn_spec() -> pb::ProfilePairSpec {
    pb::ProfilePairSpec {
        wheel: Some(file_source("Car7216_0001r.whl", false)),
        rail: Some(file_source("avg_HR.BAN", true)),
        track: Some(track(WORN_TRACK)),
        wheelset: Some(wheelset(WORN_WHEELSET)),
        ..Default::default()
    }
}

/// The library's pair of two profile files of `crates/solver/profiles`, read
/// as `railcontact wheelrail` reads them, with the default smoothing.
pub(crate) fn library_pair(
    rail: &str,
    rail_mirror_y: bool,
    wheel: &str,
    track: TrackData,
    wheelset: WheelsetData,
) -> WheelRailPair {
    let options = LoadOptions {
        mirror_y: rail_mirror_y,
        ..Default::default()
    };
    let rail = load_profile_with(profile_path(rail), &options).unwrap();
    let wheel = load_profile(profile_path(wheel)).unwrap();
    let spline = SplineOptions::default();
    WheelRailPair::new([&rail, &rail], [&wheel, &wheel], track, wheelset, &spline).unwrap()
}

fn worn_pair() -> WheelRailPair {
    library_pair(
        "avg_HR.BAN",
        true,
        "Car7216_0001r.whl",
        WORN_TRACK,
        WORN_WHEELSET,
    )
}

fn mbench_pair() -> WheelRailPair {
    library_pair(
        "MBench_UIC60_v3.prr",
        false,
        "MBench_S1002_v3.prw",
        MBENCH_TRACK,
        MBENCH_WHEELSET,
    )
}

pub(crate) fn spec_request(
    spec: pb::ProfilePairSpec,
    label: &str,
) -> pb::RegisterProfilePairRequest {
    pb::RegisterProfilePairRequest {
        pair: Some(pb::register_profile_pair_request::Pair::Spec(spec)),
        label: label.into(),
    }
}

/// All progress messages of a registration, or the status that ended it
/// (at the call or in the stream).
pub(crate) async fn register(
    client: &mut Client,
    req: pb::RegisterProfilePairRequest,
) -> Result<Vec<pb::RegistrationProgress>, tonic::Status> {
    let mut stream = client.register_profile_pair(req).await?.into_inner();
    let mut out = Vec::new();
    while let Some(m) = stream.message().await? {
        out.push(m);
    }
    Ok(out)
}

/// Registers and returns the final (READY) message.
pub(crate) async fn register_ready(
    client: &mut Client,
    req: pb::RegisterProfilePairRequest,
) -> pb::RegistrationProgress {
    let msgs = register(client, req).await.expect("registers");
    let last = msgs.last().expect("progress").clone();
    assert_eq!(last.stage, pb::RegistrationStage::Ready as i32, "{msgs:?}");
    assert!(last.pair.is_some());
    last
}

pub(crate) async fn solve(
    client: &mut Client,
    req: pb::SolveWheelRailRequest,
) -> pb::WheelRailResult {
    client
        .solve_wheel_rail(req)
        .await
        .expect("solves")
        .into_inner()
        .result
        .expect("result")
}

pub(crate) async fn solve_err(
    client: &mut Client,
    req: pb::SolveWheelRailRequest,
) -> tonic::Status {
    client.solve_wheel_rail(req).await.expect_err("must fail")
}

/// The bits of a value; a negative zero counts as zero, since proto3 does
/// not send zeros and the client decodes a missing field as +0.
pub(crate) fn bits(v: f64) -> u64 {
    if v == 0.0 {
        0
    } else {
        v.to_bits()
    }
}

/// Every figure of the wire result equals the library's, bit for bit
/// (timings aside; the sign of zeros is not sent).
pub(crate) fn assert_same(what: &str, got: &pb::WheelRailResult, want: &WheelRailSolution) {
    assert_eq!(
        bits(got.center_z_m),
        bits(want.center_z_m),
        "{what}: center_z_m"
    );
    assert_eq!(bits(got.roll_rad), bits(want.roll_rad), "{what}: roll_rad");
    assert_eq!(
        bits(got.pitch_rad_per_s),
        bits(want.pitch_rad_per_s),
        "{what}: pitch"
    );
    assert_eq!(got.wheels.len(), want.wheels.len(), "{what}: wheels");
    for (g, w) in got.wheels.iter().zip(&want.wheels) {
        let side = match w.side {
            Side::Left => pb::WheelSide::Left,
            Side::Right => pb::WheelSide::Right,
        };
        assert_eq!(g.side, side as i32);
        assert_eq!(bits(g.vertical_approach_m), bits(w.vertical_approach_m));
        assert_eq!(bits(g.min_gap_m), bits(w.min_gap_m));
        assert_eq!(g.load_iterations as usize, w.load_iterations);
        let f = g.force_track_n.unwrap();
        assert_eq!([f.x_n, f.y_n, f.z_n].map(bits), w.force_track_n.map(bits));
        assert_eq!(g.patches.len(), w.patches.len(), "{what}: patches");
        for (gp, wp) in g.patches.iter().zip(&w.patches) {
            let gv = [
                gp.contact_angle_rad,
                gp.contact_angle_variation_rad,
                gp.rail_y_m,
                gp.rail_z_m,
                gp.wheel_y_m,
                gp.track_x_m,
                gp.track_y_m,
                gp.track_z_m,
                gp.rolling_radius_m,
                gp.creepage_long,
                gp.creepage_lat,
                gp.spin_per_m,
                gp.rolling_speed_m_per_s,
                gp.normal_force_n,
                gp.fx_n,
                gp.fs_n,
                gp.mz_nm,
                gp.approach_m,
                gp.max_pressure_pa,
                gp.contact_area_m2,
                gp.adhesion_fraction,
                gp.frictional_power_w,
            ];
            let wv = [
                wp.contact_angle_rad,
                wp.contact_angle_variation_rad,
                wp.rail_y_m,
                wp.rail_z_m,
                wp.wheel_y_m,
                wp.track_x_m,
                wp.track_y_m,
                wp.track_z_m,
                wp.rolling_radius_m,
                wp.creepage_long,
                wp.creepage_lat,
                wp.spin_per_m,
                wp.rolling_speed_m_per_s,
                wp.normal_force_n,
                wp.fx_n,
                wp.fs_n,
                wp.mz_nm,
                wp.approach_m,
                wp.max_pressure_pa,
                wp.contact_area_m2,
                wp.adhesion_fraction,
                wp.frictional_power_w,
            ];
            assert_eq!(gv.map(bits), wv.map(bits), "{what}: patch figures");
            let f = gp.force_track_n.unwrap();
            assert_eq!([f.x_n, f.y_n, f.z_n].map(bits), wp.force_track_n.map(bits));
            assert_eq!([gp.grid_nx as usize, gp.grid_ns as usize], wp.grid);
        }
    }
}

/// The wire result without its timings, for comparing two server results.
fn untimed(mut r: pb::WheelRailResult) -> pb::WheelRailResult {
    r.timing = None;
    r
}

#[tokio::test]
async fn builtin_pair_is_ready_at_start_and_solves_as_the_library_bit_for_bit() {
    let dir = tempfile::tempdir().unwrap();
    let (server, mut client) = server_in(dir.path()).await;
    let pairs = support::list_pairs(&mut client).await;
    let builtin = pairs
        .iter()
        .find(|p| p.builtin_pair == BUILTIN)
        .expect("built-in pair listed");
    assert_eq!(builtin.state, pb::ProfilePairState::Ready as i32);
    assert_eq!(builtin.pair_id.len(), 32);
    assert!(!builtin.persisted);
    let wheel = builtin.wheel.as_ref().unwrap();
    assert_eq!(wheel.file_name, "MBench_S1002_v3.prw");
    assert!(wheel.builtin && wheel.point_count > 50, "{wheel:?}");

    // Manchester at 6.5 mm with CONTACT's roll and pitch rate.
    let pair = mbench_pair();
    let cache = KernelCache::default();
    for model in [
        WheelRailModel::Exact,
        WheelRailModel::HertzFastsim,
        WheelRailModel::HertzPolach,
        WheelRailModel::HertzFastsimElliptic,
        WheelRailModel::HertzStrip,
        WheelRailModel::HertzFastsimModified,
        WheelRailModel::KikPiotrowski,
    ] {
        let input = mbench_a22_input(6.5, Some(-0.004376), Some(-4.2748834), model);
        let want = solve_wheelset(&pair, &input, &cache, &mut SearchScratch::default()).unwrap();
        // By name and by id.
        let by_name = solve(&mut client, query_of(BUILTIN, &input)).await;
        assert_same(&format!("{model:?} by name"), &by_name, &want);
        let by_id = solve(&mut client, query_of(&builtin.pair_id, &input)).await;
        assert_eq!(untimed(by_id), untimed(by_name.clone()));
        // The pair's own friction and element size are the benchmark's.
        let mut defaults = query_of(BUILTIN, &input);
        defaults.friction = None;
        defaults.element_size_m = None;
        defaults.min_elements_across = None;
        let defaults = solve(&mut client, defaults).await;
        assert_eq!(untimed(defaults), untimed(by_name.clone()));
        assert_eq!(by_name.pair_id, builtin.pair_id);
        let total: f64 = by_name
            .wheels
            .iter()
            .map(|w| w.force_track_n.unwrap().z_n)
            .sum();
        assert!((total - 20_000.0).abs() < 1e-2, "{total}");
    }

    // Narrow patches on narrower elements (min_elements_across): off (0,
    // CONTACT's DX by DS), the right wheel's flange patch is solved on the
    // element size's squares, as the library solves it; contact area 9.96
    // mm² against 9.16 narrowed (9.14 on 0.1 mm squares; the validation
    // test a_narrow_flange_patch_is_solved_on_narrower_elements).
    let mut input = mbench_a22_input(
        6.5,
        Some(-0.004376),
        Some(-4.2748834),
        WheelRailModel::Exact,
    );
    let area = |r: &pb::WheelRailResult| r.wheels[1].patches[0].contact_area_m2;
    let narrowed = solve(&mut client, query_of(BUILTIN, &input)).await;
    input.settings.min_elements_across = 0;
    let want = solve_wheelset(&pair, &input, &cache, &mut SearchScratch::default()).unwrap();
    let squares = solve(&mut client, query_of(BUILTIN, &input)).await;
    assert_same("min_elements_across 0", &squares, &want);
    assert!(
        area(&squares) / area(&narrowed) > 1.05,
        "{} against {} m²",
        area(&squares),
        area(&narrowed)
    );

    // Grids sized for the forces: the library's answer under the same
    // tolerance; one out of range is refused naming the field.
    let mut input = mbench_a22_input(
        6.5,
        Some(-0.004376),
        Some(-4.2748834),
        WheelRailModel::Exact,
    );
    input.settings.force_tolerance_of_wheel_load = Some(5e-3);
    let want = solve_wheelset(&pair, &input, &cache, &mut SearchScratch::default()).unwrap();
    let sized = solve(&mut client, query_of(BUILTIN, &input)).await;
    assert_same("force_tolerance_of_wheel_load 5e-3", &sized, &want);
    let mut r = query_of(BUILTIN, &input);
    r.force_tolerance_of_wheel_load = Some(1e-3);
    assert_invalid(
        &solve_err(&mut client, r).await,
        &["force_tolerance_of_wheel_load", "0.005"],
    );

    // Fields only when asked, for exact patches with friction.
    let input = mbench_a22_input(
        6.5,
        Some(-0.004376),
        Some(-4.2748834),
        WheelRailModel::Exact,
    );
    let plain = solve(&mut client, query_of(BUILTIN, &input)).await;
    assert!(plain.wheels[0].patches.iter().all(|p| p.fields.is_none()));
    let mut req = query_of(BUILTIN, &input);
    req.include_fields = true;
    let with = solve(&mut client, req).await;
    let p = &with.wheels[0].patches[0];
    let g = p.grid.expect("grid with the fields");
    let f = p.fields.as_ref().expect("fields");
    assert_eq!(f.pressure_pa.len(), (g.nx * g.ny) as usize);
    assert_eq!((g.nx, g.ny), (p.grid_nx, p.grid_ns));
    server.shutdown().await;
}

/// A wheelset rolling backwards on the wire (forward_m_per_s < 0, the
/// pitch rate > 0): at 6.5 mm reversed, solved as the library
/// solves it, bit for bit, for the exact model and two fast ones; its
/// patches report rolling direction pi through the library. The conformal
/// model rolls forwards only: INVALID_ARGUMENT naming `model`.
#[tokio::test]
async fn a_wheelset_rolling_backwards_solves_as_the_library() {
    let dir = tempfile::tempdir().unwrap();
    let (server, mut client) = server_in(dir.path()).await;
    let pair = mbench_pair();
    let cache = KernelCache::default();
    let reversed = |model| {
        let mut input = mbench_a22_input(6.5, Some(-0.004376), Some(4.2748834), model);
        input.velocity.forward_m_per_s = -input.velocity.forward_m_per_s;
        input
    };
    for model in [
        WheelRailModel::Exact,
        WheelRailModel::HertzFastsim,
        WheelRailModel::KikPiotrowski,
    ] {
        let input = reversed(model);
        let want = solve_wheelset(&pair, &input, &cache, &mut SearchScratch::default()).unwrap();
        assert!(want
            .wheels
            .iter()
            .flat_map(|w| &w.patches)
            .all(|p| p.rolling_direction_rad == std::f64::consts::PI));
        let got = solve(&mut client, query_of(BUILTIN, &input)).await;
        assert_same(&format!("{model:?} backwards"), &got, &want);
    }
    let e = solve_err(
        &mut client,
        query_of(BUILTIN, &reversed(WheelRailModel::Cect)),
    )
    .await;
    assert_eq!(e.code(), Code::InvalidArgument, "{e:?}");
    assert!(e.message().contains("model"), "{e:?}");
    server.shutdown().await;
}

#[tokio::test]
async fn cect_queries_take_the_rigid_slip_asked_for_as_the_library() {
    let dir = tempfile::tempdir().unwrap();
    let (server, mut client) = server_in(dir.path()).await;
    let pair = mbench_pair();
    let cache = KernelCache::default();
    for surface in [
        RigidSlipSurface::ActualSurface,
        RigidSlipSurface::ReferenceSection,
    ] {
        let mut input = mbench_a22_input(0.0, None, None, WheelRailModel::Cect);
        input.settings.rigid_slip = surface;
        let want = solve_wheelset(&pair, &input, &cache, &mut SearchScratch::default()).unwrap();
        let got = solve(&mut client, query_of(BUILTIN, &input)).await;
        assert_same(&format!("cect {surface:?}"), &got, &want);
    }
    let mut r = query_of(
        BUILTIN,
        &mbench_a22_input(0.0, None, None, WheelRailModel::Cect),
    );
    r.conformal = Some(pb::ConformalSection { rigid_slip: 9 });
    assert_invalid(&solve_err(&mut client, r).await, &["conformal.rigid_slip"]);
    server.shutdown().await;
}

/// A prescribed total longitudinal force: the pitch rate is found as by
/// the library, bit for bit, with its report; saturation, a force with a
/// pitch rate, and a force out of the documented range are INVALID_ARGUMENT
/// naming the field.
#[tokio::test]
async fn a_prescribed_total_longitudinal_force_finds_the_pitch_rate_as_the_library() {
    let dir = tempfile::tempdir().unwrap();
    let (server, mut client) = server_in(dir.path()).await;
    let pair = mbench_pair();
    let cache = KernelCache::default();
    for model in [WheelRailModel::Exact, WheelRailModel::HertzFastsim] {
        let mut input = mbench_a22_input(6.5, Some(-0.004376), None, model);
        input.total_longitudinal_force_n = Some(-2500.0);
        let want = solve_wheelset(&pair, &input, &cache, &mut SearchScratch::default()).unwrap();
        let got = solve(&mut client, query_of(BUILTIN, &input)).await;
        assert_same(&format!("{model:?}, braking force"), &got, &want);
        let (c, w) = (got.pitch_control.unwrap(), want.pitch_control.unwrap());
        assert!(c.converged, "{c:?}");
        assert_eq!(c.force_n.to_bits(), w.force_n.to_bits());
        assert_eq!(c.solves as usize, w.solves);
        let total: f64 = got
            .wheels
            .iter()
            .map(|w| w.force_track_n.unwrap().x_n)
            .sum();
        // The force tolerance relative to mu Fn (wheelrail::contact's docs).
        let tolerance = pitch_force_tolerance(&input.settings);
        assert!(
            (total + 2500.0).abs() < tolerance * 0.3 * 25_000.0,
            "{total}"
        );
    }
    // Polach's parameters travel: dry rail (Polach 2005) with a driving
    // force, as the library.
    let mut input = mbench_a22_input(6.5, Some(-0.004376), None, WheelRailModel::HertzPolach);
    input.settings.polach = railcontact::core::polach::PolachParameters::DRY;
    input.total_longitudinal_force_n = Some(-2500.0);
    let want = solve_wheelset(&pair, &input, &cache, &mut SearchScratch::default()).unwrap();
    let got = solve(&mut client, query_of(BUILTIN, &input)).await;
    assert_same("Polach, dry", &got, &want);
    let mut req = query_of(BUILTIN, &input);
    req.polach.as_mut().unwrap().k_slip = 2.0;
    let e = solve_err(&mut client, req).await;
    assert_invalid(&e, &["polach.k_slip"]);
    // The modified FASTSIM's parameters travel, with falling friction, as
    // the library; one out of range names its field.
    let mut input = mbench_a22_input(
        6.5,
        Some(-0.004376),
        Some(-4.2748834),
        WheelRailModel::HertzFastsimModified,
    );
    input.settings.modified_fastsim = railcontact::core::fastsim::SlopeReduction {
        friction_limit_ratio: 0.4,
        friction_decay_s_per_m: 0.6,
        ..railcontact::core::fastsim::SlopeReduction::TRACTCURV
    };
    let want = solve_wheelset(&pair, &input, &cache, &mut SearchScratch::default()).unwrap();
    let got = solve(&mut client, query_of(BUILTIN, &input)).await;
    assert_same("modified FASTSIM, falling friction", &got, &want);
    let mut req = query_of(BUILTIN, &input);
    req.modified_fastsim.as_mut().unwrap().limit_ratio = 0.0;
    let e = solve_err(&mut client, req).await;
    assert_invalid(&e, &["modified_fastsim.limit_ratio"]);
    let field = "load.total_longitudinal_force_n";
    let mut input = mbench_a22_input(6.5, None, None, WheelRailModel::HertzFastsim);
    input.total_longitudinal_force_n = Some(-9000.0);
    let e = solve_err(&mut client, query_of(BUILTIN, &input)).await;
    assert_invalid(&e, &[field, "saturation"]);
    input.total_longitudinal_force_n = Some(2e6);
    let e = solve_err(&mut client, query_of(BUILTIN, &input)).await;
    assert_invalid(&e, &[field]);
    input.total_longitudinal_force_n = Some(1000.0);
    input.velocity.pitch_rad_per_s = Some(-4.3);
    let e = solve_err(&mut client, query_of(BUILTIN, &input)).await;
    assert_invalid(&e, &[field, "velocity.pitch_rad_per_s"]);
    server.shutdown().await;
}

#[tokio::test]
async fn file_pairs_register_once_by_content_and_are_listed_got_and_deleted() {
    let dir = tempfile::tempdir().unwrap();
    let (server, mut client) = server_in(dir.path()).await;

    // The benchmark's files with the benchmark's data: the built-in pair's
    // content, so its id, already registered.
    let mbench = pb::ProfilePairSpec {
        wheel: Some(file_source("MBench_S1002_v3.prw", false)),
        rail: Some(file_source("MBench_UIC60_v3.prr", false)),
        track: Some(track(MBENCH_TRACK)),
        wheelset: Some(wheelset(MBENCH_WHEELSET)),
        ..Default::default()
    };
    let same = register_ready(&mut client, spec_request(mbench, "mine")).await;
    assert!(same.already_registered);
    assert_eq!(same.pair.unwrap().builtin_pair, BUILTIN);

    // A new pair: its stages in order, then the same id again at once.
    let msgs = register(&mut client, spec_request(worn_spec(), "worn"))
        .await
        .unwrap();
    let stages: Vec<i32> = msgs.iter().map(|m| m.stage).collect();
    use pb::RegistrationStage as S;
    assert_eq!(
        stages,
        [
            S::Validated,
            S::WheelParsed,
            S::RailParsed,
            S::Placed,
            S::TableBuilt,
            S::Stored,
            S::Ready
        ]
        .map(|s| s as i32)
    );
    // Registration builds the contact table.
    assert!(
        msgs[4].message.starts_with("contact table built"),
        "{}",
        msgs[4].message
    );
    let ready = msgs.last().unwrap();
    assert!(!ready.already_registered);
    assert!(msgs.iter().all(|m| m.pair_id == ready.pair_id));
    assert!(msgs
        .windows(2)
        .all(|w| w[0].fraction_done < w[1].fraction_done));
    let info = ready.pair.clone().unwrap();
    assert_eq!(info.state, pb::ProfilePairState::Ready as i32);
    assert!(info.persisted);
    assert_eq!(info.label, "worn");
    assert_eq!(info.rail.as_ref().unwrap().file_name, "avg_HR.BAN");
    assert!(info.rail.as_ref().unwrap().mirror_y);
    assert!(info.wheel.as_ref().unwrap().point_count > 50);
    assert!(info.prepare_time_s > 0.0);
    let id = ready.pair_id.clone();

    let again = register_ready(&mut client, spec_request(worn_spec(), "other label")).await;
    assert!(again.already_registered);
    assert_eq!(again.pair_id, id);
    assert_eq!(again.pair.unwrap().label, "worn", "first label kept");
    let mut changed = worn_spec();
    changed.friction = Some(pb::FrictionSection {
        coefficient: Some(0.2),
        ..Default::default()
    });
    let other = register_ready(&mut client, spec_request(changed, "")).await;
    assert_ne!(other.pair_id, id, "other content, other id");

    let list = support::list_pairs(&mut client).await;
    let ids: Vec<&str> = list.iter().map(|p| p.pair_id.as_str()).collect();
    assert_eq!(list.len(), 3, "{ids:?}");
    assert!(ids.contains(&id.as_str()));
    assert!(ids.windows(2).all(|w| w[0] < w[1]), "ordered by id");
    let got = client
        .get_profile_pair(pb::GetProfilePairRequest {
            pair_id: id.clone(),
        })
        .await
        .unwrap()
        .into_inner();
    assert_eq!(got, info);

    // Solves on it as the library on the same profiles.
    let mut input = mbench_a22_input(3.0, None, None, WheelRailModel::HertzFastsim);
    input.position.yaw_rad = 0.0;
    let want = solve_wheelset(
        &worn_pair(),
        &input,
        &KernelCache::default(),
        &mut SearchScratch::default(),
    )
    .unwrap();
    let got = solve(&mut client, query_of(&id, &input)).await;
    assert_same("worn pair", &got, &want);

    // Delete: gone for get, solve and a second delete; the built-in stays.
    let del = |id: &str| pb::DeleteProfilePairRequest { pair_id: id.into() };
    let d = client.delete_profile_pair(del(&id)).await.unwrap();
    assert_eq!(d.into_inner().pair_id, id);
    let e = client
        .get_profile_pair(pb::GetProfilePairRequest {
            pair_id: id.clone(),
        })
        .await
        .unwrap_err();
    assert_eq!(e.code(), Code::NotFound, "{e:?}");
    assert_eq!(
        solve_err(&mut client, query_of(&id, &input)).await.code(),
        Code::NotFound
    );
    let e = client.delete_profile_pair(del(&id)).await.unwrap_err();
    assert_eq!(e.code(), Code::NotFound);
    let e = client.delete_profile_pair(del(BUILTIN)).await.unwrap_err();
    assert_eq!(e.code(), Code::FailedPrecondition, "{e:?}");
    server.shutdown().await;
}

/// Friction varying over the rail profile and along the track
/// (`friction_table`, read at `position.track_s_m`) and a falling law, as
/// the library bit for bit, in a query and in a session; each patch reports
/// its coefficient; a falling law scaled to a table as well. A bad table
/// and a falling law for a Hertz model are INVALID_ARGUMENT naming the
/// field.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn friction_tables_and_falling_laws_solve_as_the_library() {
    use pb::wheel_rail_session_request::Kind as In;
    use pb::wheel_rail_session_response::Kind as Out;
    let dir = tempfile::tempdir().unwrap();
    let (server, mut client) = server_in(dir.path()).await;
    let pair = mbench_pair();
    let cache = KernelCache::default();
    let table = FrictionTable {
        axis: FrictionAxis::ContactAngle,
        positions: vec![0.1, 0.4],
        track_s_m: vec![0.0, 100.0],
        coefficients: vec![0.3, 0.2, 0.4, 0.1],
    };
    let mut input = mbench_a22_input(5.0, None, None, WheelRailModel::Exact);
    input.friction_table = Some(table.clone());
    input.position.track_s_m = 40.0;
    let want = solve_wheelset(&pair, &input, &cache, &mut SearchScratch::default()).unwrap();
    let got = solve(&mut client, query_of(BUILTIN, &input)).await;
    assert_same("friction table", &got, &want);
    for (g, w) in got.wheels.iter().zip(&want.wheels) {
        for (gp, wp) in g.patches.iter().zip(&w.patches) {
            assert_eq!(
                gp.friction_coefficient.to_bits(),
                wp.friction_coefficient.to_bits()
            );
            let mu = table.coefficient(wp.contact_angle_rad, 40.0);
            assert_eq!(wp.friction_coefficient, mu);
        }
    }
    // A session opened with the table: its first step as the library.
    let q = query_of(BUILTIN, &input);
    let open = In::Open(pb::WheelRailSessionOpen {
        pair_id: BUILTIN.into(),
        model: pb::WheelRailModel::Exact as i32,
        friction_table: q.friction_table.clone(),
        ..Default::default()
    });
    let step = In::Step(pb::WheelRailSessionStep {
        step_index: 0,
        position: q.position,
        velocity: q.velocity,
        load: q.load,
        ..Default::default()
    });
    let out = wr_session(&mut client, vec![wr_request(open), wr_request(step)])
        .await
        .unwrap();
    let first = out
        .iter()
        .find_map(|o| match o {
            Out::Step(s) => s.result.clone(),
            _ => None,
        })
        .expect("a step result");
    let warm = solve_wheelset_warm(
        &pair,
        &input,
        &cache,
        &mut SearchScratch::default(),
        &mut WarmStart::default(),
    )
    .unwrap();
    assert_same("session with a friction table", &first, &warm);
    // A falling law, each patch at its own rolling speed.
    let mut input = mbench_a22_input(5.5, None, None, WheelRailModel::Exact);
    input.friction = Friction::falling(SlipVelocityLaw {
        shape: FallingShape::Exponential,
        kinetic_coefficient: 0.15,
        falling_coefficients: [0.2, 0.0],
        half_velocities_m_per_s: [0.05, 0.0],
        rolling_speed_m_per_s: 2.0,
        memory_distance_m: 0.0,
        memory_velocity_m_per_s: 0.0,
        start: SlipStart::Sticking,
        max_iterations: 0,
    });
    let want = solve_wheelset(&pair, &input, &cache, &mut SearchScratch::default()).unwrap();
    let got = solve(&mut client, query_of(BUILTIN, &input)).await;
    assert_same("falling law", &got, &want);
    // A falling law scaled to a friction table (Friction::scaled_to).
    input.friction_table = Some(table.clone());
    input.position.track_s_m = 40.0;
    let want = solve_wheelset(&pair, &input, &cache, &mut SearchScratch::default()).unwrap();
    let got = solve(&mut client, query_of(BUILTIN, &input)).await;
    assert_same("falling law with a table", &got, &want);
    input.friction_table = None;
    input.position.track_s_m = 0.0;
    // Errors.
    let mut r = query_of(BUILTIN, &input);
    r.model = pb::WheelRailModel::HertzFastsim as i32;
    assert_invalid(&solve_err(&mut client, r).await, &["friction.law", "exact"]);
    let mut r = q.clone();
    r.friction_table.as_mut().unwrap().coefficients.pop();
    assert_invalid(
        &solve_err(&mut client, r).await,
        &["friction_table.coefficients"],
    );
    let mut r = q.clone();
    r.friction_table.as_mut().unwrap().rail_y_m = vec![0.0];
    assert_invalid(
        &solve_err(&mut client, r).await,
        &["friction_table.contact_angles_rad"],
    );
    let mut r = q;
    r.position.as_mut().unwrap().track_s_m = f64::NAN;
    assert_invalid(&solve_err(&mut client, r).await, &["position.track_s_m"]);
    server.shutdown().await;
}

pub(crate) fn assert_invalid(e: &tonic::Status, needles: &[&str]) {
    assert_eq!(e.code(), Code::InvalidArgument, "{e:?}");
    for n in needles {
        assert!(e.message().contains(n), "{n:?} not in {:?}", e.message());
    }
}

#[tokio::test]
async fn bad_profiles_and_specs_are_invalid_argument_naming_file_line_and_field() {
    let dir = tempfile::tempdir().unwrap();
    let (server, mut client) = server_in(dir.path()).await;

    // A plain wheel file with a bad third line.
    let mut spec = worn_spec();
    spec.wheel = Some(pb::ProfileSource {
        source: Some(pb::profile_source::Source::File(pb::ProfileFile {
            format: pb::ProfileFormat::Plain as i32,
            content: "0.000 0.000\n-0.001 0.0001\n-0.002 zero\n".into(),
            file_name: "bad_wheel.txt".into(),
            ..Default::default()
        })),
        mirror_y: false,
    });
    let e = register(&mut client, spec_request(spec, ""))
        .await
        .unwrap_err();
    assert_invalid(&e, &["spec.wheel", "bad_wheel.txt line 3"]);

    // A Simpack rail with one point line broken.
    let text = std::fs::read_to_string(profile_path("MBench_UIC60_v3.prr")).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let begin = lines
        .iter()
        .position(|l| l.trim() == "point.begin")
        .unwrap();
    let k = begin + 10;
    let broken: Vec<String> = lines
        .iter()
        .enumerate()
        .map(|(i, l)| {
            if i == k {
                "1.0 two".to_string()
            } else {
                l.to_string()
            }
        })
        .collect();
    let mut spec = worn_spec();
    spec.rail = Some(pb::ProfileSource {
        source: Some(pb::profile_source::Source::File(pb::ProfileFile {
            format: pb::ProfileFormat::Unspecified as i32,
            content: broken.join("\n"),
            file_name: "broken.prr".into(),
            ..Default::default()
        })),
        mirror_y: false,
    });
    let e = register(&mut client, spec_request(spec, ""))
        .await
        .unwrap_err();
    assert_invalid(&e, &["spec.rail", &format!("broken.prr line {}", k + 1)]);

    // Checks of the request itself fail the call.
    let mut spec = worn_spec();
    spec.track = None;
    let e = client
        .register_profile_pair(spec_request(spec, ""))
        .await
        .unwrap_err();
    assert_invalid(&e, &["spec.track", "missing"]);
    let mut spec = worn_spec();
    spec.grid = Some(pb::WheelRailGrid {
        element_size_m: Some(f64::NAN),
    });
    let e = register(&mut client, spec_request(spec, ""))
        .await
        .unwrap_err();
    assert_invalid(&e, &["spec.grid.element_size_m"]);
    let mut spec = worn_spec();
    spec.track.as_mut().unwrap().gauge_m = -1.0;
    let e = register(&mut client, spec_request(spec, ""))
        .await
        .unwrap_err();
    assert_invalid(&e, &["spec.track.gauge_m"]);
    let e = register(
        &mut client,
        pb::RegisterProfilePairRequest {
            pair: Some(pb::register_profile_pair_request::Pair::BuiltinPair(
                "s1002_on_nothing".into(),
            )),
            label: String::new(),
        },
    )
    .await
    .unwrap_err();
    assert_invalid(&e, &["builtin_pair", BUILTIN]);

    // Nothing of these was registered.
    let list = support::list_pairs(&mut client).await;
    assert_eq!(list.len(), 1, "only the built-in pair: {list:?}");

    // Bad queries.
    let good = query_of(
        BUILTIN,
        &mbench_a22_input(0.0, None, None, WheelRailModel::HertzFastsim),
    );
    let e = solve_err(
        &mut client,
        pb::SolveWheelRailRequest {
            pair_id: "0123456789abcdef0123456789abcdef".into(),
            ..good.clone()
        },
    )
    .await;
    assert_eq!(e.code(), Code::NotFound, "{e:?}");
    let mut r = good.clone();
    r.position.as_mut().unwrap().lateral_m = f64::NAN;
    assert_invalid(&solve_err(&mut client, r).await, &["position.lateral_m"]);
    let mut r = good.clone();
    r.velocity = None;
    assert_invalid(&solve_err(&mut client, r).await, &["velocity", "missing"]);
    let mut r = good.clone();
    r.load = Some(pb::WheelLoad {
        load: Some(pb::wheel_load::Load::VerticalForceN(-5.0)),
        ..Default::default()
    });
    assert_invalid(&solve_err(&mut client, r).await, &["load.vertical_force_n"]);
    let mut r = good.clone();
    r.load = Some(pb::WheelLoad {
        load: Some(pb::wheel_load::Load::CenterZM(f64::NAN)),
        ..Default::default()
    });
    assert_invalid(&solve_err(&mut client, r).await, &["load.center_z_m"]);
    let mut r = good.clone();
    r.element_size_m = Some(1.0);
    assert_invalid(&solve_err(&mut client, r).await, &["element_size_m"]);
    let mut r = good.clone();
    r.friction = Some(pb::FrictionSection {
        coefficient: Some(f64::INFINITY),
        ..Default::default()
    });
    assert_invalid(&solve_err(&mut client, r).await, &["friction.coefficient"]);
    let mut r = good.clone();
    r.model = 42;
    assert_invalid(&solve_err(&mut client, r).await, &["model"]);
    let mut r = good.clone();
    r.conformal = Some(pb::ConformalSection::default());
    assert_invalid(&solve_err(&mut client, r).await, &["conformal", "cect"]);
    // The server still answers.
    solve(&mut client, good).await;
    server.shutdown().await;
}

#[tokio::test]
async fn wheel_rail_batches_answer_in_request_order_with_errors_in_their_slots() {
    let dir = tempfile::tempdir().unwrap();
    let (server, mut client) = server_in(dir.path()).await;
    let mut items: Vec<pb::SolveWheelRailRequest> = (0..4)
        .map(|k| {
            query_of(
                BUILTIN,
                &mbench_a22_input(2.0 * k as f64, None, None, WheelRailModel::HertzFastsim),
            )
        })
        .collect();
    items[1].pair_id = "nope".into();
    items[2].velocity.as_mut().unwrap().forward_m_per_s = 0.0;
    let out = client
        .solve_wheel_rail_batch(pb::SolveWheelRailBatchRequest {
            items: items.clone(),
        })
        .await
        .unwrap()
        .into_inner()
        .items;
    assert_eq!(out.len(), 4);
    use pb::wheel_rail_batch_item::Outcome;
    for (k, slot) in out.iter().enumerate() {
        assert_eq!(slot.index as usize, k);
        match (k, slot.outcome.as_ref().unwrap()) {
            (1, Outcome::Error(e)) => assert_eq!(e.code, Code::NotFound as i32, "{e:?}"),
            (2, Outcome::Error(e)) => {
                assert_eq!(e.code, Code::InvalidArgument as i32);
                assert_eq!(e.field, "items[2].velocity.forward_m_per_s");
            }
            (0 | 3, Outcome::Result(r)) => {
                let alone = solve(&mut client, items[k].clone()).await;
                assert_eq!(untimed(r.clone()), untimed(alone), "item {k}");
            }
            other => panic!("unexpected slot {other:?}"),
        }
    }
    server.shutdown().await;
}

#[tokio::test]
async fn registered_pairs_survive_a_restart_and_deletions_too() {
    let dir = tempfile::tempdir().unwrap();
    let mut input = mbench_a22_input(4.0, None, None, WheelRailModel::Exact);
    input.position.yaw_rad = 0.0;
    let (id, before) = {
        let (server, mut client) = server_in(dir.path()).await;
        let ready = register_ready(&mut client, spec_request(worn_spec(), "worn")).await;
        let id = ready.pair_id;
        let before = solve(&mut client, query_of(&id, &input)).await;
        server.shutdown().await;
        (id, before)
    };
    assert!(dir.path().join("pairs.redb").exists());
    let (server, mut client) = server_in(dir.path()).await;
    let get = |id: &str| pb::GetProfilePairRequest { pair_id: id.into() };
    let info = client
        .get_profile_pair(get(&id))
        .await
        .unwrap()
        .into_inner();
    assert_eq!(info.state, pb::ProfilePairState::Stored as i32, "{info:?}");
    assert!(info.persisted);
    assert_eq!(info.label, "worn");
    // Prepared on first use: the same answer as before the restart.
    let after = solve(&mut client, query_of(&id, &input)).await;
    assert_eq!(untimed(after), untimed(before));
    let info = client
        .get_profile_pair(get(&id))
        .await
        .unwrap()
        .into_inner();
    assert_eq!(info.state, pb::ProfilePairState::Ready as i32);
    // Registering it again is idempotent.
    let again = register_ready(&mut client, spec_request(worn_spec(), "")).await;
    assert!(again.already_registered);
    assert_eq!(again.pair_id, id);
    client
        .delete_profile_pair(pb::DeleteProfilePairRequest {
            pair_id: id.clone(),
        })
        .await
        .unwrap();
    server.shutdown().await;

    let (server, mut client) = server_in(dir.path()).await;
    let e = client.get_profile_pair(get(&id)).await.unwrap_err();
    assert_eq!(e.code(), Code::NotFound);
    let list = support::list_pairs(&mut client).await;
    assert_eq!(list.len(), 1, "the built-in pair only");
    server.shutdown().await;
}

/// A wheel/rail session step at Manchester A-2.2's lateral shift `mm`
/// (roll from the profiles, free rolling).
fn wr_step(index: u64, mm: f64, mark: bool) -> pb::WheelRailSessionRequest {
    let q = query_of(
        BUILTIN,
        &mbench_a22_input(mm, None, None, WheelRailModel::Exact),
    );
    pb::WheelRailSessionRequest {
        kind: Some(pb::wheel_rail_session_request::Kind::Step(
            pb::WheelRailSessionStep {
                step_index: index,
                time_s: index as f64 * 1e-3,
                position: q.position,
                velocity: q.velocity,
                load: q.load,
                mark,
            },
        )),
    }
}

pub(crate) fn wr_request(
    kind: pb::wheel_rail_session_request::Kind,
) -> pb::WheelRailSessionRequest {
    pb::WheelRailSessionRequest { kind: Some(kind) }
}

/// Runs a whole wheel/rail session; every response (the first is `opened`).
pub(crate) async fn wr_session(
    client: &mut Client,
    messages: Vec<pb::WheelRailSessionRequest>,
) -> Result<Vec<pb::wheel_rail_session_response::Kind>, tonic::Status> {
    let mut out = client
        .wheel_rail_session(tokio_stream::iter(messages))
        .await?
        .into_inner();
    let mut responses = Vec::new();
    while let Some(r) = tokio_stream::StreamExt::next(&mut out).await {
        responses.push(r?.kind.expect("a response kind"));
    }
    Ok(responses)
}

/// A braking wheelset in a session: each step's prescribed total
/// longitudinal force finds its pitch rate, warm-started from the last
/// step, with the same bits as the library's warm-started solves.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_wheel_rail_session_brakes_to_its_prescribed_force_as_the_library() {
    use pb::wheel_rail_session_request::Kind as In;
    use pb::wheel_rail_session_response::Kind as Out;
    let dir = tempfile::tempdir().unwrap();
    let (server, mut client) = server_in(dir.path()).await;
    let open = In::Open(pb::WheelRailSessionOpen {
        pair_id: BUILTIN.into(),
        model: pb::WheelRailModel::HertzFastsim as i32,
        ..Default::default()
    });
    let pair = mbench_pair();
    let cache = KernelCache::default();
    let mut scratch = SearchScratch::default();
    let mut warm = WarmStart::default();
    let mut msgs = vec![wr_request(open)];
    let mut want = Vec::new();
    for (k, (mm, force)) in [(3.0, 500.0), (3.1, 1000.0), (3.2, 1500.0)]
        .into_iter()
        .enumerate()
    {
        let mut input = mbench_a22_input(mm, None, None, WheelRailModel::HertzFastsim);
        input.total_longitudinal_force_n = Some(force);
        want.push(solve_wheelset_warm(&pair, &input, &cache, &mut scratch, &mut warm).unwrap());
        let q = query_of(BUILTIN, &input);
        msgs.push(wr_request(In::Step(pb::WheelRailSessionStep {
            step_index: k as u64,
            position: q.position,
            velocity: q.velocity,
            load: q.load,
            ..Default::default()
        })));
    }
    let out = wr_session(&mut client, msgs).await.unwrap();
    let steps: Vec<_> = out
        .iter()
        .filter_map(|o| match o {
            Out::Step(s) => s.result.clone(),
            _ => None,
        })
        .collect();
    assert_eq!(steps.len(), 3, "{out:?}");
    for (k, (got, want)) in steps.iter().zip(&want).enumerate() {
        assert_same(&format!("step {k}"), got, want);
        let c = got.pitch_control.unwrap();
        assert!(c.converged, "{c:?}");
        let total: f64 = got
            .wheels
            .iter()
            .map(|w| w.force_track_n.unwrap().x_n)
            .sum();
        assert!(
            (total - c.target_force_n).abs() < 1e-6 * 0.3 * 20_000.0,
            "{total}"
        );
    }
    server.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn wheel_rail_session_warm_starts_as_the_library_and_rolls_back_bit_for_bit() {
    use pb::wheel_rail_session_request::Kind as In;
    use pb::wheel_rail_session_response::Kind as Out;
    let dir = tempfile::tempdir().unwrap();
    let (server, mut client) = server_in(dir.path()).await;
    // A wheelset drifting 0.05 mm a step: warm starts help where the
    // previous step is close.
    let shifts = [3.0, 3.05, 3.1, 3.15];
    let open = In::Open(pb::WheelRailSessionOpen {
        pair_id: BUILTIN.into(),
        model: pb::WheelRailModel::Exact as i32,
        client_label: "test".into(),
        ..Default::default()
    });
    let mut msgs = vec![wr_request(open.clone())];
    for (k, &mm) in shifts.iter().enumerate() {
        msgs.push(wr_step(k as u64, mm, k == 1));
    }
    msgs.push(wr_step(9, 7.0, false)); // out of order
    let mut no_velocity = wr_step(4, 7.0, false);
    if let Some(In::Step(s)) = no_velocity.kind.as_mut() {
        s.velocity = None;
    }
    msgs.push(no_velocity);
    msgs.push(wr_request(In::Rollback(pb::SessionRollback {
        to_step_index: 2,
    })));
    msgs.push(wr_request(In::Rollback(pb::SessionRollback {
        to_step_index: 1,
    })));
    msgs.push(wr_step(2, shifts[2], false));
    msgs.push(wr_step(3, shifts[3], false));
    let r = wr_session(&mut client, msgs).await.unwrap();
    assert_eq!(r.len(), 11, "one response per request");
    match &r[0] {
        Out::Opened(o) => {
            assert!(o.session_id.starts_with('w'));
            assert_eq!(o.pair_id.len(), 32);
            assert_eq!(o.model, pb::WheelRailModel::Exact as i32);
        }
        other => panic!("{other:?}"),
    }
    let step = |k: usize| match &r[k] {
        Out::Step(s) => s.clone(),
        other => panic!("response {k}: expected a step, got {other:?}"),
    };
    let error = |k: usize| match &r[k] {
        Out::Error(e) => e.clone(),
        other => panic!("response {k}: expected an error, got {other:?}"),
    };

    // Step by step equals the library's warm-started sequence, bit for bit.
    let pair = mbench_pair();
    let cache = KernelCache::default();
    let mut scratch = SearchScratch::default();
    let mut warm = WarmStart::default();
    let (mut warm_iterations, mut cold_iterations) = (0, 0);
    for (k, &mm) in shifts.iter().enumerate() {
        let input = mbench_a22_input(mm, None, None, WheelRailModel::Exact);
        let want = solve_wheelset_warm(&pair, &input, &cache, &mut scratch, &mut warm).unwrap();
        let s = step(1 + k);
        assert_eq!(s.step_index, k as u64);
        assert_eq!(s.marked, k == 1);
        assert_same(&format!("step {k}"), s.result.as_ref().unwrap(), &want);
        // A warm start is only a starting point: the same solution to the
        // load tolerance (1e-6 of the load, WheelRailSettings).
        let cold = solve_wheelset(&pair, &input, &cache, &mut scratch).unwrap();
        for (w, c) in want.wheels.iter().zip(&cold.wheels) {
            assert!(
                (w.force_track_n[2] - c.force_track_n[2]).abs() <= 2e-6 * 10_000.0,
                "step {k}: {} vs {}",
                w.force_track_n[2],
                c.force_track_n[2]
            );
            warm_iterations += w.load_iterations;
            cold_iterations += c.load_iterations;
        }
    }
    assert!(
        warm_iterations <= cold_iterations,
        "warm starts cost {warm_iterations} load iterations, cold solves {cold_iterations}"
    );
    // Refused in-band, state unchanged.
    let e = error(5);
    assert_eq!(e.code, Code::FailedPrecondition as i32, "{e:?}");
    assert!(e.message.contains("expects step 4"), "{}", e.message);
    assert_eq!(e.field, "step.step_index");
    let e = error(6);
    assert_eq!(e.code, Code::InvalidArgument as i32, "{e:?}");
    assert_eq!(e.field, "step.velocity");
    let e = error(7);
    assert_eq!(e.code, Code::FailedPrecondition as i32);
    assert!(e.message.contains("marked: 1"), "{}", e.message);
    assert_eq!(e.field, "rollback.to_step_index");
    match &r[8] {
        Out::RolledBack(b) => assert_eq!((b.to_step_index, b.next_step_index), (1, 2)),
        other => panic!("{other:?}"),
    }
    // The replay after the rollback repeats steps 2 and 3 bit for bit.
    for (replay, first) in [(9, 3), (10, 4)] {
        let (a, b) = (step(replay), step(first));
        assert_eq!(a.step_index, b.step_index);
        assert_eq!(untimed(a.result.unwrap()), untimed(b.result.unwrap()));
    }

    // An unknown pair ends the stream with NOT_FOUND; a bad setting with
    // INVALID_ARGUMENT naming it under `open`.
    let unknown = In::Open(pb::WheelRailSessionOpen {
        pair_id: "no_such_pair".into(),
        ..Default::default()
    });
    let e = wr_session(&mut client, vec![wr_request(unknown)])
        .await
        .unwrap_err();
    assert_eq!(e.code(), Code::NotFound, "{e:?}");
    let bad = In::Open(pb::WheelRailSessionOpen {
        pair_id: BUILTIN.into(),
        element_size_m: Some(-1.0),
        ..Default::default()
    });
    let e = wr_session(&mut client, vec![wr_request(bad)])
        .await
        .unwrap_err();
    assert_eq!(e.code(), Code::InvalidArgument, "{e:?}");
    assert!(
        e.message().contains("open.element_size_m"),
        "{}",
        e.message()
    );
    server.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_table_model_builds_the_pairs_contact_table_once_and_solves_as_the_library() {
    let dir = tempfile::tempdir().unwrap();
    let (server, mut client) = server_in(dir.path()).await;
    let pair = mbench_pair();
    let table = ContactTable::build(&pair, &TableSettings::default()).unwrap();
    let cache = KernelCache::default();
    // Two queries at once: the first use builds the table once for both.
    let queries: Vec<_> = [2.0, 6.5]
        .iter()
        .map(|&mm| {
            let input = mbench_a22_input(mm, None, None, WheelRailModel::HertzFastsim);
            let mut q = query_of(BUILTIN, &input);
            q.model = pb::WheelRailModel::HertzFastsimTable as i32;
            (input, q)
        })
        .collect();
    let (mut c1, mut c2) = (client.clone(), client.clone());
    let (r1, r2) = tokio::join!(
        solve(&mut c1, queries[0].1.clone()),
        solve(&mut c2, queries[1].1.clone())
    );
    for ((input, _), got) in queries.iter().zip([r1, r2]) {
        let want =
            solve_wheelset_tabulated(&table, input, &cache, &mut SearchScratch::default()).unwrap();
        assert_same("tabulated", &got, &want);
        assert_eq!(got.model, pb::WheelRailModel::HertzFastsimTable as i32);
    }
    // The table's geometry differs from the direct search's (by its stated
    // tolerance), so the results do too: the table was used.
    let mut direct = queries[1].1.clone();
    direct.model = pb::WheelRailModel::HertzFastsim as i32;
    let direct = solve(&mut client, direct).await;
    let tabulated = solve(&mut client, queries[1].1.clone()).await;
    assert_ne!(untimed(direct), untimed(tabulated));
    server.shutdown().await;
}

/// Rail steel at 20 °C, a wheel at 60 °C conducting 40 % less (so that
/// rail and wheel cannot be swapped unseen).
fn a22_thermal() -> WheelRailThermal {
    WheelRailThermal {
        rail: ThermalBody::steel(293.15),
        wheel: ThermalBody {
            conductivity_w_per_m_k: 30.0,
            ..ThermalBody::steel(333.15)
        },
    }
}

/// The wire temperatures of each patch equal the library's, bit for bit:
/// the rail's as body 1, the wheel's as body 2; the fields only with
/// `fields`.
fn assert_same_temperatures(
    what: &str,
    got: &pb::WheelRailResult,
    want: &WheelRailSolution,
    fields: bool,
) {
    for (g, w) in got.wheels.iter().zip(&want.wheels) {
        for (gp, wp) in g.patches.iter().zip(&w.patches) {
            let gt = gp.temperature.as_ref().expect("temperatures on the wire");
            let wt = wp
                .temperature
                .as_ref()
                .expect("temperatures in the library");
            let peak = |p: &Option<pb::TemperaturePeak>| {
                let p = p.unwrap();
                [p.temperature_k, p.x_m, p.y_m].map(bits)
            };
            assert_eq!(
                peak(&gt.max_body1),
                [wt.max_rail.temperature_k, wt.max_rail.x_m, wt.max_rail.y_m].map(bits),
                "{what}: the rail's peak"
            );
            assert_eq!(
                peak(&gt.max_body2),
                [
                    wt.max_wheel.temperature_k,
                    wt.max_wheel.x_m,
                    wt.max_wheel.y_m
                ]
                .map(bits),
                "{what}: the wheel's peak"
            );
            assert_eq!(
                [
                    gt.contact_temperature_k,
                    gt.heat_share_body1,
                    gt.frictional_power_w,
                    gt.peclet_number
                ]
                .map(bits),
                [
                    wt.contact_temperature_k,
                    wt.heat_share_rail,
                    wt.frictional_power_w,
                    wt.peclet_number
                ]
                .map(bits),
                "{what}: totals"
            );
            if fields {
                assert_eq!(gt.body1_k, wt.surface.body1_k, "{what}: the rail's field");
                assert_eq!(gt.body2_k, wt.surface.body2_k, "{what}: the wheel's field");
                assert_eq!(gt.heat_flux_w_per_m2, wt.surface.heat_flux_w_per_m2);
                assert_eq!(gt.body1_k.len(), (gp.grid_nx * gp.grid_ns) as usize);
            } else {
                assert!(
                    gt.body1_k.is_empty()
                        && gt.body2_k.is_empty()
                        && gt.heat_flux_w_per_m2.is_empty()
                );
            }
        }
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn wheel_rail_temperatures_come_per_patch_as_the_library_and_replay_bit_for_bit() {
    use pb::wheel_rail_session_request::Kind as In;
    use pb::wheel_rail_session_response::Kind as Out;
    let dir = tempfile::tempdir().unwrap();
    let (server, mut client) = server_in(dir.path()).await;
    let pair = mbench_pair();
    let cache = KernelCache::default();

    // A query: peaks per patch as the library's; fields with include_fields.
    let mut input = mbench_a22_input(
        6.5,
        Some(-0.004376),
        Some(-4.2748834),
        WheelRailModel::Exact,
    );
    let plain = solve(&mut client, query_of(BUILTIN, &input)).await;
    assert!(plain
        .wheels
        .iter()
        .flat_map(|w| &w.patches)
        .all(|p| p.temperature.is_none()));
    input.temperature = Some(a22_thermal());
    let want = solve_wheelset(&pair, &input, &cache, &mut SearchScratch::default()).unwrap();
    let req = query_of(BUILTIN, &input);
    let section = req.temperature.expect("query_of sends the temperatures");
    let got = solve(&mut client, req.clone()).await;
    assert_same("query", &got, &want);
    assert_same_temperatures("query", &got, &want, false);
    // The contact figures are those of the query without temperatures.
    assert_eq!(untimed(plain.clone()).wheels.len(), got.wheels.len());
    for (a, b) in plain.wheels.iter().zip(&got.wheels) {
        for (pa, pb_) in a.patches.iter().zip(&b.patches) {
            assert_eq!(
                [pa.normal_force_n, pa.fx_n, pa.fs_n, pa.frictional_power_w].map(bits),
                [
                    pb_.normal_force_n,
                    pb_.fx_n,
                    pb_.fs_n,
                    pb_.frictional_power_w
                ]
                .map(bits)
            );
        }
    }
    let flange = &got.wheels[1].patches[0];
    let t = flange.temperature.as_ref().unwrap();
    assert!(
        t.max_body1.unwrap().temperature_k > t.contact_temperature_k + 100.0,
        "{t:?}"
    );
    let mut with_fields = req.clone();
    with_fields.include_fields = true;
    let got = solve(&mut client, with_fields).await;
    assert_same_temperatures("query with fields", &got, &want, true);

    // A cect patch's temperatures come from its curved grid, which is sent
    // with them (its ElementFields are not).
    let mut cect = input.clone();
    cect.settings.model = WheelRailModel::Cect;
    let want_cect = solve_wheelset(&pair, &cect, &cache, &mut SearchScratch::default()).unwrap();
    let mut r = query_of(BUILTIN, &cect);
    r.include_fields = true;
    let got_cect = solve(&mut client, r).await;
    assert_same("cect", &got_cect, &want_cect);
    assert_same_temperatures("cect", &got_cect, &want_cect, true);
    for p in got_cect.wheels.iter().flat_map(|w| &w.patches) {
        assert_eq!(p.method, pb::WheelRailModel::Cect as i32);
        let g = p.grid.expect("the grid of the temperature fields");
        assert_eq!((g.nx, g.ny), (p.grid_nx, p.grid_ns));
        assert!(p.fields.is_none());
    }

    // A batch item carries them too.
    let out = client
        .solve_wheel_rail_batch(pb::SolveWheelRailBatchRequest {
            items: vec![req.clone()],
        })
        .await
        .unwrap()
        .into_inner()
        .items;
    match out[0].outcome.as_ref().unwrap() {
        pb::wheel_rail_batch_item::Outcome::Result(r) => {
            assert_same_temperatures("batch", r, &want, false)
        }
        other => panic!("{other:?}"),
    }

    // Bad input: INVALID_ARGUMENT naming the field.
    let mut r = req.clone();
    r.temperature
        .as_mut()
        .unwrap()
        .body2
        .as_mut()
        .unwrap()
        .conductivity_w_per_m_k = 0.0;
    assert_invalid(
        &solve_err(&mut client, r).await,
        &["temperature.body2.conductivity_w_per_m_k"],
    );
    let mut r = req.clone();
    r.temperature.as_mut().unwrap().body1 = None;
    assert_invalid(
        &solve_err(&mut client, r).await,
        &["temperature.body1", "missing"],
    );
    let mut r = req.clone();
    r.temperature.as_mut().unwrap().rolling_speed_m_per_s = 2.0;
    assert_invalid(
        &solve_err(&mut client, r).await,
        &["temperature.rolling_speed_m_per_s"],
    );
    let mut r = req.clone();
    r.model = pb::WheelRailModel::HertzFastsim as i32;
    assert_invalid(
        &solve_err(&mut client, r).await,
        &["temperature", "hertz_fastsim", "exact"],
    );

    // A session computes them at every step, as the library's warm
    // sequence, and replays them bit for bit after a rollback.
    let open = pb::WheelRailSessionOpen {
        pair_id: BUILTIN.into(),
        model: pb::WheelRailModel::Exact as i32,
        temperature: Some(section),
        ..Default::default()
    };
    let shifts = [3.0, 3.05, 3.1];
    let mut msgs = vec![wr_request(In::Open(open.clone()))];
    for (k, &mm) in shifts.iter().enumerate() {
        msgs.push(wr_step(k as u64, mm, k == 1));
    }
    msgs.push(wr_request(In::Rollback(pb::SessionRollback {
        to_step_index: 1,
    })));
    msgs.push(wr_step(2, shifts[2], false));
    let r = wr_session(&mut client, msgs).await.unwrap();
    assert_eq!(r.len(), 6, "{r:?}");
    let step = |k: usize| match &r[k] {
        Out::Step(s) => s.result.clone().unwrap(),
        other => panic!("response {k}: expected a step, got {other:?}"),
    };
    let mut scratch = SearchScratch::default();
    let mut warm = WarmStart::default();
    for (k, &mm) in shifts.iter().enumerate() {
        let mut input = mbench_a22_input(mm, None, None, WheelRailModel::Exact);
        input.temperature = Some(a22_thermal());
        let want = solve_wheelset_warm(&pair, &input, &cache, &mut scratch, &mut warm).unwrap();
        assert_same(&format!("step {k}"), &step(1 + k), &want);
        assert_same_temperatures(&format!("step {k}"), &step(1 + k), &want, false);
    }
    assert!(matches!(r[4], Out::RolledBack(_)), "{:?}", r[4]);
    assert_eq!(untimed(step(5)), untimed(step(3)), "the replayed step");

    // A bad section refuses the session, naming the field under `open`.
    let mut bad = open.clone();
    bad.temperature
        .as_mut()
        .unwrap()
        .body1
        .as_mut()
        .unwrap()
        .bulk_temperature_k = 20.0;
    let e = wr_session(&mut client, vec![wr_request(In::Open(bad))])
        .await
        .unwrap_err();
    assert_eq!(e.code(), Code::InvalidArgument, "{e:?}");
    assert!(
        e.message()
            .contains("open.temperature.body1.bulk_temperature_k")
            && e.message().contains("Celsius"),
        "{}",
        e.message()
    );
    server.shutdown().await;
}

/// Issue 43's pair: the measured MiniProf rail (mirrored) and wheel in
/// place of the benchmark's S1002 on UIC60, on the benchmark's track and
/// wheelset dimensions (the flange back at the MiniProf wheel's smallest y).
fn measured_spec() -> pb::ProfilePairSpec {
    pb::ProfilePairSpec {
        wheel: Some(file_source("avg_wheel.whl", false)),
        rail: Some(file_source("avg_HR.BAN", true)),
        track: Some(track(MBENCH_TRACK)),
        wheelset: Some(wheelset(WheelsetData {
            flange_back_y_m: None,
            ..MBENCH_WHEELSET
        })),
        ..Default::default()
    }
}

/// The wire warnings as (kind, field, side), in order.
fn warning_keys(r: &pb::WheelRailResult) -> Vec<(i32, String, i32)> {
    r.warnings
        .iter()
        .map(|w| (w.kind, w.field.clone(), w.side))
        .collect()
}

/// examples/cases/wheelset_a22.toml's roll and pitch rate (CONTACT's for
/// S1002 on UIC60 at 6.5 mm) given to measured profiles: every wheel/rail
/// answer (query, batch item, session step) says that the right wheel's
/// approach is beyond elastic contact because of `position.roll_rad` and
/// that the total longitudinal force saturates because of
/// `velocity.pitch_rad_per_s`, as the library's check does; the benchmark
/// itself warns of nothing.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn answers_no_elastic_contact_gives_carry_warnings_naming_the_input() {
    use pb::wheel_rail_batch_item::Outcome;
    use pb::wheel_rail_session_request::Kind as In;
    use pb::wheel_rail_session_response::Kind as Out;
    let dir = tempfile::tempdir().unwrap();
    let (server, mut client) = server_in(dir.path()).await;
    let id = register_ready(&mut client, spec_request(measured_spec(), "measured"))
        .await
        .pair_id;
    let input = mbench_a22_input(
        6.5,
        Some(-0.004376),
        Some(-4.2748834),
        WheelRailModel::Exact,
    );
    let (approach, longitudinal) = (
        pb::WheelRailWarningKind::Approach as i32,
        pb::WheelRailWarningKind::LongitudinalForce as i32,
    );
    let (right, wheelset) = (
        pb::WheelSide::Right as i32,
        pb::WheelSide::Unspecified as i32,
    );
    let expected = |prefix: &str| {
        vec![
            (approach, format!("{prefix}position.roll_rad"), right),
            (
                longitudinal,
                format!("{prefix}velocity.pitch_rad_per_s"),
                wheelset,
            ),
        ]
    };

    // SolveWheelRail: the library's warnings, word for word.
    let got = solve(&mut client, query_of(&id, &input)).await;
    assert_eq!(warning_keys(&got), expected(""), "{:#?}", got.warnings);
    let pair = library_pair(
        "avg_HR.BAN",
        true,
        "avg_wheel.whl",
        MBENCH_TRACK,
        WheelsetData {
            flange_back_y_m: None,
            ..MBENCH_WHEELSET
        },
    );
    let want = solve_wheelset(
        &pair,
        &input,
        &KernelCache::default(),
        &mut SearchScratch::default(),
    )
    .unwrap();
    assert_same("measured", &got, &want);
    let library = check_plausibility(&input, &want);
    assert_eq!(library.len(), got.warnings.len());
    for (w, l) in got.warnings.iter().zip(&library) {
        assert_eq!(
            (&w.message, w.value, w.limit),
            (&l.message, l.value, l.limit)
        );
    }
    assert!(got.warnings[0].value > 100.0 && got.warnings[0].limit == 10.0);
    assert!(
        got.warnings[0].message.contains("5.628 mm onto its rail"),
        "{}",
        got.warnings[0].message
    );

    // The benchmark's own pair at the same motion: nothing to say.
    let a22 = solve(&mut client, query_of(BUILTIN, &input)).await;
    assert!(a22.warnings.is_empty(), "{:#?}", a22.warnings);

    // A batch: each item's warnings in its slot, named by the item's path.
    let items = vec![query_of(BUILTIN, &input), query_of(&id, &input)];
    let out = client
        .solve_wheel_rail_batch(pb::SolveWheelRailBatchRequest { items })
        .await
        .unwrap()
        .into_inner()
        .items;
    match (&out[0].outcome, &out[1].outcome) {
        (Some(Outcome::Result(a)), Some(Outcome::Result(b))) => {
            assert!(a.warnings.is_empty(), "{:#?}", a.warnings);
            assert_eq!(warning_keys(b), expected("items[1]."), "{:#?}", b.warnings);
        }
        other => panic!("unexpected slots {other:?}"),
    }

    // A session (the table model, as MBS co-simulations run): the step
    // with the benchmark's roll and pitch rate warns, then the same motion
    // with the roll found and free rolling by a zero total longitudinal
    // force does not.
    let step = |k: u64, input: &WheelRailInput| {
        let q = query_of(&id, input);
        wr_request(In::Step(pb::WheelRailSessionStep {
            step_index: k,
            position: q.position,
            velocity: q.velocity,
            load: q.load,
            ..Default::default()
        }))
    };
    let mut found = input.clone();
    found.position.roll_rad = None;
    found.velocity.pitch_rad_per_s = None;
    found.total_longitudinal_force_n = Some(0.0);
    let open = In::Open(pb::WheelRailSessionOpen {
        pair_id: id.clone(),
        model: pb::WheelRailModel::HertzFastsimTable as i32,
        ..Default::default()
    });
    let out = wr_session(
        &mut client,
        vec![wr_request(open), step(0, &input), step(1, &found)],
    )
    .await
    .unwrap();
    let steps: Vec<_> = out
        .iter()
        .filter_map(|o| match o {
            Out::Step(s) => s.result.clone(),
            _ => None,
        })
        .collect();
    assert_eq!(steps.len(), 2, "{out:?}");
    assert_eq!(
        warning_keys(&steps[0]),
        expected("step."),
        "{:#?}",
        steps[0].warnings
    );
    assert!(steps[1].warnings.is_empty(), "{:#?}", steps[1].warnings);
    server.shutdown().await;
}
