"""Skinned meshes: one continuous surface deformed by bone matrices in the vertex shader.

A :class:`SkinnedMesh` holds rest vertices and normals with, per vertex, four bone indices and
weights (linear-blend skinning, ``p = sum_k w_k M_{j_k} v``) and an *owner* bone that gives the
vertex its colour, highlight and pick id. It is uploaded once (:meth:`Renderer.add_skinned_mesh`);
per frame a :class:`~jackpy.render.scene.SkinnedItem` streams only the bone matrices and the
per-bone colour, pick id and highlight, packed in one small float texture (six RGBA texels per
bone: the matrix's four columns, the colour, then pick id and highlight), which the shader reads
with ``texelFetch``: no uniform-array size limit, any number of bones.

On a software rasteriser the vertex shading of a skin runs on the main thread, so each skin also
carries a *coarse* index buffer (:func:`coarse_indices`, about :data:`COARSE_FRACTION` of its
triangles) over the same vertices: moving frames drawn small (see ``Renderer.coarse_skin_scale``)
use it, still frames, pictures and picking the full one.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import moderngl
import numpy as np

from jackpy.render.instancing import pick_array, rgba
from jackpy.render.scene import DrawItem, SkinnedItem

TEXELS_PER_BONE = 6
COARSE_FRACTION = 0.25
"""Triangles of a skin's coarse level of detail, as a fraction of its own."""


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


def coarse_indices(mesh: SkinnedMesh, fraction: float = COARSE_FRACTION) -> np.ndarray:
    """Triangles (m', 3) of a decimated copy of ``mesh`` that reuses its vertices, m' <= ``fraction``
    of its triangles (at least 1 where it has any).

    Vertex clustering on the rest positions: the vertices in each grid cell collapse onto the one
    nearest the cell's mean, collapsed and duplicate triangles are dropped, and the cell grows until
    the budget holds. Every kept vertex is an original one with its own normal, bone indices,
    weights and owner, so the coarse copy skins, shades and picks as the full mesh does (shape error
    about one cell; for moving frames only)."""
    v, f = mesh.vertices.astype(float), mesh.indices.astype(np.int64)
    budget = max(1, int(len(f) * fraction))
    if len(f) <= budget:
        return mesh.indices.copy()
    lo = v.min(axis=0)
    edges = np.linalg.norm(v[f[:, 0]] - v[f[:, 1]], axis=1)
    cell = float(np.median(edges)) or 1e-3
    while True:
        key = np.floor((v - lo) / cell).astype(np.int64)
        n = key.max(axis=0) + 1
        _, cluster = np.unique((key[:, 0] * n[1] + key[:, 1]) * n[2] + key[:, 2], return_inverse=True)
        cluster = cluster.reshape(-1)
        ff = cluster[f]
        ff = ff[(ff[:, 0] != ff[:, 1]) & (ff[:, 1] != ff[:, 2]) & (ff[:, 0] != ff[:, 2])]
        rows = np.ascontiguousarray(np.sort(ff, axis=1)).view(np.dtype((np.void, 24))).reshape(-1)
        ff = ff[np.sort(np.unique(rows, return_index=True)[1])]
        if 0 < len(ff) <= budget or cell > 1e3:
            break
        cell *= 1.15
    k = cluster.max() + 1
    counts = np.bincount(cluster, minlength=k).astype(float)
    mean = np.stack([np.bincount(cluster, v[:, i], k) for i in range(3)], axis=1) / counts[:, None]
    order = np.lexsort((np.linalg.norm(v - mean[cluster], axis=1), cluster))
    first = np.ones(len(order), bool)
    first[1:] = cluster[order][1:] != cluster[order][:-1]
    representative = np.empty(k, np.int64)
    representative[cluster[order][first]] = order[first]
    return np.ascontiguousarray(representative[ff], np.uint32)


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
        coarse = coarse_indices(mesh) if mesh.indices.size else mesh.indices
        self.coarse_ibo = ctx.buffer(coarse.tobytes() or b"\0" * 12)
        self.coarse_count = coarse.size
        self.drawn_count = 0
        """Indices of the last draw (``index_count`` full, ``coarse_count`` coarse)."""
        self.texture = ctx.texture((TEXELS_PER_BONE, max(1, self.n_bones)), 4, dtype="f4")
        self.texture.filter = (moderngl.NEAREST, moderngl.NEAREST)
        self.uploaded = b""
        self.vaos: dict[tuple[int, bool], moderngl.VertexArray] = {}

    def draw(self, program: moderngl.Program, texels: np.ndarray, coarse: bool = False) -> None:
        """Draw the mesh posed by ``texels`` (from :func:`bone_texels`) with ``program``, its
        coarse level of detail if ``coarse``. Only changed texels are uploaded."""
        if self.index_count == 0:
            return
        data = np.ascontiguousarray(texels, np.float32).tobytes()
        if data != self.uploaded:
            self.texture.write(data)
            self.uploaded = data
        vao = self.vaos.get((program.glo, coarse))
        if vao is None:
            vao = self.ctx.vertex_array(
                program, [(self.vbo, "3f 3f 4i 4f 1i", "in_position", "in_normal", "in_joints", "in_weights",
                           "in_owner")],
                index_buffer=self.coarse_ibo if coarse else self.ibo, index_element_size=4, skip_errors=True)
            self.vaos[(program.glo, coarse)] = vao
        self.texture.use(0)
        program["u_bones"].value = 0
        self.drawn_count = self.coarse_count if coarse else self.index_count
        vao.render(moderngl.TRIANGLES, vertices=self.drawn_count)

    def release(self) -> None:
        for vao in self.vaos.values():
            vao.release()
        self.vaos.clear()
        for obj in (self.vbo, self.ibo, self.coarse_ibo, self.texture):
            obj.release()
