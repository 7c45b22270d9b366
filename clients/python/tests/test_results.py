"""What results are to a user: track forces as arrays, readable summaries,
== and hash, and the model names taken and offered."""

import dataclasses
import pickle

import grpc
import numpy as np
import pytest

import railcontact
from railcontact import TrackForce
from conftest import rolling_case, run_example

MOTION = dict(position={"lateral_m": 0.003}, velocity=30.0, load=1.0e5)


# -- TrackForce: an array, as the summed force ------------------------------


def test_a_track_force_is_a_read_only_array_with_its_components():
    f = TrackForce(1.0, -2.0, 3.0)
    assert isinstance(f, np.ndarray) and f.shape == (3,) and f.dtype == float
    assert (f.x_n, f.y_n, f.z_n) == (1.0, -2.0, 3.0)
    assert list(f) == [1.0, -2.0, 3.0] and f[1] == -2.0 and f[-1] == 3.0
    assert np.array_equal(f.as_array(), [1.0, -2.0, 3.0]) and f.as_array().flags.writeable
    with pytest.raises(ValueError):
        f[0] = 5.0
    # Arithmetic gives plain arrays and numbers.
    total = f + TrackForce(1.0, 1.0, 1.0)
    assert type(total) is np.ndarray and np.array_equal(total, [2.0, -1.0, 4.0])
    assert type(f[:2]) is np.ndarray and type(-f) is np.ndarray
    assert f.sum() == 2.0 and np.linalg.norm(f) == pytest.approx(np.sqrt(14.0))
    assert np.array_equal(f == TrackForce(1.0, 0.0, 3.0), [True, False, True])
    assert pickle.loads(pickle.dumps(f)).y_n == -2.0
    assert repr(f) == "TrackForce([ 1., -2.,  3.])"


def test_wheel_and_patch_forces_are_arrays_like_the_total(client):
    r = client.solve_wheelrail(model="hertz_fastsim", **MOTION)
    left, right = r.wheel("left").force_track_n, r.wheel("right").force_track_n
    for force in (left, right, r.force_track_n, r.wheels[0].patches[0].force_track_n):
        assert isinstance(force, TrackForce) and force.shape == (3,)
    assert np.array_equal(left + right, r.force_track_n)
    assert r.force_track_n.z_n == pytest.approx(2.0e5, rel=1e-6)
    assert left.x_n == left[0] and right.z_n == right[2]
    per_patch = sum(p.force_track_n for p in r.wheel("left").patches)
    assert np.allclose(per_patch, left, rtol=1e-9, atol=1e-6)


# -- == and hash --------------------------------------------------------------


def test_results_with_arrays_compare_and_hash_by_value(client):
    kw = dict(model="exact", sides="right", element_size_m=5e-4, include_fields=True, **MOTION)
    a, b = client.solve_wheelrail(**kw), client.solve_wheelrail(**kw)
    pa, pb = a.wheels[0].patches[0], b.wheels[0].patches[0]
    assert pa.fields is not None and pa.fields == pb.fields and hash(pa.fields) == hash(pb.fields)
    assert pa == pb and hash(pa) == hash(pb) and a.wheels == b.wheels
    assert pa != dataclasses.replace(pa, force_track_n=TrackForce(0.0, 0.0, 0.0))
    assert pa != dataclasses.replace(pa, fx_n=pa.fx_n + 1.0)
    assert len({pa, pb}) == 1
    # Frozen dataclasses with the proto's fields, as before.
    names = [f.name for f in dataclasses.fields(railcontact.WheelRailWheel)]
    assert names == ["side", "vertical_approach_m", "min_gap_m", "patches", "force_track_n", "load_iterations"]
    with pytest.raises(dataclasses.FrozenInstanceError):
        a.pair_id = "x"


# -- readable summaries -------------------------------------------------------


