"""Every constant and table of the ergonomic assessments, with its source.

Sources (full references in docs/ergonomics.md):

* **RULA** — McAtamney L. & Corlett E.N. (1993) RULA: a survey method for the investigation of
  work-related upper limb disorders. Applied Ergonomics 24(2):91-99. Body-part bands, Tables A, B,
  C, muscle-use and force/load scores, action levels.
* **REBA** — Hignett S. & McAtamney L. (2000) Rapid Entire Body Assessment (REBA). Applied
  Ergonomics 31(2):201-205. Group A/B bands, Tables A, B, C, load/force, coupling, activity
  scores, action levels.
* **OWAS** — Karhu O., Kansi P. & Kuorinka I. (1977) Correcting working postures in industry: a
  practical method for analysis. Applied Ergonomics 8(4):199-201; action-category table as given
  by Louhevaara V. & Suurnäkki T. (1992) OWAS: a method for the evaluation of postural load
  during work, Finnish Institute of Occupational Health.
* **NIOSH** — Waters T.R., Putz-Anderson V., Garg A. & Fine L.J. (1993) Revised NIOSH equation
  for the design and evaluation of manual lifting tasks. Ergonomics 36(7):749-776; Waters T.R.,
  Putz-Anderson V. & Garg A. (1994) Applications Manual for the Revised NIOSH Lifting Equation,
  DHHS (NIOSH) Publication 94-110: Table 5 (frequency multiplier), Table 7 (coupling multiplier).
* **Low back** — Chaffin D.B., Andersson G.B.J. & Martin B.J. (2006) Occupational
  Biomechanics, 4th ed., ch. 6 (static sagittal-plane L5/S1 model: a single equivalent erector
  spinae force on a 5 cm moment arm; abdominal pressure from Chaffin's regression on the
  L5/S1 moment and the hip and knee angles, acting over the diaphragm area on its own moment
  arm); NIOSH (1981) Work Practices Guide for Manual Lifting, DHHS (NIOSH) 81-122: action limit
  3,400 N and maximum permissible limit 6,400 N of L5/S1 compression.

Where a method's text is qualitative ("neutral", "twisted", "raised") and a manikin needs a
number, the number is a **[decision]** named as such here and in docs/ergonomics.md; every one can
be overridden per task.
"""

from __future__ import annotations

import numpy as np

# ---------------------------------------------------------------------------------------------
# Thresholds for qualitative words [decision]: measured from the posture, overridable per task.
# ---------------------------------------------------------------------------------------------
#: |angle| at or below which a trunk, neck or wrist counts as "upright / neutral / 0°" (degrees)
NEUTRAL_BAND_DEG = 5.0
#: twist or side bend of the trunk or neck beyond which "twisted" / "side-bent" applies (degrees)
TWIST_DEG = 10.0
SIDE_BEND_DEG = 10.0
#: wrist radial/ulnar deviation beyond which the wrist is "deviated" (degrees)
WRIST_DEVIATION_DEG = 10.0
#: forearm pronation/supination beyond which it is "at or near the end of its range": 75 % of the
#: 80° AAOS range the standard human has (jackpy.body joint_limits.csv)
WRIST_TWIST_END_DEG = 60.0
#: upper arm out of the thorax's sagittal plane beyond which the arm is "abducted" (degrees)
ARM_ABDUCTED_DEG = 45.0
#: clavicle elevation above the thorax's transverse plane beyond which the shoulder is "raised"
#: (degrees; the standard human's shoulder rhythm gives 1° hanging, 21° at 90° flexion, ~30° overhead)
SHOULDER_RAISED_DEG = 25.0
#: forearm out of the thorax's sagittal plane beyond which the lower arm works "out to the side"
FOREARM_OUT_DEG = 30.0
#: a foot bears weight when its lowest contact site is within this height of the lowest one (m)
FOOT_CONTACT_M = 0.03
#: a knee "touches the floor" (kneeling) when its centre is within this height of the floor (m)
KNEE_FLOOR_M = 0.08
#: OWAS: back bent / twisted beyond these angles; knee bent beyond this flexion (degrees)
OWAS_BENT_DEG = 20.0
OWAS_TWIST_DEG = 20.0
OWAS_KNEE_BENT_DEG = 30.0

