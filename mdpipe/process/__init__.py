"""From a Radarlog capture to features: ranging, selection, Doppler analysis, features, classification."""
