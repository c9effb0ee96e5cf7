"""The sweep as one call: scene + study + bodies -> per-body table, accommodation table and report.

``population_bodies`` turns the CLI's choice (``n`` Monte Carlo bodies, or a family holding a
share) into bodies; :func:`sweep` runs them and writes everything into the output folder.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from jackpy.population.accommodation import Accommodation
from jackpy.population.evaluate import SweepContext
from jackpy.population.families import family, monte_carlo
from jackpy.population.generate import Body
from jackpy.population.journal import Journal
from jackpy.population.model import DEFAULT_DIMENSIONS, PopulationModel
from jackpy.population.report import write_report
from jackpy.population.study import Study, check_against_scene, load_study
from jackpy.population.sweep import SweepResult, run_sweep
from jackpy.scene.workplace import Workplace, load_workplace


def population_bodies(n: int | None = None, family_share: float | None = None, sex_mix: float = 0.5,
                      seed: int = 0, family_dims: Sequence[str] = ("stature", "weight"),
                      components: int | None = None, dims: Sequence[str] = DEFAULT_DIMENSIONS) -> list[Body]:
    """``n`` Monte Carlo bodies, or (``family_share``) the boundary and centre cases of each sex
    present in the mix (``sex_mix`` 0: men only, 1: women only)."""
    model = PopulationModel.ansur2(tuple(dict.fromkeys(tuple(dims) + tuple(family_dims))))
    if family_share is not None:
        sexes = [s for s, w in (("female", sex_mix), ("male", 1.0 - sex_mix)) if w > 0]
        return family(model, family_share, family_dims, sexes, components=components)
    return monte_carlo(model, 2000 if n is None else n, sex_mix, seed)


def sweep(scene: str | os.PathLike | Workplace, study: str | os.PathLike | Study, bodies: list[Body] | None,
          out: str | os.PathLike, *, workers: int | None = None, client: Any = None, scheduler: str | None = None,
          resume: bool = False, progress: bool = True, description: dict | None = None,
          ) -> tuple[SweepResult, list[Accommodation]]:
    """Run ``study`` in ``scene`` for ``bodies`` (or, with ``resume``, finish the sweep in ``out``)
    on a local pool (``workers``), a Dask ``client`` or a ``scheduler`` address; write the tables and
    the report into ``out``. A KeyboardInterrupt propagates after the finished rows are kept."""
    wp = scene if isinstance(scene, Workplace) else load_workplace(scene)
    st = study if isinstance(study, Study) else load_study(study)
    check_against_scene(st, wp.env)
    if resume:
        bodies = Journal(out).bodies()
    if not bodies:
        raise ValueError("a sweep needs bodies")
    ctx = SweepContext(wp, st).prepare(tuple(sorted({b.sex for b in bodies})))
    manifest = {"scene": str(wp.path) if wp.path else None, "study": st.to_dict(), **(description or {})}
    result = run_sweep(ctx, bodies, out, manifest=manifest, workers=workers, client=client, scheduler=scheduler,
                       resume=resume, progress=progress)
    title = f"Population sweep: {Path(str(wp.path)).name if wp.path else 'scene'}"
    return result, write_report(out, st, result.rows, title, result.complete)