def test_a_wheelrail_result_prints_as_an_indented_summary(client):
    r = client.solve_wheelrail(model="exact", include_fields=True, element_size_m=5e-4, **MOTION)
    text = str(r)
    assert text == repr(r)
    lines = text.splitlines()
    assert lines[0] == "WheelRailResult(" and lines[-1] == ")"
    assert max(len(line) for line in lines) <= 100
    assert "  model='exact'," in lines
    assert any(line.startswith("      side='left',") for line in lines)  # a wheel, indented
    assert any(line.strip().startswith("force_track_n=TrackForce([") for line in lines)
    patch = r.wheel("left").patches[0]
    ny, nx = patch.fields.pressure_pa.shape
    expected = (
        f"pressure_pa=array(shape=({ny}, {nx}), min=0, "
        f"max={patch.fields.pressure_pa.max():.6g}),"
    )
    assert any(line.strip() == expected for line in lines)
    assert "timing=WheelRailTiming(search_s=" in text and "warnings=()," in text


def test_a_patch_result_summary_shortens_long_tuples(client):
    steps = [{"shift_x_m": 1e-6 * (k + 1)} for k in range(8)]
    case = dict(rolling_case(n=12), transient={"steps": steps})
    case.pop("rolling")
    r = client.solve_patch(case)
    assert len(r.steps) == 8
    text = str(r)
    assert "... 3 more ...," in text
    assert text.count("StepResult(") == 1 + 5  # the final result, 4 first and the last step
    small = railcontact.Creepages(1e-3, 0.0, 0.5)
    assert str(small) == "Creepages(creepage_long=0.001, creepage_lat=0, spin_per_m=0.5)"


# -- model names: any case, valid ones offered --------------------------------


def test_model_names_in_any_case(client):
    for name in ("Exact", "EXACT", "hertz_FASTSIM", "WHEEL_RAIL_MODEL_HERTZ_FASTSIM"):
        r = client.solve_wheelrail(model=name, sides="right", element_size_m=5e-4, **MOTION)
        assert r.model == name.lower().removeprefix("wheel_rail_model_")
    assert client.solve_patch(rolling_case(model="FastSim")).model == "fastsim"


@pytest.mark.parametrize("name", ["exakt", "unspecified", "WHEEL_RAIL_MODEL_UNSPECIFIED", "hertz-fastsim"])
def test_a_bad_model_name_lists_the_valid_ones(client, name):
    with pytest.raises(railcontact.RailcontactError) as e:
        client.solve_wheelrail(model=name, **MOTION)
    assert e.value.code == grpc.StatusCode.INVALID_ARGUMENT and e.value.field == "model"
    assert "unspecified" not in e.value.message.replace(repr(name), "").lower()
    for valid in railcontact.WHEELRAIL_MODELS:
        assert f'"{valid}"' in e.value.message
    with pytest.raises(railcontact.RailcontactError) as e:
        client.solve_patch(rolling_case(model=name))
    assert e.value.field == "case.model"
    assert all(f'"{m}"' in e.value.message for m in railcontact.PATCH_MODELS)


def test_help_lists_the_models_and_never_unspecified(tmp_path, server):
    assert railcontact.WHEELRAIL_MODELS[:2] == ("exact", "hertz_fastsim") and len(railcontact.WHEELRAIL_MODELS) == 10
    assert "unspecified" not in railcontact.WHEELRAIL_MODELS + railcontact.PATCH_MODELS
    for method in (railcontact.Client.solve_wheelrail,):
        doc = method.__doc__
        assert "unspecified" not in doc
        assert all(f'"{m}"' in doc for m in railcontact.WHEELRAIL_MODELS)
    for example in ("wheelset_cosim.py", "creep_curve.py"):
        done = run_example(example, server, tmp_path / "unused.png", "--help")
        assert done.returncode == 0
        assert "unspecified" not in done.stdout
        assert all(m in done.stdout for m in railcontact.WHEELRAIL_MODELS)
