#!/usr/bin/env bash
# Idempotent set-up for a fresh Debian 12 machine (run as root, or with sudo available):
# installs the Debian packages that are missing, then configures and builds with CMake.
#   scripts/setup.sh            Release build in build/
#   scripts/setup.sh --asan     also an ASan+UBSan build in build-asan/
#   scripts/setup.sh --asan-only  only the ASan+UBSan build (what scripts/test.sh needs)
#   scripts/setup.sh --slurm    also Slurm and munge (for the rk-slurm test, tests/run/slurm_array_test.sh)
#   scripts/setup.sh --fuzz     also clang and libFuzzer, and the fuzz harnesses in build-fuzz/ (tests/fuzz)
#   scripts/setup.sh --browser  also Debian's chromium, for the headless-browser test of the report pages
#   scripts/setup.sh --tshark   also Debian's tshark (Wireshark's ASTERIX dissector), the independent decoder the
#                               radar-feed test checks rk-import asterix against
#   scripts/setup.sh --kml-schema  also xmllint and the OGC KML 2.2 schema (taken out of Debian's pytrainer package,
#                               not installed: build-cache/kml-schema/), which the KML export test validates against
#   scripts/setup.sh --gige     also Aravis' software GigE Vision camera and arv-tool (aravis-tools, -cli), which the
#                               aravis: capture test runs in a private network namespace, and faketime (the
#                               software camera's clock set back and forth: a camera clock that resets)
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
ASAN=0
RELEASE=1
SLURM=0
FUZZ=0
BROWSER=0
TSHARK=0
GIGE=0
KML_SCHEMA=0
for arg in "$@"; do
  case "$arg" in
    --asan) ASAN=1 ;;
    --asan-only) ASAN=1; RELEASE=0 ;;
    --slurm) SLURM=1 ;;
    --fuzz) FUZZ=1 ;;
    --browser) BROWSER=1 ;;
    --tshark) TSHARK=1 ;;
    --gige) GIGE=1 ;;
    --kml-schema) KML_SCHEMA=1 ;;
    *) echo "setup.sh: error: unknown option $arg" >&2; exit 2 ;;
  esac
done

PACKAGES=(
  build-essential cmake pkg-config git
  libopencv-dev libeigen3-dev libceres-dev libcli11-dev nlohmann-json3-dev libgeographiclib-dev liberfa-dev libssl-dev
  libgtest-dev libgmock-dev googletest libbenchmark-dev
  python3 python3-matplotlib ffmpeg
  help2man bash-completion bsdutils
  libopencv-contrib-dev opencv-doc
  libtinyxml2-dev  # Photron .cihx headers are XML (lib/video/mraw_file.cc)
  libpcap-dev      # radar feeds captured as pcap/pcapng (lib/asterix/capture.cc)
  libaravis-dev    # GigE Vision / USB3 Vision cameras, "aravis:" sources (lib/capture/aravis_source.cc)
  libusb-1.0-0-dev # aravis-0.8.pc requires libusb-1.0.pc, which libaravis-dev does not pull in
)
# Slurm daemons only on request: nobody needs them to use rangekit on one machine (rk-nightly); the
# test that starts a one-node cluster installs them through --slurm.
if [ "$SLURM" = 1 ]; then PACKAGES+=(slurmctld slurmd slurm-client munge); fi
# clang 14 and its runtime libraries (libFuzzer, ASan, UBSan) for the fuzz harnesses only.
if [ "$FUZZ" = 1 ]; then PACKAGES+=(clang libclang-rt-14-dev); fi
# Headless Chromium opens the report pages in ctest (rk_report_pages_in_chromium); nobody needs a browser to
# build or run rangekit, so only the test set-up installs it.
if [ "$BROWSER" = 1 ]; then PACKAGES+=(chromium); fi
# tshark only for the test that compares rk-import asterix with Wireshark's decoder (import_cli_asterix_real).
if [ "$TSHARK" = 1 ]; then PACKAGES+=(tshark); fi
# Aravis' software GigE Vision camera (arv-fake-gv-camera-0.8) and arv-tool-0.8 for the aravis: capture tests;
# faketime to give the software camera a clock that resets.
if [ "$GIGE" = 1 ]; then PACKAGES+=(aravis-tools aravis-tools-cli iproute2 util-linux faketime); fi
if [ "$KML_SCHEMA" = 1 ]; then PACKAGES+=(libxml2-utils); fi
# npm for the report pages' packages (below): Debian's nodejs and npm when the machine has no npm of its own.
if ! command -v npm >/dev/null 2>&1; then PACKAGES+=(nodejs npm); fi
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO=sudo; fi
missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}" >&2
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}" >&2
fi

