"""Rigid items merged into one draw: the singleton opaque items of a frame as one vertex buffer.

A figure's segments are drawn as one :class:`~jackpy.render.scene.DrawItem` each, every one of its
own mesh (the fingers, the head, the chair): instancing cannot batch them, and on a software
rasteriser each draw call has a fixed cost (about 0.1-0.3 ms in llvmpipe, the state validation and
the vertex-shading job), so ~45 small draws cost more than the few thousand triangles they hold.
:func:`split_rigid` picks the items that can merge (opaque, no edge overlay, a mesh of their own
without vertex colours, a rigid transform); :class:`RigidBatch` holds their meshes' vertices in one
buffer, each vertex with its item's index, and draws them all at once: per frame only the items'
matrices, colours, pick ids and highlights are streamed, as six RGBA texels per item in a small
float texture (the layout of the skins' bone texels, :func:`~jackpy.render.skinning.bone_texels`),
read by ``shaders.RIGID_VERTEX``. The image is the one the items drew one by one.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Sequence

import moderngl
import numpy as np

from jackpy.render.mesh import Mesh
from jackpy.render.scene import DrawItem, SkinnedItem
from jackpy.render.skinning import TEXELS_PER_BONE, bone_texels

MAX_TRIANGLES = 20_000
"""Largest mesh merged (triangles): a bigger one gains nothing from sharing a draw, and a merged
copy is rebuilt whenever the set of merged items changes."""
MIN_ITEMS = 2
"""Fewest items worth a merged buffer."""


def rigid_mask(transforms: np.ndarray, tol: float = 1e-4) -> np.ndarray:
    """(n,) whether each of (n, 4, 4) transforms is a rotation and a translation (so that
    ``mat3(M)`` maps normals as the instanced path's normal matrix does)."""
    t = np.asarray(transforms, float).reshape(-1, 4, 4)
    a = t[:, :3, :3]
    gram = np.einsum("nki,nkj->nij", a, a)
    ok = np.abs(gram - np.eye(3)).max(axis=(1, 2), initial=0.0) <= tol
    ok &= np.abs(t[:, 3] - (0.0, 0.0, 0.0, 1.0)).max(axis=1, initial=0.0) <= tol
    return ok & (np.linalg.det(a) > 0.0) if len(t) else ok


def mergeable_mesh(mesh: Mesh) -> bool:
    """Whether items of ``mesh`` may be merged: no vertex colours, at most ``MAX_TRIANGLES``."""
    return mesh.colors is None and 0 < len(mesh.indices) <= MAX_TRIANGLES


def split_rigid(items: Sequence[DrawItem], mergeable: set[str] | frozenset[str]) -> tuple[list[DrawItem], list[DrawItem]]:
    """(kept, merged): the items to merge are opaque, without an edge overlay, of a mesh in
    ``mergeable`` that no other such item uses (a mesh drawn several times stays instanced) and
    rigidly placed; the rest are kept, in order. Fewer than ``MIN_ITEMS`` merge nothing."""
    candidates = [i for i in items if not i.transparent and not i.wireframe and i.mesh in mergeable]
    uses = Counter(i.mesh for i in candidates)
    single = [i for i in candidates if uses[i.mesh] == 1]
    if len(single) < MIN_ITEMS:
        return list(items), []
    rigid = rigid_mask(np.array([i.transform for i in single], float))
    merged = [i for i, ok in zip(single, rigid) if ok]
    if len(merged) < MIN_ITEMS:
        return list(items), []
    ids = {id(i) for i in merged}
    return [i for i in items if id(i) not in ids], merged


def item_texels(items: Sequence[DrawItem]) -> np.ndarray:
    """(n, 6, 4) float32 texels of the merged items: model matrix columns, colour, (pick id,
    highlight)."""
    return bone_texels(SkinnedItem("rigid", np.array([i.transform for i in items], float).reshape(-1, 4, 4),
                                   np.array([tuple(i.color) + (1.0,) * (4 - len(i.color)) for i in items]),
                                   [i.pick_id for i in items], [bool(i.highlighted) for i in items]),
                       len(items))


class RigidBatch:
    """The merged meshes of a list of items (item ``k`` draws ``meshes[k]``) on the GPU."""

    def __init__(self, ctx: moderngl.Context, meshes: Sequence[Mesh]) -> None:
        self.ctx = ctx
        self.n_bones = len(meshes)
        counts = [len(m.vertices) for m in meshes]
        offsets = np.concatenate([[0], np.cumsum(counts)[:-1]]).astype(np.uint32)
        data = np.empty(sum(counts), [("p", np.float32, 3), ("n", np.float32, 3), ("o", np.int32)])
        data["p"] = np.concatenate([m.vertices for m in meshes])
        data["n"] = np.concatenate([m.normals for m in meshes])
        data["o"] = np.repeat(np.arange(len(meshes), dtype=np.int32), counts)
        indices = np.concatenate([m.indices + o for m, o in zip(meshes, offsets)]).astype(np.uint32)
        self.vbo = ctx.buffer(data.tobytes())
        self.ibo = ctx.buffer(indices.tobytes())
        self.index_count = indices.size
        self.texture = ctx.texture((TEXELS_PER_BONE, max(1, self.n_bones)), 4, dtype="f4")
        self.texture.filter = (moderngl.NEAREST, moderngl.NEAREST)
        self.uploaded = b""
        self.vaos: dict[int, moderngl.VertexArray] = {}

    def draw(self, program: moderngl.Program, texels: np.ndarray) -> None:
        """Draw every merged item placed by ``texels`` (:func:`item_texels`) with ``program``;
        only changed texels are uploaded."""
        data = np.ascontiguousarray(texels, np.float32).tobytes()
        if data != self.uploaded:
            self.texture.write(data)
            self.uploaded = data
        vao = self.vaos.get(program.glo)
        if vao is None:
            vao = self.ctx.vertex_array(program, [(self.vbo, "3f 3f 1i", "in_position", "in_normal", "in_owner")],
                                        index_buffer=self.ibo, index_element_size=4, skip_errors=True)
            self.vaos[program.glo] = vao
        self.texture.use(0)
        program["u_bones"].value = 0
        vao.render(moderngl.TRIANGLES, vertices=self.index_count)

    def release(self) -> None:
        for vao in self.vaos.values():
            vao.release()
        self.vaos.clear()
        for obj in (self.vbo, self.ibo, self.texture):
            obj.release()