# ---------------------------------------------------------------------------------------------
# RULA (McAtamney & Corlett 1993). Bands are [lower, upper) ("20-45°, 45-90°, 90°+"): a score steps
# at its angle. REBA's are (lower, upper] ("> 20°"): a score steps just above it.
# ---------------------------------------------------------------------------------------------
RULA_UPPER_ARM_EXTENSION_DEG = 20.0           # 20°+ extension: 2
RULA_UPPER_ARM_FLEXION_DEG = (20.0, 45.0, 90.0)  # <20: 1, 20-45: 2, 45-90: 3, 90+: 4
RULA_LOWER_ARM_DEG = (60.0, 100.0)            # 60-100° flexion: 1, else 2
RULA_WRIST_DEG = 15.0                         # neutral: 1, 0-15: 2, 15+: 3
RULA_NECK_DEG = (10.0, 20.0)                  # 0-10: 1, 10-20: 2, 20+: 3, extension: 4
RULA_TRUNK_DEG = (20.0, 60.0)                 # upright: 1, 0-20: 2, 20-60: 3, 60+: 4
#: force/load score: < 2 kg intermittent 0; 2-10 kg intermittent 1; 2-10 kg static or repeated,
#: or 10 kg+ intermittent 2; 10 kg+ static or repeated, or shock 3
RULA_LOAD_KG = (2.0, 10.0)

#: Table A [upper arm 1-6][lower arm 1-3][wrist 1-4][wrist twist 1-2]
RULA_TABLE_A = np.array([
    [[[1, 2], [2, 2], [2, 3], [3, 3]], [[2, 2], [2, 2], [3, 3], [3, 3]], [[2, 3], [3, 3], [3, 3], [4, 4]]],
    [[[2, 3], [3, 3], [3, 4], [4, 4]], [[3, 3], [3, 3], [3, 4], [4, 4]], [[3, 4], [4, 4], [4, 4], [5, 5]]],
    [[[3, 3], [4, 4], [4, 4], [5, 5]], [[3, 4], [4, 4], [4, 4], [5, 5]], [[4, 4], [4, 4], [4, 5], [5, 5]]],
    [[[4, 4], [4, 4], [4, 5], [5, 5]], [[4, 4], [4, 4], [4, 5], [5, 5]], [[4, 4], [4, 5], [5, 5], [6, 6]]],
    [[[5, 5], [5, 5], [5, 6], [6, 7]], [[5, 6], [6, 6], [6, 7], [7, 7]], [[6, 6], [6, 7], [7, 7], [7, 8]]],
    [[[7, 7], [7, 7], [7, 8], [8, 9]], [[8, 8], [8, 8], [8, 9], [9, 9]], [[9, 9], [9, 9], [9, 9], [9, 9]]],
])
#: Table B [neck 1-6][trunk 1-6][legs 1-2]
RULA_TABLE_B = np.array([
    [[1, 3], [2, 3], [3, 4], [5, 5], [6, 6], [7, 7]],
    [[2, 3], [2, 3], [4, 5], [5, 5], [6, 7], [7, 7]],
    [[3, 3], [3, 4], [4, 5], [5, 6], [6, 7], [7, 7]],
    [[5, 5], [5, 6], [6, 7], [7, 7], [7, 7], [8, 8]],
    [[7, 7], [7, 7], [7, 8], [8, 8], [8, 8], [8, 8]],
    [[8, 8], [8, 8], [8, 8], [8, 9], [9, 9], [9, 9]],
])
#: Table C [score C 1-8+][score D 1-7+]
RULA_TABLE_C = np.array([
    [1, 2, 3, 3, 4, 5, 5],
    [2, 2, 3, 4, 4, 5, 5],
    [3, 3, 3, 4, 4, 5, 6],
    [3, 3, 3, 4, 5, 6, 6],
    [4, 4, 4, 5, 6, 7, 7],
    [4, 4, 5, 6, 6, 7, 7],
    [5, 5, 6, 6, 7, 7, 7],
    [5, 5, 6, 7, 7, 7, 7],
])
#: grand score -> (action level, action)
RULA_ACTION = ((2, 1, "acceptable if not maintained or repeated for long periods"),
               (4, 2, "investigate further; changes may be needed"),
               (6, 3, "investigate and change soon"),
               (7, 4, "investigate and change immediately"))

