"""The one error hierarchy of mdpipe. Only the CLI turns these into exit codes."""


class MdpipeError(Exception):
    """Base class of every error mdpipe raises on purpose."""


class ParameterError(MdpipeError, ValueError):
    """A parameter or configuration value is out of range or of the wrong kind."""


class CaptureFormatError(MdpipeError):
    """A capture file does not follow the Radarlog layout and cannot be read as one."""


class PlatformError(MdpipeError):
    """This platform lacks something an operation needs (e.g. ``os.pwrite`` on Windows)."""
