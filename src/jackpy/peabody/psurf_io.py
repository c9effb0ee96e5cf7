"""Psurf geometry files (``.pss``) and other mesh formats, loaded into :class:`Mesh` (metres).

The ``.pss`` format (jackpy's psurf text, see docs/peabody-format.md) is a polygon mesh in
centimetres in the psurf's own frame, one record per line::

    # a comment (also // to the end of the line)
    v X Y Z              vertex, centimetres
    f I J K [L ...]      polygon: 1-based vertex indices, counter-clockwise seen from outside

Polygons are triangulated as fans on reading (so they should be convex). ``.obj``, ``.stl`` and
``.ply`` files are read through trimesh in centimetres as well (they carry no unit); ``.glb`` and
``.gltf`` are metres, as glTF specifies.
"""

from __future__ import annotations

import hashlib
import os
import threading
from collections import OrderedDict
from pathlib import Path

import numpy as np

from jackpy.atomic import atomic_write_text
from jackpy.errors import ImportCADError, ParseError
from jackpy.peabody.geometry import Mesh
from jackpy.peabody.lexer import MAX_MAGNITUDE, MAX_TEXT
from jackpy.peabody.notation import CM, fmt
from jackpy.peabody.paths import MAX_MESH_BYTES, read_limited

#: mesh file extensions read through trimesh, with the size of one file unit in metres
TRIMESH_UNITS = {".obj": CM, ".stl": CM, ".ply": CM, ".glb": 1.0, ".gltf": 1.0}


def parse_psurf(text: str, filename: str = "<string>") -> Mesh:
    """Parse ``.pss`` text into a triangle mesh in metres; ParseError with line and column."""
    vertices: list[tuple[float, float, float]] = []
    faces: list[tuple[int, int, int]] = []
    # only "\n" ends a line (as an editor counts them; str.splitlines also splits at form feeds,
    # U+2028 and other separators, which would shift every reported line number)
    for lineno, raw in enumerate(text.split("\n"), start=1):
        line = raw
        for marker in ("#", "//"):
            cut = line.find(marker)
            if cut >= 0:
                line = line[:cut]
        fields: list[tuple[str, int]] = []
        pos = 0
        for word in line.split():
            pos = line.index(word, pos)
            fields.append((word, pos + 1))
            pos += len(word)
        if not fields:
            continue
        (key, kcol), args = fields[0], fields[1:]
        if key == "v":
            if len(args) != 3:
                col = args[3][1] if len(args) > 3 else len(line.rstrip()) + 1
                what = "end of line" if len(args) > 3 else "three coordinates (cm)"
                raise ParseError(f"expected {what} after 'v'", filename, lineno, col)
            xyz = []
            for word, col in args:
                try:
                    value = float(word)
                except ValueError:
                    value = float("nan")
                if not np.isfinite(value):
                    raise ParseError(f"expected a coordinate (cm), found {word[:40]!r}", filename, lineno, col)
                if abs(value) > MAX_MAGNITUDE:
                    raise ParseError(f"coordinate {word[:40]} out of range (magnitude at most {MAX_TEXT} cm)",
                                     filename, lineno, col)
                xyz.append(value * CM)
            vertices.append((xyz[0], xyz[1], xyz[2]))
        elif key == "f":
            if len(args) < 3:
                raise ParseError("expected at least 3 vertex indices after 'f'", filename, lineno,
                                 len(line.rstrip()) + 1)
            idx = []
            for word, col in args:
                # (a bounded length first: int() refuses strings of more than 4300 digits)
                if (not (word.isascii() and word.isdigit()) or len(word) > 18
                        or not 1 <= int(word) <= len(vertices)):
                    raise ParseError(f"expected a vertex index in 1..{len(vertices)}, found {word[:40]!r}",
                                     filename, lineno, col)
                idx.append(int(word) - 1)
            faces.extend((idx[0], idx[k], idx[k + 1]) for k in range(1, len(idx) - 1))
        else:
            raise ParseError(f"expected 'v' or 'f', found {key[:40]!r}", filename, lineno, kcol)
    return Mesh(np.array(vertices, dtype=float).reshape(-1, 3), np.array(faces, dtype=np.int64).reshape(-1, 3))


def read_psurf(path: str | os.PathLike[str], limit: int = MAX_MESH_BYTES) -> Mesh:
    """Read a ``.pss`` file (centimetres) into a mesh in metres; text that is not UTF-8 raises
    ParseError at the first bad byte; a file that is not regular or is over ``limit`` bytes
    raises OSError."""
    data = read_limited(path, limit)
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        before = data[:exc.start]
        raise ParseError("expected UTF-8 text", str(path), before.count(b"\n") + 1,
                         exc.start - (before.rfind(b"\n") + 1) + 1) from None
    return parse_psurf(text, str(path))


