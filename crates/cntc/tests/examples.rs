//! The library as its users call it: the example programs in C, Fortran
//! (ISO_C_BINDING) and Python (ctypes) built and run against the shared
//! library this package builds, their results checked against CONTACT's
//! own library, and every exported symbol linked from C. The C examples
//! and the Python one also run forwarded to a railcontact server in the
//! test process (`RAILCONTACT_CNTC_SERVER`) and print the same digits.
//!
//! gcc, gfortran and python3 are needed; missing compilers are installed
//! with apt-get (as root or through `sudo -n`, said on stderr first), or
//! the test is skipped with a `skipped:` line when
//! `RAILCONTACT_SKIP_CLIENT_TESTS` is set.

mod common;

use std::path::Path;
use std::process::Command;
use std::sync::OnceLock;

use common::{build, build_and_run, library_dir, package, run, scratch, tool, TestServer};
use railcontact_testkit::check;

/// The server the forwarded runs use (one per test binary).
fn server() -> &'static TestServer {
    static SERVER: OnceLock<TestServer> = OnceLock::new();
    SERVER.get_or_init(|| TestServer::start("127.0.0.1:0"))
}

/// Runs program `exe` with `args` in process and forwarded to
/// [`server`]: the output of both, which must be the same to the last
/// digit printed (the calculations are the same bit for bit).
fn both_modes(exe: &Path, args: &[&Path]) -> String {
    let local = run(exe, args, &[]);
    let target = server().addr.to_string();
    let forwarded = run(exe, args, &[("RAILCONTACT_CNTC_SERVER", target.as_str())]);
    assert_eq!(
        forwarded, local,
        "forwarded to {target}:\n{forwarded}\nin process:\n{local}"
    );
    local
}

/// One result line of the module 3 examples: tag, ierror, FN, FX, FY, MZ,
/// PEN (or a tag and one value).
fn parse(output: &str) -> Vec<(String, Vec<f64>)> {
    output
        .lines()
        .filter(|l| !l.starts_with("ifcver"))
        .map(|l| {
            let mut w = l.split_whitespace();
            let tag = w.next().unwrap().to_string();
            let v = w
                .map(|x| x.parse::<f64>().unwrap_or_else(|_| panic!("{l}")))
                .collect();
            (tag, v)
        })
        .collect()
}

/// CONTACT's own library (eve70a/CONTACT at d431cdb, its open-source
/// `contact_addon_linux64.so` built with gfortran 12.2 -O2 and FFTW 3.3.10)
/// running `examples/c/module3.c` unchanged, 2026-12-06: tag, ierror, FN
/// \[N\], FX \[N\], FY \[N\], MZ \[N mm; N m in SI\], PEN \[mm; m in SI\].
/// `force_cksi` is the creepage CONTACT found for the prescribed force.
const CONTACT_MODULE3: &str = "\
curve0 0 1.067000000e+05 -9.111544156e+03 -4.319809310e-05 0.000000000e+00 7.650771289e-02
curve1 0 1.067000000e+05 -3.333278060e+04 -1.693321413e-05 0.000000000e+00 7.650771289e-02
curve2 0 1.067000000e+05 -3.520669461e+04 -1.744820932e-03 0.000000000e+00 7.650771289e-02
spin 0 5.000000000e+04 -8.030324289e+03 3.018181940e+03 2.039590466e+04 5.390874099e-02
force 0 8.000000000e+04 -9.600000000e+03 -2.786742088e+03 4.793575488e+03 6.657279862e-02
force_cksi 5.730207430e-04
shift0 0 3.000000000e+04 -4.381854427e+02 -2.735159434e-15 0.000000000e+00 4.273173408e-02
shift1 0 3.000000000e+04 -8.665786471e+02 3.505957682e-15 0.000000000e+00 4.273173408e-02
shift2 0 3.000000000e+04 9.792054566e+00 7.611899595e-15 0.000000000e+00 4.273173408e-02
grid_si 0 2.000000000e+04 -1.683278635e+02 -1.015683614e+02 1.741662404e-02 1.594513318e-04
simpack 0 5.000000000e+04 1.030799401e+04 -4.844437270e+03 5.011001511e+00 5.390874099e-05
";

