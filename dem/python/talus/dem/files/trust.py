"""Which checkpoints may run their Python commands.

A checkpoint stores its engines, and some engines hold Python code: a PyRunner's command, a
controller's doneHook, a FlowEngine's blockHook. Loaded and run, that code runs with the user's
permissions, as a script would: a checkpoint is code. ``O.load`` therefore runs the commands of
a checkpoint only when it is trusted:

- a checkpoint the user saved: ``O.save`` signs the engine list with a key private to the user
  (HMAC-SHA256, key in ``$XDG_DATA_HOME/talus/checkpoint-key``, by default
  ``~/.local/share/talus/checkpoint-key``, created on first use, readable by the user only), and a
  file whose engine list carries a valid signature is the user's own, unchanged. Scripts that
  save and load their own checkpoints, in one run or across runs (as Yade's examples do), run
  unchanged. Without a writable key file, the key lives in the process: only its own saves are
  recognised. Memory slots (``O.saveTmp``) never leave the process and are always trusted;
- ``O.load(path, trusted=True)``, or every load of a run started with
  ``talus run --trust-checkpoints`` (which sets ``TALUS_TRUST_CHECKPOINTS=1``).

Otherwise the engines are rebuilt with their commands held: a warning lists them and says how
to allow them, and a held command that comes due stops the run with :class:`UntrustedCommandError`
instead of running. Saving a scene whose engines hold such commands gives an unsigned file (a
foreign command does not become the user's by going through a save).
"""
from __future__ import annotations

import hashlib
import hmac
import json
import os
import secrets
from contextlib import contextmanager
from pathlib import Path
from typing import Callable

ENVIRONMENT = "TALUS_TRUST_CHECKPOINTS"

_key_cache: bytes | None = None
# While engines of an untrusted checkpoint are rebuilt: (its path, the commands held so far).
_holding: tuple[str, list[tuple[str, str]]] | None = None


class UntrustedCommandError(RuntimeError):
    """A command of an untrusted checkpoint came due; it was not run."""


def key_path() -> Path:
    base = os.environ.get("XDG_DATA_HOME") or os.path.join(os.path.expanduser("~"), ".local", "share")
    return Path(base) / "talus" / "checkpoint-key"


def _key() -> bytes:
    """The user's signing key: read from key_path(), created there on first use (atomically, so
    that concurrent runs agree on it); a key of this process alone if that fails."""
    global _key_cache
    if _key_cache is None:
        path = key_path()
        try:
            if not path.exists():
                path.parent.mkdir(parents=True, exist_ok=True)
                fresh = path.with_name(f".checkpoint-key.{os.getpid()}")
                fd = os.open(fresh, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o600)
                with os.fdopen(fd, "w") as out:
                    out.write(secrets.token_hex(32))
                try:
                    os.link(fresh, path)              # fails if another run made it first
                except FileExistsError:
                    pass
                finally:
                    fresh.unlink()
            _key_cache = bytes.fromhex(path.read_text().strip())
            if len(_key_cache) < 16:
                raise ValueError("key too short")
        except (OSError, ValueError):
            _key_cache = secrets.token_bytes(32)
    return _key_cache


def sign(engines: str) -> str:
    """The signature O.save stores beside an engine list (JSON text)."""
    return hmac.new(_key(), engines.encode(), hashlib.sha256).hexdigest()


def signature_for(engines: str, held: set[str]) -> str | None:
    """The signature to store, None if the list holds commands of an untrusted checkpoint."""
    if any(json.dumps(command)[1:-1] in engines for command in held):
        return None
    return sign(engines)


def trusted_by_default(engines: str | None, signature: str | None) -> bool:
    """Whether ``O.load`` without ``trusted`` runs a checkpoint's commands: the user signed its
    engine list, or the run was started with --trust-checkpoints."""
    if os.environ.get(ENVIRONMENT) == "1":
        return True
    return engines is not None and signature is not None and hmac.compare_digest(sign(engines), signature)


def allow_hint(path: str) -> str:
    return (f"if you trust it, load it with O.load({path!r}, trusted=True), or run the script with "
            f"`talus run --trust-checkpoints`")


@contextmanager
def holding(path: str):
    """Rebuild engines with their commands held; yields the list of (what, command) held."""
    global _holding
    outer, _holding = _holding, (path, [])
    try:
        yield _holding[1]
    finally:
        _holding = outer


def held(command: str, what: str) -> Callable[[], None] | None:
    """Inside :func:`holding`: a stand-in for ``command`` that refuses to run it (and the
    command is listed); None otherwise."""
    if _holding is None:
        return None
    path, commands = _holding
    commands.append((what, command))

    def refuse():
        raise UntrustedCommandError(f"{what} command {command!r} of checkpoint {path!r} was not run: the checkpoint "
                                    f"is not trusted, and a checkpoint's commands run as code with your permissions; "
                                    + allow_hint(path))
    return refuse

