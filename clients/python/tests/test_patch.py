"""Patch calls against the real server: SolvePatch, batches, creep curves,
errors and PatchSession with marks and rollback."""

import grpc
import numpy as np
import pytest

import railcontact
from conftest import REPO, rolling_case


def test_server_lists_the_builtin_pair(client):
    pairs = client.list_pairs()
    builtin = [p for p in pairs if p.builtin_pair == railcontact.BUILTIN_PAIR]
    assert len(builtin) == 1 and builtin[0].state == "ready"
    assert len(builtin[0].pair_id) == 32
    assert client.get_pair(railcontact.BUILTIN_PAIR).pair_id == builtin[0].pair_id


def test_solve_patch_gives_totals_and_fields_shaped_ny_nx(client):
    case = rolling_case("exact", n=20)
    case["grid"] = {"nx": 16, "ny": 20}
    r = client.solve_patch(case, include_fields=True)
    assert r.model == "exact" and r.result.info.status == "converged"
    assert r.friction_coefficient == 0.3
    t = r.totals
    assert t.normal_force_n == pytest.approx(1.0e4, rel=1e-9)
    # Positive creepages pull the rail backwards and to the left.
    assert t.fx_n < 0 and t.fy_n < 0 and -t.fx_n < 0.3 * t.normal_force_n
    assert (r.grid.nx, r.grid.ny) == (16, 20)
    f = r.fields
    for name in ("pressure_pa", "traction_x_pa", "traction_y_pa", "slip_x", "slip_y", "state", "gap_m"):
        assert getattr(f, name).shape == (20, 16), name
    assert not f.pressure_pa.flags.writeable
    assert set(np.unique(f.state)) <= {railcontact.EXTERIOR, railcontact.ADHESION, railcontact.SLIP}
    assert (f.state == railcontact.ADHESION).any() and (f.state == railcontact.SLIP).any()
    # The fields add up to the totals.
    area = r.grid.element_size_x_m * r.grid.element_size_y_m
    assert f.pressure_pa.sum() * area == pytest.approx(t.normal_force_n, rel=1e-6)
    assert f.traction_x_pa.sum() * area == pytest.approx(t.fx_n, rel=1e-6)
    assert f.pressure_pa.max() == pytest.approx(t.max_pressure_pa)
    assert r.grid.x_m().shape == (16,) and r.grid.y_m().shape == (20,)


def test_hertz_from_a_case_file(client):
    path = REPO / "examples" / "cases" / "hertz_only.toml"
    r = client.solve_patch(path)
    assert r.model == "hertz" and r.fields is None and r.grid is None
    assert r.totals.max_pressure_pa > 1e8 and r.totals.fx_n == 0
    with pytest.raises(railcontact.RailcontactError) as e:
        client.solve_patch(path, include_fields=True)  # Hertz has no grid
    assert e.value.field == "include_fields"


def test_batch_keeps_order_and_reports_item_errors(client):
    good = rolling_case("fastsim")
    bad = rolling_case("fastsim")
    bad["load"] = {"normal_force_n": -1.0}
    results = client.solve_patch_batch([good, bad, good])
    assert isinstance(results[0], railcontact.PatchResult)
    assert isinstance(results[1], railcontact.RailcontactError)
    assert results[1].code == grpc.StatusCode.INVALID_ARGUMENT
    assert results[1].field == "items[1].case.load.normal_force_n"
    assert results[2].totals == results[0].totals


def test_creep_curve_comes_in_order_and_saturates(client):
    points = list(client.creep_curve(rolling_case("fastsim"), linear=((0, 0, 0), (0.01, 0, 0), 11)))
    assert [p.index for p in points] == list(range(11))
    xi = [p.creepages.creepage_long for p in points]
    assert xi == sorted(xi) and xi[-1] == pytest.approx(0.01)
    fx = [p.result.totals.fx_n for p in points]
    assert fx[0] == 0 and all(b <= a + 1e-9 for a, b in zip(fx, fx[1:]))
    assert -fx[-1] == pytest.approx(0.3 * 1.0e4, rel=1e-3)  # full sliding
    # An explicit list, exact model, warm-started point to point.
    listed = list(client.creep_curve(rolling_case("exact", n=12), [(1e-4, 0, 0), {"creepage_lat": 1e-3}]))
    assert [p.creepages.creepage_lat for p in listed] == [0.0, 1e-3]
    assert listed[1].result.totals.fy_n < 0


