"""Tables and figures. matplotlib is imported only in :mod:`mdpipe.report.plots`."""