/// Checks a module 3 example's output against [`CONTACT_MODULE3`]: the
/// same ierror; forces within 1e-4 of CONTACT's plus 1e-6 FN (the zero
/// components are rounding noise in both); moments within 1e-4 plus
/// 1e-6 FN x 1 mm; approaches within 1e-6; the force-controlled creepage
/// within 1e-5 (our force iteration stops at 1e-5 mu FN, CONTACT's at
/// its own tolerance).
fn matches_contact(output: &str) {
    let ours = parse(output);
    let theirs = parse(CONTACT_MODULE3);
    assert_eq!(
        ours.iter().map(|(t, _)| t).collect::<Vec<_>>(),
        theirs.iter().map(|(t, _)| t).collect::<Vec<_>>()
    );
    for ((tag, a), (_, b)) in ours.iter().zip(&theirs) {
        if tag == "force_cksi" {
            assert!(
                (a[0] / b[0] - 1.0).abs() < 1e-5,
                "{tag}: {} against CONTACT's {}",
                a[0],
                b[0]
            );
            continue;
        }
        assert_eq!(a[0], b[0], "{tag}: ierror");
        let fnn = b[1];
        // Moments are in N mm, or N m in SI (the last two cases).
        let mm = if tag == "grid_si" || tag == "simpack" {
            1e-3
        } else {
            1.0
        };
        let tol = [
            0.0,
            1e-4 * fnn,
            1e-6 * fnn,
            1e-6 * fnn,
            1e-6 * fnn * mm,
            0.0,
        ];
        for k in 1..=5 {
            let allowed = if k == 5 {
                1e-6 * b[k].abs()
            } else {
                1e-4 * b[k].abs() + tol[k]
            };
            assert!(
                (a[k] - b[k]).abs() <= allowed,
                "{tag}, value {k}: {} against CONTACT's {} (allowed {allowed:e})",
                a[k],
                b[k]
            );
        }
    }
}

#[test]
fn c_example_gives_contacts_results() {
    if !tool(
        "cc",
        "gcc",
        "the C example of the CONTACT-compatible library",
    ) {
        return;
    }
    let exe = build("cc", &package().join("examples/c/module3.c"), "module3_c");
    let out = both_modes(&exe, &[]);
    assert!(out.starts_with("ifcver 2520 ierror 0\n"), "{out}");
    matches_contact(&out);
}

#[test]
fn fortran_example_gives_the_c_examples_numbers() {
    if !tool(
        "gfortran",
        "gfortran",
        "the Fortran example of the CONTACT-compatible library",
    ) {
        return;
    }
    let f = build_and_run(
        "gfortran",
        &package().join("examples/fortran/module3.f90"),
        "module3_f",
        &[],
    );
    let c = build_and_run(
        "cc",
        &package().join("examples/c/module3.c"),
        "module3_cf",
        &[],
    );
    // The same calls from Fortran: the same numbers to the digits printed.
    assert_eq!(parse(&f), parse(&c), "Fortran:\n{f}\nC:\n{c}");
}

#[test]
fn python_example_gives_the_c_examples_numbers() {
    if !tool(
        "python3",
        "python3",
        "the Python example of the CONTACT-compatible library",
    ) {
        return;
    }
    let lib = library_dir().join("libcontact_addon.so");
    let python = |env: &[(&str, &str)]| {
        let out = Command::new("python3")
            .arg(package().join("examples/python/module3.py"))
            .arg(&lib)
            .envs(env.iter().copied())
            .output()
            .unwrap();
        check("python3 examples/python/module3.py", &out);
        String::from_utf8(out.stdout).unwrap()
    };
    let py = python(&[]);
    assert!(py.starts_with("ifcver 2520 ierror 0\n"), "{py}");
    matches_contact(&py);
    let target = server().addr.to_string();
    let forwarded = python(&[("RAILCONTACT_CNTC_SERVER", target.as_str())]);
    assert_eq!(forwarded, py, "forwarded to {target}");
}

/// CONTACT's own library (as [`CONTACT_MODULE3`]) running
/// `examples/c/module1.c` unchanged on the profiles of
/// `crates/solver/profiles`: side, ierror, patches, FX, FY, FZ on the rail
/// in track coordinates \[N\], the patch's FN, FX, FS \[N\] and contact
/// angle \[rad\] (python_mbench.py's cases 5 of the left and 16 of the
/// right wheel).
const CONTACT_MODULE1: &str = "\
left 0 1 5.462665949e+02 -3.095797536e+03 1.000000072e+04 1.004071512e+04 5.462665949e+02 -2.961083676e+03 1.344381436e-02
right 0 1 -2.085857027e+03 9.343542301e+03 9.999979346e+03 1.326322813e+04 -2.085857027e+03 -3.374633187e+03 -1.000624095e+00
";

/// Runs a module 1 example's program (C or Fortran) on the repository's
/// profiles.
fn module1_output(compiler: &str, source: &str, name: &str) -> String {
    let profiles = package().join("../solver/profiles");
    build_and_run(compiler, &package().join(source), name, &[&profiles])
}

