//! What a case asks for beyond the solution: `[subsurface]` stresses and
//! `[temperature]` (flash temperatures).

use serde::Deserialize;

use super::{bad, ranges, Model};
use crate::core::error::check_count;
use crate::core::problem::Kinematics;
use crate::core::temperature::ThermalInput;
use crate::problem::CaseError;

/// `[temperature]`: the rolling speed `rolling_speed_m_per_s` \[m/s\] and
/// the tables `[temperature.body1]`, `[temperature.body2]`, each with
/// `bulk_temperature_k` \[K\], `conductivity_w_per_m_k` \[W/(m K)\],
/// `density_kg_per_m3` \[kg/m³\] and `specific_heat_j_per_kg_k` \[J/(kg
/// K)\] (all required; ranges in [`crate::core::temperature`]). The flash
/// temperatures follow Ertz & Knothe's model
/// ([`crate::core::temperature::flash_temperatures`]).
pub type TemperatureSection = ThermalInput;

/// The checked `[temperature]` of a case of `model` with `kinematics`
/// (errors name the key).
pub(super) fn temperature_request(
    section: &TemperatureSection,
    model: Model,
    kinematics: &Kinematics,
) -> Result<ThermalInput, CaseError> {
    if model != Model::Exact {
        return Err(bad(
            "temperature",
            format!(
                "flash temperatures come from the frictional power of model = \"exact\", not \"{}\"",
                model.name()
            ),
        ));
    }
    if !matches!(kinematics, Kinematics::SteadyRolling(_)) {
        return Err(bad(
            "temperature",
            "flash temperatures need steady rolling: give `[rolling]` (a static or `[transient]` case has no steady frictional power)",
        ));
    }
    section.validate("temperature")?;
    Ok(*section)
}

/// `[subsurface]`: the depths below the surface at which to compute the
/// stresses and displacements of both bodies (under every element of the
/// grid), either as a list `depths_m` \[m\] or as `depth_count` depths
/// evenly spaced from 0 to `max_depth_m` \[m\]; and optionally the yield
/// stress in pure shear `shear_yield_stress_pa` \[Pa\] for the surface
/// fatigue index ([`crate::core::subsurface::surface_fatigue_index`]).
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SubsurfaceSection {
    /// Depths below the surface \[m\], each in [0, 1], 1 to
    /// [`crate::core::subsurface::MAX_DEPTHS`] of them.
    pub depths_m: Option<Vec<f64>>,
    /// Deepest of `depth_count` evenly spaced depths from 0 \[m\].
    pub max_depth_m: Option<f64>,
    /// Number of evenly spaced depths, 2 to [`crate::core::subsurface::MAX_DEPTHS`].
    pub depth_count: Option<usize>,
    /// Yield stress in pure shear k \[Pa\] (steel: about 300e6 to 600e6).
    pub shear_yield_stress_pa: Option<f64>,
}

/// A validated `[subsurface]` request.
#[derive(Debug, Clone, PartialEq)]
pub struct SubsurfaceRequest {
    /// Depths below the surface \[m\].
    pub depths_m: Vec<f64>,
    /// Yield stress in pure shear \[Pa\], for the surface fatigue index.
    pub shear_yield_stress_pa: Option<f64>,
}

impl SubsurfaceSection {
    /// The checked request of a case of `model` (errors name the key).
    pub fn request(&self, model: Model) -> Result<SubsurfaceRequest, CaseError> {
        use crate::core::subsurface::{check_depths, MAX_DEPTHS};
        if model != Model::Exact {
            return Err(bad(
                "subsurface",
                format!(
                    "subsurface stresses come from the tractions of model = \"exact\", not \"{}\"",
                    model.name()
                ),
            ));
        }
        let depths_m = match (&self.depths_m, self.max_depth_m, self.depth_count) {
            (Some(d), None, None) => d.clone(),
            (None, Some(max), Some(n)) => {
                ranges::WINDOW.check("subsurface.max_depth_m", max)?;
                let n = check_count("subsurface.depth_count", n, 2, MAX_DEPTHS)?;
                (0..n).map(|k| max * (k as f64 / (n - 1) as f64)).collect()
            }
            (Some(_), _, _) => {
                return Err(bad(
                    "subsurface.depths_m",
                    "give either `subsurface.depths_m` or `subsurface.max_depth_m` + \
                     `subsurface.depth_count`, not both",
                ))
            }
            (None, None, _) => {
                return Err(bad(
                    "subsurface.depths_m",
                    "missing: give `subsurface.depths_m` or `subsurface.max_depth_m` + `subsurface.depth_count`",
                ))
            }
            (None, Some(_), None) => {
                return Err(bad(
                    "subsurface.depth_count",
                    "missing (needed with `max_depth_m`)",
                ))
            }
        };
        check_depths("subsurface.depths_m", &depths_m)?;
        if let Some(k) = self.shear_yield_stress_pa {
            ranges::SHEAR_YIELD_STRESS.check("subsurface.shear_yield_stress_pa", k)?;
        }
        Ok(SubsurfaceRequest {
            depths_m,
            shear_yield_stress_pa: self.shear_yield_stress_pa,
        })
    }
}

