//! The calls that configure a result element, as values: what a setter was
//! given (CONTACT's units, as the caller passed them), applied to an
//! element by [`Call::apply`]. The library applies each call to its own
//! element; a library that forwards its calculations also keeps them in a
//! [`CallLog`] and sends them to the server, which applies the same calls
//! to its copy of the element with the same code, so that both copies are
//! equal and calculate the same numbers bit for bit.

use serde::{Deserialize, Serialize};

use crate::element::Element;
use crate::error::{CntcError, Result};
use crate::module1::SliceFile;

/// A configuring call on a result element, its arguments as given.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum Call {
    /// `cntc_setflags`, one flag (several flags are several calls).
    SetFlag {
        /// The flag's code (`CNTC_if_*`, `CNTC_ic_*`).
        code: i32,
        /// Its value.
        value: i32,
    },
    /// `cntc_setmetadata` (creates the patch; stores nothing).
    SetMetadata,
    /// `cntc_setsolverflags`.
    SetSolverFlags {
        /// The G digit.
        gdigit: i32,
        /// `iparam`.
        ints: Vec<i32>,
        /// `rparam`.
        reals: Vec<f64>,
    },
    /// `cntc_setmaterialparameters`.
    SetMaterial {
        /// The M digit.
        mdigit: i32,
        /// `rparam`.
        params: Vec<f64>,
    },
    /// `cntc_settemperaturedata`.
    SetTemperature {
        /// The H digit.
        imeth: i32,
        /// `params`.
        params: Vec<f64>,
    },
    /// `cntc_setfrictionmethod`.
    SetFriction {
        /// The V and L digits, `10 V + L`.
        imeth: i32,
        /// `params`.
        params: Vec<f64>,
    },
    /// `cntc_settimestep`.
    SetTimestep {
        /// DT.
        dt: f64,
    },
    /// `cntc_setreferencevelocity`.
    SetReferenceVelocity {
        /// VELOC.
        veloc: f64,
    },
    /// `cntc_setrollingstepsize`.
    SetRollingStep {
        /// CHI (`None`: a null pointer, which module 1 accepts).
        chi: Option<f64>,
        /// DQ (module 3) or DQREL (module 1).
        dq: f64,
    },
    /// `cntc_sethertzcontact`.
    SetHertz {
        /// IPOTCN.
        ipotcn: i32,
        /// `params`.
        params: Vec<f64>,
    },
    /// `cntc_setpotcontact`.
    SetPotcon {
        /// IPOTCN.
        ipotcn: i32,
        /// `params`.
        params: Vec<f64>,
    },
    /// `cntc_setverticalforce`.
    SetVerticalForce {
        /// FZ.
        fz: f64,
    },
    /// `cntc_setpenetration`.
    SetPenetration {
        /// PEN.
        pen: f64,
    },
    /// `cntc_setnormalforce`.
    SetNormalForce {
        /// FN.
        fn_: f64,
    },
    /// `cntc_setundeformeddistc`.
    SetUndeformedDistance {
        /// IBASE.
        ibase: i32,
        /// `prmudf`.
        params: Vec<f64>,
    },
    /// `cntc_setcreepages`.
    SetCreepages {
        /// CKSI.
        vx: f64,
        /// CETA.
        vy: f64,
        /// CPHI.
        phi: f64,
    },
    /// `cntc_setextrarigidslip`.
    SetExtraRigidSlip {
        /// WX per element.
        wx: Vec<f64>,
        /// WY per element.
        wy: Vec<f64>,
    },
    /// `cntc_settangentialforces`.
    SetTangentialForces {
        /// FX / (FSTAT FN).
        fx: f64,
        /// FY / (FSTAT FN).
        fy: f64,
    },
    /// `cntc_setprofileinputfname`, with the file's content as the caller
    /// read it (or why it could not be read), so that a server applies it
    /// without the caller's files.
    SetProfileFile {
        /// The file name as given.
        fname: String,
        /// The file's bytes, or the reason they could not be read.
        content: std::result::Result<Vec<u8>, String>,
        /// Of a rail slices file (`.slcs`): the profile files it names, by
        /// name as written, with their bytes or why they could not be read
        /// ([`crate::module1::read_slice_files`]); empty for other files.
        slice_files: Vec<SliceFile>,
        /// `iparam`.
        ints: Vec<i32>,
        /// `rparam`.
        reals: Vec<f64>,
    },
    /// `cntc_setprofileinputvalues`.
    SetProfileValues {
        /// NPOINT.
        npoint: usize,
        /// (y, z) per point.
        values: Vec<f64>,
        /// `iparam`.
        ints: Vec<i32>,
        /// `rparam`.
        reals: Vec<f64>,
    },
    /// `cntc_settrackdimensions`.
    SetTrackDimensions {
        /// ZTRACK.
        ztrack: i32,
        /// `params`.
        params: Vec<f64>,
    },
    /// `cntc_setwheelsetdimensions`.
    SetWheelsetDimensions {
        /// EWHEEL.
        ewheel: i32,
        /// `params`.
        params: Vec<f64>,
    },
    /// `cntc_setwheelsetposition`.
    SetWheelsetPosition {
        /// EWHEEL.
        ewheel: i32,
        /// `params`.
        params: Vec<f64>,
    },
    /// `cntc_setwheelsetvelocity`.
    SetWheelsetVelocity {
        /// EWHEEL.
        ewheel: i32,
        /// `params`.
        params: Vec<f64>,
    },
    /// `cntc_setwheelsetflexibility`.
    SetWheelsetFlexibility {
        /// EWHEEL.
        ewheel: i32,
        /// `params`.
        params: Vec<f64>,
    },
}

