//! The `[material]`, `[interfacial_layer]` and `[viscoelastic]` sections: the
//! bodies' elastic constants, the third-body layer and the viscoelastic
//! solids, each value checked naming its key.

use serde::Deserialize;

use super::{bad, Model};
use crate::core::frame::ROLLING_DIRECTION_KEY;
use crate::core::layer::InterfacialLayer;
use crate::core::material::{CombinedMaterial, Material};
use crate::core::problem::{Friction, Kinematics, INTERFACIAL_LAYER_KEY, VISCOELASTIC_KEY};
use crate::core::viscoelastic::Viscoelastic;
use crate::problem::CaseError;

/// The checked `[conformal]` of a case of `model` with `kinematics`: its
/// rigid slip surface (the default without the section). The section
/// belongs to the conformal models; outside steady rolling its rigid slip
/// is unused (a note says so).
/// The case's `[interfacial_layer]`, checked (each value naming its key
/// `interfacial_layer.<key>`, and against the friction law) for the exact
/// model; refused, naming `interfacial_layer`, with another model (FASTSIM,
/// the closed forms and the conformal solvers do not take it). A
/// frictionless case gets a note: the normal problem does not see the
/// layer.
pub(super) fn interfacial_layer(
    section: Option<InterfacialLayer>,
    model: Model,
    friction: &Friction,
    kinematics: &Kinematics,
    notes: &mut Vec<String>,
) -> Result<Option<InterfacialLayer>, CaseError> {
    let Some(layer) = section else {
        return Ok(None);
    };
    if model != Model::Exact {
        return Err(bad(
            INTERFACIAL_LAYER_KEY,
            format!(
                "an interfacial layer is taken by model = \"exact\" only (steady rolling and \
                 transient steps), not by \"{}\"",
                model.name()
            ),
        ));
    }
    layer.validate(INTERFACIAL_LAYER_KEY)?;
    layer.check_friction(INTERFACIAL_LAYER_KEY, friction)?;
    if matches!(kinematics, Kinematics::Frictionless) {
        notes.push(
            "interfacial_layer: a frictionless normal problem does not see the layer (it acts on \
             the tangential tractions): give [rolling] or [transient]"
                .to_string(),
        );
    }
    Ok(Some(layer))
}

/// The case's `[viscoelastic]`, checked (each value naming its key
/// `viscoelastic.<key>`) for the exact model in steady rolling in +x or
/// frictionless; refused, naming `viscoelastic`, with another model or
/// transient steps, and naming `rolling_direction_rad` for another
/// rolling direction (CONTACT takes M = 1 in steady rolling with CHI = 0
/// only).
pub(super) fn viscoelastic(
    section: Option<Viscoelastic>,
    model: Model,
    kinematics: &Kinematics,
    rolling_direction_rad: f64,
) -> Result<Option<Viscoelastic>, CaseError> {
    let Some(visc) = section else {
        return Ok(None);
    };
    if model != Model::Exact {
        return Err(bad(
            VISCOELASTIC_KEY,
            format!(
                "viscoelastic bodies are taken by model = \"exact\" only (steady rolling), not by \
                 \"{}\"",
                model.name()
            ),
        ));
    }
    visc.validate(VISCOELASTIC_KEY)?;
    if matches!(kinematics, Kinematics::Transient(_)) {
        return Err(bad(
            VISCOELASTIC_KEY,
            "viscoelastic bodies are taken in steady rolling ([rolling], or no [rolling] for its \
             frictionless normal problem) only, not with [transient]",
        ));
    }
    if rolling_direction_rad != 0.0 {
        return Err(bad(
            ROLLING_DIRECTION_KEY,
            "viscoelastic bodies roll in +x only: give 0",
        ));
    }
    Ok(Some(visc))
}

/// `[material]`: either `shear_modulus_pa` + `poisson_ratio` for both bodies,
/// or the sub-tables `[material.body1]` and `[material.body2]` for dissimilar
/// bodies (not both forms at once).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSection {
    /// Shear modulus G of both bodies \[Pa\], > 0 (steel: 81.0e9).
    pub shear_modulus_pa: Option<f64>,
    /// Poisson ratio nu of both bodies [-], in [0, 0.5) (steel: 0.30).
    pub poisson_ratio: Option<f64>,
    /// Body 1 (the rail; the body the tractions act on): `shear_modulus_pa`
    /// \[Pa\], `poisson_ratio` [-].
    pub body1: Option<Material>,
    /// Body 2 (the wheel), same keys.
    pub body2: Option<Material>,
    /// A file of numerical influence coefficients (CONTACT's C3 = 9 and
    /// its format, [`crate::core::numerical_influence`]) replacing the
    /// half-space's, relative to the case file's directory; exact model,
    /// the grid's element sizes the file's (`grid.window_x_m` = nx dx,
    /// `grid.window_y_m` = ny dy). The materials' combined shear modulus
    /// scales the coefficients.
    #[serde(default)]
    pub influence_file: Option<String>,
}

