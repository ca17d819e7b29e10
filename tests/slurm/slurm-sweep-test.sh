#!/bin/sh
# slurm-sweep-test.sh BENDER_CLI SOURCE_DIR: the same 3-candidate sweep (tests/data/sweep's
# tube bent by 0, 45 and 90 degrees, a coarse mesh) through --engine local and --engine slurm
# on a one-node cluster started here; both summaries must be the same, every candidate solved.
# Exit 77 (skipped) without root, slurm-wlm or munge, unless BENDER_REQUIRE_SLURM is set.
set -u
cli="$1"
src="$2"
here="$src/tests/slurm"
tmp=$(mktemp -d "${TMPDIR:-/tmp}/bender-slurm.XXXXXX")
cleanup() {
    "$here/one-node-cluster.sh" stop "$tmp/cluster"
    rm -rf "$tmp"
}
trap cleanup EXIT
trap 'exit 1' INT TERM

fail() {
    echo "FAIL: $*" >&2
    exit 1
}

conf=$("$here/one-node-cluster.sh" start "$tmp/cluster")
status=$?
if [ $status -eq 77 ] && [ -z "${BENDER_REQUIRE_SLURM:-}" ]; then
    echo "skipped: no one-node Slurm cluster here (root, slurm-wlm and munge: scripts/setup)"
    exit 77
fi
[ $status -eq 0 ] || fail "the one-node cluster did not start ($tmp/cluster/log)"
export SLURM_CONF="$conf"
command -v simpleFoam >/dev/null || fail "OpenFOAM is not installed (scripts/setup)"

data="$src/tests/data/sweep"
set -- "$data/tube.off" "$data/bend90.bender.json" --vary fraction=0:1:3 \
    --cell-size 0.001 --iterations 200

start=$(date +%s)
"$cli" sweep "$@" -o "$tmp/local" --engine local --jobs 2 || fail "the local sweep failed"
middle=$(date +%s)
"$cli" sweep "$@" -o "$tmp/slurm" --engine slurm --poll 0.5 || fail "the Slurm sweep failed"
end=$(date +%s)
echo "local: $((middle - start)) s, slurm: $((end - middle)) s"

solved=$(grep -c ',solved,' "$tmp/slurm/summary.csv")
[ "$solved" -eq 3 ] || fail "$solved of 3 candidates solved through Slurm"
# The same cases solved by the same programs: the same numbers, digit for digit.
cmp "$tmp/local/summary.csv" "$tmp/slurm/summary.csv" ||
    { diff "$tmp/local/summary.csv" "$tmp/slurm/summary.csv"; fail "Slurm and local differ"; }
# Each candidate ran as a task of one array job.
[ "$(ls "$tmp/slurm/slurm/status" | wc -l)" -eq 3 ] || fail "not one task per candidate"
echo "PASS: 3 candidates, Slurm and local agree"
