"""Matches: racks, turns, ball in hand, options, frames and the record of every shot.

No terminal code. The game loop of a UI::

    m = Match("8ball", frames=3, seed=7)        # racked; player 0 breaks from the kitchen
    if m.ball_in_hand:                          # None, "anywhere" or "kitchen"
        m.placement_error(x, y)                 # why not, in words (None: fine)
        m.place_cue(x, y)                       # ValueError(the reason) when illegal
    run = m.begin(Shot(speed=6.0, angle=0.0, called=("8", "foot_left") if m.needs_call()
                       else None))
    while not run.done:
        run.step(1 / 60)                        # per frame; draw run.engine.pos[0] (run.ids)
    outcome = run.finish()                      # judged, applied, recorded in m.history
    if m.option:                                # "rerack_or_accept" or "shoot_or_pass"
        m.choose("accept")                      # the incoming player answers
    if m.frame_over and m.winner is None:
        m.new_frame()
    json.dump(m.to_json(), f)                   # a replay file: `termpool replay FILE`

`Match(mode="8ball" | "9ball" | "practice", *, table="9ft", frames=1, players=(..), seed=0,
physics=None, three_foul=False, theme="standard", dt=1/60, eight_break="respot")`; `players`
are names (people) or players (`players.Player`: a name and a level, the computer's or None
for a person; a computer player, `termpool.ai.Computer`, is handed in by whoever sets the
match up). The match keeps their names (`players`), levels (`levels`, kept in the record
only: the match plays whatever shots it is given) and the players themselves (`seats`):

- `ids` (cue first, then "1".."15", or "1".."9"), `radius`, `mass`, `pos` (N, 2) and `on_table`
  (N,) describe the table between shots (a pocketed ball's `pos` is meaningless).
- `state` is the rules `State` for the next shot; `shooter`, `scores` (frames won),
  `frame` (0-based), `frame_winner` and `frame_over`, `winner` (the match), `ball_in_hand`,
  `option`, `last_outcome`, `history` (shot records, see `termpool.game.record`), `choices`
  (the options answered, with the shot they followed).
- `begin(shot) -> ShotRun`; `ShotRun.step(dt)`, `.done`, `.finish() -> Outcome`, `.engine`
  (holds only the balls on the table: `.ids`, rows `.rows` of the match's arrays).
- `needs_call()`, `warning()` (the player owed the 9-ball three-foul warning, or None),
  `placement_error(x, y)`, `place_cue(x, y)`, `waiting_spot()`, `choose(option)`,
  `new_frame()`, practice's `rerack()` and `take_back()`, `to_json()`,
  `Match.from_json(data)`, `scene_dict()` (the table now, as a scene).

Modules: `match` (turns, options, frames), `balls` (the balls between shots), `layout` (racks,
re-spots and the one placement rule), `turn` (`Shot`, `ShotRun`), `record` (shot records and
replays), `saved` (the match as JSON and back), `settings`, `players`, `history`.

Choices made:

- **Frames.** `frames` is the number of frames to win (a race). Breaks alternate: player 0
  breaks the first frame, player 1 the second, and so on. Every break is taken with ball in
  hand behind the head string (the cue ball starts on the head spot). Practice has one player
  (0), never ends, and starts with ball in hand anywhere.
- **Racks** (`layout.rack_balls`): 8-ball and practice, WPA: the 8 in the centre of the third
  row, a solid and a stripe in the two back corners, the rest random; 9-ball: the 1 on the foot
  spot, the 9 in the centre, the rest random. Random draws come from the match's seeded numpy
  Generator, so the same seed gives the same racks.
- **Re-spots** go on the foot spot, or if it is taken the nearest free point behind it on the
  long string (towards the foot rail), else in front of it. After a scratch the cue ball waits
  on the head spot (or the nearest free point behind it) for the incoming player to place.
- **Ball in hand** (`placement_error`): the cue ball must lie within the cushion noses, clear
  of every pocket mouth (the line between its jaw tips), not overlapping a ball (touching is
  fine) and, in the kitchen, with its centre at x <= L/4. WPA's rule that a ball in hand from
  the kitchen must first cross the head string is not enforced.
- **Options.** After an illegal 8-ball break the incoming player chooses "accept" (shoot the
  table as it lies) or "rerack" (a fresh rack that they break). After a 9-ball push-out the
  incoming player chooses "shoot" or "pass" (the player who pushed shoots again).
- **8 on the break**: as the referee decides: re-spotted, or with `eight_break="rerack"` a
  fresh rack broken again by the same player. **Three fouls** (9-ball): on with
  `three_foul=True`; the third consecutive foul loses the frame.
- **Calls.** `needs_call()` is True in 8-ball once the shooter's group is cleared: the shot
  must then call ("8", pocket).
- **Take back** (practice) restores the layout, state and record from before the last shot;
  the undo history lives in memory only and is cleared by a re-rack or a new frame.
- **Determinism.** Every shot is driven in fixed engine steps of `dt` (`ShotRun.step` only
  ever advances whole steps), so the live shot and its replay take identical steps.
"""

from termpool.game.match import Match
from termpool.game.record import ReplayError, read_replay, replay
from termpool.game.turn import Shot, ShotRun
from termpool.physics.results import DT

__all__ = ["DT", "Match", "ReplayError", "Shot", "ShotRun", "read_replay", "replay"]
