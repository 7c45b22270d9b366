"""Creep-force curves of the built-in wheel/rail pair (S1002 wheel on UIC60
rail, Manchester benchmark), centred wheelset, 100 kN per wheel.

Lateral: the wheelset moves sideways at v_y while rolling at V, which gives
both wheels a lateral creepage of about -v_y / V; longitudinal: the axle
turns faster or slower than free rolling, pitch rate -(V / r0)(1 + s) for a
relative slip s. Plotted are the total forces on the wheelset (minus the sum
over the rails) over the total vertical load, which approach the friction
coefficient (0.3) at full sliding. All points of a curve go in one
SolveWheelRailBatch call, solved in parallel on the server.
"""

import numpy as np

from _common import connect, parser, plt, save

import railcontact

NOMINAL_RADIUS_M = 0.46  # of the built-in pair's wheelset


def sweep(client, model, slips, load_n, speed, element_size_m):
    """Total force on the wheelset / total vertical load for each slip, as
    (lateral, longitudinal) arrays."""
    base = {"model": model, "load": load_n, "element_size_m": element_size_m}
    lateral = [dict(base, velocity={"forward_m_per_s": speed, "lateral_m_per_s": -s * speed}) for s in slips]
    longitudinal = [
        dict(base, velocity={"forward_m_per_s": speed, "pitch_rad_per_s": -(speed / NOMINAL_RADIUS_M) * (1 + s)})
        for s in slips
    ]
    out = []
    for queries, axis in ((lateral, 1), (longitudinal, 0)):
        results = client.solve_wheelrail_batch(queries)
        for r in results:
            if isinstance(r, railcontact.RailcontactError):
                raise r
        out.append(np.array([-r.force_track_n[axis] / r.force_track_n[2] for r in results]))
    return out


def main(argv=None):
    p = parser(__doc__, "creep_curve.png")
    p.add_argument("--points", type=int, default=13, help="points per curve (default %(default)s)")
    p.add_argument("--max-slip", type=float, default=0.006, help="largest creepage [-] (default %(default)s)")
    p.add_argument("--models", default="hertz_fastsim,exact", help="comma-separated (default %(default)s)")
    p.add_argument("--element-size", type=float, default=5e-4, help="patch element size [m] (default %(default)s)")
    p.add_argument("--speed", type=float, default=30.0, help="forward speed [m/s] (default %(default)s)")
    p.add_argument("--load", type=float, default=1e5, help="vertical force per wheel [N] (default %(default)s)")
    args = p.parse_args(argv)
    slips = np.linspace(0.0, args.max_slip, args.points)
    fig, axes = plt.subplots(1, 2, figsize=(10, 4), sharey=True)
    with connect(args.target) as client:
        for model in args.models.split(","):
            lateral, longitudinal = sweep(client, model, slips, args.load, args.speed, args.element_size)
            axes[0].plot(slips * 100, longitudinal, "o-", ms=3, label=model)
            axes[1].plot(slips * 100, lateral, "o-", ms=3, label=model)
            print(f"{model}: Fx/Fz at {slips[-1]:.3g}: {longitudinal[-1]:.3f}, Fy/Fz: {lateral[-1]:.3f}")
    axes[0].set(xlabel="longitudinal slip s = -(omega r0 / V) - 1 [%]", ylabel="force on wheelset / vertical load [-]")
    axes[0].set_title("longitudinal (traction)")
    axes[1].set(xlabel="lateral slip v_y / V [%]")
    axes[1].set_title("lateral")
    for ax in axes:
        ax.axhline(0.3, color="grey", lw=0.8, ls="--")
        ax.grid(alpha=0.3)
        ax.legend()
    fig.suptitle(f"{railcontact.BUILTIN_PAIR}: centred wheelset, {args.load / 1e3:.0f} kN per wheel, "
                 f"V = {args.speed} m/s")
    save(fig, args.out)


if __name__ == "__main__":
    main()
