//! The forwarding mode (`CNTC_if_mode` = 1, `RAILCONTACT_CNTC_SERVER`)
//! against a railcontact server in the test process: every value a getter
//! reads is the in-process one bit for bit (steady rolling, a transient
//! sequence of shifts whose history lives on the server, FASTSIM, a
//! prescribed force, a wheel on its rail, an element configured by an input
//! file); a lost server is `CNTC_err_server` and the next calculation
//! catches a new server up; a transient sequence cannot continue on it;
//! elements on several threads forward at once.
//!
//! The mode is the library's (global): the tests take turns ([`turn`]).

mod common;

use std::sync::{Mutex, MutexGuard, OnceLock};

use common::{
    calculate, mbench_locus, mbench_right_wheel, mbench_right_wheel_with, mode, patch_values,
    profile, read_inp, set_flags, tractcurv, wheel_results, InpDir, Load, TestServer,
    MBENCH_RIGHT_INP,
};
use contact_addon::ffi::*;
use contact_addon::flags::{self, err};

/// The test server, restartable on the same port; tests take turns.
fn turn() -> MutexGuard<'static, Option<TestServer>> {
    static SERVER: OnceLock<Mutex<Option<TestServer>>> = OnceLock::new();
    let lock = SERVER.get_or_init(|| {
        let server = TestServer::start("127.0.0.1:0");
        // Read by the library at its first use, which comes after this.
        std::env::set_var("RAILCONTACT_CNTC_SERVER", server.addr.to_string());
        std::env::set_var("RAILCONTACT_CNTC_TIMEOUT_S", "30");
        Mutex::new(Some(server))
    });
    let mut guard = lock.lock().unwrap_or_else(|p| p.into_inner());
    if guard.is_none() {
        // A test that failed while its server was down: start it again.
        let addr = std::env::var("RAILCONTACT_CNTC_SERVER").unwrap();
        *guard = Some(TestServer::start(&addr));
    }
    guard
}

/// The ierror and getter values of `scenario` run on element `ire` in
/// process and on element `ire + 100` forwarded.
fn both_modes(ire: i32, scenario: impl Fn(i32) -> Vec<(i32, Vec<u64>)>) {
    mode(false);
    let local = scenario(ire);
    mode(true);
    let forwarded = scenario(ire + 100);
    mode(false);
    assert_eq!(local.len(), forwarded.len());
    for (k, (a, b)) in local.iter().zip(&forwarded).enumerate() {
        assert_eq!(a.0, b.0, "calculation {k}: ierror in process, forwarded");
        assert_eq!(a.1.len(), b.1.len(), "calculation {k}: values");
        let differ = a.1.iter().zip(&b.1).filter(|(x, y)| x != y).count();
        assert_eq!(differ, 0, "calculation {k}: {differ} values differ");
    }
    for e in [ire, ire + 100] {
        unsafe { cntc_finalize(&e) };
    }
}

