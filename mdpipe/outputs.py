"""Output files: made under a new, unique name beside their target, then published by rename.

The temporary file is created exclusively (``O_CREAT | O_EXCL | O_NOFOLLOW``, through
:func:`tempfile.mkstemp`): a file or symlink planted at any name is never followed, truncated or
reused. It gets the mode the umask gives an ordinary new file (``mkstemp`` alone gives 0600).
"""

import os
import tempfile
from pathlib import Path


def file_mode(*, folder=False):
    """Mode of a new file (``0o666 & ~umask``) or folder (``0o777 & ~umask``) under the current umask."""
    mask = os.umask(0o022)
    os.umask(mask)
    return (0o777 if folder else 0o666) & ~mask


def create_temporary(path, *, prefix="."):
    """Create a new empty file beside ``path``, named ``prefix + name + random``; returns ``(fd, temporary_path)``.

    Raises
    ------
    FileNotFoundError
        When the folder of ``path`` does not exist.
    """
    path = Path(path)
    fd, tmp = tempfile.mkstemp(prefix=f"{prefix}{path.name}.", dir=path.parent)
    try:
        os.fchmod(fd, file_mode())
    except BaseException:
        os.close(fd)
        os.remove(tmp)
        raise
    return fd, tmp


def publish(tmp, path, *, overwrite=True):
    """Move the finished ``tmp`` to ``path``; with ``overwrite=False`` an existing ``path`` raises FileExistsError.

    Without overwrite the file is hard-linked to its name (which fails, atomically, if the name is
    taken, and never follows a symlink there) and the temporary name removed.
    """
    if overwrite:
        os.replace(tmp, path)
        return
    try:
        os.link(tmp, path, follow_symlinks=False)
    except FileExistsError:  # the name is taken: the caller says so
        raise
    except OSError:  # a file system without hard links: the check and the rename are then two steps
        if os.path.lexists(path):
            raise FileExistsError(path) from None
        os.replace(tmp, path)
        return
    os.remove(tmp)
