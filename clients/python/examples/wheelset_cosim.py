"""Co-simulation of a wheelset on tangent track: the dynamics are integrated
here, in Python, and the wheel/rail contact is solved by the server at every
time step through one WheelRailSession.

The model (SI units; track frame x forward, y to the right, z down; yaw
psi > 0 turns the forward direction to the right, as the proto's
WheelsetPosition says):

* a wheelset of mass m and yaw inertia I_z rolling at constant speed V on
  the built-in pair (S1002 on UIC60), free rolling at the nominal radius
  (pitch rate -V / r0), each wheel pressed on its rail by the load Q;
* a primary suspension to a bogie frame that runs straight along the track
  centre: lateral spring k_y and damper c_y, yaw spring k_psi and damper
  c_psi;
* the contact forces from the server. They act on the rails, so the force on
  the wheelset is minus their sum, and its yaw moment about the wheelset
  centre is sum(r_y F_x - r_x F_y) over the patches (r from the centre to
  the patch's reference point, F the force on the rail):

      m   y''   = -k_y y     - c_y y'       + F_y
      I_z psi'' = -k_psi psi - c_psi psi'   + M_z

Creep forces act like very stiff dampers (time constants of milliseconds),
so an explicit step would need microseconds. The step is linearly implicit
in the velocities instead: (M - dt C) dv = dt F(x_n, v_n), x_{n+1} = x_n +
dt v_{n+1}, with C the Jacobian of the forces with respect to (y', psi').
C is measured on the server by finite differences every --jacobian-every
steps with the session's marks: the step is marked, two probe steps with
perturbed velocities follow, and a rollback returns to the mark (the warm
starts go back with it), so the probes leave no trace.

Starting 3 mm off centre, the wheelset performs the damped kinematic
(Klingel) oscillation of a coned wheelset.

Ctrl-C stops the integration: the session is closed and the steps done so
far are plotted.
"""

import sys

import numpy as np

from _common import INTERRUPTED, StopOnCtrlC, connect, nothing_to_save, parser, plt, save, wheelrail_model

import railcontact

NOMINAL_RADIUS_M = 0.46  # of the built-in pair


def wheelset_loads(result, lateral_m):
    """(F_y, M_z) on the wheelset [N, N m] from a WheelRailResult."""
    fy, mz = 0.0, 0.0
    for wheel in result.wheels:
        for patch in wheel.patches:
            f = patch.force_track_n
            rx, ry = patch.track_x_m, patch.track_y_m - lateral_m
            fy -= f.y_n
            mz += ry * f.x_n - rx * f.y_n
    return np.array([fy, mz])


class Wheelset:
    """The wheelset's state and parameters; q = (y, psi), v = (y', psi')."""

    def __init__(self, args):
        self.mass = np.diag([args.mass, args.yaw_inertia])
        self.stiffness = np.diag([args.k_lateral, args.k_yaw])
        self.damping = np.diag([args.c_lateral, args.c_yaw])
        self.speed = args.speed
        self.load = args.load
        self.q = np.array([args.y0, 0.0])
        self.v = np.zeros(2)

    def contact_inputs(self, q, v):
        return dict(
            position={"lateral_m": q[0], "yaw_rad": q[1]},
            velocity={
                "forward_m_per_s": self.speed,
                "lateral_m_per_s": v[0],
                "yaw_rad_per_s": v[1],
                "pitch_rad_per_s": -self.speed / NOMINAL_RADIUS_M,
            },
            load={"vertical_force_n": self.load},
        )

    def suspension(self, q, v):
        return -self.stiffness @ q - self.damping @ v


def contact_jacobian(session, wheelset, base_loads, time_s, marked_index):
    """d(F_y, M_z)/d(y', psi') by forward differences on the server, from the
    marked step ``marked_index``; the session is rolled back to it after
    each probe."""
    jacobian = np.zeros((2, 2))
    for j, delta in enumerate((1e-3, 1e-3)):  # [m/s], [rad/s]
        v = wheelset.v.copy()
        v[j] += delta
        probe = session.step(time_s=time_s, **wheelset.contact_inputs(wheelset.q, v))
        jacobian[:, j] = (wheelset_loads(probe.result, wheelset.q[0]) - base_loads) / delta
        session.rollback(marked_index)
    return jacobian


