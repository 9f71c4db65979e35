"""What a cushion model reads of the physics: a protocol, so that the models need not import
`params.Physics` (which imports the models to check a scene's choice and take its defaults)."""

from __future__ import annotations

from typing import Protocol


class CushionPhysics(Protocol):
    """The numbers of `params.Physics` a cushion model may read."""

    @property
    def e_cushion(self) -> float: ...
    @property
    def mu_cushion(self) -> float: ...
    @property
    def mu_slide(self) -> float: ...
    @property
    def cushion_height(self) -> float: ...
    @property
    def v_inelastic(self) -> float: ...
