#!/usr/bin/env bash
# Peers at their own speed (issue 46): each peer traced by the suite (`accelbench trace`, one
# thread, single mode) and by a standalone caller on the same `.rays` files, compared
#  1. in instructions per ray under Callgrind (noise-free): the inclusive count of the timed
#     region (the suite: `harness::timing::time_pass`, one timed pass with --repeats 1; the
#     standalone programs: `trace_all`), and of the peer's own entry point (`rtcIntersect1`,
#     `BVH8_CPU::Intersect`, which `trace` calls in its timed and its counting pass), so the
#     caller's share per ray is the difference;
#  2. in wall-clock Mrays/s, suite and standalone alternating, ROUNDS pairs.
#
# Usage (from the repository root, libembree-dev and g++ installed, valgrind for step 1):
#   tools/peers_standalone.sh [MESH] [PRIMARY_SIZE] [INCOHERENT] [ROUNDS]
# Defaults: ../shared/meshes/stanford_bunny.obj, 256 (x 256 pixels), 65536 rays, 5 rounds.
# Callgrind runs on these sets; the wall-clock rounds on the protocol's full sets (1024 x 1024
# and 1,048,576), median of 5 repeats per standalone process. Set CALLGRIND=0 or WALL=0 to skip
# a step. Output: a table on stdout; the raw files under $WORK (default /tmp/peers-standalone).
# The binaries: $ACCELBENCH for the clock (default: cargo build --release --features peers) and
# $ACCELBENCH_V3 for Callgrind (default: the same built for AVX2 with --target
# x86_64-unknown-linux-gnu, which keeps it apart from the native build in the same target dir).
# HITS=1 (passed on to tools/embree_standalone.c) makes the C program keep every ray's answer,
# as the suite's timed pass does; without it the program only counts hits.
# Figures of 2026-12-07: docs/results/2026-12-07-peers-standalone.md.
set -euo pipefail

MESH=${1:-../shared/meshes/stanford_bunny.obj}
SIZE=${2:-256}
INCOH=${3:-65536}
ROUNDS=${4:-5}
WORK=${WORK:-/tmp/peers-standalone}
mkdir -p "$WORK"

if [[ -z "${ACCELBENCH:-}" ]]; then
    cargo build --release --features peers --quiet
    ACCELBENCH="${CARGO_TARGET_DIR:-target}/release/accelbench"
fi
cc -O2 -g -o "$WORK/embree_standalone" tools/embree_standalone.c -lembree3
g++ -O3 -g -std=c++20 -march=native -Ithird_party/tinybvh -o "$WORK/tinybvh_standalone" \
    tools/tinybvh_standalone.cpp -lpthread

# The small sets for Callgrind, the protocol's sets for the clock.
"$ACCELBENCH" rays --scene "$MESH" --set primary --size "$SIZE" --out "$WORK/primary-small.rays" >/dev/null
"$ACCELBENCH" rays --scene "$MESH" --set incoherent --count "$INCOH" --out "$WORK/incoherent-small.rays" >/dev/null
"$ACCELBENCH" rays --scene "$MESH" --set primary --out "$WORK/primary.rays" >/dev/null
"$ACCELBENCH" rays --scene "$MESH" --set incoherent --out "$WORK/incoherent.rays" >/dev/null

# The standalone command for a peer on a rays file, REPEATS repeats.
standalone() { # PEER RAYS REPEATS
    case $1 in
        embree) "$WORK/embree_standalone" "$MESH" "$2" robust "$3" ;;
        embree-fast) "$WORK/embree_standalone" "$MESH" "$2" fast "$3" ;;
        tinybvh-bvh8) "$WORK/tinybvh_standalone" "$MESH" "$2" "$3" ;;
    esac
}
suite() { # PEER RAYS
    "$ACCELBENCH" trace --scene "$MESH" --index "$1" --rays "$2" --threads 1 --repeats 5
}
# The peer's own entry points as Callgrind names them (a fixed string).
entry() {
    case $1 in
        embree*) echo '???:rtcIntersect1 ' ;;
        tinybvh-bvh8) echo 'tinybvh::BVH8_CPU::Intersect<' ;;
    esac
}
# Sum of the inclusive Ir of the functions whose entry contains the fixed string $2 in profile
# $1: the lines that name their object file (`[...]`), one per function with all its inlined
# code (the lines without it are the parts of a function inlined from other source files).
incl() {
    callgrind_annotate --inclusive=yes --auto=no --threshold=100 "$1" 2>/dev/null |
        grep -F -- "$2" | grep -E '\]$' | awk '{ gsub(",", "", $1); s += $1 } END { print s + 0 }'
}

