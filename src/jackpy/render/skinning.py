"""Skinned meshes: one continuous surface deformed by bone matrices in the vertex shader.

A :class:`SkinnedMesh` holds rest vertices and normals with, per vertex, four bone indices and
weights (linear-blend skinning, ``p = sum_k w_k M_{j_k} v``) and an *owner* bone that gives the
vertex its colour, highlight and pick id. It is uploaded once (:meth:`Renderer.add_skinned_mesh`);
per frame a :class:`~jackpy.render.scene.SkinnedItem` streams only the bone matrices and the
per-bone colour, pick id and highlight, packed in one small float texture (six RGBA texels per
bone: the matrix's four columns, the colour, then pick id and highlight), which the shader reads
with ``texelFetch``: no uniform-array size limit, any number of bones.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import moderngl
import numpy as np

from jackpy.render.instancing import pick_array, rgba
from jackpy.render.scene import DrawItem, SkinnedItem

TEXELS_PER_BONE = 6


@dataclass(frozen=True)
class SkinnedMesh:
    """Rest ``vertices`` (n,3) m, unit ``normals`` (n,3), triangles ``indices`` (m,3), bone indices
    ``joints`` (n,4) and ``weights`` (n,4) (each row sums to 1), ``owner`` (n,) bone per vertex, and
    ``n_bones``."""

    vertices: np.ndarray
    normals: np.ndarray
    indices: np.ndarray
    joints: np.ndarray
    weights: np.ndarray
    owner: np.ndarray
    n_bones: int

    def __post_init__(self) -> None:
        n = len(np.asarray(self.vertices).reshape(-1, 3))
        for name, dtype, width in (("vertices", np.float32, 3), ("normals", np.float32, 3),
                                   ("indices", np.uint32, 3), ("joints", np.int32, 4), ("weights", np.float32, 4)):
            object.__setattr__(self, name, np.ascontiguousarray(getattr(self, name), dtype).reshape(-1, width))
        object.__setattr__(self, "owner", np.ascontiguousarray(self.owner, np.int32).reshape(-1))
        for name in ("normals", "joints", "weights"):
            if len(getattr(self, name)) != n:
                raise ValueError(f"{name} has {len(getattr(self, name))} rows for {n} vertices")
        if len(self.owner) != n:
            raise ValueError(f"owner has {len(self.owner)} entries for {n} vertices")
        if self.indices.size and int(self.indices.max()) >= n:
            raise ValueError("triangle index out of range")
        for name in ("joints", "owner"):
            a = getattr(self, name)
            if a.size and (int(a.min()) < 0 or int(a.max()) >= self.n_bones):
                raise ValueError(f"{name} refers to a bone outside 0..{self.n_bones - 1}")

    @classmethod
    def of(cls, skin) -> SkinnedMesh:
        """From any object with ``vertices``, ``normals``, ``faces``, ``joints``, ``weights``,
        ``owner`` and ``bones`` (e.g. :class:`jackpy.body.skin.Skin`)."""
        return cls(skin.vertices, skin.normals, skin.faces, skin.joints, skin.weights, skin.owner, len(skin.bones))

    def deform(self, matrices: np.ndarray) -> np.ndarray:
        """Linear-blend skinned positions (n,3) for bone ``matrices`` (b,4,4), as the shader computes."""
        m = np.einsum("nk,nkij->nij", self.weights.astype(float), np.asarray(matrices, float)[self.joints])
        return np.einsum("nij,nj->ni", m[:, :3, :3], self.vertices.astype(float)) + m[:, :3, 3]


def stand_in(items: list[DrawItem], skins: list[SkinnedItem]) -> tuple[list[DrawItem], list[SkinnedItem]]:
    """Resolve :attr:`SkinnedItem.bone_items`: the skins with each bone's colour, pick id and
    highlight taken from the opaque item it stands in for (kept as given where that item is
    absent), and the items without those stood in for."""
    if not any(s.bone_items for s in skins):
        return items, skins
    by_key = {i.mesh: i for i in items if not i.transparent}
    taken: set[str] = set()
    out = []
    for skin in skins:
        if not skin.bone_items:
            out.append(skin)
            continue
        n = len(skin.bone_items)
        colors, picks = rgba(skin.colors, n).copy(), pick_array(skin.pick_ids, n)
        highlight = np.broadcast_to(np.asarray(skin.highlighted, bool), (n,)).copy()
        for b, key in enumerate(skin.bone_items):
            item = by_key.get(key)
            if item is not None:
                colors[b], picks[b], highlight[b] = rgba(item.color, 1)[0], item.pick_id or 0, item.highlighted
        taken.update(skin.bone_items)
        out.append(replace(skin, colors=colors, pick_ids=[int(p) for p in picks], highlighted=highlight))
    return [i for i in items if i.transparent or i.mesh not in taken], out


def bone_texels(item: SkinnedItem, n_bones: int) -> np.ndarray:
    """(n_bones, 6, 4) float32 texels of a :class:`SkinnedItem` (see the module docstring)."""
    bones = np.asarray(item.bones, np.float32).reshape(-1, 4, 4)
    if len(bones) != n_bones:
        raise ValueError(f"skinned item {item.mesh!r} has {len(bones)} bone matrices for {n_bones} bones")
    out = np.zeros((n_bones, TEXELS_PER_BONE, 4), np.float32)
    out[:, :4, :] = bones.transpose(0, 2, 1)  # columns
    out[:, 4, :] = rgba(item.colors, n_bones)
    out[:, 5, 0] = pick_array(item.pick_ids, n_bones)
    out[:, 5, 1] = np.broadcast_to(np.asarray(item.highlighted, np.float32), (n_bones,))
    return out


class GpuSkinnedMesh:
    """A skinned mesh's vertex and index buffers, its bone texture, and one VAO per program."""

    def __init__(self, ctx: moderngl.Context, mesh: SkinnedMesh) -> None:
        self.ctx = ctx
        self.n_bones = mesh.n_bones
        data = np.empty(len(mesh.vertices), [("p", np.float32, 3), ("n", np.float32, 3), ("j", np.int32, 4),
                                             ("w", np.float32, 4), ("o", np.int32)])
        data["p"], data["n"], data["j"], data["w"], data["o"] = (mesh.vertices, mesh.normals, mesh.joints,
                                                                 mesh.weights, mesh.owner)
        self.vbo = ctx.buffer(data.tobytes())
        self.ibo = ctx.buffer(mesh.indices.tobytes())
        self.index_count = mesh.indices.size
        self.texture = ctx.texture((TEXELS_PER_BONE, max(1, self.n_bones)), 4, dtype="f4")
        self.texture.filter = (moderngl.NEAREST, moderngl.NEAREST)
        self.uploaded = b""
        self.vaos: dict[int, moderngl.VertexArray] = {}

    def draw(self, program: moderngl.Program, texels: np.ndarray) -> None:
        """Draw the mesh posed by ``texels`` (from :func:`bone_texels`) with ``program``."""
        if self.index_count == 0:
            return
        data = np.ascontiguousarray(texels, np.float32).tobytes()
        if data != self.uploaded:
            self.texture.write(data)
            self.uploaded = data
        vao = self.vaos.get(program.glo)
        if vao is None:
            vao = self.ctx.vertex_array(
                program, [(self.vbo, "3f 3f 4i 4f 1i", "in_position", "in_normal", "in_joints", "in_weights",
                           "in_owner")],
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