def test_invalid_input_raises_with_code_and_field(client):
    case = rolling_case("exact")
    case["geometry"]["a_per_m"] = float("nan")
    with pytest.raises(railcontact.RailcontactError) as e:
        client.solve_patch(case)
    assert e.value.code == grpc.StatusCode.INVALID_ARGUMENT
    assert e.value.field == "case.geometry.a_per_m"
    assert "a_per_m" in e.value.message
    with pytest.raises(railcontact.RailcontactError) as e:
        client.solve_wheelrail("no-such-pair", velocity=30.0, load=1e5)
    assert e.value.code == grpc.StatusCode.NOT_FOUND
    # Caught in the client: unknown keys and enum names, with their path.
    with pytest.raises(railcontact.RailcontactError) as e:
        client.solve_patch(dict(case, model="exactly"))
    assert e.value.code == grpc.StatusCode.INVALID_ARGUMENT and e.value.field == "case.model"
    with pytest.raises(railcontact.RailcontactError) as e:
        client.solve_patch(dict(case, grid={"nx": 8, "nz": 8}))
    assert e.value.field == "case.grid.nz"
    # A case file that is missing or not TOML is bad input too.
    with pytest.raises(railcontact.RailcontactError) as e:
        client.solve_patch(REPO / "examples" / "cases" / "no-such-case.toml")
    assert e.value.code == grpc.StatusCode.INVALID_ARGUMENT and e.value.field == "case"
    assert "no-such-case.toml" in e.value.message
    with pytest.raises(railcontact.RailcontactError) as e:
        client.solve_patch(REPO / "README.md")
    assert e.value.field == "case"


def _run(session, creepages, mark_at=None):
    out = []
    for i, c in enumerate(creepages):
        out.append(session.step(c, time_s=0.001 * i, mark=(i == mark_at)))
    return out


def test_patch_session_replays_identically_after_rollback(client):
    case = rolling_case("exact", n=16)
    sweep = [(1e-4 * k, 2e-4, 0.0) for k in range(6)]
    with client.patch_session(case, include_fields=True, label="pytest") as s:
        assert s.session_id and s.model == "exact" and s.grid.nx == 16
        first = _run(s, sweep, mark_at=2)
        assert [r.step_index for r in first] == list(range(6))
        assert first[2].marked and not first[3].marked
        assert first[3].fields.pressure_pa.shape == (16, 16)
        assert s.rollback(2) == 3 and s.next_step_index == 3
        again = [s.step(c, time_s=0.001 * (3 + i)) for i, c in enumerate(sweep[3:])]
        for a, b in zip(first[3:], again):
            assert a.step_index == b.step_index
            assert a.totals == b.totals
            assert np.array_equal(a.fields.traction_x_pa, b.fields.traction_x_pa)
        # In-band errors raise and leave the session open.
        with pytest.raises(railcontact.RailcontactError) as e:
            s.step((1e-4, 0, 0), step_index=42)
        assert e.value.code == grpc.StatusCode.FAILED_PRECONDITION
        with pytest.raises(railcontact.RailcontactError) as e:
            s.rollback(4)  # not marked
        assert e.value.code == grpc.StatusCode.FAILED_PRECONDITION
        with pytest.raises(railcontact.RailcontactError) as e:
            s.step((float("nan"), 0, 0))
        assert e.value.code == grpc.StatusCode.INVALID_ARGUMENT
        assert e.value.field.startswith("step.creepages.")
        assert s.step(sweep[0]).step_index == 6


def test_session_open_errors_raise(client):
    case = rolling_case("exact")
    case["material"] = {"shear_modulus_pa": -1.0, "poisson_ratio": 0.3}
    with pytest.raises(railcontact.RailcontactError) as e:
        client.patch_session(case)
    assert e.value.code == grpc.StatusCode.INVALID_ARGUMENT
    assert "shear_modulus_pa" in e.value.field


def test_sensitivities_of_a_rolling_patch(client):
    r = client.solve_patch(rolling_case("fastsim", creepages=(1e-4, 0.0, 0.0)), include_sensitivities=True)
    s = r.result.sensitivities
    assert s is not None and s.solves > 0
    # Fx = -G a b C11 xi in the linear range: dFx/dxi < 0, and dFn/d(approach) > 0.
    assert s.per_creepage_long.fx < 0 and s.per_creepage_lat.fy < 0
    assert s.per_approach_m.normal_force > 0
    with client.patch_session(rolling_case("fastsim"), include_sensitivities=True) as session:
        step = session.step((1e-4, 0.0, 0.0))
        again = step.result.sensitivities
        assert again.per_creepage_long.fx == pytest.approx(s.per_creepage_long.fx, rel=1e-6)
        assert again.per_approach_m.normal_force == pytest.approx(s.per_approach_m.normal_force, rel=1e-6)


