"""Creep-force curves of the built-in wheel/rail pair (S1002 wheel on UIC60
rail, Manchester benchmark), centred wheelset, 100 kN per wheel.

Lateral: the wheelset moves sideways at v_y while rolling at V, which gives
both wheels a lateral creepage of about -v_y / V; longitudinal: the axle
turns faster or slower than free rolling, pitch rate -(V / r)(1 + s) for a
relative slip s, with r the rolling radius at the contact point (asked of
the server first: 0.45991 m, not the nominal 0.46 m, whose pitch rate would
already be a creepage of -2e-4). Plotted are the total forces on the
wheelset (minus the sum over the rails) over the total vertical load, which
approach the friction coefficient (0.3) at full sliding. All points of a
curve go in one SolveWheelRailBatch call, solved in parallel on the server.

Why the exact longitudinal curve does not start at zero: the contact is
inclined (contact angle 0.024 rad), so the rolling wheel also spins about the
contact normal (spin 0.053 /m): the slip grows linearly across the patch's
width. On a patch symmetric about its centre line (Hertz's ellipse) that
gives no longitudinal force in total, and Hertz+FASTSIM starts at Fx/Fz =
0.0002; the exact patch of these profiles is not symmetric (it spans -13 to +7 mm
across the rail about the point the rolling radius is taken at, its pressure
centre 3.1 mm off that point), and the same spin, times that offset, acts
as a longitudinal creepage of about 1.6e-4: Fx/Fz = 0.029 at s = 0.
The lateral forces of spin are equal and opposite on the two wheels and
cancel in the total, so both lateral curves start at 0.

Ctrl-C stops the sweep: the curves of the models done so far are plotted.
"""

import sys

import numpy as np

from _common import INTERRUPTED, connect, nothing_to_save, parser, plt, save, wheelrail_model

import railcontact

NOMINAL_RADIUS_M = 0.46  # of the built-in pair's wheelset


def rolling_radius(client, base, speed):
    """The rolling radius at the centred wheelset's contact point [m]."""
    probe = client.solve_wheelrail_batch(
        [dict(base, velocity={"forward_m_per_s": speed, "pitch_rad_per_s": -speed / NOMINAL_RADIUS_M})]
    )[0]
    if isinstance(probe, railcontact.RailcontactError):
        raise probe
    return probe.wheels[0].patches[0].rolling_radius_m


def sweep(client, model, slips, load_n, speed, element_size_m):
    """Total force on the wheelset / total vertical load for each slip, as
    (lateral, longitudinal) arrays."""
    base = {"model": model, "load": load_n, "element_size_m": element_size_m}
    radius = rolling_radius(client, base, speed)
    lateral = [dict(base, velocity={"forward_m_per_s": speed, "lateral_m_per_s": -s * speed}) for s in slips]
    longitudinal = [
        dict(base, velocity={"forward_m_per_s": speed, "pitch_rad_per_s": -(speed / radius) * (1 + s)})
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
    p.add_argument("--models", default="hertz_fastsim,exact",
                   help=f"comma-separated, of {', '.join(railcontact.WHEELRAIL_MODELS)} (default %(default)s)")
    p.add_argument("--element-size", type=float, default=5e-4, help="patch element size [m] (default %(default)s)")
    p.add_argument("--speed", type=float, default=30.0, help="forward speed [m/s] (default %(default)s)")
    p.add_argument("--load", type=float, default=1e5, help="vertical force per wheel [N] (default %(default)s)")
    args = p.parse_args(argv)
    try:
        models = [wheelrail_model(m) for m in args.models.split(",")]
    except Exception as e:  # argparse.ArgumentTypeError
        p.error(f"argument --models: {e}")
    slips = np.linspace(0.0, args.max_slip, args.points)
    fig, axes = plt.subplots(1, 2, figsize=(10, 4), sharey=True)
    done = []
    try:
        with connect(args.target) as client:
            for model in models:
                lateral, longitudinal = sweep(client, model, slips, args.load, args.speed, args.element_size)
                axes[0].plot(slips * 100, longitudinal, "o-", ms=3, label=model)
                axes[1].plot(slips * 100, lateral, "o-", ms=3, label=model)
                done.append(model)
                print(f"{model}: Fx/Fz at {slips[-1]:.3g}: {longitudinal[-1]:.3f}, Fy/Fz: {lateral[-1]:.3f}")
    except KeyboardInterrupt:
        if not done:
            nothing_to_save("during the first model's curves")
    interrupted = len(done) < len(models)
    axes[0].set(xlabel="longitudinal slip s = -(omega r / V) - 1 [%]", ylabel="force on wheelset / vertical load [-]")
    axes[0].set_title("longitudinal (traction)")
    axes[1].set(xlabel="lateral slip v_y / V [%]")
    axes[1].set_title("lateral")
    for ax in axes:
        ax.axhline(0.3, color="grey", lw=0.8, ls="--")
        ax.grid(alpha=0.3)
        ax.legend(loc="best")
    fig.suptitle(f"{railcontact.BUILTIN_PAIR}: centred wheelset, {args.load / 1e3:.0f} kN per wheel, "
                 f"V = {args.speed} m/s")
    save(fig, args.out, interrupted=f"{len(done)} of {len(models)} models" if interrupted else "")
    return INTERRUPTED if interrupted else 0


if __name__ == "__main__":
    sys.exit(main())
