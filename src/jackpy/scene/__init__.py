"""jackpy.scene: CAD import through trimesh (units, up axis, placement, sites) and workplace scene files."""

from jackpy.scene.cad import (
    DISPLAY_TRIANGLES, FORMATS, UNITS, UP_AXES, CADObject, ImportSettings, add_cad, decimate, import_cad,
)
from jackpy.scene.workplace import (
    AnalysisPlan, Stand, Workplace, load_workplace, resolve_target, save_workplace, stand_figure,
)

__all__ = ["AnalysisPlan", "CADObject", "DISPLAY_TRIANGLES", "FORMATS", "ImportSettings", "Stand", "UNITS",
           "UP_AXES", "Workplace", "add_cad", "decimate", "import_cad", "load_workplace", "resolve_target",
           "save_workplace", "stand_figure"]
