//! What the library's tests share: the shared library's folder, scratch
//! folders, compilers, building and running a C or Fortran program against
//! the library, and a railcontact server in the test process for the
//! forwarding mode, and the calls of a module 3 patch as a C caller makes
//! them.
#![allow(dead_code)]

use std::net::SocketAddr;
use std::path::{Path, PathBuf};
use std::process::Command;

use contact_addon::ffi::*;
use contact_addon::flags;
use railcontact::service::config::ServeConfig;
use railcontact::service::server::{start, RunningServer};
use railcontact_testkit::{apt_install, check, skip_client_test};

/// The package's folder.
pub fn package() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The folder of the shared library `libcontact_addon.so` cargo built for
/// these tests (beside the test executable).
pub fn library_dir() -> PathBuf {
    let exe = std::env::current_exe().unwrap();
    let dir = exe.parent().unwrap().to_path_buf();
    assert!(
        dir.join("libcontact_addon.so").exists(),
        "no libcontact_addon.so in {}",
        dir.display()
    );
    dir
}

/// The folder for a test's build products, under cargo's target folder
/// (`CARGO_TARGET_TMPDIR`), so that runs leave nothing in the system's
/// temporary folder; a name is one test's, and its files are rewritten.
pub fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("cntc-{name}"));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Makes sure the program `tool` exists, installing Debian `package` when
/// it does not; false when the client tests are to be skipped.
pub fn tool(tool: &str, package: &str, what: &str) -> bool {
    if Command::new(tool).arg("--version").output().is_ok() {
        return true;
    }
    if skip_client_test(what) {
        return false;
    }
    apt_install(&[package], what, &format!("{tool} builds the example"));
    true
}

/// Links `source` (C or Fortran) with `compiler` against the library;
/// the program.
pub fn build(compiler: &str, source: &Path, name: &str) -> PathBuf {
    let lib = library_dir();
    let dir = scratch(name);
    let exe = dir.join(name);
    let mut cc = Command::new(compiler);
    cc.arg(source)
        .arg("-I")
        .arg(package().join("include"))
        .arg("-o")
        .arg(&exe)
        .arg("-L")
        .arg(&lib)
        .arg("-lcontact_addon")
        .arg(format!("-Wl,-rpath,{}", lib.display()))
        .current_dir(&dir);
    if compiler == "cc" {
        cc.args(["-Wall", "-Werror"]);
    }
    check(
        &format!("{compiler} {}", source.display()),
        &cc.output().unwrap(),
    );
    exe
}

/// Runs program `exe` with `args` and the environment `env`; its
/// standard output.
pub fn run(exe: &Path, args: &[&Path], env: &[(&str, &str)]) -> String {
    let out = Command::new(exe)
        .args(args)
        .envs(env.iter().copied())
        .current_dir(exe.parent().unwrap())
        .output()
        .unwrap();
    check(&format!("running {}", exe.display()), &out);
    String::from_utf8(out.stdout).unwrap()
}

/// [`build`] and [`run`] in process mode.
pub fn build_and_run(compiler: &str, source: &Path, name: &str, args: &[&Path]) -> String {
    let exe = build(compiler, source, name);
    let out = run(&exe, args, &[]);
    let _ = std::fs::remove_dir_all(exe.parent().unwrap());
    out
}

/// A railcontact server (the service of this repository) running in the
/// test process on a loopback port, memory-only, for the library's
/// forwarding mode.
pub struct TestServer {
    /// HOST:PORT it listens on.
    pub addr: SocketAddr,
    server: Option<RunningServer>,
    rt: tokio::runtime::Runtime,
}

impl TestServer {
    /// A server on `listen` (`127.0.0.1:0`: any free port).
    pub fn start(listen: &str) -> TestServer {
        TestServer::start_with(listen, |_| {})
    }

    /// [`TestServer::start`] with the settings `edit` changes.
    pub fn start_with(listen: &str, edit: impl FnOnce(&mut ServeConfig)) -> TestServer {
        let rt = tokio::runtime::Builder::new_multi_thread()
            .worker_threads(2)
            .enable_all()
            .build()
            .unwrap();
        let mut config = ServeConfig {
            listen: listen.parse().unwrap(),
            data_dir: Default::default(),
            shutdown_grace_s: 1.0,
            ..ServeConfig::default()
        };
        edit(&mut config);
        let server = rt.block_on(start(&config)).expect("the server starts");
        TestServer {
            addr: server.addr,
            server: Some(server),
            rt,
        }
    }

