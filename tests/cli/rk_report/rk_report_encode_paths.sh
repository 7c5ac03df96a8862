#!/usr/bin/env bash
# CLI test rk_report_encode_paths: registered, and described, in tests/cli/rk_report.cmake.
set -eu
# Every test script gets the same three arguments (tests/cli/CMakeLists.txt, rk_cli_script).
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
# The page's series encoding (scripts/rk_interactive.py encode) has a numpy path (long series) and a pure-Python
# path (short ones, and every series where numpy is not installed): both must give the same bytes, and decoding
# must give back every value within half its quantum, gaps as gaps.
python3 - "$src/scripts" <<'PY'
import base64, math, random, struct, sys, zlib
sys.path.insert(0, sys.argv[1])
import rk_interactive as ix
if ix.numpy_or_none() is None:
    print("SKIP: numpy is not installed: only the pure-Python path exists")
    sys.exit(77)
rng = random.Random(7)
nan, inf = math.nan, math.inf
t = [1.0 + 0.05 * i + rng.gauss(0, 1e-4) for i in range(3000)]
cases = {
    "time": (t, 1e-9),
    "smooth angle": ([359.9 - 0.01 * i for i in range(3000)], None),
    "gaps": ([v if i % 97 else nan for i, v in enumerate(t)], None),
    "infinities": ([inf, 1.0, -inf, 2.0, nan], None),
    "all missing": ([nan] * 10, None),
    "negative, tiny": ([-1e-6 * rng.random() for _ in range(500)], None),
    "zero": ([0.0] * 20, None),
    "one row": ([42.5], None),
    "jump beyond int32": ([0.0, 1.0, 1e12, 2.0], 1e-3),
}
for name, (values, q) in cases.items():
    a = ix.encode(values, q, use_numpy=True)
    b = ix.encode(values, q, use_numpy=False)
    assert a == b, (name, a, b)
    if a is None:                                    # the float64 fallback (series())
        continue
    deltas = struct.unpack("<%di" % a["n"], zlib.decompress(base64.b64decode(a["z"])))
    k, out = a["k0"], []
    for d in deltas:
        if d == ix.NULL_DELTA:
            out.append(None)
            continue
        k += d
        out.append(k * a["q"])
    for v, w in zip(values, out):
        if not math.isfinite(v):
            assert w is None, (name, v, w)
        else:
            assert abs(v - w) <= 0.5 * a["q"] * (1 + 1e-9) + 1e-12 * abs(v), (name, v, w, a["q"])
print("encode: numpy and pure Python give the same bytes for", len(cases), "series; decoded within half a quantum")
PY
