"""Atomic file output: a result file is either complete or absent, never half-written; a run's
set of files is complete or absent (``staged_dir``); output paths are checked before any work
(``check_output_file``, ``staged_dir``)."""

from __future__ import annotations

import os
import shutil
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from shaftfe.errors import InputError


@contextmanager
def atomic_path(path: str | os.PathLike, suffix: str | None = None) -> Iterator[Path]:
    """Yield a temporary path beside ``path``; on success give it the usual file mode and rename
    it onto ``path``; on any error remove it. For writers that want a file name (meshio, VTK)::

        with atomic_path("result.vtu") as tmp:
            meshio.write(tmp, mesh)

    ``suffix`` defaults to the target's suffix, so writers that pick a format by extension work.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.stem}.",
                               suffix=path.suffix if suffix is None else suffix)
    os.close(fd)
    try:
        yield Path(tmp)
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)  # mkstemp creates 0600
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def write_atomic(path: str | os.PathLike, data: str | bytes) -> Path:
    """Write text or bytes to ``path`` atomically."""
    with atomic_path(path) as tmp:
        if isinstance(data, bytes):
            tmp.write_bytes(data)
        else:
            tmp.write_text(data, encoding="utf-8")
    return Path(path)


# --------------------------------------------------------------------------- output checks

def _nearest_existing(path: Path) -> tuple[Path, list[Path]]:
    """The nearest existing ancestor of ``path`` and the missing directories below it."""
    missing: list[Path] = []
    anc = path
    while not anc.exists() and anc != anc.parent:
        missing.append(anc)
        anc = anc.parent
    return anc, missing[::-1]


def _probe_writable(directory: Path, option: str, target: Path) -> None:
    """Create and remove a file in ``directory``: the one test that holds for root, read-only
    file systems and /proc alike."""
    try:
        fd, tmp = tempfile.mkstemp(dir=directory, prefix=".shaftfe-probe.")
        os.close(fd)
        os.unlink(tmp)
    except OSError as exc:
        raise _not_writable(option, target, exc) from None


def _not_writable(option: str, target: Path, exc: OSError | str):
    why = exc if isinstance(exc, str) else (exc.strerror or exc.__class__.__name__)
    return InputError(option, "path", "a location where shaftfe may create files",
                      got=str(target), reason=f"cannot be written ({why})")


# the formats shaftfe's figures are written in (matplotlib infers the format from the name)
PLOT_SUFFIXES = (".png", ".pdf", ".svg")


def check_suffix(path: str | os.PathLike, option: str, suffixes: tuple[str, ...] = ()) -> Path:
    """``path`` as a Path, refused in one line unless its name ends in one of ``suffixes``
    (lower case; any name where none is given): the one rule of output file names."""
    p = Path(path)
    if suffixes and p.suffix.lower() not in suffixes:
        raise InputError(option, "file extension", " | ".join(suffixes), got=str(p))
    return p


def check_output_file(path: str | os.PathLike | None, option: str,
                      suffixes: tuple[str, ...] = ()) -> Path | None:
    """Refuse, before any work is done, an output FILE that cannot be written: an empty name, a
    name that does
    not end in one of ``suffixes`` (lower case, e.g. ``PLOT_SUFFIXES``; any name where none is
    given), a directory at the path, a parent that is a file, a parent that cannot be created or
    written. Creates nothing (a probe file is made and removed in the nearest existing
    directory). The one rule of every command's output file names."""
    if path is None:
        return None
    if str(path) == "":
        raise InputError(option, "path", "a file name", got="")
    p = check_suffix(path, option, suffixes)
    if p.is_dir():
        raise _not_writable(option, p, "it is a directory; give a file name")
    anc, _ = _nearest_existing(p.parent)
    if not anc.is_dir():
        raise _not_writable(option, p, f"{anc} is a file, not a directory")
    _probe_writable(anc, option, p)
    return p


@contextmanager
def staged_dir(out: str | os.PathLike, option: str = "--out",
               replaces: tuple[str, ...] = ()) -> Iterator[Path]:
    """All the files of one run, or none: yields a hidden staging directory, created now (so an
    unwritable ``out`` fails before any work), into which the run writes everything. On success
    the files move into ``out``; on any error or Ctrl-C the staging directory is removed and
    ``out`` is left as it was.

    Where: inside ``out`` when it exists (that probes the directory the files go to and keeps
    every rename on its file system, a mount point included), else beside it, and then the
    whole directory is renamed into place. Moving into an existing ``out`` is one rename per
    file, after checking that no output lands on a directory: a crash in those microseconds can
    leave some new files beside old ones, never a half-written file.

    ``replaces``: glob patterns of files the command writes only in some runs (a plot an
    option asks for, one file per 3D zone): after the move, a file in ``out`` that matches one
    and that this run did not write is an earlier run's, and is removed, so the folder never
    shows a file beside a summary that does not account for it."""
    out = Path(out)
    if out.exists() and not out.is_dir():
        raise _not_writable(option, out, "it is a file; give a directory")
    created: list[Path] = []
    try:
        if out.is_dir():
            stage = Path(tempfile.mkdtemp(dir=out, prefix=".staging-"))
        else:
            anc, missing = _nearest_existing(out.parent)
            if not anc.is_dir():
                raise _not_writable(option, out, f"{anc} is a file, not a directory")
            for d in missing:
                try:
                    d.mkdir()
                    created.append(d)
                except FileExistsError:           # another run made it meanwhile
                    pass
            stage = Path(tempfile.mkdtemp(dir=out.parent, prefix=f".{out.name}.staging-"))
    except OSError as exc:
        _remove_dirs(created)
        raise _not_writable(option, out, exc) from None
    try:
        yield stage
        _commit(stage, out, option, replaces)
    except BaseException:
        shutil.rmtree(stage, ignore_errors=True)
        _remove_dirs(created)
        raise


def _remove_dirs(created: list[Path]) -> None:
    for d in reversed(created):
        try:
            d.rmdir()
        except OSError:
            pass


def _commit(stage: Path, out: Path, option: str, replaces: tuple[str, ...] = ()) -> None:
    umask = os.umask(0)
    os.umask(umask)
    if stage.parent != out:                      # staged beside a new out: one rename
        os.chmod(stage, 0o777 & ~umask)
        try:
            os.replace(stage, out)
            return
        except OSError:                          # another run created out meanwhile: merge
            pass
    files = sorted(p.relative_to(stage) for p in stage.rglob("*") if not p.is_dir())
    for rel in files:
        if (out / rel).is_dir():
            raise _not_writable(option, out / rel, "a directory stands where this output file "
                                "goes")
        for parent in rel.parents:
            if parent != Path(".") and (out / parent).exists() and not (out / parent).is_dir():
                raise _not_writable(option, out / parent, "a file stands where an output "
                                    "directory goes")
    for rel in files:
        (out / rel).parent.mkdir(parents=True, exist_ok=True)
        os.replace(stage / rel, out / rel)
    shutil.rmtree(stage, ignore_errors=True)
    written = set(files)
    for pattern in replaces:
        for old in out.glob(pattern):
            if old.is_file() and old.relative_to(out) not in written:
                old.unlink(missing_ok=True)
