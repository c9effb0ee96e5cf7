"""Ascension Flock of Birds RS-232 protocol: constants, command frames, record encoding/decoding.

Everything here is pure (no I/O). Device units are kept at this level: positions in inches,
angles in degrees, both in the *transmitter frame* (x forward, y right, z down). Conversion to
jackpy's metres/radians/y-up world happens in :mod:`jackpy.devices.sensors`.

Record words: each 16-bit word travels LS byte then MS byte, only its top 14 bits carry data and
bit 7 of every byte is the phasing bit (set only on the first byte of a record). See
``shared/spec/flock-of-birds-protocol.md`` §3.
"""

from __future__ import annotations

import enum
import re
import struct
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from jackpy.errors import DeviceError

# --- command bytes (host -> bird), spec §2.1 -------------------------------------------------
POINT = 0x42
STREAM = 0x40
STREAM_STOP = 0x3F
RUN = 0x46
SLEEP = 0x47
FBB_RESET = 0x2F
NEXT_TRANSMITTER = 0x30
HEMISPHERE = 0x4C
ANGLE_ALIGN1 = 0x4A
ANGLE_ALIGN2 = 0x71
REFERENCE_FRAME1 = 0x48
REFERENCE_FRAME2 = 0x72
BORESIGHT = 0x75
BORESIGHT_REMOVE = 0x76
OFFSET = 0x4B
BUTTON_MODE = 0x4D
BUTTON_READ = 0x4E
METAL = 0x73
METAL_ERROR = 0x74
SYNC = 0x41
XON = 0x11
XOFF = 0x13
CHANGE_VALUE = 0x50
EXAMINE_VALUE = 0x4F
REPORT_RATE = {1: 0x51, 2: 0x52, 8: 0x53, 32: 0x54}

#: Data bytes that follow each command byte (CHANGE VALUE is variable: see CHANGE_LENGTH).
COMMAND_DATA_LENGTH: dict[int, int] = {
    0x56: 0, 0x57: 0, 0x58: 0, 0x59: 0, 0x5A: 0, 0x5C: 0, 0x5D: 0,
    POINT: 0, STREAM: 0, STREAM_STOP: 0, RUN: 0, SLEEP: 0, FBB_RESET: 0,
    0x51: 0, 0x52: 0, 0x53: 0, 0x54: 0, NEXT_TRANSMITTER: 1, HEMISPHERE: 2,
    ANGLE_ALIGN1: 12, ANGLE_ALIGN2: 6, REFERENCE_FRAME1: 12, REFERENCE_FRAME2: 6,
    BORESIGHT: 0, BORESIGHT_REMOVE: 0, OFFSET: 6, BUTTON_MODE: 1, BUTTON_READ: 0,
    METAL: 2, METAL_ERROR: 0, SYNC: 1, XON: 0, XOFF: 0, EXAMINE_VALUE: 1,
}

# --- parameters (CHANGE / EXAMINE VALUE), spec §2.3 -------------------------------------------
P_STATUS = 0
P_REVISION = 1
P_CRYSTAL = 2
P_POSITION_SCALING = 3
P_FILTER = 4
P_RATE_COUNT = 6
P_MEASUREMENT_RATE = 7
P_ERROR_CODE = 10
P_MODEL_ID = 15
P_EXPANDED_ERROR = 16
P_ADDRESSING_MODE = 19
P_FBB_ADDRESS = 21
P_HEMISPHERE = 22
P_REPORT_RATE = 29
P_GROUP_MODE = 35
P_SYSTEM_STATUS = 36
P_AUTO_CONFIG = 50

