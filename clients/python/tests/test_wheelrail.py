"""Wheel/rail calls against the real server: pairs, SolveWheelRail, its
batch and WheelRailSession."""

import pathlib

import grpc
import numpy as np
import pytest

import railcontact

V = 30.0  # forward speed [m/s]
LOAD = 1.0e5  # vertical force per wheel [N]


def test_register_the_builtin_pair_reports_progress(client):
    seen = []
    info = client.register_pair(builtin=railcontact.BUILTIN_PAIR, progress=seen.append)
    assert seen and seen[-1].stage == "ready" and seen[-1].pair == info
    assert info.builtin_pair == railcontact.BUILTIN_PAIR and info.state == "ready"
    assert info.raw.wheel.file_name == "MBench_S1002_v3.prw"
    with pytest.raises(railcontact.RailcontactError) as e:
        client.delete_pair(info.pair_id)
    assert e.value.code == grpc.StatusCode.FAILED_PRECONDITION
    with pytest.raises(railcontact.RailcontactError) as e:
        client.get_pair("0" * 32)
    assert e.value.code == grpc.StatusCode.NOT_FOUND


def test_solve_wheelrail_both_wheels_carry_the_load(client):
    r = client.solve_wheelrail(
        position={"lateral_m": 0.003}, velocity=V, load=LOAD, model="hertz_fastsim"
    )
    assert r.model == "hertz_fastsim" and len(r.pair_id) == 32
    assert [w.side for w in r.wheels] == ["left", "right"]
    for w in r.wheels:
        assert w.force_track_n.z_n == pytest.approx(LOAD, rel=1e-6)
        assert w.patches and all(p.method == "hertz_fastsim" for p in w.patches)
        assert sum(p.normal_force_n for p in w.patches) > 0.9 * LOAD
    total = r.force_track_n
    assert total.shape == (3,) and total[2] == pytest.approx(2 * LOAD, rel=1e-6)
    # Shifted to the right, the wheelset is pushed back to the left: the
    # rails are pushed to the right (gravitational stiffness).
    assert total[1] > 0
    right = r.wheel("right")
    assert right.patches[0].rolling_radius_m > r.wheel("left").patches[0].rolling_radius_m


def test_solve_wheelrail_with_flash_temperatures(client):
    # Rail (body 1) at 20 C, wheel (body 2) at 60 C; steel. Each exact
    # patch reports both surfaces' peaks, the heat of its own frictional
    # power; fields only when asked for.
    steel = {"conductivity_w_per_m_k": 50.0, "density_kg_per_m3": 7850.0, "specific_heat_j_per_kg_k": 450.0}
    temperature = {
        "body1": {"bulk_temperature_k": 293.15, **steel},
        "body2": {"bulk_temperature_k": 333.15, **steel},
    }
    r = client.solve_wheelrail(
        position={"lateral_m": 0.003, "yaw_rad": 0.002},
        velocity=V,
        load=LOAD,
        model="exact",
        temperature=temperature,
    )
    for w in r.wheels:
        for p in w.patches:
            t = p.temperature
            assert t is not None and t.body1_k.size == 0
            assert t.frictional_power_w == pytest.approx(p.frictional_power_w, rel=1e-9)
            assert t.max_body1.temperature_k > 293.15
            assert 293.15 < t.contact_temperature_k < 333.15
            assert 0.0 < p.friction_coefficient
            # The creepages' rolling speed: the mean of the forward and the
            # circumferential speed at the point, within 2 % of the forward
            # speed on the tread (1.6 % above it on a flange).
            assert p.rolling_speed_m_per_s == pytest.approx(V, rel=0.02)
    plain = client.solve_wheelrail(position={"lateral_m": 0.003}, velocity=V, load=LOAD, model="exact")
    assert all(p.temperature is None for w in plain.wheels for p in w.patches)


def test_solve_wheelrail_by_centre_height(client):
    """The centre height of a force-loaded solve, handed back as the load,
    gives the same forces (what an MBS integrator does)."""
    kw = dict(position={"lateral_m": 0.003}, velocity=V, model="hertz_fastsim")
    by_force = client.solve_wheelrail(load=LOAD, **kw)
    approach = by_force.wheels[0].vertical_approach_m
    z = by_force.center_z_m + approach
    by_height = client.solve_wheelrail(load={"center_z_m": z}, **kw)
    for a, b in zip(by_force.wheels, by_height.wheels):
        assert b.vertical_approach_m == pytest.approx(approach, rel=1e-9)
    left = by_height.wheel("left")
    assert left.force_track_n.z_n == pytest.approx(LOAD, rel=1e-6)
    lifted = client.solve_wheelrail(load={"center_z_m": by_force.center_z_m - 1e-4}, **kw)
    assert all(not w.patches for w in lifted.wheels)