# ---------------------------------------------------------------------------------------------
# REBA (Hignett & McAtamney 2000)
# ---------------------------------------------------------------------------------------------
REBA_TRUNK_DEG = (20.0, 60.0)        # upright 1; 0-20 flex or ext 2; 20-60 flex or >20 ext 3; >60 4
REBA_NECK_DEG = 20.0                 # 0-20: 1; >20 or extension: 2
REBA_KNEE_DEG = (30.0, 60.0)         # +1 for 30-60° knee flexion, +2 above 60°
REBA_UPPER_ARM_EXTENSION_DEG = 20.0
REBA_UPPER_ARM_FLEXION_DEG = (20.0, 45.0, 90.0)
REBA_LOWER_ARM_DEG = (60.0, 100.0)
REBA_WRIST_DEG = 15.0                # 0-15: 1, >15: 2
REBA_LOAD_KG = (5.0, 10.0)           # <5: 0, 5-10: 1, >10: 2; +1 shock or rapid build-up
REBA_COUPLING = {"good": 0, "fair": 1, "poor": 2, "unacceptable": 3}
#: Table A [neck 1-3][trunk 1-5][legs 1-4]
REBA_TABLE_A = np.array([
    [[1, 2, 3, 4], [2, 3, 4, 5], [2, 4, 5, 6], [3, 5, 6, 7], [4, 6, 7, 8]],
    [[1, 2, 3, 4], [3, 4, 5, 6], [4, 5, 6, 7], [5, 6, 7, 8], [6, 7, 8, 9]],
    [[3, 3, 5, 6], [4, 5, 6, 7], [5, 6, 7, 8], [6, 7, 8, 9], [7, 8, 9, 9]],
])
#: Table B [lower arm 1-2][upper arm 1-6][wrist 1-3]
REBA_TABLE_B = np.array([
    [[1, 2, 2], [1, 2, 3], [3, 4, 5], [4, 5, 5], [6, 7, 8], [7, 8, 8]],
    [[1, 2, 3], [2, 3, 4], [4, 5, 5], [5, 6, 7], [7, 8, 8], [8, 9, 9]],
])
#: Table C [score A 1-12][score B 1-12]
REBA_TABLE_C = np.array([
    [1, 1, 1, 2, 3, 3, 4, 5, 6, 7, 7, 7],
    [1, 2, 2, 3, 4, 4, 5, 6, 6, 7, 7, 8],
    [2, 3, 3, 3, 4, 5, 6, 7, 7, 8, 8, 8],
    [3, 4, 4, 4, 5, 6, 7, 8, 8, 9, 9, 9],
    [4, 4, 4, 5, 6, 7, 8, 8, 9, 9, 9, 9],
    [6, 6, 6, 7, 8, 8, 9, 9, 10, 10, 10, 10],
    [7, 7, 7, 8, 9, 9, 9, 10, 10, 11, 11, 11],
    [8, 8, 8, 9, 10, 10, 10, 10, 10, 11, 11, 11],
    [9, 9, 9, 10, 10, 10, 11, 11, 11, 12, 12, 12],
    [10, 10, 10, 11, 11, 11, 11, 12, 12, 12, 12, 12],
    [11, 11, 11, 11, 12, 12, 12, 12, 12, 12, 12, 12],
    [12, 12, 12, 12, 12, 12, 12, 12, 12, 12, 12, 12],
])
#: REBA score -> (action level, risk, action)
REBA_ACTION = ((1, 0, "negligible", "none necessary"),
               (3, 1, "low", "may be necessary"),
               (7, 2, "medium", "necessary"),
               (10, 3, "high", "necessary soon"),
               (15, 4, "very high", "necessary now"))