/// The module 1 example from C against [`CONTACT_MODULE1`]: the same
/// ierror and number of patches, FZ within 1e-5, FN within 0.1 %, the
/// creep forces within 0.1 % of FN, the contact angle within 1e-4 rad
/// (measured: 0.005 % of FN, 0.007 % of FN and 2e-7 rad); and from
/// Fortran the C program's numbers.
#[test]
fn module1_examples_give_contacts_results() {
    if !tool(
        "cc",
        "gcc",
        "the C example of the CONTACT-compatible library",
    ) {
        return;
    }
    let profiles = package().join("../solver/profiles");
    let exe = build("cc", &package().join("examples/c/module1.c"), "module1_c");
    let c = both_modes(&exe, &[&profiles]);
    let ours = parse(&c);
    let theirs = parse(CONTACT_MODULE1);
    assert_eq!(ours.len(), 2, "{c}");
    for ((tag, a), (_, b)) in ours.iter().zip(&theirs) {
        assert_eq!(a[..2], b[..2], "{tag}: ierror, patches");
        let fnn = b[5];
        let within = |k: usize, tol: f64, what: &str| {
            assert!(
                (a[k] - b[k]).abs() <= tol,
                "{tag} {what}: {} against CONTACT's {} (allowed {tol})",
                a[k],
                b[k]
            )
        };
        within(4, 1e-5 * b[4].abs(), "FZ");
        within(5, 1e-3 * fnn, "FN");
        for (k, what) in [(2, "FX"), (3, "FY"), (6, "patch FX"), (7, "patch FS")] {
            within(k, 1e-3 * fnn, what);
        }
        within(8, 1e-4, "contact angle");
    }
    if tool(
        "gfortran",
        "gfortran",
        "the Fortran example of the CONTACT-compatible library",
    ) {
        let f = module1_output("gfortran", "examples/fortran/module1.f90", "module1_f");
        assert_eq!(parse(&f), ours, "Fortran:\n{f}\nC:\n{c}");
    }
}

/// Every function of CONTACT's library: the 66 its Python interface binds
/// and the 4 its library exports besides.
const SYMBOLS: [&str; 70] = [
    "cntc_initializefirst",
    "cntc_initializefirst_new",
    "cntc_initialize",
    "cntc_setfileunits",
    "cntc_getmaxnumthreads",
    "cntc_setglobalflags",
    "cntc_readinpfile",
    "cntc_setflags",
    "cntc_setmetadata",
    "cntc_setsolverflags",
    "cntc_setmaterialparameters",
    "cntc_settemperaturedata",
    "cntc_settimestep",
    "cntc_setreferencevelocity",
    "cntc_setrollingstepsize",
    "cntc_setfrictionmethod",
    "cntc_sethertzcontact",
    "cntc_setpotcontact",
    "cntc_setverticalforce",
    "cntc_setpenetration",
    "cntc_setnormalforce",
    "cntc_setundeformeddistc",
    "cntc_setcreepages",
    "cntc_setextrarigidslip",
    "cntc_settangentialforces",
    "cntc_setprofileinputfname",
    "cntc_setprofileinputvalues",
    "cntc_settrackdimensions",
    "cntc_setwheelsetdimensions",
    "cntc_setwheelsetposition",
    "cntc_setwheelsetvelocity",
    "cntc_setwheelsetflexibility",
    "subs_addblock",
    "cntc_calculate",
    "cntc_calculate1",
    "cntc_calculate3",
    "subs_calculate",
    "cntc_getflags",
    "cntc_getparameters",
    "cntc_getprofilevalues",
    "cntc_getprofilevalues_new",
    "cntc_getwheelsetposition",
    "cntc_getwheelsetvelocity",
    "cntc_getnumcontactpatches",
    "cntc_getcontactlocation",
    "cntc_getreferencevelocity",
    "cntc_gethertzcontact",
    "cntc_getnumelements",
    "cntc_getgriddiscretization",
    "cntc_getpotcontact",
    "cntc_getpenetration",
    "cntc_getcreepages",
    "cntc_getcontactforces",
    "cntc_getglobalforces",
    "cntc_getcontactpatchareas",
    "cntc_getelementdivision",
    "cntc_getmaximumpressure",
    "cntc_getmaximumtraction",
    "cntc_getmaximumtemperature",
    "cntc_getfielddata",
    "cntc_gettractions",
    "cntc_getmicroslip",
    "cntc_getdisplacements",
    "cntc_getsensitivities",
    "cntc_getcalculationtime",
    "cntc_resetcalculationtime",
    "subs_getblocksize",
    "subs_getresults",
    "cntc_finalize",
    "cntc_finalizelast",
];

/// A C program that takes the address of every function of the header:
/// it links only if the library exports all 70 under CONTACT's names, and
/// compiles only if the header declares them.
#[test]
fn every_function_links_from_c() {
    if !tool(
        "cc",
        "gcc",
        "the ABI check of the CONTACT-compatible library",
    ) {
        return;
    }
    let dir = scratch("symbols");
    let source = dir.join("symbols.c");
    let mut text = String::from(
        "#include <stdio.h>\n#include \"contact_addon.h\"\nint main(void) {\n   void *f[] = {\n",
    );
    for s in SYMBOLS {
        text.push_str(&format!("      (void *) {s},\n"));
    }
    text.push_str("   };\n   printf(\"%zu\\n\", sizeof f / sizeof f[0]);\n   return 0;\n}\n");
    std::fs::write(&source, text).unwrap();
    let out = build_and_run("cc", &source, "symbols", &[]);
    assert_eq!(out.trim(), "70");
}
