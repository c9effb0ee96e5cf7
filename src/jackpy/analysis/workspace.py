"""Reachable workspace of a chain by forward-kinematics sampling into voxels (book §3.4;
shared/spec/manipulation-and-ik.md §4).

A :class:`Chain` is the DOFs from a start joint out to an end segment, with a reference point on
that segment (a hand site). :func:`reachable_workspace` samples the chain's DOFs within their limits
(scrambled Sobol points, the rest of the figure held in its current posture), marks every voxel of a
world-axis-aligned grid that a sampled reference point falls in, and stops when a batch adds fewer
than ``tol`` new voxels relative to those marked (the spec's "until the count of newly marked cells
levels off"), at ``max_samples``, or when the progress callback asks to cancel. A 1 marks a reached
cell; a 0 does not prove a cell unreachable (book §3.4.1).

Sampling is vectorised by the product of exponentials: with the world screw axes ``(a_i, o_i)`` of
the chain's DOFs in the reference posture ``q0`` and ``T_i(d)`` the rotation by ``d`` about that
axis (or translation along it), the reference point at ``q`` is
``T_1(s_1 (q_1 - q0_1)) ... T_n(s_n (q_n - q0_n)) p0``, proximal DOF first (``s_i`` the DOF's
traversal sign).

**Joint groups** (book §2.2.5): a group whose member joints all lie in the chain (the shoulder
complex of an arm chain from the clavicle, the forearm's pronation) is sampled in its *group
angles*, within their box and their ``A @ theta <= b`` rows (samples outside are rejected), and
mapped to its members through the group's driver, vectorised (``driver.batch``; see
:func:`jackpy.peabody.groups.driver_batch`): so the clavicle follows the arm as it does in the IK
and the UI. A driver without ``batch`` (the spine's Monheit driver, about 0.3 ms a call) is
evaluated once per *unique* sample: its group angles are snapped to a grid of at most
``max_driver_calls`` points (per angle a step of ``cell / reach`` when that fits, else coarser),
and the driver runs once per grid point that a batch hits. A group only partly in the chain (a
chain from the shoulder joint, without the clavicle) has its in-chain members sampled within their
own limits, as before; ``Chain(..., coupled=False)`` samples every member that way.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy.stats import qmc

from jackpy.analysis.surface import surface_nets
from jackpy.errors import FigureError
from jackpy.peabody.geometry import Mesh
from jackpy.peabody.groups import JointGroup, driver_batch
from jackpy.peabody.model import Figure


@dataclass
class GroupSlot:
    """A joint group sampled in its angles: ``cols`` are the chain columns of its member DOFs in
    the chain and ``outs`` their positions in the driver's output; ``dims`` its angles' columns of
    the unit sample."""

    group: JointGroup
    cols: np.ndarray
    outs: np.ndarray
    dims: slice
    batched: bool


@dataclass
class ChainSample:
    """Chain DOF ``values`` (N, n) of the feasible samples and each coupled group's angles (N, k)."""

    values: np.ndarray
    angles: dict[str, np.ndarray]


