"""Case files of ``railcontact wheelrail`` (TOML) for the service.

A wheel/rail case file (``examples/cases/wheelset_a22.toml``; keys in
``examples/cases/README.md``, "Wheelset cases") holds three things the
service takes apart: a profile pair (``[track]``, ``[wheelset]``,
``[material]``: ``RegisterProfilePair``), the settings of a query or a
session (``model``, ``side``, ``[friction]``, ``[grid]``, ``[polach]``,
``[modified_fastsim]``, ``[conformal]``, ``[temperature]``) and the motion
of one step (``[position]``, ``[velocity]``, ``[load]``).
:func:`load_wheelrail_case` reads such a file into a :class:`WheelRailCase`
holding the three as mappings for :meth:`Client.register_pair`,
:meth:`Client.solve_wheelrail`, :meth:`Client.wheelrail_session` and
:meth:`WheelRailSession.step`; :meth:`Client.solve_wheelrail_case` does all
of it in one call, with the same answer as ``railcontact wheelrail
CASE.toml``.
"""

from __future__ import annotations

import os
import pathlib
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, Optional, Union

from .errors import invalid
from .results import summary

#: A profile's name in a case file that names a built-in profile
#: (``builtin:MBench_S1002_v3.prw``, ``builtin:MBench_UIC60_v3.prr``).
BUILTIN_PREFIX = "builtin:"

# The keys of each table as `railcontact wheelrail` reads them
# (src/cli/wheelrail.rs), as (required, optional): every table rejects
# other keys.
_TABLES: dict = {
    "": (
        (),
        ("model", "side", "material", "friction", "track", "wheelset", "position", "velocity",
         "load", "grid", "polach", "modified_fastsim", "conformal", "temperature"),
    ),
    "material": (("shear_modulus_pa", "poisson_ratio"), ()),
    "friction": (
        (),
        ("law", "coefficient", "static_coefficient", "kinetic_coefficient", "falling_coefficients",
         "half_velocities_m_per_s", "rolling_speed_m_per_s", "memory_distance_m",
         "memory_velocity_m_per_s", "start", "max_iterations", "contact_angles_rad", "rail_y_m",
         "coefficients", "track_s_m"),
    ),
    "track": (
        ("rail_profile",),
        ("rail_profile_left", "rail_mirror_y", "cant_rad", "gauge_m", "gauge_height_m", "rail_origin_y_m",
         "rail_origin_z_m", "roller_radius_m", "roller_rad_per_s", "curvature_per_m", "rail_profile_unit",
         "rail_deviation_left", "rail_deviation_right"),
    ),
    "track.rail_deviation_left": ((), ("dy_m", "dz_m", "droll_rad")),
    "wheelset": (
        ("wheel_profile", "flange_back_distance_m", "nominal_radius_m"),
        ("wheel_profile_left", "wheel_mirror_y", "flange_back_y_m", "smoothing_wavelength_m",
         "wheel_profile_unit"),
    ),
    "position": ((), ("lateral_m", "yaw_rad", "roll_rad", "track_s_m")),
    "velocity": (
        (),
        ("forward_m_per_s", "lateral_m_per_s", "vertical_m_per_s", "roll_rad_per_s", "yaw_rad_per_s",
         "pitch_rad_per_s"),
    ),
    "load": ((), ("vertical_force_n", "approach_m", "center_z_m", "total_longitudinal_force_n")),
    "grid": (("element_size_m",), ("min_elements_across", "force_tolerance_of_wheel_load")),
    "polach": (("k_adhesion", "k_slip", "limit_ratio", "decay_s_per_m"), ()),
    "modified_fastsim": (
        (),
        ("initial_factor", "limit_ratio", "transition_rate", "friction_limit_ratio",
         "friction_decay_s_per_m"),
    ),
    "conformal": ((), ("rigid_slip",)),
    "temperature": (("rail", "wheel"), ()),
    "temperature.rail": (
        ("bulk_temperature_k", "conductivity_w_per_m_k", "density_kg_per_m3", "specific_heat_j_per_kg_k"),
        (),
    ),
}
_TABLES["temperature.wheel"] = _TABLES["temperature.rail"]
_TABLES["track.rail_deviation_right"] = _TABLES["track.rail_deviation_left"]

#: The rails' deviations from their placement, the wire's ``TrackSpec``
#: fields of the same names.
_DEVIATIONS = ("rail_deviation_left", "rail_deviation_right")

#: The keys of ``[friction]`` that make a friction table (the wire's
#: ``friction_table``); the others are its law (``friction``).
_FRICTION_TABLE_KEYS = ("contact_angles_rad", "rail_y_m", "coefficients", "track_s_m")