def test_an_interfacial_layer_case_file_gives_the_layers_fields(client):
    # CONTACT's plastic_3bl.inp cases 15-31 (examples/cases): the last
    # step's FX = 424.1 N and tau_c = 424.1 N/mm² on the one plastic
    # element (plastic_3bl.ref_out, case 31).
    path = REPO / "examples" / "cases" / "layer_plastic_3bl.toml"
    r = client.solve_patch(path, include_fields=True)
    assert r.totals.fx_n == pytest.approx(424.1, abs=0.05)
    f = r.fields
    assert f.layer_plastic.shape == (5, 5)
    assert f.layer_plastic.sum() == 1 and f.layer_plastic[2, 2]
    assert f.layer_yield_limit_pa[2, 2] == pytest.approx(424.1e6, abs=0.05e6)
    assert f.layer_plastic_x_m.shape == (5, 5)
    # Without a layer the layer's fields are empty.
    plain = client.solve_patch(rolling_case("exact"), include_fields=True)
    assert plain.fields.layer_plastic.size == 0


def test_a_viscoelastic_case_file_solves_as_contacts_visc_cylindr(client):
    # CONTACT's visc_cylindr.inp case 3 (examples/cases/visc_cylindr.toml:
    # two viscoelastic PA6 cylinders braked at Fx = -0.6 mu Fn):
    # visc_cylindr.ref_out gives CREEP X 1.152e-2, PMAX 84.72 N/mm², 36
    # elements in adhesion and 21 in slip.
    path = REPO / "examples" / "cases" / "visc_cylindr.toml"
    r = client.solve_patch(path, include_fields=True)
    assert r.force_control.creepage_long == pytest.approx(1.152e-2, rel=0.01)
    assert r.totals.max_pressure_pa == pytest.approx(84.72e6, rel=0.01)
    assert (r.fields.state == railcontact.ADHESION).sum() == 36
    assert (r.fields.state == railcontact.SLIP).sum() == 21
    # Without prescribed forces there is no force control.
    assert client.solve_patch(rolling_case("exact")).force_control is None
    # A bad value is refused naming its field.
    case = railcontact.load_case(path)
    case["viscoelastic"]["body1"]["relaxation_ratio"] = -1.0
    with pytest.raises(railcontact.RailcontactError) as e:
        client.solve_patch(case)
    assert e.value.field == "case.viscoelastic.body1.relaxation_ratio", e.value.message


def test_transient_steps_start_from_a_steady_state_at_their_friction_start(client):
    # CONTACT's veldep_fric.inp case 3 (steady), then cases 4-6 (rolling
    # steps from the slip velocity V), examples/cases/
    # line_veldep_fric_steps.toml: veldep_fric.ref_out FX 1.109e5,
    # 1.064e5, 1.071e5, 1.078e5 N over DY = 200 mm (x 5 per metre).
    path = REPO / "examples" / "cases" / "line_veldep_fric_steps.toml"
    r = client.solve_patch(path)
    assert r.steady_start.totals.fx_n == pytest.approx(5.545e5, rel=0.01)
    assert [s.totals.fx_n for s in r.steps] == pytest.approx([5.320e5, 5.355e5, 5.390e5], rel=0.01)
    # From the slip velocity 0 the first step is CONTACT's case 2 (1.116e5).
    case = railcontact.load_case(path)
    case["transient"]["steps"][0]["friction_start"] = "sticking"
    assert client.solve_patch(case).steps[0].totals.fx_n == pytest.approx(5.580e5, rel=0.01)
    assert client.solve_patch(rolling_case("exact")).steady_start is None


def test_fastsim_reports_hertz_p0_and_its_bound_peak(client):
    # totals.max_pressure_pa is Hertz's p0; fastsim_max_pressure_pa the
    # peak of FASTSIM's parabolic traction bound, 2 Fn/(pi a b) = 4/3 p0
    # (CONTACT's FASTSIM PMAX), scaled so that its elements sum to Fn.
    r = client.solve_patch(rolling_case("fastsim", n=24))
    assert r.fastsim_max_pressure_pa == pytest.approx(4 / 3 * r.totals.max_pressure_pa, rel=3e-3)
    assert client.solve_patch(rolling_case("hertz")).fastsim_max_pressure_pa is None


