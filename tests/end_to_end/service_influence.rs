//! Numerical influence coefficients (CONTACT's C3 = 9) on the wire:
//! `MaterialSection.influence_file_content`, the text of a file in
//! CONTACT's format sent with the request, gives the numbers of
//! `railcontact solve` on a case file naming the same file
//! (`material.influence_file`) bit for bit; its errors are
//! INVALID_ARGUMENT naming the field (and the text's line); wheel/rail
//! requests refuse it.

use railcontact::conformal::frictional::FrictionalWorkspace;
use railcontact::problem::case::Case;
use railcontact::problem::ModelRun;
use railcontact::service::config::ServeConfig;
use railcontact::service::convert::{result_of_report, total_values};
use railcontact::service::pb;
use tonic::Code;

use crate::common::{server_with, Client};

const CASES: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/cases");
const DATA: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/crates/solver/tests/data/inflcf"
);
const FIELD: &str = "case.material.influence_file_content";

/// The text of `crates/solver/tests/data/inflcf/NAME`.
pub fn inflcf(name: &str) -> String {
    std::fs::read_to_string(format!("{DATA}/{name}")).unwrap()
}

/// `examples/cases/numerical_influence.toml` on the wire, the
/// coefficients `text` inline.
pub fn numerical_influence_case(text: String) -> pb::PatchCase {
    let body = |g: f64, nu: f64| pb::Material {
        shear_modulus_pa: g,
        poisson_ratio: nu,
    };
    pb::PatchCase {
        model: pb::Model::Exact as i32,
        material: Some(pb::MaterialSection {
            body1: Some(body(82.0e9, 0.28)),
            body2: Some(body(60.0e9, 0.20)),
            influence_file_content: Some(text),
            ..Default::default()
        }),
        friction: Some(pb::FrictionSection {
            coefficient: Some(0.30),
            ..Default::default()
        }),
        geometry: Some(pb::GeometrySection {
            kind: pb::GeometryKind::Quadratic as i32,
            a_per_m: Some(2.5),
            b_per_m: Some(3.5),
            ..Default::default()
        }),
        load: Some(pb::LoadSection {
            load: Some(pb::load_section::Load::NormalForceN(12000.0)),
        }),
        kinematics: Some(pb::patch_case::Kinematics::Rolling(pb::Creepages {
            creepage_long: -0.0012,
            creepage_lat: 0.0008,
            ..Default::default()
        })),
        grid: Some(pb::GridSection {
            nx: Some(21),
            ny: Some(17),
            window_x_m: Some(0.0084),
            window_y_m: Some(0.0068),
        }),
        ..Default::default()
    }
}

/// The edits that make the example `inflcf.inp` case 5 (CONTACT's case of
/// its per-row file `inflcf_rows.txt`): 13 x 9 elements, B = 6 /m, 3000 N.
const ROWS_CASE: [(&str, &str); 6] = [
    ("b_per_m = 3.5", "b_per_m = 6.0"),
    ("normal_force_n = 12000.0", "normal_force_n = 3000.0"),
    ("nx = 21", "nx = 13"),
    ("ny = 17", "ny = 9"),
    ("window_x_m = 0.0084", "window_x_m = 0.0052"),
    ("window_y_m = 0.0068", "window_y_m = 0.0036"),
];

/// [`numerical_influence_case`] edited as [`ROWS_CASE`] edits the file.
fn rows_case(text: String) -> pb::PatchCase {
    let mut c = numerical_influence_case(text);
    c.geometry.as_mut().unwrap().b_per_m = Some(6.0);
    c.load = Some(pb::LoadSection {
        load: Some(pb::load_section::Load::NormalForceN(3000.0)),
    });
    c.grid = Some(pb::GridSection {
        nx: Some(13),
        ny: Some(9),
        window_x_m: Some(0.0052),
        window_y_m: Some(0.0036),
    });
    c
}

/// `railcontact solve` on the example case file naming `file` (in
/// `crates/solver/tests/data/inflcf/`) edited by `edits`, as the service
/// reports it.
fn case_file_result(file: &str, edits: &[(&str, &str)]) -> pb::PatchResult {
    let mut text = std::fs::read_to_string(format!("{CASES}/numerical_influence.toml"))
        .unwrap()
        .replace("inflcf_hs.txt", file);
    for (from, to) in edits {
        assert!(text.contains(from), "{from}");
        text = text.replace(from, to);
    }
    let case = Case::from_toml_in(&text, std::path::Path::new(CASES)).expect("a valid case");
    match ModelRun::solve(&case, &mut FrictionalWorkspace::default()) {
        Ok(ModelRun::Exact(run)) => result_of_report(&run.report(&case, true)),
        Ok(_) => panic!("the exact model"),
        Err(e) => panic!("{e}"),
    }
}

