from google.protobuf.internal import containers as _containers
from google.protobuf.internal import enum_type_wrapper as _enum_type_wrapper
from google.protobuf import descriptor as _descriptor
from google.protobuf import message as _message
from collections.abc import Iterable as _Iterable, Mapping as _Mapping
from typing import ClassVar as _ClassVar, Optional as _Optional, Union as _Union

DESCRIPTOR: _descriptor.FileDescriptor

class Model(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    MODEL_UNSPECIFIED: _ClassVar[Model]
    MODEL_HERTZ: _ClassVar[Model]
    MODEL_HERTZ_CORRECTED: _ClassVar[Model]
    MODEL_FASTSIM: _ClassVar[Model]
    MODEL_EXACT: _ClassVar[Model]
    MODEL_CECT: _ClassVar[Model]
    MODEL_CECT_HALFSPACE: _ClassVar[Model]

class FrictionLaw(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    FRICTION_LAW_UNSPECIFIED: _ClassVar[FrictionLaw]
    FRICTION_LAW_COULOMB: _ClassVar[FrictionLaw]
    FRICTION_LAW_LINEAR: _ClassVar[FrictionLaw]
    FRICTION_LAW_RATIONAL: _ClassVar[FrictionLaw]
    FRICTION_LAW_EXPONENTIAL: _ClassVar[FrictionLaw]

class SlipStart(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    SLIP_START_UNSPECIFIED: _ClassVar[SlipStart]
    SLIP_START_PREVIOUS: _ClassVar[SlipStart]
    SLIP_START_STICKING: _ClassVar[SlipStart]
    SLIP_START_SLIDING: _ClassVar[SlipStart]

class GeometryKind(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    GEOMETRY_KIND_UNSPECIFIED: _ClassVar[GeometryKind]
    GEOMETRY_KIND_QUADRATIC: _ClassVar[GeometryKind]
    GEOMETRY_KIND_CONFORMAL_CIRCULAR: _ClassVar[GeometryKind]
    GEOMETRY_KIND_CONFORMAL_POINTS: _ClassVar[GeometryKind]
    GEOMETRY_KIND_LINE: _ClassVar[GeometryKind]

class FastsimMethod(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    FASTSIM_METHOD_UNSPECIFIED: _ClassVar[FastsimMethod]
    FASTSIM_METHOD_FASTSIM: _ClassVar[FastsimMethod]
    FASTSIM_METHOD_FASTRIP: _ClassVar[FastsimMethod]

class FastsimDiscretisation(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    FASTSIM_DISCRETISATION_UNSPECIFIED: _ClassVar[FastsimDiscretisation]
    FASTSIM_DISCRETISATION_STRIPS: _ClassVar[FastsimDiscretisation]
    FASTSIM_DISCRETISATION_GRID: _ClassVar[FastsimDiscretisation]

class FastsimTractionBound(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    FASTSIM_TRACTION_BOUND_UNSPECIFIED: _ClassVar[FastsimTractionBound]
    FASTSIM_TRACTION_BOUND_PARABOLIC: _ClassVar[FastsimTractionBound]
    FASTSIM_TRACTION_BOUND_ELLIPTIC: _ClassVar[FastsimTractionBound]

class RigidSlip(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    RIGID_SLIP_UNSPECIFIED: _ClassVar[RigidSlip]
    RIGID_SLIP_ACTUAL_SURFACE: _ClassVar[RigidSlip]
    RIGID_SLIP_REFERENCE_SECTION: _ClassVar[RigidSlip]

class SolveStatus(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    SOLVE_STATUS_UNSPECIFIED: _ClassVar[SolveStatus]
    SOLVE_STATUS_CONVERGED: _ClassVar[SolveStatus]
    SOLVE_STATUS_MAX_ITERATIONS: _ClassVar[SolveStatus]

class ElementState(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    ELEMENT_STATE_EXTERIOR: _ClassVar[ElementState]
    ELEMENT_STATE_ADHESION: _ClassVar[ElementState]
    ELEMENT_STATE_SLIP: _ClassVar[ElementState]

class ProfileFormat(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    PROFILE_FORMAT_UNSPECIFIED: _ClassVar[ProfileFormat]
    PROFILE_FORMAT_SIMPACK: _ClassVar[ProfileFormat]
    PROFILE_FORMAT_MINIPROF: _ClassVar[ProfileFormat]
    PROFILE_FORMAT_PLAIN: _ClassVar[ProfileFormat]

class LengthUnit(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    LENGTH_UNIT_UNSPECIFIED: _ClassVar[LengthUnit]
    LENGTH_UNIT_M: _ClassVar[LengthUnit]
    LENGTH_UNIT_MM: _ClassVar[LengthUnit]

class RegistrationStage(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    REGISTRATION_STAGE_UNSPECIFIED: _ClassVar[RegistrationStage]
    REGISTRATION_STAGE_VALIDATED: _ClassVar[RegistrationStage]
    REGISTRATION_STAGE_WHEEL_PARSED: _ClassVar[RegistrationStage]
    REGISTRATION_STAGE_RAIL_PARSED: _ClassVar[RegistrationStage]
    REGISTRATION_STAGE_PLACED: _ClassVar[RegistrationStage]
    REGISTRATION_STAGE_TABLE_BUILT: _ClassVar[RegistrationStage]
    REGISTRATION_STAGE_STORED: _ClassVar[RegistrationStage]
    REGISTRATION_STAGE_READY: _ClassVar[RegistrationStage]

class ProfilePairState(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    PROFILE_PAIR_STATE_UNSPECIFIED: _ClassVar[ProfilePairState]
    PROFILE_PAIR_STATE_PREPARING: _ClassVar[ProfilePairState]
    PROFILE_PAIR_STATE_READY: _ClassVar[ProfilePairState]
    PROFILE_PAIR_STATE_STORED: _ClassVar[ProfilePairState]
    PROFILE_PAIR_STATE_FAILED: _ClassVar[ProfilePairState]

class WheelRailModel(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    WHEEL_RAIL_MODEL_UNSPECIFIED: _ClassVar[WheelRailModel]
    WHEEL_RAIL_MODEL_EXACT: _ClassVar[WheelRailModel]
    WHEEL_RAIL_MODEL_HERTZ_FASTSIM: _ClassVar[WheelRailModel]
    WHEEL_RAIL_MODEL_CECT: _ClassVar[WheelRailModel]
    WHEEL_RAIL_MODEL_AUTO: _ClassVar[WheelRailModel]
    WHEEL_RAIL_MODEL_HERTZ_FASTSIM_TABLE: _ClassVar[WheelRailModel]
    WHEEL_RAIL_MODEL_HERTZ_POLACH: _ClassVar[WheelRailModel]
    WHEEL_RAIL_MODEL_HERTZ_FASTSIM_ELLIPTIC: _ClassVar[WheelRailModel]
    WHEEL_RAIL_MODEL_HERTZ_STRIP: _ClassVar[WheelRailModel]
    WHEEL_RAIL_MODEL_KIK_PIOTROWSKI: _ClassVar[WheelRailModel]
    WHEEL_RAIL_MODEL_HERTZ_FASTSIM_MODIFIED: _ClassVar[WheelRailModel]

class WheelSides(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    WHEEL_SIDES_UNSPECIFIED: _ClassVar[WheelSides]
    WHEEL_SIDES_BOTH: _ClassVar[WheelSides]
    WHEEL_SIDES_LEFT: _ClassVar[WheelSides]
    WHEEL_SIDES_RIGHT: _ClassVar[WheelSides]

class WheelSide(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    WHEEL_SIDE_UNSPECIFIED: _ClassVar[WheelSide]
    WHEEL_SIDE_LEFT: _ClassVar[WheelSide]
    WHEEL_SIDE_RIGHT: _ClassVar[WheelSide]

class WheelRailWarningKind(int, metaclass=_enum_type_wrapper.EnumTypeWrapper):
    __slots__ = ()
    WHEEL_RAIL_WARNING_KIND_UNSPECIFIED: _ClassVar[WheelRailWarningKind]
    WHEEL_RAIL_WARNING_KIND_APPROACH: _ClassVar[WheelRailWarningKind]
    WHEEL_RAIL_WARNING_KIND_LONGITUDINAL_FORCE: _ClassVar[WheelRailWarningKind]
    WHEEL_RAIL_WARNING_KIND_UNCONVERGED: _ClassVar[WheelRailWarningKind]
    WHEEL_RAIL_WARNING_KIND_OPPOSED_SURFACES: _ClassVar[WheelRailWarningKind]
MODEL_UNSPECIFIED: Model
MODEL_HERTZ: Model
MODEL_HERTZ_CORRECTED: Model
MODEL_FASTSIM: Model
MODEL_EXACT: Model
MODEL_CECT: Model
MODEL_CECT_HALFSPACE: Model
FRICTION_LAW_UNSPECIFIED: FrictionLaw
FRICTION_LAW_COULOMB: FrictionLaw
FRICTION_LAW_LINEAR: FrictionLaw
FRICTION_LAW_RATIONAL: FrictionLaw
FRICTION_LAW_EXPONENTIAL: FrictionLaw
SLIP_START_UNSPECIFIED: SlipStart
SLIP_START_PREVIOUS: SlipStart
SLIP_START_STICKING: SlipStart
SLIP_START_SLIDING: SlipStart
GEOMETRY_KIND_UNSPECIFIED: GeometryKind
GEOMETRY_KIND_QUADRATIC: GeometryKind
GEOMETRY_KIND_CONFORMAL_CIRCULAR: GeometryKind
GEOMETRY_KIND_CONFORMAL_POINTS: GeometryKind
GEOMETRY_KIND_LINE: GeometryKind
FASTSIM_METHOD_UNSPECIFIED: FastsimMethod
FASTSIM_METHOD_FASTSIM: FastsimMethod
FASTSIM_METHOD_FASTRIP: FastsimMethod
FASTSIM_DISCRETISATION_UNSPECIFIED: FastsimDiscretisation
FASTSIM_DISCRETISATION_STRIPS: FastsimDiscretisation
FASTSIM_DISCRETISATION_GRID: FastsimDiscretisation
FASTSIM_TRACTION_BOUND_UNSPECIFIED: FastsimTractionBound
FASTSIM_TRACTION_BOUND_PARABOLIC: FastsimTractionBound
FASTSIM_TRACTION_BOUND_ELLIPTIC: FastsimTractionBound
RIGID_SLIP_UNSPECIFIED: RigidSlip
RIGID_SLIP_ACTUAL_SURFACE: RigidSlip
RIGID_SLIP_REFERENCE_SECTION: RigidSlip
SOLVE_STATUS_UNSPECIFIED: SolveStatus
SOLVE_STATUS_CONVERGED: SolveStatus
SOLVE_STATUS_MAX_ITERATIONS: SolveStatus
ELEMENT_STATE_EXTERIOR: ElementState
ELEMENT_STATE_ADHESION: ElementState
ELEMENT_STATE_SLIP: ElementState
PROFILE_FORMAT_UNSPECIFIED: ProfileFormat
PROFILE_FORMAT_SIMPACK: ProfileFormat
PROFILE_FORMAT_MINIPROF: ProfileFormat
PROFILE_FORMAT_PLAIN: ProfileFormat
LENGTH_UNIT_UNSPECIFIED: LengthUnit
LENGTH_UNIT_M: LengthUnit
LENGTH_UNIT_MM: LengthUnit
REGISTRATION_STAGE_UNSPECIFIED: RegistrationStage
REGISTRATION_STAGE_VALIDATED: RegistrationStage
REGISTRATION_STAGE_WHEEL_PARSED: RegistrationStage
REGISTRATION_STAGE_RAIL_PARSED: RegistrationStage
REGISTRATION_STAGE_PLACED: RegistrationStage
REGISTRATION_STAGE_TABLE_BUILT: RegistrationStage
REGISTRATION_STAGE_STORED: RegistrationStage
REGISTRATION_STAGE_READY: RegistrationStage
PROFILE_PAIR_STATE_UNSPECIFIED: ProfilePairState
PROFILE_PAIR_STATE_PREPARING: ProfilePairState
PROFILE_PAIR_STATE_READY: ProfilePairState
PROFILE_PAIR_STATE_STORED: ProfilePairState
PROFILE_PAIR_STATE_FAILED: ProfilePairState
WHEEL_RAIL_MODEL_UNSPECIFIED: WheelRailModel
WHEEL_RAIL_MODEL_EXACT: WheelRailModel
WHEEL_RAIL_MODEL_HERTZ_FASTSIM: WheelRailModel
WHEEL_RAIL_MODEL_CECT: WheelRailModel
WHEEL_RAIL_MODEL_AUTO: WheelRailModel
WHEEL_RAIL_MODEL_HERTZ_FASTSIM_TABLE: WheelRailModel
WHEEL_RAIL_MODEL_HERTZ_POLACH: WheelRailModel
WHEEL_RAIL_MODEL_HERTZ_FASTSIM_ELLIPTIC: WheelRailModel
WHEEL_RAIL_MODEL_HERTZ_STRIP: WheelRailModel
WHEEL_RAIL_MODEL_KIK_PIOTROWSKI: WheelRailModel
WHEEL_RAIL_MODEL_HERTZ_FASTSIM_MODIFIED: WheelRailModel
WHEEL_SIDES_UNSPECIFIED: WheelSides
WHEEL_SIDES_BOTH: WheelSides
WHEEL_SIDES_LEFT: WheelSides
WHEEL_SIDES_RIGHT: WheelSides
WHEEL_SIDE_UNSPECIFIED: WheelSide
WHEEL_SIDE_LEFT: WheelSide
WHEEL_SIDE_RIGHT: WheelSide
WHEEL_RAIL_WARNING_KIND_UNSPECIFIED: WheelRailWarningKind
WHEEL_RAIL_WARNING_KIND_APPROACH: WheelRailWarningKind
WHEEL_RAIL_WARNING_KIND_LONGITUDINAL_FORCE: WheelRailWarningKind
WHEEL_RAIL_WARNING_KIND_UNCONVERGED: WheelRailWarningKind
WHEEL_RAIL_WARNING_KIND_OPPOSED_SURFACES: WheelRailWarningKind

class Material(_message.Message):
    __slots__ = ("shear_modulus_pa", "poisson_ratio")
    SHEAR_MODULUS_PA_FIELD_NUMBER: _ClassVar[int]
    POISSON_RATIO_FIELD_NUMBER: _ClassVar[int]
    shear_modulus_pa: float
    poisson_ratio: float
    def __init__(self, shear_modulus_pa: _Optional[float] = ..., poisson_ratio: _Optional[float] = ...) -> None: ...

class MaterialSection(_message.Message):
    __slots__ = ("shear_modulus_pa", "poisson_ratio", "body1", "body2", "influence_file_content")
    SHEAR_MODULUS_PA_FIELD_NUMBER: _ClassVar[int]
    POISSON_RATIO_FIELD_NUMBER: _ClassVar[int]
    BODY1_FIELD_NUMBER: _ClassVar[int]
    BODY2_FIELD_NUMBER: _ClassVar[int]
    INFLUENCE_FILE_CONTENT_FIELD_NUMBER: _ClassVar[int]
    shear_modulus_pa: float
    poisson_ratio: float
    body1: Material
    body2: Material
    influence_file_content: str
    def __init__(self, shear_modulus_pa: _Optional[float] = ..., poisson_ratio: _Optional[float] = ..., body1: _Optional[_Union[Material, _Mapping]] = ..., body2: _Optional[_Union[Material, _Mapping]] = ..., influence_file_content: _Optional[str] = ...) -> None: ...

class FrictionSection(_message.Message):
    __slots__ = ("coefficient", "static_coefficient", "kinetic_coefficient", "law", "falling_coefficients", "half_velocities_m_per_s", "rolling_speed_m_per_s", "memory_distance_m", "memory_velocity_m_per_s", "start", "max_iterations")
    COEFFICIENT_FIELD_NUMBER: _ClassVar[int]
    STATIC_COEFFICIENT_FIELD_NUMBER: _ClassVar[int]
    KINETIC_COEFFICIENT_FIELD_NUMBER: _ClassVar[int]
    LAW_FIELD_NUMBER: _ClassVar[int]
    FALLING_COEFFICIENTS_FIELD_NUMBER: _ClassVar[int]
    HALF_VELOCITIES_M_PER_S_FIELD_NUMBER: _ClassVar[int]
    ROLLING_SPEED_M_PER_S_FIELD_NUMBER: _ClassVar[int]
    MEMORY_DISTANCE_M_FIELD_NUMBER: _ClassVar[int]
    MEMORY_VELOCITY_M_PER_S_FIELD_NUMBER: _ClassVar[int]
    START_FIELD_NUMBER: _ClassVar[int]
    MAX_ITERATIONS_FIELD_NUMBER: _ClassVar[int]
    coefficient: float
    static_coefficient: float
    kinetic_coefficient: float
    law: FrictionLaw
    falling_coefficients: _containers.RepeatedScalarFieldContainer[float]
    half_velocities_m_per_s: _containers.RepeatedScalarFieldContainer[float]
    rolling_speed_m_per_s: float
    memory_distance_m: float
    memory_velocity_m_per_s: float
    start: SlipStart
    max_iterations: int
    def __init__(self, coefficient: _Optional[float] = ..., static_coefficient: _Optional[float] = ..., kinetic_coefficient: _Optional[float] = ..., law: _Optional[_Union[FrictionLaw, str]] = ..., falling_coefficients: _Optional[_Iterable[float]] = ..., half_velocities_m_per_s: _Optional[_Iterable[float]] = ..., rolling_speed_m_per_s: _Optional[float] = ..., memory_distance_m: _Optional[float] = ..., memory_velocity_m_per_s: _Optional[float] = ..., start: _Optional[_Union[SlipStart, str]] = ..., max_iterations: _Optional[int] = ...) -> None: ...

class ProfilePoint(_message.Message):
    __slots__ = ("y_m", "z_m")
    Y_M_FIELD_NUMBER: _ClassVar[int]
    Z_M_FIELD_NUMBER: _ClassVar[int]
    y_m: float
    z_m: float
    def __init__(self, y_m: _Optional[float] = ..., z_m: _Optional[float] = ...) -> None: ...

class GeometrySection(_message.Message):
    __slots__ = ("kind", "a_per_m", "b_per_m", "rail_lateral_radius_m", "wheel_lateral_radius_m", "wheel_rolling_radius_m", "rail_points_m", "wheel_points_m", "extra_gap_m", "gap_m")
    KIND_FIELD_NUMBER: _ClassVar[int]
    A_PER_M_FIELD_NUMBER: _ClassVar[int]
    B_PER_M_FIELD_NUMBER: _ClassVar[int]
    RAIL_LATERAL_RADIUS_M_FIELD_NUMBER: _ClassVar[int]
    WHEEL_LATERAL_RADIUS_M_FIELD_NUMBER: _ClassVar[int]
    WHEEL_ROLLING_RADIUS_M_FIELD_NUMBER: _ClassVar[int]
    RAIL_POINTS_M_FIELD_NUMBER: _ClassVar[int]
    WHEEL_POINTS_M_FIELD_NUMBER: _ClassVar[int]
    EXTRA_GAP_M_FIELD_NUMBER: _ClassVar[int]
    GAP_M_FIELD_NUMBER: _ClassVar[int]
    kind: GeometryKind
    a_per_m: float
    b_per_m: float
    rail_lateral_radius_m: float
    wheel_lateral_radius_m: float
    wheel_rolling_radius_m: float
    rail_points_m: _containers.RepeatedCompositeFieldContainer[ProfilePoint]
    wheel_points_m: _containers.RepeatedCompositeFieldContainer[ProfilePoint]
    extra_gap_m: _containers.RepeatedScalarFieldContainer[float]
    gap_m: _containers.RepeatedScalarFieldContainer[float]
    def __init__(self, kind: _Optional[_Union[GeometryKind, str]] = ..., a_per_m: _Optional[float] = ..., b_per_m: _Optional[float] = ..., rail_lateral_radius_m: _Optional[float] = ..., wheel_lateral_radius_m: _Optional[float] = ..., wheel_rolling_radius_m: _Optional[float] = ..., rail_points_m: _Optional[_Iterable[_Union[ProfilePoint, _Mapping]]] = ..., wheel_points_m: _Optional[_Iterable[_Union[ProfilePoint, _Mapping]]] = ..., extra_gap_m: _Optional[_Iterable[float]] = ..., gap_m: _Optional[_Iterable[float]] = ...) -> None: ...

class LoadSection(_message.Message):
    __slots__ = ("normal_force_n", "approach_m", "normal_force_n_per_m")
    NORMAL_FORCE_N_FIELD_NUMBER: _ClassVar[int]
    APPROACH_M_FIELD_NUMBER: _ClassVar[int]
    NORMAL_FORCE_N_PER_M_FIELD_NUMBER: _ClassVar[int]
    normal_force_n: float
    approach_m: float
    normal_force_n_per_m: float
    def __init__(self, normal_force_n: _Optional[float] = ..., approach_m: _Optional[float] = ..., normal_force_n_per_m: _Optional[float] = ...) -> None: ...

class Creepages(_message.Message):
    __slots__ = ("creepage_long", "creepage_lat", "spin_per_m", "force_x_n", "force_y_n", "force_x_n_per_m")
    CREEPAGE_LONG_FIELD_NUMBER: _ClassVar[int]
    CREEPAGE_LAT_FIELD_NUMBER: _ClassVar[int]
    SPIN_PER_M_FIELD_NUMBER: _ClassVar[int]
    FORCE_X_N_FIELD_NUMBER: _ClassVar[int]
    FORCE_Y_N_FIELD_NUMBER: _ClassVar[int]
    FORCE_X_N_PER_M_FIELD_NUMBER: _ClassVar[int]
    creepage_long: float
    creepage_lat: float
    spin_per_m: float
    force_x_n: float
    force_y_n: float
    force_x_n_per_m: float
    def __init__(self, creepage_long: _Optional[float] = ..., creepage_lat: _Optional[float] = ..., spin_per_m: _Optional[float] = ..., force_x_n: _Optional[float] = ..., force_y_n: _Optional[float] = ..., force_x_n_per_m: _Optional[float] = ...) -> None: ...

class ShiftStep(_message.Message):
    __slots__ = ("shift_x_m", "shift_y_m", "rotation_rad", "normal_force_n", "approach_m", "creepage_long", "creepage_lat", "spin_per_m", "normal_force_n_per_m", "force_x_n", "force_y_n", "force_x_n_per_m", "rolling_m", "gap_travel_x_m", "friction_start")
    SHIFT_X_M_FIELD_NUMBER: _ClassVar[int]
    SHIFT_Y_M_FIELD_NUMBER: _ClassVar[int]
    ROTATION_RAD_FIELD_NUMBER: _ClassVar[int]
    NORMAL_FORCE_N_FIELD_NUMBER: _ClassVar[int]
    APPROACH_M_FIELD_NUMBER: _ClassVar[int]
    CREEPAGE_LONG_FIELD_NUMBER: _ClassVar[int]
    CREEPAGE_LAT_FIELD_NUMBER: _ClassVar[int]
    SPIN_PER_M_FIELD_NUMBER: _ClassVar[int]
    NORMAL_FORCE_N_PER_M_FIELD_NUMBER: _ClassVar[int]
    FORCE_X_N_FIELD_NUMBER: _ClassVar[int]
    FORCE_Y_N_FIELD_NUMBER: _ClassVar[int]
    FORCE_X_N_PER_M_FIELD_NUMBER: _ClassVar[int]
    ROLLING_M_FIELD_NUMBER: _ClassVar[int]
    GAP_TRAVEL_X_M_FIELD_NUMBER: _ClassVar[int]
    FRICTION_START_FIELD_NUMBER: _ClassVar[int]
    shift_x_m: float
    shift_y_m: float
    rotation_rad: float
    normal_force_n: float
    approach_m: float
    creepage_long: float
    creepage_lat: float
    spin_per_m: float
    normal_force_n_per_m: float
    force_x_n: float
    force_y_n: float
    force_x_n_per_m: float
    rolling_m: float
    gap_travel_x_m: float
    friction_start: SlipStart
    def __init__(self, shift_x_m: _Optional[float] = ..., shift_y_m: _Optional[float] = ..., rotation_rad: _Optional[float] = ..., normal_force_n: _Optional[float] = ..., approach_m: _Optional[float] = ..., creepage_long: _Optional[float] = ..., creepage_lat: _Optional[float] = ..., spin_per_m: _Optional[float] = ..., normal_force_n_per_m: _Optional[float] = ..., force_x_n: _Optional[float] = ..., force_y_n: _Optional[float] = ..., force_x_n_per_m: _Optional[float] = ..., rolling_m: _Optional[float] = ..., gap_travel_x_m: _Optional[float] = ..., friction_start: _Optional[_Union[SlipStart, str]] = ...) -> None: ...

class SteadyStart(_message.Message):
    __slots__ = ("creepage_long", "creepage_lat", "spin_per_m")
    CREEPAGE_LONG_FIELD_NUMBER: _ClassVar[int]
    CREEPAGE_LAT_FIELD_NUMBER: _ClassVar[int]
    SPIN_PER_M_FIELD_NUMBER: _ClassVar[int]
    creepage_long: float
    creepage_lat: float
    spin_per_m: float
    def __init__(self, creepage_long: _Optional[float] = ..., creepage_lat: _Optional[float] = ..., spin_per_m: _Optional[float] = ...) -> None: ...

class TransientSection(_message.Message):
    __slots__ = ("steps", "rolling_step_m", "steady_start")
    STEPS_FIELD_NUMBER: _ClassVar[int]
    ROLLING_STEP_M_FIELD_NUMBER: _ClassVar[int]
    STEADY_START_FIELD_NUMBER: _ClassVar[int]
    steps: _containers.RepeatedCompositeFieldContainer[ShiftStep]
    rolling_step_m: float
    steady_start: SteadyStart
    def __init__(self, steps: _Optional[_Iterable[_Union[ShiftStep, _Mapping]]] = ..., rolling_step_m: _Optional[float] = ..., steady_start: _Optional[_Union[SteadyStart, _Mapping]] = ...) -> None: ...

class GridSection(_message.Message):
    __slots__ = ("nx", "ny", "window_x_m", "window_y_m")
    NX_FIELD_NUMBER: _ClassVar[int]
    NY_FIELD_NUMBER: _ClassVar[int]
    WINDOW_X_M_FIELD_NUMBER: _ClassVar[int]
    WINDOW_Y_M_FIELD_NUMBER: _ClassVar[int]
    nx: int
    ny: int
    window_x_m: float
    window_y_m: float
    def __init__(self, nx: _Optional[int] = ..., ny: _Optional[int] = ..., window_x_m: _Optional[float] = ..., window_y_m: _Optional[float] = ...) -> None: ...

class SolverSection(_message.Message):
    __slots__ = ("normal_tolerance", "tangential_tolerance", "max_iterations", "coupling_tolerance", "coupling_max_iterations")
    NORMAL_TOLERANCE_FIELD_NUMBER: _ClassVar[int]
    TANGENTIAL_TOLERANCE_FIELD_NUMBER: _ClassVar[int]
    MAX_ITERATIONS_FIELD_NUMBER: _ClassVar[int]
    COUPLING_TOLERANCE_FIELD_NUMBER: _ClassVar[int]
    COUPLING_MAX_ITERATIONS_FIELD_NUMBER: _ClassVar[int]
    normal_tolerance: float
    tangential_tolerance: float
    max_iterations: int
    coupling_tolerance: float
    coupling_max_iterations: int
    def __init__(self, normal_tolerance: _Optional[float] = ..., tangential_tolerance: _Optional[float] = ..., max_iterations: _Optional[int] = ..., coupling_tolerance: _Optional[float] = ..., coupling_max_iterations: _Optional[int] = ...) -> None: ...

class PatchCase(_message.Message):
    __slots__ = ("model", "material", "friction", "geometry", "load", "rolling", "transient", "grid", "solver", "subsurface", "temperature", "rolling_direction_rad", "extra_rigid_slip", "conformal", "interfacial_layer", "viscoelastic", "fastsim")
    MODEL_FIELD_NUMBER: _ClassVar[int]
    MATERIAL_FIELD_NUMBER: _ClassVar[int]
    FRICTION_FIELD_NUMBER: _ClassVar[int]
    GEOMETRY_FIELD_NUMBER: _ClassVar[int]
    LOAD_FIELD_NUMBER: _ClassVar[int]
    ROLLING_FIELD_NUMBER: _ClassVar[int]
    TRANSIENT_FIELD_NUMBER: _ClassVar[int]
    GRID_FIELD_NUMBER: _ClassVar[int]
    SOLVER_FIELD_NUMBER: _ClassVar[int]
    SUBSURFACE_FIELD_NUMBER: _ClassVar[int]
    TEMPERATURE_FIELD_NUMBER: _ClassVar[int]
    ROLLING_DIRECTION_RAD_FIELD_NUMBER: _ClassVar[int]
    EXTRA_RIGID_SLIP_FIELD_NUMBER: _ClassVar[int]
    CONFORMAL_FIELD_NUMBER: _ClassVar[int]
    INTERFACIAL_LAYER_FIELD_NUMBER: _ClassVar[int]
    VISCOELASTIC_FIELD_NUMBER: _ClassVar[int]
    FASTSIM_FIELD_NUMBER: _ClassVar[int]
    model: Model
    material: MaterialSection
    friction: FrictionSection
    geometry: GeometrySection
    load: LoadSection
    rolling: Creepages
    transient: TransientSection
    grid: GridSection
    solver: SolverSection
    subsurface: SubsurfaceSection
    temperature: TemperatureSection
    rolling_direction_rad: float
    extra_rigid_slip: ExtraRigidSlip
    conformal: ConformalSection
    interfacial_layer: InterfacialLayerSection
    viscoelastic: ViscoelasticSection
    fastsim: FastsimSection
    def __init__(self, model: _Optional[_Union[Model, str]] = ..., material: _Optional[_Union[MaterialSection, _Mapping]] = ..., friction: _Optional[_Union[FrictionSection, _Mapping]] = ..., geometry: _Optional[_Union[GeometrySection, _Mapping]] = ..., load: _Optional[_Union[LoadSection, _Mapping]] = ..., rolling: _Optional[_Union[Creepages, _Mapping]] = ..., transient: _Optional[_Union[TransientSection, _Mapping]] = ..., grid: _Optional[_Union[GridSection, _Mapping]] = ..., solver: _Optional[_Union[SolverSection, _Mapping]] = ..., subsurface: _Optional[_Union[SubsurfaceSection, _Mapping]] = ..., temperature: _Optional[_Union[TemperatureSection, _Mapping]] = ..., rolling_direction_rad: _Optional[float] = ..., extra_rigid_slip: _Optional[_Union[ExtraRigidSlip, _Mapping]] = ..., conformal: _Optional[_Union[ConformalSection, _Mapping]] = ..., interfacial_layer: _Optional[_Union[InterfacialLayerSection, _Mapping]] = ..., viscoelastic: _Optional[_Union[ViscoelasticSection, _Mapping]] = ..., fastsim: _Optional[_Union[FastsimSection, _Mapping]] = ...) -> None: ...

class FastsimSection(_message.Message):
    __slots__ = ("method", "discretisation", "traction_bound", "initial_factor", "limit_ratio", "transition_rate", "friction_limit_ratio", "friction_decay_s_per_m", "rolling_speed_m_per_s", "flexibility_m_per_pa", "window_scale")
    METHOD_FIELD_NUMBER: _ClassVar[int]
    DISCRETISATION_FIELD_NUMBER: _ClassVar[int]
    TRACTION_BOUND_FIELD_NUMBER: _ClassVar[int]
    INITIAL_FACTOR_FIELD_NUMBER: _ClassVar[int]
    LIMIT_RATIO_FIELD_NUMBER: _ClassVar[int]
    TRANSITION_RATE_FIELD_NUMBER: _ClassVar[int]
    FRICTION_LIMIT_RATIO_FIELD_NUMBER: _ClassVar[int]
    FRICTION_DECAY_S_PER_M_FIELD_NUMBER: _ClassVar[int]
    ROLLING_SPEED_M_PER_S_FIELD_NUMBER: _ClassVar[int]
    FLEXIBILITY_M_PER_PA_FIELD_NUMBER: _ClassVar[int]
    WINDOW_SCALE_FIELD_NUMBER: _ClassVar[int]
    method: FastsimMethod
    discretisation: FastsimDiscretisation
    traction_bound: FastsimTractionBound
    initial_factor: float
    limit_ratio: float
    transition_rate: float
    friction_limit_ratio: float
    friction_decay_s_per_m: float
    rolling_speed_m_per_s: float
    flexibility_m_per_pa: float
    window_scale: float
    def __init__(self, method: _Optional[_Union[FastsimMethod, str]] = ..., discretisation: _Optional[_Union[FastsimDiscretisation, str]] = ..., traction_bound: _Optional[_Union[FastsimTractionBound, str]] = ..., initial_factor: _Optional[float] = ..., limit_ratio: _Optional[float] = ..., transition_rate: _Optional[float] = ..., friction_limit_ratio: _Optional[float] = ..., friction_decay_s_per_m: _Optional[float] = ..., rolling_speed_m_per_s: _Optional[float] = ..., flexibility_m_per_pa: _Optional[float] = ..., window_scale: _Optional[float] = ...) -> None: ...

class ViscoelasticSection(_message.Message):
    __slots__ = ("rolling_speed_m_per_s", "body1", "body2")
    ROLLING_SPEED_M_PER_S_FIELD_NUMBER: _ClassVar[int]
    BODY1_FIELD_NUMBER: _ClassVar[int]
    BODY2_FIELD_NUMBER: _ClassVar[int]
    rolling_speed_m_per_s: float
    body1: ViscoelasticBody
    body2: ViscoelasticBody
    def __init__(self, rolling_speed_m_per_s: _Optional[float] = ..., body1: _Optional[_Union[ViscoelasticBody, _Mapping]] = ..., body2: _Optional[_Union[ViscoelasticBody, _Mapping]] = ...) -> None: ...

class ViscoelasticBody(_message.Message):
    __slots__ = ("relaxation_ratio", "creep_relaxation_time_s")
    RELAXATION_RATIO_FIELD_NUMBER: _ClassVar[int]
    CREEP_RELAXATION_TIME_S_FIELD_NUMBER: _ClassVar[int]
    relaxation_ratio: float
    creep_relaxation_time_s: float
    def __init__(self, relaxation_ratio: _Optional[float] = ..., creep_relaxation_time_s: _Optional[float] = ...) -> None: ...

class InterfacialLayerSection(_message.Message):
    __slots__ = ("thickness_m", "shear_modulus_pa", "yield_limit_pa", "hardening_pa_per_m")
    THICKNESS_M_FIELD_NUMBER: _ClassVar[int]
    SHEAR_MODULUS_PA_FIELD_NUMBER: _ClassVar[int]
    YIELD_LIMIT_PA_FIELD_NUMBER: _ClassVar[int]
    HARDENING_PA_PER_M_FIELD_NUMBER: _ClassVar[int]
    thickness_m: float
    shear_modulus_pa: float
    yield_limit_pa: float
    hardening_pa_per_m: float
    def __init__(self, thickness_m: _Optional[float] = ..., shear_modulus_pa: _Optional[float] = ..., yield_limit_pa: _Optional[float] = ..., hardening_pa_per_m: _Optional[float] = ...) -> None: ...

class ExtraRigidSlip(_message.Message):
    __slots__ = ("slip_x", "slip_y", "shift_x_m", "shift_y_m")
    SLIP_X_FIELD_NUMBER: _ClassVar[int]
    SLIP_Y_FIELD_NUMBER: _ClassVar[int]
    SHIFT_X_M_FIELD_NUMBER: _ClassVar[int]
    SHIFT_Y_M_FIELD_NUMBER: _ClassVar[int]
    slip_x: _containers.RepeatedScalarFieldContainer[float]
    slip_y: _containers.RepeatedScalarFieldContainer[float]
    shift_x_m: _containers.RepeatedScalarFieldContainer[float]
    shift_y_m: _containers.RepeatedScalarFieldContainer[float]
    def __init__(self, slip_x: _Optional[_Iterable[float]] = ..., slip_y: _Optional[_Iterable[float]] = ..., shift_x_m: _Optional[_Iterable[float]] = ..., shift_y_m: _Optional[_Iterable[float]] = ...) -> None: ...

class ConformalSection(_message.Message):
    __slots__ = ("rigid_slip",)
    RIGID_SLIP_FIELD_NUMBER: _ClassVar[int]
    rigid_slip: RigidSlip
    def __init__(self, rigid_slip: _Optional[_Union[RigidSlip, str]] = ...) -> None: ...

class ThermalBody(_message.Message):
    __slots__ = ("bulk_temperature_k", "conductivity_w_per_m_k", "density_kg_per_m3", "specific_heat_j_per_kg_k")
    BULK_TEMPERATURE_K_FIELD_NUMBER: _ClassVar[int]
    CONDUCTIVITY_W_PER_M_K_FIELD_NUMBER: _ClassVar[int]
    DENSITY_KG_PER_M3_FIELD_NUMBER: _ClassVar[int]
    SPECIFIC_HEAT_J_PER_KG_K_FIELD_NUMBER: _ClassVar[int]
    bulk_temperature_k: float
    conductivity_w_per_m_k: float
    density_kg_per_m3: float
    specific_heat_j_per_kg_k: float
    def __init__(self, bulk_temperature_k: _Optional[float] = ..., conductivity_w_per_m_k: _Optional[float] = ..., density_kg_per_m3: _Optional[float] = ..., specific_heat_j_per_kg_k: _Optional[float] = ...) -> None: ...

class TemperatureSection(_message.Message):
    __slots__ = ("rolling_speed_m_per_s", "body1", "body2")
    ROLLING_SPEED_M_PER_S_FIELD_NUMBER: _ClassVar[int]
    BODY1_FIELD_NUMBER: _ClassVar[int]
    BODY2_FIELD_NUMBER: _ClassVar[int]
    rolling_speed_m_per_s: float
    body1: ThermalBody
    body2: ThermalBody
    def __init__(self, rolling_speed_m_per_s: _Optional[float] = ..., body1: _Optional[_Union[ThermalBody, _Mapping]] = ..., body2: _Optional[_Union[ThermalBody, _Mapping]] = ...) -> None: ...

class SubsurfaceSection(_message.Message):
    __slots__ = ("depths_m", "max_depth_m", "depth_count", "shear_yield_stress_pa")
    DEPTHS_M_FIELD_NUMBER: _ClassVar[int]
    MAX_DEPTH_M_FIELD_NUMBER: _ClassVar[int]
    DEPTH_COUNT_FIELD_NUMBER: _ClassVar[int]
    SHEAR_YIELD_STRESS_PA_FIELD_NUMBER: _ClassVar[int]
    depths_m: _containers.RepeatedScalarFieldContainer[float]
    max_depth_m: float
    depth_count: int
    shear_yield_stress_pa: float
    def __init__(self, depths_m: _Optional[_Iterable[float]] = ..., max_depth_m: _Optional[float] = ..., depth_count: _Optional[int] = ..., shear_yield_stress_pa: _Optional[float] = ...) -> None: ...

class PatchTotals(_message.Message):
    __slots__ = ("normal_force_n", "fx_n", "fy_n", "mz_nm", "approach_m", "max_pressure_pa", "max_traction_pa", "contact_area_m2", "patch_length_m", "patch_width_m", "adhesion_fraction", "tgamma_n", "frictional_work_j")
    NORMAL_FORCE_N_FIELD_NUMBER: _ClassVar[int]
    FX_N_FIELD_NUMBER: _ClassVar[int]
    FY_N_FIELD_NUMBER: _ClassVar[int]
    MZ_NM_FIELD_NUMBER: _ClassVar[int]
    APPROACH_M_FIELD_NUMBER: _ClassVar[int]
    MAX_PRESSURE_PA_FIELD_NUMBER: _ClassVar[int]
    MAX_TRACTION_PA_FIELD_NUMBER: _ClassVar[int]
    CONTACT_AREA_M2_FIELD_NUMBER: _ClassVar[int]
    PATCH_LENGTH_M_FIELD_NUMBER: _ClassVar[int]
    PATCH_WIDTH_M_FIELD_NUMBER: _ClassVar[int]
    ADHESION_FRACTION_FIELD_NUMBER: _ClassVar[int]
    TGAMMA_N_FIELD_NUMBER: _ClassVar[int]
    FRICTIONAL_WORK_J_FIELD_NUMBER: _ClassVar[int]
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
    def __init__(self, normal_force_n: _Optional[float] = ..., fx_n: _Optional[float] = ..., fy_n: _Optional[float] = ..., mz_nm: _Optional[float] = ..., approach_m: _Optional[float] = ..., max_pressure_pa: _Optional[float] = ..., max_traction_pa: _Optional[float] = ..., contact_area_m2: _Optional[float] = ..., patch_length_m: _Optional[float] = ..., patch_width_m: _Optional[float] = ..., adhesion_fraction: _Optional[float] = ..., tgamma_n: _Optional[float] = ..., frictional_work_j: _Optional[float] = ...) -> None: ...

class ConformalTotals(_message.Message):
    __slots__ = ("contact_angle_variation_deg", "length_width_ratio", "normal_force_from_tractions_n", "pressure_resultant_n", "fy_global_n", "fz_global_n")
    CONTACT_ANGLE_VARIATION_DEG_FIELD_NUMBER: _ClassVar[int]
    LENGTH_WIDTH_RATIO_FIELD_NUMBER: _ClassVar[int]
    NORMAL_FORCE_FROM_TRACTIONS_N_FIELD_NUMBER: _ClassVar[int]
    PRESSURE_RESULTANT_N_FIELD_NUMBER: _ClassVar[int]
    FY_GLOBAL_N_FIELD_NUMBER: _ClassVar[int]
    FZ_GLOBAL_N_FIELD_NUMBER: _ClassVar[int]
    contact_angle_variation_deg: float
    length_width_ratio: float
    normal_force_from_tractions_n: float
    pressure_resultant_n: float
    fy_global_n: float
    fz_global_n: float
    def __init__(self, contact_angle_variation_deg: _Optional[float] = ..., length_width_ratio: _Optional[float] = ..., normal_force_from_tractions_n: _Optional[float] = ..., pressure_resultant_n: _Optional[float] = ..., fy_global_n: _Optional[float] = ..., fz_global_n: _Optional[float] = ...) -> None: ...

class SolverInfo(_message.Message):
    __slots__ = ("status", "normal_iterations", "tangential_iterations", "coupling_iterations", "matvecs", "normal_residual", "tangential_residual", "solve_time_s")
    STATUS_FIELD_NUMBER: _ClassVar[int]
    NORMAL_ITERATIONS_FIELD_NUMBER: _ClassVar[int]
    TANGENTIAL_ITERATIONS_FIELD_NUMBER: _ClassVar[int]
    COUPLING_ITERATIONS_FIELD_NUMBER: _ClassVar[int]
    MATVECS_FIELD_NUMBER: _ClassVar[int]
    NORMAL_RESIDUAL_FIELD_NUMBER: _ClassVar[int]
    TANGENTIAL_RESIDUAL_FIELD_NUMBER: _ClassVar[int]
    SOLVE_TIME_S_FIELD_NUMBER: _ClassVar[int]
    status: SolveStatus
    normal_iterations: int
    tangential_iterations: int
    coupling_iterations: int
    matvecs: int
    normal_residual: float
    tangential_residual: float
    solve_time_s: float
    def __init__(self, status: _Optional[_Union[SolveStatus, str]] = ..., normal_iterations: _Optional[int] = ..., tangential_iterations: _Optional[int] = ..., coupling_iterations: _Optional[int] = ..., matvecs: _Optional[int] = ..., normal_residual: _Optional[float] = ..., tangential_residual: _Optional[float] = ..., solve_time_s: _Optional[float] = ...) -> None: ...

class StepResult(_message.Message):
    __slots__ = ("totals", "info", "conformal", "sensitivities", "force_control")
    TOTALS_FIELD_NUMBER: _ClassVar[int]
    INFO_FIELD_NUMBER: _ClassVar[int]
    CONFORMAL_FIELD_NUMBER: _ClassVar[int]
    SENSITIVITIES_FIELD_NUMBER: _ClassVar[int]
    FORCE_CONTROL_FIELD_NUMBER: _ClassVar[int]
    totals: PatchTotals
    info: SolverInfo
    conformal: ConformalTotals
    sensitivities: Sensitivities
    force_control: StepForceControl
    def __init__(self, totals: _Optional[_Union[PatchTotals, _Mapping]] = ..., info: _Optional[_Union[SolverInfo, _Mapping]] = ..., conformal: _Optional[_Union[ConformalTotals, _Mapping]] = ..., sensitivities: _Optional[_Union[Sensitivities, _Mapping]] = ..., force_control: _Optional[_Union[StepForceControl, _Mapping]] = ...) -> None: ...

class StepForceControl(_message.Message):
    __slots__ = ("shift_x_m", "shift_y_m", "rolling_m", "creepage_long", "creepage_lat", "force_iterations", "force_solves")
    SHIFT_X_M_FIELD_NUMBER: _ClassVar[int]
    SHIFT_Y_M_FIELD_NUMBER: _ClassVar[int]
    ROLLING_M_FIELD_NUMBER: _ClassVar[int]
    CREEPAGE_LONG_FIELD_NUMBER: _ClassVar[int]
    CREEPAGE_LAT_FIELD_NUMBER: _ClassVar[int]
    FORCE_ITERATIONS_FIELD_NUMBER: _ClassVar[int]
    FORCE_SOLVES_FIELD_NUMBER: _ClassVar[int]
    shift_x_m: float
    shift_y_m: float
    rolling_m: float
    creepage_long: float
    creepage_lat: float
    force_iterations: int
    force_solves: int
    def __init__(self, shift_x_m: _Optional[float] = ..., shift_y_m: _Optional[float] = ..., rolling_m: _Optional[float] = ..., creepage_long: _Optional[float] = ..., creepage_lat: _Optional[float] = ..., force_iterations: _Optional[int] = ..., force_solves: _Optional[int] = ...) -> None: ...

class ForceDerivatives(_message.Message):
    __slots__ = ("normal_force", "fx", "fy", "mz")
    NORMAL_FORCE_FIELD_NUMBER: _ClassVar[int]
    FX_FIELD_NUMBER: _ClassVar[int]
    FY_FIELD_NUMBER: _ClassVar[int]
    MZ_FIELD_NUMBER: _ClassVar[int]
    normal_force: float
    fx: float
    fy: float
    mz: float
    def __init__(self, normal_force: _Optional[float] = ..., fx: _Optional[float] = ..., fy: _Optional[float] = ..., mz: _Optional[float] = ...) -> None: ...

class Sensitivities(_message.Message):
    __slots__ = ("per_approach_m", "per_creepage_long", "per_creepage_lat", "per_spin_per_m", "solves")
    PER_APPROACH_M_FIELD_NUMBER: _ClassVar[int]
    PER_CREEPAGE_LONG_FIELD_NUMBER: _ClassVar[int]
    PER_CREEPAGE_LAT_FIELD_NUMBER: _ClassVar[int]
    PER_SPIN_PER_M_FIELD_NUMBER: _ClassVar[int]
    SOLVES_FIELD_NUMBER: _ClassVar[int]
    per_approach_m: ForceDerivatives
    per_creepage_long: ForceDerivatives
    per_creepage_lat: ForceDerivatives
    per_spin_per_m: ForceDerivatives
    solves: int
    def __init__(self, per_approach_m: _Optional[_Union[ForceDerivatives, _Mapping]] = ..., per_creepage_long: _Optional[_Union[ForceDerivatives, _Mapping]] = ..., per_creepage_lat: _Optional[_Union[ForceDerivatives, _Mapping]] = ..., per_spin_per_m: _Optional[_Union[ForceDerivatives, _Mapping]] = ..., solves: _Optional[int] = ...) -> None: ...

class GridInfo(_message.Message):
    __slots__ = ("nx", "ny", "element_size_x_m", "element_size_y_m", "x0_m", "y0_m")
    NX_FIELD_NUMBER: _ClassVar[int]
    NY_FIELD_NUMBER: _ClassVar[int]
    ELEMENT_SIZE_X_M_FIELD_NUMBER: _ClassVar[int]
    ELEMENT_SIZE_Y_M_FIELD_NUMBER: _ClassVar[int]
    X0_M_FIELD_NUMBER: _ClassVar[int]
    Y0_M_FIELD_NUMBER: _ClassVar[int]
    nx: int
    ny: int
    element_size_x_m: float
    element_size_y_m: float
    x0_m: float
    y0_m: float
    def __init__(self, nx: _Optional[int] = ..., ny: _Optional[int] = ..., element_size_x_m: _Optional[float] = ..., element_size_y_m: _Optional[float] = ..., x0_m: _Optional[float] = ..., y0_m: _Optional[float] = ...) -> None: ...

class ElementFields(_message.Message):
    __slots__ = ("pressure_pa", "traction_x_pa", "traction_y_pa", "slip_x", "slip_y", "state", "gap_m", "delta_rad", "reference_points_m", "wfric_lateral_j_per_m2", "layer_yield_limit_pa", "layer_plastic_x_m", "layer_plastic_y_m", "layer_plastic")
    PRESSURE_PA_FIELD_NUMBER: _ClassVar[int]
    TRACTION_X_PA_FIELD_NUMBER: _ClassVar[int]
    TRACTION_Y_PA_FIELD_NUMBER: _ClassVar[int]
    SLIP_X_FIELD_NUMBER: _ClassVar[int]
    SLIP_Y_FIELD_NUMBER: _ClassVar[int]
    STATE_FIELD_NUMBER: _ClassVar[int]
    GAP_M_FIELD_NUMBER: _ClassVar[int]
    DELTA_RAD_FIELD_NUMBER: _ClassVar[int]
    REFERENCE_POINTS_M_FIELD_NUMBER: _ClassVar[int]
    WFRIC_LATERAL_J_PER_M2_FIELD_NUMBER: _ClassVar[int]
    LAYER_YIELD_LIMIT_PA_FIELD_NUMBER: _ClassVar[int]
    LAYER_PLASTIC_X_M_FIELD_NUMBER: _ClassVar[int]
    LAYER_PLASTIC_Y_M_FIELD_NUMBER: _ClassVar[int]
    LAYER_PLASTIC_FIELD_NUMBER: _ClassVar[int]
    pressure_pa: _containers.RepeatedScalarFieldContainer[float]
    traction_x_pa: _containers.RepeatedScalarFieldContainer[float]
    traction_y_pa: _containers.RepeatedScalarFieldContainer[float]
    slip_x: _containers.RepeatedScalarFieldContainer[float]
    slip_y: _containers.RepeatedScalarFieldContainer[float]
    state: _containers.RepeatedScalarFieldContainer[ElementState]
    gap_m: _containers.RepeatedScalarFieldContainer[float]
    delta_rad: _containers.RepeatedScalarFieldContainer[float]
    reference_points_m: _containers.RepeatedCompositeFieldContainer[ProfilePoint]
    wfric_lateral_j_per_m2: _containers.RepeatedScalarFieldContainer[float]
    layer_yield_limit_pa: _containers.RepeatedScalarFieldContainer[float]
    layer_plastic_x_m: _containers.RepeatedScalarFieldContainer[float]
    layer_plastic_y_m: _containers.RepeatedScalarFieldContainer[float]
    layer_plastic: _containers.RepeatedScalarFieldContainer[bool]
    def __init__(self, pressure_pa: _Optional[_Iterable[float]] = ..., traction_x_pa: _Optional[_Iterable[float]] = ..., traction_y_pa: _Optional[_Iterable[float]] = ..., slip_x: _Optional[_Iterable[float]] = ..., slip_y: _Optional[_Iterable[float]] = ..., state: _Optional[_Iterable[_Union[ElementState, str]]] = ..., gap_m: _Optional[_Iterable[float]] = ..., delta_rad: _Optional[_Iterable[float]] = ..., reference_points_m: _Optional[_Iterable[_Union[ProfilePoint, _Mapping]]] = ..., wfric_lateral_j_per_m2: _Optional[_Iterable[float]] = ..., layer_yield_limit_pa: _Optional[_Iterable[float]] = ..., layer_plastic_x_m: _Optional[_Iterable[float]] = ..., layer_plastic_y_m: _Optional[_Iterable[float]] = ..., layer_plastic: _Optional[_Iterable[bool]] = ...) -> None: ...

class PatchResult(_message.Message):
    __slots__ = ("model", "result", "steps", "friction_coefficient", "grid", "notes", "fields", "force_control", "subsurface", "temperature", "fastsim_max_pressure_pa", "steady_start")
    MODEL_FIELD_NUMBER: _ClassVar[int]
    RESULT_FIELD_NUMBER: _ClassVar[int]
    STEPS_FIELD_NUMBER: _ClassVar[int]
    FRICTION_COEFFICIENT_FIELD_NUMBER: _ClassVar[int]
    GRID_FIELD_NUMBER: _ClassVar[int]
    NOTES_FIELD_NUMBER: _ClassVar[int]
    FIELDS_FIELD_NUMBER: _ClassVar[int]
    FORCE_CONTROL_FIELD_NUMBER: _ClassVar[int]
    SUBSURFACE_FIELD_NUMBER: _ClassVar[int]
    TEMPERATURE_FIELD_NUMBER: _ClassVar[int]
    FASTSIM_MAX_PRESSURE_PA_FIELD_NUMBER: _ClassVar[int]
    STEADY_START_FIELD_NUMBER: _ClassVar[int]
    model: Model
    result: StepResult
    steps: _containers.RepeatedCompositeFieldContainer[StepResult]
    friction_coefficient: float
    grid: GridInfo
    notes: _containers.RepeatedScalarFieldContainer[str]
    fields: ElementFields
    force_control: ForceControl
    subsurface: SubsurfaceResult
    temperature: TemperatureResult
    fastsim_max_pressure_pa: float
    steady_start: StepResult
    def __init__(self, model: _Optional[_Union[Model, str]] = ..., result: _Optional[_Union[StepResult, _Mapping]] = ..., steps: _Optional[_Iterable[_Union[StepResult, _Mapping]]] = ..., friction_coefficient: _Optional[float] = ..., grid: _Optional[_Union[GridInfo, _Mapping]] = ..., notes: _Optional[_Iterable[str]] = ..., fields: _Optional[_Union[ElementFields, _Mapping]] = ..., force_control: _Optional[_Union[ForceControl, _Mapping]] = ..., subsurface: _Optional[_Union[SubsurfaceResult, _Mapping]] = ..., temperature: _Optional[_Union[TemperatureResult, _Mapping]] = ..., fastsim_max_pressure_pa: _Optional[float] = ..., steady_start: _Optional[_Union[StepResult, _Mapping]] = ...) -> None: ...

class TemperaturePeak(_message.Message):
    __slots__ = ("temperature_k", "x_m", "y_m")
    TEMPERATURE_K_FIELD_NUMBER: _ClassVar[int]
    X_M_FIELD_NUMBER: _ClassVar[int]
    Y_M_FIELD_NUMBER: _ClassVar[int]
    temperature_k: float
    x_m: float
    y_m: float
    def __init__(self, temperature_k: _Optional[float] = ..., x_m: _Optional[float] = ..., y_m: _Optional[float] = ...) -> None: ...

class TemperatureResult(_message.Message):
    __slots__ = ("max_body1", "max_body2", "contact_temperature_k", "heat_share_body1", "frictional_power_w", "peclet_number", "body1_k", "body2_k", "heat_flux_w_per_m2")
    MAX_BODY1_FIELD_NUMBER: _ClassVar[int]
    MAX_BODY2_FIELD_NUMBER: _ClassVar[int]
    CONTACT_TEMPERATURE_K_FIELD_NUMBER: _ClassVar[int]
    HEAT_SHARE_BODY1_FIELD_NUMBER: _ClassVar[int]
    FRICTIONAL_POWER_W_FIELD_NUMBER: _ClassVar[int]
    PECLET_NUMBER_FIELD_NUMBER: _ClassVar[int]
    BODY1_K_FIELD_NUMBER: _ClassVar[int]
    BODY2_K_FIELD_NUMBER: _ClassVar[int]
    HEAT_FLUX_W_PER_M2_FIELD_NUMBER: _ClassVar[int]
    max_body1: TemperaturePeak
    max_body2: TemperaturePeak
    contact_temperature_k: float
    heat_share_body1: float
    frictional_power_w: float
    peclet_number: float
    body1_k: _containers.RepeatedScalarFieldContainer[float]
    body2_k: _containers.RepeatedScalarFieldContainer[float]
    heat_flux_w_per_m2: _containers.RepeatedScalarFieldContainer[float]
    def __init__(self, max_body1: _Optional[_Union[TemperaturePeak, _Mapping]] = ..., max_body2: _Optional[_Union[TemperaturePeak, _Mapping]] = ..., contact_temperature_k: _Optional[float] = ..., heat_share_body1: _Optional[float] = ..., frictional_power_w: _Optional[float] = ..., peclet_number: _Optional[float] = ..., body1_k: _Optional[_Iterable[float]] = ..., body2_k: _Optional[_Iterable[float]] = ..., heat_flux_w_per_m2: _Optional[_Iterable[float]] = ...) -> None: ...

class StressPeak(_message.Message):
    __slots__ = ("value_pa", "x_m", "y_m", "depth_m")
    VALUE_PA_FIELD_NUMBER: _ClassVar[int]
    X_M_FIELD_NUMBER: _ClassVar[int]
    Y_M_FIELD_NUMBER: _ClassVar[int]
    DEPTH_M_FIELD_NUMBER: _ClassVar[int]
    value_pa: float
    x_m: float
    y_m: float
    depth_m: float
    def __init__(self, value_pa: _Optional[float] = ..., x_m: _Optional[float] = ..., y_m: _Optional[float] = ..., depth_m: _Optional[float] = ...) -> None: ...

class BodySubsurface(_message.Message):
    __slots__ = ("max_von_mises", "max_shear", "max_principal", "min_principal", "sigma_xx_pa", "sigma_yy_pa", "sigma_nn_pa", "sigma_xy_pa", "sigma_xn_pa", "sigma_yn_pa", "ux_m", "uy_m", "un_m")
    MAX_VON_MISES_FIELD_NUMBER: _ClassVar[int]
    MAX_SHEAR_FIELD_NUMBER: _ClassVar[int]
    MAX_PRINCIPAL_FIELD_NUMBER: _ClassVar[int]
    MIN_PRINCIPAL_FIELD_NUMBER: _ClassVar[int]
    SIGMA_XX_PA_FIELD_NUMBER: _ClassVar[int]
    SIGMA_YY_PA_FIELD_NUMBER: _ClassVar[int]
    SIGMA_NN_PA_FIELD_NUMBER: _ClassVar[int]
    SIGMA_XY_PA_FIELD_NUMBER: _ClassVar[int]
    SIGMA_XN_PA_FIELD_NUMBER: _ClassVar[int]
    SIGMA_YN_PA_FIELD_NUMBER: _ClassVar[int]
    UX_M_FIELD_NUMBER: _ClassVar[int]
    UY_M_FIELD_NUMBER: _ClassVar[int]
    UN_M_FIELD_NUMBER: _ClassVar[int]
    max_von_mises: StressPeak
    max_shear: StressPeak
    max_principal: StressPeak
    min_principal: StressPeak
    sigma_xx_pa: _containers.RepeatedScalarFieldContainer[float]
    sigma_yy_pa: _containers.RepeatedScalarFieldContainer[float]
    sigma_nn_pa: _containers.RepeatedScalarFieldContainer[float]
    sigma_xy_pa: _containers.RepeatedScalarFieldContainer[float]
    sigma_xn_pa: _containers.RepeatedScalarFieldContainer[float]
    sigma_yn_pa: _containers.RepeatedScalarFieldContainer[float]
    ux_m: _containers.RepeatedScalarFieldContainer[float]
    uy_m: _containers.RepeatedScalarFieldContainer[float]
    un_m: _containers.RepeatedScalarFieldContainer[float]
    def __init__(self, max_von_mises: _Optional[_Union[StressPeak, _Mapping]] = ..., max_shear: _Optional[_Union[StressPeak, _Mapping]] = ..., max_principal: _Optional[_Union[StressPeak, _Mapping]] = ..., min_principal: _Optional[_Union[StressPeak, _Mapping]] = ..., sigma_xx_pa: _Optional[_Iterable[float]] = ..., sigma_yy_pa: _Optional[_Iterable[float]] = ..., sigma_nn_pa: _Optional[_Iterable[float]] = ..., sigma_xy_pa: _Optional[_Iterable[float]] = ..., sigma_xn_pa: _Optional[_Iterable[float]] = ..., sigma_yn_pa: _Optional[_Iterable[float]] = ..., ux_m: _Optional[_Iterable[float]] = ..., uy_m: _Optional[_Iterable[float]] = ..., un_m: _Optional[_Iterable[float]] = ...) -> None: ...

class SubsurfaceResult(_message.Message):
    __slots__ = ("depths_m", "body1", "body2", "surface_fatigue_index")
    DEPTHS_M_FIELD_NUMBER: _ClassVar[int]
    BODY1_FIELD_NUMBER: _ClassVar[int]
    BODY2_FIELD_NUMBER: _ClassVar[int]
    SURFACE_FATIGUE_INDEX_FIELD_NUMBER: _ClassVar[int]
    depths_m: _containers.RepeatedScalarFieldContainer[float]
    body1: BodySubsurface
    body2: BodySubsurface
    surface_fatigue_index: float
    def __init__(self, depths_m: _Optional[_Iterable[float]] = ..., body1: _Optional[_Union[BodySubsurface, _Mapping]] = ..., body2: _Optional[_Union[BodySubsurface, _Mapping]] = ..., surface_fatigue_index: _Optional[float] = ...) -> None: ...

class ForceControl(_message.Message):
    __slots__ = ("creepage_long", "creepage_lat", "spin_per_m", "force_iterations", "force_solves")
    CREEPAGE_LONG_FIELD_NUMBER: _ClassVar[int]
    CREEPAGE_LAT_FIELD_NUMBER: _ClassVar[int]
    SPIN_PER_M_FIELD_NUMBER: _ClassVar[int]
    FORCE_ITERATIONS_FIELD_NUMBER: _ClassVar[int]
    FORCE_SOLVES_FIELD_NUMBER: _ClassVar[int]
    creepage_long: float
    creepage_lat: float
    spin_per_m: float
    force_iterations: int
    force_solves: int
    def __init__(self, creepage_long: _Optional[float] = ..., creepage_lat: _Optional[float] = ..., spin_per_m: _Optional[float] = ..., force_iterations: _Optional[int] = ..., force_solves: _Optional[int] = ...) -> None: ...

class SolvePatchRequest(_message.Message):
    __slots__ = ("case", "include_fields", "include_sensitivities")
    CASE_FIELD_NUMBER: _ClassVar[int]
    INCLUDE_FIELDS_FIELD_NUMBER: _ClassVar[int]
    INCLUDE_SENSITIVITIES_FIELD_NUMBER: _ClassVar[int]
    case: PatchCase
    include_fields: bool
    include_sensitivities: bool
    def __init__(self, case: _Optional[_Union[PatchCase, _Mapping]] = ..., include_fields: _Optional[bool] = ..., include_sensitivities: _Optional[bool] = ...) -> None: ...

class SolvePatchResponse(_message.Message):
    __slots__ = ("result",)
    RESULT_FIELD_NUMBER: _ClassVar[int]
    result: PatchResult
    def __init__(self, result: _Optional[_Union[PatchResult, _Mapping]] = ...) -> None: ...

class SolvePatchBatchRequest(_message.Message):
    __slots__ = ("items",)
    ITEMS_FIELD_NUMBER: _ClassVar[int]
    items: _containers.RepeatedCompositeFieldContainer[SolvePatchRequest]
    def __init__(self, items: _Optional[_Iterable[_Union[SolvePatchRequest, _Mapping]]] = ...) -> None: ...

class ItemError(_message.Message):
    __slots__ = ("code", "message", "field")
    CODE_FIELD_NUMBER: _ClassVar[int]
    MESSAGE_FIELD_NUMBER: _ClassVar[int]
    FIELD_FIELD_NUMBER: _ClassVar[int]
    code: int
    message: str
    field: str
    def __init__(self, code: _Optional[int] = ..., message: _Optional[str] = ..., field: _Optional[str] = ...) -> None: ...

class BatchItemResult(_message.Message):
    __slots__ = ("index", "result", "error")
    INDEX_FIELD_NUMBER: _ClassVar[int]
    RESULT_FIELD_NUMBER: _ClassVar[int]
    ERROR_FIELD_NUMBER: _ClassVar[int]
    index: int
    result: PatchResult
    error: ItemError
    def __init__(self, index: _Optional[int] = ..., result: _Optional[_Union[PatchResult, _Mapping]] = ..., error: _Optional[_Union[ItemError, _Mapping]] = ...) -> None: ...

class SolvePatchBatchResponse(_message.Message):
    __slots__ = ("items",)
    ITEMS_FIELD_NUMBER: _ClassVar[int]
    items: _containers.RepeatedCompositeFieldContainer[BatchItemResult]
    def __init__(self, items: _Optional[_Iterable[_Union[BatchItemResult, _Mapping]]] = ...) -> None: ...

class LinearSweep(_message.Message):
    __slots__ = ("to", "points")
    FROM_FIELD_NUMBER: _ClassVar[int]
    TO_FIELD_NUMBER: _ClassVar[int]
    POINTS_FIELD_NUMBER: _ClassVar[int]
    to: Creepages
    points: int
    def __init__(self, to: _Optional[_Union[Creepages, _Mapping]] = ..., points: _Optional[int] = ..., **kwargs) -> None: ...

class CreepageList(_message.Message):
    __slots__ = ("points",)
    POINTS_FIELD_NUMBER: _ClassVar[int]
    points: _containers.RepeatedCompositeFieldContainer[Creepages]
    def __init__(self, points: _Optional[_Iterable[_Union[Creepages, _Mapping]]] = ...) -> None: ...

class CreepCurveRequest(_message.Message):
    __slots__ = ("case", "linear", "list", "include_fields")
    CASE_FIELD_NUMBER: _ClassVar[int]
    LINEAR_FIELD_NUMBER: _ClassVar[int]
    LIST_FIELD_NUMBER: _ClassVar[int]
    INCLUDE_FIELDS_FIELD_NUMBER: _ClassVar[int]
    case: PatchCase
    linear: LinearSweep
    list: CreepageList
    include_fields: bool
    def __init__(self, case: _Optional[_Union[PatchCase, _Mapping]] = ..., linear: _Optional[_Union[LinearSweep, _Mapping]] = ..., list: _Optional[_Union[CreepageList, _Mapping]] = ..., include_fields: _Optional[bool] = ...) -> None: ...

class CreepCurvePoint(_message.Message):
    __slots__ = ("index", "creepages", "result")
    INDEX_FIELD_NUMBER: _ClassVar[int]
    CREEPAGES_FIELD_NUMBER: _ClassVar[int]
    RESULT_FIELD_NUMBER: _ClassVar[int]
    index: int
    creepages: Creepages
    result: PatchResult
    def __init__(self, index: _Optional[int] = ..., creepages: _Optional[_Union[Creepages, _Mapping]] = ..., result: _Optional[_Union[PatchResult, _Mapping]] = ...) -> None: ...

class SessionOpen(_message.Message):
    __slots__ = ("case", "include_fields", "client_label", "include_sensitivities")
    CASE_FIELD_NUMBER: _ClassVar[int]
    INCLUDE_FIELDS_FIELD_NUMBER: _ClassVar[int]
    CLIENT_LABEL_FIELD_NUMBER: _ClassVar[int]
    INCLUDE_SENSITIVITIES_FIELD_NUMBER: _ClassVar[int]
    case: PatchCase
    include_fields: bool
    client_label: str
    include_sensitivities: bool
    def __init__(self, case: _Optional[_Union[PatchCase, _Mapping]] = ..., include_fields: _Optional[bool] = ..., client_label: _Optional[str] = ..., include_sensitivities: _Optional[bool] = ...) -> None: ...

class SessionStep(_message.Message):
    __slots__ = ("step_index", "time_s", "normal_force_n", "approach_m", "creepages", "shift", "mark")
    STEP_INDEX_FIELD_NUMBER: _ClassVar[int]
    TIME_S_FIELD_NUMBER: _ClassVar[int]
    NORMAL_FORCE_N_FIELD_NUMBER: _ClassVar[int]
    APPROACH_M_FIELD_NUMBER: _ClassVar[int]
    CREEPAGES_FIELD_NUMBER: _ClassVar[int]
    SHIFT_FIELD_NUMBER: _ClassVar[int]
    MARK_FIELD_NUMBER: _ClassVar[int]
    step_index: int
    time_s: float
    normal_force_n: float
    approach_m: float
    creepages: Creepages
    shift: ShiftStep
    mark: bool
    def __init__(self, step_index: _Optional[int] = ..., time_s: _Optional[float] = ..., normal_force_n: _Optional[float] = ..., approach_m: _Optional[float] = ..., creepages: _Optional[_Union[Creepages, _Mapping]] = ..., shift: _Optional[_Union[ShiftStep, _Mapping]] = ..., mark: _Optional[bool] = ...) -> None: ...

class SessionRollback(_message.Message):
    __slots__ = ("to_step_index",)
    TO_STEP_INDEX_FIELD_NUMBER: _ClassVar[int]
    to_step_index: int
    def __init__(self, to_step_index: _Optional[int] = ...) -> None: ...

class SessionRequest(_message.Message):
    __slots__ = ("open", "step", "rollback")
    OPEN_FIELD_NUMBER: _ClassVar[int]
    STEP_FIELD_NUMBER: _ClassVar[int]
    ROLLBACK_FIELD_NUMBER: _ClassVar[int]
    open: SessionOpen
    step: SessionStep
    rollback: SessionRollback
    def __init__(self, open: _Optional[_Union[SessionOpen, _Mapping]] = ..., step: _Optional[_Union[SessionStep, _Mapping]] = ..., rollback: _Optional[_Union[SessionRollback, _Mapping]] = ...) -> None: ...

class SessionOpened(_message.Message):
    __slots__ = ("session_id", "model", "grid", "notes")
    SESSION_ID_FIELD_NUMBER: _ClassVar[int]
    MODEL_FIELD_NUMBER: _ClassVar[int]
    GRID_FIELD_NUMBER: _ClassVar[int]
    NOTES_FIELD_NUMBER: _ClassVar[int]
    session_id: str
    model: Model
    grid: GridInfo
    notes: _containers.RepeatedScalarFieldContainer[str]
    def __init__(self, session_id: _Optional[str] = ..., model: _Optional[_Union[Model, str]] = ..., grid: _Optional[_Union[GridInfo, _Mapping]] = ..., notes: _Optional[_Iterable[str]] = ...) -> None: ...

class SessionStepResult(_message.Message):
    __slots__ = ("step_index", "time_s", "result", "fields", "marked", "force_control")
    STEP_INDEX_FIELD_NUMBER: _ClassVar[int]
    TIME_S_FIELD_NUMBER: _ClassVar[int]
    RESULT_FIELD_NUMBER: _ClassVar[int]
    FIELDS_FIELD_NUMBER: _ClassVar[int]
    MARKED_FIELD_NUMBER: _ClassVar[int]
    FORCE_CONTROL_FIELD_NUMBER: _ClassVar[int]
    step_index: int
    time_s: float
    result: StepResult
    fields: ElementFields
    marked: bool
    force_control: ForceControl
    def __init__(self, step_index: _Optional[int] = ..., time_s: _Optional[float] = ..., result: _Optional[_Union[StepResult, _Mapping]] = ..., fields: _Optional[_Union[ElementFields, _Mapping]] = ..., marked: _Optional[bool] = ..., force_control: _Optional[_Union[ForceControl, _Mapping]] = ...) -> None: ...

class SessionRolledBack(_message.Message):
    __slots__ = ("to_step_index", "next_step_index")
    TO_STEP_INDEX_FIELD_NUMBER: _ClassVar[int]
    NEXT_STEP_INDEX_FIELD_NUMBER: _ClassVar[int]
    to_step_index: int
    next_step_index: int
    def __init__(self, to_step_index: _Optional[int] = ..., next_step_index: _Optional[int] = ...) -> None: ...

class SessionResponse(_message.Message):
    __slots__ = ("opened", "step", "rolled_back", "error")
    OPENED_FIELD_NUMBER: _ClassVar[int]
    STEP_FIELD_NUMBER: _ClassVar[int]
    ROLLED_BACK_FIELD_NUMBER: _ClassVar[int]
    ERROR_FIELD_NUMBER: _ClassVar[int]
    opened: SessionOpened
    step: SessionStepResult
    rolled_back: SessionRolledBack
    error: ItemError
    def __init__(self, opened: _Optional[_Union[SessionOpened, _Mapping]] = ..., step: _Optional[_Union[SessionStepResult, _Mapping]] = ..., rolled_back: _Optional[_Union[SessionRolledBack, _Mapping]] = ..., error: _Optional[_Union[ItemError, _Mapping]] = ...) -> None: ...

class ProfileSource(_message.Message):
    __slots__ = ("builtin_name", "file", "slices", "mirror_y")
    BUILTIN_NAME_FIELD_NUMBER: _ClassVar[int]
    FILE_FIELD_NUMBER: _ClassVar[int]
    SLICES_FIELD_NUMBER: _ClassVar[int]
    MIRROR_Y_FIELD_NUMBER: _ClassVar[int]
    builtin_name: str
    file: ProfileFile
    slices: RailSlices
    mirror_y: bool
    def __init__(self, builtin_name: _Optional[str] = ..., file: _Optional[_Union[ProfileFile, _Mapping]] = ..., slices: _Optional[_Union[RailSlices, _Mapping]] = ..., mirror_y: _Optional[bool] = ...) -> None: ...

class RailSlices(_message.Message):
    __slots__ = ("file_name", "content", "profiles")
    FILE_NAME_FIELD_NUMBER: _ClassVar[int]
    CONTENT_FIELD_NUMBER: _ClassVar[int]
    PROFILES_FIELD_NUMBER: _ClassVar[int]
    file_name: str
    content: str
    profiles: _containers.RepeatedCompositeFieldContainer[ProfileFile]
    def __init__(self, file_name: _Optional[str] = ..., content: _Optional[str] = ..., profiles: _Optional[_Iterable[_Union[ProfileFile, _Mapping]]] = ...) -> None: ...

class ProfileFile(_message.Message):
    __slots__ = ("format", "content", "file_name", "plain_unit")
    FORMAT_FIELD_NUMBER: _ClassVar[int]
    CONTENT_FIELD_NUMBER: _ClassVar[int]
    FILE_NAME_FIELD_NUMBER: _ClassVar[int]
    PLAIN_UNIT_FIELD_NUMBER: _ClassVar[int]
    format: ProfileFormat
    content: str
    file_name: str
    plain_unit: LengthUnit
    def __init__(self, format: _Optional[_Union[ProfileFormat, str]] = ..., content: _Optional[str] = ..., file_name: _Optional[str] = ..., plain_unit: _Optional[_Union[LengthUnit, str]] = ...) -> None: ...

class TrackSpec(_message.Message):
    __slots__ = ("gauge_m", "gauge_height_m", "cant_rad", "rail_origin_y_m", "rail_origin_z_m", "rail_deviation_left", "rail_deviation_right", "roller_radius_m", "curvature_per_m")
    GAUGE_M_FIELD_NUMBER: _ClassVar[int]
    GAUGE_HEIGHT_M_FIELD_NUMBER: _ClassVar[int]
    CANT_RAD_FIELD_NUMBER: _ClassVar[int]
    RAIL_ORIGIN_Y_M_FIELD_NUMBER: _ClassVar[int]
    RAIL_ORIGIN_Z_M_FIELD_NUMBER: _ClassVar[int]
    RAIL_DEVIATION_LEFT_FIELD_NUMBER: _ClassVar[int]
    RAIL_DEVIATION_RIGHT_FIELD_NUMBER: _ClassVar[int]
    ROLLER_RADIUS_M_FIELD_NUMBER: _ClassVar[int]
    CURVATURE_PER_M_FIELD_NUMBER: _ClassVar[int]
    gauge_m: float
    gauge_height_m: float
    cant_rad: float
    rail_origin_y_m: float
    rail_origin_z_m: float
    rail_deviation_left: RailDeviation
    rail_deviation_right: RailDeviation
    roller_radius_m: float
    curvature_per_m: float
    def __init__(self, gauge_m: _Optional[float] = ..., gauge_height_m: _Optional[float] = ..., cant_rad: _Optional[float] = ..., rail_origin_y_m: _Optional[float] = ..., rail_origin_z_m: _Optional[float] = ..., rail_deviation_left: _Optional[_Union[RailDeviation, _Mapping]] = ..., rail_deviation_right: _Optional[_Union[RailDeviation, _Mapping]] = ..., roller_radius_m: _Optional[float] = ..., curvature_per_m: _Optional[float] = ...) -> None: ...

class RailDeviation(_message.Message):
    __slots__ = ("dy_m", "dz_m", "droll_rad")
    DY_M_FIELD_NUMBER: _ClassVar[int]
    DZ_M_FIELD_NUMBER: _ClassVar[int]
    DROLL_RAD_FIELD_NUMBER: _ClassVar[int]
    dy_m: float
    dz_m: float
    droll_rad: float
    def __init__(self, dy_m: _Optional[float] = ..., dz_m: _Optional[float] = ..., droll_rad: _Optional[float] = ...) -> None: ...

class WheelsetSpec(_message.Message):
    __slots__ = ("flange_back_distance_m", "nominal_radius_m", "flange_back_y_m")
    FLANGE_BACK_DISTANCE_M_FIELD_NUMBER: _ClassVar[int]
    NOMINAL_RADIUS_M_FIELD_NUMBER: _ClassVar[int]
    FLANGE_BACK_Y_M_FIELD_NUMBER: _ClassVar[int]
    flange_back_distance_m: float
    nominal_radius_m: float
    flange_back_y_m: float
    def __init__(self, flange_back_distance_m: _Optional[float] = ..., nominal_radius_m: _Optional[float] = ..., flange_back_y_m: _Optional[float] = ...) -> None: ...

class WheelRailGrid(_message.Message):
    __slots__ = ("element_size_m",)
    ELEMENT_SIZE_M_FIELD_NUMBER: _ClassVar[int]
    element_size_m: float
    def __init__(self, element_size_m: _Optional[float] = ...) -> None: ...

class ProfilePairSpec(_message.Message):
    __slots__ = ("wheel", "rail", "material", "friction", "grid", "wheel_left", "rail_left", "track", "wheelset", "smoothing_wavelength_m")
    WHEEL_FIELD_NUMBER: _ClassVar[int]
    RAIL_FIELD_NUMBER: _ClassVar[int]
    MATERIAL_FIELD_NUMBER: _ClassVar[int]
    FRICTION_FIELD_NUMBER: _ClassVar[int]
    GRID_FIELD_NUMBER: _ClassVar[int]
    WHEEL_LEFT_FIELD_NUMBER: _ClassVar[int]
    RAIL_LEFT_FIELD_NUMBER: _ClassVar[int]
    TRACK_FIELD_NUMBER: _ClassVar[int]
    WHEELSET_FIELD_NUMBER: _ClassVar[int]
    SMOOTHING_WAVELENGTH_M_FIELD_NUMBER: _ClassVar[int]
    wheel: ProfileSource
    rail: ProfileSource
    material: MaterialSection
    friction: FrictionSection
    grid: WheelRailGrid
    wheel_left: ProfileSource
    rail_left: ProfileSource
    track: TrackSpec
    wheelset: WheelsetSpec
    smoothing_wavelength_m: float
    def __init__(self, wheel: _Optional[_Union[ProfileSource, _Mapping]] = ..., rail: _Optional[_Union[ProfileSource, _Mapping]] = ..., material: _Optional[_Union[MaterialSection, _Mapping]] = ..., friction: _Optional[_Union[FrictionSection, _Mapping]] = ..., grid: _Optional[_Union[WheelRailGrid, _Mapping]] = ..., wheel_left: _Optional[_Union[ProfileSource, _Mapping]] = ..., rail_left: _Optional[_Union[ProfileSource, _Mapping]] = ..., track: _Optional[_Union[TrackSpec, _Mapping]] = ..., wheelset: _Optional[_Union[WheelsetSpec, _Mapping]] = ..., smoothing_wavelength_m: _Optional[float] = ...) -> None: ...

class RegisterProfilePairRequest(_message.Message):
    __slots__ = ("builtin_pair", "spec", "label")
    BUILTIN_PAIR_FIELD_NUMBER: _ClassVar[int]
    SPEC_FIELD_NUMBER: _ClassVar[int]
    LABEL_FIELD_NUMBER: _ClassVar[int]
    builtin_pair: str
    spec: ProfilePairSpec
    label: str
    def __init__(self, builtin_pair: _Optional[str] = ..., spec: _Optional[_Union[ProfilePairSpec, _Mapping]] = ..., label: _Optional[str] = ...) -> None: ...

class RegistrationProgress(_message.Message):
    __slots__ = ("stage", "pair_id", "fraction_done", "elapsed_s", "message", "pair", "already_registered")
    STAGE_FIELD_NUMBER: _ClassVar[int]
    PAIR_ID_FIELD_NUMBER: _ClassVar[int]
    FRACTION_DONE_FIELD_NUMBER: _ClassVar[int]
    ELAPSED_S_FIELD_NUMBER: _ClassVar[int]
    MESSAGE_FIELD_NUMBER: _ClassVar[int]
    PAIR_FIELD_NUMBER: _ClassVar[int]
    ALREADY_REGISTERED_FIELD_NUMBER: _ClassVar[int]
    stage: RegistrationStage
    pair_id: str
    fraction_done: float
    elapsed_s: float
    message: str
    pair: ProfilePairInfo
    already_registered: bool
    def __init__(self, stage: _Optional[_Union[RegistrationStage, str]] = ..., pair_id: _Optional[str] = ..., fraction_done: _Optional[float] = ..., elapsed_s: _Optional[float] = ..., message: _Optional[str] = ..., pair: _Optional[_Union[ProfilePairInfo, _Mapping]] = ..., already_registered: _Optional[bool] = ...) -> None: ...

class ProfileSummary(_message.Message):
    __slots__ = ("file_name", "builtin", "mirror_y", "format", "point_count", "warnings")
    FILE_NAME_FIELD_NUMBER: _ClassVar[int]
    BUILTIN_FIELD_NUMBER: _ClassVar[int]
    MIRROR_Y_FIELD_NUMBER: _ClassVar[int]
    FORMAT_FIELD_NUMBER: _ClassVar[int]
    POINT_COUNT_FIELD_NUMBER: _ClassVar[int]
    WARNINGS_FIELD_NUMBER: _ClassVar[int]
    file_name: str
    builtin: bool
    mirror_y: bool
    format: str
    point_count: int
    warnings: _containers.RepeatedScalarFieldContainer[str]
    def __init__(self, file_name: _Optional[str] = ..., builtin: _Optional[bool] = ..., mirror_y: _Optional[bool] = ..., format: _Optional[str] = ..., point_count: _Optional[int] = ..., warnings: _Optional[_Iterable[str]] = ...) -> None: ...

class ProfilePairInfo(_message.Message):
    __slots__ = ("pair_id", "label", "builtin_pair", "state", "error", "wheel", "rail", "wheel_left", "rail_left", "track", "wheelset", "material", "friction", "element_size_m", "smoothing_wavelength_m", "prepare_time_s", "persisted")
    PAIR_ID_FIELD_NUMBER: _ClassVar[int]
    LABEL_FIELD_NUMBER: _ClassVar[int]
    BUILTIN_PAIR_FIELD_NUMBER: _ClassVar[int]
    STATE_FIELD_NUMBER: _ClassVar[int]
    ERROR_FIELD_NUMBER: _ClassVar[int]
    WHEEL_FIELD_NUMBER: _ClassVar[int]
    RAIL_FIELD_NUMBER: _ClassVar[int]
    WHEEL_LEFT_FIELD_NUMBER: _ClassVar[int]
    RAIL_LEFT_FIELD_NUMBER: _ClassVar[int]
    TRACK_FIELD_NUMBER: _ClassVar[int]
    WHEELSET_FIELD_NUMBER: _ClassVar[int]
    MATERIAL_FIELD_NUMBER: _ClassVar[int]
    FRICTION_FIELD_NUMBER: _ClassVar[int]
    ELEMENT_SIZE_M_FIELD_NUMBER: _ClassVar[int]
    SMOOTHING_WAVELENGTH_M_FIELD_NUMBER: _ClassVar[int]
    PREPARE_TIME_S_FIELD_NUMBER: _ClassVar[int]
    PERSISTED_FIELD_NUMBER: _ClassVar[int]
    pair_id: str
    label: str
    builtin_pair: str
    state: ProfilePairState
    error: str
    wheel: ProfileSummary
    rail: ProfileSummary
    wheel_left: ProfileSummary
    rail_left: ProfileSummary
    track: TrackSpec
    wheelset: WheelsetSpec
    material: MaterialSection
    friction: FrictionSection
    element_size_m: float
    smoothing_wavelength_m: float
    prepare_time_s: float
    persisted: bool
    def __init__(self, pair_id: _Optional[str] = ..., label: _Optional[str] = ..., builtin_pair: _Optional[str] = ..., state: _Optional[_Union[ProfilePairState, str]] = ..., error: _Optional[str] = ..., wheel: _Optional[_Union[ProfileSummary, _Mapping]] = ..., rail: _Optional[_Union[ProfileSummary, _Mapping]] = ..., wheel_left: _Optional[_Union[ProfileSummary, _Mapping]] = ..., rail_left: _Optional[_Union[ProfileSummary, _Mapping]] = ..., track: _Optional[_Union[TrackSpec, _Mapping]] = ..., wheelset: _Optional[_Union[WheelsetSpec, _Mapping]] = ..., material: _Optional[_Union[MaterialSection, _Mapping]] = ..., friction: _Optional[_Union[FrictionSection, _Mapping]] = ..., element_size_m: _Optional[float] = ..., smoothing_wavelength_m: _Optional[float] = ..., prepare_time_s: _Optional[float] = ..., persisted: _Optional[bool] = ...) -> None: ...

class GetProfilePairRequest(_message.Message):
    __slots__ = ("pair_id",)
    PAIR_ID_FIELD_NUMBER: _ClassVar[int]
    pair_id: str
    def __init__(self, pair_id: _Optional[str] = ...) -> None: ...

class ListProfilePairsRequest(_message.Message):
    __slots__ = ()
    def __init__(self) -> None: ...

class ListProfilePairsResponse(_message.Message):
    __slots__ = ("pairs",)
    PAIRS_FIELD_NUMBER: _ClassVar[int]
    pairs: _containers.RepeatedCompositeFieldContainer[ProfilePairInfo]
    def __init__(self, pairs: _Optional[_Iterable[_Union[ProfilePairInfo, _Mapping]]] = ...) -> None: ...

class DeleteProfilePairRequest(_message.Message):
    __slots__ = ("pair_id",)
    PAIR_ID_FIELD_NUMBER: _ClassVar[int]
    pair_id: str
    def __init__(self, pair_id: _Optional[str] = ...) -> None: ...

class DeleteProfilePairResponse(_message.Message):
    __slots__ = ("pair_id",)
    PAIR_ID_FIELD_NUMBER: _ClassVar[int]
    pair_id: str
    def __init__(self, pair_id: _Optional[str] = ...) -> None: ...

class ModifiedFastsimParameters(_message.Message):
    __slots__ = ("initial_factor", "limit_ratio", "transition_rate", "friction_limit_ratio", "friction_decay_s_per_m")
    INITIAL_FACTOR_FIELD_NUMBER: _ClassVar[int]
    LIMIT_RATIO_FIELD_NUMBER: _ClassVar[int]
    TRANSITION_RATE_FIELD_NUMBER: _ClassVar[int]
    FRICTION_LIMIT_RATIO_FIELD_NUMBER: _ClassVar[int]
    FRICTION_DECAY_S_PER_M_FIELD_NUMBER: _ClassVar[int]
    initial_factor: float
    limit_ratio: float
    transition_rate: float
    friction_limit_ratio: float
    friction_decay_s_per_m: float
    def __init__(self, initial_factor: _Optional[float] = ..., limit_ratio: _Optional[float] = ..., transition_rate: _Optional[float] = ..., friction_limit_ratio: _Optional[float] = ..., friction_decay_s_per_m: _Optional[float] = ...) -> None: ...

class PolachParameters(_message.Message):
    __slots__ = ("k_adhesion", "k_slip", "limit_ratio", "decay_s_per_m")
    K_ADHESION_FIELD_NUMBER: _ClassVar[int]
    K_SLIP_FIELD_NUMBER: _ClassVar[int]
    LIMIT_RATIO_FIELD_NUMBER: _ClassVar[int]
    DECAY_S_PER_M_FIELD_NUMBER: _ClassVar[int]
    k_adhesion: float
    k_slip: float
    limit_ratio: float
    decay_s_per_m: float
    def __init__(self, k_adhesion: _Optional[float] = ..., k_slip: _Optional[float] = ..., limit_ratio: _Optional[float] = ..., decay_s_per_m: _Optional[float] = ...) -> None: ...

class WheelsetPosition(_message.Message):
    __slots__ = ("lateral_m", "yaw_rad", "roll_rad", "track_s_m")
    LATERAL_M_FIELD_NUMBER: _ClassVar[int]
    YAW_RAD_FIELD_NUMBER: _ClassVar[int]
    ROLL_RAD_FIELD_NUMBER: _ClassVar[int]
    TRACK_S_M_FIELD_NUMBER: _ClassVar[int]
    lateral_m: float
    yaw_rad: float
    roll_rad: float
    track_s_m: float
    def __init__(self, lateral_m: _Optional[float] = ..., yaw_rad: _Optional[float] = ..., roll_rad: _Optional[float] = ..., track_s_m: _Optional[float] = ...) -> None: ...

class FrictionTable(_message.Message):
    __slots__ = ("contact_angles_rad", "rail_y_m", "coefficients", "track_s_m")
    CONTACT_ANGLES_RAD_FIELD_NUMBER: _ClassVar[int]
    RAIL_Y_M_FIELD_NUMBER: _ClassVar[int]
    COEFFICIENTS_FIELD_NUMBER: _ClassVar[int]
    TRACK_S_M_FIELD_NUMBER: _ClassVar[int]
    contact_angles_rad: _containers.RepeatedScalarFieldContainer[float]
    rail_y_m: _containers.RepeatedScalarFieldContainer[float]
    coefficients: _containers.RepeatedScalarFieldContainer[float]
    track_s_m: _containers.RepeatedScalarFieldContainer[float]
    def __init__(self, contact_angles_rad: _Optional[_Iterable[float]] = ..., rail_y_m: _Optional[_Iterable[float]] = ..., coefficients: _Optional[_Iterable[float]] = ..., track_s_m: _Optional[_Iterable[float]] = ...) -> None: ...

class WheelsetVelocity(_message.Message):
    __slots__ = ("forward_m_per_s", "lateral_m_per_s", "vertical_m_per_s", "roll_rad_per_s", "yaw_rad_per_s", "pitch_rad_per_s", "roller_rad_per_s")
    FORWARD_M_PER_S_FIELD_NUMBER: _ClassVar[int]
    LATERAL_M_PER_S_FIELD_NUMBER: _ClassVar[int]
    VERTICAL_M_PER_S_FIELD_NUMBER: _ClassVar[int]
    ROLL_RAD_PER_S_FIELD_NUMBER: _ClassVar[int]
    YAW_RAD_PER_S_FIELD_NUMBER: _ClassVar[int]
    PITCH_RAD_PER_S_FIELD_NUMBER: _ClassVar[int]
    ROLLER_RAD_PER_S_FIELD_NUMBER: _ClassVar[int]
    forward_m_per_s: float
    lateral_m_per_s: float
    vertical_m_per_s: float
    roll_rad_per_s: float
    yaw_rad_per_s: float
    pitch_rad_per_s: float
    roller_rad_per_s: float
    def __init__(self, forward_m_per_s: _Optional[float] = ..., lateral_m_per_s: _Optional[float] = ..., vertical_m_per_s: _Optional[float] = ..., roll_rad_per_s: _Optional[float] = ..., yaw_rad_per_s: _Optional[float] = ..., pitch_rad_per_s: _Optional[float] = ..., roller_rad_per_s: _Optional[float] = ...) -> None: ...

class WheelLoad(_message.Message):
    __slots__ = ("vertical_force_n", "approach_m", "center_z_m", "total_longitudinal_force_n")
    VERTICAL_FORCE_N_FIELD_NUMBER: _ClassVar[int]
    APPROACH_M_FIELD_NUMBER: _ClassVar[int]
    CENTER_Z_M_FIELD_NUMBER: _ClassVar[int]
    TOTAL_LONGITUDINAL_FORCE_N_FIELD_NUMBER: _ClassVar[int]
    vertical_force_n: float
    approach_m: float
    center_z_m: float
    total_longitudinal_force_n: float
    def __init__(self, vertical_force_n: _Optional[float] = ..., approach_m: _Optional[float] = ..., center_z_m: _Optional[float] = ..., total_longitudinal_force_n: _Optional[float] = ...) -> None: ...

class SolveWheelRailRequest(_message.Message):
    __slots__ = ("pair_id", "model", "sides", "position", "velocity", "load", "friction", "element_size_m", "include_fields", "polach", "conformal", "friction_table", "modified_fastsim", "temperature", "min_elements_across", "force_tolerance_of_wheel_load")
    PAIR_ID_FIELD_NUMBER: _ClassVar[int]
    MODEL_FIELD_NUMBER: _ClassVar[int]
    SIDES_FIELD_NUMBER: _ClassVar[int]
    POSITION_FIELD_NUMBER: _ClassVar[int]
    VELOCITY_FIELD_NUMBER: _ClassVar[int]
    LOAD_FIELD_NUMBER: _ClassVar[int]
    FRICTION_FIELD_NUMBER: _ClassVar[int]
    ELEMENT_SIZE_M_FIELD_NUMBER: _ClassVar[int]
    INCLUDE_FIELDS_FIELD_NUMBER: _ClassVar[int]
    POLACH_FIELD_NUMBER: _ClassVar[int]
    CONFORMAL_FIELD_NUMBER: _ClassVar[int]
    FRICTION_TABLE_FIELD_NUMBER: _ClassVar[int]
    MODIFIED_FASTSIM_FIELD_NUMBER: _ClassVar[int]
    TEMPERATURE_FIELD_NUMBER: _ClassVar[int]
    MIN_ELEMENTS_ACROSS_FIELD_NUMBER: _ClassVar[int]
    FORCE_TOLERANCE_OF_WHEEL_LOAD_FIELD_NUMBER: _ClassVar[int]
    pair_id: str
    model: WheelRailModel
    sides: WheelSides
    position: WheelsetPosition
    velocity: WheelsetVelocity
    load: WheelLoad
    friction: FrictionSection
    element_size_m: float
    include_fields: bool
    polach: PolachParameters
    conformal: ConformalSection
    friction_table: FrictionTable
    modified_fastsim: ModifiedFastsimParameters
    temperature: TemperatureSection
    min_elements_across: int
    force_tolerance_of_wheel_load: float
    def __init__(self, pair_id: _Optional[str] = ..., model: _Optional[_Union[WheelRailModel, str]] = ..., sides: _Optional[_Union[WheelSides, str]] = ..., position: _Optional[_Union[WheelsetPosition, _Mapping]] = ..., velocity: _Optional[_Union[WheelsetVelocity, _Mapping]] = ..., load: _Optional[_Union[WheelLoad, _Mapping]] = ..., friction: _Optional[_Union[FrictionSection, _Mapping]] = ..., element_size_m: _Optional[float] = ..., include_fields: _Optional[bool] = ..., polach: _Optional[_Union[PolachParameters, _Mapping]] = ..., conformal: _Optional[_Union[ConformalSection, _Mapping]] = ..., friction_table: _Optional[_Union[FrictionTable, _Mapping]] = ..., modified_fastsim: _Optional[_Union[ModifiedFastsimParameters, _Mapping]] = ..., temperature: _Optional[_Union[TemperatureSection, _Mapping]] = ..., min_elements_across: _Optional[int] = ..., force_tolerance_of_wheel_load: _Optional[float] = ...) -> None: ...

class TrackForce(_message.Message):
    __slots__ = ("x_n", "y_n", "z_n")
    X_N_FIELD_NUMBER: _ClassVar[int]
    Y_N_FIELD_NUMBER: _ClassVar[int]
    Z_N_FIELD_NUMBER: _ClassVar[int]
    x_n: float
    y_n: float
    z_n: float
    def __init__(self, x_n: _Optional[float] = ..., y_n: _Optional[float] = ..., z_n: _Optional[float] = ...) -> None: ...

class WheelRailPatch(_message.Message):
    __slots__ = ("method", "contact_angle_rad", "contact_angle_variation_rad", "rail_y_m", "rail_z_m", "wheel_y_m", "track_x_m", "track_y_m", "track_z_m", "rolling_radius_m", "creepage_long", "creepage_lat", "spin_per_m", "normal_force_n", "fx_n", "fs_n", "mz_nm", "approach_m", "max_pressure_pa", "contact_area_m2", "adhesion_fraction", "frictional_power_w", "force_track_n", "grid_nx", "grid_ns", "grid", "fields", "friction_coefficient", "temperature", "rolling_speed_m_per_s", "fastsim_max_pressure_pa")
    METHOD_FIELD_NUMBER: _ClassVar[int]
    CONTACT_ANGLE_RAD_FIELD_NUMBER: _ClassVar[int]
    CONTACT_ANGLE_VARIATION_RAD_FIELD_NUMBER: _ClassVar[int]
    RAIL_Y_M_FIELD_NUMBER: _ClassVar[int]
    RAIL_Z_M_FIELD_NUMBER: _ClassVar[int]
    WHEEL_Y_M_FIELD_NUMBER: _ClassVar[int]
    TRACK_X_M_FIELD_NUMBER: _ClassVar[int]
    TRACK_Y_M_FIELD_NUMBER: _ClassVar[int]
    TRACK_Z_M_FIELD_NUMBER: _ClassVar[int]
    ROLLING_RADIUS_M_FIELD_NUMBER: _ClassVar[int]
    CREEPAGE_LONG_FIELD_NUMBER: _ClassVar[int]
    CREEPAGE_LAT_FIELD_NUMBER: _ClassVar[int]
    SPIN_PER_M_FIELD_NUMBER: _ClassVar[int]
    NORMAL_FORCE_N_FIELD_NUMBER: _ClassVar[int]
    FX_N_FIELD_NUMBER: _ClassVar[int]
    FS_N_FIELD_NUMBER: _ClassVar[int]
    MZ_NM_FIELD_NUMBER: _ClassVar[int]
    APPROACH_M_FIELD_NUMBER: _ClassVar[int]
    MAX_PRESSURE_PA_FIELD_NUMBER: _ClassVar[int]
    CONTACT_AREA_M2_FIELD_NUMBER: _ClassVar[int]
    ADHESION_FRACTION_FIELD_NUMBER: _ClassVar[int]
    FRICTIONAL_POWER_W_FIELD_NUMBER: _ClassVar[int]
    FORCE_TRACK_N_FIELD_NUMBER: _ClassVar[int]
    GRID_NX_FIELD_NUMBER: _ClassVar[int]
    GRID_NS_FIELD_NUMBER: _ClassVar[int]
    GRID_FIELD_NUMBER: _ClassVar[int]
    FIELDS_FIELD_NUMBER: _ClassVar[int]
    FRICTION_COEFFICIENT_FIELD_NUMBER: _ClassVar[int]
    TEMPERATURE_FIELD_NUMBER: _ClassVar[int]
    ROLLING_SPEED_M_PER_S_FIELD_NUMBER: _ClassVar[int]
    FASTSIM_MAX_PRESSURE_PA_FIELD_NUMBER: _ClassVar[int]
    method: WheelRailModel
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
    force_track_n: TrackForce
    grid_nx: int
    grid_ns: int
    grid: GridInfo
    fields: ElementFields
    friction_coefficient: float
    temperature: TemperatureResult
    rolling_speed_m_per_s: float
    fastsim_max_pressure_pa: float
    def __init__(self, method: _Optional[_Union[WheelRailModel, str]] = ..., contact_angle_rad: _Optional[float] = ..., contact_angle_variation_rad: _Optional[float] = ..., rail_y_m: _Optional[float] = ..., rail_z_m: _Optional[float] = ..., wheel_y_m: _Optional[float] = ..., track_x_m: _Optional[float] = ..., track_y_m: _Optional[float] = ..., track_z_m: _Optional[float] = ..., rolling_radius_m: _Optional[float] = ..., creepage_long: _Optional[float] = ..., creepage_lat: _Optional[float] = ..., spin_per_m: _Optional[float] = ..., normal_force_n: _Optional[float] = ..., fx_n: _Optional[float] = ..., fs_n: _Optional[float] = ..., mz_nm: _Optional[float] = ..., approach_m: _Optional[float] = ..., max_pressure_pa: _Optional[float] = ..., contact_area_m2: _Optional[float] = ..., adhesion_fraction: _Optional[float] = ..., frictional_power_w: _Optional[float] = ..., force_track_n: _Optional[_Union[TrackForce, _Mapping]] = ..., grid_nx: _Optional[int] = ..., grid_ns: _Optional[int] = ..., grid: _Optional[_Union[GridInfo, _Mapping]] = ..., fields: _Optional[_Union[ElementFields, _Mapping]] = ..., friction_coefficient: _Optional[float] = ..., temperature: _Optional[_Union[TemperatureResult, _Mapping]] = ..., rolling_speed_m_per_s: _Optional[float] = ..., fastsim_max_pressure_pa: _Optional[float] = ...) -> None: ...

class WheelRailWheel(_message.Message):
    __slots__ = ("side", "vertical_approach_m", "min_gap_m", "patches", "force_track_n", "load_iterations")
    SIDE_FIELD_NUMBER: _ClassVar[int]
    VERTICAL_APPROACH_M_FIELD_NUMBER: _ClassVar[int]
    MIN_GAP_M_FIELD_NUMBER: _ClassVar[int]
    PATCHES_FIELD_NUMBER: _ClassVar[int]
    FORCE_TRACK_N_FIELD_NUMBER: _ClassVar[int]
    LOAD_ITERATIONS_FIELD_NUMBER: _ClassVar[int]
    side: WheelSide
    vertical_approach_m: float
    min_gap_m: float
    patches: _containers.RepeatedCompositeFieldContainer[WheelRailPatch]
    force_track_n: TrackForce
    load_iterations: int
    def __init__(self, side: _Optional[_Union[WheelSide, str]] = ..., vertical_approach_m: _Optional[float] = ..., min_gap_m: _Optional[float] = ..., patches: _Optional[_Iterable[_Union[WheelRailPatch, _Mapping]]] = ..., force_track_n: _Optional[_Union[TrackForce, _Mapping]] = ..., load_iterations: _Optional[int] = ...) -> None: ...

class WheelRailTiming(_message.Message):
    __slots__ = ("search_s", "geometry_s", "solve_s")
    SEARCH_S_FIELD_NUMBER: _ClassVar[int]
    GEOMETRY_S_FIELD_NUMBER: _ClassVar[int]
    SOLVE_S_FIELD_NUMBER: _ClassVar[int]
    search_s: float
    geometry_s: float
    solve_s: float
    def __init__(self, search_s: _Optional[float] = ..., geometry_s: _Optional[float] = ..., solve_s: _Optional[float] = ...) -> None: ...

class WheelRailResult(_message.Message):
    __slots__ = ("pair_id", "model", "center_z_m", "roll_rad", "pitch_rad_per_s", "wheels", "timing", "pitch_control", "warnings")
    PAIR_ID_FIELD_NUMBER: _ClassVar[int]
    MODEL_FIELD_NUMBER: _ClassVar[int]
    CENTER_Z_M_FIELD_NUMBER: _ClassVar[int]
    ROLL_RAD_FIELD_NUMBER: _ClassVar[int]
    PITCH_RAD_PER_S_FIELD_NUMBER: _ClassVar[int]
    WHEELS_FIELD_NUMBER: _ClassVar[int]
    TIMING_FIELD_NUMBER: _ClassVar[int]
    PITCH_CONTROL_FIELD_NUMBER: _ClassVar[int]
    WARNINGS_FIELD_NUMBER: _ClassVar[int]
    pair_id: str
    model: WheelRailModel
    center_z_m: float
    roll_rad: float
    pitch_rad_per_s: float
    wheels: _containers.RepeatedCompositeFieldContainer[WheelRailWheel]
    timing: WheelRailTiming
    pitch_control: PitchControl
    warnings: _containers.RepeatedCompositeFieldContainer[WheelRailWarning]
    def __init__(self, pair_id: _Optional[str] = ..., model: _Optional[_Union[WheelRailModel, str]] = ..., center_z_m: _Optional[float] = ..., roll_rad: _Optional[float] = ..., pitch_rad_per_s: _Optional[float] = ..., wheels: _Optional[_Iterable[_Union[WheelRailWheel, _Mapping]]] = ..., timing: _Optional[_Union[WheelRailTiming, _Mapping]] = ..., pitch_control: _Optional[_Union[PitchControl, _Mapping]] = ..., warnings: _Optional[_Iterable[_Union[WheelRailWarning, _Mapping]]] = ...) -> None: ...

class WheelRailWarning(_message.Message):
    __slots__ = ("kind", "field", "side", "value", "limit", "message")
    KIND_FIELD_NUMBER: _ClassVar[int]
    FIELD_FIELD_NUMBER: _ClassVar[int]
    SIDE_FIELD_NUMBER: _ClassVar[int]
    VALUE_FIELD_NUMBER: _ClassVar[int]
    LIMIT_FIELD_NUMBER: _ClassVar[int]
    MESSAGE_FIELD_NUMBER: _ClassVar[int]
    kind: WheelRailWarningKind
    field: str
    side: WheelSide
    value: float
    limit: float
    message: str
    def __init__(self, kind: _Optional[_Union[WheelRailWarningKind, str]] = ..., field: _Optional[str] = ..., side: _Optional[_Union[WheelSide, str]] = ..., value: _Optional[float] = ..., limit: _Optional[float] = ..., message: _Optional[str] = ...) -> None: ...

class PitchControl(_message.Message):
    __slots__ = ("target_force_n", "force_n", "nominal_creepage", "iterations", "solves", "converged")
    TARGET_FORCE_N_FIELD_NUMBER: _ClassVar[int]
    FORCE_N_FIELD_NUMBER: _ClassVar[int]
    NOMINAL_CREEPAGE_FIELD_NUMBER: _ClassVar[int]
    ITERATIONS_FIELD_NUMBER: _ClassVar[int]
    SOLVES_FIELD_NUMBER: _ClassVar[int]
    CONVERGED_FIELD_NUMBER: _ClassVar[int]
    target_force_n: float
    force_n: float
    nominal_creepage: float
    iterations: int
    solves: int
    converged: bool
    def __init__(self, target_force_n: _Optional[float] = ..., force_n: _Optional[float] = ..., nominal_creepage: _Optional[float] = ..., iterations: _Optional[int] = ..., solves: _Optional[int] = ..., converged: _Optional[bool] = ...) -> None: ...

class SolveWheelRailResponse(_message.Message):
    __slots__ = ("result",)
    RESULT_FIELD_NUMBER: _ClassVar[int]
    result: WheelRailResult
    def __init__(self, result: _Optional[_Union[WheelRailResult, _Mapping]] = ...) -> None: ...

class SolveWheelRailBatchRequest(_message.Message):
    __slots__ = ("items",)
    ITEMS_FIELD_NUMBER: _ClassVar[int]
    items: _containers.RepeatedCompositeFieldContainer[SolveWheelRailRequest]
    def __init__(self, items: _Optional[_Iterable[_Union[SolveWheelRailRequest, _Mapping]]] = ...) -> None: ...

class WheelRailBatchItem(_message.Message):
    __slots__ = ("index", "result", "error")
    INDEX_FIELD_NUMBER: _ClassVar[int]
    RESULT_FIELD_NUMBER: _ClassVar[int]
    ERROR_FIELD_NUMBER: _ClassVar[int]
    index: int
    result: WheelRailResult
    error: ItemError
    def __init__(self, index: _Optional[int] = ..., result: _Optional[_Union[WheelRailResult, _Mapping]] = ..., error: _Optional[_Union[ItemError, _Mapping]] = ...) -> None: ...

class SolveWheelRailBatchResponse(_message.Message):
    __slots__ = ("items",)
    ITEMS_FIELD_NUMBER: _ClassVar[int]
    items: _containers.RepeatedCompositeFieldContainer[WheelRailBatchItem]
    def __init__(self, items: _Optional[_Iterable[_Union[WheelRailBatchItem, _Mapping]]] = ...) -> None: ...

class WheelRailSessionOpen(_message.Message):
    __slots__ = ("pair_id", "model", "sides", "friction", "element_size_m", "include_fields", "client_label", "polach", "conformal", "friction_table", "modified_fastsim", "temperature", "min_elements_across", "force_tolerance_of_wheel_load")
    PAIR_ID_FIELD_NUMBER: _ClassVar[int]
    MODEL_FIELD_NUMBER: _ClassVar[int]
    SIDES_FIELD_NUMBER: _ClassVar[int]
    FRICTION_FIELD_NUMBER: _ClassVar[int]
    ELEMENT_SIZE_M_FIELD_NUMBER: _ClassVar[int]
    INCLUDE_FIELDS_FIELD_NUMBER: _ClassVar[int]
    CLIENT_LABEL_FIELD_NUMBER: _ClassVar[int]
    POLACH_FIELD_NUMBER: _ClassVar[int]
    CONFORMAL_FIELD_NUMBER: _ClassVar[int]
    FRICTION_TABLE_FIELD_NUMBER: _ClassVar[int]
    MODIFIED_FASTSIM_FIELD_NUMBER: _ClassVar[int]
    TEMPERATURE_FIELD_NUMBER: _ClassVar[int]
    MIN_ELEMENTS_ACROSS_FIELD_NUMBER: _ClassVar[int]
    FORCE_TOLERANCE_OF_WHEEL_LOAD_FIELD_NUMBER: _ClassVar[int]
    pair_id: str
    model: WheelRailModel
    sides: WheelSides
    friction: FrictionSection
    element_size_m: float
    include_fields: bool
    client_label: str
    polach: PolachParameters
    conformal: ConformalSection
    friction_table: FrictionTable
    modified_fastsim: ModifiedFastsimParameters
    temperature: TemperatureSection
    min_elements_across: int
    force_tolerance_of_wheel_load: float
    def __init__(self, pair_id: _Optional[str] = ..., model: _Optional[_Union[WheelRailModel, str]] = ..., sides: _Optional[_Union[WheelSides, str]] = ..., friction: _Optional[_Union[FrictionSection, _Mapping]] = ..., element_size_m: _Optional[float] = ..., include_fields: _Optional[bool] = ..., client_label: _Optional[str] = ..., polach: _Optional[_Union[PolachParameters, _Mapping]] = ..., conformal: _Optional[_Union[ConformalSection, _Mapping]] = ..., friction_table: _Optional[_Union[FrictionTable, _Mapping]] = ..., modified_fastsim: _Optional[_Union[ModifiedFastsimParameters, _Mapping]] = ..., temperature: _Optional[_Union[TemperatureSection, _Mapping]] = ..., min_elements_across: _Optional[int] = ..., force_tolerance_of_wheel_load: _Optional[float] = ...) -> None: ...

class WheelRailSessionStep(_message.Message):
    __slots__ = ("step_index", "time_s", "position", "velocity", "load", "mark")
    STEP_INDEX_FIELD_NUMBER: _ClassVar[int]
    TIME_S_FIELD_NUMBER: _ClassVar[int]
    POSITION_FIELD_NUMBER: _ClassVar[int]
    VELOCITY_FIELD_NUMBER: _ClassVar[int]
    LOAD_FIELD_NUMBER: _ClassVar[int]
    MARK_FIELD_NUMBER: _ClassVar[int]
    step_index: int
    time_s: float
    position: WheelsetPosition
    velocity: WheelsetVelocity
    load: WheelLoad
    mark: bool
    def __init__(self, step_index: _Optional[int] = ..., time_s: _Optional[float] = ..., position: _Optional[_Union[WheelsetPosition, _Mapping]] = ..., velocity: _Optional[_Union[WheelsetVelocity, _Mapping]] = ..., load: _Optional[_Union[WheelLoad, _Mapping]] = ..., mark: _Optional[bool] = ...) -> None: ...

class WheelRailSessionRequest(_message.Message):
    __slots__ = ("open", "step", "rollback")
    OPEN_FIELD_NUMBER: _ClassVar[int]
    STEP_FIELD_NUMBER: _ClassVar[int]
    ROLLBACK_FIELD_NUMBER: _ClassVar[int]
    open: WheelRailSessionOpen
    step: WheelRailSessionStep
    rollback: SessionRollback
    def __init__(self, open: _Optional[_Union[WheelRailSessionOpen, _Mapping]] = ..., step: _Optional[_Union[WheelRailSessionStep, _Mapping]] = ..., rollback: _Optional[_Union[SessionRollback, _Mapping]] = ...) -> None: ...

class WheelRailSessionOpened(_message.Message):
    __slots__ = ("session_id", "pair_id", "model")
    SESSION_ID_FIELD_NUMBER: _ClassVar[int]
    PAIR_ID_FIELD_NUMBER: _ClassVar[int]
    MODEL_FIELD_NUMBER: _ClassVar[int]
    session_id: str
    pair_id: str
    model: WheelRailModel
    def __init__(self, session_id: _Optional[str] = ..., pair_id: _Optional[str] = ..., model: _Optional[_Union[WheelRailModel, str]] = ...) -> None: ...

class WheelRailSessionStepResult(_message.Message):
    __slots__ = ("step_index", "time_s", "result", "marked")
    STEP_INDEX_FIELD_NUMBER: _ClassVar[int]
    TIME_S_FIELD_NUMBER: _ClassVar[int]
    RESULT_FIELD_NUMBER: _ClassVar[int]
    MARKED_FIELD_NUMBER: _ClassVar[int]
    step_index: int
    time_s: float
    result: WheelRailResult
    marked: bool
    def __init__(self, step_index: _Optional[int] = ..., time_s: _Optional[float] = ..., result: _Optional[_Union[WheelRailResult, _Mapping]] = ..., marked: _Optional[bool] = ...) -> None: ...

class WheelRailSessionResponse(_message.Message):
    __slots__ = ("opened", "step", "rolled_back", "error")
    OPENED_FIELD_NUMBER: _ClassVar[int]
    STEP_FIELD_NUMBER: _ClassVar[int]
    ROLLED_BACK_FIELD_NUMBER: _ClassVar[int]
    ERROR_FIELD_NUMBER: _ClassVar[int]
    opened: WheelRailSessionOpened
    step: WheelRailSessionStepResult
    rolled_back: SessionRolledBack
    error: ItemError
    def __init__(self, opened: _Optional[_Union[WheelRailSessionOpened, _Mapping]] = ..., step: _Optional[_Union[WheelRailSessionStepResult, _Mapping]] = ..., rolled_back: _Optional[_Union[SessionRolledBack, _Mapping]] = ..., error: _Optional[_Union[ItemError, _Mapping]] = ...) -> None: ...

class ContactLibraryRequest(_message.Message):
    __slots__ = ("open", "calculate")
    OPEN_FIELD_NUMBER: _ClassVar[int]
    CALCULATE_FIELD_NUMBER: _ClassVar[int]
    open: ContactLibraryOpen
    calculate: ContactLibraryCalculate
    def __init__(self, open: _Optional[_Union[ContactLibraryOpen, _Mapping]] = ..., calculate: _Optional[_Union[ContactLibraryCalculate, _Mapping]] = ...) -> None: ...

class ContactLibraryOpen(_message.Message):
    __slots__ = ("format_version", "module", "ire", "client_label")
    FORMAT_VERSION_FIELD_NUMBER: _ClassVar[int]
    MODULE_FIELD_NUMBER: _ClassVar[int]
    IRE_FIELD_NUMBER: _ClassVar[int]
    CLIENT_LABEL_FIELD_NUMBER: _ClassVar[int]
    format_version: int
    module: int
    ire: int
    client_label: str
    def __init__(self, format_version: _Optional[int] = ..., module: _Optional[int] = ..., ire: _Optional[int] = ..., client_label: _Optional[str] = ...) -> None: ...

class ContactLibraryCalculate(_message.Message):
    __slots__ = ("request",)
    REQUEST_FIELD_NUMBER: _ClassVar[int]
    request: bytes
    def __init__(self, request: _Optional[bytes] = ...) -> None: ...

class ContactLibraryResponse(_message.Message):
    __slots__ = ("opened", "reply", "error")
    OPENED_FIELD_NUMBER: _ClassVar[int]
    REPLY_FIELD_NUMBER: _ClassVar[int]
    ERROR_FIELD_NUMBER: _ClassVar[int]
    opened: ContactLibraryOpened
    reply: bytes
    error: ItemError
    def __init__(self, opened: _Optional[_Union[ContactLibraryOpened, _Mapping]] = ..., reply: _Optional[bytes] = ..., error: _Optional[_Union[ItemError, _Mapping]] = ...) -> None: ...

class ContactLibraryOpened(_message.Message):
    __slots__ = ("session_id", "format_version")
    SESSION_ID_FIELD_NUMBER: _ClassVar[int]
    FORMAT_VERSION_FIELD_NUMBER: _ClassVar[int]
    session_id: str
    format_version: int
    def __init__(self, session_id: _Optional[str] = ..., format_version: _Optional[int] = ...) -> None: ...