#: ``[modified_fastsim]``'s defaults, key by key (the command line's
#: ``SlopeReduction::TRACTCURV``); the wire takes the section whole.
_MODIFIED_FASTSIM_DEFAULTS = {
    "initial_factor": 0.54,
    "limit_ratio": 0.02,
    "transition_rate": 0.62,
    "friction_limit_ratio": 1.0,
    "friction_decay_s_per_m": 0.0,
}

#: The vertical load's keys, exactly one of which a case gives.
_LOAD_KINDS = ("vertical_force_n", "approach_m", "center_z_m")

#: The two ways of placing the rails, one of which a case gives whole: by
#: the gauge, or by the rail profiles' origins.
_PLACEMENTS = (("gauge_m", "gauge_height_m"), ("rail_origin_y_m", "rail_origin_z_m"))

#: The keys of ``[track]`` that the pair's ``TrackSpec`` takes as they are.
_TRACK_SPEC_KEYS = (
    "gauge_m", "gauge_height_m", "cant_rad", "rail_origin_y_m", "rail_origin_z_m", "roller_radius_m",
    "curvature_per_m",
)


@dataclass(frozen=True)
class WheelRailCase:
    """A ``railcontact wheelrail`` case file, taken apart for the service.

    ``pair``: the profile pair, a ``ProfilePairSpec`` mapping for
    :meth:`Client.register_pair` (profile files read, relative to the case
    file; ``builtin:`` names as built-in profiles). ``settings``: the
    keyword arguments of :meth:`Client.wheelrail_session` (and of
    :meth:`Client.solve_wheelrail`) the case gives: ``model``, ``sides``,
    ``friction``, ``friction_table``, ``element_size_m``,
    ``min_elements_across``, ``force_tolerance_of_wheel_load``, ``polach``,
    ``modified_fastsim``, ``conformal``, ``temperature``. ``motion``: those of
    :meth:`WheelRailSession.step`, ``position``, ``velocity`` and ``load``.
    ``label``: the case file's name, the pair's label when it is new.

    ::

        case = railcontact.load_wheelrail_case("examples/cases/wheelset_a22.toml")
        pair = client.register_pair(case.pair, label=case.label)
        r = client.solve_wheelrail(pair.pair_id, **case.solve_arguments())
        with client.wheelrail_session(pair.pair_id, **case.settings) as s:
            step = s.step(**case.motion)
    """

    path: pathlib.Path
    label: str
    pair: dict
    settings: dict
    motion: dict

    def solve_arguments(self, **overrides: Any) -> dict:
        """The keyword arguments of :meth:`Client.solve_wheelrail` after the
        pair id: ``settings`` and ``motion``, with ``overrides`` in place
        of the case's (``model="hertz_fastsim"``, ``position={...}``,
        ``include_fields=True``)."""
        return {**self.settings, **self.motion, **overrides}

    def __repr__(self) -> str:
        return summary(self)


def load_wheelrail_case(path: Union[str, os.PathLike]) -> WheelRailCase:
    """Reads a ``railcontact wheelrail`` case file (TOML) into a
    :class:`WheelRailCase`: its profile pair, settings and motion.

    The keys are the command line's (``examples/cases/README.md``,
    "Wheelset cases"), with its defaults: model ``"exact"``, both wheels,
    the pair's material (82 GPa, 0.28), friction (Coulomb 0.3) and element
    size (0.2 mm) where the file gives none. Profile files are read
    relative to the case file; ``builtin:NAME`` names a built-in profile.
    A file that cannot be read or is not TOML, an unknown or missing key
    and a profile file that cannot be read raise :class:`RailcontactError`
    (INVALID_ARGUMENT) naming the case file's key (``case`` for the file
    itself); the values are checked by the server.
    """
    path = pathlib.Path(path)
    try:
        with open(path, "rb") as f:
            case = tomllib.load(f)
    except (OSError, tomllib.TOMLDecodeError) as e:
        raise invalid("case", f"cannot read case file {os.fspath(path)}: {e}") from e
    _check_table(case, "")
    for key in ("track", "wheelset", "velocity", "load"):
        if key not in case:
            raise invalid(key, f"missing: a wheel/rail case file needs [{key}] ({path})")
    tables = {
        key: _check_table(case[key], key)
        for key in _TABLES
        if key and "." not in key and key in case
    }
    if "temperature" in tables:
        for body in ("rail", "wheel"):
            _check_table(tables["temperature"][body], f"temperature.{body}")
    for key in _DEVIATIONS:
        if key in tables["track"]:
            _check_table(tables["track"][key], f"track.{key}")

    pair = _pair(tables["track"], tables["wheelset"], tables.get("material"), path.parent)
    return WheelRailCase(
        path=path,
        label=path.name,
        pair=pair,
        settings=_settings(case, tables),
        motion=_motion(tables),
    )