#: vertices are written rounded to this many decimals of a centimetre (1 micrometre): far below any
#: modelling or scanning accuracy, and it keeps generated bodies' files a third of the size
PSURF_DECIMALS = 4


#: texts of recently written meshes, by a digest of their content: every autosave writes the
#: generated human's surfaces again, and they rarely change (formatting is most of a save's time)
TEXT_CACHE_ENTRIES = 512
_texts: OrderedDict[bytes, str] = OrderedDict()
_texts_lock = threading.Lock()


def psurf_to_text(mesh: Mesh, comment: str | None = None) -> str:
    """``.pss`` text of a mesh (vertices in centimetres to 1e-4 cm, triangles as faces).

    The text of a mesh already written with the same vertices, faces and comment is reused (a
    bounded cache keyed by a BLAKE2 digest of the content, so a mesh changed in place is
    formatted anew)."""
    key = hashlib.blake2b(np.ascontiguousarray(mesh.vertices, dtype=float).tobytes(), digest_size=20)
    key.update(np.ascontiguousarray(mesh.faces, dtype=np.int64).tobytes())
    key.update(str(len(mesh.vertices)).encode() + b"\0" + (comment or "").encode("utf-8", "surrogatepass"))
    digest = key.digest()
    with _texts_lock:
        text = _texts.get(digest)
        if text is not None:
            _texts.move_to_end(digest)
            return text
    text = _format_psurf(mesh, comment)
    with _texts_lock:
        _texts[digest] = text
        while len(_texts) > TEXT_CACHE_ENTRIES:
            _texts.popitem(last=False)
    return text


def _format_psurf(mesh: Mesh, comment: str | None) -> str:
    lines = [f"# {c}" for c in (comment.splitlines() if comment else [])]
    verts = np.round(mesh.vertices / CM, PSURF_DECIMALS)
    lines += ["v " + " ".join(fmt(float(x)) for x in v) for v in verts]
    lines += ["f " + " ".join(str(int(i) + 1) for i in f) for f in mesh.faces]
    return "\n".join(lines) + "\n"


def write_psurf(path: str | os.PathLike[str], mesh: Mesh, comment: str | None = None) -> None:
    """Write a mesh as a ``.pss`` file, atomically."""
    atomic_write_text(path, psurf_to_text(mesh, comment))


def check_obj_text(text: str, filename: str) -> None:
    """Check the records of OBJ text that trimesh passes over silently: every ``v`` coordinate a
    finite number within :data:`MAX_MAGNITUDE`, every ``f`` index a vertex that exists (1-based,
    or negative counting back; 0 is invalid). ParseError at the line and column."""
    count = 0
    for lineno, line in enumerate(text.split("\n"), start=1):
        stripped = line.lstrip()
        if stripped.startswith("v ") or stripped.startswith("v\t"):
            count += 1
            pos = 0
            for word in stripped.split()[1:4]:
                pos = line.index(word, pos)
                try:
                    value = float(word)
                except ValueError:
                    value = float("nan")
                if not (np.isfinite(value) and abs(value) <= MAX_MAGNITUDE):
                    raise ParseError(f"vertex coordinate {word[:40]!r} is not a finite number of at most "
                                     f"{MAX_TEXT}", filename, lineno, pos + 1)
                pos += len(word)
        elif stripped.startswith("f ") or stripped.startswith("f\t"):
            pos = 0
            for word in stripped.split()[1:]:
                pos = line.index(word, pos)
                head = word.split("/", 1)[0]
                ok = head.lstrip("-").isdigit() and len(head) < 19
                k = int(head) if ok else 0
                if not ok or k == 0 or k > count or k < -count:
                    raise ParseError(f"face refers to vertex {head[:40]!r}; this file has {count} vertices so far "
                                     f"(indices 1..{count}, or -1..-{count})", filename, lineno, pos + 1)
                pos += len(word)


def load_mesh(path: str | os.PathLike[str], limit: int = MAX_MESH_BYTES) -> Mesh:
    """Load geometry by extension: ``.pss`` (cm), ``.obj``/``.stl``/``.ply`` (cm) or ``.glb``/``.gltf`` (m).

    The result is in metres. A malformed ``.pss`` raises ParseError; a file trimesh cannot read
    raises ImportCADError; a missing file raises FileNotFoundError.
    """
    p = Path(path)
    ext = p.suffix.lower()
    if ext == ".pss":
        return read_psurf(p, limit)
    if ext not in TRIMESH_UNITS:
        raise ImportCADError(f"{p}: unknown geometry format {ext!r} (use .pss, "
                             + ", ".join(TRIMESH_UNITS) + ")")
    from jackpy.peabody.meshfile import read_mesh_file

    mesh = read_mesh_file(p, ext[1:], limit)  # (checked: regular file, size, counts, finite, indices)
    return Mesh(mesh.vertices * TRIMESH_UNITS[ext], mesh.faces)
