"""Labels of a scene's sections: one rule for the prefix of parameter labels and the suffix of outputs.

A one-section scene writes ``cable.ae`` and ``tension_mid``; a scene of several sections writes
``sections[1].cable.ae`` and ``tension_mid_2``. The scene's error messages, the model's parameter
vector and its coordinate and output labels all use these two functions
(:mod:`cablesys.model.params` re-exports them).
"""

from __future__ import annotations

__all__ = ["section_prefix", "section_suffix"]


def section_prefix(scene_or_n, i: int) -> str:
    """Prefix of section ``i``'s parameter labels: "" for one section, else ``sections[i].``.

    Parameters
    ----------
    scene_or_n : Scene or int
        The scene, or its number of sections.
    i : int
        Section index, 0 at the top.

    Returns
    -------
    str
        The prefix (``sections[1].`` in ``sections[1].cable.ae``).
    """
    return "" if _count(scene_or_n) == 1 else f"sections[{i}]."


def section_suffix(scene_or_n, i: int) -> str:
    """Suffix of section ``i``'s coordinate and output labels: "" for one section, else ``_{i+1}``.

    Parameters
    ----------
    scene_or_n : Scene or int
        The scene, or its number of sections.
    i : int
        Section index, 0 at the top.

    Returns
    -------
    str
        The suffix (``_2`` in ``tension_mid_2``, ``u_2``).
    """
    return "" if _count(scene_or_n) == 1 else f"_{i + 1}"


def _count(scene_or_n) -> int:
    return scene_or_n if isinstance(scene_or_n, int) else len(scene_or_n.sections)
