"""What a caller sees of each run the ladder makes: its blocks of output and its progress.

A plan may run several times (a rejected rung, an N / 2 check, the extrapolation's coarse runs); only a
*candidate* run, whose result may be returned, streams its blocks to the caller.
"""

from __future__ import annotations


def hooks(kw: dict, description: str, candidate: bool) -> dict:
    """``on_block`` / ``progress`` for one run of the ladder: the caller's own (a candidate run only: one whose
    result may be returned) and what ``on_run(description, candidate)`` gives for it."""
    out = {k: kw[k] for k in ("on_block", "progress") if candidate and kw.get(k) is not None}
    on_run = kw.get("on_run")
    if on_run is not None:
        got = on_run(description, candidate) or (None, None)
        out.update({k: v for k, v in zip(("on_block", "progress"), got) if v is not None})
    return out


def checking(kw: dict) -> dict:
    """The run options of a check run (an N / 2 or extrapolation run): no ``on_block``, ``progress`` or start of the
    caller's; ``on_run`` stays so that the caller can show the check's progress."""
    return {k: v for k, v in kw.items() if k not in ("on_block", "progress", "x0", "times")}
