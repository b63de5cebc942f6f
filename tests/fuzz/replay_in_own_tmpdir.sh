#!/bin/sh
# Runs a replay driver with TMPDIR a new empty folder and fails if the driver
# fails or leaves anything in it (its scratch folder must go at exit).
#   replay_in_own_tmpdir.sh DRIVER INPUTS
tmp=$(mktemp -d) || exit 1
TMPDIR=$tmp "$1" "$2"
rc=$?
left=$(ls -A "$tmp")
rm -rf "$tmp"
[ "$rc" -eq 0 ] || exit "$rc"
[ -z "$left" ] || { echo "replay_in_own_tmpdir.sh: $1 left in TMPDIR: $left" >&2; exit 1; }