def _check_table(table: Any, key: str) -> dict:
    """``table`` (the case file's table ``key``, ``""`` the top level) after
    checking its keys: none unknown, none missing."""
    if not isinstance(table, Mapping):
        raise invalid(key, f"expected a table ([{key}]), got {table!r}")
    required, optional = _TABLES[key]
    for name in table:
        if name not in required and name not in optional:
            known = ", ".join(f"`{k}`" for k in required + optional)
            raise invalid(_join(key, name), f"unknown key; expected one of {known}")
    for name in required:
        if name not in table:
            raise invalid(_join(key, name), "missing: required")
    return dict(table)


def _join(table: str, key: str) -> str:
    return f"{table}.{key}" if table else key


def _profile(
    name: Any, mirror_y: Any, unit: Optional[str], directory: pathlib.Path, key: str, mirror_key: str
) -> dict:
    """A ``ProfileSource`` mapping of the case file's profile ``name`` (a
    path relative to ``directory`` or ``builtin:NAME``); ``unit``, the
    case's unit of plain tables (``"m"``, ``"mm"`` or None: the file's
    own), is each file's ``plain_unit``."""
    if not isinstance(name, str) or not name:
        raise invalid(key, f"expected a file name or `{BUILTIN_PREFIX}NAME`, got {name!r}")
    if not isinstance(mirror_y, bool):
        raise invalid(mirror_key, f"expected true or false, got {mirror_y!r}")
    if name.startswith(BUILTIN_PREFIX):
        return {"builtin_name": name[len(BUILTIN_PREFIX):], "mirror_y": mirror_y}
    file = directory / name
    content = _read_text(file, key)
    if file.suffix.lower() == ".slcs" and key.startswith("track."):
        # A rail varying along the track: the slices file with the profile
        # files it names (relative to it), by the names written there.
        profiles = [
            _file(_read_text(file.parent / n, key), n, unit) for n in _slice_profile_names(content)
        ]
        return {
            "slices": {"file_name": file.name, "content": content, "profiles": profiles},
            "mirror_y": mirror_y,
        }
    return {"file": _file(content, file.name, unit), "mirror_y": mirror_y}


def _file(content: str, file_name: str, unit: Optional[str]) -> dict:
    """A ``ProfileFile`` mapping; ``unit`` (when given) its ``plain_unit``."""
    file = {"content": content, "file_name": file_name}
    if unit is not None:
        file["plain_unit"] = unit
    return file


def _unit(table: dict, key: str, table_name: str) -> Optional[str]:
    """The profile unit ``table[key]``: ``"m"``, ``"mm"`` or None."""
    unit = table.get(key)
    if unit is not None and unit not in ("m", "mm"):
        raise invalid(f"{table_name}.{key}", f'expected "m" or "mm", got {unit!r}')
    return unit


def _read_text(file: pathlib.Path, key: str) -> str:
    """The text of ``file``; one that cannot be read raises naming ``key``."""
    try:
        raw = file.read_bytes()
    except OSError as e:
        raise invalid(key, f"cannot read profile file {file}: {e}") from e
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError:
        # MiniProf files written on Windows: their comments in Latin-1.
        return raw.decode("latin-1")


def _slice_profile_names(text: str) -> list:
    """The profile file names of a rail slices file (CONTACT's ``.slcs``),
    each once, in order: the second word (quoted with ' or ", or bare) of
    the lines after the four header lines (U_OFFSET, NSLC, NFEAT, U_INTPOL),
    skipping blank lines and ``%`` comments. The server reads the file
    itself and says what is wrong with it."""
    lines = [line.strip() for line in text.splitlines()]
    values = [line for line in lines if line and not line.startswith("%")][4:]
    names: list = []
    for line in values:
        rest = line.split(None, 1)[1].lstrip() if len(line.split(None, 1)) == 2 else ""
        if rest[:1] in ("'", '"'):
            name = rest[1:].split(rest[0], 1)[0]
        else:
            name = rest.split()[0] if rest else ""
        if name and name not in names:
            names.append(name)
    return names


def _placement(track: dict) -> None:
    """Checks that ``[track]`` places the rails one way, whole: by the
    gauge or by the rail profiles' origins (the command line's rule)."""
    gauge, origin = ([k for k in keys if k in track] for keys in _PLACEMENTS)
    if gauge and origin:
        raise invalid(
            "track",
            "give either gauge_m and gauge_height_m (the rails placed by the gauge point) or "
            "rail_origin_y_m and rail_origin_z_m (the rail profiles' origins placed absolutely)",
        )
    for key in _PLACEMENTS[1] if origin else _PLACEMENTS[0]:
        if key not in track:
            other = " or ".join(" and ".join(keys) for keys in _PLACEMENTS)
            raise invalid(_join("track", key), f"missing: the rails are placed by {other}")


