//! `ContactLibrary`, the stream CONTACT's library (crates/cntc) forwards
//! its calculations on, as a hostile or mismatched client meets it: a
//! payload of another version, an unknown module, a request that does not
//! decode (refused in-band, the element unchanged), a grid beyond the
//! server's limit (CONTACT's discretisation error in the reply), a first
//! message that is not `open`. The library's own tests
//! (`crates/cntc/tests/forward.rs`) check the numbers against in-process
//! calculations.

use railcontact::service::config::ServeConfig;
use railcontact::service::pb;
use railcontact_cntc_core::call::Call;
use railcontact_cntc_core::element::CalculationResult;
use railcontact_cntc_core::flags::{self, err};
use railcontact_cntc_core::remote::{decode, encode, Reply, Request, FORMAT_VERSION};
use tokio::sync::mpsc;
use tokio_stream::wrappers::ReceiverStream;
use tonic::Code;

use crate::common::{server_with, Client};
use pb::contact_library_request::Kind as In;
use pb::contact_library_response::Kind as Out;

/// A stream whose first message is `open`; the sender and the responses.
async fn open(
    client: &mut Client,
    o: pb::ContactLibraryOpen,
) -> (
    mpsc::Sender<pb::ContactLibraryRequest>,
    Result<tonic::Streaming<pb::ContactLibraryResponse>, tonic::Status>,
) {
    let (tx, rx) = mpsc::channel(4);
    tx.send(pb::ContactLibraryRequest {
        kind: Some(In::Open(o)),
    })
    .await
    .unwrap();
    let r = client
        .contact_library(ReceiverStream::new(rx))
        .await
        .map(|r| r.into_inner());
    (tx, r)
}

fn module3() -> pb::ContactLibraryOpen {
    pb::ContactLibraryOpen {
        format_version: FORMAT_VERSION,
        module: 3,
        ire: 1,
        client_label: "test".into(),
    }
}

/// The calls of a Hertzian steady-rolling patch (CONTACT's units) of
/// `mx` x `my` elements at creepage 1e-3.
fn patch_calls(mx: f64, my: f64) -> Vec<(i32, Call)> {
    let mut calls: Vec<(i32, Call)> = [
        (flags::IF_UNITS, flags::UN_CNTC),
        (flags::IC_TANG, 3),
        (flags::IC_PVTIME, 2),
    ]
    .iter()
    .map(|&(code, value)| (1, Call::SetFlag { code, value }))
    .collect();
    calls.extend([
        (
            1,
            Call::SetMaterial {
                mdigit: 0,
                params: vec![0.28, 0.28, 82000.0, 82000.0],
            },
        ),
        (
            1,
            Call::SetFriction {
                imeth: 0,
                params: vec![0.3, 0.3],
            },
        ),
        (
            1,
            Call::SetHertz {
                ipotcn: -2,
                params: vec![mx, my, 0.0008, 0.5, 1.1],
            },
        ),
        (1, Call::SetNormalForce { fn_: 50000.0 }),
        (
            1,
            Call::SetCreepages {
                vx: 1e-3,
                vy: 0.0,
                phi: 0.0,
            },
        ),
    ]);
    calls
}

fn calculate(calls: Vec<(i32, Call)>) -> pb::ContactLibraryRequest {
    let request = encode(&Request { calls, icp: 1 }).unwrap();
    pb::ContactLibraryRequest {
        kind: Some(In::Calculate(pb::ContactLibraryCalculate { request })),
    }
}

async fn next(s: &mut tonic::Streaming<pb::ContactLibraryResponse>) -> Out {
    s.message().await.unwrap().unwrap().kind.unwrap()
}

fn reply(out: Out) -> Reply {
    match out {
        Out::Reply(bytes) => decode(&bytes, "reply").unwrap(),
        other => panic!("not a reply: {other:?}"),
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn open_refuses_another_payload_version_and_an_unknown_module() {
    let (_server, mut client) = server_with(ServeConfig::default()).await;
    let (_tx, r) = open(
        &mut client,
        pb::ContactLibraryOpen {
            format_version: FORMAT_VERSION + 1,
            ..module3()
        },
    )
    .await;
    let st = r.unwrap().message().await.unwrap_err();
    assert_eq!(st.code(), Code::FailedPrecondition, "{st:?}");
    assert!(st.message().contains("open.format_version"), "{st:?}");
    let (_tx, r) = open(
        &mut client,
        pb::ContactLibraryOpen {
            module: 2,
            ..module3()
        },
    )
    .await;
    let st = r.unwrap().message().await.unwrap_err();
    assert_eq!(st.code(), Code::InvalidArgument, "{st:?}");
    assert!(st.message().contains("open.module"), "{st:?}");
    // The first message must be `open`.
    let (tx, rx) = mpsc::channel(2);
    tx.send(calculate(patch_calls(20.0, 20.0))).await.unwrap();
    let st = client
        .contact_library(ReceiverStream::new(rx))
        .await
        .unwrap()
        .into_inner()
        .message()
        .await
        .unwrap_err();
    assert_eq!(st.code(), Code::InvalidArgument, "{st:?}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_request_that_does_not_decode_is_refused_and_changes_nothing() {
    let (_server, mut client) = server_with(ServeConfig::default()).await;
    let (tx, r) = open(&mut client, module3()).await;
    let mut s = r.unwrap();
    let Out::Opened(o) = next(&mut s).await else {
        panic!("not opened")
    };
    assert_eq!(o.format_version, FORMAT_VERSION);
    // Bytes that are no payload: refused in-band, naming the field.
    tx.send(pb::ContactLibraryRequest {
        kind: Some(In::Calculate(pb::ContactLibraryCalculate {
            request: vec![0xff; 64],
        })),
    })
    .await
    .unwrap();
    let Out::Error(e) = next(&mut s).await else {
        panic!("not refused")
    };
    assert_eq!(e.code, Code::InvalidArgument as i32, "{e:?}");
    assert_eq!(e.field, "calculate.request", "{e:?}");
    // The element is as it was: a whole configuration calculates.
    tx.send(calculate(patch_calls(20.0, 20.0))).await.unwrap();
    let r = reply(next(&mut s).await);
    assert_eq!(r.code, Ok(0));
    let CalculationResult::Patch { outcome: Some(o) } = r.result else {
        panic!("no outcome")
    };
    assert!((o.normal_force_n - 50000.0).abs() < 1e-6 * 50000.0);
    assert!(o.fx_n < 0.0, "a creep force opposing the creepage");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_grid_beyond_the_servers_limit_is_contacts_discretisation_error() {
    let (_server, mut client) = server_with(ServeConfig {
        max_grid_elements: 1000,
        ..ServeConfig::default()
    })
    .await;
    let (tx, r) = open(&mut client, module3()).await;
    let mut s = r.unwrap();
    next(&mut s).await;
    tx.send(calculate(patch_calls(48.0, 44.0))).await.unwrap();
    let r = reply(next(&mut s).await);
    let e = r.code.unwrap_err();
    assert_eq!(e.ierror, err::DISCR, "{e:?}");
    assert!(e.message.contains("max_grid_elements = 1000"), "{e:?}");
    // Fewer elements, the same element: solved.
    let smaller = vec![(
        1,
        Call::SetHertz {
            ipotcn: -2,
            params: vec![30.0, 30.0, 0.0008, 0.5, 1.1],
        },
    )];
    tx.send(calculate(smaller)).await.unwrap();
    assert_eq!(reply(next(&mut s).await).code, Ok(0));
}
