//! The getters of one solved patch ([`Outcome`]), in the caller's units:
//! everything `cntc_get*` reads of a patch in either module.

use railcontact_solver::core::solution::ElementState;

use crate::error::{CntcError, Result};
use crate::flags::field;
use crate::outcome::Outcome;
use crate::units::Units;

/// `cntc_getcontactforces`: FN, FX, FY \[force\], MZ \[force.length\] on
/// the output body.
pub fn contact_forces(o: &Outcome, u: Units) -> [f64; 4] {
    let s = u.body_sign();
    [
        o.normal_force_n,
        s * o.fx_n,
        s * o.fy_n,
        s * u.len_out(o.mz_nm),
    ]
}

/// `cntc_getcreepages`: CKSI, CETA, CPHI (rolling: [-], [-],
/// \[angle/length\]; a shift: \[length\], \[length\], \[angle\]).
pub fn creepages(o: &Outcome, u: Units) -> [f64; 3] {
    let s = u.body_sign();
    let [a, b, c] = o.creepages;
    if o.is_shift {
        [s * u.len_out(a), s * u.len_out(b), s * c]
    } else {
        [s * a, s * b, s * u.per_len_out(c)]
    }
}

/// `cntc_getcontactpatchareas`: contact, adhesion and slip areas
/// \[area\] (an elasto-plastic layer's plasticity area is contact minus
/// adhesion minus slip, as CONTACT's).
pub fn areas(o: &Outcome, u: Units) -> [f64; 3] {
    let l2 = u.length_m() * u.length_m();
    o.areas_m2.map(|a| a / l2)
}

/// `cntc_getpotcontact`: MX, MY, XC1, YC1, DX, DY (ipotcn = 3's form).
pub fn potcontact(o: &Outcome, u: Units) -> [f64; 6] {
    let g = &o.grid;
    [
        g.nx as f64,
        g.ny as f64,
        u.len_out(g.x_m(0)),
        u.len_out(g.y_m(0)),
        u.len_out(g.dx_m),
        u.len_out(g.dy_m),
    ]
}

/// Fails when the outcome has no fields on its grid (every model fills
/// them; kept so that a getter never reads past a short field).
fn require_fields(o: &Outcome) -> Result<()> {
    if o.has_fields() {
        Ok(())
    } else {
        Err(CntcError::Input(
            "the last calculation has no per-element results on its grid".into(),
        ))
    }
}

/// `cntc_getelementdivision`: 0 exterior, 1 adhesion, 2 slip, 3
/// plasticity (an elasto-plastic layer flowing without slip).
pub fn element_division(o: &Outcome) -> Result<Vec<i32>> {
    require_fields(o)?;
    let plastic = o.layer.as_ref().map_or(&[][..], |l| &l.plastic);
    Ok(o.fields
        .state
        .iter()
        .enumerate()
        .map(|(i, s)| match s {
            ElementState::Exterior => 0,
            ElementState::Adhesion if plastic.get(i) == Some(&true) => 3,
            ElementState::Adhesion => 1,
            ElementState::Slip => 2,
        })
        .collect())
}

