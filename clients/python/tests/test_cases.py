"""Case files of ``railcontact wheelrail`` through the client: the same
forces as the command line on the same file."""

import json
import pathlib
import shutil

import grpc
import numpy as np
import pytest

import railcontact
from conftest import REPO, run_cli

CASES = REPO / "examples" / "cases"
PROFILES = REPO / "crates" / "solver" / "profiles"

# Measured profiles (MiniProf: a rail measured from the gauge side, mirrored;
# a wheel), the roll and the free-rolling pitch rate found.
MEASURED = """
model = "{model}"
side = "{side}"

[friction]
coefficient = 0.35

[track]
rail_profile = "profiles/avg_HR.BAN"
rail_mirror_y = true
gauge_m = 1.435
gauge_height_m = 0.014

[wheelset]
wheel_profile = "profiles/Car7216_0001r.whl"
{left_wheel}flange_back_distance_m = 1.360
nominal_radius_m = 0.46

[position]
lateral_m = 0.004
yaw_rad = 0.001

[velocity]
forward_m_per_s = 20.0

[load]
vertical_force_n = 50000.0
total_longitudinal_force_n = 0.0
{extra}
"""

GENERATED = {
    "measured_hertz_fastsim": dict(model="Hertz_FASTSIM", side="both", left_wheel="", extra=""),
    "measured_exact_right": dict(
        model="EXACT", side="Right", left_wheel="", extra="\n[grid]\nelement_size_m = 0.0004\n"
    ),
    "measured_polach_left_wheel": dict(
        model="hertz_polach",
        side="both",
        left_wheel='wheel_profile_left = "profiles/avg_wheel.whl"\n',
        extra="\n[polach]\nk_adhesion = 1.0\nk_slip = 0.4\nlimit_ratio = 0.4\ndecay_s_per_m = 0.6\n",
    ),
    "measured_modified_fastsim": dict(
        model="hertz_fastsim_modified", side="both", left_wheel="", extra="\n[modified_fastsim]\ninitial_factor = 0.7\n"
    ),
}


def _example_copy(name: str, tmp_path: pathlib.Path, edit) -> pathlib.Path:
    """The example case file ``name`` edited by ``edit`` (text to text),
    written to ``tmp_path`` with its relative paths into the repository
    made absolute."""
    text = (CASES / name).read_text().replace("../../crates", str(REPO / "crates"))
    path = tmp_path / name
    path.write_text(edit(text))
    return path


def _case_file(name: str, tmp_path: pathlib.Path) -> pathlib.Path:
    """The case file ``name``: an example's, ``a22_curved`` (the A-2.2
    case on a curve of 500 m, its profiles built in), or one of GENERATED
    written to ``tmp_path`` beside copies of its profiles (relative paths)."""
    if name.endswith(".toml"):
        return CASES / name
    if name == "crossing_nose":
        # The example's rail slices at 0.28 m instead of 0.239 m.
        return _example_copy("crossing_nose.toml", tmp_path, lambda t: t.replace("track_s_m = 0.239", "track_s_m = 0.28"))
    if name == "a22_curved":
        text = (CASES / "wheelset_a22.toml").read_text()
        assert "cant_rad = 0.0\n" in text
        path = tmp_path / "a22_curved.toml"
        path.write_text(text.replace("cant_rad = 0.0\n", "cant_rad = 0.0\ncurvature_per_m = 0.002\n"))
        return path
    (tmp_path / "profiles").mkdir(exist_ok=True)
    for profile in ("avg_HR.BAN", "Car7216_0001r.whl", "avg_wheel.whl"):
        shutil.copy(PROFILES / profile, tmp_path / "profiles" / profile)
    path = tmp_path / f"{name}.toml"
    path.write_text(MEASURED.format(**GENERATED[name]))
    return path


def _cli(path: pathlib.Path) -> dict:
    done = run_cli("wheelrail", str(path), "--json")
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