#[test]
fn forwarded_calculations_equal_the_in_process_ones_bit_for_bit() {
    let _turn = turn();
    // Steady rolling, exact: a creep curve and spin.
    both_modes(1, |ire| {
        tractcurv(ire, 3, 2);
        [[1e-4, 0.0, 0.0], [1e-3, 0.0, 0.0], [0.0, 5e-4, 1e-4]]
            .iter()
            .map(|c| (calculate(ire, *c), patch_values(ire)))
            .collect()
    });
    // A transient sequence of shifts continued (P = 1): the history is
    // the server's.
    both_modes(2, |ire| {
        tractcurv(ire, 1, 2);
        let first = (calculate(ire, [1e-3, 0.0, 0.0]), patch_values(ire));
        set_flags(ire, 1, &[(flags::IC_PVTIME, 1)]);
        let mut out = vec![first];
        for k in 1..4 {
            let c = [1e-3 + 5e-4 * k as f64, 2e-4 * k as f64, 0.0];
            out.push((calculate(ire, c), patch_values(ire)));
        }
        out
    });
    // FASTSIM (M = 3; M = 2 with FLX given) and a prescribed tangential
    // force (F = 1).
    both_modes(3, |ire| {
        tractcurv(ire, 3, 2);
        let mat = [0.28, 0.28, 82000.0, 82000.0, 1.0, 1.0, 1.0];
        unsafe { cntc_setmaterialparameters(&ire, &1, &3, &7, mat.as_ptr()) };
        let fastsim = (calculate(ire, [8e-4, 0.0, 0.0]), patch_values(ire));
        let mat = [0.28, 0.28, 82000.0, 82000.0, 5e-5, 0.54, 0.02, 0.62];
        unsafe { cntc_setmaterialparameters(&ire, &1, &2, &8, mat.as_ptr()) };
        let given = (calculate(ire, [8e-4, 2e-4, 1e-4]), patch_values(ire));
        assert_eq!(given.0, 0);
        let mat = [0.28, 0.28, 82000.0, 82000.0];
        unsafe { cntc_setmaterialparameters(&ire, &1, &0, &4, mat.as_ptr()) };
        set_flags(ire, 1, &[(flags::IC_FORCE, 1)]);
        unsafe { cntc_settangentialforces(&ire, &1, &-0.4, &0.0) };
        let force = (calculate(ire, [0.0, 0.0, 0.0]), patch_values(ire));
        vec![fastsim, given, force]
    });
    // A wheel on its rail (module 1): the Manchester benchmark's right
    // wheel in flange contact, its global forces and patch locations.
    both_modes(4, |ire| {
        let mut out = Vec::new();
        for y in [2.0, 7.5] {
            out.push(mbench_right_wheel(ire, y, None));
        }
        // F = 1: the pitch rate found for a total force FX_WS.
        out.push(mbench_right_wheel(ire, 3.0, Some(1500.0)));
        // F = 3: the massless rail's deflections (DY_DEFL, DZ_DEFL among
        // the location values), the second from the first (I = 1).
        set_flags(ire, -1, &[(flags::IC_FORCE, 3)]);
        let rail = [20000.0, -2000.0, 20000.0, -5000.0, 0.5];
        unsafe { cntc_settrackdimensions(&ire, &32, &5, rail.as_ptr()) };
        out.push(wheel_results(ire));
        set_flags(ire, -1, &[(flags::IC_IESTIM, 1)]);
        unsafe { cntc_settrackdimensions(&ire, &32, &4, rail.as_ptr()) };
        out.push(wheel_results(ire));
        set_flags(ire, -1, &[(flags::IC_FORCE, 0), (flags::IC_IESTIM, 0)]);
        // M = 3 (modified FASTSIM on each patch): tread and flange; M = 2
        // (FLX given) on the flange; T = 0; M = 4, an elasto-plastic layer
        // on the flange. Every patch getter of the first patch too (fields
        // included).
        let fastsim: &[f64] = &[0.54, 0.02, 0.62];
        let given: &[f64] = &[1.5e-4, 0.54, 0.02, 0.62];
        let layer: &[f64] = &[500.0, 0.1, 60.0, 0.0];
        for (y, tang, material) in [
            (2.0, 3, Some((3, fastsim))),
            (7.5, 3, Some((3, fastsim))),
            (7.5, 3, Some((2, given))),
            (7.5, 0, None),
            (7.5, 3, Some((4, layer))),
        ] {
            out.push(mbench_right_wheel_with(ire, y, None, tang, material));
            out.push((0, patch_values(ire)));
        }
        out
    });
}

/// An element configured by an input file (`cntc_readinpfile`): its calls
/// reach the server as a setter's do, the same bits in both modes.
#[test]
fn an_input_file_reaches_the_server_as_its_calls() {
    let _turn = turn();
    let dir = InpDir::new("forward");
    let inp = dir.write("mbench.inp", MBENCH_RIGHT_INP);
    both_modes(5, |ire| {
        assert_eq!(read_inp(ire, flags::INP_MODUL1, &inp), 0);
        vec![wheel_results(ire)]
    });
}

