"""What ``jackpy ergo`` and ``jackpy analyze`` read: the figure from a scene, the task from a file."""

from __future__ import annotations

from pathlib import Path

from jackpy.ergonomics.base import ErgonomicsError, Task
from jackpy.errors import SessionError
from jackpy.peabody.model import Figure


def load_task(path: str | None, load_kg: float | None = None) -> Task:
    """The task of the JSON file at ``path`` (default: :class:`Task()`), ``load_kg`` replacing its load.
    Errors name the file (and line:column for bad JSON)."""
    from jackpy import jsonfile

    task = Task()
    if path is not None:
        try:
            data = jsonfile.load(Path(path), ErgonomicsError)
        except FileNotFoundError:
            raise ErgonomicsError(f"{path}: no such task file") from None
        except OSError as exc:
            raise ErgonomicsError(f"{path}: cannot read the task file: {exc.strerror or exc}") from None
        try:
            task = Task.from_dict(data)
        except ErgonomicsError as exc:
            raise ErgonomicsError(f"{path}: {exc}") from None
    if load_kg is not None:
        task.load_kg = load_kg
        task.validate()
    from jackpy.ergonomics.niosh import validate_lifts

    try:
        validate_lifts(task)
    except ErgonomicsError as exc:
        raise ErgonomicsError(f"{path}: {exc}" if path else str(exc)) from None
    return task


def is_human(figure: Figure) -> bool:
    return getattr(figure, "body_spec", None) is not None


def figure_from_scene(path: str, name: str | None, human: str = "male:50") -> Figure:
    """The figure to assess: from a session (``.env``: the named figure, default the only standard
    human, as posed), a workplace scene (``.json``: a standard human of size ``human`` (``SEX:PCT``)
    named ``name`` standing where the scene says, neutral posture) or ``-`` (that human on an empty
    floor at the origin)."""
    p = Path(path)
    if path == "-" or p.suffix.lower() == ".json":
        from jackpy.analysis.report import parse_figures
        from jackpy.body import make_human

        sizes = parse_figures(human)
        if len(sizes) != 1:
            raise ErgonomicsError(f"--human: give one size (SEX:PCT), not {human!r}")
        fig = make_human(*sizes[0], name=name)
        if path != "-":
            from jackpy.scene.workplace import load_workplace, stand_figure

            stand_figure(fig, load_workplace(p).stand)
        return fig
    import jackpy.body  # noqa: F401  (registers the standard human's joint-group kinds for reading)
    from jackpy.document.session import load_session

    env, _ = load_session(p)
    humans = [f for f in env.figures.values() if is_human(f)]
    if name is not None:
        if name not in env.figures:
            raise SessionError(f"{p}: no figure {name!r} (figures: {', '.join(sorted(env.figures)) or 'none'})")
        fig = env.figures[name]
        if not is_human(fig):
            raise ErgonomicsError(f"{p}: figure {name!r} is not a standard human; the assessments measure those")
        return fig
    if len(humans) != 1:
        names = ", ".join(sorted(f.name for f in humans)) or "none"
        raise ErgonomicsError(f"{p}: {len(humans)} standard humans ({names}); choose one with --figure NAME")
    return humans[0]
