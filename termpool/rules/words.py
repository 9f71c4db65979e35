"""Words for people and for the record: the referee's verdicts (codes, `rules.codes`), the
match's news and the rules page, written once here.

A `Voice` says how players, pockets and groups are named. `RECORD` is the record's voice:
"player 0" and "player 1", the rules' names of pockets ("foot_left") and groups ("solids");
records and `termpool sim` keep verdicts in it. `voice(players, theme)` is a person's: the
players' names (a player called "You" is spoken to: "you continue", "your turn"), pockets as
people say them ("the top-right corner pocket", "the bottom side pocket") and the theme's
groups ("reds" for solids in the classic theme).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace

from termpool.rules.codes import STRIPES, Aim, Choice, Option, PlanNote, Said, Why, group_of

YOU = "You"  # the name of a player spoken to (the person against the computer)
# The ball themes and each one's words for the rules' groups. The balls' colours are the UI's.
GROUP_WORDS = {
    "standard": {"solids": "solids", "stripes": "stripes"},
    "classic": {"solids": "reds", "stripes": "yellows"},
}
THEMES = tuple(GROUP_WORDS)
# Themes whose group balls carry no number a player can see: a person hears their colour.
COLOUR_NAMES = {"classic": {"solids": "red", "stripes": "yellow"}}


def shown_theme(theme: str, ids: Sequence[str]) -> str:
    """The theme a game's balls are drawn and named in. The classic theme's reds and yellows
    are 8-ball's two groups; a game without balls 10 to 15 (9-ball's 1 to 9, whose rules ask
    for the lowest ball) keeps the standard theme, whose colours tell its balls apart."""
    if any(b in STRIPES and b != "9" for b in ids):  # (9-ball's own 9 is a stripe)
        return theme
    return "standard"


def group_label(group: str, theme: str = "standard") -> str:
    """The theme's word for a rules group: "solids" is "reds" in the classic theme."""
    return GROUP_WORDS[theme][group]


@dataclass(frozen=True)
class Voice:
    """How words name the players, the pockets and the groups."""

    players: tuple[str, str] = ("player 0", "player 1")
    theme: str = "standard"
    plain: bool = True  # pockets as the table names them ("foot_left"), else in words
    ahead: bool = False  # of a shot not yet played (the aim aid's): "goes", not "went"

    def did(self, past: str, now: str) -> str:
        """A verb of what a shot did: `past` ("went"), or ahead of the shot `now` ("goes")."""
        return now if self.ahead else past

    def pocket(self, name: str) -> str:
        """A pocket's name before the word "pocket": "foot_left" in the record's voice,
        "top-right corner" in a person's ("side_right": "bottom side"; `spoken_pocket`)."""
        return name if self.plain else spoken_pocket(name)

    def group(self, group: str) -> str:
        return group_label(group, self.theme)

    def colour(self, b: str | None) -> str | None:
        """The colour a person names ball b by (the classic theme's "red" for the 3), else
        None: it is named by its number."""
        names = None if self.plain else COLOUR_NAMES.get(self.theme)
        group = group_of(b) if names is not None and b is not None else None
        return None if group is None else names[group]

    def ball(self, b: str | None) -> str:
        """"the cue ball", "the 3", or in a theme of colours "a red"."""
        if b == "cue":
            return "the cue ball"
        colour = self.colour(b)
        return f"a {colour}" if colour else f"the {b}"

    def balls(self, balls: Sequence[str]) -> str:
        """"the 2 and the 5"; in a theme of colours, balls of a colour counted where the
        first of them comes ("two reds and the cue ball")."""
        counts: dict[str, int] = {}
        names: list[str] = []
        for b in balls:
            colour = self.colour(b)
            if colour is None:
                names.append(self.ball(b))
            elif colour not in counts:
                counts[colour] = 1
                names.append(colour)
            else:
                counts[colour] += 1
        names = [f"a {x}" if counts.get(x) == 1 else f"{count_word(counts[x])} {x}s"
                 if x in counts else x for x in names]
        return names[0] if len(names) == 1 else ", ".join(names[:-1]) + " and " + names[-1]

    def spoken_to(self, p: int) -> bool:
        return self.players[p] == YOU

    def name(self, p: int) -> str:
        return "you" if self.spoken_to(p) else self.players[p]

    def verb(self, p: int, third: str, second: str) -> str:
        """The verb's form for player p: "continues", or "continue" for a player spoken to."""
        return second if self.spoken_to(p) else third

    def does(self, p: int, third: str, second: str) -> str:
        """The player and a verb: "Bob continues", "you continue"."""
        return f"{self.name(p)} {self.verb(p, third, second)}"

    def whose(self, p: int) -> str:
        return "your" if self.spoken_to(p) else f"{self.players[p]}'s"

    def whose_first(self, p: int) -> str:
        """`whose` opening a line: "Your", "bob's" (a name keeps its case)."""
        return "Your" if self.spoken_to(p) else self.whose(p)


