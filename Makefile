# mdpipe: set-up, tests, samples and benchmarks. `make demo` and `make test` are all a new machine needs.
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
MDPIPE := $(BIN)/mdpipe

SAMPLES := data_samples/fimi_1rx.h5 data_samples/phantom4_xband.h5 data_samples/gull_flyby.h5 \
           data_samples/clutter_only.h5

.PHONY: demo install test test-slow samples bench-sim clean

$(MDPIPE): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/pip install --quiet --upgrade pip
	$(BIN)/pip install --quiet -e ".[test]"
	touch $@

install: $(MDPIPE)

demo: $(MDPIPE)
	$(MDPIPE) info data_samples/fimi_1rx.h5

test: $(MDPIPE)
	$(BIN)/python -m pytest -q

test-slow: $(MDPIPE)
	$(BIN)/python -m pytest -q -m slow

# The bundled captures: small, seeded, remade exactly by this target (see data_samples/README.md).
samples: $(SAMPLES)

data_samples/fimi_1rx.h5: configs/fimi.yaml $(MDPIPE)
	$(MDPIPE) simulate --config $< -o $@ --chirps 2048 --channels 1
data_samples/phantom4_xband.h5: configs/paper/table1_config7.yaml $(MDPIPE)
	$(MDPIPE) simulate --config $< -o $@ --chirps 6250
data_samples/gull_flyby.h5: configs/samples/gull_flyby.yaml $(MDPIPE)
	$(MDPIPE) simulate --config $< -o $@
data_samples/clutter_only.h5: configs/samples/clutter_only.yaml $(MDPIPE)
	$(MDPIPE) simulate --config $< -o $@

# Full-size simulation benchmark (writes ~1.3 GB under BENCH_DIR, then removes it).
BENCH_DIR ?= /tmp
bench-sim: $(MDPIPE)
	$(BIN)/python benchmarks/bench_simulate.py --workdir $(BENCH_DIR)

clean:
	rm -rf $(VENV) build *.egg-info .pytest_cache