@pytest.mark.parametrize(
    "name",
    ["wheelset_a22.toml", "wheelset_a22_varfric.toml", "wheelset_a22_temperature.toml", "roller_rig.toml",
     "a22_curved", "crossing_nose", *GENERATED],
)
def test_a_case_file_gives_the_forces_of_the_command_line(client, name, tmp_path):
    path = _case_file(name, tmp_path)
    expected = _cli(path)
    r = client.solve_wheelrail_case(path)
    assert r.model == expected["model"]
    close = dict(rel=1e-9, abs=1e-6)
    assert r.center_z_m == pytest.approx(expected["center_z_m"], **close)
    assert r.roll_rad == pytest.approx(expected["roll_rad"], **close)
    assert r.pitch_rad_per_s == pytest.approx(expected["pitch_rad_per_s"], **close)
    assert [w.side for w in r.wheels] == list(expected["wheels"])
    for wheel in r.wheels:
        cli = expected["wheels"][wheel.side]
        assert wheel.force_track_n == pytest.approx(cli["force_track_n"], **close)
        assert len(wheel.patches) == len(cli["patches"])
        for patch, cli_patch in zip(wheel.patches, cli["patches"]):
            for key in ("normal_force_n", "fx_n", "fs_n", "mz_nm", "max_pressure_pa", "contact_angle_rad"):
                assert getattr(patch, key) == pytest.approx(cli_patch[key], **close), key
            if "temperature" in cli_patch:
                assert patch.temperature.max_body1.temperature_k == pytest.approx(
                    cli_patch["temperature"]["max_rail"]["temperature_k"], **close
                )
    assert [(w.kind, w.side) for w in r.warnings] == [(w["kind"], w["side"]) for w in expected["warnings"]]


def test_the_a22_case_numbers(client):
    # examples/cases/wheelset_a22.toml as `railcontact wheelrail` prints it:
    # the flange patch of the right wheel, the tread of the left.
    r = client.solve_wheelrail_case(CASES / "wheelset_a22.toml")
    left, right = r.wheel("left").force_track_n, r.wheel("right").force_track_n
    assert left == pytest.approx([2251.49, -2050.16, 10000.0], abs=0.01)
    assert right == pytest.approx([-2003.70, 12501.63, 9999.99], abs=0.01)
    # It is the built-in pair: the same profiles give the same id.
    assert r.pair_id == client.get_pair(railcontact.BUILTIN_PAIR).pair_id


def test_narrow_patches_keep_the_element_size_with_min_elements_across_0(client, tmp_path):
    # grid.min_elements_across = 0 (CONTACT's DX by DS): the right wheel's
    # flange patch of at 6.5 mm on 0.2 mm squares, contact area 9.96
    # mm² against 9.16 mm² narrowed (the default, 8), as the command line.
    text = (CASES / "wheelset_a22.toml").read_text()
    grid = "\n[grid]\nelement_size_m = 0.0002\n"
    assert grid in text
    path = tmp_path / "a22_squares.toml"
    path.write_text(text.replace(grid, grid + "min_elements_across = 0\n"))
    assert railcontact.load_wheelrail_case(path).settings["min_elements_across"] == 0
    squares = client.solve_wheelrail_case(path)
    cli = _cli(path)["wheels"]["right"]["patches"][0]
    flange = squares.wheel("right").patches[0]
    assert flange.contact_area_m2 == pytest.approx(cli["contact_area_m2"], rel=1e-9)
    narrowed = client.solve_wheelrail_case(CASES / "wheelset_a22.toml").wheel("right").patches[0]
    assert flange.contact_area_m2 / narrowed.contact_area_m2 > 1.05


def test_load_wheelrail_case_takes_the_file_apart(tmp_path):
    path = _case_file("measured_polach_left_wheel", tmp_path)
    case = railcontact.load_wheelrail_case(path)
    assert case.path == path and case.label == path.name
    pair = case.pair
    assert pair["rail"]["mirror_y"] is True and pair["wheel"]["mirror_y"] is False
    assert pair["rail"]["file"]["file_name"] == "avg_HR.BAN"
    assert pair["rail"]["file"]["content"] == (PROFILES / "avg_HR.BAN").read_text()
    assert pair["wheel_left"]["file"]["file_name"] == "avg_wheel.whl"
    assert pair["track"] == {"gauge_m": 1.435, "gauge_height_m": 0.014}
    assert case.settings == {
        "model": "hertz_polach",
        "sides": "both",
        "friction": {"coefficient": 0.35},
        "polach": {"k_adhesion": 1.0, "k_slip": 0.4, "limit_ratio": 0.4, "decay_s_per_m": 0.6},
    }
    assert case.motion == {
        "position": {"lateral_m": 0.004, "yaw_rad": 0.001},
        "velocity": {"forward_m_per_s": 20.0},
        "load": {"vertical_force_n": 50000.0, "total_longitudinal_force_n": 0.0},
    }
    assert case.solve_arguments(model="exact")["model"] == "exact"
    # Builtin names and the friction table of the examples.
    varfric = railcontact.load_wheelrail_case(CASES / "wheelset_a22_varfric.toml")
    assert varfric.pair["wheel"] == {"builtin_name": "MBench_S1002_v3.prw", "mirror_y": False}
    assert "friction" not in varfric.settings
    assert varfric.settings["friction_table"]["coefficients"] == [0.3, 0.2]
    # Its summary names the profile file's size, not its text.
    assert "<text: " in repr(case) and "Filename=" not in repr(case)