RECORD = Voice()


# Where each pocket is on screen, which draws the table from above with the head on the left:
# the pockets on the left as seen from the head are along the top.
_ACROSS = {"left": "top", "right": "bottom"}
_ALONG = {"head": "left", "foot": "right"}


def spoken_pocket(name: str) -> str:
    """A table's pocket name ("end_side", as `physics.table.POCKET_NAMES`) as people say it
    before "pocket": where the screen shows it ("top side", "bottom-right corner",
    "top-left corner"; the record's "foot_right" is the right foot corner as seen from the
    head). A name of another form is said with its underscores as spaces."""
    end, _, side = name.partition("_")
    if side not in _ACROSS or end not in (*_ALONG, "side"):
        return name.replace("_", " ")
    return f"{_ACROSS[side]} side" if end == "side" else f"{_ACROSS[side]}-{_ALONG[end]} corner"


def calling(v: Voice, ball: str, pocket: str) -> str:
    """The call of a shot: "calling the 8 in the bottom side pocket"."""
    return f"calling the {ball} in the {v.pocket(pocket)} pocket"


def signed(x: float) -> str:
    """A signed reading to one decimal ("+0.3", "-1.0"); one that rounds to zero is "0.0",
    never "-0.0" or "+0.0"."""
    text = f"{x:+.1f}"
    return "0.0" if float(text) == 0.0 else text


def tip_words(side: float, top: float) -> str:
    """The cue tip's offset, each figure after its name: "tip: side +0.3, top -0.2"."""
    return f"tip: side {signed(side)}, top {signed(top)}"


def voice(players: Sequence[str], theme: str = "standard") -> Voice:
    """A person's voice: the players' names, pockets in words, the theme's groups."""
    return Voice((players[0], players[1]), theme, plain=False)


def _start(text: str) -> str:
    """A sentence that begins with a player spoken to begins "You"."""
    return "Y" + text[1:] if text.startswith("you ") else text


# ------------------------------------------------------------------------------- shared facts
# Said by the referees in their verdicts and stated by the rules page (`rules_page`, shown by
# H in the game and by `termpool rules`): written once, so the two never disagree.
BREAK_RAIL_BALLS = 4  # a break that pockets nothing must drive this many object balls to a
# cushion (8-ball and 9-ball)
FOUL_LIMIT = 3  # 9-ball's three-foul rule: this many fouls in a row lose the frame
KITCHEN = "behind the head string"  # where ball in hand goes on a break (and after a scratch
# on the 8-ball break)


def _no_hit(v: Voice) -> str:
    return f"the cue ball {v.did('hit', 'hits')} no ball"


def _no_rail(v: Voice) -> str:
    return (f"no ball {v.did('reached', 'reaches')} a cushion after contact and nothing "
            f"{v.did('was', 'is')} pocketed")


NO_HIT = _no_hit(RECORD)
NO_RAIL = _no_rail(RECORD)
PUSH_OUT_CHOICE = "to shoot or to pass the shot back"  # the answer to a 9-ball push-out

NUMBER_WORDS = {1: "one", 2: "two", 3: "three", 4: "four", 5: "five", 6: "six"}
ORDINALS = {1: "first", 2: "second", 3: "third", 4: "fourth", 5: "fifth", 6: "sixth"}


def count_word(n: int) -> str:
    """A small count in words ("four"); larger ones in digits."""
    return NUMBER_WORDS.get(n, str(n))


