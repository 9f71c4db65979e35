"""The referee's words for people: "player 0" becomes the player's name, pockets lose their
underscores ("foot left"), a player called "You" gets its grammar ("you continue"), and the
groups take the theme's words ("reds" for solids in the classic theme)."""

from __future__ import annotations

import re
from collections.abc import Sequence

from termpool.rules.themes import group_label

YOU_GRAMMAR = (("You continues", "You continue"), ("You loses", "You lose"),
               ("You wins", "You win"), ("You has", "You have"), ("You's", "your"),
               ("You is", "You are"))


def themed(text: str, theme: str = "standard") -> str:
    """`text` with the rules' group names ("solids", "stripes") in the words of `theme`."""
    if theme != "standard":
        for g in ("solids", "stripes"):
            text = re.sub(rf"\b{g}\b", group_label(g, theme), text)
    return text


def in_names(text: str, players: Sequence[str], theme: str = "standard") -> str:
    """`text` (a referee's reason) with "player 0" / "player 1" as `players` name them, in the
    words of the ball `theme`."""
    # The referee says "player 0"; default names such as "Player 1" must not be rewritten.
    text = re.sub(r"\bplayer ([01])\b", lambda g: players[int(g.group(1))], text)
    for a, b in YOU_GRAMMAR:
        text = text.replace(a, b)
    text = re.sub(r"(?<=[a-z0-9,;:] )You\b", "you", text)  # "... and you continue"
    text = themed(text, theme)
    return re.sub(r"\b(head|side|foot)_(left|right)\b", r"\1 \2", text)

# ------------------------------------------------------------------------------- shared facts
# Said by the referees in their verdicts and stated by the rules page (`rules_page`, shown by
# H in the game and by `termpool rules`): written once, so the two never disagree.
BREAK_RAIL_BALLS = 4  # a break that pockets nothing must drive this many object balls to a
# cushion (8-ball and 9-ball)
FOUL_LIMIT = 3  # 9-ball's three-foul rule: this many fouls in a row lose the frame
KITCHEN = "behind the head string"  # where ball in hand goes on a break (and after a scratch
# on the 8-ball break)
NO_HIT = "the cue ball hit no ball"
NO_RAIL = "no ball reached a cushion after contact and nothing was pocketed"
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


def rules_page(mode: str, *, three_foul: bool | None = None, eight_break: str | None = None,
               theme: str = "standard") -> list[tuple[str, str]]:
    """The rules of `mode` in plain words, as (heading, text) paragraphs. `three_foul` and
    `eight_break` say how the game in play is set (None: both ways are described); `theme`
    names the groups ("reds" and "yellows" in the classic theme)."""
    if mode == "8ball":
        page = _eight(eight_break)
    elif mode == "9ball":
        page = _nine(three_foul)
    elif mode == "practice":
        page = _practice()
    else:
        raise ValueError(f"mode: must be one of 8ball, 9ball, practice, not {mode!r}")
    return [(head, themed(text, theme)) for head, text in [*page, POCKETS]]


# The pockets' names, as verdicts and the computer's plans say them ("the foot left pocket").
POCKETS = ("Pockets", "the head is the end you break from (the left end on screen), the foot "
                      "the far end, where the balls are racked; the two side pockets are "
                      "halfway along. Left and right are as seen from the head: the left "
                      "pockets are along the top of the screen, the right ones along the "
                      "bottom.")


def _fouls(after: str) -> str:
    return (f"a scratch (the cue ball pocketed); {NO_HIT}; the wrong ball hit first; {NO_RAIL}. "
            + after)


def _eight(eight_break: str | None) -> list[tuple[str, str]]:
    rail = count_word(BREAK_RAIL_BALLS)
    respot = ("the 8 is re-spotted and the breaker shoots on, unless the break was a foul")
    rerack = "the balls are re-racked and the breaker breaks again"
    on_break = {"respot": respot, "rerack": rerack}.get(
        eight_break, f"{respot} (with --eight-break rerack: {rerack})")
    return [
        ("Goal", "pocket all seven balls of your group, the solids (1-7) or the stripes "
                 "(9-15), then the 8."),
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
             False: f"off in this game (--three-foul turns it on). With it, {rule}",
             None: f"with --three-foul, {rule}"}[three_foul]
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
