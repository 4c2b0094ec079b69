#!/bin/bash
# Resident memory of a bake a moment into its solve (what a level holds before its links), then stops
# the bake. usage: bench/rss_at_solve.sh WALKRAD SCENE VIEWS [DELAY_SECONDS, default 3]
# (Used for the 150-room level: what it holds before its links.)
B=$1; S=$2; V=$3; DELAY=${4:-3}
out=$(mktemp -d)
coproc BAKE { exec "$B" bake "$S" --views "$V" -o "$out/bake" --threads 2 2>&1; }
P=$BAKE_PID
while IFS= read -r l <&"${BAKE[0]}"; do
  case "$l" in *"walkrad: solve"*) sleep "$DELAY"; echo "$(basename "$B"): $(grep -E 'VmRSS|VmHWM' /proc/$P/status | tr -s ' \t' ' ' | tr '\n' ' ')"; kill $P; break;; esac
done
wait $P 2>/dev/null
rm -rf "$out"