# The OGC KML 2.2 schema (ogckml22.xsd with the atom-author-link.xsd and xAL.xsd it imports): Debian ships it only
# inside pytrainer, a GTK application; its .deb is downloaded and only the schemas taken out, nothing installed.
SCHEMA_DIR=$ROOT/build-cache/kml-schema
if [ "$KML_SCHEMA" = 1 ] && [ ! -f "$SCHEMA_DIR/usr/share/pytrainer/schemas/ogckml22.xsd" ]; then
  mkdir -p "$ROOT/build-cache/deb"
  if ! (cd "$ROOT/build-cache/deb" && apt-get download pytrainer >&2 2>/dev/null); then
    $SUDO apt-get update -qq
    (cd "$ROOT/build-cache/deb" && apt-get download pytrainer >&2)
  fi
  rm -rf "$SCHEMA_DIR"
  dpkg-deb -x "$(ls "$ROOT"/build-cache/deb/pytrainer_*.deb | head -1)" "$SCHEMA_DIR.tmp"
  mkdir -p "$SCHEMA_DIR/usr/share/pytrainer"
  mv "$SCHEMA_DIR.tmp/usr/share/pytrainer/schemas" "$SCHEMA_DIR/usr/share/pytrainer/schemas"
  rm -rf "$SCHEMA_DIR.tmp"
fi

# The report pages' interactive figures (uPlot, three.js, bundled by esbuild) and their browser test's driver
# (playwright-core): npm packages pinned in package-lock.json, installed into node_modules/ from the npm registry
# (npm itself with the packages above). Nothing of them is fetched when a page is opened.
if [ ! -f "$ROOT/node_modules/.package-lock.json" ] || [ "$ROOT/package-lock.json" -nt "$ROOT/node_modules/.package-lock.json" ]; then
  (cd "$ROOT" && npm ci --no-audit --no-fund --loglevel=error >&2)
fi

JOBS=$(nproc)
if [ "$RELEASE" = 1 ]; then
  cmake -S "$ROOT" -B "$ROOT/build" -DCMAKE_BUILD_TYPE=Release >&2
  cmake --build "$ROOT/build" -j"$JOBS" >&2
fi
if [ "$ASAN" = 1 ]; then
  # -O1 -g1: the sanitizers' usual level. Against -O2 -g it compiles ≈ 1.7x faster (UBSan's checks in
  # Eigen- and CLI11-heavy code dominate), keeps line numbers in the reports, and still runs the suite
  # at a reasonable pace. NDEBUG as in Release, so both builds run the same code.
  echo "== setup.sh: ASan+UBSan build at ${SECONDS} s" >&2
  cmake -S "$ROOT" -B "$ROOT/build-asan" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DRANGEKIT_ENABLE_ASAN=ON \
    -DRANGEKIT_BUILD_BENCH=OFF >&2
  cmake --build "$ROOT/build-asan" -j"$JOBS" >&2
fi
if [ "$FUZZ" = 1 ]; then
  # clang++ with -fsanitize=fuzzer,address,undefined in a folder of its own; -O1 -g1 and assertions on
  # (no NDEBUG: a failed assert is a finding). Only the harnesses and the modules they link are built.
  echo "== setup.sh: libFuzzer build at ${SECONDS} s" >&2
  cmake -S "$ROOT" -B "$ROOT/build-fuzz" -DCMAKE_CXX_COMPILER=clang++ -DRANGEKIT_BUILD_FUZZ=ON \
    -DRANGEKIT_BUILD_TESTS=OFF -DRANGEKIT_BUILD_BENCH=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1" >&2
  cmake --build "$ROOT/build-fuzz" -j"$JOBS" --target fuzz_all >&2
fi
echo "== setup.sh: done at ${SECONDS} s" >&2
