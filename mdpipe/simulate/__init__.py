"""The simulator: a YAML scene -> FMCW chirp matrices -> a Radarlog file with its expected answer."""