def simulate(session, wheelset, dt, steps, jacobian_every):
    """Integrates ``steps`` steps; returns the history as a dict of arrays
    and whether Ctrl-C stopped it early (the history then holds the steps
    done; the session has ended)."""
    history = {k: [] for k in ("t", "y", "psi", "fy_contact", "mz_contact", "q_left", "q_right", "fy_left", "fy_right")}
    jacobian = np.zeros((2, 2))
    report_every = max(1, steps // 10)
    interrupted = False
    try:
        with StopOnCtrlC() as stop:
            for n in range(steps):
                if stop.requested:
                    interrupted = True
                    break
                t = n * dt
                if n % report_every == 0:
                    print(f"step {n} of {steps} (t = {t:.3f} s)", file=sys.stderr, flush=True)
                refresh = n % jacobian_every == 0
                r = session.step(time_s=t, mark=refresh, **wheelset.contact_inputs(wheelset.q, wheelset.v))
                contact = wheelset_loads(r.result, wheelset.q[0])
                if refresh:
                    jacobian = contact_jacobian(session, wheelset, contact, t, r.step_index)
                force = wheelset.suspension(wheelset.q, wheelset.v) + contact
                system = wheelset.mass - dt * (jacobian - wheelset.damping)
                wheelset.v = wheelset.v + np.linalg.solve(system, dt * force)
                left, right = r.result.wheel("left"), r.result.wheel("right")
                for key, value in (
                    ("t", t), ("y", wheelset.q[0]), ("psi", wheelset.q[1]),
                    ("fy_contact", contact[0]), ("mz_contact", contact[1]),
                    ("q_left", sum(p.normal_force_n for p in left.patches)),
                    ("q_right", sum(p.normal_force_n for p in right.patches)),
                    ("fy_left", -left.force_track_n.y_n), ("fy_right", -right.force_track_n.y_n),
                ):
                    history[key].append(value)
                wheelset.q = wheelset.q + dt * wheelset.v
    except KeyboardInterrupt:
        interrupted = True
    done = min(len(v) for v in history.values())  # a step interrupted while recorded is dropped
    return {k: np.array(v[:done]) for k, v in history.items()}, interrupted


def main(argv=None):
    p = parser(__doc__, "wheelset_cosim.png")
    p.add_argument("--model", default="hertz_fastsim", type=wheelrail_model,
                   help=f"contact model, one of {', '.join(railcontact.WHEELRAIL_MODELS)} (default %(default)s)")
    p.add_argument("--element-size", type=float, default=None,
                   help="patch element size [m] of the exact model (default: the pair's 2e-4; 5e-4 is much faster)")
    p.add_argument("--duration", type=float, default=1.0, help="simulated time [s] (default %(default)s)")
    p.add_argument("--dt", type=float, default=1e-3, help="time step [s] (default %(default)s)")
    p.add_argument("--steps", type=int, default=None, help="number of steps (overrides --duration)")
    p.add_argument("--jacobian-every", type=int, default=50,
                   help="steps between Jacobian updates (default %(default)s)")
    p.add_argument("--speed", type=float, default=30.0, help="forward speed V [m/s] (default %(default)s)")
    p.add_argument("--load", type=float, default=1e5, help="vertical load per wheel Q [N] (default %(default)s)")
    p.add_argument("--y0", type=float, default=3e-3, help="initial lateral offset [m] (default %(default)s)")
    p.add_argument("--mass", type=float, default=1500.0, help="wheelset mass m [kg] (default %(default)s)")
    p.add_argument("--yaw-inertia", type=float, default=700.0, help="I_z [kg m^2] (default %(default)s)")
    p.add_argument("--k-lateral", type=float, default=1.0e6, help="k_y [N/m] (default %(default)s)")
    p.add_argument("--c-lateral", type=float, default=1.0e4, help="c_y [N s/m] (default %(default)s)")
    p.add_argument("--k-yaw", type=float, default=2.0e6, help="k_psi [N m/rad] (default %(default)s)")
    p.add_argument("--c-yaw", type=float, default=1.0e3, help="c_psi [N m s/rad] (default %(default)s)")
    args = p.parse_args(argv)
    steps = args.steps if args.steps is not None else int(round(args.duration / args.dt))
    wheelset = Wheelset(args)
    h, interrupted = None, False
    try:
        with connect(args.target) as client:
            opened = client.wheelrail_session(
                railcontact.BUILTIN_PAIR, model=args.model, element_size_m=args.element_size, label="wheelset_cosim"
            )
            with opened as session:
                h, interrupted = simulate(session, wheelset, args.dt, steps, args.jacobian_every)
    except KeyboardInterrupt:
        interrupted = True  # while connecting, opening or closing
    done = 0 if h is None else len(h["t"])
    if done == 0:
        nothing_to_save("before the first step")
    print(f"{done} steps of {args.dt * 1e3:g} ms ({args.model}): y from {h['y'][0] * 1e3:.2f} mm "
          f"to {h['y'][-1] * 1e3:.3f} mm, largest |F_y| {np.abs(h['fy_contact']).max() / 1e3:.1f} kN")

    fig, axes = plt.subplots(3, 1, figsize=(10.5, 8), sharex=True)
    axes[0].plot(h["t"], h["y"] * 1e3, label="lateral y [mm]")
    axes[0].plot(h["t"], h["psi"] * 1e3, label="yaw psi [mrad]")
    axes[0].set(ylabel="displacement")
    axes[1].plot(h["t"], h["fy_contact"] / 1e3, label="total F_y\non wheelset")
    axes[1].plot(h["t"], h["fy_left"] / 1e3, lw=0.8, label="left wheel")
    axes[1].plot(h["t"], h["fy_right"] / 1e3, lw=0.8, label="right wheel")
    axes[1].set(ylabel="lateral contact force [kN]")
    axes[2].plot(h["t"], h["q_left"] / 1e3, label="left wheel")
    axes[2].plot(h["t"], h["q_right"] / 1e3, label="right wheel")
    axes[2].set(ylabel="normal force [kN]", xlabel="time [s]")
    for ax in axes:
        ax.grid(alpha=0.3)
        # Beside the axes: the curves fill them from end to end.
        ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)
    stopped = f", interrupted at t = {h['t'][-1]:.3f} s" if interrupted else ""
    fig.suptitle(f"Wheelset on tangent track, V = {args.speed} m/s, {args.model}, dt = {args.dt * 1e3:g} ms{stopped}")
    save(fig, args.out, interrupted=f"{done} of {steps} steps" if interrupted else "")
    return INTERRUPTED if interrupted else 0


if __name__ == "__main__":
    sys.exit(main())
