"""Conformal contact across models: Case 1 of Blanco-Lorenzo et al. (2018)
(examples/cases/conformal_case1_frictionless.toml: rail crown R_yr = 10 mm
in a hollow wheel R_yw = -10.1 mm, R_xw = 500 mm, frictionless), loaded from
a few kN to 200 kN.

Compared: the conformal exact theory (cect, Blanco's influence
coefficients; cect_halfspace, plain half-space coefficients), Kalker's exact
theory on the flattened gap (exact: no conformal effects), plain Hertz and
Hertz with the corrected lateral curvature (paper Eq. 5). As in the paper
(and docs/conformal_study.md), plain Hertz underestimates the maximum
pressure and the approach and overestimates the contact angle variation
as the patch wraps around the rail crown; the corrected Hertz comes close
to cect. Each model's loads go in one SolvePatchBatch call.

The exact theory on the flattened gap and plain Hertz agree to a fraction
of a percent here: exact is drawn on top of hertz (small filled markers on
a dashed line over large open ones) so that both show.

Ctrl-C stops the sweep: the models done so far are plotted.
"""

import pathlib
import sys

import numpy as np

from _common import INTERRUPTED, connect, nothing_to_save, parser, plt, save

import railcontact

CASE = pathlib.Path(__file__).resolve().parents[3] / "examples" / "cases" / "conformal_case1_frictionless.toml"
MODELS = ("cect", "cect_halfspace", "exact", "hertz", "hertz_corrected")

#: How each model is drawn: exact over hertz (they nearly coincide).
STYLES = {
    "cect": dict(marker="o", ms=4),
    "cect_halfspace": dict(marker="s", ms=4),
    "exact": dict(marker="o", ms=3.5, ls="--", lw=1.2, zorder=4),
    "hertz": dict(marker="o", ms=9, mfc="none", mew=1.3, lw=2.5, alpha=0.8, zorder=2),
    "hertz_corrected": dict(marker="^", ms=5),
}


def main(argv=None):
    p = parser(__doc__, "conformal_models.png")
    p.add_argument("--loads", type=int, default=10, help="number of loads (default %(default)s)")
    p.add_argument("--max-load", type=float, default=200e3, help="largest normal force [N] (default %(default)s)")
    p.add_argument("--grid", type=int, nargs=2, default=(72, 94), metavar=("NX", "NY"),
                   help="grid of the gridded models (default %(default)s, the case file's)")
    args = p.parse_args(argv)
    base = railcontact.load_case(CASE)
    loads = np.geomspace(args.max_load / 40, args.max_load, args.loads)
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.2))
    done = []
    try:
        with connect(args.target) as client:
            for i, model in enumerate(MODELS):
                case = dict(base, model=model)
                if model.startswith("hertz"):
                    case.pop("grid")  # closed form: no grid
                else:
                    case["grid"] = {"nx": args.grid[0], "ny": args.grid[1]}
                cases = [dict(case, load={"normal_force_n": f}) for f in loads]
                results = client.solve_patch_batch(cases)
                for r in results:
                    if isinstance(r, railcontact.RailcontactError):
                        raise r
                kn = loads / 1e3
                style = dict(STYLES[model], label=model, color=f"C{i}")
                axes[0].plot(kn, [r.totals.max_pressure_pa / 1e6 for r in results], **style)
                axes[1].plot(kn, [r.totals.approach_m * 1e6 for r in results], **style)
                if results[0].result.conformal is not None:
                    axes[2].plot(kn, [r.result.conformal.contact_angle_variation_deg for r in results], **style)
                done.append(model)
                last = results[-1]
                print(f"{model:16s} at {kn[-1]:.0f} kN: p_max {last.totals.max_pressure_pa / 1e6:7.0f} MPa, "
                      f"approach {last.totals.approach_m * 1e6:6.1f} um")
    except KeyboardInterrupt:
        if not done:
            nothing_to_save("during the first model's loads")
    interrupted = len(done) < len(MODELS)
    axes[0].set(ylabel="max pressure [MPa]", title="maximum pressure")
    axes[1].set(ylabel="approach [um]", title="approach along n(0)")
    axes[2].set(ylabel="contact angle variation [deg]", title="contact angle variation")
    for ax in axes:
        ax.set(xlabel="normal force [kN]")
        ax.grid(alpha=0.3)
    # The curves rise from the lower left: legends in the upper left of the
    # first two panels (the largest values lie right), the lower right of
    # the third (its curves flatten at the top).
    axes[0].legend(fontsize=8, loc="upper left")
    axes[1].legend(fontsize=8, loc="upper left")
    axes[2].legend(fontsize=8, loc="lower right")
    fig.suptitle("Conformal Case 1 (R_yr = 10 mm, R_yw = -10.1 mm, R_xw = 500 mm), frictionless")
    save(fig, args.out, interrupted=f"{len(done)} of {len(MODELS)} models" if interrupted else "")
    return INTERRUPTED if interrupted else 0


if __name__ == "__main__":
    sys.exit(main())