def _pair(track: dict, wheelset: dict, material: Any, directory: pathlib.Path) -> dict:
    """The ``ProfilePairSpec`` mapping of ``[track]``, ``[wheelset]`` and
    ``[material]``."""
    _placement(track)
    rail_mirror = track.get("rail_mirror_y", False)
    wheel_mirror = wheelset.get("wheel_mirror_y", False)
    rail_unit = _unit(track, "rail_profile_unit", "track")
    wheel_unit = _unit(wheelset, "wheel_profile_unit", "wheelset")
    pair: dict = {
        "wheel": _profile(
            wheelset["wheel_profile"], wheel_mirror, wheel_unit, directory, "wheelset.wheel_profile",
            "wheelset.wheel_mirror_y",
        ),
        "rail": _profile(
            track["rail_profile"], rail_mirror, rail_unit, directory, "track.rail_profile", "track.rail_mirror_y"
        ),
        "track": {
            **{k: track[k] for k in _TRACK_SPEC_KEYS if k in track},
            **{k: dict(track[k]) for k in _DEVIATIONS if k in track},
        },
        "wheelset": {
            k: wheelset[k] for k in ("flange_back_distance_m", "nominal_radius_m", "flange_back_y_m") if k in wheelset
        },
    }
    if "wheel_profile_left" in wheelset:
        pair["wheel_left"] = _profile(
            wheelset["wheel_profile_left"], wheel_mirror, wheel_unit, directory, "wheelset.wheel_profile_left",
            "wheelset.wheel_mirror_y",
        )
    if "rail_profile_left" in track:
        pair["rail_left"] = _profile(
            track["rail_profile_left"], rail_mirror, rail_unit, directory, "track.rail_profile_left", "track.rail_mirror_y"
        )
    if "smoothing_wavelength_m" in wheelset:
        pair["smoothing_wavelength_m"] = wheelset["smoothing_wavelength_m"]
    if material is not None:
        pair["material"] = dict(material)
    return pair


def _settings(case: dict, tables: dict) -> dict:
    """The query's or session's settings of the case file."""
    settings: dict = {"model": case.get("model", "exact"), "sides": case.get("side", "both")}
    friction = tables.get("friction")
    if friction is not None:
        law = {k: v for k, v in friction.items() if k not in _FRICTION_TABLE_KEYS}
        table = {k: v for k, v in friction.items() if k in _FRICTION_TABLE_KEYS}
        # A table alone scales the pair's Coulomb law to its coefficients,
        # as the command line scales its Coulomb law of coefficient 1.
        if law or not table:
            settings["friction"] = law
        if table:
            settings["friction_table"] = table
    if "grid" in tables:
        settings["element_size_m"] = tables["grid"]["element_size_m"]
        for key in ("min_elements_across", "force_tolerance_of_wheel_load"):
            if key in tables["grid"]:
                settings[key] = tables["grid"][key]
    if "polach" in tables:
        settings["polach"] = tables["polach"]
    if "modified_fastsim" in tables:
        settings["modified_fastsim"] = {**_MODIFIED_FASTSIM_DEFAULTS, **tables["modified_fastsim"]}
    if "conformal" in tables:
        settings["conformal"] = tables["conformal"]
    if "temperature" in tables:
        t = tables["temperature"]
        settings["temperature"] = {"body1": dict(t["rail"]), "body2": dict(t["wheel"])}
    return settings


def _motion(tables: dict) -> dict:
    """The step's position, velocity and load of the case file. A roller
    rig's ``track.roller_rad_per_s`` is the velocity's ``roller_rad_per_s``
    on the wire (a motion, not a property of the pair)."""
    load = tables["load"]
    given = [k for k in _LOAD_KINDS if k in load]
    if len(given) != 1:
        raise invalid("load", "give exactly one of vertical_force_n, approach_m and center_z_m")
    track, velocity = tables["track"], dict(tables["velocity"])
    roller = "roller_radius_m" in track
    if roller != ("roller_rad_per_s" in track):
        raise invalid(
            "track.roller_rad_per_s",
            "a roller rig (track.roller_radius_m) needs its rollers' angular velocity"
            if roller
            else "needs a roller rig (track.roller_radius_m)",
        )
    if roller:
        velocity["roller_rad_per_s"] = track["roller_rad_per_s"]
    elif "forward_m_per_s" not in velocity:
        raise invalid("velocity.forward_m_per_s", "missing: the wheelset's forward speed on a track")
    return {
        "position": tables.get("position", {}),
        "velocity": velocity,
        "load": load,
    }
