"""Results as frozen dataclasses.

Field names, units and meanings mirror the proto messages of the same name
(``proto/railcontact/v1/railcontact.proto``, SI units in the names; forces
act ON THE RAIL). Enums are short lower-case names (``"exact"``,
``"converged"``, ``"left"``); optional messages are ``None`` when absent;
repeated fields are tuples; per-element fields are read-only numpy arrays
shaped ``(ny, nx)`` (row ``iy``, column ``ix``).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from typing import Optional

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


@dataclass(frozen=True)
class Creepages:
    """Steady-rolling creepages: rail relative to wheel over the rolling speed."""

    creepage_long: float  # [-]
    creepage_lat: float  # [-]
    spin_per_m: float  # [1/m]


@dataclass(frozen=True)
class PatchTotals:
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


@dataclass(frozen=True)
class ConformalTotals:
    """Additional totals of the conformal models."""

    contact_angle_variation_deg: float
    length_width_ratio: float
    normal_force_from_tractions_n: float
    pressure_resultant_n: float
    fy_global_n: float
    fz_global_n: float


@dataclass(frozen=True)
class SolverInfo:
    """Solver counters; ``status`` is ``"converged"`` or ``"max_iterations"``."""

    status: str = _enum()
    normal_iterations: int
    tangential_iterations: int
    coupling_iterations: int
    matvecs: int
    normal_residual: float
    tangential_residual: float
    solve_time_s: float


@dataclass(frozen=True)
class ForceDerivatives:
    """Derivatives of (Fn, Fx, Fy, Mz) on the rail with respect to one input."""

    normal_force: float
    fx: float
    fy: float
    mz: float


@dataclass(frozen=True)
class Sensitivities:
    """The Jacobian of the patch forces at fixed approach."""

    per_approach_m: ForceDerivatives = _sub(ForceDerivatives)
    per_creepage_long: ForceDerivatives = _sub(ForceDerivatives)
    per_creepage_lat: ForceDerivatives = _sub(ForceDerivatives)
    per_spin_per_m: ForceDerivatives = _sub(ForceDerivatives)
    solves: int


@dataclass(frozen=True)
class StepResult:
    """One solution: totals, solver counters and the optional parts."""

    totals: PatchTotals = _sub(PatchTotals)
    info: SolverInfo = _sub(SolverInfo)
    conformal: Optional[ConformalTotals] = _optional(ConformalTotals)
    sensitivities: Optional[Sensitivities] = _optional(Sensitivities)


@dataclass(frozen=True)
class Grid:
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


@dataclass(frozen=True, eq=False)
class ElementFields:
    """Per-element fields on the grid, arrays shaped ``(ny, nx)``.

    ``state`` holds EXTERIOR (0), ADHESION (1) or SLIP (2). The conformal
    models add ``delta_rad`` and ``wfric_lateral_j_per_m2`` (``ny`` values)
    and ``reference_points_m`` (``(ny, 2)``: y, z); empty otherwise.
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


@dataclass(frozen=True)
class TemperaturePeak:
    """A surface's highest flash temperature [K] and where it is [m]."""

    temperature_k: float
    x_m: float
    y_m: float


@dataclass(frozen=True, eq=False)
class TemperatureResult:
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


@dataclass(frozen=True)
class PatchResult:
    """The result of one patch case (SolvePatch, a creep-curve point)."""

    model: str = _enum()
    result: StepResult = _sub(StepResult)
    steps: tuple = _many(StepResult)
    friction_coefficient: float
    grid: Optional[Grid] = _optional(Grid)
    notes: tuple = _many()
    fields: Optional[ElementFields] = _given()
    temperature: Optional[TemperatureResult] = _optional(TemperatureResult)

    @classmethod
    def from_pb(cls, message) -> "PatchResult":
        return _gridded(cls, message)

    @property
    def totals(self) -> PatchTotals:
        """The final solution's totals (``result.totals``)."""
        return self.result.totals


@dataclass(frozen=True)
class CreepCurvePoint:
    """One point of a creep curve."""

    index: int
    creepages: Creepages = _sub(Creepages)
    result: PatchResult = field(
        metadata={"pb": lambda m, name: PatchResult.from_pb(m.result)}
    )


@dataclass(frozen=True)
class SessionStepResult:
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


@dataclass(frozen=True)
class TrackForce:
    """A force in the track frame (x forward, y right, z down) on the rail [N]."""

    x_n: float
    y_n: float
    z_n: float

    def as_array(self) -> np.ndarray:
        return np.array([self.x_n, self.y_n, self.z_n])


@dataclass(frozen=True)
class WheelRailPatch:
    """One contact patch of a wheel (see the proto's WheelRailPatch)."""

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
    force_track_n: TrackForce = _sub(TrackForce)
    grid_nx: int
    grid_ns: int
    grid: Optional[Grid] = _optional(Grid)
    fields: Optional[ElementFields] = _given()
    friction_coefficient: float
    temperature: Optional[TemperatureResult] = _optional(TemperatureResult)
    rolling_speed_m_per_s: float

    @classmethod
    def from_pb(cls, message) -> "WheelRailPatch":
        return _gridded(cls, message)


@dataclass(frozen=True)
class WheelRailWheel:
    """One wheel: its patches (field side to gauge side) and totals."""

    side: str = _enum()
    vertical_approach_m: float
    min_gap_m: float
    patches: tuple = field(
        metadata={"pb": lambda m, name: tuple(WheelRailPatch.from_pb(p) for p in m.patches)}
    )
    force_track_n: TrackForce = _sub(TrackForce)
    load_iterations: int


@dataclass(frozen=True)
class WheelRailTiming:
    """Where the server's solve time went [s]."""

    search_s: float
    geometry_s: float
    solve_s: float


@dataclass(frozen=True)
class PitchControl:
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


@dataclass(frozen=True)
class WheelRailWarning:
    """A finding about a wheel/rail answer (the proto's WheelRailWarning):
    what no elastic contact gives, or forces inconsistent with the motion
    given. ``kind`` is ``"approach"`` (a wheel pressed into its rail far
    beyond the elastic approach of its load) or ``"longitudinal_force"``
    (both wheels driven or braked the same way to near saturation by the
    pitch rate given); ``field`` the request path of the input at fault
    (``"position.roll_rad"``, ``"velocity.pitch_rad_per_s"``,
    ``"load.vertical_force_n"``; ``"items[3]."`` before it in a batch,
    ``"step."`` in a session); ``side`` the wheel (``"left"``,
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


@dataclass(frozen=True)
class WheelRailResult:
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
    def force_track_n(self) -> np.ndarray:
        """Sum of the wheels' forces on the rails, track frame [N] (x, y, z)."""
        return sum((w.force_track_n.as_array() for w in self.wheels), np.zeros(3))


@dataclass(frozen=True)
class WheelRailStepResult:
    """The answer to one wheel/rail session step."""

    step_index: int
    time_s: float
    result: WheelRailResult = _sub(WheelRailResult)
    marked: bool


@dataclass(frozen=True)
class ProfilePairInfo:
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


@dataclass(frozen=True)
class RegistrationProgress:
    """One progress message of a registration (``stage`` e.g. ``"ready"``)."""

    stage: str = _enum()
    pair_id: str
    fraction_done: float
    elapsed_s: float
    message: str
    pair: Optional[ProfilePairInfo] = _optional(ProfilePairInfo)
    already_registered: bool
