"""Python client of the railcontact gRPC service (package ``railcontact.v1``).

Quickstart::

    import railcontact

    with railcontact.Client("127.0.0.1:50051") as client:
        r = client.solve_patch(railcontact.load_case("examples/cases/hertz_ellipse_rolling.toml"),
                               include_fields=True)
        print(r.totals.fx_n, r.fields.pressure_pa.shape)  # (ny, nx)
        w = client.solve_wheelrail_case("examples/cases/wheelset_a22.toml")
        print(w)                                 # an indented summary
        print(w.wheel("right").force_track_n)    # [x, y, z] on the rail [N]

Results are frozen dataclasses (:mod:`railcontact.results`) whose fields
mirror the proto (SI units in the names; forces act on the rail). Errors
raise :class:`RailcontactError`. The generated stubs are ``client.stub`` and
the message module ``railcontact.pb``.
"""

from ._proto import railcontact_pb2 as pb
from ._proto import railcontact_pb2_grpc as pb_grpc
from .cases import WheelRailCase, load_wheelrail_case
from .client import (
    BUILTIN_PAIR,
    PATCH_MODELS,
    WHEELRAIL_MODELS,
    Client,
    PatchSession,
    WheelRailSession,
    load_case,
    patch_case,
    wheelrail_request,
)
from .errors import RailcontactError
from .results import (
    ADHESION,
    EXTERIOR,
    SLIP,
    CreepCurvePoint,
    Creepages,
    ElementFields,
    ForceControl,
    Grid,
    PatchResult,
    PatchTotals,
    PitchControl,
    ProfilePairInfo,
    RegistrationProgress,
    SessionStepResult,
    StepResult,
    TemperaturePeak,
    TemperatureResult,
    TrackForce,
    WheelRailPatch,
    WheelRailResult,
    WheelRailStepResult,
    WheelRailWarning,
    WheelRailWheel,
    summary,
)

__all__ = [
    "ADHESION",
    "BUILTIN_PAIR",
    "EXTERIOR",
    "PATCH_MODELS",
    "SLIP",
    "WHEELRAIL_MODELS",
    "Client",
    "CreepCurvePoint",
    "Creepages",
    "ElementFields",
    "ForceControl",
    "Grid",
    "PatchResult",
    "PatchSession",
    "PatchTotals",
    "PitchControl",
    "ProfilePairInfo",
    "RailcontactError",
    "RegistrationProgress",
    "SessionStepResult",
    "StepResult",
    "TemperaturePeak",
    "TemperatureResult",
    "TrackForce",
    "WheelRailPatch",
    "WheelRailResult",
    "WheelRailSession",
    "WheelRailStepResult",
    "WheelRailCase",
    "WheelRailWarning",
    "WheelRailWheel",
    "load_case",
    "load_wheelrail_case",
    "patch_case",
    "pb",
    "pb_grpc",
    "summary",
    "wheelrail_request",
]
__version__ = "0.1.0"