def test_a_slices_rail_is_sent_with_the_profile_files_it_names(tmp_path):
    case = railcontact.load_wheelrail_case(_case_file("crossing_nose", tmp_path))
    slices = case.pair["rail"]["slices"]
    assert slices["file_name"] == "uk_crossing_nose.slcs"
    names = [p["file_name"] for p in slices["profiles"]]
    assert names == [f"uk_crossing/Crossing_{k}.txt" for k in range(66, 76)]
    assert slices["profiles"][0]["content"] == (PROFILES / names[0]).read_text()
    assert case.motion["position"]["track_s_m"] == 0.28


def test_a_cases_profile_unit_reaches_every_table_of_the_slices(client, tmp_path):
    # crossing_nose.toml's slices are tables in metres without a unit line:
    # `rail_profile_unit = "m"` says so (each profile's plain_unit) and
    # changes no number; "mm" reads them a thousand times smaller, a rail
    # 0.08 mm wide, which the server refuses naming a slice's profile.
    base = _example_copy("crossing_nose.toml", tmp_path, lambda t: t)
    plain = client.solve_wheelrail_case(base)
    for unit, field in (("m", None), ("mm", "spec.rail.slices")):
        path = _example_copy(
            "crossing_nose.toml", tmp_path, lambda t: t.replace("[wheelset]", f'rail_profile_unit = "{unit}"\n\n[wheelset]')
        )
        case = railcontact.load_wheelrail_case(path)
        assert {p["plain_unit"] for p in case.pair["rail"]["slices"]["profiles"]} == {unit}
        if field is None:
            r = client.solve_wheelrail_case(case)
            assert r.wheel("right").patches[0].normal_force_n == plain.wheel("right").patches[0].normal_force_n
        else:
            with pytest.raises(railcontact.RailcontactError) as e:
                client.solve_wheelrail_case(case)
            assert e.value.code == grpc.StatusCode.INVALID_ARGUMENT
            assert e.value.field.startswith(field), e.value.field
    bad = _example_copy("crossing_nose.toml", tmp_path, lambda t: t.replace("[wheelset]", 'rail_profile_unit = "cm"\n\n[wheelset]'))
    with pytest.raises(railcontact.RailcontactError) as e:
        railcontact.load_wheelrail_case(bad)
    assert e.value.field == "track.rail_profile_unit"


def test_rail_deviations_reach_the_pair_and_move_the_rails(client, tmp_path):
    # Both rails 1 mm to the right under a wheelset 1 mm further right: the
    # case's forces, as `railcontact wheelrail` finds
    # (src/cli/wheelrail.rs, rail_deviations_move_the_rails).
    def shifted(t):
        return t.replace("lateral_m = 0.0065", "lateral_m = 0.0075").replace(
            "[wheelset]", "[track.rail_deviation_left]\ndy_m = 0.001\n[track.rail_deviation_right]\ndy_m = 0.001\n\n[wheelset]"
        )

    case = railcontact.load_wheelrail_case(_example_copy("wheelset_a22.toml", tmp_path, shifted))
    assert case.pair["track"]["rail_deviation_right"] == {"dy_m": 0.001}
    a = client.solve_wheelrail_case(CASES / "wheelset_a22.toml")
    b = client.solve_wheelrail_case(case)
    for side in ("left", "right"):
        for p, q in zip(a.wheel(side).patches, b.wheel(side).patches):
            assert q.normal_force_n == pytest.approx(p.normal_force_n, abs=1e-2)
    far = _example_copy(
        "wheelset_a22.toml", tmp_path, lambda t: t.replace("[wheelset]", "[track.rail_deviation_right]\ndy_m = 6.0\n\n[wheelset]")
    )
    with pytest.raises(railcontact.RailcontactError) as e:
        client.solve_wheelrail_case(far)
    assert e.value.field == "spec.track.rail_deviation_right.dy_m"
    odd = _example_copy("wheelset_a22.toml", tmp_path, lambda t: t.replace("[wheelset]", "[track.rail_deviation_right]\ndx_m = 0.001\n\n[wheelset]"))
    with pytest.raises(railcontact.RailcontactError) as e:
        railcontact.load_wheelrail_case(odd)
    assert e.value.field == "track.rail_deviation_right.dx_m"


