"""The task knowledge base: task names to the scene's geometry, resolved at the moment of use, so
a reference follows its object when it moves ([SH6] §6.3.1 "should the cup move, KB resolves its
location"). Holds the controls' current states and the supported-by relations (Kalita's
*maintain*: moving a supporter carries what rests on it)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from jackpy.tasks.semantics import Control, Semantics, TaskError, fold, load

if TYPE_CHECKING:
    from jackpy.peabody.model import Environment


@dataclass(frozen=True)
class Ref:
    """A resolved name: an object's site (``site`` None: the object itself) or an agent."""

    obj: str
    site: str | None = None
    agent: bool = False


class KnowledgeBase:
    """Semantics of the scene's objects plus the agents by name."""

    def __init__(self, env: "Environment", semantics: dict[str, Semantics] | None = None) -> None:
        self.env = env
        self.semantics: dict[str, Semantics] = {}
        self.agents: dict[str, str] = {}
        self.supported_by: dict[str, tuple[str, np.ndarray]] = {}
        self.stands: dict[str, dict] = {}
        for s in (semantics or {}).values():
            self.add(s)

    @classmethod
    def for_scene(cls, env: "Environment", scene_dir: str | Path) -> "KnowledgeBase":
        """Load ``OBJECT.semantics.json`` for every object of ``env`` found in ``scene_dir``, and the
        scene-level sidecar ``scene.semantics.json`` (stands) when present."""
        kb = cls(env)
        d = Path(scene_dir)
        for name in sorted(env.figures):
            p = d / f"{name}.semantics.json"
            if p.exists():
                kb.add(load(p))
        p = d / "scene.semantics.json"
        kb.stands = load(p).stands if p.exists() else {}
        return kb

    def add(self, s: Semantics) -> None:
        """Register an object's semantics and put its sites on the object (``object.site``)."""
        if s.name not in self.env.figures:
            raise TaskError(f"semantics for {s.name!r}, but the scene has no object of that name")
        obj = self.env.figures[s.name]
        for site, pos in s.sites.items():
            if hasattr(obj, "add_site"):
                obj.add_site(site, pos)
        self.semantics[s.name] = s

    def add_agent(self, name: str) -> None:
        self.agents[fold(name)] = name

    # ----- resolution ----------------------------------------------------------------------------
    def resolve(self, name: str) -> Ref:
        """An agent, an object, ``object.site``, or a bare site / alias / control name found in
        exactly one object (``figure.segment.site`` paths of the book's name map drop the segment)."""
        key = fold(name)
        if key in self.agents:
            return Ref(self.agents[key], agent=True)
        parts = key.split(".")
        objs = {fold(n): n for n in self.env.figures if n not in self.agents.values()}
        if len(parts) >= 2 and parts[0] in objs:
            obj = objs[parts[0]]
            site = self._site_of(obj, parts[-1])
            if site is None:
                raise TaskError(f"object {obj!r} has no site {parts[-1]!r}")
            return Ref(obj, site)
        if key in objs:
            return Ref(objs[key])
        hits = [(o, st) for o in sorted(self.semantics) if (st := self._site_of(o, key)) is not None]
        if len(hits) == 1:
            return Ref(*hits[0])
        if len(hits) > 1:
            raise TaskError(f"{name!r} is ambiguous: {', '.join(f'{o}.{s}' for o, s in hits)}")
        raise TaskError(f"nothing in the scene is called {name!r}")

    def _site_of(self, obj: str, key: str) -> str | None:
        s = self.semantics.get(obj)
        if s is None:
            return None
        key = s.aliases.get(key, key)
        if key in s.controls:
            return s.controls[key].site
        return key if key in s.sites else None

    def control(self, name: str) -> tuple[Ref, Control]:
        ref = self.resolve(name)
        s = self.semantics.get(ref.obj)
        if s is not None:
            key = s.aliases.get(fold(name.split(".")[-1]), fold(name.split(".")[-1]))
            if key in s.controls:
                return ref, s.controls[key]
            for c in s.controls.values():
                if c.site == ref.site:
                    return ref, c
        raise TaskError(f"{name!r} is not a control")

    def target(self, ref: Ref) -> dict:
        """The motion-model target of a reference: a point in the object's frame, relative to the
        object (so it follows the object, and needs no site the scene file lacks), or an agent's
        view site."""
        if ref.agent:
            return {"site": f"{ref.obj}.head.view"}
        obj = self.env.figures[ref.obj]
        local = [0.0, 0.0, 0.0] if ref.site is None else obj.user_sites()[ref.site].location[:3, 3].tolist()
        return {"point": [float(v) for v in local], "relative_to": ref.obj}

    def world(self, ref: Ref) -> np.ndarray:
        """World position (m) of a reference now."""
        obj = self.env.figures[ref.obj]
        if ref.agent:
            return obj.site_world("head", "view")[:3, 3]
        if ref.site is None:
            return obj.location[:3, 3].copy()
        return obj.site_position(ref.site)

    # ----- relations ------------------------------------------------------------------------------
    def rest_on(self, obj: str, supporter: str) -> None:
        """``obj`` is supported by ``supporter`` from now on (relative transform frozen)."""
        a, b = self.env.figures[obj], self.env.figures[supporter]
        self.supported_by[obj] = (supporter, np.linalg.inv(b.location) @ a.location)

    def lift(self, obj: str) -> None:
        self.supported_by.pop(obj, None)

    def move_object(self, name: str, location: np.ndarray) -> None:
        """Place object ``name`` at world 4x4 ``location``; what rests on it (transitively) follows."""
        self.env.figures[name].location = np.asarray(location, dtype=float).copy()
        for child, (parent, rel) in list(self.supported_by.items()):
            if parent == name:
                self.move_object(child, self.env.figures[name].location @ rel)