@dataclass
class Chain:
    """The DOFs that move ``end_segment`` from ``start_joint`` outwards (proximal first), and the
    reference ``point`` on ``end_segment`` (segment frame, metres). With ``coupled`` the joint
    groups wholly inside the chain are sampled in their group angles (module docstring)."""

    figure: Figure
    start_joint: str
    end_segment: str
    point: np.ndarray
    coupled: bool = True

    def __post_init__(self) -> None:
        kin = self.figure.kinematics()
        if self.end_segment not in kin.segment_index:
            raise FigureError(f"figure {self.figure.name!r} has no segment {self.end_segment!r}")
        self.figure.joint(self.start_joint)
        path: list[int] = []  # joints from the end segment up to the start joint
        s = kin.segment_index[self.end_segment]
        while s > 0:
            ji = int(kin.parent_joint[s])
            path.append(ji)
            if kin.joint_names[ji] == self.start_joint:
                break
            s = int(kin.parent[s])
        else:
            raise FigureError(f"figure {self.figure.name!r}: joint {self.start_joint!r} does not move "
                              f"segment {self.end_segment!r} from the root")
        # every joint that moves the end segment (up to the root): a group member among them but
        # outside the chain would move the chain's base, so such a group cannot be coupled here
        self._moving = {int(kin.parent_joint[t]) for t in self._to_root(kin, kin.segment_index[self.end_segment])}
        slot_in_joint = kin.dof_slot % 3
        dofs: list[int] = []
        for ji in reversed(path):
            mine = np.flatnonzero(kin.dof_joint == ji)
            down = kin.joint_direction[ji] == 1
            mine = mine[np.argsort(slot_in_joint[mine] if down else -slot_in_joint[mine])]
            dofs.extend(int(i) for i in mine)
        self.dofs = np.array(dofs, dtype=int)
        self.point = np.asarray(self.point, dtype=float).reshape(3)
        self._slots()

    @staticmethod
    def _to_root(kin, s: int) -> list[int]:
        out = []
        while s > 0:
            out.append(s)
            s = int(kin.parent[s])
        return out

    def _slots(self) -> None:
        """Coupled groups (wholly inside the chain) and the chain columns sampled directly."""
        kin = self.figure.kinematics()
        col_of = {int(d): c for c, d in enumerate(self.dofs)}
        grouped: list[int] = []
        self.groups: list[GroupSlot] = []
        slots = []
        for g in (self.figure.groups.values() if self.coupled else ()):
            members = np.concatenate([np.arange(self.figure.ndof)[self.figure.joint_dof_slice(jn)]
                                      for jn in g.joints])
            moving = [int(d) for d in members if int(kin.dof_joint[d]) in self._moving]
            if not moving or not all(d in col_of for d in moving):
                continue  # not in the chain, or a member moves its base: members sampled on their own
            # driver output positions of the members in the chain (members on a side branch, e.g.
            # the spine's c7_t1 for an arm chain, do not move the end segment and are dropped)
            outs = np.array([i for i, d in enumerate(members) if int(d) in col_of], dtype=int)
            cols = np.array([col_of[int(members[i])] for i in outs], dtype=int)
            grouped.extend(cols.tolist())
            slots.append((g, cols, outs))
        self.free_cols = np.array([c for c in range(len(self.dofs)) if c not in set(grouped)], dtype=int)
        k = len(self.free_cols)
        for g, cols, outs in slots:
            self.groups.append(GroupSlot(g, cols, outs, slice(k, k + g.nangles), hasattr(g.driver, "batch")))
            k += g.nangles
        self.sample_dims = k

    @classmethod
    def to_site(cls, figure: Figure, start_joint: str, segment: str, site: str, coupled: bool = True) -> Chain:
        """The chain from ``start_joint`` to the origin of ``segment.site``."""
        return cls(figure, start_joint, segment, figure.site_location(segment, site)[:3, 3].copy(), coupled)

    @property
    def lower(self) -> np.ndarray:
        return self.figure.lower[self.dofs]

    @property
    def upper(self) -> np.ndarray:
        return self.figure.upper[self.dofs]

    def screws(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Reference-posture data: (signed world axes (n,3), origins (n,3), rotational mask (n,),
        reference values q0 (n,), reference point p0 (3,), world metres)."""
        f = self.figure
        kin = f.kinematics()
        q0 = f.q
        fk = kin.forward(q0, f.location)
        w = fk.segments[kin.segment_index[self.end_segment]]
        p0 = w[:3, :3] @ self.point + w[:3, 3]
        axes = fk.dof_axes[self.dofs] * kin.dof_sign[self.dofs, None]
        rot = np.isin(self.dofs, kin.rot_dofs)
        return axes, fk.dof_origins[self.dofs], rot, q0[self.dofs], p0

    def sampler(self, step: float = 0.0, max_driver_calls: int = 4096) -> _Sampler:
        """Maps unit samples (N, :attr:`sample_dims`) to chain DOF values; ``step`` (radians) is the
        wanted grid step of drivers without ``batch`` (0: the coarsest, ``max_driver_calls`` points)."""
        return _Sampler(self, step, max_driver_calls)

    def sample(self, u: np.ndarray) -> ChainSample:
        """Chain DOF values for unit samples ``u`` (N, :attr:`sample_dims`); samples outside a
        group's linear limits are dropped."""
        return self.sampler()(u)

    def points(self, values: np.ndarray) -> np.ndarray:
        """World reference points (N,3) for chain DOF values (N,n) (radians/metres)."""
        axes, origins, rot, q0, p0 = self.screws()
        return _poe_points(axes, origins, rot, np.asarray(values, dtype=float) - q0, p0)

    def base_and_reach(self) -> tuple[np.ndarray, float]:
        """The first DOF's origin (world) and an upper bound on the reference point's distance from
        it (the sum of the distances along the chain), metres."""
        _, origins, _, _, p0 = self.screws()
        pts = np.vstack([origins, p0])
        return origins[0].copy(), float(np.linalg.norm(np.diff(pts, axis=0), axis=1).sum())


class _Sampler:
    """Unit cube -> feasible chain values (free DOFs in their limits, groups through their drivers)."""

    def __init__(self, chain: Chain, step: float, max_driver_calls: int) -> None:
        self.chain = chain
        self.lo, self.hi = chain.lower, chain.upper
        self.q0 = chain.figure.q[chain.dofs]
        self.grids: dict[str, tuple[list[np.ndarray], np.ndarray, np.ndarray]] = {}
        for slot in chain.groups:
            if slot.batched:
                continue
            g = slot.group
            span = g.upper - g.lower
            cap = max(2, int(np.floor(max(max_driver_calls, 2) ** (1.0 / g.nangles) + 1e-9)))
            levels = [int(min(cap, max(2, np.ceil(sp / step) + 1 if step > 0 else cap))) for sp in span]
            axes = [np.linspace(lo, hi, n) for lo, hi, n in zip(g.lower, g.upper, levels)]
            size = int(np.prod(levels))
            self.grids[g.name] = (axes, np.full((size, slot.outs.size), np.nan), np.array(levels))
        #: driver calls made on snapped grids (drivers without ``batch``)
        self.driver_calls = 0

    def __call__(self, u: np.ndarray) -> ChainSample:
        c = self.chain
        u = np.atleast_2d(np.asarray(u, dtype=float))
        values = np.tile(self.q0, (len(u), 1))
        f = c.free_cols
        values[:, f] = self.lo[f] + u[:, :f.size] * (self.hi[f] - self.lo[f])
        ok = np.ones(len(u), dtype=bool)
        angles = {}
        for slot in c.groups:
            g = slot.group
            us = u[:, slot.dims]
            if slot.batched:
                theta = g.lower + us * (g.upper - g.lower)
                ok &= g.feasible_rows(theta)
                values[:, slot.cols] = driver_batch(g.driver, theta)[:, slot.outs]
            else:
                axes, table, levels = self.grids[g.name]
                idx = np.rint(us * (levels - 1)).astype(np.int64)
                theta = np.stack([ax[i] for ax, i in zip(axes, idx.T)], axis=1)
                ok &= g.feasible_rows(theta)
                code = np.ravel_multi_index(tuple(idx.T), tuple(levels))
                missing = np.unique(code[ok & np.isnan(table[code, 0])])
                if missing.size:
                    grid_idx = np.stack(np.unravel_index(missing, tuple(levels)), axis=1)
                    table[missing] = driver_batch(g.driver, np.stack(
                        [ax[i] for ax, i in zip(axes, grid_idx.T)], axis=1))[:, slot.outs]
                    self.driver_calls += int(missing.size)
                values[:, slot.cols] = np.where(ok[:, None], table[code], values[:, slot.cols])
            angles[g.name] = theta
            # a driver may carry a member past its own joint's limits (the shoulder's twist
            # member is its first angle minus the elevation): such samples are not postures
            cols = slot.cols
            ok &= np.all((values[:, cols] >= c.lower[cols] - 1e-12)
                         & (values[:, cols] <= c.upper[cols] + 1e-12), axis=1)
        return ChainSample(values[ok], {k: v[ok] for k, v in angles.items()})


def _poe_points(axes: np.ndarray, origins: np.ndarray, rot: np.ndarray, delta: np.ndarray,
                p0: np.ndarray) -> np.ndarray:
    d_all = np.ascontiguousarray(np.asarray(delta, dtype=float).T)  # (n, N): one row per DOF
    count = d_all.shape[1]
    px, py, pz = (np.full(count, c) for c in p0)
    for i in range(len(axes) - 1, -1, -1):  # distal first, so proximal transforms act last
        d = d_all[i]
        ax, ay, az = axes[i]
        if not rot[i]:
            px, py, pz = px + d * ax, py + d * ay, pz + d * az
            continue
        ox, oy, oz = origins[i]
        vx, vy, vz = px - ox, py - oy, pz - oz
        c, s = np.cos(d), np.sin(d)
        k = (vx * ax + vy * ay + vz * az) * (1.0 - c)
        px = ox + vx * c + (ay * vz - az * vy) * s + ax * k
        py = oy + vy * c + (az * vx - ax * vz) * s + ay * k
        pz = oz + vz * c + (ax * vy - ay * vx) * s + az * k
    return np.stack([px, py, pz], axis=1)


@dataclass
class Progress:
    """Progress report: samples drawn so far, the sample cap, voxels marked."""

    samples: int
    max_samples: int
    marked: int


@dataclass
class Workspace:
    """Voxels reached by a chain's reference point: ``occupied[i, j, k]`` covers the world box from
    ``origin + cell * (i, j, k)`` to ``+ cell`` (metres)."""

    occupied: np.ndarray
    origin: np.ndarray
    cell: float
    samples: int
    converged: bool
    cancelled: bool

    @property
    def resolution(self) -> int:
        return int(self.occupied.shape[0])

    def volume(self) -> float:
        """Marked volume (m^3)."""
        return float(self.occupied.sum()) * self.cell ** 3

    def _index(self, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        idx = np.floor((np.atleast_2d(points) - self.origin) / self.cell).astype(np.int64)
        ok = np.all((idx >= 0) & (idx < np.array(self.occupied.shape)), axis=1)
        return idx, ok

    def contains(self, points: np.ndarray) -> np.ndarray:
        """Whether each world point (N,3) lies in a marked voxel."""
        idx, ok = self._index(points)
        out = np.zeros(len(idx), dtype=bool)
        out[ok] = self.occupied[tuple(idx[ok].T)]
        return out

    def distance(self, points: np.ndarray) -> np.ndarray:
        """Distance (metres) from each world point (N,3) to the nearest marked voxel centre, 0 for
        points inside marked voxels; ``inf`` when nothing is marked."""
        from scipy.spatial import cKDTree

        pts = np.atleast_2d(points)
        cells = np.argwhere(self.occupied)
        if len(cells) == 0:
            return np.full(len(pts), np.inf)
        d, _ = cKDTree(self.origin + (cells + 0.5) * self.cell).query(pts)
        return np.where(self.contains(pts), 0.0, d)

    def remove_solids(self, meshes: list[Mesh]) -> int:
        """Unmark the voxels whose centre lies inside one of the closed world ``meshes`` (the
        workplace's objects: a hand there would be inside a desk, issue 16); meshes that do not
        enclose a volume are skipped. Returns the count of voxels unmarked."""
        import trimesh

        cells = np.argwhere(self.occupied)
        if not len(cells):
            return 0
        centres = self.origin + (cells + 0.5) * self.cell
        inside = np.zeros(len(cells), dtype=bool)
        for m in meshes:
            tm = trimesh.Trimesh(m.vertices, m.faces, process=True)
            if not tm.is_watertight:
                continue
            lo, hi = tm.bounds
            near = np.all((centres >= lo) & (centres <= hi), axis=1) & ~inside
            if np.any(near):
                inside[np.flatnonzero(near)[tm.contains(centres[near])]] = True
        self.occupied[tuple(cells[inside].T)] = False
        return int(inside.sum())

    def classify(self, sites: dict[str, np.ndarray]) -> dict[str, tuple[bool, float]]:
        """``name -> (inside, distance to the workspace in metres)`` for named world points."""
        names = list(sites)
        if not names:
            return {}
        pts = np.array([sites[n] for n in names], dtype=float)
        inside, dist = self.contains(pts), self.distance(pts)
        return {n: (bool(i), float(d)) for n, i, d in zip(names, inside, dist)}

    def surface(self, smooth: float = 1.0) -> Mesh:
        """A closed surface around the marked voxels (world metres) by surface nets on the occupancy,
        Gaussian-smoothed by ``smooth`` voxels first (0: none; smoothing avoids the non-manifold
        edges of voxel corners touching diagonally), for translucent display."""
        field = self.occupied.astype(float)
        if smooth > 0:
            from scipy.ndimage import gaussian_filter

            field = gaussian_filter(field, smooth, mode="constant")
        return surface_nets(field, 0.5, self.cell, self.origin + 0.5 * self.cell)


def reachable_workspace(chain: Chain, resolution: int = 64, max_samples: int = 4_000_000,
                        batch: int = 1 << 16, tol: float = 2e-3, seed: int = 0, fill_gaps: int = 8,
                        progress: Callable[[Progress], bool | None] | None = None,
                        max_driver_calls: int = 4096) -> Workspace:
    """Sample ``chain`` into a ``resolution``³ grid spanning its reach sphere (see the module docstring).

    ``progress`` is called after every batch; returning ``False`` cancels (the result so far comes
    back with ``cancelled=True``). Sampling stops early when a batch marks fewer than ``tol`` times
    the marked count of new voxels (``converged=True``). Afterwards, enclosed empty pockets of at
    most ``fill_gaps`` voxels (6-connected, not touching the grid's border) are marked: they are
    sampling misses, far smaller than a real void of a human chain (0 keeps every pocket).
    ``samples`` counts drawn samples, those rejected by a group's linear limits included;
    ``max_driver_calls`` caps the grid of a group driver without ``batch`` (module docstring)."""
    if resolution < 2:
        raise ValueError(f"workspace resolution must be at least 2, not {resolution}")
    axes, origins, rot, q0, p0 = chain.screws()
    centre, reach = chain.base_and_reach()
    cell = 2.0 * reach / resolution * (1.0 + 1e-9) or 1e-3
    origin = centre - 0.5 * resolution * cell
    occupied = np.zeros((resolution,) * 3, dtype=bool)
    n = chain.sample_dims
    sampler = chain.sampler(step=cell / max(reach, 1e-9), max_driver_calls=max_driver_calls)
    batch = 1 << max(int(np.ceil(np.log2(max(batch, 2)))), 1)  # Sobol balance needs powers of two
    sobol = qmc.Sobol(d=max(n, 1), scramble=True, seed=seed)
    samples, marked, converged, cancelled = 0, 0, False, False
    while samples < max_samples:
        m = min(batch, max_samples - samples)
        u = sobol.random(batch)[:m, :n]
        pts = _poe_points(axes, origins, rot, sampler(u).values - q0, p0)
        idx = np.floor((pts - origin) / cell).astype(np.int64)
        np.clip(idx, 0, resolution - 1, out=idx)
        occupied[idx[:, 0], idx[:, 1], idx[:, 2]] = True
        samples += m
        now = int(np.count_nonzero(occupied))
        new, marked = now - marked, now
        if progress is not None and progress(Progress(samples, max_samples, marked)) is False:
            cancelled = True
            break
        if samples > batch and new < tol * marked:
            converged = True
            break
    if fill_gaps > 0:
        _fill_small_pockets(occupied, fill_gaps)
    return Workspace(occupied, origin, cell, samples, converged, cancelled)


def _fill_small_pockets(occupied: np.ndarray, max_cells: int) -> None:
    from scipy import ndimage

    labels, count = ndimage.label(~occupied)
    if count == 0:
        return
    sizes = np.bincount(labels.ravel(), minlength=count + 1)
    border = np.unique(np.concatenate([labels[[0, -1]].ravel(), labels[:, [0, -1]].ravel(),
                                       labels[:, :, [0, -1]].ravel()]))
    small = sizes <= max_cells
    small[0] = False
    small[border] = False
    occupied[small[labels]] = True
