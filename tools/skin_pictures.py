"""Make the before/after pictures of docs/workbench.md "A body that bends smoothly" (EGL offscreen).

The spine bent 60 degrees forward and twisted 30 degrees: drawn with the rigid per-vertebra slabs
(``before``: the scene's skins dropped) and with the continuous skins (``after``).
``python tools/skin_pictures.py docs/img``
"""

import sys
from pathlib import Path

import numpy as np

from jackpy.body import make_human
from jackpy.peabody import Environment
from jackpy.render import look_at, offscreen_renderer, perspective_matrix, write_png
from jackpy.ui.scene_view import SceneView


def main(out: Path) -> None:
    fig = make_human("male", 50)
    fig.groups["spine"].set_angles(fig, np.radians([60.0, 0.0, 30.0]))  # flexion, lateral, axial twist
    env = Environment()
    env.figures[fig.name] = fig
    c = fig.world_transforms()["t6"][:3, 3]
    renderer = offscreen_renderer(640, 640)
    view = SceneView()
    view.upload(renderer, env)
    for name, eye in (("side", c + [0.9, 0.1, 0.2]), ("back", c + [-0.4, 0.5, -0.8])):
        for tag, skinned in (("before", False), ("after", True)):
            scene = view.build(env)
            scene.grid = None
            if not skinned:
                scene.skins = []
            renderer.render(scene, look_at(eye, c), perspective_matrix(np.radians(40), 1.0, 0.05, 10.0))
            write_png(out / f"skin_{name}_{tag}.png", renderer.read_pixels())
    renderer.release()


if __name__ == "__main__":
    main(Path(sys.argv[1]))
