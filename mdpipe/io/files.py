"""Files read from the field that are not regular files: a FIFO would hang the read, a device never end it."""

import os
import stat

from mdpipe.errors import CaptureFormatError


def file_kind(mode):
    """What a file of stat ``mode`` is, in words, for one that is not a regular file."""
    return {stat.S_IFIFO: "a FIFO", stat.S_IFCHR: "a character device", stat.S_IFBLK: "a block device",
            stat.S_IFDIR: "a folder", stat.S_IFSOCK: "a socket"}.get(stat.S_IFMT(mode), "not a regular file")


def check_regular_file(path):
    """Raise :class:`CaptureFormatError` unless ``path`` is an existing regular file (a FIFO would hang the open, a
    device never end it)."""
    try:
        mode = os.stat(path).st_mode
    except FileNotFoundError:
        raise CaptureFormatError(f"{path}: no such file") from None
    except OSError as exc:
        raise CaptureFormatError(f"{path}: cannot be read ({exc.strerror})") from None
    if not stat.S_ISREG(mode):
        raise CaptureFormatError(f"{path}: is {file_kind(mode)}; captures are read from regular files only")
