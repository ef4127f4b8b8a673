"""rosbags' AnyReader, opened at a fraction of the cost for a fleet of small recordings, with the same results.

Two costs of rosbags' open dwarf reading a small recording's messages:
- it parses every stored message definition and generates, registers and compiles Python classes for it, and the
  fresh typestore then generates its decoders again. A fleet's recordings come from a handful of software
  versions, so the typestore built for a set of definitions is kept (least recently used first out) and shared
  with the decoders it has generated; a typestore is only read from once built, so sharing changes no result.
- it reads metadata.yaml with ruamel's pure-Python parser. PyYAML's libyaml parser reads the same file about ten
  times faster; where libyaml is missing, or the file is anything but a plain uncompressed rosbag2 recording with
  the fields rosbags reads, rosbags opens it itself, so every error and its text stay rosbags'.
- its sqlite3 and MCAP storages parse every topic's offered QoS profiles, stored as YAML text, with ruamel again,
  on every open (a quarter of a small recording's reading). A fleet stores the same few texts in every recording,
  so the storages here are rosbags' own code with that one helper answering each distinct text from the first
  time rosbags parsed it: the same values, the same errors (a failed parse is not kept, so it fails again).
"""

from __future__ import annotations

import types
from collections.abc import Callable, Mapping
from contextlib import ExitStack, suppress
from functools import lru_cache
from pathlib import Path, PurePath
from types import MappingProxyType
from typing import TYPE_CHECKING, Any, TypeVar, cast

import yaml
from rosbags.highlevel import AnyReader
from rosbags.highlevel.anyreader import AnyReaderError
from rosbags.interfaces import Connection, ConnectionExtRosbag2, MessageDefinition, MessageDefinitionFormat, Qos
from rosbags.rosbag2.metadata import ReaderMetadata, parse_qos
from rosbags.rosbag2.reader import DirectoryReader
from rosbags.rosbag2.reader import Reader as Reader2
from rosbags.rosbag2.storage_mcap import McapReader, get_qos
from rosbags.rosbag2.storage_sqlite3 import Sqlite3Reader
from rosbags.typesys import Stores, get_types_from_idl, get_types_from_msg, get_typestore
from rosbags.typesys.store import Typestore

from hexar.events.humble import humble
from hexar.fastyaml import LIBYAML, load

if TYPE_CHECKING:
    from rosbags.rosbag2.reader import ReaderProtocol

# (message type, definition format, definition text, type hash) of a connection that stores its definition
Definition = tuple[str, MessageDefinitionFormat, str, str]
_IDL_SEPARATOR = "=" * 80 + "\n"
SETS_KEPT = 32  # distinct definition sets whose typestores stay built: a few per robot software version
QOS_KEPT = 256  # distinct offered-QoS texts kept parsed: a few per topic and robot software version