#: Total bytes of a CHANGE VALUE frame (``P``, param, value bytes) per parameter.
CHANGE_LENGTH: dict[int, int] = {
    3: 4, 4: 4, 5: 16, 6: 4, 7: 4, 8: 3, 9: 3, 11: 3, 12: 16, 13: 16, 14: 3, 17: 3, 18: 3,
    20: 3, 22: 4, 23: 8, 24: 8, 28: 12, 29: 3, 32: 4, 35: 3, 50: 3,
}
#: Reply length (bytes, raw, no phasing) of EXAMINE VALUE per parameter (normal addressing).
EXAMINE_LENGTH: dict[int, int] = {
    0: 2, 1: 2, 2: 2, 3: 2, 4: 2, 5: 14, 6: 2, 7: 2, 8: 1, 9: 1, 10: 1, 11: 1, 12: 14, 13: 14,
    14: 1, 15: 10, 16: 2, 17: 1, 18: 1, 19: 1, 20: 1, 21: 1, 22: 2, 23: 6, 24: 6, 25: 2, 26: 2,
    27: 2, 28: 10, 29: 1, 32: 2, 35: 1, 36: 14, 50: 5,
}

#: Hemisphere name -> the two data bytes of ``L`` (HEMI_AXIS, HEMI_SIGN), spec §2.4.
HEMISPHERES: dict[str, bytes] = {
    "forward": b"\x00\x00", "aft": b"\x00\x01", "upper": b"\x0c\x01",
    "lower": b"\x0c\x00", "left": b"\x06\x01", "right": b"\x06\x00",
}

#: Position full scale in inches: param 3 code 0 / 1, and the Extended Range Transmitter.
POSITION_SCALES = (36.0, 72.0, 144.0)
#: Full scale of every bird in a flock driven by an Extended Range Controller (spec §3.3, §5.4).
ERT_SCALE = 144.0

#: Bits of a FLOCK SYSTEM STATUS byte (param 36, one per FBB address), spec §2.5.
UNIT_ACCESSIBLE = 0x80
UNIT_RUNNING = 0x40
UNIT_HAS_SENSOR = 0x20
UNIT_IS_ERC = 0x10
UNIT_TRANSMITTERS = 0x0F

#: Commands that address one sensor bird (spec §2.2): they need an FBB prefix on a flock and
#: must never reach an ERC. Formats are added below, with :class:`Format`.
SENSOR_COMMANDS = {HEMISPHERE, ANGLE_ALIGN1, ANGLE_ALIGN2, BORESIGHT, BORESIGHT_REMOVE, OFFSET,
                   BUTTON_MODE, BUTTON_READ, METAL, METAL_ERROR}
#: Parameters (CHANGE and EXAMINE VALUE) of one sensor bird, spec §2.2.
SENSOR_PARAMS = {3, 4, 5, 12, 13, 14, 17, 20, 22, 23, 25, 26, 27, 28}

#: Device error codes: code -> (meaning, severity), spec §4.1.
ERROR_CODES: dict[int, tuple[str, str]] = {
    1: ("system RAM failure", "FATAL"), 2: ("non-volatile storage write failure", "FATAL"),
    3: ("PCB EEPROM configuration corrupt", "WARNING1"),
    4: ("transmitter EEPROM corrupt or transmitter not connected", "WARNING1"),
    5: ("sensor EEPROM corrupt or sensor not connected", "WARNING1"),
    6: ("invalid RS232 command", "WARNING2"), 7: ("not an FBB master", "WARNING2"),
    8: ("no birds accessible in device list", "WARNING2"), 9: ("bird not initialized", "WARNING2"),
    10: ("FBB receive error (intra-bird bus)", "WARNING1"),
    11: ("RS232 receive overrun or framing error", "WARNING1"),
    12: ("FBB receive error (host bus)", "WARNING1"), 13: ("no FBB command response", "WARNING1"),
    14: ("invalid FBB host command", "WARNING1"), 15: ("FBB run-time error", "FATAL"),
    16: ("invalid CPU speed", "FATAL"), 17: ("no FBB data", "WARNING1"),
    18: ("illegal baud rate", "WARNING1"), 19: ("slave acknowledge error", "WARNING1"),
    **{c: (f"CPU exception {c}", "FATAL") for c in range(20, 28)},
    28: ("CRT sync lost", "WARNING1"), 29: ("transmitter not accessible", "WARNING1"),
    30: ("ERT not attached to ERC", "WARNING1"), 31: ("CPU time overflow", "WARNING2"),
    32: ("sensor saturated at power-up", "WARNING1"), 33: ("slave configuration error", "WARNING1"),
    34: ("ERC watchdog", "WARNING1"), 35: ("ERC over-temperature", "WARNING1"),
}