/// Every total and field value's bits, and the element states.
fn bits(r: &pb::PatchResult) -> (Vec<u64>, Vec<i32>) {
    let t = r.result.as_ref().unwrap().totals.as_ref().unwrap();
    let f = r.fields.as_ref().unwrap();
    let values = total_values(t)
        .iter()
        .chain(&f.pressure_pa)
        .chain(&f.traction_x_pa)
        .chain(&f.traction_y_pa)
        .chain(&f.slip_x)
        .chain(&f.slip_y)
        .map(|v| v.to_bits())
        .collect();
    (values, f.state.clone())
}

async fn solve(client: &mut Client, case: pb::PatchCase) -> Result<pb::PatchResult, tonic::Status> {
    Ok(client
        .solve_patch(pb::SolvePatchRequest {
            case: Some(case),
            include_fields: true,
            ..Default::default()
        })
        .await?
        .into_inner()
        .result
        .unwrap())
}

/// The field and message of an INVALID_ARGUMENT status.
fn refusal(r: Result<pb::PatchResult, tonic::Status>) -> (String, String) {
    let s = r.expect_err("refused");
    assert_eq!(s.code(), Code::InvalidArgument, "{}", s.message());
    let m = s.message().to_string();
    let field = m
        .strip_prefix("invalid `")
        .and_then(|r| r.split_once('`'))
        .map_or(String::new(), |(f, _)| f.to_string());
    (field, m)
}

/// The example's case (CONTACT's `inflcf.inp` case 2) through the wire and
/// through the case file, with one matrix of the grid (the half-space's
/// coefficients), a smaller file (an approximation: other numbers) and a
/// larger one, and its case 5 with one matrix per grid row: the same bits,
/// every total and field; CONTACT's forces. A creep curve takes the
/// coefficients as SolvePatch does.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn influence_coefficients_on_the_wire_solve_as_the_case_file() {
    let (server, mut client) = server_with(ServeConfig::default()).await;
    let mut fx = Vec::new();
    let planar: fn(String) -> pb::PatchCase = numerical_influence_case;
    for (file, edits, wire_case) in [
        ("inflcf_hs.txt", &[][..], planar),
        ("inflcf_hs_small.txt", &[][..], planar),
        ("inflcf_hs_large.txt", &[][..], planar),
        ("inflcf_rows.txt", &ROWS_CASE[..], rows_case),
    ] {
        let wire = solve(&mut client, wire_case(inflcf(file)))
            .await
            .unwrap_or_else(|e| panic!("{file}: {e}"));
        let cli = case_file_result(file, edits);
        assert_eq!(bits(&wire), bits(&cli), "{file}");
        assert!(
            wire.notes.iter().any(|n| n.starts_with(
                "material.influence_file_content: the influence coefficients are the file's"
            )),
            "{file}: {:?}",
            wire.notes
        );
        fx.push(wire.result.unwrap().totals.unwrap().fx_n);
    }
    // A creep curve takes the coefficients too: its point at the case's
    // creepages (warm-started from the one before) is SolvePatch's answer
    // to the solver's tolerance.
    let case = numerical_influence_case(inflcf("inflcf_hs_small.txt"));
    let creepages = |xi: f64, eta: f64| pb::Creepages {
        creepage_long: xi,
        creepage_lat: eta,
        ..Default::default()
    };
    let mut stream = client
        .creep_curve(pb::CreepCurveRequest {
            case: Some(case),
            sweep: Some(pb::creep_curve_request::Sweep::List(pb::CreepageList {
                points: vec![creepages(-0.0006, 0.0004), creepages(-0.0012, 0.0008)],
            })),
            include_fields: false,
        })
        .await
        .unwrap()
        .into_inner();
    let mut curve = Vec::new();
    while let Some(p) = stream.message().await.unwrap() {
        curve.push(p.result.unwrap().result.unwrap().totals.unwrap().fx_n);
    }
    assert_eq!(curve.len(), 2);
    assert!((curve[1] / fx[1] - 1.0).abs() < 1e-6, "{curve:?} {fx:?}");
    // CONTACT's inflcf.inp case 2 on the half-space's file: FX 2217 N; case
    // 5 on the per-row file: FX 654.6 N (its printed 4 digits; the
    // validation test `numerical_influence`).
    assert!((fx[0] - 2217.0).abs() < 0.5, "{fx:?}");
    assert!((fx[3] - 654.6).abs() < 0.05, "{fx:?}");
    // The smaller file is another table: other forces, so the wire did
    // not fall back on the half-space.
    assert!((fx[1] - fx[0]).abs() > 1.0, "{fx:?}");
    server.shutdown().await;
}

