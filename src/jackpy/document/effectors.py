"""The end effectors a user grabs on a figure (hands, feet, head, pelvis) and what grabs them."""

from __future__ import annotations

from jackpy.peabody import Figure

HAND_ROLES = ("right_hand", "left_hand")
FOOT_ROLES = ("right_foot", "left_foot")

EFFECTOR_SITES: dict[str, tuple[str, ...]] = {
    # role: candidate "segment.site" names, the standard human's (docs/body.md) first, then the
    # synthetic tree's (jackpy.peabody.synthetic.human_like_tree)
    "right_hand": ("right_palm.palm_centre", "palm_right.tip"),
    "left_hand": ("left_palm.palm_centre", "palm_left.tip"),
    "right_foot": ("right_foot.ball", "right_foot.heel", "foot_right.tip"),
    "left_foot": ("left_foot.ball", "left_foot.heel", "foot_left.tip"),
    "head": ("head.view", "head.tip"),
    "pelvis": ("pelvis.centre", "lower_torso.proximal"),
}
"""The end effectors the operator grabs, by role; the first existing site of each role is used."""

EYE_SEGMENTS = ("left_eye", "right_eye", "eye_left", "eye_right")
"""Segments whose press grabs the eyes target (the gaze's look-at point) on a behavior-driven human."""


def is_object(figure: Figure) -> bool:
    """A figure without joints (a chair, a table, CAD) rather than an articulated figure."""
    return not figure.joints


def find_effectors(figure: Figure) -> dict[str, str]:
    """``role -> "segment.site"`` of the end effectors this figure has (see :data:`EFFECTOR_SITES`)."""
    out = {}
    for role, candidates in EFFECTOR_SITES.items():
        for c in candidates:
            seg, site = c.split(".", 1)
            if seg in figure.segments and site in figure.segments[seg].sites:
                out[role] = c
                break
    return out


def effector_segments(figure: Figure, effectors: dict[str, str]) -> dict[str, str]:
    """``segment -> role``: each effector's own segment, and for hands, feet and head everything
    beyond it away from the pelvis (fingers, toes, jaw and eyes grab their hand, foot, head)."""
    adj: dict[str, list[str]] = {s: [] for s in figure.segments}
    for j in figure.joints.values():
        adj[j.from_seg].append(j.to_seg)
        adj[j.to_seg].append(j.from_seg)
    centre = effectors.get("pelvis", f"{figure.root_segment()}.x").split(".")[0]
    out: dict[str, str] = {}
    for role, site in effectors.items():
        seg = site.split(".")[0]
        out[seg] = role
        if role == "pelvis":
            continue
        toward = _next_toward(adj, seg, centre)
        stack, seen = [seg], {seg, toward}
        while stack:
            s = stack.pop()
            for n in adj[s]:
                if n not in seen:
                    seen.add(n)
                    out.setdefault(n, role)
                    stack.append(n)
    if "head" in effectors:
        for seg in EYE_SEGMENTS:
            if out.get(seg) == "head":
                out[seg] = "eyes"
    return out


def _next_toward(adj: dict[str, list[str]], start: str, goal: str) -> str | None:
    """The neighbour of ``start`` on the tree path to ``goal`` (None if ``start`` is ``goal``)."""
    prev = {start: start}
    queue = [start]
    while queue:
        s = queue.pop(0)
        if s == goal:
            break
        for n in adj[s]:
            if n not in prev:
                prev[n] = s
                queue.append(n)
    if goal not in prev or goal == start:
        return None
    s = goal
    while prev[s] != start:
        s = prev[s]
    return s