PEERS=(embree embree-fast tinybvh-bvh8)
if [[ "${CALLGRIND:-1}" != 0 ]]; then
    # Valgrind does not decode AVX-512: the suite and the C++ program built for AVX2
    # (docs/profiling.md); Embree picks its AVX2 kernels under Valgrind by itself.
    if [[ -z "${ACCELBENCH_V3:-}" ]]; then
        RUSTFLAGS="-C target-cpu=x86-64-v3" CFLAGS=-march=x86-64-v3 CXXFLAGS=-march=x86-64-v3 \
            cargo build --release --features peers --quiet --target x86_64-unknown-linux-gnu --bin accelbench
        ACCELBENCH_V3="${CARGO_TARGET_DIR:-target}/x86_64-unknown-linux-gnu/release/accelbench"
    fi
    g++ -O3 -g -std=c++20 -march=x86-64-v3 -Ithird_party/tinybvh -o "$WORK/tinybvh_standalone_v3" \
        tools/tinybvh_standalone.cpp -lpthread
    echo "instructions per ray (Callgrind): set, peer, suite: timed region (time_pass) and the peer's part | standalone: trace_all and the peer's part | region suite / standalone, peer part suite / standalone"
    for set in primary incoherent; do
        rays="$WORK/$set-small.rays"
        n=$(($(stat -c %s "$rays") / 32))
        for peer in "${PEERS[@]}"; do
            s="$WORK/cg-suite-$peer-$set.out"
            c="$WORK/cg-alone-$peer-$set.out"
            valgrind --tool=callgrind --callgrind-out-file="$s" "$ACCELBENCH_V3" trace --scene "$MESH" \
                --index "$peer" --rays "$rays" --threads 1 --repeats 1 >"$s.log" 2>&1
            case $peer in
                embree) alone=("$WORK/embree_standalone" "$MESH" "$rays" robust 1) ;;
                embree-fast) alone=("$WORK/embree_standalone" "$MESH" "$rays" fast 1) ;;
                tinybvh-bvh8) alone=("$WORK/tinybvh_standalone_v3" "$MESH" "$rays" 1) ;;
            esac
            valgrind --tool=callgrind --callgrind-out-file="$c" "${alone[@]}" >"$c.log" 2>&1
            e=$(entry "$peer")
            awk -v set="$set" -v peer="$peer" -v n="$n" \
                -v sr="$(incl "$s" 'timing::time_pass [')" -v sp="$(incl "$s" "$e")" \
                -v cr="$(incl "$c" ':trace_all')" -v cp="$(incl "$c" "$e")" \
                'BEGIN { printf "%-10s %-13s %7.1f %7.1f | %7.1f %7.1f | %.3f %.3f\n", set, peer,
                         sr / n, sp / (2 * n), cr / n, cp / n, sr / cr, (sp / 2) / cp }'
        done
    done
fi

if [[ "${WALL:-1}" != 0 ]]; then
    echo "wall clock, Mrays/s per round (suite then standalone, alternating), one thread"
    for set in primary incoherent; do
        rays="$WORK/$set.rays"
        for peer in "${PEERS[@]}"; do
            line="$set $peer:"
            for _ in $(seq "$ROUNDS"); do
                a=$(suite "$peer" "$rays" | awk '/^Mrays/ { print $2 }')
                b=$(standalone "$peer" "$rays" 5 | sed -E 's/.* ([0-9.]+) Mrays.*/\1/')
                line+=" $(awk -v a="$a" -v b="$b" 'BEGIN { printf "%.2f/%.2f=%.3f", a, b, a / b }')"
            done
            echo "$line"
        done
    done
fi
