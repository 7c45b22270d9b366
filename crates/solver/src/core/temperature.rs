//! Flash temperatures of both surfaces in steady rolling, from the
//! frictional power of a solved patch (Ertz & Knothe's model, as CONTACT
//! offers it).
//!
//! M. Ertz, K. Knothe, "A comparison of analytical and numerical methods
//! for the calculation of temperatures in wheel/rail contact", Wear 253
//! (2002) 498–508. At the high Peclet numbers of wheel/rail contact the heat
//! conducted along the surface is small beside the heat carried by the
//! material, so each surface point of each body is a 1-D semi-infinite solid
//! (depth only) whose surface receives the heat flux of the contact while it
//! passes through it.
//!
//! # Conventions
//!
//! * Grid and frame: the potential contact grid of [`crate::core::grid`],
//!   axes of [`crate::core::problem`]. Temperatures are per element centre.
//! * Motion: the patch travels in +x over both bodies at the rolling speed
//!   V \[m/s\]; the material enters at the leading edge (large x) and a point
//!   at x has been in the patch for the time (x_lead − x)/V. Each grid row
//!   (fixed y) is one independent strip.
//! * Heat source: the frictional power density of element i,
//!   q_i = |p_t,i| |s_i| V \[W/m²\], with p_t the tangential traction \[Pa\]
//!   and s the slip of steady rolling (slip velocity over V, [-],
//!   [`crate::core::solution::ElementFields::slip_x`]); uniform over the
//!   element.
//! * Temperatures in kelvin \[K\]; the inputs in SI
//!   ([`ThermalBody`]: W/(m K), kg/m³, J/(kg K)).
//!
//! # Model
//!
//! A semi-infinite solid of effusivity beta = sqrt(lambda rho c) whose
//! surface takes the flux F(t) has the surface temperature rise
//! (Carslaw & Jaeger, Conduction of Heat in Solids, 2nd ed. 1959, ch. II,
//! the semi-infinite solid with a prescribed surface flux)
//!
//! ```text
//! dT(t) = 1/(beta sqrt(pi)) ∫_0^t F(tau) / sqrt(t − tau) dtau .
//! ```
//!
//! With t = (x_lead − x)/V this is, along a row,
//! dT(x) = 1/(beta sqrt(pi V)) ∫_x^x_lead F(x') / sqrt(x' − x) dx'.
//! (Ertz & Knothe's equation numbers below are those CONTACT's
//! `m_temperature` cites.)
//!
//! * Heat partition (Ertz & Knothe eq. 25 with equal surface speeds): body 1
//!   takes the share eps1 = beta1/(beta1 + beta2) of q, body 2 the rest, so
//!   that both surfaces have the same rise in the contact:
//!   dT(x) = 1/((beta1 + beta2) sqrt(pi V)) ∫ q(x') / sqrt(x' − x) dx'.
//!   After the trailing edge each body cools by the same integral (the flux
//!   has stopped), so the frictional rise is one field for both bodies.
//! * Discretisation: q is uniform over each element, so the integral over
//!   element j upstream of the centre of element i is exact:
//!   2 (sqrt(x_j − x_i + dx/2) − sqrt(x_j − x_i − dx/2)), and over the
//!   upstream half of element i itself 2 sqrt(dx/2). A uniform q thus gives
//!   the closed form 2 q sqrt(x_lead − x) / ((beta1 + beta2) sqrt(pi V)) to
//!   rounding at every element centre.
//! * Bulk temperatures (Ertz & Knothe's convection part, their eq. 47):
//!   the bodies at T1 and T2 touching at the leading edge take at once the
//!   common surface temperature Tc = (beta1 T1 + beta2 T2)/(beta1 + beta2)
//!   (two semi-infinite solids in perfect contact), which holds over the
//!   row's contact span (its first to its last element with p_n > 0, the
//!   contact time tc = L/V). After the trailing edge body k relaxes to its
//!   bulk value: T = Tk + (Tc − Tk) (2/pi) asin(sqrt(tc/t)) (the flux that
//!   held the surface at Tc, beta (Tc − Tk)/sqrt(pi tau), switched off at
//!   tc, in the integral above). Upstream of the span each surface is at
//!   its bulk temperature.
//!
//! # Against CONTACT
//!
//! CONTACT (`m_temperature`, example `ertz_temperature`) evaluates the same
//! sum with the element's own upstream half counted twice (4 sqrt(dx/2)
//! where the integral gives 2 sqrt(dx/2)): its temperatures exceed these by
//! that term, which vanishes as sqrt(dx) when the grid is refined. Its
//! contact temperature weights each bulk temperature with the other body's
//! effusivity, (beta2 T1 + beta1 T2)/(beta1 + beta2), and its frictional
//! rise of body 1 is beta2/beta1 times the common rise above (body 2's is
//! the same); the two agree for bodies of equal effusivity (its example)
//! and differ otherwise.
//!
//! # Cost
//!
//! O(nx² ny) square roots at most (each element sums over the contact
//! elements upstream in its row); [`flash_temperatures_into`] does not
//! allocate.

