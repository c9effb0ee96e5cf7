"""Derive jackpy's shipped ANSUR II tables from the public ANSUR II subject files.

Reads ``ansur2_male.csv`` and ``ansur2_female.csv`` (the 2017 public release of the 2012 US Army
Anthropometric Survey; Gordon et al. 2014, NATICK/TR-15/007) and writes

* ``src/jackpy/body/data/ansur2_summary.csv`` - per sex and measurement: n, mean, SD (n - 1) and the
  empirical P1/P5/P50/P95/P99 (linear interpolation between order statistics), for all 93 measured
  dimensions plus the derived key dimensions (``KEY_DIMENSIONS`` below);
* ``src/jackpy/body/data/ansur2_correlations.csv`` - per sex, the Pearson correlation matrix of the
  key dimensions.

Statistics are unweighted sample statistics of the public subjects (4,082 men, 1,986 women); the
report's own tables are weighted to the Army's make-up, so they differ slightly. Lengths in mm;
``weightkg`` is stored by ANSUR II in tenths of a kilogram and is converted to kg here.

Usage::

    python tools/derive_ansur2.py [--data ../shared/data/anthropometry] [--out src/jackpy/body/data]
"""

from __future__ import annotations

import argparse
import csv
import hashlib
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
DEFAULT_DATA = ROOT.parent / "shared" / "data" / "anthropometry"
DEFAULT_OUT = ROOT / "src" / "jackpy" / "body" / "data"
SEX_FILES = {"female": "ansur2_female.csv", "male": "ansur2_male.csv"}
PERCENTILES = (1, 5, 50, 95, 99)
ID_AND_DEMOGRAPHIC = {"subjectid", "SubjectId", "Gender", "Date", "Installation", "Component", "Branch",
                      "PrimaryMOS", "SubjectsBirthLocation", "SubjectNumericRace", "Ethnicity", "DODRace",
                      "Age", "Heightin", "Weightlbs", "WritingPreference"}

#: key dimension -> (ANSUR II measurement or formula of measurements, unit). A formula is a sum/difference
#: of ANSUR II column names separated by " + " / " - ".
KEY_DIMENSIONS: dict[str, str] = {
    "stature": "stature",
    "weight": "weightkg",
    "sitting_height": "sittingheight",
    "eye_height_sitting": "eyeheightsitting",
    "acromial_height": "acromialheight",
    "cervicale_height": "cervicaleheight",
    "arm_length": "acromionradialelength + radialestylionlength",
    "upper_arm_length": "acromionradialelength",
    "forearm_length": "radialestylionlength",
    "hand_length": "handlength",
    "hand_breadth": "handbreadth",
    "span": "span",
    "bideltoid_breadth": "bideltoidbreadth",
    "biacromial_breadth": "biacromialbreadth",
    "chest_breadth": "chestbreadth",
    "chest_depth": "chestdepth",
    "waist_breadth": "waistbreadth",
    "waist_depth": "waistdepth",
    "hip_breadth": "hipbreadth",
    "hip_breadth_sitting": "hipbreadthsitting",
    "buttock_depth": "buttockdepth",
    "thigh_length": "trochanterionheight - lateralfemoralepicondyleheight",
    "shank_length": "lateralfemoralepicondyleheight - lateralmalleolusheight",
    "ankle_height": "lateralmalleolusheight",
    "knee_height_sitting": "kneeheightsitting",
    "popliteal_height": "poplitealheight",
    "buttock_knee_length": "buttockkneelength",
    "foot_length": "footlength",
    "foot_breadth": "footbreadthhorizontal",
    "head_breadth": "headbreadth",
    "head_length": "headlength",
    "head_height": "tragiontopofhead",
    "neck_circumference": "neckcircumference",
    "biceps_circumference_flexed": "bicepscircumferenceflexed",
    "forearm_circumference_flexed": "forearmcircumferenceflexed",
    "wrist_circumference": "wristcircumference",
    "thigh_circumference": "thighcircumference",
    "calf_circumference": "calfcircumference",
    "bimalleolar_breadth": "bimalleolarbreadth",
}