def ordinal(n: int) -> str:
    """"third" for 3 ("7th" beyond the words)."""
    return ORDINALS.get(n, f"{n}th")


MODE_NAMES = {"8ball": "8-ball", "9ball": "9-ball", "practice": "practice"}


# ----------------------------------------------------------------------------------- verdicts


def _potted(v: Voice, s: Said) -> str:
    """Balls pocketed: one in a person's voice with its pocket ("the 2 in the top-right
    corner pocket"), else "the 2 and the 5 pocketed" (the record's words stay as they were)."""
    if not v.plain and len(s.balls) == 1 and s.pockets and s.pockets[0] is not None:
        return f"{v.ball(s.balls[0])} in the {v.pocket(s.pockets[0])} pocket"
    return f"{v.balls(s.balls)} pocketed"


def _cue_down(v: Voice, pocket: str | None) -> str:
    if pocket is None:
        return f"the cue ball {v.did('was', 'is')} pocketed"
    return f"the cue ball {v.did('went', 'goes')} into the {v.pocket(pocket)} pocket"


def _scratch(v: Voice, s: Said) -> str:
    # (ahead of the shot the aid's "a foul:" has said what a scratch is)
    return _cue_down(v, s.pocket) if v.ahead else f"scratch: {_cue_down(v, s.pocket)}"


def _illegal_break(v: Voice, n: int) -> str:
    nothing = "nothing is pocketed" if v.ahead else "nothing pocketed"
    balls, reach = ("ball", "reaches") if n == 1 else ("balls", "reach")
    return (f"illegal break: {nothing} and {n} object {balls} {v.did('reached', reach)} a "
            f"cushion ({BREAK_RAIL_BALLS} needed)")


def _left(v: Voice, s: Said) -> str:
    leave = "leaves" if len(s.balls) == 1 else "leave"
    return f"{v.balls(s.balls)} {v.did('left', leave)} the table"


def _first(v: Voice, s: Said) -> str:
    return f"the cue ball {v.did('hit', 'hits')} {v.ball(s.ball)} first"


def _eight_down(v: Voice) -> str:
    return f"the 8 {v.did('went', 'goes')}"


def _early(v: Voice, s: Said) -> str:
    still = ("the table is open" if s.group is None else
             f"the {v.group(s.group)} {'are' if v.ahead else 'were'} not cleared")
    return f"{_eight_down(v)} down early ({still}): {v.does(s.player, 'loses', 'lose')}"


def _push_out(v: Voice, s: Said) -> str:
    return "push-out" + (f": {v.balls(s.balls)} pocketed, not counted" if s.balls else "")


