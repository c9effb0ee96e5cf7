"""The one exception family of jackpy.

Every error a user can cause by bad input derives from :class:`JackpyError`; the CLI prints its
message on one line and exits non-zero instead of showing a traceback.
"""

from __future__ import annotations


class JackpyError(Exception):
    """Base class of every error jackpy raises on purpose."""

    exit_code: int = 1


class ParseError(JackpyError):
    """Malformed text in a file: carries file, line and column (1-based) and what was expected.

    ``line = 0`` means no position applies (a schema error in a JSON file names its key path
    instead); the message is then ``file: message``.
    """

    exit_code = 2

    def __init__(self, message: str, file: str = "<string>", line: int = 0, column: int = 0) -> None:
        self.file = file
        self.line = line
        self.column = column
        self.message = message
        super().__init__(f"{file}:{line}:{column}: {message}" if line > 0 else f"{file}: {message}")


class FigureError(JackpyError):
    """A semantically invalid figure: names the figure, segment, site or joint at fault."""

    exit_code = 2


class DeviceError(JackpyError):
    """A device problem: says which port and what the device answered (or that it did not)."""

    def __init__(self, message: str, port: str | None = None) -> None:
        self.port = port
        super().__init__(f"{port}: {message}" if port else message)


class ImportCADError(JackpyError):
    """A CAD file that could not be imported (format, units, malformed content)."""

    exit_code = 2


class SessionError(JackpyError):
    """A session/scene file that could not be read or written."""

    exit_code = 2
