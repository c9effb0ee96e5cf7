"""Names for people: ``right_shoulder`` -> "right shoulder", ``l4_l5`` -> "L4-L5", DOF 1 of
``right_shoulder`` -> "right shoulder elevation" (the anatomical DOF names of
:data:`jackpy.body.skeleton.DOF_NAMES`, in the joint's DOF order). Joints of other figures keep
their own name, their DOFs are numbered from 1."""

from __future__ import annotations

import re

from jackpy.body.skeleton import DOF_NAMES, joint_kind

_DOF_KEY = re.compile(r"^(?P<joint>.+)\[(?P<k>\d+)\]$")


def joint_label(name: str) -> str:
    """A joint's name for people (vertebral joints in capitals, ``l4_l5`` -> ``L4-L5``)."""
    if joint_kind(name) == "spine":
        return "-".join(part.upper() for part in name.split("_"))
    return name.replace("_", " ")


def dof_name(joint: str, k: int) -> str:
    """The anatomical name of DOF ``k`` of ``joint`` (``flexion``), else ``DOF k+1``."""
    names = DOF_NAMES.get(joint_kind(joint), ())
    return names[k].replace("_", " ") if 0 <= k < len(names) else f"DOF {k + 1}"


def dof_label(joint: str, k: int) -> str:
    """``right shoulder elevation`` for DOF ``k`` of ``joint``."""
    return f"{joint_label(joint)} {dof_name(joint, k)}"


def dof_key_label(key: str) -> str:
    """``right_clavicle[1]`` (a DOF as the analyses name it) -> ``right clavicle protraction``."""
    m = _DOF_KEY.match(key)
    return dof_label(m["joint"], int(m["k"])) if m else key.replace("_", " ")


def is_human(figure: object) -> bool:
    """Whether every joint of ``figure`` is a joint of the standard human (its DOFs have names)."""
    joints = getattr(figure, "joints", {})
    return bool(joints) and all(joint_kind(name) in DOF_NAMES for name in joints)