def test_a_cases_force_tolerance_reaches_the_solve(client, tmp_path):
    # grid.force_tolerance_of_wheel_load: the case's forces within
    # that fraction of the wheel load of the default grid's; below its
    # range refused by the server naming the field.
    def tolerance(value):
        return lambda t: t.replace("element_size_m = 0.0002", f"element_size_m = 0.0002\nforce_tolerance_of_wheel_load = {value}")

    case = railcontact.load_wheelrail_case(_example_copy("wheelset_a22.toml", tmp_path, tolerance(0.005)))
    assert case.settings["force_tolerance_of_wheel_load"] == 0.005
    fine = client.solve_wheelrail_case(CASES / "wheelset_a22.toml")
    sized = client.solve_wheelrail_case(case)
    for side in ("left", "right"):
        for k in range(3):
            a = sum(p.force_track_n[k] for p in fine.wheel(side).patches)
            b = sum(p.force_track_n[k] for p in sized.wheel(side).patches)
            assert abs(a - b) <= 0.005 * 1e4, (side, k, a, b)
    with pytest.raises(railcontact.RailcontactError) as e:
        client.solve_wheelrail_case(_example_copy("wheelset_a22.toml", tmp_path, tolerance(0.001)))
    assert e.value.code == grpc.StatusCode.INVALID_ARGUMENT
    assert e.value.field == "force_tolerance_of_wheel_load", e.value.field


def test_a_roller_rig_case_takes_the_rollers_rate_into_the_velocity(client):
    # examples/cases/roller_rig.toml: the rails placed by their origins on
    # rollers (the pair), the rollers' rate with the wheel's (the motion).
    case = railcontact.load_wheelrail_case(CASES / "roller_rig.toml")
    assert case.pair["track"] == {"rail_origin_y_m": 0.2, "rail_origin_z_m": 0.0, "roller_radius_m": 0.4}
    assert case.motion["velocity"] == {"pitch_rad_per_s": -7.5, "roller_rad_per_s": 2.5}
    r = client.solve_wheelrail_case(case)
    assert [w.side for w in r.wheels] == ["right"]
    # CONTACT's test-rollers2 case 2a (.ref_out: FN = 9.719E+04 N), within
    # the 0.1 % the examples' README gives.
    normal = sum(p.normal_force_n for p in r.wheel("right").patches)
    assert normal == pytest.approx(9.719e4, rel=1e-3)
    info = client.get_pair(r.pair_id)
    assert info.raw.track.roller_radius_m == 0.4 and info.raw.track.HasField("rail_origin_y_m")


@pytest.mark.parametrize(
    "edit, field",
    [
        (lambda t: t.replace("roller_radius_m = 0.4", "roller_radius_m = -0.4"), "spec.track.roller_radius_m"),
        (lambda t: t.replace("rail_origin_y_m = 0.2", "rail_origin_y_m = 200.0"), "spec.track.rail_origin_y_m"),
        (lambda t: t.replace("roller_rad_per_s = 2.5", "roller_rad_per_s = 0.0"), "velocity.roller_rad_per_s"),
        (lambda t: t.replace("[wheelset]", "curvature_per_m = 0.5\n\n[wheelset]"), "spec.track.curvature_per_m"),
    ],
)
def test_a_bad_roller_rig_value_is_refused_naming_the_field(client, tmp_path, edit, field):
    path = _example_copy("roller_rig.toml", tmp_path, edit)
    with pytest.raises(railcontact.RailcontactError) as e:
        client.solve_wheelrail_case(path)
    assert e.value.code == grpc.StatusCode.INVALID_ARGUMENT
    assert e.value.field == field, e.value.message


