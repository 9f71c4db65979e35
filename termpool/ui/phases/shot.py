"""A shot rolling: its frames shown by the clock (fast-forwarded with F), then judged."""

from __future__ import annotations

from dataclasses import replace

from termpool.ui.phases.turn import finish_shot
from termpool.ui.state import State


def key(s: State, key, action: str | None, t: float) -> State:
    if action == "shoot":
        s.controls.charge.observe(key, t)  # a key still held after the strike: its repeats
    elif action == "fast_forward" and key.kind == "press":
        return replace(s, part=replace(s.part, fast=not s.part.fast))
    elif action in WAIT_FOR_REST and key.kind == "press" and WAIT not in s.message:
        return replace(s, message=(*s.message, WAIT))  # the verdict takes its place
    return s


WAIT_FOR_REST = ("place", "push_out", "undo", "rerack", "call_pocket")  # keys of the next shot
WAIT = ("wait for the balls to stop", "dim")


def tick(s: State, t: float) -> State:
    run = s.part
    started = run.clock.started()
    clock = run.clock.at(t, run.fast)
    if not started:
        return replace(s, part=replace(run, clock=clock))
    n, clock = clock.frames()
    shown = min(run.shown + n, len(run.frames)) if n else run.shown
    s = replace(s, part=replace(run, clock=clock, shown=shown))
    if shown >= len(run.frames):
        return finish_shot(s)
    return s


def pause(s: State) -> State:
    """A box is open: the shot waits (its clock starts again at the next tick after)."""
    return replace(s, part=replace(s.part, clock=s.part.clock.stopped()))
