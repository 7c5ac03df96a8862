#!/usr/bin/env bash
# CLI test rk_nightly_symlinks: registered, and described, in tests/cli/rk_run.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/rk_run/lib.sh"
d=$data/run/symlinks; r=$d/root; rm -rf "$d"; mkdir -p "$d/bin" "$d/other/t9" "$r/t1"
standin_rk_run "$d/bin/rk-run"
echo '{}' > "$r/t1/trial.json"; echo '{}' > "$d/other/t9/trial.json"
# Symbolic links: to a trial on another disk (followed), to a trial found anyway, back up to ROOT, to nothing.
ln -s "$d/other/t9" "$r/linked"; ln -s t1 "$r/again"; ln -s . "$r/loop"; ln -s "$d/gone" "$r/dangling"
rk-nightly "$r" --rk-run "$d/bin/rk-run" > "$d/nightly.out" 2> "$d/nightly.err"
cat "$d/nightly.out" "$d/nightly.err"
python3 - "$r" <<'PY'
import json, sys
s = json.load(open(sys.argv[1] + "/rk-nightly-summary.json"))
assert [t["trial"] for t in s["trials"]] == ["linked", "t1"], s["trials"]
assert s["counts"]["done"] == 2, s["counts"]
got = {p["path"]: p["reason"] for p in s["not_followed"]}
assert sorted(got) == ["again", "dangling", "loop"], got
assert got["again"].startswith("the same folder as t1") and got["loop"].startswith("the same folder as ROOT"), got
assert "does not exist" in got["dangling"], got
PY
for p in again dangling loop; do
  grep -q "^rk-nightly: warning: $r/$p not searched: " "$d/nightly.err"
  grep -q "^not searched: $p: " "$r/rk-nightly-summary.txt"
done
echo ok
