"""The aim aid in the app's state: the engine's prediction (ui.predict) of the shot being
aimed, and the pocket the 8 is called in.

The prediction is computed again only when the aim, power, spin or table change (`refresh`,
which the driver calls before it draws, and the update before it reads the aid): the first
share of it at once, then a share a frame (`advance`, on each tick), so that a long one fills
in over a few frames and never stalls one.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from termpool.game import Shot
from termpool.physics.table import POCKET_NAMES
from termpool.rules.common import Outcome
from termpool.rules.events import ShotSummary
from termpool.rules.referee import judge
from termpool.ui.predict import Prediction, Predictor
from termpool.ui.shots import power_to_speed
from termpool.ui.state import AidJob, Aiming, Phase, State, Waiting, cue_index, trace

AID_STEP = 8  # event times of the aid's prediction run per frame (about 3 ms on the project's
# machine, benchmarks/aid.py): a long prediction fills in over a few frames


def level(s: State) -> str:
    """What the aid shows now: the player's choice; on the computer's turn at least the
    ghost ball, so that its aim can be followed."""
    if s.phase is Phase.CPU and s.opts.aid == "off":
        return "ghost"
    return s.opts.aid


def aim_power(s: State) -> float:
    """The power (0..1) the player aiming would shoot with now: set, charging, or their
    last."""
    ch = s.controls.charge
    return ch.preset_level if ch.preset_level is not None else (
        round(ch.level(s.now), 2) if ch.active else s.last_power)


def shot(s: State) -> Shot | None:
    """The shot the aid predicts: the shooter's aim and spin at `aim_power`, the computer's
    plan as its stick turns, or an online opponent's stick at the power their aid has;
    None when no shot is being aimed."""
    st = s.stroke
    if s.phase is Phase.AIM:
        return Shot(power_to_speed(aim_power(s)), st.angle, st.side, st.top)
    if isinstance(s.part, Aiming):
        return Shot(s.part.plan.speed, st.angle, st.side, st.top)
    if isinstance(s.part, Waiting) and s.part.stick and s.part.power is not None:
        return Shot(power_to_speed(s.part.power), st.angle, st.side, st.top)
    return None


def _aimed(s: State) -> tuple[tuple, Shot] | None:
    """(the table as it lies, the shot) when the aid has a shot to predict, else None."""
    m = s.match
    sh = shot(s) if m is not None and level(s) != "off" else None
    if sh is None or not m.on_table[cue_index(s)]:
        return None
    return (len(m.history), m.frame, m.pos.tobytes(), m.on_table.tobytes()), sh


def refresh(s: State) -> State:
    """The state with the aid's prediction started for the shot aimed now (and its first
    share run), unless it is already."""
    aimed = _aimed(s)
    if aimed is None:
        return s
    where, sh = aimed
    aid = s.aid
    if aid.predictor is None or aid.table != where:
        aid = AidJob(where, Predictor(s.match))
    if aid.job is None or aid.key != (where, sh):
        job = aid.predictor.start(sh)
        if job is None:  # a miscue: nothing to predict (the last job stays as it was)
            return s if aid is s.aid else replace(s, aid=aid)
        job.run(AID_STEP)
        aid = replace(aid, key=(where, sh), job=job)
    return s if aid is s.aid else replace(s, aid=aid)


def advance(s: State) -> State:
    """A frame's share more of the prediction, if it is not done."""
    job = s.aid.job
    if job is None or job.done:
        return s
    job.run(AID_STEP)
    return replace(s, aid=replace(s.aid))  # a new value: the screen shows more of it


def running(s: State) -> bool:
    return s.aid.job is not None and not s.aid.job.done


def prediction(s: State) -> Prediction | None:
    """The aid's prediction of the shot aimed now, as far as it has run (see `refresh`);
    None with the aid off or nothing aimed."""
    aimed = _aimed(s)
    if aimed is None or s.aid.job is None or s.aid.key != aimed:
        return None
    return s.aid.job.result()


def aimed_pocket(s: State) -> int:
    """Index of the pocket the aid sees the first ball go into; else the one it heads for
    (0 with no ball hit)."""
    m = s.match
    pred = prediction(s)
    names = list(m.table.hole_names)
    if pred is not None and pred.object is not None and len(pred.object.points) > 1:
        if pred.object.end == "pocket" and pred.object.pocket in names:
            return names.index(pred.object.pocket)
        p, q = pred.object.points[0], pred.object.points[1]
    else:
        aim = trace(s)
        if aim is None or aim.ball is None or aim.object_dir is None:
            return 0
        p = m.pos[aim.ball]
        q = p + np.asarray(aim.object_dir)
    d = m.table.hole_c.reshape(-1, 2) - p
    u = (q - p) / max(float(np.hypot(*(q - p))), 1e-12)
    score = (d @ u) / np.maximum(np.hypot(d[:, 0], d[:, 1]), 1e-9)
    return int(np.argmax(score))


def called(s: State) -> tuple[str, str]:
    """The call for this shot (the 8, which is the only ball ever called): the pocket the
    aim sends it to, unless the player picked one with C (which stays called for the shot,
    however the aim moves). Reads the aid as it stands (an update refreshes it first)."""
    k = s.stroke.called_k if s.stroke.call_picked else aimed_pocket(s)
    return "8", POCKET_NAMES[k % len(POCKET_NAMES)]


def foreseen(s: State) -> Outcome | None:
    """The referee's outcome of the player's shot as the aid sees it (its first ball, that
    ball into a pocket, the cue ball into one after the hit; a cushion counted as reached,
    which the aid does not follow that far; or no ball hit at all, where the cue ball comes
    to rest or drops without meeting one), or None with nothing sure to judge (the aid off
    or still running, a cue ball that may yet meet a ball past the cushions the aid follows;
    the break, whose rack it does not follow)."""
    m = s.match
    pred = prediction(s) if s.phase is Phase.AIM and not m.state.is_break else None
    if pred is None:
        return None
    if pred.ball is None:
        if pred.cue.end not in ("rest", "pocket"):
            return None
        pocketed = {"cue": pred.cue.pocket} if pred.cue.end == "pocket" else {}
        summary = ShotSummary(first_contact=None, pocketed=pocketed, scratch=bool(pocketed))
    else:
        first = m.ids[pred.ball]
        pocketed = {}
        if pred.object is not None and pred.object.end == "pocket":
            pocketed[first] = pred.object.pocket
        if pred.after is not None and pred.after.end == "pocket":
            pocketed["cue"] = pred.after.pocket
        on = tuple(b for b, here in zip(m.ids, m.on_table, strict=True) if here)
        summary = ShotSummary(first_contact=first, cushions_after_contact=1, rail_balls=on,
                              pocketed=pocketed, scratch="cue" in pocketed)
    state = replace(m.state, called=called(s) if m.needs_call() else None,
                    push_out="declared" if s.stroke.push_out else m.state.push_out)
    return judge(state, summary)[0]
