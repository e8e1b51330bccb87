"""mdpipe: radar micro-Doppler analysis of drones and birds from FMCW captures.

Axis order throughout the package: slow time (chirps) first, then channel where present,
fast time (samples) or frequency last.
"""

__version__ = "0.1.0"