impl MaterialSection {
    /// The checked materials of the two bodies (errors name the key).
    pub fn combine(&self) -> Result<CombinedMaterial, CaseError> {
        let direct = self.shear_modulus_pa.is_some() || self.poisson_ratio.is_some();
        let bodies = self.body1.is_some() || self.body2.is_some();
        if direct && bodies {
            return Err(bad(
                "material",
                "give either `material.shear_modulus_pa` + `material.poisson_ratio` (both bodies) \
                 or the tables `[material.body1]` + `[material.body2]`, not both",
            ));
        }
        if bodies {
            let b1 = self.body1.ok_or_else(|| {
                bad(
                    "material.body1",
                    "missing: `[material.body2]` was given, give `[material.body1]` too",
                )
            })?;
            let b2 = self.body2.ok_or_else(|| {
                bad(
                    "material.body2",
                    "missing: `[material.body1]` was given, give `[material.body2]` too",
                )
            })?;
            return Ok(CombinedMaterial::new(b1, b2)?);
        }
        let g = self
            .shear_modulus_pa
            .ok_or_else(|| bad("material.shear_modulus_pa", "missing"))?;
        let nu = self
            .poisson_ratio
            .ok_or_else(|| bad("material.poisson_ratio", "missing"))?;
        let m = Material {
            shear_modulus_pa: g,
            poisson_ratio: nu,
        };
        m.validate("material")?;
        Ok(CombinedMaterial::identical(m)?)
    }
}

#[cfg(test)]
mod layer_tests {
    use crate::core::solution::SolveStatus;
    use crate::problem::case::*;
    use crate::problem::ExactRun;

    const EXAMPLE: &str = include_str!("../../../../../examples/cases/layer_plastic_3bl.toml");

    /// CONTACT's FX \[N\] of `plastic_3bl.ref_out` cases 15-31 as printed
    /// (the clay series the example states), and whether the element flows
    /// (NPLAST = 1).
    const CLAY_FX: [(&str, bool); 17] = [
        ("200.0", false),
        ("216.0", true),
        ("232.0", true),
        ("248.0", true),
        ("262.4", true),
        ("262.4", false),
        ("82.43", false),
        ("82.43", false),
        ("266.4", true),
        ("284.0", true),
        ("304.0", true),
        ("324.1", true),
        ("344.1", true),
        ("364.1", true),
        ("384.1", true),
        ("404.1", true),
        ("424.1", true),
    ];

    /// Half a unit of the last digit of a printed decimal.
    fn half_unit(s: &str) -> f64 {
        let decimals = s.find('.').map_or(0, |i| s.len() - i - 1) as i32;
        0.5 * 10f64.powi(-decimals)
    }

    /// The message of a case refused as bad input.
    pub(super) fn message(r: Result<Case, CaseError>) -> String {
        match r {
            Err(CaseError::BadInput(m)) => m,
            other => panic!("expected bad input, got {:?}", other.map(|c| c.model)),
        }
    }

    #[test]
    fn layer_plastic_3bl_example_matches_contacts_forces() {
        let case = Case::from_toml(EXAMPLE).unwrap();
        let layer = case.settings.interfacial_layer.expect("the layer");
        assert_eq!(layer.thickness_m, 2.0e-5);
        assert_eq!(layer.hardening_pa_per_m, 4.35e11);
        let run = ExactRun::solve(&case).unwrap();
        assert_eq!(run.solutions().len(), CLAY_FX.len());
        for (k, (s, (fx, _))) in run.solutions().iter().zip(CLAY_FX).enumerate() {
            let want: f64 = fx.parse().unwrap();
            assert_eq!(s.info.status, SolveStatus::Converged, "case {}", 15 + k);
            assert!(
                (s.totals.fx_n - want).abs() <= half_unit(fx) * (1.0 + 1e-9),
                "case {}: FX {} N against CONTACT's {fx}",
                15 + k,
                s.totals.fx_n
            );
            assert!((s.totals.normal_force_n - 900.0).abs() < 1e-6 * 900.0);
        }
        // The last step (case 31) flows: one plastic element of 1 mm²,
        // tau_c = FX / 1 mm² = 424.1 N/mm² as CONTACT prints.
        let report = run.report(&case, true);
        let l = report
            .interfacial_layer
            .as_ref()
            .expect("a plastic layer's state");
        assert_eq!(l.plastic_elements, 1);
        assert!((l.plastic_area_m2 - 1e-6).abs() < 1e-15);
        assert!((l.max_yield_limit_pa - 424.1e6).abs() <= 0.05e6 * (1.0 + 1e-9));
        assert_eq!(l.min_yield_limit_pa, 2.0e8);
        // tau_c = tau_c0 + k_tau u_pl.
        let u_pl = (l.max_yield_limit_pa - 2.0e8) / 4.35e11;
        assert!((l.max_plastic_deformation_m - u_pl).abs() <= 1e-9 * u_pl);
        let json = serde_json::to_value(&report).unwrap();
        let fields = &json["interfacial_layer"]["fields"];
        assert_eq!(fields["yield_limit_pa"].as_array().unwrap().len(), 25);
        assert_eq!(fields["plastic"][12], serde_json::Value::Bool(true));
        assert!(run
            .report(&case, false)
            .interfacial_layer
            .unwrap()
            .fields
            .is_none());
        assert!(report.human().contains("layer plastic area"));
    }