def error_text(code: int) -> str:
    """Human text for a device error code, e.g. ``"error 6 (WARNING2): invalid RS232 command"``."""
    meaning, severity = ERROR_CODES.get(code, ("unknown error", "?"))
    return f"error {code} ({severity}): {meaning}"


class Format(enum.IntEnum):
    """Output record formats; the value is the command byte that selects it."""

    POSITION = 0x56
    ANGLES = 0x57
    MATRIX = 0x58
    POSITION_ANGLES = 0x59
    POSITION_MATRIX = 0x5A
    QUATERNION = 0x5C
    POSITION_QUATERNION = 0x5D

    @property
    def has_position(self) -> bool:
        return self in (Format.POSITION, Format.POSITION_ANGLES, Format.POSITION_MATRIX,
                        Format.POSITION_QUATERNION)

    @property
    def orientation_words(self) -> int:
        """Number of orientation words: 0, 3 (angles), 9 (matrix) or 4 (quaternion)."""
        return _ORIENT_WORDS[self]

    @property
    def words(self) -> int:
        return 3 * self.has_position + self.orientation_words

    @property
    def status_code(self) -> int:
        """The format code in the BIRD STATUS word (bits 4..1): command byte − 0x55."""
        return int(self) - 0x55

    @classmethod
    def parse(cls, name: str) -> Format:
        """A format from its name (``position_angles``, ``pos_quat``, ``Y`` ...)."""
        key = name.strip().lower().replace("-", "_").replace("/", "_")
        if len(name) == 1 and ord(name) in cls._value2member_map_:
            return cls(ord(name))
        fmt = _FORMAT_ALIASES.get(key) or cls.__members__.get(key.upper())
        if fmt is None:
            raise DeviceError(f"unknown record format {name!r}; one of "
                              + ", ".join(f.name.lower() for f in cls))
        return fmt


_ORIENT_WORDS = {
    Format.POSITION: 0, Format.ANGLES: 3, Format.MATRIX: 9, Format.POSITION_ANGLES: 3,
    Format.POSITION_MATRIX: 9, Format.QUATERNION: 4, Format.POSITION_QUATERNION: 4,
}

SENSOR_COMMANDS |= {int(f) for f in Format}

_FORMAT_ALIASES = {
    "pos": Format.POSITION, "ang": Format.ANGLES, "mat": Format.MATRIX, "quat": Format.QUATERNION,
    "pos_ang": Format.POSITION_ANGLES, "pos_mat": Format.POSITION_MATRIX,
    "pos_quat": Format.POSITION_QUATERNION,
}

# --- word packing ------------------------------------------------------------------------------

WORD_MAX = 0x7FFC  # largest word a record can carry (14-bit quantisation)
WORD_MIN = -0x8000


def quantise(value: float, full_scale: float) -> int:
    """Value -> signed record word (``value·32768/full_scale`` rounded to the 14-bit grid)."""
    w = int(round(value * 32768.0 / full_scale / 4.0)) * 4
    return max(WORD_MIN, min(WORD_MAX, w))


def pack_words(words: Sequence[int]) -> bytes:
    """Signed 16-bit words -> record bytes (LS, MS each; phasing bit on the first byte)."""
    out = bytearray(2 * len(words))
    for k, w in enumerate(words):
        u = w & 0xFFFF
        out[2 * k] = (u >> 2) & 0x7F
        out[2 * k + 1] = (u >> 9) & 0x7F
    if out:
        out[0] |= 0x80
    return bytes(out)


