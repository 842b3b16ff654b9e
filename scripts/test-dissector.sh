#!/usr/bin/env bash
# By hand: capture a loopback stream with tshark and decode it with tools/wireshark/rcsim.lua.
#   scripts/test-dissector.sh [BUILD_DIR] [SCENE]
# Needs tshark (Debian package `tshark`) and the right to capture on lo (root, or the wireshark
# group). Prints the decoded datagrams and checks that tshark saw as many as the listener got.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
scene="${2:-$root/docs/examples/front_approach.json}"
rcsim="$build/bin/rcsim"
dissector="$root/tools/wireshark/rcsim.lua"
port=47555
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

command -v tshark >/dev/null || { echo "tshark not found: apt-get install tshark" >&2; exit 1; }
tshark -l -P -i lo -f "udp dst port $port" -w "$work/live.pcapng" >"$work/capture.out" 2>"$work/capture.err" &
capture=$!
for _ in $(seq 100); do grep -q "Capture started" "$work/capture.err" && break; sleep 0.05; done
grep -q "Capture started" "$work/capture.err" || { cat "$work/capture.err" >&2; kill "$capture"; exit 1; }
sleep 0.5

"$rcsim" listen --port "$port" -o "$work/listened.csv" 2>"$work/listen.err" &
listener=$!
sleep 0.3
"$rcsim" stream "$scene" --to "127.0.0.1:$port" --speed 10 --messages simulated,truth
wait "$listener"
sleep 0.5
kill -INT "$capture"
wait "$capture" || true

tshark -r "$work/live.pcapng" -X lua_script:"$dissector" -Y rcsim 2>/dev/null | tail -n 5
decoded=$(tshark -r "$work/live.pcapng" -X lua_script:"$dissector" -Y rcsim 2>/dev/null | wc -l)
received=$(sed -n 's/^rcsim listen: \([0-9]*\) datagrams.*/\1/p' "$work/listen.err")
echo "tshark decoded $decoded rcsim datagrams; the listener received $received"
malformed=$(tshark -r "$work/live.pcapng" -X lua_script:"$dissector" -Y "_ws.expert.severity == error" 2>/dev/null | wc -l)
[ "$decoded" = "$received" ] && [ "$malformed" = 0 ] && echo OK
