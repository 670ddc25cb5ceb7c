#!/usr/bin/env bash
# The README's figures that come from the binary (issue 28): the controller
# table (max / RMS error of sjct, dyninv, scct and pid on STOP, SCHOOL and
# STOP --letter-height 3.6, with what SCCT fails) and the Monte Carlo
# example (STOP, 40 plants within +-10 %, seed 7). tests/doc_figures.rs
# computes them with the library calls `basr compile` and
# `basr simulate --json` make and compares them with README.md's blocks
# between `<!-- doc-figures: NAME -->` and `<!-- /doc-figures: NAME -->`;
# this script has it write the blocks anew instead (review `git diff
# README.md` after). `cargo test --test doc_figures` fails while they differ.
#
#   scripts/doc-figures.sh          # rewrite the blocks (release build, ~1 min)
#   scripts/doc-figures.sh --check  # only compare (exit 1 on a difference)
set -euo pipefail
cd "$(dirname "$0")/.."
case "${1:-}" in
    --check) exec nice -n 10 cargo test --release --quiet --test doc_figures ;;
    "") BASR_DOC_FIGURES=write exec nice -n 10 cargo test --release --quiet --test doc_figures ;;
    *) echo "usage: scripts/doc-figures.sh [--check]" >&2; exit 2 ;;
esac