#[cfg(test)]
mod subsurface_tests {
    use crate::problem::case::tests::ROLLING;

    use crate::conformal::frictional::FrictionalWorkspace;
    use crate::problem::case::*;
    use crate::problem::ModelRun;

    fn bad(extra: &str) -> String {
        match Case::from_toml(&format!("{ROLLING}{extra}")) {
            Err(CaseError::BadInput(m)) => m,
            other => panic!("expected bad input, got {other:?}"),
        }
    }

    #[test]
    fn subsurface_section_is_checked_and_names_the_key() {
        let c = Case::from_toml(&format!(
            "{ROLLING}[subsurface]\nmax_depth_m = 3e-3\ndepth_count = 4\n"
        ))
        .unwrap();
        let r = c.subsurface.unwrap();
        assert_eq!(r.depths_m.len(), 4);
        for (got, want) in r.depths_m.iter().zip([0.0, 1e-3, 2e-3, 3e-3]) {
            assert!((got - want).abs() < 1e-18);
        }
        assert!(bad("[subsurface]\n").contains("`subsurface.depths_m`"));
        assert!(
            bad("[subsurface]\ndepths_m = [1e-3, -1e-3]\n").contains("`subsurface.depths_m[1]`")
        );
        assert!(
            bad("[subsurface]\ndepths_m = [1e-3]\nmax_depth_m = 1e-3\ndepth_count = 2\n")
                .contains("not both")
        );
        assert!(bad("[subsurface]\nmax_depth_m = 1e-3\n").contains("`subsurface.depth_count`"));
        assert!(bad("[subsurface]\nmax_depth_m = 3\ndepth_count = 4\n")
            .contains("`subsurface.max_depth_m`"));
        assert!(
            bad("[subsurface]\ndepths_m = [1e-3]\nshear_yield_stress_pa = -1.0\n")
                .contains("`subsurface.shear_yield_stress_pa`")
        );
        assert!(bad("[subsurface]\ndepths = [1e-3]\n").contains("depths"));
        let m = match Case::from_toml(&format!(
            "model = \"fastsim\"\n{ROLLING}[subsurface]\ndepths_m = [1e-3]\n"
        )) {
            Err(CaseError::BadInput(m)) => m,
            other => panic!("expected bad input, got {other:?}"),
        };
        assert!(m.contains("`subsurface`") && m.contains("exact"), "{m}");
    }

    #[test]
    fn exact_run_reports_the_subsurface_peaks() {
        let c = Case::from_toml(&format!(
            "{ROLLING}[subsurface]\ndepths_m = [0.0, 1e-3, 2e-3, 3e-3, 4e-3]\nshear_yield_stress_pa = 300e6\n"
        ))
        .unwrap();
        let run = ModelRun::solve(&c, &mut FrictionalWorkspace::default()).unwrap();
        let report = run.report(&c, false);
        let s = report.subsurface.as_ref().unwrap();
        let t = &report.totals.totals;
        // Below a Hertz-like patch with little traction (Fx < 0.3 Fn) the
        // largest shear sits under the surface and is about 0.3 p0
        // (Johnson 1985 §4.2: 0.31 p0 for a circle).
        let ratio = s.body1.max_shear.value_pa / t.max_pressure_pa;
        assert!((0.27..0.34).contains(&ratio), "{ratio}");
        assert!(s.body1.max_shear.depth_m > 0.0);
        assert_eq!(s.body1.max_shear.depth_m, s.body2.max_shear.depth_m);
        let fi = s.surface_fatigue_index.unwrap();
        let f = t.fx_n.hypot(t.fy_n) / t.normal_force_n;
        assert!(
            (fi - (f - 2.0 * t.contact_area_m2 * 300e6 / (3.0 * t.normal_force_n))).abs() < 1e-12
        );
        assert!(report.human().contains("body 2 max von Mises [MPa]"));
        let json = serde_json::to_string(&report).unwrap();
        assert!(json.contains("\"subsurface\":{\"depths_m\""), "{json}");
    }
}

