# rle_vision: `make demo` and `make test` do all set-up on a fresh Debian bookworm machine.
SHELL := /bin/bash
DURATION ?= 0
ARGS ?=
JOBS ?= 2
export JOBS
# RECORD=1 make bench / eval / bench-latency: write bench/results/ (the committed figures) and
# the docs' tables; by default they write the git-ignored bench/measured/.
RECORD ?= 0
export RECORD

.PHONY: all deps build demo test test-readme test-asan test-core test-install fuzz bench eval train-horizon train bench-latency screenshot clean

all: build

deps:
	@scripts/install_deps.sh

build: deps
	@scripts/build.sh

demo: build
	@scripts/demo.sh "$(DURATION)" $(ARGS)

test: build
	@scripts/run_tests.sh

test-readme: build
	@scripts/test_readme.sh

test-asan: deps
	@scripts/test_asan.sh

test-core: deps
	@scripts/test_core_plain.sh

test-install: build
	@scripts/test_install_space.sh

fuzz: deps
	@scripts/fuzz.sh

bench: build
	@scripts/bench.sh

eval: build
	@scripts/eval.sh

train-horizon: build
	@scripts/train_horizon.sh

train: build
	@scripts/train_verifier.sh

bench-latency: build
	@scripts/bench_latency.sh

screenshot: build
	@scripts/screenshot.sh

clean:
	rm -rf .ws .ws-asan .ws-fuzz