@pytest.mark.parametrize(
    "edit, field",
    [
        (lambda t: t.replace("roller_rad_per_s = 2.5\n", ""), "track.roller_rad_per_s"),
        (lambda t: t.replace("roller_radius_m = 0.4\n", ""), "track.roller_rad_per_s"),
        (lambda t: t.replace("rail_origin_z_m = 0.0\n", ""), "track.rail_origin_z_m"),
        (lambda t: t.replace("rail_origin_z_m = 0.0\n", "rail_origin_z_m = 0.0\ngauge_m = 1.435\n"), "track"),
        (lambda t: t.replace("roller_rad_per_s = 2.5\n", "roller_rad_per_s = 2.5\nroller = 1\n"), "track.roller"),
    ],
)
def test_a_roller_rig_case_file_names_its_key(tmp_path, edit, field):
    path = _example_copy("roller_rig.toml", tmp_path, edit)
    with pytest.raises(railcontact.RailcontactError) as e:
        railcontact.load_wheelrail_case(path)
    assert e.value.code == grpc.StatusCode.INVALID_ARGUMENT
    assert e.value.field == field, e.value.message


def test_a_case_session_steps_as_the_solve(client):
    case = railcontact.load_wheelrail_case(CASES / "wheelset_a22.toml")
    pair = client.register_pair(case.pair, label=case.label)
    alone = client.solve_wheelrail(pair.pair_id, **case.solve_arguments(model="hertz_fastsim"))
    with client.wheelrail_session(pair.pair_id, **dict(case.settings, model="hertz_fastsim")) as s:
        step = s.step(**case.motion)
    assert np.array_equal(step.result.force_track_n, alone.force_track_n)


def test_a_case_pair_is_registered_once_per_client(server, tmp_path):
    path = _case_file("measured_hertz_fastsim", tmp_path)
    with railcontact.Client(server, timeout_s=120) as client:
        registered = []
        register = client.register_pair
        client.register_pair = lambda *a, **k: registered.append(a) or register(*a, **k)
        first = client.solve_wheelrail_case(path)
        again = client.solve_wheelrail_case(path, position={"lateral_m": 0.0})
        assert len(registered) == 1 and again.pair_id == first.pair_id
        assert first.pair_id in [p.pair_id for p in client.list_pairs()]
        assert client.get_pair(first.pair_id).label == path.name
        client.delete_pair(first.pair_id)


@pytest.mark.parametrize(
    "edit, field",
    [
        (lambda t: t.replace("yaw_rad = 0.001", "yaw_rad = 0.001\nroll = 0.0"), "position.roll"),
        (lambda t: t.replace("gauge_m = 1.435\n", ""), "track.gauge_m"),
        (lambda t: t.replace("profiles/avg_HR.BAN", "profiles/missing.BAN"), "track.rail_profile"),
        (lambda t: t.replace("total_longitudinal_force_n", "approach_m"), "load"),
        (lambda t: t.replace("[velocity]\nforward_m_per_s = 20.0\n", ""), "velocity"),
        (lambda t: t.replace("rail_mirror_y = true", 'rail_mirror_y = "yes"'), "track.rail_mirror_y"),
        (lambda t: t + "\n[grid]\n", "grid.element_size_m"),
        (lambda t: "model = 'exact'\n" + t, "case"),  # not TOML: a key given twice
    ],
)
def test_a_bad_case_file_names_its_key(tmp_path, edit, field):
    path = _case_file("measured_hertz_fastsim", tmp_path)
    path.write_text(edit(path.read_text()))
    with pytest.raises(railcontact.RailcontactError) as e:
        railcontact.load_wheelrail_case(path)
    assert e.value.code == grpc.StatusCode.INVALID_ARGUMENT
    assert e.value.field == field, e.value.message


def test_a_wheelrail_case_given_as_a_patch_says_what_to_use(client):
    with pytest.raises(railcontact.RailcontactError) as e:
        client.solve_patch(CASES / "wheelset_a22.toml")
    assert e.value.field == "case" and "solve_wheelrail_case" in e.value.message
