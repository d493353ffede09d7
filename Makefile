# Two entry points for a fresh machine (see README): `make run` and `make test`.
PYTHON ?= python3
VENV   ?= .venv
BIN     = $(VENV)/bin
OUT    ?= runs/demo

.PHONY: run test test-all lint bench clean

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --upgrade pip

# torch first, pinned: its CPU wheel is on this machine; an unpinned torch (pulled by stable-baselines3) would
# download GBs of CUDA packages.
$(VENV)/.installed: pyproject.toml | $(BIN)/python
	$(BIN)/python -m pip install "torch==2.13.0"
	$(BIN)/python -m pip install -e ".[dev,rl]"
	touch $@

# The main job: a headless closed-loop (sigmoid, thesis Algorithm 1) brushing rollout on a curly wig that writes a
# rerun recording, a video, a JSON summary and a plot into $(OUT).
run: $(VENV)/.installed
	MUJOCO_GL=$${MUJOCO_GL:-egl} $(BIN)/hairbrush rollout --env HairBrush-v8 --wig curly --policy sigmoid \
		--episodes 1 --max-steps 30 --seed 0 --rerun $(OUT)/rollout.rrd --video $(OUT)/rollout.webm \
		--json $(OUT)/rollout.json --plot $(OUT)/rollout.png

# Default suite (< 10 min on 2 cores); long physics runs are marked `slow`.
test: $(VENV)/.installed
	$(BIN)/ruff check .
	$(BIN)/lint-imports
	MUJOCO_GL=$${MUJOCO_GL:-egl} $(BIN)/python -m pytest -n 2 -q

test-all: $(VENV)/.installed
	MUJOCO_GL=$${MUJOCO_GL:-egl} $(BIN)/python -m pytest -n 2 -q -m "slow or not slow"

lint: $(VENV)/.installed
	$(BIN)/ruff check . && $(BIN)/ruff format --check .

bench: $(VENV)/.installed
	$(BIN)/python scripts/benchmark_topology.py

clean:
	rm -rf $(VENV) runs .pytest_cache