def unpack_words(data: bytes | bytearray | memoryview, start: int = 0, count: int | None = None) -> tuple[int, ...]:
    """Record bytes -> signed 16-bit words (the two dropped LSBs read as 0)."""
    if count is None:
        count = (len(data) - start) // 2
    out = []
    for k in range(start, start + 2 * count, 2):
        u = ((data[k + 1] & 0x7F) << 9) | ((data[k] & 0x7F) << 2)
        out.append(u - 0x10000 if u & 0x8000 else u)
    return tuple(out)


def s16(value: int) -> bytes:
    """A signed or unsigned 16-bit command word, LS byte first (no phasing)."""
    return (value & 0xFFFF).to_bytes(2, "little")


def u16_le(data: bytes) -> int:
    """An unsigned 16-bit reply or command word, LS byte first."""
    return int.from_bytes(data[:2], "little")


# --- records ---------------------------------------------------------------------------------

@dataclass(frozen=True)
class Record:
    """One decoded data record, in device units and the transmitter frame.

    ``words`` are the signed 16-bit words in transmission order; ``scale`` the position full
    scale in inches (36, 72 or 144). Trailer bytes are ``None`` when the mode is off.
    """

    format: Format
    words: tuple[int, ...]
    scale: float = 36.0
    button: int | None = None
    metal: int | None = None
    address: int | None = None

    @property
    def position(self) -> tuple[float, float, float] | None:
        """Position (x, y, z) in inches, transmitter frame; ``None`` without position words."""
        if not self.format.has_position:
            return None
        k = self.scale / 32768.0
        return (self.words[0] * k, self.words[1] * k, self.words[2] * k)

    def _orient(self) -> tuple[int, ...]:
        return self.words[3:] if self.format.has_position else self.words

    @property
    def angles(self) -> tuple[float, float, float] | None:
        """(azimuth, elevation, roll) in degrees, or ``None`` for other formats."""
        if self.format.orientation_words != 3:
            return None
        return tuple(w * 180.0 / 32768.0 for w in self._orient())  # type: ignore[return-value]

    @property
    def matrix(self) -> np.ndarray | None:
        """The manual's 3×3 matrix M (row i = sensor axis i in transmitter coordinates)."""
        if self.format.orientation_words != 9:
            return None
        return np.array(self._orient(), dtype=float).reshape(3, 3).T / 32768.0

    @property
    def quaternion(self) -> tuple[float, float, float, float] | None:
        """(q0, q1, q2, q3) as transmitted, q0 scalar (read as the rotation M, spec §3.4)."""
        if self.format.orientation_words != 4:
            return None
        return tuple(w / 32768.0 for w in self._orient())  # type: ignore[return-value]

    @property
    def saturated(self) -> bool:
        """All words zero: the sensor is saturated (spec §3.4); the sample is not valid."""
        return self.format.orientation_words in (4, 9) and not any(self.words)

    def rotation(self, conjugate_quaternion: bool = True) -> np.ndarray | None:
        """3×3 rotation R taking sensor-frame vectors into the transmitter frame (R = Mᵀ).

        ``conjugate_quaternion`` is the sign-convention switch of spec §3.4: True (default)
        reads the transmitted quaternion as M, so the sensor orientation is its conjugate.
        """
        n = self.format.orientation_words
        if n == 3:
            a, e, r = np.radians(self.angles)
            return rotation_from_angles(a, e, r)
        if n == 9:
            return self.matrix.T
        if n == 4:
            q = np.array(self.quaternion)
            if conjugate_quaternion:
                q[1:] = -q[1:]
            return quaternion_to_matrix(q)
        return None