class Reader(AnyReader):
    """AnyReader, opened the same way and raising the same errors, with its typestore from the shared cache and
    its storages parsing each distinct QoS text once; a recording that stores no definitions is read with the
    standard (Humble) ones unless another default is given."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        for reader in self.readers:
            if not (isinstance(reader, Reader2) and isinstance(path := getattr(reader.storage, "path", None), Path)):
                continue
            storage = type(reader.storage)
            if storage is DirectoryReader:
                reader.storage = Directory(path)
            elif storage in _FAST_STORAGE:
                reader.storage = _FAST_STORAGE[storage](path)

    def _open(self) -> None:
        assert self.stack
        for reader in self.readers:
            self.stack.enter_context(reader)
        connections = [y for x in self.readers for y in x.connections]
        if connections:
            defs = definitions(connections)
            # the standard store only for a recording that stores no definitions: building it is not free
            default = self.default_typestore if self.default_typestore is not None or defs else humble()
            self.typestore = typestore_for(defs, self.is2, default)
        self.connections = connections


def definitions(connections: list[Connection]) -> tuple[Definition, ...]:
    return tuple((conn.msgtype, conn.msgdef.format, conn.msgdef.data, conn.digest) for conn in connections
                 if conn.msgdef.format != MessageDefinitionFormat.NONE)


@lru_cache(maxsize=SETS_KEPT)
def typestore_for(defs: tuple[Definition, ...], is2: bool, default: Typestore | None) -> Typestore:
    """The typestore AnyReader builds for these stored definitions (else the default one), checked against the
    hashes the recording stores. Only a store that was built is kept: an error is raised again on every open."""
    types = {}
    digests: dict[str, str] = {}
    for msgtype, form, data, digest in defs:
        if form == MessageDefinitionFormat.MSG:
            types.update(get_types_from_msg(data, msgtype))
        elif data.startswith(f"{_IDL_SEPARATOR}IDL: "):
            for part in data.split(_IDL_SEPARATOR)[1:]:
                header, idl = part.split("\n", 1)
                assert header.startswith("IDL: ")
                types.update(get_types_from_idl(idl))
        else:
            types.update(get_types_from_idl(data))
        if digest:
            digests[msgtype] = digest
    if not defs:
        if default is None:
            raise AnyReaderError("Bag contains no type definitions. Instantiate AnyReader with a default_typestore "
                                 "argument.")
        types.update(default.fielddefs)
    store = get_typestore(Stores.EMPTY)
    store.register(types)
    for msgtype, digest in digests.items():
        have = store.hash_rihs01(msgtype) if is2 else store.generate_msgdef(msgtype)[1]
        if have != digest:
            raise AnyReaderError(f"Message type {msgtype!r} hash mismatch {have} != {digest}")
    return store


@lru_cache(maxsize=QOS_KEPT)
def _qos_of_text(text: str) -> tuple[Qos, ...]:
    return tuple(parse_qos(text))


def qos_once(dcts: Any) -> list[Qos]:
    """rosbags' parse_qos, parsing each distinct YAML text once per process (a fresh list each call, as rosbags
    returns; Qos values are immutable)."""
    return list(_qos_of_text(dcts)) if isinstance(dcts, str) else parse_qos(dcts)


@lru_cache(maxsize=QOS_KEPT)
def _mcap_qos_of(metadata: bytes) -> tuple[Qos, ...]:
    return tuple(get_qos(metadata))


def mcap_qos_once(metadata: bytes) -> list[Qos]:
    """rosbags' get_qos of an MCAP channel's metadata record, parsed once per distinct record."""
    return list(_mcap_qos_of(bytes(metadata)))


F = TypeVar("F", bound=Callable[..., Any])


def _rebound(func: F, **names: Any) -> F:
    """`func`'s own code, looking `names` up here instead of in its module (which stays as it is)."""
    missing = set(names) - _names_used(func.__code__)
    assert not missing, f"{func.__qualname__} no longer calls {missing}"  # rosbags changed: check the swap
    fresh = types.FunctionType(func.__code__, {**func.__globals__, **names}, func.__name__, func.__defaults__,
                               func.__closure__)
    fresh.__kwdefaults__, fresh.__qualname__, fresh.__doc__ = func.__kwdefaults__, func.__qualname__, func.__doc__
    return cast(F, fresh)


def _names_used(code: types.CodeType) -> set[str]:
    """The global names a function's code (comprehensions included) looks up."""
    found = set(code.co_names)
    for const in code.co_consts:
        if isinstance(const, types.CodeType):
            found |= _names_used(const)
    return found


class Sqlite3Storage(Sqlite3Reader):
    """rosbags' sqlite3 storage, its topics' QoS texts parsed once per process."""

    _open = _rebound(Sqlite3Reader._open, parse_qos=qos_once)


class McapStorage(McapReader):
    """rosbags' MCAP storage, its channels' QoS records parsed once per process."""

    read_index = _rebound(McapReader.read_index, get_qos=mcap_qos_once)
    meta_scan = _rebound(McapReader.meta_scan, get_qos=mcap_qos_once)


_FAST_STORAGE: dict[type[Any], type[Any]] = {Sqlite3Reader: Sqlite3Storage, McapReader: McapStorage}


