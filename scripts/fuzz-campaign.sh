#!/usr/bin/env bash
# Fuzzes every topography reader for a number of executions each (the `reader` target with
# FUZZ_READER set to the reader's name; the names come from the registry, printed by the
# `reader_names` example), then `topography` for as many, then the study target for a
# wall-clock time, one at a time, and prints a Markdown table (target, runs, seconds, crashes,
# peak RSS). Not part of `cargo test` or CI. Needs the nightly toolchain and cargo-fuzz
# (`cargo install cargo-fuzz`); see fuzz/README.md.
#
#   scripts/fuzz-campaign.sh [RUNS_PER_READER] [STUDY_SECONDS] [TARGET...]
#
# A TARGET is a reader name (`x3p`, …), `topography` or `study`. Defaults: 1000000 runs per
# reader and for `topography`, 3600 s for `study`, every target. Seeds: the
# fixtures in tests/data and the shared instrument files. Inputs are at most MAX_LEN bytes
# (default 4096, libFuzzer's own default; longer seeds are truncated): headers, where the
# readers' sizes and offsets are declared, lie within it, and a run of 10^6 inputs takes
# minutes instead of hours (with 64 KiB inputs the Nanoscope target ran 72 inputs/s).
set -euo pipefail
cd "$(dirname "$0")/../fuzz"
runs=${1:-1000000}
study_seconds=${2:-3600}
max_len=${MAX_LEN:-4096}
shift 2 2>/dev/null || shift $#
mapfile -t readers < <(cd .. && cargo run -q -p asperity-numerics --example reader_names)
[ ${#readers[@]} -gt 0 ] || { echo "no reader names (cargo run --example reader_names failed)" >&2; exit 1; }
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=("${readers[@]}" topography study)
shared=../../shared/data/topography
log_dir=target/fuzz-logs
mkdir -p "$log_dir"
echo "| target | runs | seconds | crashes | peak RSS (MB) |"
echo "|---|---:|---:|---:|---:|"
for t in "${targets[@]}"; do
  corpus=corpus/$t
  seeds=target/seeds/$t
  mkdir -p "$corpus" "$seeds"
  if [ "$t" = study ]; then
    cp ../studies/*.yaml ../tests/studies/bad/*.yaml "$seeds"/ 2>/dev/null || true
    limit=(-max_total_time="$study_seconds")
    # The study target links the whole application (polars included): built without ASAN (safe
    # Rust has nothing for it to find; panics, timeouts and -rss_limit_mb still count) into a
    # target folder of its own, so it does not rebuild the readers' ASAN build.
    features=(-s none --target-dir target-study --features study)
  else
    cp ../tests/data/* "$seeds"/ 2>/dev/null || true
    if [ -d "$shared" ]; then find "$shared" -type f ! -name '*.md' ! -name '*.json' -size -8M -exec cp {} "$seeds"/ \; ; fi
    limit=(-runs="$runs")
    features=()
  fi
  # A reader name runs the `reader` target on that reader alone, its crashes kept apart.
  fuzz_target=$t
  reader_env=()
  if [ "$t" != study ] && [ "$t" != topography ]; then
    fuzz_target=reader
    reader_env=(FUZZ_READER="$t")
    mkdir -p "artifacts/$t"
    limit+=(-artifact_prefix="artifacts/$t/")
  fi
  start=$(date +%s)
  status=0
  env "${reader_env[@]}" cargo +nightly fuzz run "${features[@]}" "$fuzz_target" "$corpus" "$seeds" -- \
    "${limit[@]}" -max_len="$max_len" -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 \
    > "$log_dir/$t.log" 2>&1 || status=$?
  seconds=$(( $(date +%s) - start ))
  done_runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log_dir/$t.log" | grep -o '[0-9]*$' | tail -1)
  rss=$(grep -o 'stat::peak_rss_mb: *[0-9]*' "$log_dir/$t.log" | grep -o '[0-9]*$' | tail -1)
  crashes=$(ls "artifacts/$t" 2>/dev/null | wc -l)
  [ "$status" -eq 0 ] || crashes="$crashes (exit $status, see $log_dir/$t.log)"
  echo "| $t | ${done_runs:-?} | $seconds | $crashes | ${rss:-?} |"
done