def rotation_from_angles(azimuth: float, elevation: float, roll: float) -> np.ndarray:
    """R = Rz(azimuth)·Ry(elevation)·Rx(roll), radians: sensor -> transmitter frame."""
    ca, sa = np.cos(azimuth), np.sin(azimuth)
    ce, se = np.cos(elevation), np.sin(elevation)
    cr, sr = np.cos(roll), np.sin(roll)
    rz = np.array([[ca, -sa, 0], [sa, ca, 0], [0, 0, 1.0]])
    ry = np.array([[ce, 0, se], [0, 1.0, 0], [-se, 0, ce]])
    rx = np.array([[1.0, 0, 0], [0, cr, -sr], [0, sr, cr]])
    return rz @ ry @ rx


def quaternion_to_matrix(q: Sequence[float]) -> np.ndarray:
    """Unit quaternion (w, x, y, z), Hamilton convention -> 3×3 rotation matrix."""
    w, x, y, z = np.asarray(q, dtype=float) / np.linalg.norm(q)
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
    ])


def matrix_to_quaternion(m: np.ndarray) -> np.ndarray:
    """3×3 rotation matrix -> unit quaternion (w, x, y, z) with w ≥ 0 (Shepperd's method)."""
    m = np.asarray(m, dtype=float)
    tr = np.trace(m)
    cands = (tr, m[0, 0], m[1, 1], m[2, 2])
    k = int(np.argmax(cands))
    if k == 0:
        s = 2.0 * np.sqrt(1.0 + tr)
        q = [0.25 * s, (m[2, 1] - m[1, 2]) / s, (m[0, 2] - m[2, 0]) / s, (m[1, 0] - m[0, 1]) / s]
    elif k == 1:
        s = 2.0 * np.sqrt(1.0 + m[0, 0] - m[1, 1] - m[2, 2])
        q = [(m[2, 1] - m[1, 2]) / s, 0.25 * s, (m[0, 1] + m[1, 0]) / s, (m[0, 2] + m[2, 0]) / s]
    elif k == 2:
        s = 2.0 * np.sqrt(1.0 + m[1, 1] - m[0, 0] - m[2, 2])
        q = [(m[0, 2] - m[2, 0]) / s, (m[0, 1] + m[1, 0]) / s, 0.25 * s, (m[1, 2] + m[2, 1]) / s]
    else:
        s = 2.0 * np.sqrt(1.0 + m[2, 2] - m[0, 0] - m[1, 1])
        q = [(m[1, 0] - m[0, 1]) / s, (m[0, 2] + m[2, 0]) / s, (m[1, 2] + m[2, 1]) / s, 0.25 * s]
    q = np.array(q)
    q /= np.linalg.norm(q)
    return -q if q[0] < 0 else q


def make_record(fmt: Format, position: Sequence[float] = (0.0, 0.0, 0.0),
                angles: Sequence[float] = (0.0, 0.0, 0.0), *, scale: float = 36.0,
                button: int | None = None, metal: int | None = None,
                address: int | None = None) -> Record:
    """The record a bird at ``position`` (inches) and ``angles`` (azimuth, elevation, roll in
    degrees) sends in format ``fmt``: matrix and quaternion derived from the same M (spec §3.4)."""
    words: list[int] = []
    if fmt.has_position:
        words += [quantise(p, scale) for p in position]
    n = fmt.orientation_words
    if n == 3:
        words += [quantise(a, 180.0) for a in angles]
    elif n:
        m = rotation_from_angles(*np.radians(angles)).T  # M = Rᵀ
        if n == 9:
            words += [quantise(m[i, j], 1.0) for j in range(3) for i in range(3)]
        else:
            words += [quantise(c, 1.0) for c in matrix_to_quaternion(m)]
    return Record(fmt, tuple(words), scale, button, metal, address)


def encode_record(record: Record, group: bool = False) -> bytes:
    """Record -> bytes as the bird sends it: phased words, then button, metal, group address."""
    out = bytearray(pack_words(record.words))
    for trailer in (record.button, record.metal):
        if trailer is not None:
            out.append(trailer & 0x7F)
    if group:
        if record.address is None or not 1 <= record.address <= 126:
            raise DeviceError(f"group-mode record needs an FBB address 1..126, got {record.address}")
        out.append(record.address)
    return bytes(out)