class Directory(DirectoryReader):
    """A rosbag2 folder whose metadata.yaml libyaml reads, when it is plain (else rosbags reads it itself), and
    whose storages parse each distinct QoS text once."""

    STORAGE_PLUGINS: Mapping[str, type[ReaderProtocol]] = MappingProxyType(
        {"mcap": McapStorage, "sqlite3": Sqlite3Storage})

    def open(self) -> None:
        parsed = _plain_metadata(self.path / "metadata.yaml") if LIBYAML and isinstance(self.path, Path) else None
        if parsed is None:
            super().open()
            return
        self.stack = ExitStack()
        try:
            self._open(*parsed)
        except BaseException:
            with suppress(Exception):
                self.close()
            raise

    def _open(self, info: dict[str, Any], paths: list[Path], qos: list[Any]) -> None:
        assert self.stack is not None
        self.connections = [
            Connection(id=idx + 1, topic=t["topic_metadata"]["name"], msgtype=t["topic_metadata"]["type"],
                       msgdef=MessageDefinition(MessageDefinitionFormat.NONE, ""),
                       digest=t["topic_metadata"].get("type_description_hash", ""), msgcount=t["message_count"],
                       ext=ConnectionExtRosbag2(serialization_format="cdr",
                                                offered_qos_profiles=parse_qos(profiles)),
                       owner=self)
            for idx, (t, profiles) in enumerate(zip(info["topics_with_message_count"], qos, strict=True))]
        duration, count = info["duration"]["nanoseconds"], info["message_count"]
        start = info["starting_time"]["nanoseconds_since_epoch"]
        mode = info.get("compression_mode", "").lower()  # "" or "none": uncompressed, as rosbags keeps it
        self.metadata = ReaderMetadata(duration=duration + 1 if count else 0, start_time=start if count else 2**63 - 1,
                                       end_time=start + duration + 1 if count else 0, message_count=count,
                                       compression_format=None, compression_mode=None if mode == "none" else mode,
                                       ros_distro=info.get("ros_distro"), custom=info.get("custom_data"))
        self.files = info.get("files", [])[:]
        plugin = self.STORAGE_PLUGINS[info["storage_identifier"]]
        self.storages = []
        for path in paths:
            storage = plugin(path)
            storage.open()
            self.stack.callback(storage.close)
            self.storages.append(storage)
        for idx, conn in enumerate(self.connections):
            stored = next((y.msgdef for x in self.storages for y in x.connections
                           if y.msgtype == conn.msgtype and y.msgdef.format != MessageDefinitionFormat.NONE), None)
            if stored:
                self.connections[idx] = conn._replace(msgdef=stored)


def _plain_metadata(path: Path) -> tuple[dict[str, Any], list[Path], list[Any]] | None:
    """The metadata of an uncompressed rosbag2 recording of version 9 or older whose storage files are all there,
    every field rosbags reads of the type it expects; None for anything else (rosbags then reads it, and names
    what is wrong). Plain text fields are compared as libyaml reads them: a YAML 1.1 boolean or number where a
    name belongs (ruamel reads YAML 1.2) sends the file to rosbags too."""
    try:
        info = metadata(path)["rosbag2_bagfile_information"]
        if not (isinstance(info["version"], int) and info["version"] <= 9):
            return None
        if info.get("compression_format") or info.get("compression_mode", "").lower() not in ("", "none"):
            return None
        if info["storage_identifier"] not in DirectoryReader.STORAGE_PLUGINS:
            return None
        names = info["relative_file_paths"]
        if not all(isinstance(n, str) for n in names):
            return None
        paths = [path.parent / PurePath(n).name for n in names]
        numbers = (info["duration"]["nanoseconds"], info["starting_time"]["nanoseconds_since_epoch"],
                   info["message_count"])
        if any(type(n) is not int for n in numbers):
            return None
        qos = []
        for t in info["topics_with_message_count"]:
            meta = t["topic_metadata"]
            given = meta.get("offered_qos_profiles", [])
            qos.append(load(given) if isinstance(given, str) and given else given)
            if not (isinstance(meta["name"], str) and isinstance(meta["type"], str) and type(t["message_count"]) is int
                    and meta["serialization_format"] == "cdr" and isinstance(meta.get("type_description_hash", ""), str)
                    and isinstance(qos[-1], list)):
                return None
        if not all(p.exists() for p in paths):
            return None
        if not (info.get("ros_distro") is None or isinstance(info.get("ros_distro"), str)):
            return None
        custom = info.get("custom_data")
        if not (custom is None or all(isinstance(v, str) for v in custom.values())):
            return None
        return info, paths, qos
    except (yaml.YAMLError, OSError, KeyError, TypeError, AttributeError, ValueError):
        return None


def metadata(path: Path) -> Any:
    """metadata.yaml as libyaml (else PyYAML) reads it, parsed once while the file stays the same: opening a
    recording and reading its messages both look at it."""
    st = path.stat()
    return _parsed(str(path), st.st_mtime_ns, st.st_size)


@lru_cache(maxsize=4)
def _parsed(path: str, mtime_ns: int, size: int) -> Any:
    return load(Path(path).read_text())