def test_solve_wheelrail_for_a_traction_force(client):
    """A prescribed total longitudinal force: the server finds the pitch
    rate; the rails are pushed backwards by a driven wheelset."""
    kw = dict(position={"lateral_m": 0.003}, velocity=V, model="hertz_fastsim")
    r = client.solve_wheelrail(
        load={"vertical_force_n": LOAD, "total_longitudinal_force_n": -2.0e4}, **kw
    )
    c = r.pitch_control
    assert c is not None and c.converged and c.target_force_n == -2.0e4
    assert r.force_track_n[0] == pytest.approx(-2.0e4, abs=1e-6 * 0.3 * 2 * LOAD)
    # Driven: the wheels turn faster than free rolling at 0.46 m.
    assert r.pitch_rad_per_s < -V / 0.46 and c.nominal_creepage > 0
    assert client.solve_wheelrail(load=LOAD, **kw).pitch_control is None
    with pytest.raises(railcontact.RailcontactError) as e:
        client.solve_wheelrail(
            load={"vertical_force_n": LOAD, "total_longitudinal_force_n": -1.0e5}, **kw
        )
    assert e.value.code == grpc.StatusCode.INVALID_ARGUMENT
    assert "load.total_longitudinal_force_n" in str(e.value)


def test_solve_wheelrail_exact_with_fields(client):
    r = client.solve_wheelrail(
        velocity={"forward_m_per_s": V, "lateral_m_per_s": -0.03},
        load={"vertical_force_n": LOAD},
        sides="right",
        element_size_m=5e-4,
        include_fields=True,
    )
    (wheel,) = r.wheels
    patch = wheel.patches[0]
    assert patch.method == "exact" and patch.grid is not None
    assert patch.fields.pressure_pa.shape == (patch.grid.ny, patch.grid.nx)
    # Moving to the left: the rail slides to the right relative to the wheel.
    assert patch.creepage_lat > 0 and patch.fs_n < 0


def test_wheelrail_batch_keeps_order_and_item_errors(client):
    good = {"velocity": V, "load": LOAD, "model": "hertz_fastsim"}
    bad = dict(good, velocity={"forward_m_per_s": 0.0})
    out = client.solve_wheelrail_batch([good, bad, dict(good, position={"lateral_m": 0.002})])
    assert isinstance(out[0], railcontact.WheelRailResult)
    assert isinstance(out[1], railcontact.RailcontactError)
    assert out[1].field == "items[1].velocity.forward_m_per_s"
    assert out[2].force_track_n[1] > 0


def _steps(session, lateral_m, mark_at=None):
    return [
        session.step(
            position={"lateral_m": y},
            velocity={"forward_m_per_s": V, "lateral_m_per_s": 0.01},
            load=LOAD,
            time_s=1e-3 * i,
            mark=(i == mark_at),
        )
        for i, y in enumerate(lateral_m)
    ]


def test_wheelrail_session_steps_mark_and_roll_back(client):
    path = np.linspace(0.0, 0.004, 6)
    with client.wheelrail_session(model="hertz_fastsim", label="pytest") as s:
        assert s.session_id and s.model == "hertz_fastsim" and len(s.pair_id) == 32
        first = _steps(s, path, mark_at=2)
        assert [r.step_index for r in first] == list(range(6)) and first[2].marked
        # The same as independent solves of the same inputs.
        alone = client.solve_wheelrail(
            position={"lateral_m": path[4]},
            velocity={"forward_m_per_s": V, "lateral_m_per_s": 0.01},
            load=LOAD,
            model="hertz_fastsim",
        )
        # (Warm starts change the iterations' path, not the solution.)
        assert np.allclose(first[4].result.force_track_n, alone.force_track_n, rtol=1e-4, atol=1.0)
        assert s.rollback(2) == 3
        again = [
            s.step(position={"lateral_m": y}, velocity={"forward_m_per_s": V, "lateral_m_per_s": 0.01}, load=LOAD)
            for y in path[3:]
        ]
        for a, b in zip(first[3:], again):
            assert a.step_index == b.step_index
            assert np.array_equal(a.result.force_track_n, b.result.force_track_n)
            assert a.result.wheels[0].patches == b.result.wheels[0].patches
        with pytest.raises(railcontact.RailcontactError) as e:
            s.step(velocity=0.0, load=LOAD)
        assert e.value.code == grpc.StatusCode.INVALID_ARGUMENT
        assert e.value.field == "step.velocity.forward_m_per_s"
        with pytest.raises(railcontact.RailcontactError) as e:
            s.rollback(5)
        assert e.value.code == grpc.StatusCode.FAILED_PRECONDITION
        assert s.step(velocity=V, load=LOAD).step_index == 6


