"""Capture files. h5py is imported only in this package."""

from mdpipe.io.radarlog import CaptureWriter, Layout, RadarlogReader, open_capture

__all__ = ["CaptureWriter", "Layout", "RadarlogReader", "open_capture"]