# --- command frames ----------------------------------------------------------------------------

def fbb_prefix(address: int, addressing: str = "normal") -> bytes:
    """RS232-TO-FBB prefix for ``address`` (spec §2.1); ``addressing`` normal/expanded/super."""
    if addressing == "normal" and 1 <= address <= 15:
        return bytes([0xF0 + address])
    if addressing == "expanded" and 1 <= address <= 30:
        return bytes([0xF0 + address if address <= 15 else 0xE0 + address - 16])
    if addressing == "super" and 1 <= address <= 126:
        return bytes([0xA0, address])
    raise DeviceError(f"FBB address {address} is out of range for {addressing} addressing")


def change_value(param: int, value: bytes) -> bytes:
    """CHANGE VALUE frame ``P param value``; checks the value length against the table."""
    want = CHANGE_LENGTH.get(param)
    if want is None or len(value) != want - 2:
        raise DeviceError(f"CHANGE VALUE parameter {param} with {len(value)} value bytes is not valid")
    return bytes([CHANGE_VALUE, param]) + value


def examine_value(param: int) -> bytes:
    """EXAMINE VALUE frame ``O param``."""
    if param not in EXAMINE_LENGTH:
        raise DeviceError(f"unknown EXAMINE VALUE parameter {param}")
    return bytes([EXAMINE_VALUE, param])


def hemisphere_command(name: str) -> bytes:
    """``L`` frame for a hemisphere name (forward, aft, upper, lower, left, right)."""
    try:
        return bytes([HEMISPHERE]) + HEMISPHERES[name]
    except KeyError:
        raise DeviceError(f"unknown hemisphere {name!r}; one of {', '.join(HEMISPHERES)}") from None


def measurement_rate_value(hz: float) -> bytes:
    """Param 7 value bytes for a measurement rate in Hz (rate × 256, LS first)."""
    if not 10.0 <= hz <= 144.0:
        raise DeviceError(f"measurement rate {hz} Hz is outside 10..144 Hz")
    return s16(int(round(hz * 256)))


def angle_words(azimuth: float, elevation: float, roll: float) -> bytes:
    """Three full 16-bit command angle words (degrees·32768/180), as ANGLE ALIGN2 data."""
    return b"".join(s16(max(-32768, min(32767, int(round(a * 32768 / 180.0)))))
                    for a in (azimuth, elevation, roll))


def decode_revision(reply: bytes) -> str:
    """Param 1 reply -> ``"3.67"`` (first byte integer part, second byte fraction)."""
    return f"{reply[0]}.{reply[1]:02d}"


@dataclass(frozen=True)
class BirdStatus:
    """The BIRD STATUS word (param 0), spec §2.5."""

    word: int

    master = property(lambda self: bool(self.word & 0x8000))
    initialized = property(lambda self: bool(self.word & 0x4000))
    error = property(lambda self: bool(self.word & 0x2000))
    running = property(lambda self: bool(self.word & 0x1000))
    sleeping = property(lambda self: bool(self.word & 0x0020))
    stream = property(lambda self: bool(self.word & 0x0001))

    @property
    def format(self) -> Format | None:
        code = (self.word >> 1) & 0x0F
        try:
            return Format(code + 0x55)
        except ValueError:
            return None


# --- stream decoder ----------------------------------------------------------------------------

@dataclass(frozen=True)
class BirdLayout:
    """What one bird's records look like: format, position scale (in) and trailer modes."""

    format: Format = Format.POSITION_ANGLES
    scale: float = 36.0
    button: bool = False
    metal: bool = False

    def length(self, group: bool) -> int:
        """Record length in bytes (spec §3.2)."""
        return 2 * self.format.words + self.button + self.metal + group


_PHASE = re.compile(rb"[\x80-\xff]")


def _word_table() -> tuple[int, ...]:
    """Signed word for every raw little-endian byte pair (phasing bits ignored)."""
    v = np.arange(65536, dtype=np.int64)
    u = ((v & 0x7F00) << 1) | ((v & 0x7F) << 2)
    return tuple(int(w) for w in np.where(u & 0x8000, u - 0x10000, u))


