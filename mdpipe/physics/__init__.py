"""Physics shared by the simulator and the feature extractor (numpy only).

Every relation is written once, as a forward/inverse pair where both directions are used.
"""
