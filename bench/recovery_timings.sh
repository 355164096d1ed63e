#!/usr/bin/env bash
# Recovery latencies of `tirpol acquire` with the real devices of the test rig (not a throughput
# benchmark): Aravis's fake GigE camera on 127.0.0.1, tirpol-stage-sim, the tirpol CLI.
#   1. re-running at once after `kill -9` of a session that streams from the camera (5 rounds);
#   2. the camera process killed mid-session: time from the kill to tirpol's exit ("camera disconnected");
#   3. SIGINT during a 45° move at 10°/s (APT simulator): time from the signal to tirpol's exit, and
#      where the stage stopped.
# Usage: bench/recovery_timings.sh BUILD_DIR        (needs arv-fake-gv-camera-0.8, package aravis-tools)
set -u
B=${1:?usage: recovery_timings.sh BUILD_DIR}
D=$(mktemp -d)
trap 'kill $FAKE $SIM 2>/dev/null; rm -rf "$D"' EXIT
FAKE=; SIM=
exec 9>/tmp/tirpol-loopback-gige.lock && flock 9   # one GigE device on 127.0.0.1:3956 at a time
arv-fake-gv-camera-0.8 -i 127.0.0.1 >/dev/null 2>&1 & FAKE=$!
sleep 1.5
CAM='aravis://127.0.0.1?pixel_format=Mono16&width=64&height=48&fps=50'
now() { date +%s.%N; }
elapsed() { echo "$2 - $1" | bc; }
printf 'frames_per_angle: 1\nsettle_s: 60\n' >"$D/hold.yaml"
printf 'frames_per_angle: 2\nsettle_s: 0\n' >"$D/quick.yaml"

echo "1. re-run right after kill -9 of a streaming session"
ok=0
for i in 1 2 3 4 5; do
  rm -rf "$D/h" "$D/q"
  "$B/apps/tirpol" acquire "$D/hold.yaml" --camera "$CAM" --stage sim:// -o "$D/h" --non-interactive >/dev/null 2>&1 & H=$!
  while [ ! -f "$D/h/session.json" ]; do sleep 0.05; done
  sleep 0.3
  kill -9 $H; wait $H 2>/dev/null
  t0=$(now)
  "$B/apps/tirpol" acquire "$D/quick.yaml" --camera "$CAM" --stage sim:// -o "$D/q" --non-interactive >"$D/q.log" 2>&1
  rc=$?; t1=$(now); [ $rc = 0 ] && ok=$((ok + 1))
  printf '   round %d: exit %d after %.1f s %s\n' $i $rc "$(elapsed $t0 $t1)" "$(grep -o 'still held.*s$\|privilege obtained.*' "$D/q.log" | head -1)"
done
echo "   $ok/5 sessions completed"

echo "2. camera killed mid-session"
printf 'frames_per_angle: 100\nsettle_s: 0\nframe_timeout_s: 30\n' >"$D/long.yaml"
"$B/apps/tirpol" acquire "$D/long.yaml" --camera "$CAM" --stage sim:// -o "$D/l" --non-interactive >"$D/l.log" 2>&1 & A=$!
while ! grep -q '"file"' "$D/l/session.json" 2>/dev/null; do sleep 0.05; done
t0=$(now); kill -9 $FAKE; wait $A; rc=$?; t1=$(now)
printf '   exit %d after %.2f s: %s\n' $rc "$(elapsed $t0 $t1)" "$(grep -o 'camera disconnected[^;]*' "$D/l.log" | cut -c1-150)"

echo "3. SIGINT 1.5 s into a 45° move at 10°/s"
"$B/acquisition/tirpol-stage-sim" --protocol apt --link "$D/stage" --move-deg-per-s 10 >/dev/null 2>&1 & SIM=$!
sleep 0.3
printf 'angles_deg: [0, 45]\nframes_per_angle: 2\nsettle_s: 0\n' >"$D/move.yaml"
"$B/apps/tirpol" acquire "$D/move.yaml" --camera 'sim://uniform?width=16&height=12' --stage "thorlabs-apt://$D/stage" \
  -o "$D/m" --non-interactive >"$D/m.log" 2>&1 & A=$!
while ! grep -q '"file"' "$D/m/session.json" 2>/dev/null; do sleep 0.05; done
sleep 1.5
t0=$(now); kill -INT $A; wait $A; rc=$?; t1=$(now)
printf '   exit %d after %.2f s: %s\n' $rc "$(elapsed $t0 $t1)" "$(grep -o 'stopped at [0-9.]*°' "$D/m.log")"