CLAUSES = {
    Why.SCRATCH: _scratch,
    Why.LEFT_TABLE: _left,
    Why.ILLEGAL_BREAK: lambda v, s: _illegal_break(v, s.count),
    Why.NO_HIT: lambda v, s: _no_hit(v),
    Why.HIT_ON_OPEN_TABLE: lambda v, s: f"{_first(v, s)}, which is not allowed on an open "
                                        "table",
    Why.HIT_NOT_EIGHT: lambda v, s: f"{_first(v, s)}; with the {v.group(s.group)} cleared it "
                                    "must be the 8",
    Why.HIT_NOT_GROUP: lambda v, s: f"{_first(v, s)}, not one of the {v.group(s.group)}",
    Why.HIT_NOT_LOWEST: lambda v, s: f"{_first(v, s)}, not the lowest ball, "
                                     f"{v.ball(s.lowest)}",
    Why.NO_RAIL: lambda v, s: _no_rail(v),
    Why.LEGAL_BREAK: lambda v, s: "legal break",
    Why.LEGAL_BREAK_POTTED: lambda v, s: f"legal break: {_potted(v, s)}",
    Why.LEGAL_BREAK_RAILS: lambda v, s: f"legal break: {s.count} object balls reached a "
                                        "cushion, nothing pocketed",
    Why.EIGHT_RESPOTTED: lambda v, s: "the 8 went down on the break and is re-spotted",
    Why.EIGHT_RERACKED: lambda v, s: "the 8 on the break: re-racked, "
                                     f"{v.does(s.player, 'breaks', 'break')} again",
    Why.MAY_RERACK: lambda v, s: f"{v.name(s.player)} may accept the table or have it "
                                 "re-racked",
    Why.OPEN_CONTINUES: lambda v, s: "the table is open and "
                                     f"{v.does(s.player, 'continues', 'continue')}",
    Why.OPEN_TURN: lambda v, s: f"the table is open and it is {v.whose(s.player)} turn",
    Why.IN_HAND: lambda v, s: f"{v.does(s.player, 'has', 'have')} ball in hand",
    Why.IN_HAND_KITCHEN: lambda v, s: f"{v.does(s.player, 'has', 'have')} ball in hand "
                                      f"{KITCHEN}",
    Why.STAY_DOWN: lambda v, s: f"{v.balls(s.balls)} stay{'s' if len(s.balls) == 1 else ''} "
                                "down",
    Why.POTTED_ON_FOUL: lambda v, s: f"{v.balls(s.balls)} pocketed on a foul",
    Why.NINE_RESPOTTED: lambda v, s: "the 9 is re-spotted",
    Why.TAKES_GROUP: lambda v, s: f"{_potted(v, s)}: "
                                  f"{v.does(s.player, 'takes', 'take')} the "
                                  f"{v.group(s.group)} and "
                                  f"{v.verb(s.player, 'continues', 'continue')}",
    Why.POTTED_CONTINUES: lambda v, s: f"{_potted(v, s)}: "
                                       f"{v.does(s.player, 'continues', 'continue')}",
    Why.POTTED_NOT_OWN: lambda v, s: f"{_potted(v, s)}, none of the "
                                     f"{v.group(s.group)}: {v.whose(s.player)} turn",
    Why.NOTHING_TURN: lambda v, s: f"nothing pocketed: {v.whose(s.player)} turn",
    Why.PUSH_OUT: _push_out,
    Why.CHOOSES: lambda v, s: f"{v.does(s.player, 'chooses', 'choose')} {PUSH_OUT_CHOICE}",
    Why.EIGHT_OFF_TABLE: lambda v, s: "with the 8 off the table "
                                      f"{v.does(s.player, 'loses', 'lose')}",
    Why.EIGHT_ON_FOUL: lambda v, s: f"{_eight_down(v)} down on a foul: "
                                    f"{v.does(s.player, 'loses', 'lose')}",
    Why.EIGHT_EARLY: _early,
    Why.EIGHT_UNCALLED: lambda v, s: f"{_eight_down(v)} into the {v.pocket(s.pocket)} pocket "
                                     f"without a call: {v.does(s.player, 'loses', 'lose')}",
    Why.EIGHT_WRONG_POCKET: lambda v, s: f"{_eight_down(v)} into the {v.pocket(s.pocket)} "
                                         f"pocket, not the called {v.pocket(s.called)}: "
                                         f"{v.does(s.player, 'loses', 'lose')}",
    Why.EIGHT_CALLED: lambda v, s: f"the 8 went into the called {v.pocket(s.pocket)} pocket: "
                                   f"{v.does(s.player, 'wins', 'win')}",
    Why.NINE_ON_BREAK: lambda v, s: f"the 9 went into the {v.pocket(s.pocket)} pocket on the "
                                    f"break: {v.does(s.player, 'wins', 'win')}",
    Why.NINE_LEGAL: lambda v, s: f"the 9 went into the {v.pocket(s.pocket)} pocket on a legal "
                                 f"shot: {v.does(s.player, 'wins', 'win')}",
    Why.FOUL_LIMIT: lambda v, s: f"{ordinal(FOUL_LIMIT)} consecutive foul: "
                                 f"{v.does(s.player, 'loses', 'lose')}",
    # (the record's words list the balls with commas alone, as they always have)
    Why.PRACTICE_POTTED: lambda v, s: (f"{', '.join('the ' + b for b in s.balls)} pocketed"
                                       if v.plain else _potted(v, s)),
    Why.NOTHING_POCKETED: lambda v, s: "nothing pocketed",
    Why.SCRATCH_IN_HAND: lambda v, s: f"{_cue_down(v, s.pocket)}: ball in hand",
    Why.CUE_LEFT_IN_HAND: lambda v, s: f"the cue ball {v.did('left', 'leaves')} the table: "
                                       "ball in hand",
}