    /// Stops the server at once, dropping its streams (as a killed one).
    pub fn kill(mut self) {
        if let Some(s) = self.server.take() {
            self.rt.block_on(s.shutdown_or(async {}));
        }
    }
}

// ---------------------------------------------------------------------
// Module 1: profiles and comparisons.

/// A profile file of the repository's test data (`crates/solver/profiles`:
/// CONTACT's test bank, with its licence and source).
pub fn profile(name: &str) -> String {
    format!("{}/../solver/profiles/{name}", env!("CARGO_MANIFEST_DIR"))
}

/// Configures result element `ire` as `python_mbench.py` does for its
/// wheel `iwhe`: 1 the left wheel on the Simpack rail, 2 the right wheel on
/// the MiniProf rail (mirrored in y: MiniProf measures from the gauge
/// side), with the N digit `norm` (N = 1: FZ = 10 kN) and the F digit
/// `force`.
pub unsafe fn mbench_wheel(ire: i32, iwhe: i32, norm: i32, force: i32) {
    let (rail, mirror) = if iwhe == 1 {
        (profile("MBench_UIC60_v3.prr"), 0)
    } else {
        (profile("MBench_UIC60_v3.ban"), 1)
    };
    wheelrail_element(
        ire,
        &[
            (flags::IC_CONFIG, iwhe - 1),
            (flags::IC_TANG, 3),
            (flags::IC_PVTIME, 2),
            (flags::IC_NORM, norm),
            (flags::IC_FORCE, force),
            (flags::IC_DISCNS, 2),
        ],
    );
    let icp = -1;
    let mat = [0.28, 0.28, 82000.0, 82000.0];
    cntc_setmaterialparameters(&ire, &icp, &0, &4, mat.as_ptr());
    cntc_setfrictionmethod(&ire, &icp, &0, &2, [0.3, 0.3].as_ptr());
    if norm == 1 {
        // (cntc_setverticalforce sets N = 1.)
        cntc_setverticalforce(&ire, &10000.0);
    }
    let pot = [0.2, 0.2, std::f64::consts::FRAC_PI_2, 8.0, 4.0];
    cntc_setpotcontact(&ire, &icp, &-1, &5, pot.as_ptr());
    let track = [14.0, 0.0, 1435.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
    cntc_settrackdimensions(&ire, &3, &11, track.as_ptr());
    set_profile_file(ire, &rail, mirror);
    cntc_setwheelsetdimensions(&ire, &3, &3, [1360.0, -70.0, 460.0].as_ptr());
    set_profile_file(ire, &profile("MBench_S1002_v3.prw"), 0);
}

/// `cntc_setprofileinputfname` of the file `path` on element `ire`: the
/// type from its extension (ITYPE = -1), mirrored in y with `mirror_y` = 1,
/// scale factor 1, no smoothing.
pub fn set_profile_file(ire: i32, path: &str, mirror_y: i32) {
    set_profile_file_with(ire, path, &[-1, 0, mirror_y], &[1.0, 0.0]);
}

/// `cntc_setprofileinputfname` of the file `path` on element `ire` with
/// `iparam` and `rparam`.
pub fn set_profile_file_with(ire: i32, path: &str, iparam: &[i32], rparam: &[f64]) {
    unsafe {
        cntc_setprofileinputfname(
            &ire,
            path.as_ptr() as *const std::ffi::c_char,
            &(path.len() as i32),
            &(iparam.len() as i32),
            iparam.as_ptr(),
            &(rparam.len() as i32),
            rparam.as_ptr(),
        )
    }
}

/// Initializes `ire` as a module 1 (wheel/rail) element in CONTACT's
/// units with `flags` (code, value) on all its patches.
pub unsafe fn wheelrail_element(ire: i32, flags: &[(i32, i32)]) {
    let (mut ifcver, mut ierror) = (0, 0);
    cntc_initialize(
        &ire,
        &1,
        &mut ifcver,
        &mut ierror,
        std::ptr::null(),
        std::ptr::null(),
    );
    assert_eq!(ierror, 0);
    let mut all = vec![(flags::IF_UNITS, flags::UN_CNTC)];
    all.extend_from_slice(flags);
    set_flags(ire, -1, &all);
}

/// Asserts |ours - contact| <= tol, naming `what`.
pub fn close(what: &str, ours: f64, contact: f64, tol: f64) {
    assert!(
        (ours - contact).abs() <= tol,
        "{what}: ours {ours}, CONTACT's {contact} (tolerance {tol})"
    );
}

// ---------------------------------------------------------------------
// Calls on module 3 patches, as a C caller makes them.

/// Forwarding on (1) or off (0).
pub fn mode(on: bool) {
    let (codes, values) = ([flags::IF_MODE], [on as i32]);
    unsafe { cntc_setglobalflags(&1, codes.as_ptr(), values.as_ptr()) };
}

pub fn set_flags(ire: i32, icp: i32, pairs: &[(i32, i32)]) {
    let codes: Vec<i32> = pairs.iter().map(|p| p.0).collect();
    let values: Vec<i32> = pairs.iter().map(|p| p.1).collect();
    let n = pairs.len() as i32;
    unsafe { cntc_setflags(&ire, &icp, &n, codes.as_ptr(), values.as_ptr()) };
}

/// Module 3 on (ire, 1): CONTACT's tractcurv ellipse (a/b = 0.5, 48 x 44
/// elements, 106.7 kN, mu 0.33, CONTACT's units) with the T digit `tang`
/// and the P digit `pvtime`.
pub fn tractcurv(ire: i32, tang: i32, pvtime: i32) {
    let icp = 1;
    set_flags(
        ire,
        icp,
        &[
            (flags::IF_UNITS, flags::UN_CNTC),
            (flags::IC_TANG, tang),
            (flags::IC_NORM, 1),
            (flags::IC_PVTIME, pvtime),
        ],
    );
    unsafe {
        let mat = [0.28, 0.28, 82000.0, 82000.0];
        cntc_setmaterialparameters(&ire, &icp, &0, &4, mat.as_ptr());
        cntc_setfrictionmethod(&ire, &icp, &0, &2, [0.33, 0.33].as_ptr());
        let hz = [48.0, 44.0, 0.0008, 0.5, 1.1];
        cntc_sethertzcontact(&ire, &icp, &-2, &5, hz.as_ptr());
        cntc_setreferencevelocity(&ire, &icp, &10000.0);
        cntc_setnormalforce(&ire, &icp, &106700.0);
    }
}

/// Calculates (ire, 1) at creepages `c`: ierror.
pub fn calculate(ire: i32, c: [f64; 3]) -> i32 {
    let (icp, mut ierror) = (1, 12345);
    unsafe {
        cntc_setcreepages(&ire, &icp, &c[0], &c[1], &c[2]);
        cntc_calculate(&ire, &icp, &mut ierror);
    }
    ierror
}

/// A patch's totals as its getters give them (CONTACT's units).
pub struct PatchTotals {
    /// FN, FX, FS \[N\], MZ \[N mm\] (`cntc_getcontactforces`).
    pub forces: [f64; 4],
    /// PMAX \[N/mm2\] (`cntc_getmaximumpressure`).
    pub pmax: f64,
    /// The areas of contact, adhesion and slip \[mm2\]
    /// (`cntc_getcontactpatchareas`).
    pub areas: [f64; 3],
}

/// The totals of patch `icp` of element `ire`.
pub unsafe fn patch_totals(ire: i32, icp: i32) -> PatchTotals {
    let [mut fn_, mut fx, mut fs, mut mz] = [0.0; 4];
    cntc_getcontactforces(&ire, &icp, &mut fn_, &mut fx, &mut fs, &mut mz);
    let mut pmax = 0.0;
    cntc_getmaximumpressure(&ire, &icp, &mut pmax);
    let [mut carea, mut harea, mut sarea] = [0.0; 3];
    cntc_getcontactpatchareas(&ire, &icp, &mut carea, &mut harea, &mut sarea);
    PatchTotals {
        forces: [fn_, fx, fs, mz],
        pmax,
        areas: [carea, harea, sarea],
    }
}

/// Every value the getters of module 3 patch (ire, 1) give (the
/// displacement differences too), as bits.
pub fn patch_values(ire: i32) -> Vec<u64> {
    let icp = 1;
    let mut v = Vec::new();
    unsafe {
        let (mut fn_, mut fx, mut fy, mut mz) = (0.0, 0.0, 0.0, 0.0);
        cntc_getcontactforces(&ire, &icp, &mut fn_, &mut fx, &mut fy, &mut mz);
        let (mut cx, mut cy, mut cp) = (0.0, 0.0, 0.0);
        cntc_getcreepages(&ire, &icp, &mut cx, &mut cy, &mut cp);
        let mut pen = 0.0;
        cntc_getpenetration(&ire, &icp, &mut pen);
        let (mut ca, mut ha, mut sa) = (0.0, 0.0, 0.0);
        cntc_getcontactpatchareas(&ire, &icp, &mut ca, &mut ha, &mut sa);
        let (mut pm, mut tm) = (0.0, 0.0);
        cntc_getmaximumpressure(&ire, &icp, &mut pm);
        cntc_getmaximumtraction(&ire, &icp, &mut tm);
        v.extend([fn_, fx, fy, mz, cx, cy, cp, pen, ca, ha, sa, pm, tm].map(f64::to_bits));
        let (mut mx, mut my) = (0, 0);
        cntc_getnumelements(&ire, &icp, &mut mx, &mut my);
        let n = mx * my;
        assert!(n > 0, "no grid on element {ire}");
        let mut arrays = vec![vec![0.0; n as usize]; 8];
        let [pn, px, py, sx, sy, un, ux, uy] = &mut arrays[..] else {
            unreachable!()
        };
        cntc_gettractions(
            &ire,
            &icp,
            &n,
            pn.as_mut_ptr(),
            px.as_mut_ptr(),
            py.as_mut_ptr(),
        );
        cntc_getmicroslip(&ire, &icp, &n, sx.as_mut_ptr(), sy.as_mut_ptr());
        cntc_getdisplacements(
            &ire,
            &icp,
            &n,
            un.as_mut_ptr(),
            ux.as_mut_ptr(),
            uy.as_mut_ptr(),
        );
        for a in &arrays {
            v.extend(a.iter().map(|x| x.to_bits()));
        }
        let mut division = vec![0; n as usize];
        cntc_getelementdivision(&ire, &icp, &n, division.as_mut_ptr());
        v.extend(division.iter().map(|d| *d as u64));
    }
    v
}

/// The Manchester benchmark's right wheel at lateral shift `y` [mm] on
/// element `ire` (module 1, CONTACT's units, the MiniProf rail), at
/// CONTACT's pitch rate for the benchmark or (F = 1) at the pitch rate
/// found for the total force `fx_ws` [N]: [`wheel_results`].
pub fn mbench_right_wheel(ire: i32, y: f64, fx_ws: Option<f64>) -> (i32, Vec<u64>) {
    mbench_right_wheel_with(ire, y, fx_ws, 3, None)
}

/// [`mbench_right_wheel`] with the T digit `tang` and, with `Some`, the M
/// digit and its material parameters after [nu1, nu2, G1, G2] (M = 3:
/// k0, alpha_inf, beta; M = 4: G3, LAYTHK, TAU_C0, K_TAU).
pub fn mbench_right_wheel_with(
    ire: i32,
    y: f64,
    fx_ws: Option<f64>,
    tang: i32,
    material: Option<(i32, &[f64])>,
) -> (i32, Vec<u64>) {
    let icp = -1;
    let profiles = package().join("../solver/profiles");
    set_flags(
        ire,
        icp,
        &[
            (flags::IF_UNITS, flags::UN_CNTC),
            (flags::IC_CONFIG, 1),
            (flags::IC_TANG, tang),
            (flags::IC_PVTIME, 2),
            (flags::IC_NORM, 1),
            (flags::IC_DISCNS, 2),
            (flags::IC_FORCE, fx_ws.is_some() as i32),
        ],
    );
    unsafe {
        let (m, extra) = material.unwrap_or((0, &[]));
        let mat: Vec<f64> = [0.28, 0.28, 82000.0, 82000.0]
            .into_iter()
            .chain(extra.iter().copied())
            .collect();
        cntc_setmaterialparameters(&ire, &icp, &m, &(mat.len() as i32), mat.as_ptr());
        cntc_setfrictionmethod(&ire, &icp, &0, &2, [0.3, 0.3].as_ptr());
        cntc_setverticalforce(&ire, &10000.0);
        let pot = [0.2, 0.2, std::f64::consts::FRAC_PI_2, 8.0, 4.0];
        cntc_setpotcontact(&ire, &icp, &-1, &5, pot.as_ptr());
        let track = [14.0, 0.0, 1435.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
        cntc_settrackdimensions(&ire, &3, &11, track.as_ptr());
        for (name, mirror) in [("MBench_UIC60_v3.ban", 1), ("MBench_S1002_v3.prw", 0)] {
            let path = profiles.join(name).display().to_string();
            let len = path.len() as i32;
            let iparam = [-1, 0, mirror];
            cntc_setprofileinputfname(
                &ire,
                path.as_ptr().cast(),
                &len,
                &3,
                iparam.as_ptr(),
                &2,
                [1.0, 0.0].as_ptr(),
            );
        }
        cntc_setwheelsetdimensions(&ire, &3, &3, [1360.0, -70.0, 460.0].as_ptr());
        cntc_setwheelsetflexibility(&ire, &1, &12, [0.0; 12].as_ptr());
        let pos = [0.0, y, 0.0, -0.007642, 0.018, 0.0];
        cntc_setwheelsetposition(&ire, &2, &6, pos.as_ptr());
        let vel = [2000.0, 0.0, 0.0, 0.0, 0.0, -4.2575747];
        cntc_setwheelsetvelocity(&ire, &2, &6, vel.as_ptr());
        if let Some(fx) = fx_ws {
            cntc_settangentialforces(&ire, &-1, &fx, &0.0);
        }
    }
    wheel_results(ire)
}

/// Calculates wheel/rail element `ire` (at least one patch): ierror, and
/// its 24 global forces, number of patches, every patch's location,
/// contact forces and creepages, and the wheelset's velocity (last), as
/// bits.
pub fn wheel_results(ire: i32) -> (i32, Vec<u64>) {
    let mut ierror = 12345;
    let mut v = Vec::new();
    unsafe {
        cntc_calculate1(&ire, &mut ierror);
        let mut npatch = 0;
        cntc_getnumcontactpatches(&ire, &mut npatch);
        assert!(npatch >= 1, "ierror {ierror}: no patch on element {ire}");
        let mut g = [0.0; 24];
        cntc_getglobalforces(&ire, &-1, &24, g.as_mut_ptr());
        v.extend(g.map(f64::to_bits));
        v.push(npatch as u64);
        for p in 1..=npatch {
            let mut loc = [0.0; 38];
            cntc_getcontactlocation(&ire, &p, &38, loc.as_mut_ptr());
            v.extend(loc.map(f64::to_bits));
            let mut f = [0.0; 7];
            let [fn_, fx, fs, mz, cksi, ceta, cphi] = &mut f;
            cntc_getcontactforces(&ire, &p, fn_, fx, fs, mz);
            cntc_getcreepages(&ire, &p, cksi, ceta, cphi);
            v.extend(f.map(f64::to_bits));
        }
        let mut vel = [0.0; 6];
        cntc_getwheelsetvelocity(&ire, &6, vel.as_mut_ptr());
        v.extend(vel.map(f64::to_bits));
    }
    (ierror, v)
}

/// CONTACT's module 1 input file of the Manchester benchmark's right wheel
/// (A-2.2, the first case of CONTACT's `examples/mbench_a22_right.inp`, at
/// its case 7: 3 mm lateral shift, 7.2 mrad yaw), its profiles named
/// relative to the file's folder, and a second case that is not read.
pub const MBENCH_RIGHT_INP: &str = "\
% Manchester benchmark A-2.2, right wheel, y = 3 mm, yaw 7.2 mrad.

  1 MODULE
 1203100    C-P-B-T-N-F-S   CONFIG, PVTIME, BOUND,  TANG,   NORM,   FORCE,  STRESS
 0022033    V-L-D-C-M-Z-E   VARFRC, FRCLAW, DISCNS, INFLCF, MATER,  ZTRACK, EWHEEL
 0000321    H-G-I-A-O-W-R     HEAT, GAUSEI, IESTIM, MATFIL, OUTPUT, FLOW,   RETURN
    999     100    30    1     1d-5         MAXGS , MAXIN , MAXNR , MAXOUT, EPS
  0.300   0.300                                 FSTAT, FKIN
  0.280,  0.280,  82000., 82000.                POISS 1,2,  GG 1,2
  0.200   0.200   1.000   90d   8.0   4.0       DX, DS, DQREL, A_SEP, D_SEP, D_COMB
   14.0     0    1435.0   0.000                 GAUGHT, GAUGSQ, GAUGWD, CANT
  'MBench_UIC60_v3.prr'   0     1.0   0.0       RFNAME, MIRRORY, SCALE, SMOOTH
     0.0    0.0   0.000   0.0   0.0   0.000     DY, DZ, ROLL, VY, VZ, VROLL
  1360.0  -70.0   460.0                         FBDIST, FBPOS, NOMRAD
  'MBench_S1002_v3.prw'   0     1.0   0.0       WFNAME, MIRRORY, SCALE, SMOOTH
  0.0  3.0  10000. -0.00018030 0.0072  0.0      S, Y, FZ, ROLL, YAW, PITCH
 2000. 0.0    0.0   0.0        0.0  -4.34515030 VS,VY,VZ, VROLL,VYAW,VPITCH

% The next case is not read.
  1 MODULE
 1203100    C-P-B-T-N-F-S
";

/// The lines of a module 1 input file from DX to the wheel profile that
/// the Manchester benchmark's right wheel files share (0.2 mm elements,
/// gauge-point placement of UIC60 and S1002, the files' names relative to
/// [`InpDir`]).
pub const MBENCH_M1_GEOMETRY: &str = "\
\x20 0.200   0.200   1.000   90d   8.0   4.0       DX, DS, DQREL, A_SEP, D_SEP, D_COMB
\x20  14.0     0    1435.0   0.000                 GAUGHT, GAUGSQ, GAUGWD, CANT
\x20 'MBench_UIC60_v3.prr'   0     1.0   0.0       RFNAME, MIRRORY, SCALE, SMOOTH
\x20    0.0    0.0   0.000   0.0   0.0   0.000     DY, DZ, ROLL, VY, VZ, VROLL
\x20 1360.0  -70.0   460.0                         FBDIST, FBPOS, NOMRAD
\x20 'MBench_S1002_v3.prw'   0     1.0   0.0       WFNAME, MIRRORY, SCALE, SMOOTH
";

/// A scratch folder holding the benchmark's rail and wheel profiles, for
/// input files that name them relative to their own folder; removed when
/// dropped.
pub struct InpDir(pub PathBuf);

impl InpDir {
    /// A fresh folder `tag` with the profiles.
    pub fn new(tag: &str) -> InpDir {
        let dir = scratch(&format!("inp-{tag}"));
        for name in ["MBench_UIC60_v3.prr", "MBench_S1002_v3.prw"] {
            std::fs::copy(
                package().join("../solver/profiles").join(name),
                dir.join(name),
            )
            .unwrap();
        }
        InpDir(dir)
    }

    /// Writes input file `name` with `text`; its path.
    pub fn write(&self, name: &str, text: &str) -> PathBuf {
        let path = self.0.join(name);
        std::fs::write(&path, text).unwrap();
        path
    }
}

impl Drop for InpDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// `cntc_readinpfile(ire, inp_type, path)`: ierror.
pub fn read_inp(ire: i32, inp_type: i32, path: &Path) -> i32 {
    let name = path.display().to_string();
    let mut ierror = 12345;
    unsafe {
        cntc_readinpfile(
            &ire,
            &inp_type,
            name.as_ptr().cast(),
            &(name.len() as i32),
            &mut ierror,
        )
    };
    ierror
}

// ---------------------------------------------------------------------
// A wheel on a rail as CONTACT's mbench_locus.inp sets it up.

/// The wheel's load: a vertical force FZ [N] (N = 1) or the wheelset's
/// height Z_WS [mm] (N = 0).
#[derive(Clone, Copy)]
pub enum Load {
    /// FZ \[N\].
    Force(f64),
    /// Z_WS \[mm\].
    Height(f64),
}

/// Writes a slices file `name` in `dir` (`key` "U" for a rail's, "TH"
/// for a wheel's; offset 0, scale 1, method `intpol`) with a slice at each
/// position of `slices` naming its profile file (relative to `dir`);
/// returns its path.
pub fn write_slices_file(
    dir: &Path,
    name: &str,
    key: &str,
    intpol: i32,
    slices: &[(f64, &str)],
) -> String {
    let mut text = format!("% test slices\n   0.0   1.0   {key}_OFFSET, {key}_SCALE\n");
    text += &format!(
        "  {}   NSLC\n  0 0 0   NFEAT, NKINK, NACCEL\n  {intpol}   {key}_INTPOL\n",
        slices.len()
    );
    for (u, f) in slices {
        text += &format!("  {u}  '{f}'\n");
    }
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path.display().to_string()
}

/// A module 1 element `ire` as CONTACT's examples set it (mbench_locus.inp,
/// wheelflat.inp): the right wheel (C1 = 1), steady rolling (T = 3),
/// the grid by DX and DS (D = 2), a vertical force (N = 1, `force`) or
/// height; CONTACT's solver settings (999, 100, 30, 1; 1e-5), steel
/// (0.28, 82 GPa) and Coulomb friction 0.3.
pub unsafe fn rolling_right_wheel(ire: i32, force: bool) {
    wheelrail_element(
        ire,
        &[
            (flags::IC_CONFIG, 1),
            (flags::IC_TANG, 3),
            (flags::IC_PVTIME, 2),
            (flags::IC_NORM, force as i32),
            (flags::IC_DISCNS, 2),
        ],
    );
    let icp = -1;
    let ints = [999, 100, 30, 1];
    cntc_setsolverflags(&ire, &icp, &0, &4, ints.as_ptr(), &1, [1e-5].as_ptr());
    let mat = [0.28, 0.28, 82000.0, 82000.0];
    cntc_setmaterialparameters(&ire, &icp, &0, &4, mat.as_ptr());
    cntc_setfrictionmethod(&ire, &icp, &0, &2, [0.3, 0.3].as_ptr());
}

/// CONTACT's `mbench_locus.inp` setup on element `ire` (right wheel,
/// steady rolling, the S1002 wheel, the rail placed absolutely at RAILY0 =
/// 750 mm; its load FZ = 10 kN), the rail from `rail` (SCALE_YZ `scale`),
/// the wheelset at S, Y [mm] and yaw [rad] with `load`; calculated:
/// ierror.
pub unsafe fn mbench_locus(
    ire: i32,
    rail: &str,
    scale: f64,
    (s_mm, y_mm, yaw): (f64, f64, f64),
    load: Load,
) -> i32 {
    rolling_right_wheel(ire, matches!(load, Load::Force(_)));
    let icp = -1;
    let z_ws = match load {
        Load::Force(fz) => {
            cntc_setverticalforce(&ire, &fz);
            0.0
        }
        Load::Height(z) => z,
    };
    let pot = [0.2, 0.2, std::f64::consts::FRAC_PI_2, 8.0, 4.0];
    cntc_setpotcontact(&ire, &icp, &-1, &5, pot.as_ptr());
    let track = [-1.0, 750.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
    cntc_settrackdimensions(&ire, &3, &11, track.as_ptr());
    set_profile(ire, rail, 0, scale);
    cntc_setwheelsetdimensions(&ire, &3, &3, [1360.0, -70.0, 460.0].as_ptr());
    set_profile(ire, &profile("MBench_S1002_v3.prw"), 1, 1.0);
    let pos = [s_mm, y_mm, z_ws, 0.0, yaw, 0.0];
    cntc_setwheelsetposition(&ire, &3, &6, pos.as_ptr());
    let vel = [2000.0, 0.0, 0.0, 0.0, 0.0, -4.34811810];
    cntc_setwheelsetvelocity(&ire, &3, &6, vel.as_ptr());
    let mut ierror = -1;
    cntc_calculate1(&ire, &mut ierror);
    ierror
}

/// `cntc_setprofileinputfname` with ITYPE `itype`, MIRRORZ = -1 (z as
/// given), SCALE_YZ `scale`, no smoothing (as `mbench_locus.inp`).
fn set_profile(ire: i32, path: &str, itype: i32, scale: f64) {
    set_profile_file_with(ire, path, &[itype, 0, 0, -1], &[scale, 0.0]);
}
