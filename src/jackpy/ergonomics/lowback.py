"""Static sagittal-plane L5/S1 load (Chaffin, Andersson & Martin 2006, ch. 6), against the NIOSH limits.

Everything above the L5/S1 joint (the segments on the ``l5`` side of joint ``l5_s1``: trunk, head,
arms) and the load in the hands (half at each grip site) pull with their weight. In the disc frame —
the world frame of segment ``l5``: x lateral (left), y along the lumbar spine (up), z forward —

* ``M`` = flexion moment of that weight about the L5/S1 joint centre (the x component, N·m; > 0
  means the extensors must act);
* abdominal pressure ``P_A = 1e-4 (43 - 0.36 (θ_H + θ_K)) M^1.8`` mmHg (θ_H, θ_K: mean hip and knee
  flexion, degrees; floored at 0) acting over the diaphragm area ``A_D`` gives ``F_A = P_A A_D``
  on the moment arm ``D_A`` in front of the disc;
* the erector spinae, one equivalent force on the moment arm ``E = 5 cm`` behind the disc centre:
  ``F_M = (M - F_A D_A) / E`` (>= 0);
* compression ``F_C = F_M - F_A + W_axial`` (``W_axial``: the weight's component along -y) and
  anterior shear ``F_S = W · z``.

Compared with the NIOSH (1981) design limit 3,400 N and upper limit 6,400 N. Valid for static,
symmetric sagittal-plane exertions; lateral and twisting moments are reported and flagged when they
are not small, and a negative (extending) moment is flagged (the abdominal muscles, not modelled,
would act).
"""

from __future__ import annotations

import weakref
from typing import Any

import numpy as np

from jackpy.ergonomics import constants as C
from jackpy.ergonomics.base import Assessment, Method, Task, register
from jackpy.ergonomics.posture import Posture
from jackpy.errors import FigureError
from jackpy.peabody.kinematics import FKResult, Kinematics
from jackpy.peabody.model import Figure

G = 9.80665
VALIDITY = ("static (slow) sagittal-plane, symmetric exertions; L5/S1 flexion moments 0-400 N·m "
            "(the abdominal pressure regression's range)")

#: per flattened tree: the indices of the segments above L5/S1
_UPPER: "weakref.WeakKeyDictionary[Kinematics, np.ndarray]" = weakref.WeakKeyDictionary()


def upper_body(figure: Figure, kin: Kinematics) -> np.ndarray:
    """Indices (into ``kin`` segments) of the segments on the ``l5`` side of joint ``l5_s1``."""
    if kin not in _UPPER:
        if "l5_s1" not in figure.joints:
            raise FigureError(f"figure {figure.name!r} has no l5_s1 joint: the low-back model needs the standard human")
        adj: dict[str, list[str]] = {s: [] for s in figure.segments}
        for j in figure.joints.values():
            if j.name != "l5_s1":
                adj[j.from_seg].append(j.to_seg)
                adj[j.to_seg].append(j.from_seg)
        seen, todo = {"l5"}, ["l5"]
        while todo:
            for n in adj[todo.pop()]:
                if n not in seen:
                    seen.add(n)
                    todo.append(n)
        _UPPER[kin] = np.array(sorted(kin.segment_index[s] for s in seen))
    return _UPPER[kin]


def level(compression: float) -> tuple[int, str]:
    if compression <= C.COMPRESSION_DESIGN_LIMIT_N:
        return 1, "below the NIOSH design limit (3,400 N)"
    if compression <= C.COMPRESSION_UPPER_LIMIT_N:
        return 2, "above the NIOSH design limit (3,400 N): redesign advised"
    return 3, "above the NIOSH upper limit (6,400 N): redesign needed"


