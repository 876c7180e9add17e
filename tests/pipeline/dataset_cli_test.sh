#!/bin/sh
# casmap dataset's exit statuses: 2 with file and field for a bad spec; 64 + failed count when
# samples fail (the run still writes its manifest); 0 on a rerun that finds everything.
# Usage: dataset_cli_test.sh CASMAP
set -u
casmap=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

printf 'count: 2\nscene:\n  pole_diameter_m: [0.001, 0.01]\n' > "$work/bad.yaml"
"$casmap" dataset --spec "$work/bad.yaml" --out "$work/bad" 2> "$work/err"
test $? -eq 2 || fail "bad spec: exit status $?"
grep -q "bad.yaml" "$work/err" && grep -q "scene.pole_diameter_m" "$work/err" ||
    fail "message names neither file nor field: $(cat "$work/err")"

mkdir "$work/meshes"
echo "not a mesh" > "$work/meshes/rock_01.ply"
printf 'count: 2\nregion: {length_m: 1.0}\nscene:\n  clutter_per_m2: 2\n  kind_weights: {box: 0, drum: 0, pole: 0, ramp: 0, curb: 0, step: 0, rock: 1}\n' \
    > "$work/rocks.yaml"
"$casmap" dataset --spec "$work/rocks.yaml" --out "$work/rocks" --meshes "$work/meshes" \
    2> "$work/err"
status=$?
test $status -eq 66 || fail "2 failed samples: exit status $status, expected 66"
test "$(grep -c '"status":"failed"' "$work/rocks/manifest.jsonl")" -eq 2 || fail "manifest"

printf 'count: 2\nregion: {length_m: 1.0}\ndomain: {angular_resolutions_deg: [1]}\n' > "$work/ok.yaml"
"$casmap" dataset --spec "$work/ok.yaml" --out "$work/ok" > /dev/null || fail "first run"
"$casmap" dataset --spec "$work/ok.yaml" --out "$work/ok" > "$work/out" || fail "rerun"
grep -q "0 generated, 2 reused" "$work/out" || fail "rerun did not reuse: $(cat "$work/out")"
# The manifest's re-simulate line, run as given in the sample's folder, writes a new run file
# and leaves the sample's own run.h5 (maps, filters, checksums) alone.
sample="$work/ok/samples/000000"
line=$(sed -n 's/.*"simulate":"\([^"]*\)".*/\1/p' "$sample/sample.json")
case "$line" in "casmap simulate "*) ;; *) fail "no simulate line: $line" ;; esac
(cd "$sample" && "$casmap" ${line#casmap } > /dev/null) || fail "re-simulate line: $line"
(cd "$sample" && sha256sum --quiet -c files.sha256) || fail "re-simulate line overwrote a file"
test "$(ls "$sample" | grep -c '\.h5$')" -eq 2 || fail "re-simulate line wrote no new run file"
# A run killed part-way (SIGKILL: no clean-up) resumes to the same bytes as a clean run.
printf 'count: 6\nseed: 9\nregion: {length_m: 1.0}\ndomain: {angular_resolutions_deg: [1]}\n' \
    > "$work/kill.yaml"
"$casmap" dataset --spec "$work/kill.yaml" --out "$work/clean" --threads 1 > /dev/null ||
    fail "clean run"
"$casmap" dataset --spec "$work/kill.yaml" --out "$work/killed" --threads 1 > /dev/null &
pid=$!
sleep 0.7
kill -9 $pid 2> /dev/null
wait $pid 2> /dev/null
"$casmap" dataset --spec "$work/kill.yaml" --out "$work/killed" --threads 1 > /dev/null ||
    fail "resume after kill"
diff -r "$work/clean" "$work/killed" || fail "resumed dataset differs from a clean run"
echo "exit statuses 2, 66 and 0 as documented; the re-simulate line keeps run.h5; a killed run resumes to the same bytes"
