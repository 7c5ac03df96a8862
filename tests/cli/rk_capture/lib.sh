# shellcheck shell=bash
# Sourced by the rk_capture/ test scripts.
# wait_links PATH...: waits until the emulators' links exist (they are made once the pty is up).
wait_links() { for i in $(seq 1 100); do ok=1; for l in "$@"; do [ -e "$l" ] || ok=0; done; [ $ok = 1 ] && return 0; sleep 0.05; done; echo "emulator did not start"; return 1; }