use serde::{Deserialize, Serialize};

use crate::core::error::{show, ContactError};
use crate::core::error::{Range, UnitHint};
use crate::core::grid::Grid;
use crate::core::solution::ElementFields;

/// Range of a bulk temperature \[K\] (−100 °C to about the melting point of
/// steel); the message for a value below it that is in it as degrees
/// Celsius (such as 20) suggests the kelvin value.
pub const BULK_TEMPERATURE_RANGE: Range =
    Range::closed(173.15, 2000.0, "K").hint(UnitHint::Celsius);
/// Range of a thermal conductivity \[W/(m K)\] (steel: about 50).
pub const CONDUCTIVITY_RANGE: Range = Range::positive(1e4, "W/(m K)");
/// Range of a density \[kg/m³\] (steel: about 7850).
pub const DENSITY_RANGE: Range = Range::positive(1e5, "kg/m^3");
/// Range of a specific heat capacity \[J/(kg K)\] (steel: about 450).
pub const SPECIFIC_HEAT_RANGE: Range = Range::positive(1e5, "J/(kg K)");
/// Range of the rolling speed \[m/s\].
pub const ROLLING_SPEED_RANGE: Range = Range::positive(1e3, "m/s");

/// Thermal properties of one body.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ThermalBody {
    /// Bulk (initial) temperature of the body's surface layer \[K\], in
    /// [`BULK_TEMPERATURE_RANGE`].
    pub bulk_temperature_k: f64,
    /// Thermal conductivity lambda \[W/(m K)\], in [`CONDUCTIVITY_RANGE`].
    pub conductivity_w_per_m_k: f64,
    /// Density rho \[kg/m³\], in [`DENSITY_RANGE`].
    pub density_kg_per_m3: f64,
    /// Specific heat capacity c \[J/(kg K)\], in [`SPECIFIC_HEAT_RANGE`].
    pub specific_heat_j_per_kg_k: f64,
}

impl ThermalBody {
    /// Rail/wheel steel as in Ertz & Knothe's example (and CONTACT's
    /// `ertz_temperature`): lambda = 50 W/(m K), rho = 7850 kg/m³,
    /// c = 450 J/(kg K), at `bulk_temperature_k`.
    pub fn steel(bulk_temperature_k: f64) -> Self {
        Self {
            bulk_temperature_k,
            conductivity_w_per_m_k: 50.0,
            density_kg_per_m3: 7850.0,
            specific_heat_j_per_kg_k: 450.0,
        }
    }

    /// Checks every value against its range; `key` names the body
    /// (`temperature.body1`).
    pub fn validate(&self, key: &str) -> Result<(), ContactError> {
        BULK_TEMPERATURE_RANGE.check(
            &format!("{key}.bulk_temperature_k"),
            self.bulk_temperature_k,
        )?;
        CONDUCTIVITY_RANGE.check(
            &format!("{key}.conductivity_w_per_m_k"),
            self.conductivity_w_per_m_k,
        )?;
        DENSITY_RANGE.check(&format!("{key}.density_kg_per_m3"), self.density_kg_per_m3)?;
        SPECIFIC_HEAT_RANGE.check(
            &format!("{key}.specific_heat_j_per_kg_k"),
            self.specific_heat_j_per_kg_k,
        )?;
        Ok(())
    }

    /// Thermal effusivity beta = sqrt(lambda rho c) \[W s^(1/2)/(m² K)\].
    pub fn effusivity(&self) -> f64 {
        (self.conductivity_w_per_m_k * self.density_kg_per_m3 * self.specific_heat_j_per_kg_k)
            .sqrt()
    }

    /// Thermal diffusivity kappa = lambda/(rho c) \[m²/s\].
    pub fn diffusivity_m2_per_s(&self) -> f64 {
        self.conductivity_w_per_m_k / (self.density_kg_per_m3 * self.specific_heat_j_per_kg_k)
    }
}