/// Refusals name the wire field: the text's line and field, the grid it
/// does not fit, a model that does not take it; in a batch, the item's
/// field; in a wheel/rail registration, the spec's.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn influence_coefficient_errors_name_the_wire_field() {
    let (server, mut client) = server_with(ServeConfig::default()).await;
    let text = inflcf("inflcf_hs_small.txt");
    let line = |t: &str, k: usize| t.lines().nth(k - 1).unwrap().to_string();
    // Line 7 is the first coefficient line (ixofs 0); its Cnn the third word.
    let first = line(&text, 7);
    let cnn = first.split_whitespace().nth(2).unwrap();
    let cases = [
        ("garbage", "not a file".to_string(), "line 1: `nmatrix`"),
        ("empty", String::new(), "ends at line 0"),
        (
            "NaN",
            text.replacen(&first, &first.replacen(cnn, "NaN", 1), 1),
            "line 7: `Cnn` is not a finite number",
        ),
        (
            "1e400",
            text.replacen(&first, &first.replacen(cnn, "1e400", 1), 1),
            "line 7: `Cnn` is not a finite number",
        ),
        (
            "1e300",
            text.replacen(&first, &first.replacen(cnn, "1e300", 1), 1),
            "line 7: `Cnn` must be within +-1e6 mm",
        ),
        (
            "huge declared grid",
            "1 1\n0 312\n1 0\n1048576 1048576 0.4 0.4\n".to_string(),
            "line 4: `mxfile`",
        ),
        (
            "declared lines missing",
            "1 1\n0 312\n1 0\n1048576 1 0.4 0.4\n".to_string(),
            "expected 1048576 coefficient lines",
        ),
        (
            "other element size",
            text.replacen(" 0.4 0.4 ", " 0.5 0.4 ", 1),
            "dxfile",
        ),
    ];
    for (what, content, expect) in cases {
        let (field, m) = refusal(solve(&mut client, numerical_influence_case(content)).await);
        assert_eq!(field, FIELD, "{what}: {m}");
        assert!(m.contains(expect), "{what}: {m}");
    }
    let mut fastsim = numerical_influence_case(text.clone());
    fastsim.model = pb::Model::Fastsim as i32;
    let (field, m) = refusal(solve(&mut client, fastsim).await);
    assert_eq!(field, FIELD, "{m}");
    assert!(m.contains("model = \"exact\" only"), "{m}");

    let batch = client
        .solve_patch_batch(pb::SolvePatchBatchRequest {
            items: vec![pb::SolvePatchRequest {
                case: Some(numerical_influence_case("1 3".into())),
                ..Default::default()
            }],
        })
        .await
        .unwrap()
        .into_inner();
    let Some(pb::batch_item_result::Outcome::Error(e)) = &batch.items[0].outcome else {
        panic!("{:?}", batch.items[0]);
    };
    assert_eq!(e.field, format!("items[0].{FIELD}"), "{}", e.message);
    assert!(
        e.message.contains("`iaconvex` must be 1 or 2"),
        "{}",
        e.message
    );

    let mut spec = pb::ProfilePairSpec {
        material: Some(pb::MaterialSection {
            shear_modulus_pa: Some(82e9),
            poisson_ratio: Some(0.28),
            influence_file_content: Some(text),
            ..Default::default()
        }),
        ..Default::default()
    };
    spec.wheel = None;
    let s = client
        .register_profile_pair(pb::RegisterProfilePairRequest {
            pair: Some(pb::register_profile_pair_request::Pair::Spec(spec)),
            label: "influence".into(),
        })
        .await
        .expect_err("refused");
    assert_eq!(s.code(), Code::InvalidArgument, "{}", s.message());
    assert!(
        s.message()
            .starts_with("invalid `spec.material.influence_file_content`: "),
        "{}",
        s.message()
    );
    server.shutdown().await;
}

/// A request larger than the server's `max_message_bytes` never reaches
/// the parser: the transport refuses it.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn influence_text_beyond_the_request_size_is_refused_by_the_transport() {
    let (server, mut client) = server_with(ServeConfig {
        max_message_bytes: 64 << 10,
        ..ServeConfig::default()
    })
    .await;
    // 108 kB of text.
    let s = solve(
        &mut client,
        numerical_influence_case(inflcf("inflcf_hs.txt")),
    )
    .await
    .expect_err("too large");
    assert_eq!(s.code(), Code::ResourceExhausted, "{}", s.message());
    assert!(s.message().contains("max_message_bytes"), "{}", s.message());
    server.shutdown().await;
}

/// A session's memory counts the coefficients it holds: 72 bytes a
/// coefficient line, (2 x 9 - 1) x 13 = 221 lines of
/// `inflcf_hs_small.txt`, beside the same case on the half-space.
#[test]
fn a_sessions_memory_counts_its_influence_coefficients() {
    use railcontact::core::cache::KernelCache;
    use railcontact::service::convert::{validate_case, CaseLimits};
    use railcontact::service::engine::PatchEngine;
    let limits = CaseLimits {
        max_grid_elements: ServeConfig::default().max_grid_elements,
    };
    let cache = KernelCache::default();
    let bytes = |c: &pb::PatchCase| {
        PatchEngine::new(validate_case(c, limits).unwrap(), &cache)
            .unwrap()
            .heap_bytes()
    };
    let with = numerical_influence_case(inflcf("inflcf_hs_small.txt"));
    let mut without = with.clone();
    without.material.as_mut().unwrap().influence_file_content = None;
    assert_eq!(bytes(&with) - bytes(&without), 221 * 9 * 8);
}