def assess(figure: Figure, task: Task, posture: Posture, fk: FKResult | None = None) -> Assessment:
    """L5/S1 compression and shear of the figure's posture with ``task.load_kg`` in the hands."""
    kin = figure.kinematics()
    if fk is None:
        fk = kin.forward(figure.q, figure.location)
    idx = upper_body(figure, kin)
    coms = kin.segment_coms(fk)[idx]
    mass = kin.mass[idx]
    disc = fk.segments[kin.segment_index["l5"]]
    centre, R = disc[:3, 3], disc[:3, :3]
    r = mass @ (coms - centre)  # the weights are vertical: sum r x (m g) = g (sum m r_z, 0, -sum m r_x)
    total = float(mass.sum())
    mz, mx = float(r[2]), float(r[0])
    load = task.load_kg
    if load > 0:
        for grip in posture.grips.values():
            mz += 0.5 * load * float(grip[2] - centre[2])
            mx += 0.5 * load * float(grip[0] - centre[0])
        total += load
    m_local = R.T @ np.array([G * mz, 0.0, -G * mx])
    f_local = R.T @ np.array([0.0, -G * total, 0.0])
    m_flex, m_twist, m_lat = float(m_local[0]), float(m_local[1]), float(m_local[2])
    hip = 0.5 * (posture.hip_flexion["left"] + posture.hip_flexion["right"])
    knee = 0.5 * (posture.knee_flexion["left"] + posture.knee_flexion["right"])
    k, a0, a1, expo = C.ABDOMINAL_COEFFICIENTS
    p_mmhg = max(0.0, k * (a0 - a1 * (max(hip, 0.0) + knee)) * max(m_flex, 0.0) ** expo)
    f_abd = p_mmhg * C.MMHG_PA * C.DIAPHRAGM_AREA_M2
    f_muscle = max(0.0, (m_flex - f_abd * C.ABDOMINAL_MOMENT_ARM_M) / C.ERECTOR_MOMENT_ARM_M)
    axial = float(-f_local[1])
    compression = f_muscle - f_abd + axial
    shear = float(f_local[2])
    flags = []
    if m_flex < 0:
        flags.append(f"extending L5/S1 moment {m_flex:.0f} N·m: the abdominal muscles would act (not modelled)")
    if m_flex > 400:
        flags.append(f"L5/S1 moment {m_flex:.0f} N·m beyond the abdominal-pressure regression's range (400 N·m)")
    off = abs(m_lat) + abs(m_twist)
    if off > 10.0 and off > 0.2 * abs(m_flex):
        flags.append(f"asymmetric: lateral {m_lat:.0f} N·m and twisting {m_twist:.0f} N·m moments are outside the "
                     "sagittal model")
    lv, text = level(compression)
    ws: dict[str, Any] = {
        "upper_body_mass_kg": float(mass.sum()), "load_kg": load, "flexion_moment_Nm": m_flex,
        "lateral_moment_Nm": m_lat, "twist_moment_Nm": m_twist, "abdominal_pressure_mmHg": p_mmhg,
        "abdominal_force_N": f_abd, "erector_force_N": f_muscle, "axial_weight_N": axial,
        "compression_N": compression, "shear_N": shear, "design_limit_N": C.COMPRESSION_DESIGN_LIMIT_N,
        "upper_limit_N": C.COMPRESSION_UPPER_LIMIT_N, "erector_moment_arm_m": C.ERECTOR_MOMENT_ARM_M,
        "abdominal_moment_arm_m": C.ABDOMINAL_MOMENT_ARM_M, "diaphragm_area_m2": C.DIAPHRAGM_AREA_M2,
        "disc_tilt_deg": float(np.degrees(np.arccos(np.clip(R[1, 1], -1.0, 1.0)))),
    }
    measured = {"trunk_flexion": posture.trunk_flexion, "hip_flexion": hip, "knee_flexion": knee,
                "disc_tilt": ws["disc_tilt_deg"]}
    return Assessment("lowback", compression, lv, text, ws, measured,
                      "disc frame: segment l5 (x left, y along the lumbar spine, z forward); forces N, moments N·m",
                      flags, "l5_s1", unit="N")


METHOD = register(Method("lowback", "L5/S1 low-back compression and shear (static sagittal model)",
                         "Chaffin D.B., Andersson G.B.J. & Martin B.J. (2006) Occupational Biomechanics, 4th ed., "
                         "ch. 6; NIOSH (1981) Work Practices Guide for Manual Lifting", VALIDITY, assess, (1, 3)))
