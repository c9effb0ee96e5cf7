"""Reading mesh and CAD files safely: limits, declared counts, contained references, true units.

One function, :func:`read_mesh_file`, reads OBJ, STL, PLY, OFF, glTF/GLB, 3MF, COLLADA and STEP
into a :class:`~jackpy.peabody.geometry.Mesh` through trimesh (STEP through ``cascadio``), after
checks that turn hostile or broken files into one-line errors in well under two seconds:

- a regular file (a FIFO or device is refused without opening it), at most ``limit`` bytes;
- counts a header declares (binary STL triangles, PLY and OFF elements) must fit in the file;
- zip containers (3MF) at most :data:`MAX_UNZIPPED_BYTES` unpacked and at most
  :data:`MAX_ZIP_RATIO` times their packed size (a zip bomb is refused before unpacking);
- files a glTF names (buffers, images) must be regular files in the glTF's folder;
- OBJ ``v`` records finite and in range, ``f`` indices naming existing vertices (file:line:col);
- every vertex finite and within range, every face index valid.

Units. :data:`DECLARED_UNITS` formats say their own unit and are returned **in metres** (glTF is
metres by specification; 3MF has a ``unit`` attribute, millimetres by default; COLLADA a
``<unit meter=...>``; STEP is converted to metres by OpenCascade); the others carry no unit and
are returned in file units, to be scaled by the caller.
"""

from __future__ import annotations

import contextlib
import json
import os
import re
import struct
import tempfile
import zipfile
from collections.abc import Iterator
from pathlib import Path

import numpy as np

from jackpy.errors import ImportCADError
from jackpy.peabody.geometry import Mesh
from jackpy.peabody.lexer import MAX_MAGNITUDE, MAX_TEXT
from jackpy.peabody.paths import MAX_MESH_BYTES, regular_file_size

#: largest unpacked content of a zip container (3MF), bytes, and largest unpack ratio
MAX_UNZIPPED_BYTES = 512 * 2**20
MAX_ZIP_RATIO = 200
#: formats whose files declare their unit; :func:`read_mesh_file` returns them in metres
DECLARED_UNITS = frozenset(["gltf", "glb", "3mf", "dae", "step"])
#: metres per 3MF unit name (3MF core specification, ``model@unit``)
_3MF_UNITS = {"micron": 1e-6, "millimeter": 1e-3, "centimeter": 1e-2, "inch": 0.0254, "foot": 0.3048,
              "meter": 1.0}


def read_mesh_file(path: str | os.PathLike[str], kind: str, limit: int = MAX_MESH_BYTES) -> Mesh:
    """The triangles of a mesh file (all parts concatenated, scene transforms applied).

    ``kind`` is the format (``obj``, ``stl``, ``ply``, ``off``, ``gltf``, ``glb``, ``3mf``, ``dae``,
    ``step``). Vertices are in metres for :data:`DECLARED_UNITS` formats, else in file units.
    Raises ImportCADError naming the file and what is wrong with it (ParseError at a line and
    column for OBJ records); OSError when the file is missing, not regular or too large.
    """
    p = Path(path)
    size = regular_file_size(p, limit)
    scale = 1.0
    if kind == "stl":
        _check_stl(p, size)
    elif kind == "ply":
        _check_ply(p, size)
    elif kind == "off":
        _check_off(p, size)
    elif kind == "obj":
        from jackpy.peabody.psurf_io import check_obj_text

        check_obj_text(_text(p), str(p))
    elif kind == "3mf":
        scale = _check_3mf(p, size)
    elif kind in ("gltf", "glb"):
        _check_gltf(p, kind)
    elif kind == "dae":
        scale = _dae_scale(p)
    if kind == "step":
        vertices, faces = _load_step(p)
    else:
        vertices, faces = _load_trimesh(p, kind)
    if faces.ndim != 2 or faces.shape[1] != 3 or len(faces) == 0:
        raise ImportCADError(f"{p}: no triangles found in the {kind.upper()} file")
    if not np.all(np.isfinite(vertices)) or np.abs(vertices).max() > MAX_MAGNITUDE:
        raise ImportCADError(f"{p}: vertex coordinates are not finite numbers of at most {MAX_TEXT}")
    if faces.min() < 0 or faces.max() >= len(vertices):
        raise ImportCADError(f"{p}: a face refers to a vertex that does not exist")
    return Mesh(vertices * scale, faces)