#[cfg(test)]
mod temperature_tests {
    use crate::problem::case::tests::ROLLING;

    use crate::conformal::frictional::FrictionalWorkspace;
    use crate::problem::case::*;
    use crate::problem::ModelRun;

    /// Steel on steel (Ertz & Knothe's values), rail at 20 C, wheel at 60 C,
    /// 30 m/s.
    const TEMPERATURE: &str = r#"
[temperature]
rolling_speed_m_per_s = 30.0
[temperature.body1]
bulk_temperature_k = 293.15
conductivity_w_per_m_k = 50.0
density_kg_per_m3 = 7850.0
specific_heat_j_per_kg_k = 450.0
[temperature.body2]
bulk_temperature_k = 333.15
conductivity_w_per_m_k = 50.0
density_kg_per_m3 = 7850.0
specific_heat_j_per_kg_k = 450.0
"#;

    fn bad(text: &str) -> String {
        match Case::from_toml(text) {
            Err(CaseError::BadInput(m)) => m,
            other => panic!("expected bad input, got {other:?}"),
        }
    }

    #[test]
    fn temperature_section_is_checked_and_names_the_key() {
        let c = Case::from_toml(&format!("{ROLLING}{TEMPERATURE}")).unwrap();
        let t = c.temperature.unwrap();
        assert_eq!(t.rolling_speed_m_per_s, 30.0);
        assert_eq!(t.body2.bulk_temperature_k, 333.15);
        let m = bad(&format!(
            "{ROLLING}{}",
            TEMPERATURE.replace("333.15", "60.0")
        ));
        assert!(
            m.contains("`temperature.body2.bulk_temperature_k`") && m.contains("Celsius"),
            "{m}"
        );
        let m = bad(&format!(
            "{ROLLING}{}",
            TEMPERATURE.replace(
                "rolling_speed_m_per_s = 30.0",
                "rolling_speed_m_per_s = -1.0"
            )
        ));
        assert!(m.contains("`temperature.rolling_speed_m_per_s`"), "{m}");
        let m = bad(&format!(
            "{ROLLING}{}",
            TEMPERATURE.replacen("density_kg_per_m3 = 7850.0\n", "", 1)
        ));
        assert!(m.contains("density_kg_per_m3"), "{m}");
        let m = bad(&format!(
            "{ROLLING}{}",
            TEMPERATURE.replacen("density_kg_per_m3", "density", 1)
        ));
        assert!(m.contains("density"), "{m}");
        let m = bad(&format!("model = \"fastsim\"\n{ROLLING}{TEMPERATURE}"));
        assert!(m.contains("`temperature`") && m.contains("exact"), "{m}");
        let m = bad(&format!(
            "{}{TEMPERATURE}",
            ROLLING.replace("[rolling]\ncreepage_long = 0.001\n", "")
        ));
        assert!(
            m.contains("`temperature`") && m.contains("steady rolling"),
            "{m}"
        );
    }

    #[test]
    fn exact_run_reports_the_flash_temperatures() {
        let c = Case::from_toml(&format!("{ROLLING}{TEMPERATURE}")).unwrap();
        let run = ModelRun::solve(&c, &mut FrictionalWorkspace::default()).unwrap();
        let report = run.report(&c, false);
        let t = report.temperature.unwrap();
        // The frictional power is T-gamma times the rolling speed
        // (-sum p_t . s dA V; |p_t||s| = -p_t . s where the material slips).
        let tgamma = report.totals.totals.tgamma_n;
        assert!(tgamma > 0.0);
        assert!(
            (t.frictional_power_w - 30.0 * tgamma).abs() < 1e-9 * 30.0 * tgamma,
            "{} {tgamma}",
            t.frictional_power_w
        );
        // Equal steels: the contact temperature is the mean bulk
        // temperature, the heat splits in halves, the rail heats above it
        // and the wheel is nowhere below its bulk temperature.
        assert!((t.contact_temperature_k - 313.15).abs() < 1e-9);
        assert!((t.heat_share_body1 - 0.5).abs() < 1e-12);
        assert!(t.max_body1.temperature_k > 313.15);
        assert!(t.max_body2.temperature_k >= 333.15);
        assert!(report.human().contains("body 1 max temperature [K]"));
        let json = serde_json::to_string(&report).unwrap();
        assert!(json.contains("\"temperature\":{\"max_body1\""), "{json}");
    }
}