#[test]
fn a_lost_server_is_a_server_error_and_the_next_calculation_catches_a_new_one_up() {
    let mut server = turn();
    let (local, fwd) = (11, 12);
    mode(false);
    tractcurv(local, 3, 2);
    assert_eq!(calculate(local, [1e-3, 0.0, 0.0]), 0);
    let expected = patch_values(local);
    mode(true);
    tractcurv(fwd, 3, 2);
    assert_eq!(calculate(fwd, [2e-3, 0.0, 0.0]), 0);
    // The server goes away: the calculation says so.
    let addr = std::env::var("RAILCONTACT_CNTC_SERVER").unwrap();
    server.take().unwrap().kill();
    assert_eq!(calculate(fwd, [1e-3, 0.0, 0.0]), err::SERVER);
    // A server on the same port: the element's calls are sent again and
    // the calculation is the in-process one, bit for bit.
    *server = Some(TestServer::start(&addr));
    assert_eq!(calculate(fwd, [1e-3, 0.0, 0.0]), 0);
    assert_eq!(patch_values(fwd), expected);
    mode(false);
    for e in [local, fwd] {
        unsafe { cntc_finalize(&e) };
    }
}

#[test]
fn a_transient_sequence_does_not_continue_on_a_new_server() {
    let mut server = turn();
    let ire = 21;
    mode(true);
    tractcurv(ire, 1, 2);
    assert_eq!(calculate(ire, [1e-3, 0.0, 0.0]), 0);
    set_flags(ire, 1, &[(flags::IC_PVTIME, 1)]);
    assert_eq!(calculate(ire, [2e-3, 0.0, 0.0]), 0);
    let addr = std::env::var("RAILCONTACT_CNTC_SERVER").unwrap();
    server.take().unwrap().kill();
    *server = Some(TestServer::start(&addr));
    // The element's stream went with the old server; the new copy has no
    // history: continuing is refused, starting again (P = 2) is not.
    assert_eq!(calculate(ire, [3e-3, 0.0, 0.0]), err::SERVER);
    assert_eq!(calculate(ire, [3e-3, 0.0, 0.0]), err::SERVER);
    set_flags(ire, 1, &[(flags::IC_PVTIME, 2)]);
    assert_eq!(calculate(ire, [3e-3, 0.0, 0.0]), 0);
    set_flags(ire, 1, &[(flags::IC_PVTIME, 1)]);
    assert_eq!(calculate(ire, [4e-3, 0.0, 0.0]), 0);
    mode(false);
    unsafe { cntc_finalize(&ire) };
}

#[test]
fn elements_on_several_threads_forward_at_once() {
    let _turn = turn();
    mode(false);
    let expected: Vec<Vec<u64>> = (0..4)
        .map(|t| {
            let ire = 31 + t;
            tractcurv(ire, 3, 2);
            assert_eq!(calculate(ire, [2e-4 * (t + 1) as f64, 0.0, 0.0]), 0);
            let v = patch_values(ire);
            unsafe { cntc_finalize(&ire) };
            v
        })
        .collect();
    mode(true);
    let got: Vec<Vec<u64>> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..4)
            .map(|t| {
                s.spawn(move || {
                    let ire = 41 + t;
                    tractcurv(ire, 3, 2);
                    assert_eq!(calculate(ire, [2e-4 * (t + 1) as f64, 0.0, 0.0]), 0);
                    let v = patch_values(ire);
                    unsafe { cntc_finalize(&ire) };
                    v
                })
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    mode(false);
    assert_eq!(got, expected);
}

/// A variable rail (a rail slices file, the UK crossing nose): the call
/// carries the slices' profile files, which the server reads from it (it
/// never opens the caller's files), and both modes give the same bits.
#[test]
fn a_rail_slices_file_reaches_the_server_with_its_profiles() {
    let _turn = turn();
    let rail = profile("uk_crossing_nose.slcs");
    both_modes(7, |ire| {
        let ierror =
            unsafe { mbench_locus(ire, &rail, 1000.0, (239.0, 0.81, 0.0), Load::Force(1e4)) };
        assert_eq!(ierror, 0);
        vec![wheel_results(ire)]
    });
}