impl Call {
    /// The C function this call came from (for messages).
    pub fn name(&self) -> &'static str {
        match self {
            Call::SetFlag { .. } => "cntc_setflags",
            Call::SetMetadata => "cntc_setmetadata",
            Call::SetSolverFlags { .. } => "cntc_setsolverflags",
            Call::SetMaterial { .. } => "cntc_setmaterialparameters",
            Call::SetTemperature { .. } => "cntc_settemperaturedata",
            Call::SetFriction { .. } => "cntc_setfrictionmethod",
            Call::SetTimestep { .. } => "cntc_settimestep",
            Call::SetReferenceVelocity { .. } => "cntc_setreferencevelocity",
            Call::SetRollingStep { .. } => "cntc_setrollingstepsize",
            Call::SetHertz { .. } => "cntc_sethertzcontact",
            Call::SetPotcon { .. } => "cntc_setpotcontact",
            Call::SetVerticalForce { .. } => "cntc_setverticalforce",
            Call::SetPenetration { .. } => "cntc_setpenetration",
            Call::SetNormalForce { .. } => "cntc_setnormalforce",
            Call::SetUndeformedDistance { .. } => "cntc_setundeformeddistc",
            Call::SetCreepages { .. } => "cntc_setcreepages",
            Call::SetExtraRigidSlip { .. } => "cntc_setextrarigidslip",
            Call::SetTangentialForces { .. } => "cntc_settangentialforces",
            Call::SetProfileFile { .. } => "cntc_setprofileinputfname",
            Call::SetProfileValues { .. } => "cntc_setprofileinputvalues",
            Call::SetTrackDimensions { .. } => "cntc_settrackdimensions",
            Call::SetWheelsetDimensions { .. } => "cntc_setwheelsetdimensions",
            Call::SetWheelsetPosition { .. } => "cntc_setwheelsetposition",
            Call::SetWheelsetVelocity { .. } => "cntc_setwheelsetvelocity",
            Call::SetWheelsetFlexibility { .. } => "cntc_setwheelsetflexibility",
        }
    }

    /// Applies the call to patch `icp` of `e` (module 3) or to `e`
    /// (module 1). `Ok` holds the warnings the caller logs.
    pub fn apply(&self, e: &mut Element, icp: i32) -> Result<Vec<String>> {
        let module = e.module();
        match self {
            Call::SetFlag { code, value } => {
                let cfg = e.config_mut(icp)?;
                return Ok(cfg.set_flag(module, *code, *value).into_iter().collect());
            }
            Call::SetMetadata => {
                e.config_mut(icp)?;
            }
            Call::SetSolverFlags {
                gdigit,
                ints,
                reals,
            } => e.config_mut(icp)?.set_solver(*gdigit, ints, reals)?,
            Call::SetMaterial { mdigit, params } => {
                let cfg = e.config_mut(icp)?;
                cfg.set_material(*mdigit, params)?;
                return Ok(unsupported(cfg, |call| {
                    call.starts_with("cntc_setmaterialparameters")
                }));
            }
            Call::SetTemperature { imeth, params } => {
                let cfg = e.config_mut(icp)?;
                cfg.set_temperature(*imeth, params)?;
                return Ok(unsupported(cfg, |call| call == "cntc_settemperaturedata"));
            }
            Call::SetFriction { imeth, params } => {
                let cfg = e.config_mut(icp)?;
                cfg.set_friction(module, *imeth, params)?;
                return Ok(unsupported(cfg, |call| call == "cntc_setfrictionmethod"));
            }
            Call::SetTimestep { dt } => match e {
                Element::Basic(_) => e.patch_mut(icp)?.set_timestep(*dt)?,
                Element::WheelRail(_) => {}
            },
            Call::SetReferenceVelocity { veloc } => {
                e.patch_mut(icp)?.set_reference_velocity(*veloc)?
            }
            Call::SetRollingStep { chi, dq } => match e {
                // Module 1 reads DQREL only (CONTACT's Python passes no chi).
                Element::WheelRail(w) => w.set_rolling_step(chi.unwrap_or(0.0), *dq)?,
                Element::Basic(_) => {
                    let chi = chi.ok_or_else(|| CntcError::argument("chi", "is a null pointer"))?;
                    e.patch_mut(icp)?.set_rolling_step(chi, *dq)?
                }
            },
            Call::SetHertz { ipotcn, params } => e.patch_mut(icp)?.set_hertz(*ipotcn, params)?,
            Call::SetPotcon { ipotcn, params } => match e {
                Element::WheelRail(w) => w.set_discretisation(*ipotcn, params)?,
                Element::Basic(_) => e.patch_mut(icp)?.set_potcon(*ipotcn, params)?,
            },
            Call::SetVerticalForce { fz } => e.wheelrail_mut()?.set_vertical_force(*fz)?,
            Call::SetPenetration { pen } => e.patch_mut(icp)?.set_penetration(*pen)?,
            Call::SetNormalForce { fn_ } => e.patch_mut(icp)?.set_normal_force(*fn_)?,
            Call::SetUndeformedDistance { ibase, params } => {
                e.patch_mut(icp)?.set_udist(*ibase, params)?
            }
            Call::SetCreepages { vx, vy, phi } => {
                e.patch_mut(icp)?.set_creepages(*vx, *vy, *phi)?
            }
            Call::SetExtraRigidSlip { wx, wy } => e.patch_mut(icp)?.set_extra_rigid_slip(wx, wy)?,
            Call::SetTangentialForces { fx, fy } => match e {
                Element::WheelRail(w) => w.set_longitudinal_force(icp, *fx)?,
                Element::Basic(_) => e.patch_mut(icp)?.set_tangential_forces(*fx, *fy)?,
            },
            Call::SetProfileFile {
                fname,
                content,
                slice_files,
                ints,
                reals,
            } => e.wheelrail_mut()?.set_profile_file(
                fname,
                content.as_deref(),
                slice_files,
                ints,
                reals,
            )?,
            Call::SetProfileValues {
                npoint,
                values,
                ints,
                reals,
            } => e
                .wheelrail_mut()?
                .set_profile_values(*npoint, values, ints, reals)?,
            Call::SetTrackDimensions { ztrack, params } => {
                e.wheelrail_mut()?.set_track_dimensions(*ztrack, params)?
            }
            Call::SetWheelsetDimensions { ewheel, params } => e
                .wheelrail_mut()?
                .set_wheelset_dimensions(*ewheel, params)?,
            Call::SetWheelsetPosition { ewheel, params } => {
                e.wheelrail_mut()?.set_wheelset_position(*ewheel, params)?
            }
            Call::SetWheelsetVelocity { ewheel, params } => {
                e.wheelrail_mut()?.set_wheelset_velocity(*ewheel, params)?
            }
            Call::SetWheelsetFlexibility { ewheel, params } => e
                .wheelrail_mut()?
                .set_wheelset_flexibility(*ewheel, params)?,
        }
        Ok(Vec::new())
    }

    /// The key of a call that, when it succeeds, replaces everything an
    /// earlier call of the same key set (its input and the digit it sets),
    /// which only a calculation reads: the kinematic inputs a simulator
    /// sets every step. A log keeps the last successful call of each key;
    /// a failed one changed nothing and is not kept. `None`: every such
    /// call is kept, failed or not (a failed profile is kept as a failure).
    fn key(&self) -> Option<(u8, i32)> {
        match self {
            Call::SetTimestep { .. } => Some((1, 0)),
            Call::SetReferenceVelocity { .. } => Some((2, 0)),
            Call::SetRollingStep { .. } => Some((3, 0)),
            Call::SetVerticalForce { .. } => Some((4, 0)),
            Call::SetPenetration { .. } => Some((5, 0)),
            Call::SetNormalForce { .. } => Some((6, 0)),
            Call::SetCreepages { .. } => Some((7, 0)),
            Call::SetTangentialForces { .. } => Some((8, 0)),
            Call::SetExtraRigidSlip { .. } => Some((9, 0)),
            // Six values set them all (E = 1 without values sets nothing).
            Call::SetWheelsetPosition { ewheel, params } if params.len() == 6 => {
                Some((10, *ewheel))
            }
            Call::SetWheelsetVelocity { ewheel, params } if params.len() == 6 => {
                Some((11, *ewheel))
            }
            _ => None,
        }
    }
}

