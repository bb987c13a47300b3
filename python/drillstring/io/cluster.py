"""Dask cluster helpers shared by sweeps and drilling maps."""

from __future__ import annotations

from typing import Any

from ..errors import ValidationError


def check_client(client: Any) -> None:
    """Refuses a ``client`` that is neither None, a scheduler address nor a Dask client
    (anything with ``submit``), naming the field."""
    if client is None or (isinstance(client, str) and client.strip()) or callable(getattr(client, "submit", None)):
        return
    raise ValidationError("client", client, "a dask.distributed.Client or a scheduler address (a non-empty str)")


def require_distributed() -> Any:
    try:
        import distributed
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise ImportError(
            "running a sweep on a Dask cluster needs dask.distributed: "
            "pip install '.[dask]' in the drillstring checkout"
        ) from exc
    return distributed
