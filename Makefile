# mdpipe: set-up, tests, samples and benchmarks. `make demo` and `make test` are all a new machine needs.
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
MDPIPE := $(BIN)/mdpipe

SAMPLES := data_samples/fimi_1rx.h5 data_samples/phantom4_xband.h5 data_samples/gull_flyby.h5 \
           data_samples/clutter_only.h5

.PHONY: demo install test test-slow samples bench bench-sim bench-scale bench-batch bench-impairments batch paper evaluate evaluate-reuse evaluate-fresh evaluate-heldout evaluate-heldout-lowprf evaluate-heldout-lowprf-fresh evaluate-heldout-lowprf-birds evaluate-heldout-birds evaluate-heldout-birds-fresh offmodel offmodel-blades offmodel-cw offmodel-cw-hum readme clean

$(MDPIPE): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/pip install --quiet --upgrade pip
	$(BIN)/pip install --quiet -e ".[test]"
	touch $@

install: $(MDPIPE)

demo: $(MDPIPE)
	$(MDPIPE) process data_samples/*.h5 --out out/demo
	$(MDPIPE) summarize out/demo

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

# The README's table of output columns, from mdpipe/process/columns.py (a test fails when they differ).
readme: $(MDPIPE)
	$(BIN)/python -m mdpipe.process.columns --write-readme

# Speed against error: each choice swept from the defaults, with the SNR breakdown (~1 min). bench.csv and
# bench.png hold timings, which differ from run to run: not committed; snr_breakdown.csv is reproducible.
bench: $(MDPIPE)
	$(BIN)/python benchmarks/bench_tradeoffs.py --out reports

# Full-size simulation benchmark (writes ~1.3 GB under BENCH_DIR, then removes it).
BENCH_DIR ?= /tmp
bench-sim: $(MDPIPE)
	$(BIN)/python benchmarks/bench_simulate.py --workdir $(BENCH_DIR)

# Full-size processing against a bare read, and a capture twice as long (~4 GB under BENCH_DIR, removed).
bench-scale: $(MDPIPE)
	$(BIN)/python benchmarks/bench_scale.py --workdir $(BENCH_DIR)

# mdpipe batch against one `mdpipe process` per capture two at a time, on the bundled samples, that way run
# with this mdpipe and with the mdpipe of the last commit before `mdpipe batch` (the former make rule) (~2 min).
BATCH_BASELINE ?= 4eec045^
bench-batch: $(MDPIPE)
	$(BIN)/python benchmarks/bench_batch.py --repeats 5 --baseline-commit '$(BATCH_BASELINE)'

# Receiver impairments: the bundled samples and 24 default-sweep scenes overdriven until 0.1-50 % of the samples clip,
# crossed by another radar's chirps, or with a drifting TX-RX leakage, read against their clean reading (~2 min).
bench-impairments: $(MDPIPE)
	$(BIN)/python benchmarks/bench_impairments.py

# The paper's Tables IV and V from simulations of every Table I and II configuration (~30 s).
paper: $(MDPIPE)
	$(MDPIPE) paper --out reports

# The evaluation benchmark: 240 seeded scenes (drones, birds, negatives; X / K / 77 / 94 GHz) simulated,
# processed and scored against what their physics makes estimable (a few minutes on 2 cores).
evaluate: $(MDPIPE)
	$(MDPIPE) evaluate configs/sweeps/default.yaml --out out/evaluate -j 2

# The default sweep simulated with its captures kept (~1 GB under out/evaluate_kept/captures), then processed again from
# them (--reuse-captures: no scene simulated): the two summaries' `wall` lines time a processing change's rerun, and
# the two scenes.csv must agree row by row (benchmarks/compare_scenes.py)
evaluate-reuse: $(MDPIPE)
	$(MDPIPE) evaluate configs/sweeps/default.yaml --out out/evaluate_kept -j 2 --keep-captures
	$(MDPIPE) evaluate configs/sweeps/default.yaml --out out/evaluate_reused -j 2 --reuse-captures out/evaluate_kept/captures
	$(BIN)/python benchmarks/compare_scenes.py out/evaluate_kept/scenes.csv out/evaluate_reused/scenes.csv

# The default sweep's distributions drawn with two other seeds: the same families and bands, scenes no change was
# tuned on (the default seed's numbers flatter the estimators; about 3 minutes each on 2 cores)
evaluate-fresh: $(MDPIPE)
	$(MDPIPE) evaluate configs/sweeps/default.yaml --seed 777 --out out/evaluate_fresh -j 2
	$(MDPIPE) evaluate configs/sweeps/default.yaml --seed 4321 --out out/evaluate_fresh_4321 -j 2

# The held-out drone sweep (another seed): what the estimators give on draws they were not tuned on
evaluate-heldout: $(MDPIPE)
	$(MDPIPE) evaluate configs/sweeps/heldout_drones.yaml --out out/evaluate_heldout -j 2

# The low-PRF sweep: the drone families at PRFs of 1.5-6 kHz, their tips folded many times, at the four seeds rules
# came from, 558 drawn after the other three's (~2 min each)
evaluate-heldout-lowprf: $(MDPIPE)
	$(MDPIPE) evaluate configs/sweeps/heldout_lowprf.yaml --out out/evaluate_heldout_lowprf -j 2
	$(MDPIPE) evaluate configs/sweeps/heldout_lowprf.yaml --seed 556 --out out/evaluate_heldout_lowprf_556 -j 2
	$(MDPIPE) evaluate configs/sweeps/heldout_lowprf.yaml --seed 557 --out out/evaluate_heldout_lowprf_557 -j 2
	$(MDPIPE) evaluate configs/sweeps/heldout_lowprf.yaml --seed 558 --out out/evaluate_heldout_lowprf_558 -j 2

# The low-PRF sweep at six more seeds, drawn after every rule (~15 min): a rule's check on draws it did not come from
evaluate-heldout-lowprf-fresh: $(MDPIPE)
	for seed in 561 562 563 564 565 566; do \
		$(MDPIPE) evaluate configs/sweeps/heldout_lowprf.yaml --seed $$seed --out out/evaluate_heldout_lowprf_$$seed -j 2 \
			|| exit 1; \
	done

# The held-out birds at the low-PRF sweep's PRFs, 1.5-6 kHz (~1 min a seed): does a bird read a drone there?
evaluate-heldout-lowprf-birds: $(MDPIPE)
	$(MDPIPE) evaluate configs/sweeps/heldout_lowprf_birds.yaml --out out/evaluate_heldout_lowprf_birds -j 2
	$(MDPIPE) evaluate configs/sweeps/heldout_lowprf_birds.yaml --seed 999 --out out/evaluate_heldout_lowprf_birds_999 -j 2

# The held-out bird sweep: the default sweep's birds at a counter-drone radar's PRF and dwell (~2 min)
evaluate-heldout-birds: $(MDPIPE)
	$(MDPIPE) evaluate configs/sweeps/heldout_birds.yaml --out out/evaluate_heldout_birds -j 2

# The held-out bird sweep drawn with another seed: birds no change was tuned on (~2 min)
evaluate-heldout-birds-fresh: $(MDPIPE)
	$(MDPIPE) evaluate configs/sweeps/heldout_birds.yaml --seed 999 --out out/evaluate_heldout_birds_999 -j 2

# mdpipe on 380 scenes of an FMCW simulator written apart from its own (benchmarks/offmodel): ~4 GB of captures
# kept under OFFMODEL_DIR and reused (about 17 min with -j 2 to simulate them, 2 min to process them again).
OFFMODEL_DIR ?= $(BENCH_DIR)/mdpipe_offmodel
OFFMODEL_ROWS ?= out/offmodel_rows.csv
offmodel: $(MDPIPE)
	mkdir -p $(dir $(OFFMODEL_ROWS))
	$(BIN)/python benchmarks/bench_offmodel.py --workdir $(OFFMODEL_DIR) -j 2 --rows $(OFFMODEL_ROWS)

# The blade count without --blades on 36 multirotor scenes of that simulator built to read it or to fool it (rotors of
# unequal blades, odd counts, rotors at one rate phased to cancel lines): captures kept under BLADES_DIR (~3 min).
BLADES_DIR ?= $(BENCH_DIR)/mdpipe_blade_count
offmodel-blades: $(MDPIPE)
	$(BIN)/python benchmarks/bench_blade_count.py --workdir $(BLADES_DIR) -j 2

# The same 380 scenes recorded by a CW radar (I/Q at the scene's PRF, no range), through an anti-alias filter and
# sampled without one: recordings kept under CW_DIR (~0.3 GB; about 15 min to render them, 2 min to process them again).
CW_DIR ?= $(BENCH_DIR)/mdpipe_cw
offmodel-cw: $(MDPIPE)
	$(BIN)/python benchmarks/bench_cw.py --workdir $(CW_DIR) -j 2

# The same recordings with mains hum added (50 Hz and its harmonics, in I only, 20 dB over the noise; a copy of each
# kept beside it under CW_DIR, ~0.3 GB), read with the hum searched (mdpipe/process/mains.py) and not (~6 min).
offmodel-cw-hum: $(MDPIPE)
	$(BIN)/python benchmarks/bench_cw.py --workdir $(CW_DIR) -j 2 --hum-db 20
	$(BIN)/python benchmarks/bench_cw.py --workdir $(CW_DIR) -j 2 --hum-db 20 --mains-hz none

# Every capture under IN (a folder, searched recursively), processed by JOBS worker processes into OUT
# (make batch IN=captures OUT=results JOBS=4 ARGS="--blades 3"). Only captures whose input, options or
# mdpipe version changed are redone (OUT/manifest.json); see `mdpipe batch --help`.
IN ?= data_samples
OUT ?= out/batch
JOBS ?= 2
ARGS ?=

batch: $(MDPIPE)
	$(MDPIPE) batch "$(IN)" --out "$(OUT)" -j $(JOBS) $(ARGS)

clean:
	rm -rf $(VENV) build *.egg-info .pytest_cache
