"""Python client of the railcontact gRPC service (package ``railcontact.v1``).

Quickstart::

    import railcontact

    with railcontact.Client("127.0.0.1:50051") as client:
        r = client.solve_patch(railcontact.load_case("examples/cases/hertz_ellipse_rolling.toml"),
                               include_fields=True)
        print(r.totals.fx_n, r.fields.pressure_pa.shape)  # (ny, nx)

Results are frozen dataclasses (:mod:`railcontact.results`) whose fields
mirror the proto (SI units in the names; forces act on the rail). Errors
raise :class:`RailcontactError`. The generated stubs are ``client.stub`` and
the message module ``railcontact.pb``.
"""

from ._proto import railcontact_pb2 as pb
from ._proto import railcontact_pb2_grpc as pb_grpc
from .client import (
    BUILTIN_PAIR,
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
)

__all__ = [
    "ADHESION",
    "BUILTIN_PAIR",
    "EXTERIOR",
    "SLIP",
    "Client",
    "CreepCurvePoint",
    "Creepages",
    "ElementFields",
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
    "WheelRailWarning",
    "WheelRailWheel",
    "load_case",
    "patch_case",
    "pb",
    "pb_grpc",
    "wheelrail_request",
]
__version__ = "0.1.0"