/// The inputs of the flash temperatures: both bodies and the rolling speed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ThermalInput {
    /// Body 1 (the rail in wheel/rail contact).
    pub body1: ThermalBody,
    /// Body 2 (the wheel).
    pub body2: ThermalBody,
    /// Rolling speed V \[m/s\], the speed of the patch over both bodies, in
    /// [`ROLLING_SPEED_RANGE`].
    pub rolling_speed_m_per_s: f64,
}

impl ThermalInput {
    /// Checks both bodies and the speed; `key` names the section
    /// (`temperature`).
    pub fn validate(&self, key: &str) -> Result<(), ContactError> {
        self.body1.validate(&format!("{key}.body1"))?;
        self.body2.validate(&format!("{key}.body2"))?;
        ROLLING_SPEED_RANGE.check(
            &format!("{key}.rolling_speed_m_per_s"),
            self.rolling_speed_m_per_s,
        )?;
        Ok(())
    }

    /// Whether every value is in its range (what [`ThermalInput::validate`]
    /// checks, without formatting a key).
    pub fn in_range(&self) -> bool {
        let body = |b: &ThermalBody| {
            BULK_TEMPERATURE_RANGE.contains(b.bulk_temperature_k)
                && CONDUCTIVITY_RANGE.contains(b.conductivity_w_per_m_k)
                && DENSITY_RANGE.contains(b.density_kg_per_m3)
                && SPECIFIC_HEAT_RANGE.contains(b.specific_heat_j_per_kg_k)
        };
        body(&self.body1)
            && body(&self.body2)
            && ROLLING_SPEED_RANGE.contains(self.rolling_speed_m_per_s)
    }

    /// Share of the frictional heat that flows into body 1,
    /// beta1/(beta1 + beta2) [-].
    pub fn heat_share_body1(&self) -> f64 {
        let (b1, b2) = (self.body1.effusivity(), self.body2.effusivity());
        b1 / (b1 + b2)
    }

    /// The common surface temperature of the bodies in the contact before
    /// frictional heating, (beta1 T1 + beta2 T2)/(beta1 + beta2) \[K\].
    pub fn contact_temperature_k(&self) -> f64 {
        let e = self.heat_share_body1();
        e * self.body1.bulk_temperature_k + (1.0 - e) * self.body2.bulk_temperature_k
    }
}

/// Where and what a body's highest surface temperature is.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TemperaturePeak {
    /// The temperature \[K\].
    pub temperature_k: f64,
    /// x of the element centre \[m\].
    pub x_m: f64,
    /// y of the element centre \[m\].
    pub y_m: f64,
}

/// Totals of the flash temperatures of a patch.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TemperatureSummary {
    /// Highest surface temperature of body 1.
    pub max_body1: TemperaturePeak,
    /// Highest surface temperature of body 2.
    pub max_body2: TemperaturePeak,
    /// Common surface temperature in the contact before frictional heating
    /// \[K\] ([`ThermalInput::contact_temperature_k`]).
    pub contact_temperature_k: f64,
    /// Share of the frictional heat into body 1 [-].
    pub heat_share_body1: f64,
    /// Frictional power of the patch, sum q dA \[W\] (a line contact: per
    /// metre of its length \[W/m\]).
    pub frictional_power_w: f64,
    /// Peclet number V a / (2 kappa) [-] with a the half length of the
    /// longest contact row and kappa the larger diffusivity of the bodies:
    /// the model neglects the heat conducted along the surface, which holds
    /// for Pe >> 1; 0 without contact.
    pub peclet_number: f64,
}

/// The surface temperature fields of both bodies on the grid (index
/// `iy * nx + ix`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SurfaceTemperatures {
    /// Surface temperature of body 1 \[K\].
    pub body1_k: Vec<f64>,
    /// Surface temperature of body 2 \[K\].
    pub body2_k: Vec<f64>,
    /// Frictional power density q = |p_t| |s| V \[W/m²\].
    pub heat_flux_w_per_m2: Vec<f64>,
    /// Peaks and totals.
    pub summary: TemperatureSummary,
}

/// The frictional power density |p_t| |s| V \[W/m²\] of element `i` of
/// steady-rolling `fields` at rolling speed `speed_m_per_s`.
#[inline]
pub fn heat_flux_w_per_m2(fields: &ElementFields, i: usize, speed_m_per_s: f64) -> f64 {
    fields.traction_x_pa[i].hypot(fields.traction_y_pa[i])
        * fields.slip_x[i].hypot(fields.slip_y[i])
        * speed_m_per_s
}

