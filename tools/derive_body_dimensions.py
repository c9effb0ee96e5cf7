"""Derive ``src/jackpy/body/data/population_ansur2.csv`` (the figure's dimensions) from the ANSUR II
public subject files.

Usage: ``python tools/derive_body_dimensions.py [DATA_DIR]`` (default ``../shared/data/anthropometry``).

Each figure dimension is a formula over one subject's ANSUR II measurements (mm; ``weightkg`` is in
tenths of kg), evaluated per subject; the file gets, per sex, its sample mean and SD (n - 1), its
Pearson correlations with stature and with weight, the ordinary-least-squares regression on stature
and weight (intercept mm, slopes mm/mm and mm/kg) and normal-model percentiles (lognormal for mass).
Because the formulas of the stature path sum to stature for every subject, their regressions on
(stature, weight) sum to stature exactly: a figure built from the regression is as tall as asked.
"""

from __future__ import annotations

import csv
import sys
from pathlib import Path
from statistics import NormalDist

import numpy as np

OUT = Path(__file__).resolve().parents[1] / "src/jackpy/body/data/population_ansur2.csv"
PCT = (1, 5, 25, 50, 75, 95, 99)
PI = np.pi

#: figure dimension -> (formula over a subject's columns, text for the 'measure' column)
DIMENSIONS: dict[str, tuple] = {
    "stature": (lambda c: c["stature"], "STATURE"),
    "mass": (lambda c: c["weightkg"] / 10.0, "WEIGHTKG / 10 (kg); lognormal percentiles"),
    "eye_height": (lambda c: c["stature"] - c["sittingheight"] + c["eyeheightsitting"],
                   "standing eye height = STATURE - (SITTINGHEIGHT - EYEHEIGHTSITTING) (head above eyes "
                   "as measured sitting; ANSUR II has no standing eye height)"),
    "foot.height": (lambda c: c["lateralmalleolusheight"], "ankle joint centre height = LATERALMALLEOLUSHEIGHT"),
    "shank.length": (lambda c: c["lateralfemoralepicondyleheight"] - c["lateralmalleolusheight"],
                     "knee to ankle joint centre: LATERALFEMORALEPICONDYLEHEIGHT - LATERALMALLEOLUSHEIGHT"),
    "thigh.length": (lambda c: c["trochanterionheight"] - c["lateralfemoralepicondyleheight"],
                     "hip to knee joint centre: TROCHANTERIONHEIGHT - LATERALFEMORALEPICONDYLEHEIGHT"),
    "pelvis.length": (lambda c: 0.164 * (c["cervicaleheight"] - 20.0 - c["trochanterionheight"]),
                      "hip joint centre to L5/S1: 0.164 (CERVICALEHEIGHT - 20 - TROCHANTERIONHEIGHT) [estimate]"),
    "spine.length": (lambda c: 0.836 * (c["cervicaleheight"] - 20.0 - c["trochanterionheight"]),
                     "L5/S1 to C7/T1: 0.836 (CERVICALEHEIGHT - 20 - TROCHANTERIONHEIGHT); C7/T1 20 mm below cervicale"),
    "neck.length": (lambda c: c["stature"] - c["tragiontopofhead"] - 24.0 - (c["cervicaleheight"] - 20.0),
                    "C7/T1 to atlanto-occipital joint: STATURE - (TRAGIONTOPOFHEAD + 24) - (CERVICALEHEIGHT - 20)"),
    "head.height": (lambda c: c["tragiontopofhead"] + 24.0,
                    "atlanto-occipital joint to vertex: TRAGIONTOPOFHEAD + 24 (joint 24 mm below the tragion)"),
    "seat.hip_height": (lambda c: c["sittingheight"] - c["stature"] + c["trochanterionheight"],
                        "seat to hip joint centre, sitting erect: SITTINGHEIGHT - (STATURE - TROCHANTERIONHEIGHT)"),
    "acromion.drop": (lambda c: c["cervicaleheight"] - 20.0 - c["acromialheight"],
                      "C7/T1 joint down to the acromion: CERVICALEHEIGHT - 20 - ACROMIALHEIGHT"),
    "thigh.clearance": (lambda c: c["thighclearance"], "THIGHCLEARANCE (seat to the top of the thigh)"),
    "buttock_knee.length": (lambda c: c["buttockkneelength"], "BUTTOCKKNEELENGTH"),
    "knee.height_sitting": (lambda c: c["kneeheightsitting"], "KNEEHEIGHTSITTING"),
    "hip.breadth_sitting": (lambda c: c["hipbreadthsitting"], "HIPBREADTHSITTING"),
    "span": (lambda c: c["span"], "SPAN"),
    "head.breadth": (lambda c: c["headbreadth"], "HEADBREADTH"),
    "head.length": (lambda c: c["headlength"], "HEADLENGTH"),
    "neck.breadth": (lambda c: c["neckcircumference"] / PI, "NECKCIRCUMFERENCE / pi"),
    "shoulder.breadth": (lambda c: c["biacromialbreadth"], "BIACROMIALBREADTH"),
    "bideltoid.breadth": (lambda c: c["bideltoidbreadth"], "BIDELTOIDBREADTH"),
    "chest.breadth": (lambda c: c["chestbreadth"], "CHESTBREADTH"),
    "chest.depth": (lambda c: c["chestdepth"], "CHESTDEPTH"),
    "waist.breadth": (lambda c: c["waistbreadth"], "WAISTBREADTH"),
    "waist.depth": (lambda c: c["waistdepth"], "WAISTDEPTH"),
    "hip.breadth": (lambda c: c["hipbreadth"], "HIPBREADTH"),
    "buttock.depth": (lambda c: c["buttockdepth"], "BUTTOCKDEPTH"),
    "thigh.breadth": (lambda c: c["thighcircumference"] / PI, "THIGHCIRCUMFERENCE / pi"),
    "knee.breadth": (lambda c: 0.82 * c["lowerthighcircumference"] / PI,
                     "0.82 LOWERTHIGHCIRCUMFERENCE / pi [estimate: knee narrower than the lower thigh]"),
    "calf.breadth": (lambda c: c["calfcircumference"] / PI, "CALFCIRCUMFERENCE / pi"),
    "ankle.breadth": (lambda c: c["bimalleolarbreadth"], "BIMALLEOLARBREADTH"),
    "foot.length": (lambda c: c["footlength"], "FOOTLENGTH (barefoot)"),
    "foot.breadth": (lambda c: c["footbreadthhorizontal"], "FOOTBREADTHHORIZONTAL"),
    "upper_arm.length": (lambda c: c["acromionradialelength"] - 35.0,
                         "shoulder to elbow joint centre: ACROMIONRADIALELENGTH - 35 (acromion above the joint)"),
    "forearm.length": (lambda c: c["radialestylionlength"], "elbow to wrist joint centre: RADIALESTYLIONLENGTH"),
    "upper_arm.breadth": (lambda c: c["bicepscircumferenceflexed"] / PI, "BICEPSCIRCUMFERENCEFLEXED / pi"),
    "forearm.breadth": (lambda c: c["forearmcircumferenceflexed"] / PI, "FOREARMCIRCUMFERENCEFLEXED / pi"),
    "wrist.breadth": (lambda c: c["wristcircumference"] / PI, "WRISTCIRCUMFERENCE / pi"),
    "hand.length": (lambda c: c["handlength"], "HANDLENGTH"),
    "hand.breadth": (lambda c: c["handbreadth"], "HANDBREADTH"),
    "eyes.breadth": (lambda c: c["interpupillarybreadth"] / 10.0, "INTERPUPILLARYBREADTH (file in 0.1 mm)"),
}