def _load_trimesh(p: Path, kind: str) -> tuple[np.ndarray, np.ndarray]:
    import trimesh

    try:
        with _quiet():
            loaded = trimesh.load(str(p), file_type=kind, force="mesh", process=False)
    except ImportCADError:
        raise
    except Exception as exc:  # trimesh and its readers raise anything on malformed input
        raise ImportCADError(f"{p}: cannot read {kind.upper()} file: {_one_line(exc)}") from None
    try:
        vertices = np.asarray(getattr(loaded, "vertices", np.zeros((0, 3))), dtype=float)
        faces = np.asarray(getattr(loaded, "faces", np.zeros((0, 3))))
    except (TypeError, ValueError) as exc:
        raise ImportCADError(f"{p}: cannot read {kind.upper()} file: {_one_line(exc)}") from None
    if vertices.size and (vertices.ndim != 2 or vertices.shape[1] != 3):
        raise ImportCADError(f"{p}: the {kind.upper()} file's vertices are not 3-D points")
    if faces.size and not np.issubdtype(faces.dtype, np.integer):
        raise ImportCADError(f"{p}: face indices are not integers")
    return vertices.reshape(-1, 3), faces.astype(np.int64) if faces.size else np.zeros((0, 3), np.int64)


def _load_step(p: Path) -> tuple[np.ndarray, np.ndarray]:
    """STEP through OpenCascade (``cascadio``) to a temporary GLB (metres), its output silenced."""
    head = p.open("rb").read(64)
    if not head.lstrip().startswith(b"ISO-10303-21"):
        raise ImportCADError(f"{p}: not a STEP file (it must begin with 'ISO-10303-21;')")
    import cascadio

    with tempfile.TemporaryDirectory(prefix="jackpy-step-") as tmp:
        glb = Path(tmp) / "converted.glb"
        try:
            with _quiet():
                status = cascadio.step_to_glb(str(p), str(glb), tol_linear=0.01, tol_angular=0.5,
                                              tol_relative=False, merge_primitives=True)
        except Exception as exc:
            raise ImportCADError(f"{p}: cannot read STEP file: {_one_line(exc)}") from None
        if status not in (0, None) or not glb.is_file() or glb.stat().st_size == 0:
            raise ImportCADError(f"{p}: cannot read STEP file: OpenCascade found no shapes in it "
                                 "(is it a valid STEP AP203/AP214 file with solids or surfaces?)")
        vertices, faces = _load_trimesh(glb, "glb")
    return vertices, faces


@contextlib.contextmanager
def _quiet() -> Iterator[None]:
    """Silence what C++ libraries (OpenCascade) print on the process's stdout and stderr."""
    try:
        saved = [os.dup(1), os.dup(2)]
    except OSError:
        yield
        return
    with open(os.devnull, "wb") as null:
        try:
            os.dup2(null.fileno(), 1)
            os.dup2(null.fileno(), 2)
            yield
        finally:
            os.dup2(saved[0], 1)
            os.dup2(saved[1], 2)
            os.close(saved[0])
            os.close(saved[1])


def _text(p: Path) -> str:
    data = p.read_bytes()
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        return data.decode("latin-1")


def _head(p: Path, n: int = 4096) -> bytes:
    with p.open("rb") as f:
        return f.read(n)


def _check_stl(p: Path, size: int) -> None:
    """A binary STL's declared triangle count must match its size; ASCII STL must be ASCII text."""
    head = _head(p, 84)
    if size >= 84:
        count = struct.unpack("<I", head[80:84])[0]
        if size == 84 + 50 * count:
            return  # a consistent binary STL
    if head.lstrip().lower().startswith(b"solid"):
        data = p.read_bytes()
        if not data.isascii():
            raise ImportCADError(f"{p}: an ASCII STL (it begins with 'solid') with bytes that are not ASCII")
        if b"facet" not in data and b"endsolid" not in data:
            raise ImportCADError(f"{p}: an ASCII STL with no facets")
        return
    if size < 84:
        raise ImportCADError(f"{p}: not an STL file: {size} bytes, shorter than a binary STL header (84)")
    raise ImportCADError(f"{p}: binary STL header declares {count} triangles ({84 + 50 * count} bytes) but "
                         f"the file has {size} bytes (truncated or not an STL file)")


_PLY_ELEMENT = re.compile(rb"^element\s+(\S+)\s+(\d+)\s*$", re.M)


def _check_ply(p: Path, size: int) -> None:
    head = _head(p, 65536)
    if not head.startswith(b"ply"):
        raise ImportCADError(f"{p}: not a PLY file (it must begin with 'ply')")
    end = head.find(b"end_header")
    if end < 0:
        raise ImportCADError(f"{p}: PLY header has no 'end_header' in its first 64 KB")
    body = size - end
    for name, count in _PLY_ELEMENT.findall(head[:end]):
        need = int(count) * (2 if name == b"vertex" else 4)  # at least "0\n" / a byte per field
        if need > body:
            raise ImportCADError(f"{p}: PLY header declares {int(count)} {name.decode('ascii', 'replace')} "
                                 f"elements but the file has {size} bytes (truncated or a false count)")


def _check_off(p: Path, size: int) -> None:
    words = _head(p, 4096).split()
    if not words or not words[0].endswith(b"OFF"):
        raise ImportCADError(f"{p}: not an OFF file (it must begin with 'OFF')")
    counts = words[1:3] if words[0] == b"OFF" else []
    if len(counts) == 2 and all(c.isdigit() for c in counts):
        nv, nf = int(counts[0]), int(counts[1])
        if nv * 6 + nf * 8 > size:
            raise ImportCADError(f"{p}: OFF header declares {nv} vertices and {nf} faces but the file has "
                                 f"{size} bytes (truncated or a false count)")