PROVENANCE = """\
# source: ANSUR II public release (2017) of the 2012 Anthropometric Survey of U.S. Army Personnel:
#   Gordon C.C., Blackwell C.L., Bradtmiller B., Parham J.L., Barrientos P., Paquette S.P., Corner B.D.,
#   Carson J.M., Venezia J.C., Rockwell B.M., Mucher M., Kristensen S. (2014). 2012 Anthropometric Survey
#   of U.S. Army Personnel: Methods and Summary Statistics. NATICK/TR-15/007. Files ANSUR_II_MALE_Public.csv
#   and ANSUR_II_FEMALE_Public.csv (Penn State OPEN Design Lab); copies in jackpy's shared/data/anthropometry
#   (sha256 male {male_sha}, female {female_sha}).
# method: derived by tools/derive_ansur2.py: unweighted sample statistics of the public subjects
#   (n = {n_male} men, {n_female} women); sd with n - 1; percentiles empirical (linear between order
#   statistics); not the report's weighted tables. weightkg is converted from tenths of kg to kg.
"""


def read_subjects(path: Path) -> dict[str, np.ndarray]:
    """Measured columns of one ANSUR II file -> float arrays (units as in the file)."""
    with path.open(newline="", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    names = [k for k in rows[0] if k not in ID_AND_DEMOGRAPHIC]
    return {k: np.array([float(r[k]) for r in rows]) for k in names}


def evaluate(formula: str, columns: dict[str, np.ndarray]) -> np.ndarray:
    """Value of a ``a + b - c`` formula of ANSUR II columns, in table units (mm; kg for weight)."""
    tokens = formula.split()
    total = to_table_units(tokens[0], columns[tokens[0]])
    for op, name in zip(tokens[1::2], tokens[2::2]):
        total = total + to_table_units(name, columns[name]) * (1.0 if op == "+" else -1.0)
    return total


def to_table_units(name: str, values: np.ndarray) -> np.ndarray:
    return values / 10.0 if name == "weightkg" else values


def unit_of(formula: str) -> str:
    return "kg" if formula == "weightkg" else "mm"


def summary_row(sex: str, key: str, measurement: str, values: np.ndarray) -> list[str]:
    pct = np.percentile(values, PERCENTILES)
    return [sex, key, measurement, unit_of(measurement), str(values.size), f"{values.mean():.2f}",
            f"{values.std(ddof=1):.2f}", *(f"{v:.1f}" for v in pct)]


def derive(data_dir: Path, out_dir: Path) -> None:
    subjects = {sex: read_subjects(data_dir / name) for sex, name in SEX_FILES.items()}
    sha = {sex: hashlib.sha256((data_dir / name).read_bytes()).hexdigest() for sex, name in SEX_FILES.items()}
    header = PROVENANCE.format(male_sha=sha["male"], female_sha=sha["female"],
                               n_male=len(subjects["male"]["stature"]), n_female=len(subjects["female"]["stature"]))
    key_of = {formula: key for key, formula in KEY_DIMENSIONS.items()}
    summary = [["sex", "key", "measurement", "unit", "n", "mean", "sd", *(f"p{p}" for p in PERCENTILES)]]
    correlations = [["sex", "dimension", *KEY_DIMENSIONS]]
    for sex, columns in subjects.items():
        for name in columns:
            summary.append(summary_row(sex, key_of.get(name, ""), name, to_table_units(name, columns[name])))
        for key, formula in KEY_DIMENSIONS.items():
            if formula not in columns:
                summary.append(summary_row(sex, key, formula, evaluate(formula, columns)))
        matrix = np.corrcoef(np.array([evaluate(f, columns) for f in KEY_DIMENSIONS.values()]))
        for key, row in zip(KEY_DIMENSIONS, matrix):
            correlations.append([sex, key, *(f"{r:.4f}" for r in row)])
    write_table(out_dir / "ansur2_summary.csv",
                "# table: ANSUR II summary statistics per sex and measurement (key = jackpy population-model name)\n"
                + header + "# units: mm; kg for weightkg\n", summary)
    write_table(out_dir / "ansur2_correlations.csv",
                "# table: ANSUR II Pearson correlations of the key dimensions, per sex (rows and columns in the "
                "same order)\n" + header
                + "# key dimensions:\n" + "".join(f"#   {k} = {f}\n" for k, f in KEY_DIMENSIONS.items()),
                correlations)


def write_table(path: Path, header: str, rows: list[list[str]]) -> None:
    lines = [header.rstrip("\n")] + [",".join(r) for r in rows]
    tmp = path.with_suffix(".tmp")
    tmp.write_text("\n".join(lines) + "\n", encoding="utf-8")
    tmp.replace(path)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--data", type=Path, default=DEFAULT_DATA, help="folder with ansur2_{male,female}.csv")
    parser.add_argument("--out", type=Path, default=DEFAULT_OUT, help="folder for the derived tables")
    args = parser.parse_args()
    derive(args.data, args.out)


if __name__ == "__main__":
    main()
