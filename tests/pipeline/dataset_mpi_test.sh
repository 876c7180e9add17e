#!/bin/sh
# casmap dataset under mpirun: 1 process (threads) and 2 MPI ranks must write byte-identical
# samples and manifests.  Usage: dataset_mpi_test.sh CASMAP MPIRUN SOURCE_DIR
set -eu
casmap=$1
mpirun=$2
src=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cat > "$work/spec.yaml" <<SPEC
count: 4
seed: 3
region: {length_m: 1.0}
scene: {ground_cell_m: 0.1}
domain:
  motion_weights: {T: 1, TR: 1, TP: 1, TRP: 1, vehicle: 0}
  table_speed_m_s: 1.0
  angular_resolutions_deg: [1]
outputs: {pose_decimation: 10}
SPEC
cd "$src"
"$casmap" dataset --spec "$work/spec.yaml" --out "$work/one" --threads 1
OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl=self,vader \
    "$mpirun" --oversubscribe -n 2 "$casmap" dataset --spec "$work/spec.yaml" --out "$work/two" \
    --threads 1
diff -r "$work/one" "$work/two"
test "$(wc -l < "$work/two/manifest.jsonl")" -eq 4
echo "1 and 2 ranks: identical samples and manifest"
