#!/usr/bin/env bash
# One benchmark sitting, the one the pages quote: every bench in both builds,
# the viewer's frame times and callgrind's instruction counts, written to
# docs/bench/ (see docs/bench/README.md). Then
#   RASTERLAB_UPDATE_DOCS=1 cargo test --release --test suite benched::
# rewrites the pages' generated blocks from it. Took 25 minutes on 2 cores, with
# the native build compiled from cold.
#
#   bash benches/sitting.sh            everything
#   bash benches/sitting.sh default    the default build's benches only
#   bash benches/sitting.sh native     the native build's benches only
#   bash benches/sitting.sh viewer     the viewer's frame times (needs xvfb-run)
#   bash benches/sitting.sh instructions   callgrind's counts (needs valgrind)
#   bash benches/sitting.sh stages BUILD   the stages bench, now and BEFORE in turns
set -euo pipefail
cd "$(dirname "$0")/.."
what=${1:-all}
# Pinned to one core, the other left to the system: the machine is shared and
# noisy, and one thread is what the tables compare.
pin="taskset -c 1 nice -n -15"
command -v taskset >/dev/null || pin=""

benches() { # build: default or native
    local flags="" target=target
    if [ "$1" = native ]; then
        flags="-C target-cpu=native"
        target=target/native
    fi
    for bench in stages versus_euc threads check; do
        if [ "$1" = native ] && [ $bench = check ]; then
            continue # check's time is quoted for the default build only
        fi
        local cores=$pin
        if [ $bench = threads ] && [ -n "$pin" ]; then
            cores="taskset -c 0,1 nice -n -15" # one thread against two: both cores
        fi
        if [ $bench = stages ]; then
            stages "$1"
            continue
        fi
        RUSTFLAGS="$flags" CARGO_TARGET_DIR=$target cargo build --release --features bench --bench $bench
        RASTERLAB_RECORD=1 RUSTFLAGS="$flags" CARGO_TARGET_DIR=$target CRITERION_HOME=$target/criterion \
            $cores cargo bench --features bench --bench $bench
    done
}

# The commit issue #20 was filed at: its stages bench runs beside ours, in the
# same sitting, so that "no stage slower than then" compares like with like.
BEFORE=247e374

# `stages BUILD`: our stages bench, and the same bench (benches/stages.rs and
# its harness) built against BEFORE's code (from `git archive`), so the cases,
# the criterion settings and the reading of the medians are ours. The two run
# case by case in turns, each case measured now and then seconds apart rather
# than minutes (the host's speed moves within minutes): docs/bench/stages-BUILD.tsv
# and stages-before-BUILD.tsv, the latter headed by BEFORE.
stages() {
    local flags="" now=$PWD/target then=$PWD/target/before
    if [ "$1" = native ]; then
        flags="-C target-cpu=native"
        now=$PWD/target/native
        then=$PWD/target/before/native
    fi
    local tree=$PWD/target/before/tree
    if [ ! -f "$tree/Cargo.toml" ]; then
        mkdir -p "$tree"
        git archive "$BEFORE" | tar -x -C "$tree"
    fi
    cp benches/stages.rs "$tree/benches/"
    cp -r benches/common "$tree/benches/"
    # `bench DIR TARGET ARGS...`: the stages bench of the tree in DIR.
    bench() {
        local dir=$1 target=$2
        shift 2
        # shellcheck disable=SC2086
        (cd "$dir" && RASTERLAB_RECORD=1 RASTERLAB_RECORD_ADD=1 RUSTFLAGS="$flags" CARGO_TARGET_DIR=$target \
            CRITERION_HOME=$target/criterion $pin cargo bench --features bench --bench stages -- "$@")
    }
    RUSTFLAGS="$flags" CARGO_TARGET_DIR=$now cargo build --release --features bench --bench stages
    (cd "$tree" && RUSTFLAGS="$flags" CARGO_TARGET_DIR=$then cargo build --release --features bench --bench stages)
    rm -f "docs/bench/stages-$1.tsv" "$tree/docs/bench/stages-$1.tsv"
    local cases
    cases=$(bench "$PWD" "$now" --list | sed -n 's/: benchmark$//p')
    while IFS= read -r case; do
        bench "$PWD" "$now" --exact "$case"
        bench "$tree" "$then" --exact "$case"
    done <<<"$cases"
    # The bench names the commit git finds, the one this tree lies in.
    sed "1s/^# commit [^,]*,/# commit $BEFORE,/" "$tree/docs/bench/stages-$1.tsv" >"docs/bench/stages-before-$1.tsv.new"
    mv "docs/bench/stages-before-$1.tsv.new" "docs/bench/stages-before-$1.tsv"
    local want
    want=$(($(grep -c . <<<"$cases") + 2))
    for sheet in "docs/bench/stages-$1.tsv" "docs/bench/stages-before-$1.tsv"; do
        if [ "$(wc -l <"$sheet")" -ne "$want" ]; then
            echo "sitting.sh: $sheet has not every case" >&2
            exit 1
        fi
    done
}

