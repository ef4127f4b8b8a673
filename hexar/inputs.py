"""File and folder arguments checked once, the same way for every command: one line for whatever is wrong.

A person passes a questions file saved by Notepad (UTF-16), a folder instead of a file, a PDF, or a path with a
typo; each gets a sentence that says which argument and what to do, never a traceback.
"""

from __future__ import annotations

import codecs
import os
from pathlib import Path

from hexar.errors import BadOptionValueError, InputFileError
from hexar.safe_text import visible

_BOMS = ((codecs.BOM_UTF8, "utf-8-sig"), (codecs.BOM_UTF16_LE, "utf-16"), (codecs.BOM_UTF16_BE, "utf-16"))


def _name(path: Path) -> str:
    return visible(str(path))


def check_input_file(path: Path, what: str) -> Path:
    """`path` if it is a readable file; else InputFileError naming the argument `what`."""
    if not path.exists():
        raise InputFileError(f"{what}: no such file: {_name(path)}")
    if path.is_dir():
        raise InputFileError(f"{what}: {_name(path)} is a folder; give a file")
    if not path.is_file():
        raise InputFileError(f"{what}: {_name(path)} is not a regular file")
    if not os.access(path, os.R_OK):
        raise InputFileError(f"{what}: cannot read {_name(path)}: permission denied")
    return path


def read_bytes_arg(path: Path, what: str) -> bytes:
    check_input_file(path, what)
    try:
        return path.read_bytes()
    except OSError as err:
        raise InputFileError(f"{what}: cannot read {_name(path)}: {visible(err.strerror or err)}") from err


def decode_text(data: bytes, path: Path, what: str) -> str:
    """UTF-8 (with or without a BOM) or UTF-16 with a BOM; anything else is refused with the reason."""
    for bom, codec in _BOMS:
        if data.startswith(bom):
            try:
                return data.decode(codec)
            except UnicodeDecodeError as err:
                raise InputFileError(f"{what}: {_name(path)} starts like {codec.upper()} but is not valid "
                                     f"{codec.upper()} (byte {err.start})") from err
    if b"\x00" in data:
        raise InputFileError(f"{what}: {_name(path)} is a binary file, not text")
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as err:
        raise InputFileError(f"{what}: {_name(path)} is not UTF-8 text (byte 0x{data[err.start]:02x} at offset "
                             f"{err.start}); save it as UTF-8") from err


def read_text_arg(path: Path, what: str) -> str:
    """The text of a file argument, checked and decoded, or one InputFileError line."""
    return decode_text(read_bytes_arg(path, what), path, what)


def port_number(port: int, lowest: int = 1, what: str = "--port") -> int:
    """A TCP port to listen on, from `lowest` (0: any free port) to 65535; the socket layer's own error for 70000
    read as an internal error."""
    if not lowest <= port <= 65535:
        raise BadOptionValueError(f"{what} must be a port number from {lowest} to 65535, not {port}")
    return port


def output_dir(path: Path, what: str) -> Path:
    """`path` as a folder that exists and can be written, created if missing; else one InputFileError line."""
    if path.exists() and not path.is_dir():
        raise InputFileError(f"{what}: {_name(path)} is a file; give a folder")
    try:
        path.mkdir(parents=True, exist_ok=True)
    except OSError as err:
        raise InputFileError(f"{what}: cannot create folder {_name(path)}: {visible(err.strerror or err)}") from err
    if not os.access(path, os.W_OK | os.X_OK):
        raise InputFileError(f"{what}: cannot write in folder {_name(path)}: permission denied")
    return path


_SQLITE_MAGIC = b"SQLite format 3\x00"


def _nearest_existing(path: Path) -> Path:
    for parent in (path, *path.parents):
        if parent.exists():
            return parent
    return Path(".")


def checkpoints_file(path: Path | None, what: str = "--checkpoints") -> Path | None:
    """`path` as a SQLite file of conversations HEXAR can read and write, or a new one it can create; else one
    InputFileError line (sqlite3 itself would say only "unable to open database file" or "file is not a
    database", after the recording was already decoded)."""
    if path is None:
        return None
    if path.exists():
        if path.is_dir():
            raise InputFileError(f"{what}: {_name(path)} is a folder; give a file such as "
                                 f"{_name(path / 'threads.sqlite')}")
        if not path.is_file():
            raise InputFileError(f"{what}: {_name(path)} is not a regular file")
        if not os.access(path, os.R_OK | os.W_OK):
            raise InputFileError(f"{what}: cannot read and write {_name(path)}: permission denied")
        try:
            with path.open("rb") as f:
                head = f.read(len(_SQLITE_MAGIC))
        except OSError as err:
            raise InputFileError(f"{what}: cannot read {_name(path)}: {visible(err.strerror or err)}") from err
        if head and head != _SQLITE_MAGIC:  # an empty file is a new, empty database to SQLite
            raise InputFileError(f"{what}: {_name(path)} is not a SQLite database; give a new file name or one "
                                 "written by hexar chat")
        if head:
            _check_sqlite(path, what)
        return path
    base = _nearest_existing(path.parent)
    if not base.is_dir():
        raise InputFileError(f"{what}: cannot create {_name(path)}: {_name(base)} is a file, not a folder")
    if not os.access(base, os.W_OK | os.X_OK):
        raise InputFileError(f"{what}: cannot create {_name(path)}: folder {_name(base)} is not writable")
    return path


def _check_sqlite(path: Path, what: str) -> None:
    """A SQLite header over a damaged body: reading the schema (read-only) finds it before any question."""
    import sqlite3

    try:
        conn = sqlite3.connect(f"{path.resolve().as_uri()}?mode=ro", uri=True)
        try:
            conn.execute("SELECT count(*) FROM sqlite_master").fetchone()
        finally:
            conn.close()
    except sqlite3.Error as err:
        raise InputFileError(f"{what}: {_name(path)} is a damaged SQLite database: {visible(err)}") from err