# ---------------------------------------------------------------------------------------------
# OWAS (Karhu et al. 1977; table of Louhevaara & Suurnäkki 1992)
# ---------------------------------------------------------------------------------------------
OWAS_LOAD_KG = (10.0, 20.0)          # ≤10: 1, 10-20: 2, >20: 3
OWAS_BACK = {1: "straight", 2: "bent", 3: "twisted", 4: "bent and twisted"}
OWAS_ARMS = {1: "both arms below shoulder level", 2: "one arm at or above shoulder level",
             3: "both arms at or above shoulder level"}
OWAS_LEGS = {1: "sitting", 2: "standing on both straight legs", 3: "standing on one straight leg",
             4: "standing or squatting on both knees bent", 5: "standing or squatting on one knee bent",
             6: "kneeling on one or both knees", 7: "walking or moving"}
OWAS_LOAD = {1: "10 kg or less", 2: "10 to 20 kg", 3: "more than 20 kg"}
#: action category [back 1-4][arms 1-3][legs 1-7][load 1-3]
OWAS_TABLE = np.array([
    [[[1, 1, 1], [1, 1, 1], [1, 1, 1], [2, 2, 2], [2, 2, 2], [1, 1, 1], [1, 1, 1]],
     [[1, 1, 1], [1, 1, 1], [1, 1, 1], [2, 2, 2], [2, 2, 2], [1, 1, 1], [1, 1, 1]],
     [[1, 1, 1], [1, 1, 1], [1, 1, 1], [2, 2, 3], [2, 2, 3], [1, 1, 1], [1, 1, 2]]],
    [[[2, 2, 3], [2, 2, 3], [2, 2, 3], [3, 3, 3], [3, 3, 3], [2, 2, 2], [2, 3, 3]],
     [[2, 2, 3], [2, 2, 3], [2, 3, 3], [3, 4, 4], [3, 4, 4], [3, 3, 4], [2, 3, 4]],
     [[3, 3, 4], [2, 2, 3], [3, 3, 3], [3, 4, 4], [4, 4, 4], [4, 4, 4], [2, 3, 4]]],
    [[[1, 1, 1], [1, 1, 1], [1, 1, 2], [3, 3, 3], [4, 4, 4], [1, 1, 1], [1, 1, 1]],
     [[2, 2, 3], [1, 1, 1], [1, 1, 2], [4, 4, 4], [4, 4, 4], [3, 3, 3], [1, 1, 1]],
     [[2, 2, 3], [1, 1, 1], [2, 3, 3], [4, 4, 4], [4, 4, 4], [4, 4, 4], [1, 1, 1]]],
    [[[2, 3, 3], [2, 2, 3], [2, 2, 3], [4, 4, 4], [4, 4, 4], [4, 4, 4], [2, 3, 4]],
     [[3, 3, 4], [2, 3, 4], [3, 3, 4], [4, 4, 4], [4, 4, 4], [4, 4, 4], [2, 3, 4]],
     [[4, 4, 4], [2, 3, 4], [3, 3, 4], [4, 4, 4], [4, 4, 4], [4, 4, 4], [2, 3, 4]]],
])
OWAS_ACTION = {1: "no corrective measures needed", 2: "corrective measures in the near future",
               3: "corrective measures as soon as possible", 4: "corrective measures immediately"}

