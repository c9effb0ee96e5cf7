"""The document's terrain drawn in the viewport (offscreen EGL): shaded ground, forbidden zones
tinted, no floor grid fighting it."""

from pathlib import Path

import numpy as np

from jackpy.document import Document
from jackpy.document.terrain import load_terrain
from jackpy.peabody import Environment
from jackpy.render import Scene
from jackpy.ui.camera import OrbitCamera
from jackpy.ui.scene_view import TERRAIN_MESH, SceneView

from ui_support import offscreen_renderer_or_skip

EXAMPLES = Path(__file__).resolve().parents[2] / "examples" / "creatures"


def _frame(renderer, view: SceneView, doc: Document) -> np.ndarray:
    scene = view.build(doc.env)
    view.add_terrain(renderer, scene, doc)
    cam = OrbitCamera(target=np.array([0.0, 0.0, 1.5]), distance=7.0, yaw=0.0, pitch=np.radians(80.0))
    renderer.render(scene, cam.view_matrix(), cam.projection_matrix(renderer.aspect))
    return renderer.read_pixels()[..., :3].astype(int), scene


def test_terrain_is_drawn_with_its_forbidden_zones_tinted():
    renderer = offscreen_renderer_or_skip(320, 240)
    doc = Document(Environment())
    view = SceneView()
    empty, scene0 = _frame(renderer, view, doc)
    assert scene0.grid is not None and not any(i.mesh == TERRAIN_MESH for i in scene0.items)
    load_terrain(doc, EXAMPLES / "steps.terrain.json")
    img, scene = _frame(renderer, view, doc)
    assert scene.grid is None and sum(i.mesh == TERRAIN_MESH for i in scene.items) == 1
    r, g, b = img[..., 0], img[..., 1], img[..., 2]
    red = (r > g + 40) & (r > b + 40)
    green = (g > r + 5) & (g > b + 15)
    assert red.sum() > 100, "the forbidden bank is tinted"
    assert green.sum() > 5 * red.sum(), "most of the ground is allowed"
    er, eg, eb = empty[..., 0], empty[..., 1], empty[..., 2]
    assert red.sum() > 3 * ((er > eg + 40) & (er > eb + 40)).sum()  # (the bare floor has only its red x axis)
