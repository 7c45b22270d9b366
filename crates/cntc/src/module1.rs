//! Module 1: wheel/rail contact of one wheel on its rail (CONTACT's C1
//! digit: 0 left, 1 right). Not in this build: every module 1 call answers
//! `CNTC_err_notsupported` naming itself.

use railcontact_solver::core::cache::KernelCache;

use crate::config::Config;
use crate::error::{CntcError, Result};
use crate::outcome::Outcome;

/// A module 1 result element.
#[derive(Default)]
pub struct WheelRail {
    /// Units, digits, materials, friction, solver parameters (for all its
    /// patches).
    pub config: Config,
    /// The patches of the last calculation (icp = 1..=npatch).
    pub outcomes: Vec<Outcome>,
    /// Cases calculated.
    pub ncase: usize,
    /// Wall time of the calculations since the last reset \[s\].
    pub time_s: f64,
}

fn todo(call: &str) -> CntcError {
    CntcError::NotSupported(format!("{call} (module 1) is not in this build"))
}

impl WheelRail {
    /// `cntc_setprofileinputfname`: a rail or wheel profile from a file.
    pub fn set_profile_file(
        &mut self,
        _fname: &str,
        _iparam: &[i32],
        _rparam: &[f64],
    ) -> Result<()> {
        Err(todo("cntc_setprofileinputfname"))
    }

    /// `cntc_setprofileinputvalues`: a profile from `npoint` (y, z) pairs.
    pub fn set_profile_values(
        &mut self,
        _npoint: usize,
        _values: &[f64],
        _iparam: &[i32],
        _rparam: &[f64],
    ) -> Result<()> {
        Err(todo("cntc_setprofileinputvalues"))
    }

    /// `cntc_settrackdimensions`.
    pub fn set_track_dimensions(&mut self, _ztrack: i32, _p: &[f64]) -> Result<()> {
        Err(todo("cntc_settrackdimensions"))
    }

    /// `cntc_setwheelsetdimensions`.
    pub fn set_wheelset_dimensions(&mut self, _ewheel: i32, _p: &[f64]) -> Result<()> {
        Err(todo("cntc_setwheelsetdimensions"))
    }

    /// `cntc_setwheelsetposition`.
    pub fn set_wheelset_position(&mut self, _ewheel: i32, _p: &[f64]) -> Result<()> {
        Err(todo("cntc_setwheelsetposition"))
    }

    /// `cntc_setwheelsetvelocity`.
    pub fn set_wheelset_velocity(&mut self, _ewheel: i32, _p: &[f64]) -> Result<()> {
        Err(todo("cntc_setwheelsetvelocity"))
    }

    /// `cntc_setwheelsetflexibility`.
    pub fn set_wheelset_flexibility(&mut self, _ewheel: i32, _p: &[f64]) -> Result<()> {
        Err(todo("cntc_setwheelsetflexibility"))
    }

    /// `cntc_setverticalforce` (also sets N = 1).
    pub fn set_vertical_force(&mut self, _fz: f64) -> Result<()> {
        Err(todo("cntc_setverticalforce"))
    }

    /// `cntc_setpotcontact` with icp = -1: DX, DS, A_SEP, D_SEP, D_COMB, ...
    pub fn set_discretisation(&mut self, _ipotcn: i32, _p: &[f64]) -> Result<()> {
        Err(todo("cntc_setpotcontact"))
    }

    /// `cntc_setrollingstepsize` with icp = -1: DQREL.
    pub fn set_rolling_step(&mut self, _chi: f64, _dqrel: f64) -> Result<()> {
        Err(todo("cntc_setrollingstepsize"))
    }

    /// `cntc_calculate` of the wheel.
    pub fn calculate(&mut self, _cache: &KernelCache) -> Result<i32> {
        Err(todo("cntc_calculate"))
    }

    /// `cntc_getgriddiscretization` with icp = -1: DX, DS.
    pub fn grid_size(&self) -> Result<[f64; 2]> {
        Err(todo("cntc_getgriddiscretization"))
    }

    /// `cntc_getwheelsetposition`.
    pub fn wheelset_position(&self) -> Result<[f64; 6]> {
        Err(todo("cntc_getwheelsetposition"))
    }

    /// `cntc_getwheelsetvelocity`.
    pub fn wheelset_velocity(&self) -> Result<[f64; 6]> {
        Err(todo("cntc_getwheelsetvelocity"))
    }

    /// `cntc_getglobalforces`.
    pub fn global_forces(&self, _icp: Option<usize>) -> Result<[f64; 24]> {
        Err(todo("cntc_getglobalforces"))
    }

    /// `subs_addblock` for patch `icp`.
    pub fn subs_add(
        &mut self,
        _icp: i32,
        _iblk: i32,
        _isubs: i32,
        _x: &[f64],
        _y: &[f64],
        _z: &[f64],
    ) -> Result<()> {
        Err(todo("subs_addblock"))
    }

    /// `subs_calculate` for patch `icp`.
    pub fn subs_calculate(&mut self, _icp: i32) -> Result<()> {
        Err(todo("subs_calculate"))
    }

    /// `subs_getblocksize` of block `iblk` of patch `icp`.
    pub fn subs_block_size(&self, _icp: i32, _iblk: i32) -> Result<[usize; 3]> {
        Err(todo("subs_getblocksize"))
    }

    /// `subs_getresults`: columns `icol` of block `iblk` of patch `icp`.
    pub fn subs_results(&self, _icp: i32, _iblk: i32, _icol: &[i32]) -> Result<Vec<f64>> {
        Err(todo("subs_getresults"))
    }

    /// `cntc_getprofilevalues`.
    pub fn profile_values(
        &self,
        _itask: i32,
        _iparam: &[i32],
        _rparam: &[f64],
    ) -> Result<Vec<f64>> {
        Err(todo("cntc_getprofilevalues"))
    }
}
