"""The one error hierarchy of mdpipe. Only the CLI turns these into exit codes."""


class MdpipeError(Exception):
    """Base class of every error mdpipe raises on purpose."""


class ParameterError(MdpipeError, ValueError):
    """A parameter or configuration value is out of range or of the wrong kind."""


class CaptureFormatError(MdpipeError):
    """A capture file does not follow the Radarlog layout and cannot be read as one."""


class PlatformError(MdpipeError):
    """This platform lacks something an operation needs (e.g. ``os.pwrite`` on Windows)."""


def one_line(exc):
    """``exc`` as one line: its text with whitespace runs (newlines too) made single spaces; an exception
    mdpipe did not raise on purpose (neither an :class:`MdpipeError` nor an ``OSError``) is called an internal
    error and named by its type."""
    text = str(exc)
    if not isinstance(exc, (MdpipeError, OSError)):
        text = f"internal error, {type(exc).__name__}: {text}"
    return " ".join(text.split())