def test_wheelrail_session_on_an_unknown_pair_fails_at_open(client):
    with pytest.raises(railcontact.RailcontactError) as e:
        client.wheelrail_session("0" * 32)
    assert e.value.code == grpc.StatusCode.NOT_FOUND


def _mbench_spec(smoothing_wavelength_m):
    """The built-in pair's profiles as a spec of its own (another smoothing
    gives another id)."""
    return {
        "wheel": {"builtin_name": "MBench_S1002_v3.prw"},
        "rail": {"builtin_name": "MBench_UIC60_v3.prr"},
        "track": {"gauge_m": 1.435, "gauge_height_m": 0.014, "cant_rad": 0.0},
        "wheelset": {"flange_back_distance_m": 1.360, "nominal_radius_m": 0.46, "flange_back_y_m": -0.070},
        "smoothing_wavelength_m": smoothing_wavelength_m,
    }


def test_register_solve_and_delete_a_pair_of_its_own(client):
    stages = []
    info = client.register_pair(_mbench_spec(0.003), label="pytest", progress=stages.append)
    names = [p.stage for p in stages]
    assert names[0] == "validated" and names[-1] == "ready" and "placed" in names
    assert [p.fraction_done for p in stages] == sorted(p.fraction_done for p in stages)
    assert info.label == "pytest" and info.persisted and info.smoothing_wavelength_m == 0.003
    again = []
    assert client.register_pair(_mbench_spec(0.003), progress=again.append).pair_id == info.pair_id
    assert again[-1].already_registered
    r = client.solve_wheelrail(info.pair_id, velocity=V, load=LOAD, model="hertz_fastsim")
    assert r.pair_id == info.pair_id and len(r.wheels) == 2
    assert info.pair_id in [p.pair_id for p in client.list_pairs()]
    client.delete_pair(info.pair_id)
    with pytest.raises(railcontact.RailcontactError) as e:
        client.get_pair(info.pair_id)
    assert e.value.code == grpc.StatusCode.NOT_FOUND


def test_register_rejects_a_bad_spec_with_its_field(client):
    spec = _mbench_spec(0.003)
    spec["track"]["gauge_m"] = -1.0
    with pytest.raises(railcontact.RailcontactError) as e:
        client.register_pair(spec)
    assert e.value.code == grpc.StatusCode.INVALID_ARGUMENT
    assert "gauge_m" in e.value.field


def test_wheelrail_session_exact_with_fields(client):
    with client.wheelrail_session(sides="right", element_size_m=5e-4, include_fields=True) as s:
        assert s.model == "exact"
        r = s.step(velocity={"forward_m_per_s": V, "lateral_m_per_s": -0.03}, load=LOAD)
    (wheel,) = r.result.wheels
    patch = wheel.patches[0]
    assert wheel.side == "right" and patch.method == "exact"
    assert patch.fields.pressure_pa.shape == (patch.grid.ny, patch.grid.nx)
    assert patch.fields.pressure_pa.max() == pytest.approx(patch.max_pressure_pa)


def test_a_pair_the_server_lost_is_registered_again(client, server):
    # Another client deletes the pair (as a replica that never saw the
    # registration, or a server restarted without its store, would answer):
    # this client registers it again and retries, once.
    info = client.register_pair(_mbench_spec(0.0031), label="lost")
    with railcontact.Client(server, timeout_s=120) as other:
        other.delete_pair(info.pair_id)
        r = client.solve_wheelrail(info.pair_id, velocity=V, load=LOAD, model="hertz_fastsim")
        assert r.pair_id == info.pair_id and len(r.wheels) == 2
        other.delete_pair(info.pair_id)
        with client.wheelrail_session(info.pair_id, model="hertz_fastsim") as s:
            assert s.pair_id == info.pair_id
    # A pair this client deleted stays deleted.
    client.delete_pair(info.pair_id)
    with pytest.raises(railcontact.RailcontactError) as e:
        client.solve_wheelrail(info.pair_id, velocity=V, load=LOAD, model="hertz_fastsim")
    assert e.value.code == grpc.StatusCode.NOT_FOUND


