#!/bin/sh
# examples/python/read_dataset.py over a freshly generated two-sample dataset.
# Usage: read_dataset_test.sh CASMAP SOURCE_DIR
set -eu
casmap=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
printf 'count: 2\nregion: {length_m: 1.0}\ndomain: {angular_resolutions_deg: [1]}\n' \
    > "$work/spec.yaml"
cd "$src"
"$casmap" dataset --spec "$work/spec.yaml" --out "$work/data" --threads 1
out=$(/usr/bin/python3 examples/python/read_dataset.py "$work/data")
echo "$out"
test "$(echo "$out" | grep -c '^sample ')" -eq 2
echo "$out" | grep -q '^labels: valid [1-9]'