/// The warning `cfg` keeps of its last unsupported setting, when `of`
/// its call.
fn unsupported(cfg: &crate::config::Config, of: impl Fn(&str) -> bool) -> Vec<String> {
    match &cfg.unsupported {
        Some((call, what)) if of(call) => vec![what.clone()],
        _ => Vec::new(),
    }
}

/// The calls made on one result element since it was created, each with
/// its patch `icp`, in order, the superseded kinematic calls dropped (see
/// [`Call`]'s keys); and which of them a server has received.
#[derive(Debug, Clone, Default)]
pub struct CallLog {
    calls: Vec<(i32, Call)>,
    /// Calls `..sent` have been sent.
    sent: usize,
    /// Bytes held by the calls' arrays (an estimate of the log's size).
    bytes: usize,
}

/// The most calls a log holds; beyond, it stops keeping them and a lost
/// server cannot be caught up (the element must be configured anew).
pub const MAX_LOGGED_CALLS: usize = 100_000;
/// The most bytes of arrays a log holds (as [`MAX_LOGGED_CALLS`]).
pub const MAX_LOGGED_BYTES: usize = 256 << 20;

impl CallLog {
    /// Appends `call` on patch `icp`, which `applied` (succeeded or not),
    /// dropping an earlier call it supersedes. Returns false when the log
    /// is full (it no longer holds the whole history;
    /// [`CallLog::complete`] says so).
    pub fn push(&mut self, icp: i32, call: Call, applied: bool) -> bool {
        if let Some(key) = call.key() {
            if !applied {
                return self.complete();
            }
            if let Some(i) = self
                .calls
                .iter()
                .rposition(|(c, k)| *c == icp && k.key() == Some(key))
            {
                let (_, old) = self.calls.remove(i);
                self.bytes -= size_of_call(&old);
                if i < self.sent {
                    self.sent -= 1;
                }
            }
        }
        if !self.complete() {
            return false;
        }
        let b = size_of_call(&call);
        if self.calls.len() >= MAX_LOGGED_CALLS || self.bytes + b > MAX_LOGGED_BYTES {
            self.bytes = usize::MAX;
            return false;
        }
        self.bytes += b;
        self.calls.push((icp, call));
        true
    }