def _check_3mf(p: Path, size: int) -> float:
    """Refuse zip bombs before unpacking; the model's unit in metres."""
    try:
        with zipfile.ZipFile(p) as z:
            infos = z.infolist()
            unpacked = sum(i.file_size for i in infos)
            packed = sum(i.compress_size for i in infos)
            if unpacked > MAX_UNZIPPED_BYTES or unpacked > MAX_ZIP_RATIO * max(packed, 4096):
                raise ImportCADError(f"{p}: the 3MF container unpacks to {unpacked / 2**20:.0f} MB from "
                                     f"{size / 2**20:.1f} MB (at most {MAX_UNZIPPED_BYTES / 2**20:.0f} MB and "
                                     f"{MAX_ZIP_RATIO}x): refused as a possible zip bomb")
            models = [i for i in infos if i.filename.lower().endswith("3d/3dmodel.model")]
            if not models:
                raise ImportCADError(f"{p}: not a 3MF file (no 3D/3dmodel.model inside)")
            with z.open(models[0]) as f:
                head = f.read(4096)
    except zipfile.BadZipFile as exc:
        raise ImportCADError(f"{p}: not a 3MF file (not a zip container: {exc})") from None
    m = re.search(rb"<(?:\w+:)?model\b[^>]*\bunit\s*=\s*[\"'](\w+)[\"']", head)
    unit = m.group(1).decode("ascii") if m else "millimeter"
    if unit not in _3MF_UNITS:
        raise ImportCADError(f"{p}: unknown 3MF unit {unit!r} (expected one of {', '.join(_3MF_UNITS)})")
    return _3MF_UNITS[unit]


def _dae_scale(p: Path) -> float:
    """COLLADA ``<unit meter="...">`` of the asset (1 when absent), unless trimesh applies it."""
    m = re.search(rb"<unit\b[^>]*\bmeter\s*=\s*[\"']([^\"']+)[\"']", _head(p, 65536))
    if not m:
        return 1.0
    try:
        value = float(m.group(1))
    except ValueError:
        raise ImportCADError(f"{p}: COLLADA <unit meter={m.group(1)!r}> is not a number") from None
    if not (np.isfinite(value) and value > 0):
        raise ImportCADError(f"{p}: COLLADA <unit meter={value}> must be a positive number")
    return value


def _check_gltf(p: Path, kind: str) -> None:
    """Files a glTF names must be regular files inside its folder (never a FIFO, never ../..)."""
    if kind == "glb":
        head = _head(p, 20)
        if len(head) < 20 or head[:4] != b"glTF":
            raise ImportCADError(f"{p}: not a GLB file (it must begin with 'glTF')")
        length, chunk = struct.unpack("<I", head[8:12])[0], struct.unpack("<I", head[12:16])[0]
        if length != p.stat().st_size:
            raise ImportCADError(f"{p}: GLB header declares {length} bytes but the file has {p.stat().st_size}")
        if chunk + 20 > length:
            raise ImportCADError(f"{p}: GLB JSON chunk of {chunk} bytes does not fit in the file")
        with p.open("rb") as f:
            f.seek(20)
            raw = f.read(chunk)
    else:
        raw = p.read_bytes()
    try:
        doc = json.loads(raw.decode("utf-8"))
    except (UnicodeDecodeError, ValueError, RecursionError) as exc:
        raise ImportCADError(f"{p}: the glTF JSON is not valid: {_one_line(exc)}") from None
    if not isinstance(doc, dict):
        raise ImportCADError(f"{p}: the glTF JSON is not an object")
    folder = p.parent.resolve()
    for group in ("buffers", "images"):
        items = doc.get(group, [])
        for k, item in enumerate(items if isinstance(items, list) else []):
            uri = item.get("uri") if isinstance(item, dict) else None
            if not isinstance(uri, str) or uri.startswith("data:"):
                continue
            from urllib.parse import unquote

            ref = (p.parent / unquote(uri))
            real = ref.resolve()
            if "://" in uri or not (real == folder or folder in real.parents):
                raise ImportCADError(f"{p}: {group}[{k}] names {uri[:80]!r}, outside the glTF's folder")
            try:
                regular_file_size(ref, MAX_MESH_BYTES)
            except OSError as exc:
                raise ImportCADError(f"{p}: {group}[{k}] names {uri[:80]!r}: {exc.strerror or exc}") from None


def _one_line(exc: BaseException) -> str:
    text = " ".join(str(exc).split()) or type(exc).__name__
    if isinstance(exc, ModuleNotFoundError):
        text = f"the file is malformed (trimesh needed the missing module {exc.name!r} to go on)"
    return text if len(text) <= 200 else text[:197] + "..."