PROFILES = pathlib.Path(__file__).resolve().parents[3] / "crates" / "solver" / "profiles"


def _file(name, mirror_y=False):
    return {"file": {"content": (PROFILES / name).read_text(), "file_name": name}, "mirror_y": mirror_y}


def test_answers_no_elastic_contact_gives_carry_warnings(client):
    """examples/cases/wheelset_a22.toml's roll and pitch rate (CONTACT's
    for S1002 on UIC60 at 6.5 mm) given to measured profiles: the right
    wheel is pressed 5.6 mm into its rail by 10 kN and both wheels are
    braked the same way; the result says so, naming the inputs. The
    benchmark's own pair, and the measured one with roll and pitch rate
    found, warn of nothing."""
    measured = client.register_pair(
        {
            "wheel": _file("avg_wheel.whl"),
            "rail": _file("avg_HR.BAN", mirror_y=True),
            "track": {"gauge_m": 1.435, "gauge_height_m": 0.014, "cant_rad": 0.0},
            "wheelset": {"flange_back_distance_m": 1.360, "nominal_radius_m": 0.46},
        },
        label="issue 43",
    )
    motion = dict(
        position={"lateral_m": 0.0065, "yaw_rad": 0.0156, "roll_rad": -0.004376},
        velocity={"forward_m_per_s": 2.0, "pitch_rad_per_s": -4.2748834},
        load=1.0e4,
        model="hertz_fastsim",
    )
    r = client.solve_wheelrail(measured.pair_id, **motion)
    assert [(w.kind, w.field, w.side) for w in r.warnings] == [
        ("approach", "position.roll_rad", "right"),
        ("longitudinal_force", "velocity.pitch_rad_per_s", None),
    ]
    approach, longitudinal = r.warnings
    assert isinstance(approach, railcontact.WheelRailWarning)
    assert approach.value > 100 and approach.limit == 10.0
    assert r.wheel("right").vertical_approach_m > 5e-3
    assert "Leave position.roll_rad out" in approach.message
    assert str(approach).startswith("position.roll_rad: the right wheel is pressed")
    assert longitudinal.value > 0.9 and longitudinal.limit == 0.9
    assert "load.total_longitudinal_force_n = 0" in longitudinal.message

    assert client.solve_wheelrail(**motion).warnings == ()

    found = client.solve_wheelrail(
        measured.pair_id,
        position={"lateral_m": 0.0065, "yaw_rad": 0.0156},
        velocity=2.0,
        load={"vertical_force_n": 1.0e4, "total_longitudinal_force_n": 0.0},
        model="hertz_fastsim",
    )
    assert found.warnings == ()
    assert abs(found.wheel("left").force_track_n.x_n) < 300.0

    # In a session step, named under `step.`.
    with client.wheelrail_session(measured.pair_id, model="hertz_fastsim") as s:
        step = s.step(**{k: v for k, v in motion.items() if k != "model"})
    assert [w.field for w in step.result.warnings] == [
        "step.position.roll_rad",
        "step.velocity.pitch_rad_per_s",
    ]
    client.delete_pair(measured.pair_id)


def test_fastsim_patches_report_hertz_p0_and_fastsims_bound_peak(client):
    # A Hertz patch's max_pressure_pa is Hertz's p0; FASTSIM's parabolic
    # bound peaks at 2 Fn/(pi a b) = 4/3 p0 (CONTACT's FASTSIM PMAX), the
    # elliptic one at p0, each scaled so that the elements' pressures sum
    # to Fn (well within 1 %); the exact model has no such number.
    kw = dict(position={"lateral_m": 0.003}, velocity=V, load=LOAD)
    for model, ratio in (("hertz_fastsim", 4 / 3), ("hertz_fastsim_elliptic", 1.0)):
        r = client.solve_wheelrail(model=model, **kw)
        for p in (p for w in r.wheels for p in w.patches):
            assert p.fastsim_max_pressure_pa == pytest.approx(ratio * p.max_pressure_pa, rel=1e-2), model
    exact = client.solve_wheelrail(model="exact", **kw)
    assert all(p.fastsim_max_pressure_pa is None for w in exact.wheels for p in w.patches)