    /// Whether the log holds every call since the element was created.
    pub fn complete(&self) -> bool {
        self.bytes != usize::MAX
    }

    /// The calls not yet sent.
    pub fn unsent(&self) -> &[(i32, Call)] {
        &self.calls[self.sent.min(self.calls.len())..]
    }

    /// Every call kept (to bring a new server up to date).
    pub fn all(&self) -> &[(i32, Call)] {
        &self.calls
    }

    /// Marks every call as sent.
    pub fn mark_sent(&mut self) {
        self.sent = self.calls.len();
    }

    /// Marks every call as unsent (a new server has none of them).
    pub fn mark_unsent(&mut self) {
        self.sent = 0;
    }

    /// The number of calls kept.
    pub fn len(&self) -> usize {
        self.calls.len()
    }

    /// Whether no call is kept.
    pub fn is_empty(&self) -> bool {
        self.calls.is_empty()
    }
}

/// The bytes of `call`'s arrays and strings, roughly.
fn size_of_call(call: &Call) -> usize {
    let f = std::mem::size_of::<f64>();
    let i = std::mem::size_of::<i32>();
    64 + match call {
        Call::SetSolverFlags { ints, reals, .. } => ints.len() * i + reals.len() * f,
        Call::SetMaterial { params, .. }
        | Call::SetTemperature { params, .. }
        | Call::SetFriction { params, .. }
        | Call::SetHertz { params, .. }
        | Call::SetPotcon { params, .. }
        | Call::SetUndeformedDistance { params, .. }
        | Call::SetTrackDimensions { params, .. }
        | Call::SetWheelsetDimensions { params, .. }
        | Call::SetWheelsetPosition { params, .. }
        | Call::SetWheelsetVelocity { params, .. }
        | Call::SetWheelsetFlexibility { params, .. } => params.len() * f,
        Call::SetExtraRigidSlip { wx, wy } => (wx.len() + wy.len()) * f,
        Call::SetProfileFile {
            fname,
            content,
            slice_files,
            ints,
            reals,
        } => {
            fname.len()
                + content.as_ref().map_or_else(String::len, Vec::len)
                + slice_files
                    .iter()
                    .map(|(n, c)| n.len() + c.as_ref().map_or_else(String::len, Vec::len))
                    .sum::<usize>()
                + ints.len() * i
                + reals.len() * f
        }
        Call::SetProfileValues {
            values,
            ints,
            reals,
            ..
        } => values.len() * f + ints.len() * i + reals.len() * f,
        _ => 0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_log_keeps_the_last_kinematic_call_of_each_patch_and_every_other_call() {
        let mut log = CallLog::default();
        let creep = |vx: f64| Call::SetCreepages {
            vx,
            vy: 0.0,
            phi: 0.0,
        };
        log.push(1, Call::SetFlag { code: 1, value: 2 }, true);
        log.push(1, creep(1.0), true);
        log.push(2, creep(2.0), true);
        // A failed creepage call changed nothing: not kept.
        log.push(2, creep(f64::NAN), false);
        log.mark_sent();
        log.push(1, Call::SetFlag { code: 1, value: 3 }, false);
        log.push(1, creep(3.0), true);
        // Both flag calls are kept (flags are not keyed; the second failed
        // and is kept all the same), patch 1's first creepage call dropped,
        // patch 2's kept.
        assert_eq!(
            log.all(),
            &[
                (1, Call::SetFlag { code: 1, value: 2 }),
                (2, creep(2.0)),
                (1, Call::SetFlag { code: 1, value: 3 }),
                (1, creep(3.0)),
            ]
        );
        // The dropped call had been sent: the unsent ones are the two new.
        assert_eq!(log.unsent().len(), 2);
        assert!(log.complete());
    }

    #[test]
    fn a_full_log_says_it_is_incomplete() {
        let mut log = CallLog::default();
        for k in 0..MAX_LOGGED_CALLS {
            assert!(log.push(
                1,
                Call::SetFlag {
                    code: 1,
                    value: k as i32
                },
                true
            ));
        }
        assert!(!log.push(1, Call::SetMetadata, true));
        assert!(!log.complete());
    }
}