def test_influence_coefficients_of_a_case_file_are_sent_inline(client):
    # examples/cases/numerical_influence.toml names a file of influence
    # coefficients (CONTACT's C3 = 9): load_case reads it and sends its
    # text (material.influence_file_content); the forces are the command
    # line's on the same file, bit for bit, and CONTACT's for its
    # inflcf.inp case 2: FX 2217 N, FY -1079 N (its printed digits).
    import json

    from conftest import run_cli

    path = REPO / "examples" / "cases" / "numerical_influence.toml"
    case = railcontact.load_case(path)
    text = case["material"]["influence_file_content"]
    assert "influence_file" not in case["material"] and text.lstrip().startswith("1")
    r = client.solve_patch(path, include_fields=True)
    done = run_cli("solve", str(path), "--json")
    assert done.returncode == 0, done.stderr
    expected = json.loads(done.stdout)
    for name in ("normal_force_n", "fx_n", "fy_n", "mz_nm", "max_pressure_pa", "approach_m"):
        assert getattr(r.totals, name) == expected[name], name
    assert r.totals.fx_n == pytest.approx(2217, abs=0.5)
    assert r.totals.fy_n == pytest.approx(-1079, abs=0.5)
    assert any(n.startswith("material.influence_file_content:") for n in r.notes)
    # A damaged text is refused naming the field, and the line in it.
    line = text.splitlines()[6]  # line 7, the first coefficient line
    damaged = text.replace(line, line.replace(line.split()[2], "nan", 1), 1)
    with pytest.raises(railcontact.RailcontactError) as e:
        client.solve_patch({**case, "material": {**case["material"], "influence_file_content": damaged}})
    assert e.value.code == grpc.StatusCode.INVALID_ARGUMENT
    assert e.value.field == "case.material.influence_file_content"
    assert "line 7: `Cnn` is not a finite number" in str(e.value)
    # A file that cannot be read is named before any call.
    missing = {**case, "material": {**case["material"], "influence_file": "no-such-file.txt"}}
    del missing["material"]["influence_file_content"]
    with pytest.raises(railcontact.RailcontactError) as e:
        client.solve_patch(missing)
    assert e.value.field == "case.material.influence_file" and "no-such-file.txt" in str(e.value)


def test_a_fastsim_section_builds_its_enums_by_name():
    # `[fastsim]` of a case file maps key for key onto PatchCase.fastsim,
    # its enums by their short names.
    case = railcontact.load_case(REPO / "examples" / "cases" / "fastsim_contact_grid.toml")
    message = railcontact.patch_case(case)
    f = message.fastsim
    assert f.method == railcontact.pb.FASTSIM_METHOD_FASTRIP
    assert f.discretisation == railcontact.pb.FASTSIM_DISCRETISATION_GRID
    assert f.traction_bound == railcontact.pb.FASTSIM_TRACTION_BOUND_ELLIPTIC
    assert f.window_scale == 1.1
    assert not f.HasField("initial_factor")


def test_a_fastsim_variant_solves_as_contact_on_its_grid(client):
    # examples/cases/fastsim_contact_grid.toml: CONTACT's fastsim.inp case 4
    # (modified FaStrip, elliptic bound, 44 x 44 elements), fastsim.ref_out
    # FY -1.583E+04 N, MZ -4.816E+04 N mm, PMAX 1223. N/mm², 626 elements
    # in adhesion and 638 in slip.
    path = REPO / "examples" / "cases" / "fastsim_contact_grid.toml"
    r = client.solve_patch(path)
    assert r.totals.fy_n == pytest.approx(-1.583e4, abs=5.0)
    assert r.totals.mz_nm == pytest.approx(-48.16, abs=0.005)
    assert r.fastsim_max_pressure_pa == pytest.approx(1223e6, abs=0.5e6)
    assert any("626 in adhesion, 638 in slip" in n for n in r.notes), r.notes
    # A bad value is refused naming its field.
    case = railcontact.load_case(path)
    case["fastsim"]["window_scale"] = 0.5
    with pytest.raises(railcontact.RailcontactError) as e:
        client.solve_patch(case)
    assert e.value.field == "case.fastsim.window_scale", e.value.message
    # With another model the section is refused naming it.
    case = railcontact.load_case(path)
    case["model"] = "exact"
    with pytest.raises(railcontact.RailcontactError) as e:
        client.solve_patch(case)
    assert e.value.field == "case.fastsim", e.value.message