HEADER = """# population: ansur2
# title: US Army personnel, ANSUR II (2012) - derived per subject from the public data
# source: Gordon C.C., Blackwell C.L., Bradtmiller B., Parham J.L., Barrientos P., Paquette S.P.,
#   Corner B.D., Carson J.M., Venezia J.C., Rockwell B.M., Mucher M., Kristensen S. (2014) 2012
#   Anthropometric Survey of U.S. Army Personnel: Methods and Summary Statistics, NATICK/TR-15/007;
#   public subject files ANSUR_II_MALE_Public.csv / ANSUR_II_FEMALE_Public.csv (4082 men, 1986 women).
# method: tools/derive_body_dimensions.py: each dimension is the formula in 'measure' evaluated per
#   subject (unweighted sample, sd with n - 1); r_stature / r_weight: Pearson correlations; a, b_stature,
#   b_weight: least-squares regression value = a + b_stature * stature + b_weight * weight (mm, kg);
#   p1..p99 = mean + z sd (normal model), mass lognormal with the same mean and sd.
# units: mm, kg
"""


def read(path: Path) -> dict[str, np.ndarray]:
    with path.open(encoding="utf-8", newline="") as f:
        rows = list(csv.DictReader(f))
    numeric = {}
    for k in rows[0]:
        try:
            numeric[k] = np.array([float(r[k]) for r in rows])
        except ValueError:
            continue
    return numeric


def quantiles(mean: float, sd: float, lognormal: bool) -> list[float]:
    z = [NormalDist().inv_cdf(p / 100.0) for p in PCT]
    if not lognormal:
        return [mean + zi * sd for zi in z]
    s2 = np.log(1.0 + (sd / mean) ** 2)
    mu = np.log(mean) - s2 / 2
    return [float(np.exp(mu + zi * np.sqrt(s2))) for zi in z]


def main(data_dir: Path) -> None:
    lines = [HEADER.rstrip("\n"),
             "sex,dimension,unit,mean,sd,r_stature,r_weight,a,b_stature,b_weight,"
             + ",".join(f"p{p}" for p in PCT) + ",measure"]
    for sex in ("male", "female"):
        cols = read(data_dir / f"ansur2_{sex}.csv")
        s, w = cols["stature"], cols["weightkg"] / 10.0
        design = np.column_stack([np.ones_like(s), s, w])
        for name, (formula, text) in DIMENSIONS.items():
            v = formula(cols)
            coef = np.linalg.lstsq(design, v, rcond=None)[0]
            mean, sd = float(v.mean()), float(v.std(ddof=1))
            ps = quantiles(mean, sd, name == "mass")
            unit = "kg" if name == "mass" else "mm"
            vals = [mean, sd, np.corrcoef(v, s)[0, 1], np.corrcoef(v, w)[0, 1], *coef, *ps]
            lines.append(f"{sex},{name},{unit}," + ",".join(f"{x:.6g}" for x in vals) + f",{text}")
    OUT.write_text("\n".join(lines) + "\n", encoding="utf-8")
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parents[2] / "shared/data/anthropometry")