fn check_lengths(key: &str, n: usize, lens: &[usize]) -> Result<(), ContactError> {
    match lens.iter().find(|&&l| l != n) {
        Some(l) => Err(ContactError::invalid(
            key,
            format!("has {l} values for a grid of {n} elements"),
        )),
        None => Ok(()),
    }
}

/// The flash temperatures of both surfaces for the steady-rolling solution
/// `fields` on `grid` (see the module documentation).
pub fn flash_temperatures(
    grid: &Grid,
    fields: &ElementFields,
    input: &ThermalInput,
) -> Result<SurfaceTemperatures, ContactError> {
    let n = grid.len();
    let (mut body1_k, mut body2_k, mut heat) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let summary = flash_temperatures_into(grid, fields, input, &mut body1_k, &mut body2_k)?;
    for (i, q) in heat.iter_mut().enumerate() {
        *q = heat_flux_w_per_m2(fields, i, input.rolling_speed_m_per_s);
    }
    Ok(SurfaceTemperatures {
        body1_k,
        body2_k,
        heat_flux_w_per_m2: heat,
        summary,
    })
}

/// [`flash_temperatures`] into the caller's buffers `body1_k`, `body2_k`
/// (one value per element); allocates nothing.
pub fn flash_temperatures_into(
    grid: &Grid,
    fields: &ElementFields,
    input: &ThermalInput,
    body1_k: &mut [f64],
    body2_k: &mut [f64],
) -> Result<TemperatureSummary, ContactError> {
    if !input.in_range() {
        // The error names the key (formatting it allocates: only here).
        input.validate("temperature")?;
    }
    let n = grid.len();
    check_lengths(
        "fields",
        n,
        &[
            fields.pressure_pa.len(),
            fields.traction_x_pa.len(),
            fields.traction_y_pa.len(),
            fields.slip_x.len(),
            fields.slip_y.len(),
        ],
    )?;
    check_lengths("temperature buffers", n, &[body1_k.len(), body2_k.len()])?;
    let v = input.rolling_speed_m_per_s;
    let (t1, t2) = (
        input.body1.bulk_temperature_k,
        input.body2.bulk_temperature_k,
    );
    let tc = input.contact_temperature_k();
    let beta_sum = input.body1.effusivity() + input.body2.effusivity();
    // dT = scale * sum of q times twice the element integrals of 1/sqrt.
    let scale = 2.0 / (beta_sum * (std::f64::consts::PI * v).sqrt());
    let (dx, h) = (grid.dx_m, 0.5 * grid.dx_m);
    let own = h.sqrt();
    let mut power_w = 0.0;
    let mut longest_m: f64 = 0.0;
    for iy in 0..grid.ny {
        let row = iy * grid.nx..(iy + 1) * grid.nx;
        let p = &fields.pressure_pa[row.clone()];
        let (r1, r2) = (&mut body1_k[row.clone()], &mut body2_k[row.clone()]);
        let (Some(trail), Some(lead)) = (
            p.iter().position(|&v| v > 0.0),
            p.iter().rposition(|&v| v > 0.0),
        ) else {
            r1.fill(t1);
            r2.fill(t2);
            continue;
        };
        let span_m = (lead - trail + 1) as f64 * dx;
        longest_m = longest_m.max(span_m);
        for ix in 0..grid.nx {
            let (b1, b2) = if ix > lead {
                (t1, t2)
            } else if ix >= trail {
                (tc, tc)
            } else {
                // Distance from the leading edge of the span over its
                // length: t / tc.
                let d_m = (lead - ix) as f64 * dx + h;
                let relax = std::f64::consts::FRAC_2_PI * (span_m / d_m).sqrt().asin();
                (t1 + (tc - t1) * relax, t2 + (tc - t2) * relax)
            };
            let i0 = row.start;
            let mut sum = own * heat_flux_w_per_m2(fields, i0 + ix, v);
            for jx in (ix + 1).max(trail)..=lead {
                let q = heat_flux_w_per_m2(fields, i0 + jx, v);
                if q > 0.0 {
                    let d = (jx - ix) as f64 * dx;
                    sum += q * ((d + h).sqrt() - (d - h).sqrt());
                }
            }
            let rise = scale * sum;
            r1[ix] = b1 + rise;
            r2[ix] = b2 + rise;
            power_w += heat_flux_w_per_m2(fields, i0 + ix, v);
        }
    }
    power_w *= grid.element_area_m2();
    let peak = |t: &[f64]| {
        let (i, &temperature_k) = t
            .iter()
            .enumerate()
            .max_by(|a, b| a.1.total_cmp(b.1))
            .unwrap_or((0, &f64::NAN));
        TemperaturePeak {
            temperature_k,
            x_m: grid.x_m(i % grid.nx),
            y_m: grid.y_m(i / grid.nx),
        }
    };
    let kappa = input
        .body1
        .diffusivity_m2_per_s()
        .max(input.body2.diffusivity_m2_per_s());
    let summary = TemperatureSummary {
        max_body1: peak(body1_k),
        max_body2: peak(body2_k),
        contact_temperature_k: tc,
        heat_share_body1: input.heat_share_body1(),
        frictional_power_w: power_w,
        peclet_number: v * 0.5 * longest_m / (2.0 * kappa),
    };
    if !summary.max_body1.temperature_k.is_finite() || !summary.max_body2.temperature_k.is_finite()
    {
        return Err(ContactError::invalid(
            "fields",
            format!(
                "the tractions and slips give no finite temperature (largest {} K, {} K)",
                show(summary.max_body1.temperature_k),
                show(summary.max_body2.temperature_k)
            ),
        ));
    }
    Ok(summary)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::error::CELSIUS_ZERO_K;
    use crate::core::material::{CombinedMaterial, Material};
    use crate::core::normal::NormalLoad;
    use crate::core::problem::{ContactProblem, Creepages, Friction, Kinematics};
    use crate::core::solve::solve;
    use std::f64::consts::PI;

    /// A 60 x 4 grid (dx = 0.25 mm) with a contact strip over elements
    /// 20..40 of every row (x in [-2.5, 2.5] mm, a = 2.5 mm) carrying the
    /// uniform heat flux `q` at V = 20 m/s (p_t = 3e8 Pa, |s| = q/(p_t V)).
    fn strip(q: f64) -> (Grid, ElementFields, f64) {
        let grid = Grid::new(60, 4, 0.25e-3, 1e-3, -7.5e-3, -2e-3).unwrap();
        let v = 20.0;
        let n = grid.len();
        let mut f = ElementFields {
            pressure_pa: vec![0.0; n],
            traction_x_pa: vec![0.0; n],
            traction_y_pa: vec![0.0; n],
            slip_x: vec![0.0; n],
            slip_y: vec![0.0; n],
            ..Default::default()
        };
        for iy in 0..grid.ny {
            for ix in 20..40 {
                let i = grid.index(ix, iy);
                f.pressure_pa[i] = 1e9;
                f.traction_x_pa[i] = -3e8;
                f.slip_x[i] = q / (3e8 * v);
            }
        }
        (grid, f, v)
    }

    fn temperatures(
        grid: &Grid,
        fields: &ElementFields,
        body1: ThermalBody,
        body2: ThermalBody,
        v: f64,
    ) -> SurfaceTemperatures {
        let input = ThermalInput {
            body1,
            body2,
            rolling_speed_m_per_s: v,
        };
        flash_temperatures(grid, fields, &input).unwrap()
    }

    /// Surface temperature rise of a semi-infinite solid (conductivity
    /// lambda, diffusivity kappa) under the flux q1 switched on at t = 0 and
    /// off at t = tc: 2 q1 sqrt(kappa)/(lambda sqrt(pi)) (sqrt(t) −
    /// sqrt(t − tc)) (Carslaw & Jaeger 1959, ch. II: constant flux at the
    /// surface of a semi-infinite solid, 2 F sqrt(kappa t / pi)/K,
    /// superposed with its negative from tc on).
    fn constant_flux_rise(q1: f64, body: &ThermalBody, t: f64, tc: f64) -> f64 {
        let k = body.diffusivity_m2_per_s();
        let on = |t: f64| if t > 0.0 { t.sqrt() } else { 0.0 };
        2.0 * q1 * k.sqrt() / (body.conductivity_w_per_m_k * PI.sqrt()) * (on(t) - on(t - tc))
    }

    #[test]
    fn uniform_strip_matches_the_constant_flux_solution() {
        let q = 4e7;
        let (grid, fields, v) = strip(q);
        // Dissimilar bodies: body 2 conducts twice as well, half as dense.
        let body1 = ThermalBody::steel(300.0);
        let body2 = ThermalBody {
            conductivity_w_per_m_k: 100.0,
            density_kg_per_m3: 3925.0,
            ..ThermalBody::steel(300.0)
        };
        let t = temperatures(&grid, &fields, body1, body2, v);
        // Equal surface temperatures in the contact need q1/beta1 = q2/beta2
        // with q1 + q2 = q (beta = lambda/sqrt(kappa)).
        let beta = |b: &ThermalBody| b.conductivity_w_per_m_k / b.diffusivity_m2_per_s().sqrt();
        let q1 = q * beta(&body1) / (beta(&body1) + beta(&body2));
        let (a, tc) = (2.5e-3, 5e-3 / v);
        for iy in 0..grid.ny {
            for ix in 0..grid.nx {
                let i = grid.index(ix, iy);
                let time = (a - grid.x_m(ix)) / v;
                let r1 = constant_flux_rise(q1, &body1, time, tc);
                let r2 = constant_flux_rise(q - q1, &body2, time, tc);
                assert!(
                    (t.body1_k[i] - 300.0 - r1).abs() <= 1e-9 * r1.max(1.0),
                    "{ix}: {} {r1}",
                    t.body1_k[i]
                );
                assert!(
                    (t.body2_k[i] - 300.0 - r2).abs() <= 1e-9 * r2.max(1.0),
                    "{ix}: {} {r2}",
                    t.body2_k[i]
                );
            }
        }
        // The trailing element is the hottest: 2 q1 sqrt(kappa1 t)/(lambda1 sqrt(pi)).
        let peak = constant_flux_rise(q1, &body1, (a - grid.x_m(20)) / v, tc);
        assert!((t.summary.max_body1.temperature_k - 300.0 - peak).abs() < 1e-9 * peak);
        assert!((t.summary.max_body1.x_m - grid.x_m(20)).abs() < 1e-12);
        let power = q * 5e-3 * 4e-3;
        assert!((t.summary.frictional_power_w - power).abs() < 1e-9 * power);
        assert!((t.summary.heat_share_body1 - q1 / q).abs() < 1e-12);
    }

    #[test]
    fn bulk_temperatures_meet_in_the_contact_and_relax_after_it() {
        let (grid, mut fields, v) = strip(0.0);
        fields.slip_x.fill(0.0);
        let body1 = ThermalBody::steel(280.0);
        let body2 = ThermalBody {
            conductivity_w_per_m_k: 25.0,
            ..ThermalBody::steel(420.0)
        };
        let t = temperatures(&grid, &fields, body1, body2, v);
        // Heat flux continuity at the interface of two semi-infinite
        // solids: beta1 (Tc − T1) = beta2 (T2 − Tc).
        let tc_k = t.summary.contact_temperature_k;
        let (b1, b2) = (body1.effusivity(), body2.effusivity());
        assert!((b1 * (tc_k - 280.0) - b2 * (420.0 - tc_k)).abs() < 1e-9 * b1 * tc_k);
        // After the contact (duration tc), the surface of body k held at Tc
        // by the flux beta_k (Tc − Tk)/sqrt(pi tau) cools as
        // dT(t) = 1/(beta sqrt(pi)) ∫_0^tc F(tau)/sqrt(t − tau) dtau
        //       = (2 (Tc − Tk) sqrt(tc)/pi) ∫_0^1 du / sqrt(t − tc u²)
        // (tau = tc u²), integrated here by the midpoint rule.
        let duhamel = |dt0: f64, time: f64, tc: f64| {
            let m = 20_000;
            let s: f64 = (0..m)
                .map(|k| {
                    let u = (k as f64 + 0.5) / m as f64;
                    1.0 / (time - tc * u * u).sqrt()
                })
                .sum::<f64>()
                / m as f64;
            2.0 * dt0 * tc.sqrt() / PI * s
        };
        let tc = 5e-3 / v;
        for ix in 0..grid.nx {
            let i = grid.index(ix, 1);
            let time = (2.5e-3 - grid.x_m(ix)) / v;
            let (e1, e2) = if time < 0.0 {
                (280.0, 420.0)
            } else if time < tc {
                (tc_k, tc_k)
            } else {
                (
                    280.0 + duhamel(tc_k - 280.0, time, tc),
                    420.0 + duhamel(tc_k - 420.0, time, tc),
                )
            };
            assert!(
                (t.body1_k[i] - e1).abs() < 1e-6 * e1,
                "{ix}: {} {e1}",
                t.body1_k[i]
            );
            assert!(
                (t.body2_k[i] - e2).abs() < 1e-6 * e2,
                "{ix}: {} {e2}",
                t.body2_k[i]
            );
        }
    }

    #[test]
    fn bad_inputs_name_the_key() {
        let (grid, fields, v) = strip(1e7);
        let good = ThermalInput {
            body1: ThermalBody::steel(300.0),
            body2: ThermalBody::steel(300.0),
            rolling_speed_m_per_s: v,
        };
        let err = |input: ThermalInput| {
            flash_temperatures(&grid, &fields, &input)
                .unwrap_err()
                .to_string()
        };
        let m = err(ThermalInput {
            body1: ThermalBody::steel(20.0),
            ..good
        });
        assert!(
            m.contains("`temperature.body1.bulk_temperature_k`") && m.contains("293.15 K"),
            "{m}"
        );
        let m = err(ThermalInput {
            body2: ThermalBody {
                conductivity_w_per_m_k: f64::NAN,
                ..good.body2
            },
            ..good
        });
        assert!(
            m.contains("`temperature.body2.conductivity_w_per_m_k`"),
            "{m}"
        );
        let m = err(ThermalInput {
            rolling_speed_m_per_s: 0.0,
            ..good
        });
        assert!(m.contains("`temperature.rolling_speed_m_per_s`"), "{m}");
        let mut short = fields.clone();
        short.slip_y.pop();
        let m = flash_temperatures(&grid, &short, &good)
            .unwrap_err()
            .to_string();
        assert!(m.contains("`fields`"), "{m}");
    }

    /// CONTACT's example `ertz_temperature` (eve70a/CONTACT,
    /// examples/ertz_temperature.inp): Ertz & Knothe's ellipse a = 5.88 mm,
    /// b = 10.54 mm (A = 0.001015 /mm, B = 0.0004215 /mm), Fn = 100 kN,
    /// G = 82 GPa, nu = 0.28, mu = 0.3, V = 30000 mm/s, 216 x 45 elements of
    /// 0.2 x 0.5 mm reaching 35.3 mm behind the centre (CONTACT rolls in −x
    /// with CHI = 180 deg: its grid, x in [−7.9, 35.3] mm, is mirrored here);
    /// steel: HEATCP 450 J/(kg C), LAMBDA 50e-3 W/(mm C), DENS 7.85e-6
    /// kg/mm³.
    fn ertz_case(
        creepages: Creepages,
        bulk1_c: f64,
        bulk2_c: f64,
        refine: usize,
    ) -> (Grid, ElementFields, ThermalInput) {
        let grid = Grid::new(
            216 * refine,
            45,
            0.2e-3 / refine as f64,
            0.5e-3,
            -35.3e-3,
            -11.25e-3,
        )
        .unwrap();
        let steel = Material {
            shear_modulus_pa: 82e9,
            poisson_ratio: 0.28,
        };
        let problem = ContactProblem {
            material: CombinedMaterial::identical(steel).unwrap(),
            friction: Friction::coulomb(0.3),
            gap_m: ContactProblem::quadratic_gap(&grid, 1.015, 0.4215),
            grid,
            load: NormalLoad::NormalForce(1e5),
            kinematics: Kinematics::SteadyRolling(creepages),
            settings: Default::default(),
            rolling_direction_rad: 0.0,
            extra_rigid_slip: None,
            numerical_influence: None,
        };
        let s = solve(&problem).unwrap().pop().unwrap();
        let input = ThermalInput {
            body1: ThermalBody::steel(bulk1_c + CELSIUS_ZERO_K),
            body2: ThermalBody::steel(bulk2_c + CELSIUS_ZERO_K),
            rolling_speed_m_per_s: 30.0,
        };
        (grid, s.fields, input)
    }

    /// The largest surface temperature of both bodies \[degC\], and the same
    /// with CONTACT's sum (the element's own upstream half counted twice,
    /// see the module documentation).
    fn max_both_c(grid: &Grid, input: &ThermalInput, t: &SurfaceTemperatures) -> (f64, f64) {
        let beta_sum = input.body1.effusivity() + input.body2.effusivity();
        let own =
            2.0 / (beta_sum * (PI * input.rolling_speed_m_per_s).sqrt()) * (0.5 * grid.dx_m).sqrt();
        let (mut ours, mut contact_sum) = (f64::NEG_INFINITY, f64::NEG_INFINITY);
        for i in 0..grid.len() {
            let hottest = t.body1_k[i].max(t.body2_k[i]);
            ours = ours.max(hottest);
            contact_sum = contact_sum.max(hottest + own * t.heat_flux_w_per_m2[i]);
        }
        (ours - CELSIUS_ZERO_K, contact_sum - CELSIUS_ZERO_K)
    }

    #[test]
    fn full_sliding_of_the_ertz_example_matches_contact() {
        // CONTACT's cases 1 and 3 (CKSI = -0.03333, full sliding at 1 m/s):
        // MAX(T1,T2) = 166.8 C with both bodies at 0 C and 241.8 C with the
        // wheel (body 2) at 150 C; FRIC.POWER = -2.994E+04 W
        // (eve70a/CONTACT, examples/ertz_temperature.ref_out).
        let sliding = Creepages {
            creepage_long: -0.03333,
            ..Default::default()
        };
        let mut gaps = Vec::new();
        for (bulk2_c, reference_c, refine) in [(0.0, 166.8, 1), (150.0, 241.8, 1), (0.0, 166.8, 4)]
        {
            let (grid, fields, input) = ertz_case(sliding, 0.0, bulk2_c, refine);
            let t = flash_temperatures(&grid, &fields, &input).unwrap();
            let (ours_c, contact_sum_c) = max_both_c(&grid, &input, &t);
            let tc_c = t.summary.contact_temperature_k - CELSIUS_ZERO_K;
            assert!((tc_c - 0.5 * bulk2_c).abs() < 1e-9, "{tc_c}");
            if refine == 1 {
                // 29939 W on CONTACT's grid.
                let power = t.summary.frictional_power_w;
                assert!((power - 2.994e4).abs() < 1e-3 * 2.994e4, "{power}");
                // On CONTACT's grid, CONTACT's sum reproduces its maxima
                // (166.82 and 241.82 C): the rise above Tc within 0.5 %.
                let rise = reference_c - tc_c;
                assert!(
                    (contact_sum_c - reference_c).abs() < 5e-3 * rise,
                    "{contact_sum_c} {reference_c}"
                );
                // Ours is lower by the doubled own half: 152.34 C, 8.7 %
                // of the rise.
                assert!(
                    (ours_c - tc_c - 0.913 * rise).abs() < 5e-3 * rise,
                    "{ours_c}"
                );
            }
            gaps.push((ours_c - tc_c, contact_sum_c - ours_c));
        }
        // Refining dx four times: our maximum moves by 0.18 % (152.34 to
        // 152.61 C), CONTACT's sum halves its excess (sqrt(dx/2) term:
        // 14.5 to 7.1 K).
        let (coarse, fine) = (gaps[0], gaps[2]);
        assert!(
            (fine.0 - coarse.0).abs() < 5e-3 * fine.0,
            "{coarse:?} {fine:?}"
        );
        assert!(
            (fine.1 / coarse.1 - 0.5).abs() < 0.03,
            "{coarse:?} {fine:?}"
        );
    }

    #[test]
    fn partial_slip_of_the_ertz_example_matches_contact() {
        // CONTACT's case 4: CKSI = -0.002, CETA = 0.001, CPHI = 0.0002 /mm,
        // wheel at 150 C, rail at 0 C: FX = 2.182E+04 N, FY = -4476 N,
        // FRIC.POWER = -1672 W, 1199 slipping of 1969 contact elements,
        // MAX(T1,T2) = 150.0 C (the wheel's bulk temperature: the contact,
        // at Tc = 75 C plus the frictional rise, stays cooler)
        // (eve70a/CONTACT, examples/ertz_temperature.ref_out). The spin
        // changes sign with the mirrored rolling direction.
        let c = Creepages {
            creepage_long: -0.002,
            creepage_lat: 1e-3,
            spin_per_m: -0.2,
        };
        let (grid, fields, input) = ertz_case(c, 0.0, 150.0, 1);
        let t = flash_temperatures(&grid, &fields, &input).unwrap();
        let power = t.summary.frictional_power_w;
        // 1674.4 W.
        assert!((power - 1672.0).abs() < 5e-3 * 1672.0, "{power}");
        let (ours_c, _) = max_both_c(&grid, &input, &t);
        assert!((ours_c - 150.0).abs() < 1e-9, "{ours_c}");
        // The rail's hottest point is in the contact: 89.1 C.
        let rail_c = t.summary.max_body1.temperature_k - CELSIUS_ZERO_K;
        assert!(rail_c > 75.0 && rail_c < 150.0, "{rail_c}");
    }
}