# ---------------------------------------------------------------------------------------------
# NIOSH revised lifting equation (Waters et al. 1993; applications manual 1994), metric form
# ---------------------------------------------------------------------------------------------
NIOSH_LC_KG = 23.0
NIOSH_H_CM = (25.0, 63.0)        # HM = 25/H; 1 below 25 cm; 0 beyond 63 cm
NIOSH_V_MAX_CM = 175.0           # VM = 1 - 0.003 |V - 75|; 0 above 175 cm
NIOSH_V_REF_CM = 75.0
NIOSH_D_CM = (25.0, 175.0)       # DM = 0.82 + 4.5/D; 1 below 25 cm; 0 beyond 175 cm
NIOSH_A_MAX_DEG = 135.0          # AM = 1 - 0.0032 A; 0 beyond 135°
#: frequency multiplier, manual Table 5: rows lifts/min; columns (≤1 h, ≤2 h, ≤8 h) x (V < 75, V ≥ 75)
NIOSH_FREQUENCIES = np.array([0.2, 0.5, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15], dtype=float)
NIOSH_FM = np.array([
    [1.00, 1.00, 0.95, 0.95, 0.85, 0.85],
    [0.97, 0.97, 0.92, 0.92, 0.81, 0.81],
    [0.94, 0.94, 0.88, 0.88, 0.75, 0.75],
    [0.91, 0.91, 0.84, 0.84, 0.65, 0.65],
    [0.88, 0.88, 0.79, 0.79, 0.55, 0.55],
    [0.84, 0.84, 0.72, 0.72, 0.45, 0.45],
    [0.80, 0.80, 0.60, 0.60, 0.35, 0.35],
    [0.75, 0.75, 0.50, 0.50, 0.27, 0.27],
    [0.70, 0.70, 0.42, 0.42, 0.22, 0.22],
    [0.60, 0.60, 0.35, 0.35, 0.18, 0.18],
    [0.52, 0.52, 0.30, 0.30, 0.00, 0.15],
    [0.45, 0.45, 0.26, 0.26, 0.00, 0.13],
    [0.41, 0.41, 0.00, 0.23, 0.00, 0.00],
    [0.37, 0.37, 0.00, 0.21, 0.00, 0.00],
    [0.00, 0.34, 0.00, 0.00, 0.00, 0.00],
    [0.00, 0.31, 0.00, 0.00, 0.00, 0.00],
    [0.00, 0.28, 0.00, 0.00, 0.00, 0.00],
])
#: work durations (upper bound in hours) of the table's column pairs
NIOSH_DURATIONS_H = (1.0, 2.0, 8.0)
#: coupling multiplier, manual Table 7: (V < 75 cm, V ≥ 75 cm)
NIOSH_CM = {"good": (1.00, 1.00), "fair": (0.95, 1.00), "poor": (0.90, 0.90)}
#: the manual's coupling decision tree: an object is "optimal" when its length is at most 40 cm
#: and its height at most 30 cm; fingers "flexed about 90°" for a fair coupling [decision: the
#: mean MCP + PIP flexion of the holding hand's four fingers at least 70°]
NIOSH_OPTIMAL_LENGTH_CM = 40.0
NIOSH_OPTIMAL_HEIGHT_CM = 30.0
NIOSH_FINGERS_FLEXED_DEG = 70.0

# ---------------------------------------------------------------------------------------------
# Static sagittal low-back model (Chaffin et al. 2006, ch. 6)
# ---------------------------------------------------------------------------------------------
#: moment arm of the single equivalent erector spinae force about the L5/S1 disc (m)
ERECTOR_MOMENT_ARM_M = 0.05
#: diaphragm area over which abdominal pressure acts (m^2) and the moment arm of that force
#: anterior to L5/S1 (m)
DIAPHRAGM_AREA_M2 = 0.0465
ABDOMINAL_MOMENT_ARM_M = 0.11
#: abdominal pressure regression (mmHg): P = 1e-4 (43 - 0.36 (theta_H + theta_K)) M^1.8, M the L5/S1
#: moment in N m, theta_H and theta_K the hip and knee flexion in degrees (0 = standing straight,
#: the reading used here), P floored at 0
ABDOMINAL_COEFFICIENTS = (1e-4, 43.0, 0.36, 1.8)
MMHG_PA = 133.322
#: L5/S1 compression limits (N): NIOSH 1981 action limit and maximum permissible limit
COMPRESSION_DESIGN_LIMIT_N = 3400.0
COMPRESSION_UPPER_LIMIT_N = 6400.0
