"""Pressure, traction and adhesion/slip maps of one rolling contact patch
(Kalker's exact theory), from the per-element fields of SolvePatch.

The case is examples/cases/hertz_ellipse_rolling.toml (elliptic Hertz
geometry, 10 kN, mu = 0.3) with longitudinal, lateral and spin creepage.
Rolling direction +x: material enters at the leading edge (right) and
adheres; it slides near the trailing edge (left). Tractions are those on
the rail. The maps are drawn to scale (equal x and y axes).

Ctrl-C before the answer stops it without writing anything (one solve).
"""

import pathlib
import sys

import numpy as np

from _common import connect, nothing_to_save, parser, plt, save

import railcontact

CASE = pathlib.Path(__file__).resolve().parents[3] / "examples" / "cases" / "hertz_ellipse_rolling.toml"


def main(argv=None):
    p = parser(__doc__, "patch_maps.png")
    p.add_argument("--n", type=int, default=40, help="elements in x and y (default %(default)s)")
    p.add_argument("--creepages", type=float, nargs=3, default=(1e-3, 5e-4, 0.3),
                   metavar=("XI", "ETA", "PHI_PER_M"), help="creepages (default %(default)s)")
    args = p.parse_args(argv)
    case = railcontact.load_case(CASE)
    case["rolling"] = dict(zip(("creepage_long", "creepage_lat", "spin_per_m"), args.creepages))
    case["grid"] = {"nx": args.n, "ny": args.n}
    try:
        with connect(args.target) as client:
            r = client.solve_patch(case, include_fields=True)
    except KeyboardInterrupt:
        nothing_to_save("before the solve's answer")
    t, f, g = r.totals, r.fields, r.grid
    print(f"Fx = {t.fx_n:.1f} N, Fy = {t.fy_n:.1f} N, p_max = {t.max_pressure_pa / 1e6:.0f} MPa, "
          f"adhesion {t.adhesion_fraction:.0%}, {r.result.info.status}")
    mm = np.array(g.extent_m()) * 1e3
    fig, axes = plt.subplots(1, 3, figsize=(12, 4.4))
    show = dict(origin="lower", extent=mm, aspect="equal")

    im = axes[0].imshow(np.ma.masked_equal(f.pressure_pa, 0) / 1e6, cmap="viridis", **show)
    fig.colorbar(im, ax=axes[0], label="pressure [MPa]")
    axes[0].set_title("pressure")

    traction = np.ma.masked_where(f.state == railcontact.EXTERIOR, f.traction_pa / 1e6)
    im = axes[1].imshow(traction, cmap="magma", **show)
    fig.colorbar(im, ax=axes[1], label="|traction| [MPa]")
    x, y = np.meshgrid(g.x_m() * 1e3, g.y_m() * 1e3)
    step = max(1, args.n // 12)
    inside = (f.state != railcontact.EXTERIOR)[::step, ::step]
    axes[1].quiver(x[::step, ::step][inside], y[::step, ::step][inside],
                   f.traction_x_pa[::step, ::step][inside], f.traction_y_pa[::step, ::step][inside],
                   color="tab:cyan", angles="xy", scale_units="xy", width=0.006,
                   scale=f.traction_pa.max() / (2.0 * step * g.element_size_x_m * 1e3))
    axes[1].set_title("tangential traction on the rail")

    colours = plt.matplotlib.colors.ListedColormap(["white", "tab:blue", "tab:red"])
    axes[2].imshow(f.state, cmap=colours, vmin=-0.5, vmax=2.5, **show)
    legend = (("tab:blue", "adhesion"), ("tab:red", "slip"))
    handles = [plt.matplotlib.patches.Patch(color=c, label=n) for c, n in legend]
    # Below the map: in a corner it would cover the patch's edge.
    axes[2].legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2, fontsize=8,
                   frameon=False)
    axes[2].set_title(f"adhesion / slip ({t.adhesion_fraction:.0%} adhesion)")
    for ax in axes:
        ax.set(xlabel="x (rolling) [mm]", ylabel="y [mm]")
    xi, eta, phi = args.creepages
    fig.suptitle(f"exact, {g.nx} x {g.ny}: xi = {xi:g}, eta = {eta:g}, phi = {phi:g} 1/m; "
                 f"Fx = {t.fx_n / 1e3:.2f} kN, Fy = {t.fy_n / 1e3:.2f} kN on the rail")
    save(fig, args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
