"""Results as frozen dataclasses.

Field names, units and meanings mirror the proto messages of the same name
(``proto/railcontact/v1/railcontact.proto``, SI units in the names; forces
act ON THE RAIL). Enums are short lower-case names (``"exact"``,
``"converged"``, ``"left"``); optional messages are ``None`` when absent;
repeated fields are tuples; per-element fields are read-only numpy arrays
shaped ``(ny, nx)`` (row ``iy``, column ``ix``); forces in the track frame
are :class:`TrackForce` arrays of shape ``(3,)``.

Results compare with ``==`` field by field (arrays by value) and print as
indented summaries, one field a line, arrays as their shape and range
(``repr(result)`` and ``str(result)``; the fields themselves hold
everything).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any, Optional

import numpy as np

from ._build import enum_name

# Element states of ElementFields.state.
EXTERIOR, ADHESION, SLIP = 0, 1, 2


def from_pb(cls, message, **given):
    """A ``cls`` dataclass from ``message``: each field from the message's
    field of the same name (converted as the field's metadata says), except
    those in ``given``."""
    values = {}
    for f in dataclasses.fields(cls):
        if f.name in given:
            values[f.name] = given[f.name]
            continue
        convert = f.metadata.get("pb")
        if convert is None:
            values[f.name] = getattr(message, f.name)
        else:
            values[f.name] = convert(message, f.name)
    return cls(**values)


def _sub(cls):
    """A nested message."""
    return field(metadata={"pb": lambda m, name: from_pb(cls, getattr(m, name))})


def _optional(cls):
    """An optional nested message: None when not set."""
    return field(
        metadata={"pb": lambda m, name: from_pb(cls, getattr(m, name)) if m.HasField(name) else None}
    )


def _optional_number():
    """An optional scalar field: None when not set."""
    return field(metadata={"pb": lambda m, name: getattr(m, name) if m.HasField(name) else None})


def _many(cls=None):
    """A repeated field: a tuple (of dataclasses when ``cls`` is given)."""
    if cls is None:
        return field(metadata={"pb": lambda m, name: tuple(getattr(m, name))})
    return field(metadata={"pb": lambda m, name: tuple(from_pb(cls, x) for x in getattr(m, name))})


def _array():
    """A repeated number field: a read-only 1-D array."""
    return field(metadata={"pb": lambda m, name: _readonly(getattr(m, name))})


def _enum():
    """An enum: its short lower-case name."""
    return field(
        metadata={"pb": lambda m, name: enum_name(m.DESCRIPTOR.fields_by_name[name].enum_type, getattr(m, name))}
    )


def _given():
    """Set by the caller (it needs more than the message)."""
    return field(metadata={"pb": None})


def _track_force():
    """A TrackForce message: a :class:`TrackForce` array."""
    return field(metadata={"pb": lambda m, name: TrackForce.from_pb(getattr(m, name))})


# -- what every result shares: ==, hash and a readable repr -----------------

#: Width up to which a value is written on one line.
_LINE = 88
#: Items of a longer tuple shown: the first ones and the last.
_HEAD, _TAIL = 4, 1


def _equal(a: Any, b: Any) -> bool:
    """Whether two field values are equal, arrays by shape and value."""
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return (
            isinstance(a, np.ndarray)
            and isinstance(b, np.ndarray)
            and a.shape == b.shape
            and bool(np.array_equal(a, b))
        )
    if isinstance(a, tuple) and isinstance(b, tuple):
        return len(a) == len(b) and all(_equal(x, y) for x, y in zip(a, b))
    return bool(a == b)


def _hashable(value: Any) -> Any:
    """A hashable stand-in of a field value (arrays by shape and bytes)."""
    if isinstance(value, np.ndarray):
        return (value.shape, value.tobytes())
    if isinstance(value, tuple):
        return tuple(_hashable(v) for v in value)
    return value


def _number(value: Any) -> str:
    """A number as the summaries write it (6 significant digits)."""
    if isinstance(value, (bool, np.bool_)):
        return str(bool(value))
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    return f"{float(value):.6g}"


def _array_summary(array: np.ndarray) -> str:
    """An array in a summary: its values when there are at most three,
    else its shape and range."""
    name = type(array).__name__ if isinstance(array, TrackForce) else "array"
    if array.ndim == 1 and array.size <= 3:
        return f"{name}([{', '.join(_number(v) for v in array)}])"
    if array.size == 0:
        return f"{name}(shape={array.shape})"
    return f"{name}(shape={array.shape}, min={_number(array.min())}, max={_number(array.max())})"


def _block(opening: str, items: list, closing: str, indent: str, single: str = "") -> str:
    """``items`` (already formatted) between ``opening`` and ``closing``: on
    one line when they fit (``single`` before the closing of one item:
    ``(x,)``), else one a line, indented."""
    one_line = f"{opening}{', '.join(items)}{single if len(items) == 1 else ''}{closing}"
    if len(indent) + len(one_line) <= _LINE and "\n" not in one_line:
        return one_line
    inner = indent + "  "
    lines = "".join(f"{inner}{item},\n" for item in items)
    return f"{opening}\n{lines}{indent}{closing}"


def summary(value: Any, indent: str = "") -> str:
    """A readable, indented summary of a result (or of any value in one):
    a dataclass one field a line, nested ones indented, arrays as their
    shape and range, numbers to 6 significant digits, tuples of more than
    five items as their first four and last, texts of several lines as
    their size. What ``repr`` and ``str`` of every result give."""
    inner = indent + "  "
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        items = [
            f"{f.name}={summary(getattr(value, f.name), inner)}"
            for f in dataclasses.fields(value)
            if f.repr
        ]
        return _block(f"{type(value).__name__}(", items, ")", indent)
    if isinstance(value, np.ndarray):
        return _array_summary(value)
    if isinstance(value, (tuple, list)):
        shown = list(value)
        if len(shown) > _HEAD + _TAIL:
            hidden = len(shown) - _HEAD - _TAIL
            items = [summary(v, inner) for v in shown[:_HEAD]]
            items.append(f"... {hidden} more ...")
            items += [summary(v, inner) for v in shown[-_TAIL:]]
        else:
            items = [summary(v, inner) for v in shown]
        if isinstance(value, tuple):
            return _block("(", items, ")", indent, single=",")
        return _block("[", items, "]", indent)
    if isinstance(value, Mapping):
        items = [f"{k!r}: {summary(v, inner)}" for k, v in value.items()]
        return _block("{", items, "}", indent)
    if isinstance(value, (float, int, np.floating, np.integer, np.bool_)) and not isinstance(value, bool):
        return _number(value)
    if isinstance(value, str) and "\n" in value.strip():
        lines = value.count("\n") + 1
        return f"<text: {lines} lines, {len(value)} characters>"
    return repr(value)


class _Result:
    """Base of the result dataclasses (declared ``eq=False, repr=False``):
    ``==`` compares the fields, arrays by value; results with equal fields
    hash equally; ``repr`` and ``str`` are :func:`summary`."""

    __slots__ = ()

    def __eq__(self, other: object) -> bool:
        if other.__class__ is not self.__class__:
            return NotImplemented
        return all(
            _equal(getattr(self, f.name), getattr(other, f.name))
            for f in dataclasses.fields(self)
            if f.compare
        )

    def __hash__(self) -> int:
        values = tuple(_hashable(getattr(self, f.name)) for f in dataclasses.fields(self) if f.compare)
        return hash((type(self).__name__, values))

    def __repr__(self) -> str:
        return summary(self)

    __str__ = __repr__


def _result(cls):
    """The dataclass decorator of the results: frozen, with
    :class:`_Result`'s ``==``, hash and repr."""
    return dataclass(frozen=True, eq=False, repr=False)(cls)


@_result
class Creepages(_Result):
    """Steady-rolling creepages: rail relative to wheel over the rolling speed."""

    creepage_long: float  # [-]
    creepage_lat: float  # [-]
    spin_per_m: float  # [1/m]


@_result
class PatchTotals(_Result):
    """Totals of one solution; forces and moment act on the rail."""

    normal_force_n: float
    fx_n: float
    fy_n: float
    mz_nm: float
    approach_m: float
    max_pressure_pa: float
    max_traction_pa: float
    contact_area_m2: float
    patch_length_m: float
    patch_width_m: float
    adhesion_fraction: float
    tgamma_n: float
    frictional_work_j: float


@_result
class ConformalTotals(_Result):
    """Additional totals of the conformal models."""

    contact_angle_variation_deg: float
    length_width_ratio: float
    normal_force_from_tractions_n: float
    pressure_resultant_n: float
    fy_global_n: float
    fz_global_n: float


@_result
class SolverInfo(_Result):
    """Solver counters; ``status`` is ``"converged"`` or ``"max_iterations"``."""

    status: str = _enum()
    normal_iterations: int
    tangential_iterations: int
    coupling_iterations: int
    matvecs: int
    normal_residual: float
    tangential_residual: float
    solve_time_s: float


@_result
class ForceDerivatives(_Result):
    """Derivatives of (Fn, Fx, Fy, Mz) on the rail with respect to one input."""

    normal_force: float
    fx: float
    fy: float
    mz: float


@_result
class Sensitivities(_Result):
    """The Jacobian of the patch forces at fixed approach."""

    per_approach_m: ForceDerivatives = _sub(ForceDerivatives)
    per_creepage_long: ForceDerivatives = _sub(ForceDerivatives)
    per_creepage_lat: ForceDerivatives = _sub(ForceDerivatives)
    per_spin_per_m: ForceDerivatives = _sub(ForceDerivatives)
    solves: int


@_result
class StepResult(_Result):
    """One solution: totals, solver counters and the optional parts."""

    totals: PatchTotals = _sub(PatchTotals)
    info: SolverInfo = _sub(SolverInfo)
    conformal: Optional[ConformalTotals] = _optional(ConformalTotals)
    sensitivities: Optional[Sensitivities] = _optional(Sensitivities)


@_result
class Grid(_Result):
    """The potential contact grid (y is s for the conformal models)."""

    nx: int
    ny: int
    element_size_x_m: float
    element_size_y_m: float
    x0_m: float
    y0_m: float

    def x_m(self) -> np.ndarray:
        """Element centres in x [m], ``nx`` values."""
        return self.x0_m + (np.arange(self.nx) + 0.5) * self.element_size_x_m

    def y_m(self) -> np.ndarray:
        """Element centres in y (conformal: s) [m], ``ny`` values."""
        return self.y0_m + (np.arange(self.ny) + 0.5) * self.element_size_y_m

    def extent_m(self) -> tuple:
        """``(x_min, x_max, y_min, y_max)`` of the grid [m] (for imshow)."""
        return (
            self.x0_m,
            self.x0_m + self.nx * self.element_size_x_m,
            self.y0_m,
            self.y0_m + self.ny * self.element_size_y_m,
        )


def _readonly(values, shape=None, dtype=float) -> np.ndarray:
    array = np.array(values, dtype=dtype)
    if shape is not None:
        array = array.reshape(shape)
    array.flags.writeable = False
    return array


def _layer(values, shape, dtype=float) -> np.ndarray:
    """An interfacial layer's field: shaped as the grid, empty without."""
    return _readonly(values, shape if len(values) else None, dtype)


@_result
class ElementFields(_Result):
    """Per-element fields on the grid, arrays shaped ``(ny, nx)``.

    ``state`` holds EXTERIOR (0), ADHESION (1) or SLIP (2). The conformal
    models add ``delta_rad`` and ``wfric_lateral_j_per_m2`` (``ny`` values)
    and ``reference_points_m`` (``(ny, 2)``: y, z); empty otherwise. A
    case with an elasto-plastic ``interfacial_layer`` (model exact) adds
    the layer's state after the solve, shaped ``(ny, nx)``:
    ``layer_yield_limit_pa`` (CONTACT's TAUCRT), ``layer_plastic_x_m``,
    ``layer_plastic_y_m`` (UPLSX, UPLSY) and ``layer_plastic`` (bool, the
    plasticity area); empty otherwise.
    """

    pressure_pa: np.ndarray
    traction_x_pa: np.ndarray
    traction_y_pa: np.ndarray
    slip_x: np.ndarray
    slip_y: np.ndarray
    state: np.ndarray
    gap_m: np.ndarray
    delta_rad: np.ndarray
    reference_points_m: np.ndarray
    wfric_lateral_j_per_m2: np.ndarray
    layer_yield_limit_pa: np.ndarray
    layer_plastic_x_m: np.ndarray
    layer_plastic_y_m: np.ndarray
    layer_plastic: np.ndarray

    @classmethod
    def from_pb(cls, message, grid: Grid) -> "ElementFields":
        shape = (grid.ny, grid.nx)
        return cls(
            pressure_pa=_readonly(message.pressure_pa, shape),
            traction_x_pa=_readonly(message.traction_x_pa, shape),
            traction_y_pa=_readonly(message.traction_y_pa, shape),
            slip_x=_readonly(message.slip_x, shape),
            slip_y=_readonly(message.slip_y, shape),
            state=_readonly(message.state, shape, np.int8),
            gap_m=_readonly(message.gap_m, shape),
            delta_rad=_readonly(message.delta_rad),
            reference_points_m=_readonly([(p.y_m, p.z_m) for p in message.reference_points_m]).reshape(-1, 2),
            wfric_lateral_j_per_m2=_readonly(message.wfric_lateral_j_per_m2),
            layer_yield_limit_pa=_layer(message.layer_yield_limit_pa, shape),
            layer_plastic_x_m=_layer(message.layer_plastic_x_m, shape),
            layer_plastic_y_m=_layer(message.layer_plastic_y_m, shape),
            layer_plastic=_layer(message.layer_plastic, shape, bool),
        )

    @property
    def traction_pa(self) -> np.ndarray:
        """Magnitude of the tangential traction [Pa]."""
        return np.hypot(self.traction_x_pa, self.traction_y_pa)


def fields_of(message, grid: Optional[Grid]) -> Optional[ElementFields]:
    """The message's optional ``fields`` on ``grid`` (None if absent)."""
    if grid is None or not message.HasField("fields"):
        return None
    return ElementFields.from_pb(message.fields, grid)


def _gridded(cls, message):
    """A ``cls`` from a message with an optional ``grid`` and ``fields`` on it."""
    grid = from_pb(Grid, message.grid) if message.HasField("grid") else None
    return from_pb(cls, message, fields=fields_of(message, grid))


@_result
class TemperaturePeak(_Result):
    """A surface's highest flash temperature [K] and where it is [m]."""

    temperature_k: float
    x_m: float
    y_m: float


@_result
class TemperatureResult(_Result):
    """Flash temperatures of a patch (the proto's TemperatureResult):
    body 1 is the rail in wheel/rail results, the wheel body 2. The
    per-element fields (index ``iy * nx + ix``) are empty unless fields
    were asked for."""

    max_body1: TemperaturePeak = _sub(TemperaturePeak)
    max_body2: TemperaturePeak = _sub(TemperaturePeak)
    contact_temperature_k: float
    heat_share_body1: float
    frictional_power_w: float
    peclet_number: float
    body1_k: np.ndarray = _array()
    body2_k: np.ndarray = _array()
    heat_flux_w_per_m2: np.ndarray = _array()


@_result
class ForceControl(_Result):
    """The outcome of a prescribed-force solve (a patch case's
    ``force_x_n``, ``force_y_n`` or ``force_x_n_per_m``): the creepages that
    give the prescribed forces (the given ones in the other directions) and
    the outer iteration's count of iterations and exact solves."""

    creepage_long: float
    creepage_lat: float
    spin_per_m: float
    force_iterations: int
    force_solves: int


@_result
class PatchResult(_Result):
    """The result of one patch case (SolvePatch, a creep-curve point).
    ``force_control`` is set when the case prescribes a force in steady
    rolling (None otherwise). Model ``fastsim``: ``totals.max_pressure_pa``
    is Hertz's p0, ``fastsim_max_pressure_pa`` the peak of FASTSIM's
    traction bound (the maximum pressure CONTACT's FASTSIM reports): the
    parabolic one's 2 Fn/(pi a b) = 4/3 p0 by default, the elliptic one's
    p0 with ``fastsim.traction_bound = "elliptic"``; None with the other
    models.
    ``steady_start`` is the steady rolling state transient steps started
    from (``transient.steady_start``; None otherwise)."""

    model: str = _enum()
    result: StepResult = _sub(StepResult)
    steps: tuple = _many(StepResult)
    friction_coefficient: float
    grid: Optional[Grid] = _optional(Grid)
    notes: tuple = _many()
    fields: Optional[ElementFields] = _given()
    temperature: Optional[TemperatureResult] = _optional(TemperatureResult)
    force_control: Optional[ForceControl] = _optional(ForceControl)
    fastsim_max_pressure_pa: Optional[float] = _optional_number()
    steady_start: Optional[StepResult] = _optional(StepResult)

    @classmethod
    def from_pb(cls, message) -> "PatchResult":
        return _gridded(cls, message)

    @property
    def totals(self) -> PatchTotals:
        """The final solution's totals (``result.totals``)."""
        return self.result.totals


@_result
class CreepCurvePoint(_Result):
    """One point of a creep curve."""

    index: int
    creepages: Creepages = _sub(Creepages)
    result: PatchResult = field(
        metadata={"pb": lambda m, name: PatchResult.from_pb(m.result)}
    )


@_result
class SessionStepResult(_Result):
    """The answer to one patch-session step."""

    step_index: int
    time_s: float
    result: StepResult = _sub(StepResult)
    fields: Optional[ElementFields] = _given()
    marked: bool

    @property
    def totals(self) -> PatchTotals:
        """``result.totals``."""
        return self.result.totals


class TrackForce(np.ndarray):
    """A force on the rail in the track frame (x forward, y to the right,
    z down) [N]: a read-only numpy array ``[x, y, z]`` of shape ``(3,)``,
    like :attr:`WheelRailResult.force_track_n`, with its components also as
    ``x_n``, ``y_n`` and ``z_n``. Arithmetic on it gives plain arrays
    (``left.force_track_n + right.force_track_n``), ``==`` compares
    element by element as numpy does."""

    def __new__(cls, x_n: float = 0.0, y_n: float = 0.0, z_n: float = 0.0) -> "TrackForce":
        force = np.array((x_n, y_n, z_n), dtype=float).view(cls)
        force.flags.writeable = False
        return force

    @classmethod
    def from_pb(cls, message) -> "TrackForce":
        """The force of a ``TrackForce`` message."""
        return cls(message.x_n, message.y_n, message.z_n)

    @property
    def x_n(self) -> float:
        """Longitudinal component [N] (forward)."""
        return float(self.view(np.ndarray)[0])

    @property
    def y_n(self) -> float:
        """Lateral component [N] (to the right)."""
        return float(self.view(np.ndarray)[1])

    @property
    def z_n(self) -> float:
        """Vertical component [N] (down)."""
        return float(self.view(np.ndarray)[2])

    def as_array(self) -> np.ndarray:
        """A plain, writable copy ``[x, y, z]`` [N]."""
        return np.array(self.view(np.ndarray))

    def __getitem__(self, key):
        # Components and slices as plain numbers and arrays.
        return self.view(np.ndarray)[key]

    def __array_wrap__(self, array, context=None, return_scalar=False):
        # Arithmetic and reductions give plain arrays and numbers (numpy 1
        # passes no return_scalar: a 0-d result is a reduction's number).
        array = array.view(np.ndarray)
        return array[()] if return_scalar or array.ndim == 0 else array

    def __reduce__(self):
        # Pickled by its components (read-only again when unpickled).
        return (TrackForce, tuple(float(v) for v in self.view(np.ndarray)))


@_result
class WheelRailPatch(_Result):
    """One contact patch of a wheel (see the proto's WheelRailPatch).

    ``max_pressure_pa`` of a Hertz patch is Hertz's p0;
    ``fastsim_max_pressure_pa`` (None unless FASTSIM solved the patch) the
    peak of the pressure bounding FASTSIM's tractions: 2 Fn/(pi a b) =
    4/3 p0 with the parabolic bound (CONTACT's FASTSIM PMAX), p0 with the
    elliptic bound of ``hertz_fastsim_elliptic``."""

    method: str = _enum()
    contact_angle_rad: float
    contact_angle_variation_rad: float
    rail_y_m: float
    rail_z_m: float
    wheel_y_m: float
    track_x_m: float
    track_y_m: float
    track_z_m: float
    rolling_radius_m: float
    creepage_long: float
    creepage_lat: float
    spin_per_m: float
    normal_force_n: float
    fx_n: float
    fs_n: float
    mz_nm: float
    approach_m: float
    max_pressure_pa: float
    contact_area_m2: float
    adhesion_fraction: float
    frictional_power_w: float
    force_track_n: TrackForce = _track_force()
    grid_nx: int
    grid_ns: int
    grid: Optional[Grid] = _optional(Grid)
    fields: Optional[ElementFields] = _given()
    friction_coefficient: float
    temperature: Optional[TemperatureResult] = _optional(TemperatureResult)
    rolling_speed_m_per_s: float
    fastsim_max_pressure_pa: Optional[float] = _optional_number()

    @classmethod
    def from_pb(cls, message) -> "WheelRailPatch":
        return _gridded(cls, message)


@_result
class WheelRailWheel(_Result):
    """One wheel: its patches (field side to gauge side) and totals."""

    side: str = _enum()
    vertical_approach_m: float
    min_gap_m: float
    patches: tuple = field(
        metadata={"pb": lambda m, name: tuple(WheelRailPatch.from_pb(p) for p in m.patches)}
    )
    force_track_n: TrackForce = _track_force()
    load_iterations: int


@_result
class WheelRailTiming(_Result):
    """Where the server's solve time went [s]."""

    search_s: float
    geometry_s: float
    solve_s: float


@_result
class PitchControl(_Result):
    """How the pitch rate was found for a prescribed total longitudinal
    force (``load={"total_longitudinal_force_n": ...}``): the force reached
    [N], the nominal longitudinal creepage [-], steps and solves."""

    target_force_n: float
    force_n: float
    nominal_creepage: float
    iterations: int
    solves: int
    converged: bool


def _side_or_none():
    """A WheelSide: its short name, ``None`` when unspecified."""
    def convert(m, name):
        number = getattr(m, name)
        return enum_name(m.DESCRIPTOR.fields_by_name[name].enum_type, number) if number else None

    return field(metadata={"pb": convert})


@_result
class WheelRailWarning(_Result):
    """A finding about a wheel/rail answer (the proto's WheelRailWarning):
    what no elastic contact gives, or forces inconsistent with the motion
    given. ``kind`` is ``"approach"`` (a wheel pressed into its rail far
    beyond the elastic approach of its load), ``"longitudinal_force"``
    (both wheels driven or braked the same way to near saturation by the
    pitch rate given), ``"unconverged"`` (patches of the wheel whose exact
    solver stopped at its iteration limit: ``value`` counts them) or
    ``"opposed_surfaces"`` (a longitudinal creepage beyond the 2 of a
    locked wheel: the wheel's and the rail's or roller's surfaces move
    against each other, e.g. rollers and wheel turning the same way);
    ``field`` the request path of the input at fault
    (``"position.roll_rad"``, ``"velocity.pitch_rad_per_s"``,
    ``"load.vertical_force_n"``, ``"model"``; ``"items[3]."`` before it in
    a batch, ``"step."`` in a session, whose model is ``"open.model"``); ``side`` the wheel (``"left"``,
    ``"right"``), ``None`` for the wheelset; ``value`` the measure that
    exceeded its ``limit`` [-]; ``message`` what, why and what to do."""

    kind: str = _enum()
    field: str
    side: Optional[str] = _side_or_none()
    value: float
    limit: float
    message: str

    def __str__(self) -> str:
        return f"{self.field}: {self.message}"


@_result
class WheelRailResult(_Result):
    """The solution of one wheelset query: the wheels solved, left first.
    ``pitch_control`` is set when the total longitudinal force was
    prescribed. ``warnings`` (a tuple of :class:`WheelRailWarning`, empty
    for a plausible answer) says what in the answer no elastic contact
    gives, naming the input at fault; the answer is the solver's all the
    same."""

    pair_id: str
    model: str = _enum()
    center_z_m: float
    roll_rad: float
    pitch_rad_per_s: float
    wheels: tuple = _many(WheelRailWheel)
    timing: WheelRailTiming = _sub(WheelRailTiming)
    pitch_control: Optional[PitchControl] = _optional(PitchControl)
    warnings: tuple = _many(WheelRailWarning)

    def wheel(self, side: str) -> WheelRailWheel:
        """The wheel of ``side`` (``"left"`` or ``"right"``)."""
        for w in self.wheels:
            if w.side == side:
                return w
        raise KeyError(f"no {side} wheel in this result")

    @property
    def force_track_n(self) -> TrackForce:
        """Sum of the wheels' forces on the rails, track frame [N]: a
        :class:`TrackForce` as each wheel's (``[x, y, z]``, ``.x_n``, ...)."""
        total = sum((w.force_track_n.as_array() for w in self.wheels), np.zeros(3))
        return TrackForce(*total)


@_result
class WheelRailStepResult(_Result):
    """The answer to one wheel/rail session step."""

    step_index: int
    time_s: float
    result: WheelRailResult = _sub(WheelRailResult)
    marked: bool


@_result
class ProfilePairInfo(_Result):
    """A registered profile pair. ``raw`` is the full ProfilePairInfo
    message (profiles, track, wheelset, materials, friction)."""

    pair_id: str
    label: str
    builtin_pair: str
    state: str = _enum()
    error: str
    element_size_m: float
    smoothing_wavelength_m: float
    prepare_time_s: float
    persisted: bool
    raw: object = field(metadata={"pb": lambda m, name: m}, compare=False, repr=False)


@_result
class RegistrationProgress(_Result):
    """One progress message of a registration (``stage`` e.g. ``"ready"``)."""

    stage: str = _enum()
    pair_id: str
    fraction_done: float
    elapsed_s: float
    message: str
    pair: Optional[ProfilePairInfo] = _optional(ProfilePairInfo)
    already_registered: bool
