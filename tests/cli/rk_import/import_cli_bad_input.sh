#!/usr/bin/env bash
# CLI test import_cli_bad_input: registered, and described, in tests/cli/rk_import.cmake.
set -eu
# shellcheck disable=SC2034
data=$1 expect=$2 src=$3
i=$data/import
o=$i/bad.csv
# A truncated CINE: the byte offset of the image that runs past the end; the report still written, failed.
"$expect" 3 "$o" "truncated.cine: byte [0-9]+: image 5 .* runs past the end of the file" -- \
  rk-import frames --video "$i/truncated.cine" -o "$o" --report "$i/bad.json"
grep -q '"status": "failed"' "$i/bad.json"
# A CIHX whose frame count disagrees with the .mraw's size: the XML line of totalFrame.
"$expect" 3 "$o" "count.cihx:[0-9]+: 3 frames of 6x4 12-bit packed need 108 bytes but .*count.mraw has 72" -- \
  rk-import frames --video "$i/count.mraw" -o "$o"
# An unknown bit depth.
"$expect" 3 "$o" "depth10.cihx:[0-9]+: unknown bit depth 10" -- rk-import frames --video "$i/depth10.cihx" -o "$o"
# Offsets past the end: OffImageOffsets (byte 32) moved beyond the file.
/usr/bin/python3 -c "
import struct, sys
b = bytearray(open(sys.argv[1], 'rb').read()); struct.pack_into('<I', b, 32, len(b) + 4096)
open(sys.argv[2], 'wb').write(b)" "$i/gaps.cine" "$i/offsets.cine"
"$expect" 3 "$o" "offsets.cine: byte [0-9]+: .*runs past the end of the file" -- rk-import frames --video "$i/offsets.cine" -o "$o"
# The .mraw without its header: an I/O error naming it.
cp "$i/count.mraw" "$i/alone.mraw"
"$expect" 4 "$o" "alone.mraw: no .cihx or .cih" -- rk-import frames --video "$i/alone.mraw" -o "$o"
# No times of its own and no --fps; a bad epoch; -o over the input.
"$expect" 2 "$o" "give --fps" -- rk-import frames --video "$data/extract/seq/%06d.png" -o "$o"
"$expect" 2 "$o" "--epoch-utc" -- rk-import frames --video "$i/gaps.cine" --epoch-utc 2023-13-01T00:00:00Z -o "$o"
before=$(sha256sum < "$i/gaps.cine")
"$expect" 2 - -- rk-import frames --video "$i/gaps.cine" -o "$i/gaps.cine"
[ "$(sha256sum < "$i/gaps.cine")" = "$before" ]
echo PASS