def reason(said: Sequence[Said], v: Voice = RECORD) -> str:
    """A verdict's clauses in words, joined by semicolons (in the record's voice unless
    given another)."""
    return _start("; ".join(CLAUSES[s.why](v, s) for s in said))


def verdict(outcome, v: Voice, shooter: int) -> tuple[str, str]:
    """An outcome of `shooter`'s shot as the panel says it: (text, tone), the tone "foul"
    ("Your foul: ...", "Bob's foul: ...": whose, before what it was), "good" (the shooter
    goes on, or won) or "plain"."""
    text = reason(outcome.said, v)
    if outcome.foul:
        return f"{v.whose_first(shooter)} foul: {text}", "foul"
    return text, "good" if outcome.continue_turn or outcome.winner == shooter else "plain"


def aid_warning(outcome, v: Voice, shooter: int) -> str | None:
    """What the aim aid warns of, from the referee's outcome of the shot as the aid sees it,
    said ahead of the shot: "As aimed: the 8 goes down early (...): you lose" for a shot that
    loses the game, "As aimed, a foul: the cue ball hits the 8 first, not one of the solids"
    for a foul; None for a legal shot; in practice, "As aimed: the cue ball goes into the ...
    pocket: ball in hand"."""
    v = replace(v, ahead=True)
    fouls = outcome.said[:len(outcome.fouls)]
    if outcome.winner is not None and outcome.winner != shooter:
        return "As aimed: " + reason((*fouls, outcome.said[-1]), v)
    if outcome.foul is not None:
        return "As aimed, a foul: " + reason(fouls, v)
    # Practice has no fouls, but a cue ball lost is still a shot spoiled.
    lost = [x for x in outcome.said if x.why in (Why.SCRATCH_IN_HAND, Why.CUE_LEFT_IN_HAND)]
    if lost:
        return "As aimed: " + reason(lost, v)
    return None


# ---------------------------------------------------------------------------- the match's news


def frame_won(v: Voice, winner: int, scores: Sequence[int], breaker: int) -> str:
    return _start(f"{v.does(winner, 'wins', 'win')} the frame ({scores[0]}-{scores[1]}); "
                  f"{v.does(breaker, 'breaks', 'break')}")


def game_won(v: Voice, winner: int) -> str:
    return _start(f"{v.does(winner, 'wins', 'win')}!")


def match_won(v: Voice, winner: int, scores: Sequence[int] | None = None) -> str:
    """"Bob wins the match 2-1", the winner's frames first (no score without `scores`)."""
    score = f" {scores[winner]}-{scores[1 - winner]}" if scores is not None else ""
    return _start(f"{v.does(winner, 'wins', 'win')} the match{score}")


def foul_warning(v: Voice, player: int) -> str:
    """The warning owed before a shot that could be a player's last foul in a row."""
    return _start(f"{v.does(player, 'is', 'are')} on {count_word(FOUL_LIMIT - 1)} fouls: a "
                  f"{ordinal(FOUL_LIMIT)} foul in a row loses the frame")


# The options: what the box asks, the key of each answer, and the answer in words.
OPTION_QUESTIONS = {
    Option.RERACK_OR_ACCEPT: "The break was illegal.",
    Option.SHOOT_OR_PASS: "Your opponent pushed out.",
}
CHOICE_KEYS = {Choice.RERACK: "r", Choice.ACCEPT: "a", Choice.SHOOT: "s", Choice.PASS: "p"}
CHOICE_WORDS = {Choice.RERACK: "re-rack and break", Choice.ACCEPT: "accept the table",
                Choice.SHOOT: "shoot", Choice.PASS: "pass the shot back"}
CHOICE_OFFERS = {Choice.RERACK: "re-rack and break yourself",
                 Choice.ACCEPT: "accept the table and shoot",
                 Choice.SHOOT: "shoot from here", Choice.PASS: "pass the shot back"}


