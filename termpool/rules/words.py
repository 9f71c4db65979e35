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


def in_names(text: str, players: Sequence[str], theme: str = "standard") -> str:
    """`text` (a referee's reason) with "player 0" / "player 1" as `players` name them, in the
    words of the ball `theme`."""
    # The referee says "player 0"; default names such as "Player 1" must not be rewritten.
    text = re.sub(r"\bplayer ([01])\b", lambda g: players[int(g.group(1))], text)
    for a, b in YOU_GRAMMAR:
        text = text.replace(a, b)
    text = re.sub(r"(?<=[a-z0-9,;:] )You\b", "you", text)  # "... and you continue"
    if theme != "standard":
        for g in ("solids", "stripes"):
            text = re.sub(rf"\b{g}\b", group_label(g, theme), text)
    return re.sub(r"\b(head|side|foot)_(left|right)\b", r"\1 \2", text)
