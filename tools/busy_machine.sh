#!/usr/bin/env bash
# The README's test command with every core of the machine busy: one CPU-bound process per core beside it
# (issue 29: a test that waits on a process or a browser must hold on a busy machine).
# Usage: bash tools/busy_machine.sh   (from the checkout, after the README's first command)
set -uo pipefail
cd "$(dirname "$0")/.."
hogs=()
for _ in $(seq "$(nproc)"); do
  python3 -c 'while True: pass' &
  hogs+=($!)
done
trap 'kill "${hogs[@]}" 2>/dev/null' EXIT
start=$(date +%s)
.venv/bin/python -m pytest -q -p no:cacheprovider
status=$?
echo "busy machine: $(nproc) CPU-bound processes beside the tests; exit $status after $(( $(date +%s) - start )) s"
exit $status
