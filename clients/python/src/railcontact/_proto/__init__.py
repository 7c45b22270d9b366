"""Generated gRPC stubs of railcontact.v1 (do not edit).

Regenerate with ``python -m railcontact._generate``.
"""
