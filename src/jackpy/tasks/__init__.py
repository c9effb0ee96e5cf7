"""Task-level commands (reach, look, turn, put …) scripted, timed by Fitts' law and compiled to the
motion timeline ([SH6] ch. 6; docs/tasks.md)."""