    /// A rolling ellipse with `section` (TOML) under models fastsim and
    /// hertz: refused naming `key` and the model (only the exact model
    /// takes the section).
    pub(super) fn only_the_exact_model_takes(key: &str, section: &str) {
        for model in ["fastsim", "hertz"] {
            let m = message(Case::from_toml(&format!(
                "model = \"{model}\"\n[material]\nshear_modulus_pa = 81.0e9\npoisson_ratio = 0.3\n\
                 [friction]\ncoefficient = 0.3\n[geometry]\nkind = \"quadratic\"\na_per_m = 1.0\n\
                 b_per_m = 1.0\n[load]\nnormal_force_n = 1e4\n[rolling]\ncreepage_long = 1e-3\n\
                 {section}"
            )));
            assert!(m.contains(&format!("`{key}`")) && m.contains(model), "{m}");
        }
    }

    #[test]
    fn a_bad_layer_value_is_refused_naming_its_key() {
        for (from, to, key) in [
            (
                "thickness_m = 2.0e-5",
                "thickness_m = -1e-5",
                "interfacial_layer.thickness_m",
            ),
            (
                "shear_modulus_pa = 1.0625e8",
                "shear_modulus_pa = 0.0",
                "interfacial_layer.shear_modulus_pa",
            ),
            (
                "yield_limit_pa = 2.0e8",
                "yield_limit_pa = -1.0",
                "interfacial_layer.yield_limit_pa",
            ),
            (
                "hardening_pa_per_m = 4.35e11",
                "hardening_pa_per_m = nan",
                "interfacial_layer.hardening_pa_per_m",
            ),
            // A plastic layer needs one friction coefficient.
            (
                "coefficient = 0.7",
                "static_coefficient = 0.7\nkinetic_coefficient = 0.6",
                "interfacial_layer.yield_limit_pa",
            ),
            (
                "hardening_pa_per_m = 4.35e11",
                "hardening = 1.0",
                "hardening",
            ),
        ] {
            assert!(EXAMPLE.contains(from), "{from}");
            let m = message(Case::from_toml(&EXAMPLE.replacen(from, to, 1)));
            assert!(m.contains(key), "{to}: {m}");
        }
        only_the_exact_model_takes(
            "interfacial_layer",
            "[interfacial_layer]\nthickness_m = 2e-5\nshear_modulus_pa = 1e8\n",
        );
        // Without a yield limit the layer is elastic; without thickness_m
        // the section is incomplete.
        let elastic = EXAMPLE
            .replacen("yield_limit_pa = 2.0e8\n", "", 1)
            .replacen("hardening_pa_per_m = 4.35e11\n", "", 1);
        let c = Case::from_toml(&elastic).unwrap();
        assert!(!c.settings.interfacial_layer.unwrap().is_plastic());
        let m = message(Case::from_toml(&EXAMPLE.replacen(
            "thickness_m = 2.0e-5\n",
            "",
            1,
        )));
        assert!(m.contains("thickness_m"), "{m}");
    }
}

#[cfg(test)]
mod viscoelastic_tests {
    use crate::core::solution::{ElementState, SolveStatus};
    use crate::problem::case::*;
    use crate::problem::ExactRun;

    use super::layer_tests::{message, only_the_exact_model_takes};

    const EXAMPLE: &str = include_str!("../../../../../examples/cases/visc_cylindr.toml");

    #[test]
    fn visc_cylindr_example_matches_contacts_case_3() {
        // visc_cylindr.ref_out, case 3 (TC = 0.045 s): CREEP X 1.152E-02,
        // PMAX 84.72 N/mm², NCON 57, NADH 36, NSLIP 21 (the example gives
        // CONTACT's gap at its element centres).
        let case = Case::from_toml(EXAMPLE).unwrap();
        let visc = case.settings.viscoelastic.expect("viscoelastic bodies");
        assert_eq!(visc.body2.creep_relaxation_time_s, 0.045);
        let run = ExactRun::solve(&case).unwrap();
        let s = run.last();
        assert_eq!(s.info.status, SolveStatus::Converged);
        let xi = run
            .force_control
            .as_ref()
            .expect("Fx prescribed")
            .creepage_long;
        assert!((xi / 1.152e-2 - 1.0).abs() < 0.01, "creepage {xi}");
        assert!((s.totals.max_pressure_pa / 84.72e6 - 1.0).abs() < 0.01);
        let n = |st: ElementState| s.fields.state.iter().filter(|&&e| e == st).count();
        let contact = s.fields.pressure_pa.iter().filter(|&&p| p > 0.0).count();
        for (got, want) in [
            (contact, 57),
            (n(ElementState::Adhesion), 36),
            (n(ElementState::Slip), 21),
        ] {
            assert!(got.abs_diff(want) <= 2, "{got} vs CONTACT's {want}");
        }
    }