def option_lines(option: Option) -> list[str]:
    """The option box: the question, then a line per answer with its key."""
    option = Option(option)
    return [OPTION_QUESTIONS[option], "",
            *(f"{CHOICE_KEYS[c]}: {CHOICE_OFFERS[c]}" for c in option.choices)]


PLANS = voice(("player 0", "player 1"))  # a plan's words with no match to name its players


def plan_note(note: PlanNote, v: Voice = PLANS) -> str:
    """The computer's plan in words: "the 3 in the top-right corner pocket", "safety on the 5",
    or the referee's verdict on the shot (in a theme of colours, "a red in ...")."""
    if note.aim is Aim.VERDICT:
        why = reason(note.said, v)
        return f"foul: {why}" if note.foul else why

    pocket = f"in the {v.pocket(note.pocket)} pocket" if note.pocket is not None else ""
    if note.aim is Aim.POT:
        return f"{v.ball(note.ball)} {pocket}"
    if note.aim is Aim.COMBO:
        return f"combination: {v.ball(note.ball)} into {v.ball(note.sunk)}, " \
               f"{v.ball(note.sunk)} {pocket}"
    if note.aim is Aim.FLUKE:
        by = "the break" if note.by_break else "a kiss or combination"
        return f"{v.balls(note.balls)} in by {by}"
    if note.aim is Aim.TRY:
        if note.sunk is None or note.sunk == note.ball:
            return f"try {v.ball(note.ball)} {pocket}".rstrip()
        return f"try {v.ball(note.ball)} into {v.ball(note.sunk)}, {v.ball(note.sunk)} {pocket}"
    if note.aim is Aim.BREAK:
        return "break"
    if note.aim is Aim.NOTHING:
        return "no object ball on the table"
    return f"{note.aim.value} on {v.ball(note.ball)}"  # a safety or a kick


def computer_plan(note: PlanNote, v: Voice = PLANS, done: bool = False) -> str:
    """The computer's plan ("the 3 in the top-right corner pocket") as the panel says it: while
    it aims and shoots, then (`done`) once the shot is over, beside the verdict on it, where
    the present tense would read as a shot still to come."""
    return f"Computer's plan{' was' if done else ''}: {plan_note(note, v)}"


def chose(name: str, choice: Choice) -> str:
    """"Bob chose to accept the table"."""
    return f"{name} chose to {CHOICE_WORDS[choice]}"


def rules_page(mode: str, *, three_foul: bool | None = None, eight_break: str | None = None,
               theme: str = "standard") -> list[tuple[str, str]]:
    """The rules of `mode` in plain words, as (heading, text) paragraphs. `three_foul` and
    `eight_break` say how the game in play is set (None: both ways are described); `theme`
    names the groups ("reds" and "yellows" in the classic theme)."""
    if mode == "8ball":
        page = _eight(eight_break, theme)
    elif mode == "9ball":
        page = _nine(three_foul)
    elif mode == "practice":
        page = _practice()
    else:
        raise ValueError(f"mode: must be one of 8ball, 9ball, practice, not {mode!r}")
    return [*page, POCKETS]


# The pockets' names, as verdicts and the computer's plans say them ("the top-right corner
# pocket", "the bottom side pocket").
POCKETS = ("Pockets", "named where the screen shows them: the four corners "
                      "(\"the top-left corner\") and the two side pockets halfway along the top "
                      "and bottom rails (\"the bottom side\"). The head is the end you break "
                      "from (the left end on screen), the foot the far end, where the balls are "
                      "racked.")


def _fouls(after: str) -> str:
    return (f"a scratch (the cue ball pocketed); {NO_HIT}; the wrong ball hit first; {NO_RAIL}. "
            + after)


