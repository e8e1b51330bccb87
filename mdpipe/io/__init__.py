"""Capture files. h5py is imported only in this package."""

from mdpipe.io.radarlog import INT16_FULL_SCALE, CaptureWriter, Layout, RadarlogReader, open_capture

__all__ = ["INT16_FULL_SCALE", "CaptureWriter", "Layout", "RadarlogReader", "open_capture"]