    #[test]
    fn viscoelastic_bodies_are_refused_where_they_are_not_taken() {
        for (from, to, key) in [
            (
                "relaxation_ratio = 1.0",
                "relaxation_ratio = -1.0",
                "viscoelastic.body1.relaxation_ratio",
            ),
            // Over 1e6 (1e300 made the forces non-finite).
            (
                "relaxation_ratio = 1.0",
                "relaxation_ratio = 1.0e7",
                "viscoelastic.body1.relaxation_ratio",
            ),
            (
                "creep_relaxation_time_s = 0.045\n\n[grid]",
                "creep_relaxation_time_s = inf\n\n[grid]",
                "viscoelastic.body2.creep_relaxation_time_s",
            ),
            (
                "rolling_speed_m_per_s = 1.0",
                "rolling_speed_m_per_s = 0.0",
                "viscoelastic.rolling_speed_m_per_s",
            ),
            // CONTACT's M = 1 rolls in +x only (CHI = 0).
            (
                "model = \"exact\"",
                "model = \"exact\"\nrolling_direction_rad = 3.141592653589793",
                "`rolling_direction_rad`",
            ),
            // Steady rolling only: not transient steps.
            (
                "[rolling]\nforce_x_n_per_m = -1.08e5",
                "[transient]\nsteps = [{ shift_x_m = 1e-6 }]",
                "`viscoelastic`",
            ),
            ("relaxation_ratio = 1.0", "ratio = 1.0", "ratio"),
        ] {
            assert!(EXAMPLE.contains(from), "{from}");
            let m = message(Case::from_toml(&EXAMPLE.replacen(from, to, 1)));
            assert!(m.contains(key), "{to}: {m}");
        }
        only_the_exact_model_takes(
            "viscoelastic",
            "[viscoelastic]\nrolling_speed_m_per_s = 1.0\n[viscoelastic.body1]\n\
             relaxation_ratio = 1.0\ncreep_relaxation_time_s = 0.01\n",
        );
        // The frictionless normal problem of the rolling bodies is taken;
        // a body left out is elastic.
        let c = Case::from_toml(
            &EXAMPLE
                .replacen("[rolling]\nforce_x_n_per_m = -1.08e5\n", "", 1)
                .replacen(
                    "[viscoelastic.body2]\nrelaxation_ratio = 1.0\ncreep_relaxation_time_s = 0.045\n",
                    "",
                    1,
                ),
        )
        .unwrap();
        assert!(matches!(c.kinematics, Kinematics::Frictionless));
        assert!(c.settings.viscoelastic.unwrap().body2.is_elastic());
        assert!(ExactRun::solve(&c).is_ok());
    }

    #[test]
    fn a_surface_grid_over_128_x_128_is_refused_by_the_case_before_a_solver_is_built() {
        // The case's validation refuses it (in microseconds), not the
        // solve after `ContactSolver::new` integrated the coefficients
        // (seconds); 128 x 128 and elastic bodies on 129 x 129 pass it.
        let sphere = |n: usize, ratio: f64| {
            format!(
                "model = \"exact\"\n[material]\nshear_modulus_pa = 81.0e9\npoisson_ratio = 0.3\n\
                 [friction]\ncoefficient = 0.3\n[geometry]\nkind = \"quadratic\"\na_per_m = 1.0\n\
                 b_per_m = 1.0\n[load]\nnormal_force_n = 1e4\n[rolling]\ncreepage_long = 1e-3\n\
                 [grid]\nnx = {n}\nny = {n}\n\
                 [viscoelastic]\nrolling_speed_m_per_s = 1.0\n[viscoelastic.body1]\n\
                 relaxation_ratio = {ratio:?}\ncreep_relaxation_time_s = 0.01\n"
            )
        };
        let m = message(Case::from_toml(&sphere(129, 1.0)));
        assert!(
            m.contains("`viscoelastic`") && m.contains("129 x 129"),
            "{m}"
        );
        assert!(Case::from_toml(&sphere(128, 1.0)).is_ok());
        assert!(Case::from_toml(&sphere(129, 0.0)).is_ok());
    }
}
