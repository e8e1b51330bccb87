"""mdpipe evaluate: a seeded sweep of simulated scenes, processed and scored against their truth."""