_WORD = _word_table()


class StreamDecoder:
    """Incremental record parser that frames on the phasing bit (spec §4.2), and counts exactly
    what it could not deliver.

    ``layouts`` maps FBB address -> :class:`BirdLayout`. With ``group=True`` records end with
    the address byte, which is validated against ``layouts``; without it there must be exactly
    one layout and its key labels the records. Never raises on any input.

    Framing: a record starts at a byte with the phasing bit and must hold no other one; in group
    mode it ends with a configured address. A record that follows the previous one directly and
    is the bird due next in the cycle is accepted at once; any other candidate (after a gap of
    stray bytes, or out of turn) waits for the bytes after it: they must start a record, or be
    the remains of the next record without its phasing byte. So a false start inside a garbage
    burst, or the remains of two damaged records read as one, is not delivered; the price is
    that the first record after a fault comes out when the next one starts (at most one cycle
    later), and a record squeezed between two garbage bursts is lost (and counted). A burst whose
    last bytes look exactly like a whole record (probability about 2^-(length-1) per burst, and
    1/256 of that in group mode) is taken for one.

    Counting (``dropped``: records lost; ``skipped_bytes``: stray bytes that belong to no lost
    record), settled at each delivered record for the gap before it:

    * several birds in group mode: the records lost are the birds missing in the cycle between
      the previous delivered address and this one (records come in ascending address order every
      cycle), so a record that lost its phasing byte, its address or any other byte counts as one
      lost record; the gap's bytes beyond those records' lengths are stray bytes. A whole lost
      cycle leaves no trace in the addresses and is not counted.
    * one bird per stream (standalone, one port per bird, or one sensor behind an ERC): a record
      that lost one byte leaves ``length - 1`` bytes with no phasing bit after their first, so a
      gap made only of such remains counts that many lost records; any other gap counts as stray
      bytes. (Garbage that looks exactly like such remains is counted as lost records.)

    A stream starts with a cycle's first record (the driver drains the port and restarts the
    stream after every :meth:`reset`).
    """

    def __init__(self, layouts: Mapping[int, BirdLayout], group: bool = False) -> None:
        if not layouts:
            raise DeviceError("a decoder needs at least one bird layout")
        if not group and len(layouts) != 1:
            raise DeviceError("several birds on one port need group mode")
        self.group = group
        self.layouts = dict(layouts)
        addrs = sorted(self.layouts)
        self._addrs = addrs
        self._lengths = {a: self.layouts[a].length(group) for a in addrs}
        self._structs = {a: struct.Struct(f"<{self.layouts[a].format.words}H") for a in addrs}
        # candidate order after each address: the next address first, then the others
        self._order = {a: addrs[i + 1:] + addrs[:i + 1] for i, a in enumerate(addrs)}
        self._cycle = group and len(addrs) > 1  # lost records are read from the address sequence
        self._buf = bytearray()
        self._gap = bytearray()  # bytes since the last delivered record that framed nothing
        self._last: int | None = None
        self._next = self._order[addrs[-1]]
        self.records = 0
        self.dropped = 0
        self.skipped_bytes = 0

    @property
    def pending(self) -> int:
        """Bytes buffered waiting for the rest of a record (or for the byte after it)."""
        return len(self._buf)

    def reset(self) -> None:
        """Forget buffered bytes (after a flush or a command exchange)."""
        self._buf.clear()
        self._gap.clear()
        self._last = None
        self._next = self._order[self._addrs[-1]]

    def feed(self, data: bytes | bytearray) -> list[Record]:
        """Add received bytes; return the complete records now available, in order."""
        buf = self._buf
        buf += data
        n = len(buf)
        out: list[Record] = []
        i = 0
        search = _PHASE.search
        while i < n:
            if buf[i] < 0x80:  # hunt for a record start
                m = search(buf, i)
                j = m.start() if m else n
                self._skip(buf, i, j)
                i = j
                if i >= n:
                    break
            addr = self._match(buf, i, n)
            if addr is None:  # need more bytes
                break
            if addr < 0:  # no record starts here: on to the next phasing byte
                m = search(buf, i + 1)
                j = m.start() if m else n
                self._skip(buf, i, j)
                i = j
                continue
            self._settle(addr)
            lay = self.layouts[addr]
            unpack = self._structs[addr]
            words = tuple(map(_WORD.__getitem__, unpack.unpack_from(buf, i)))
            k = i + unpack.size
            button = metal = None
            if lay.button:
                button = buf[k]
                k += 1
            if lay.metal:
                metal = buf[k]
            out.append(Record(lay.format, words, lay.scale, button, metal, addr))
            i += self._lengths[addr]
            self._last = addr
            self._next = self._order[addr]
        del buf[:i]
        self.records += len(out)
        return out

    _GAP_KEEP = 4096  # gap bytes kept for the one-bird rule; a longer gap is all stray bytes

    def _skip(self, buf: bytearray, i: int, j: int) -> None:
        take = min(j - i, self._GAP_KEEP - len(self._gap))
        self._gap += buf[i:i + take]
        self.skipped_bytes += j - i - take

    def _match(self, buf: bytearray, i: int, n: int) -> int | None:
        """Address of the record starting at ``i``; None = need more bytes; -1 = none starts here."""
        search = _PHASE.search
        in_turn = not self._gap  # right after the previous record (or at the stream's start)
        for k, addr in enumerate(self._next):
            length = self._lengths[addr]
            end = i + length
            if search(buf, i + 1, min(end, n)):
                continue  # a phasing byte inside: not this bird's record
            if end > n:
                return None
            if self.group and buf[end - 1] != addr:
                continue
            if not (in_turn and k == 0):  # out of turn: what follows must fit too
                fits = self._followed_well(buf, end, n, addr)
                if fits is None:
                    return None
                if not fits:
                    continue
            return addr
        return -1

    def _followed_well(self, buf: bytearray, end: int, n: int, addr: int) -> bool | None:
        """Whether what follows a candidate record of ``addr`` ending at ``end`` is a record
        start, or the remains of the next bird's record that lost its phasing byte
        (``length - 1`` bytes without one, ending with its address in group mode); None until
        enough bytes have arrived to tell."""
        if end >= n:
            return None
        if buf[end] >= 0x80:
            return True
        nxt = self._order[addr][0]
        stop = end + self._lengths[nxt] - 1
        if _PHASE.search(buf, end, min(stop, n)):
            return False
        if stop >= n:
            return None
        return (not self.group or buf[stop - 1] == nxt) and buf[stop] >= 0x80

    def _settle(self, addr: int) -> None:
        """Count the gap before a delivered record of ``addr``: records lost and stray bytes."""
        gap = len(self._gap)
        lost = 0
        if self._cycle:
            order = self._next  # after a reset: the cycle's first address is due
            missing = order[:order.index(addr)]
            lost = len(missing)
            gap -= min(gap, sum(self._lengths[b] for b in missing))
        elif gap:
            remains = self._lengths[addr] - 1
            g = self._gap
            if remains > 0 and gap % remains == 0 and not any(
                    _PHASE.search(g, k + 1, k + remains) for k in range(0, gap, remains)):
                lost, gap = gap // remains, 0
        self.dropped += lost
        self.skipped_bytes += gap
        self._gap.clear()


def angles_from_rotation(r: np.ndarray) -> tuple[float, float, float]:
    """Inverse of :func:`rotation_from_angles`: (azimuth, elevation, roll) in radians."""
    elevation = float(np.arcsin(np.clip(-r[2, 0], -1.0, 1.0)))
    return float(np.arctan2(r[1, 0], r[0, 0])), elevation, float(np.arctan2(r[2, 1], r[2, 2]))
