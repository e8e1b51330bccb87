"""Many captures: the per-capture unit of work, its manifest, and the runners (serial, process pool, Dask)."""