/// `cntc_getfielddata` of field code `ifld`.
pub fn field_data(o: &Outcome, u: Units, ifld: i32) -> Result<Vec<f64>> {
    require_fields(o)?;
    let f = &o.fields;
    let s = u.body_sign();
    let n = o.grid.len();
    let stress = |v: &[f64], sign: f64| v.iter().map(|p| sign * u.stress_out(*p)).collect();
    let slip = |v: &[f64]| -> Vec<f64> {
        if o.is_shift {
            v.iter().map(|x| s * u.len_out(*x)).collect()
        } else {
            v.iter().map(|x| s * x).collect()
        }
    };
    Ok(match ifld {
        field::H => f.gap_m.iter().map(|h| u.len_out(*h)).collect(),
        field::MU => {
            if o.mu.len() == n {
                o.mu.clone()
            } else {
                vec![o.friction_coefficient; n]
            }
        }
        field::PX => stress(&f.traction_x_pa, s),
        field::PY => stress(&f.traction_y_pa, s),
        field::PN => stress(&f.pressure_pa, 1.0),
        field::SX => slip(&f.slip_x),
        field::SY => slip(&f.slip_y),
        field::TEMP1 | field::TEMP2 => match &o.temperature_k {
            Some(t) => t[(ifld - field::TEMP1) as usize]
                .iter()
                .map(|k| u.temperature_from_k(*k))
                .collect(),
            None => {
                return Err(CntcError::Input(
                    "temperatures were not computed: set H = 3 with cntc_settemperaturedata".into(),
                ))
            }
        },
        // Body 1's minus body 2's whatever the convention: CONTACT scales
        // UX, UY, UN by the length unit only, without the output body's
        // sign (cntc_getfielddata); a left wheel's y is mirrored in the
        // outcome already.
        field::UX | field::UY | field::UN => {
            let d = o.displacements_m()?;
            d[(ifld - field::UX) as usize]
                .iter()
                .map(|x| u.len_out(*x))
                .collect()
        }
        // An elasto-plastic layer's yield limit and plastic deformation
        // (zero without one). CONTACT scales UPLSX, UPLSY by the length
        // unit only, without the output body's sign: the same here.
        field::TAUCRT | field::UPLSX | field::UPLSY => match &o.layer {
            Some(l) if l.yield_limit_pa.len() == n => match ifld {
                field::TAUCRT => stress(&l.yield_limit_pa, 1.0),
                field::UPLSX => l.plastic_x_m.iter().map(|x| u.len_out(*x)).collect(),
                _ => l.plastic_y_m.iter().map(|y| u.len_out(*y)).collect(),
            },
            _ => vec![0.0; n],
        },
        // CONTACT returns the rigid slip's right-hand side, -w (m_sdis'
        // set_tang_rhs stores -dq w, the getter divides by dq): the same
        // sign here, so that a coupling reads what it reads from CONTACT.
        field::WX | field::WY => match &o.rigid_slip {
            Some(w) => slip(&w[(ifld - field::WX) as usize])
                .into_iter()
                .map(|v| -v)
                .collect(),
            None => vec![0.0; n],
        },
        other => {
            return Err(CntcError::Input(format!(
                "field code {other} (cntc_getfielddata) is not one of CONTACT's field codes"
            )))
        }
    })
}

/// `cntc_getcalculationtime`-style conversions are plain seconds; kept
/// here for symmetry with the other getters.
pub fn seconds(t: f64) -> [f64; 2] {
    [t, t]
}

/// `cntc_getsensitivities`: the `lenout` x `lenin` matrix (columns
/// consecutive, zero beyond 4 x 4) of the outputs Fn \[force\], Fx/(mu Fn),
/// Fy/(mu Fn) [-], Mz \[force.length\] over the inputs pen \[length\],
/// cksi, ceta [-], cphi \[angle/length\] (a shift: cksi, ceta
/// \[length\], cphi \[angle\]), as CONTACT defines them. Like CONTACT's,
/// they are those of body 1 under every unit convention.
pub fn sensitivities(o: &Outcome, u: Units, lenout: usize, lenin: usize) -> Result<Vec<f64>> {
    let j = o.sensitivities.ok_or_else(|| {
        CntcError::Input(
            "sensitivities were not computed: set S = 2 or 3 (CNTC_ic_sens) before cntc_calculate, \
             in steady rolling"
                .into(),
        )
    })?;
    let l = u.length_m();
    let (fn_, mu) = (o.normal_force_n, o.friction_coefficient);
    let rel = |f: f64, df: f64, dfn: f64| {
        if fn_ > 0.0 && mu > 0.0 {
            (df * fn_ - f * dfn) / (mu * fn_ * fn_)
        } else {
            0.0
        }
    };
    let in_scale = if o.is_shift {
        [l, l, l, 1.0]
    } else {
        [l, 1.0, 1.0, 1.0 / l]
    };
    let mut m = vec![0.0; lenout * lenin];
    for (c, col) in j.iter().enumerate().take(lenin.min(4)) {
        // col = d(Fn, Fx, Fy, Mz)/d(input c), SI.
        let out = [
            col[0],
            rel(o.fx_n, col[1], col[0]),
            rel(o.fy_n, col[2], col[0]),
            col[3] / l,
        ];
        for (r, v) in out.iter().enumerate().take(lenout.min(4)) {
            m[c * lenout + r] = v * in_scale[c];
        }
    }
    Ok(m)
}
