"""The scene document: the headless owner of the user's work (environment, behavior loops, goals,
settings, undo, file, timeline) and its step (timeline → goals → behaviors → IK → FK → analyses).

Nothing here imports :mod:`jackpy.ui`; the window's app holds a :class:`Document`.
"""

from jackpy.document.document import Document, DocumentState, StepStats, solve_goals
from jackpy.document.goals import EYES, GoalEntry, new_goal, placeable_kinds
from jackpy.document.settings import Settings

__all__ = ["EYES", "Document", "DocumentState", "GoalEntry", "Settings", "StepStats", "new_goal",
           "placeable_kinds", "solve_goals"]