def _eight(eight_break: str | None, theme: str) -> list[tuple[str, str]]:
    rail = count_word(BREAK_RAIL_BALLS)
    respot = ("the 8 is re-spotted and the breaker shoots on, unless the break was a foul")
    rerack = "the balls are re-racked and the breaker breaks again"
    on_break = {"respot": respot, "rerack": rerack}.get(
        eight_break, f"{respot} (with --eight-break rerack: {rerack})")
    return [
        ("Goal", f"pocket all seven balls of your group, the {group_label('solids', theme)} "
                 f"(1-7) or the {group_label('stripes', theme)} (9-15), then the 8."),
        ("The break", f"from ball in hand {KITCHEN} (the line across the table a quarter of "
                      f"its length from the head rail). It is legal when a ball is pocketed "
                      f"or at least {rail} object balls reach a cushion; if not, it is a foul "
                      f"and the other player may accept the table or have it re-racked. A "
                      f"scratch on the break gives the other player ball in hand {KITCHEN}. "
                      f"If the 8 goes down on the break, {on_break}."),
        ("Groups", "after the break the table is open: a ball of either group may be hit "
                   "first, but not the 8. The first ball pocketed on a legal shot gives its "
                   "group to the shooter, and the other group to the other player."),
        ("Each shot", "hit a ball of your group first (the 8 once your group is down), then "
                      "pocket a ball or send a ball to a cushion. Pocket a ball of your group "
                      "and you shoot again; otherwise it is the other player's turn."),
        ("Calling", "only the 8 is called: its pocket is named before the shot. Other balls "
                    "count wherever they drop."),
        ("The 8", "pocketed in the called pocket, with your group down and no foul, it wins "
                  "the game. It loses the game when it goes down before your group is "
                  "cleared, into another pocket than the one called, or on a foul."),
        ("Fouls", _fouls("After a foul the other player has ball in hand anywhere on the "
                         "table. Balls pocketed on a foul stay down and give no group.")),
    ]


def _nine(three_foul: bool | None) -> list[tuple[str, str]]:
    rail = count_word(BREAK_RAIL_BALLS)
    n = count_word(FOUL_LIMIT)
    rule = (f"{n} fouls in a row by the same player lose the frame; a legal shot starts the "
            f"count again, and the panel warns a player who is on {count_word(FOUL_LIMIT - 1)}.")
    three = {True: f"on in this game: {rule}",
             False: f"off in this game (the setting Three-foul rule, or --three-foul, turns "
                    f"it on). With it, {rule}",
             None: f"with the Three-foul rule (a setting, or --three-foul), {rule}"}[three_foul]
    return [
        ("Goal", "the balls are numbered 1 to 9; whoever pockets the 9 on a legal shot wins, "
                 "on the break too."),
        ("Each shot", "the cue ball must hit the lowest-numbered ball on the table first; "
                      "then a ball must be pocketed or some ball must reach a cushion. Every "
                      "ball pocketed on a legal shot counts, and you shoot again."),
        ("The break", f"from ball in hand {KITCHEN}. The cue ball must hit the 1 first, and "
                      f"the break must pocket a ball or send at least {rail} object balls to "
                      f"a cushion."),
        ("Push-out", "on the shot after a legal break, the shooter may declare a push-out: "
                     "the cue ball need not hit the lowest ball or any ball, and nothing need "
                     "reach a cushion, but a scratch is still a foul. Balls pocketed on it do "
                     f"not count (the 9 is re-spotted). The other player then chooses "
                     f"{PUSH_OUT_CHOICE}."),
        ("Fouls", _fouls("After a foul the other player has ball in hand anywhere on the "
                         "table. Balls pocketed on a foul stay down, except the 9, which is "
                         "re-spotted.")),
        ("Three fouls", three),
    ]


def _practice() -> list[tuple[str, str]]:
    return [
        ("Practice", "one player and a full rack of fifteen balls, with no fouls, no turns "
                     "and no end: every shot is yours."),
        ("Ball in hand", "anywhere on the table, to start with and after a scratch. Balls "
                         "you pocket stay down."),
        ("Take back", "the last shot can be taken back (again and again, back to the last "
                      "re-rack), and the balls re-racked at any time."),
    ]


def rules_text(mode: str, width: int = 80, **how) -> list[str]:
    """The rules page of `mode` as lines of at most `width` characters: its title, then each
    paragraph ("Heading: text") wrapped, a blank line between them."""
    import textwrap

    lines = [f"{MODE_NAMES[mode]} rules" if mode in MODE_NAMES else "rules"]
    for head, text in rules_page(mode, **how):
        lines.append("")
        lines += textwrap.wrap(f"{head}: {text}", width, break_on_hyphens=False)
    return lines
