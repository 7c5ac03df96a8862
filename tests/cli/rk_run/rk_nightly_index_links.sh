#!/usr/bin/env bash
# CLI test rk_nightly_index_links: registered, and described, in tests/cli/rk_run.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
. "$src/tests/cli/rk_run/lib.sh"
d=$data/run/links; r=$d/root; rm -rf "$d"; mkdir -p "$d/bin"
standin_rk_run "$d/bin/rk-run"
# Trial folders named as a file system allows and a URL does not: '#' (fragment), '?' (query), '%' (escape),
# a space, and a folder below another one.
for t in 't#1' 'run?2' '100%' '50%25' 'a b' 'site/t#3'; do
  mkdir -p "$r/$t/out"; echo '{}' > "$r/$t/trial.json"; echo '<html></html>' > "$r/$t/out/report.html"
done
rk-nightly "$r" --rk-run "$d/bin/rk-run" -q
python3 - "$r" <<'PY'
import html, os, re, sys, urllib.parse
root = sys.argv[1]
index = "file://" + urllib.parse.quote(root) + "/index.html"
hrefs = [html.unescape(h) for h in re.findall(r'<a href="([^"]*)"', open(root + "/index.html").read())]
assert len(hrefs) == 6, hrefs
for h in hrefs:
    u = urllib.parse.urlsplit(urllib.parse.urljoin(index, h))   # what a browser opens
    path = urllib.parse.unquote(u.path)
    assert not u.query and not u.fragment and os.path.isfile(path), (h, u)
print("links ok:", hrefs)
PY
echo ok