# One row of the viewer's own summary: `view LABEL ARGS...` runs it under Xvfb.
view() {
    local label=$1
    shift
    xvfb-run -a -s "-screen 0 1920x1200x24" target/release/rasterlab view "$@" 2>&1 >/dev/null |
        sed -nE "s/^view: [0-9]+ frames, frame time median ([0-9.]+) ms, draw median ([0-9.]+) ms$/$label\t\1\t\2/p"
}

viewer() {
    cargo build --release
    local out=docs/bench/viewer-default.tsv.new
    {
        echo "# commit $(git rev-parse --short=7 HEAD), $(date -u +%Y-%m-%d), default build, under Xvfb, pixel-light 500x500 unless the case says, threads: all cores"
        printf 'case\tframe_ms\tdraw_ms\n'
        for run in 1 2 3; do
            view "--fps 0, run $run" --fps 0 --frames 600
        done
        view "--fps 60" --frames 300
        view "cornell:183 1920x1080 --raster edge, --fps 0" \
            --scene cornell:183 --size 1920x1080 --raster edge --fps 0 --frames 300
    } >$out
    mv $out docs/bench/viewer-default.tsv
}

# Instructions per frame of pixel-light with each option beyond the handout:
# the difference between 11 timed renders and 1, over 10 (callgrind counts
# exactly, so one run each is enough).
instructions() {
    cargo build --release
    local out=docs/bench/instructions-default.tsv.new
    {
        echo "# commit $(git rev-parse --short=7 HEAD), $(date -u +%Y-%m-%d), default build, one thread, callgrind"
        printf 'case\tinstructions_per_frame\n'
        while IFS= read -r case; do
            local counts=()
            for n in 1 11; do
                # shellcheck disable=SC2086
                valgrind --tool=callgrind --callgrind-out-file=/tmp/rasterlab-cg.out \
                    target/release/rasterlab $case --threads 1 --time $n -o /tmp/rasterlab-cg.png \
                    >/dev/null 2>&1
                counts+=("$(sed -n 's/^summary: //p' /tmp/rasterlab-cg.out)")
            done
            printf '%s\t%s\n' "$case" $(((counts[1] - counts[0]) / 10))
        done <<'EOF'
depth
pixel-light
pixel-light --texture checker
pixel-light --texture checker --filter bilinear
pixel-light --texture checker --affine
pixel-light --normal-map bumps
pixel-light --texture checker --normal-map bumps --parallax
pixel-light --shadows
pixel-light --shadows --pcf
pixel-light --dof 4.001,0.05
depth --scene cornell:64
EOF
    } >$out
    mv $out docs/bench/instructions-default.tsv
    rm -f /tmp/rasterlab-cg.out /tmp/rasterlab-cg.png
}

case $what in
all) benches default && benches native && viewer && instructions ;;
default | native) benches "$what" ;;
viewer) viewer ;;
instructions) instructions ;;
stages) stages "${2:?which build: default or native}" ;;
*) echo "sitting.sh: unknown part '$what' (all, default, native, viewer, instructions, stages)" >&2 && exit 2 ;;
esac
