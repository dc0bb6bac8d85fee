"""Small text helpers for messages and reprs."""

from __future__ import annotations


def counted(n: int, noun: str) -> str:
    """``n`` and the noun, plural unless n is 1: "1 cable", "0 cables", "8 cables".

    Examples
    --------
    >>> counted(1, "mode"), counted(3, "mode")
    ('1 mode', '3 modes')
    """
    return f"{n} {noun}" if n == 1 else f"{n} {noun}s"
