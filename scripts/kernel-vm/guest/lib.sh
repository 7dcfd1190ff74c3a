# Helpers and cases for cases.sh (sourced; runs inside the test VM).
# The rig: vcan0; a gpio-sim chip whose lines carry the names tnv-fw's
# config asks for; tnv-board-emu serving the register window on a Unix
# socket; guest/ticker.c toggling the gpio-sim tick line at 100 Hz (the board
# emulator has no GPIO side, so the harness makes the edge); tnv-fw on all
# of it. Peers: tnvctl and can-utils.

RUN=/run/tnv
NODE=1
# tnv-fw's tick.period_us stays 1000: the firmware checks the board's
# latched tick period against a fixed 1 ms (tick_task.cpp
# kNominalPeriodClocks), so 10000 latches late_tick on every tick. The
# gpio-sim edge comes at TICK_HZ (slower is fine: the board emulator
# advances the table one 1 ms tick per edge, so simulated time runs at
# TICK_HZ/1000 of real time).
PERIOD_US=1000
TICK_HZ=100
TICK_US=$((1000000 / TICK_HZ))
BIN_FW=$build/tools/tnv-fw
BIN_EMU=$build/tools/tnv-board-emu
BIN_CTL=$build/tools/tnvctl
BIN_TICKER=$build/kernel-vm-ticker
SIM_CFG=/sys/kernel/config/gpio-sim/tnv
# gpio-sim line offsets (names as in packaging/tnv-fw.toml); SPARE is for the stock test.
LINE_NAMES=(TNV_TICK TNV_ESTOP TNV_ALARM_X TNV_ALARM_Y TNV_LIMIT_XP TNV_LIMIT_XN TNV_LIMIT_YP TNV_LIMIT_YN
            TNV_ENABLE_X TNV_ENABLE_Y TNV_SPARE)
SIM_SYS=""     # /sys/devices/platform/gpio-sim.N/gpiochipM, once live
SIM_CHIP=""    # gpiochipM
FW_PID="" EMU_PID="" TICKER_PID="" FLOOD_PIDS=()
mkdir -p "$RUN"

fail() { echo "  why: $*"; return 1; }
metric() { echo "TNV-METRIC $*"; }

# A sleep without fork (bash's read timeout on a FIFO nobody writes).
mkfifo "$RUN/nap.fifo"
exec {NAP_FD}<>"$RUN/nap.fifo"
nap() { read -r -t "$1" -u "$NAP_FD" _ || true; }

# wait_for SECONDS COMMAND...: polls every 10 ms until COMMAND succeeds.
wait_for() {
  local limit=$1; shift
  local end
  end=$(awk -v t="$EPOCHREALTIME" -v d="$limit" 'BEGIN{printf "%.6f", t + d}')
  until "$@"; do
    [[ ${EPOCHREALTIME/./} -lt ${end/./} ]] || return 1
    nap 0.01
  done
}

usec_since() { echo $(( ${EPOCHREALTIME/./} - ${1/./} )); }

# ---- gpio-sim -------------------------------------------------------------
offset_of() {
  local i
  for i in "${!LINE_NAMES[@]}"; do [[ ${LINE_NAMES[$i]} == "$1" ]] && { echo "$i"; return 0; }; done
  return 1
}
# drive NAME high|low: the simulated pull, i.e. what a consumer of an input reads.
drive() { echo "pull-$([[ $2 == high ]] && echo up || echo down)" > "$SIM_SYS/sim_gpio$(offset_of "$1")/pull"; }
# level NAME: the line's value (for an output requested by tnv-fw: what it drives).
level() { cat "$SIM_SYS/sim_gpio$(offset_of "$1")/value"; }

setup_gpio_sim() {
  [[ -n $SIM_SYS ]] && return 0
  [[ -d /sys/kernel/config/gpio-sim ]] || { fail "no /sys/kernel/config/gpio-sim (gpio-sim.ko not loaded?)"; return 1; }
  mkdir -p "$SIM_CFG/bank0" || return 1
  echo "${#LINE_NAMES[@]}" > "$SIM_CFG/bank0/num_lines"
  local i
  for i in "${!LINE_NAMES[@]}"; do
    mkdir -p "$SIM_CFG/bank0/line$i"
    echo "${LINE_NAMES[$i]}" > "$SIM_CFG/bank0/line$i/name"
  done
  echo 1 > "$SIM_CFG/live" || { fail "gpio-sim chip did not go live"; return 1; }
  SIM_CHIP=$(cat "$SIM_CFG/bank0/chip_name")
  SIM_SYS=/sys/devices/platform/$(cat "$SIM_CFG/dev_name")/$SIM_CHIP
  [[ -d $SIM_SYS ]] || { fail "no $SIM_SYS"; return 1; }
  # Idle levels: e-stop and servo alarms are active low (released = high).
  drive TNV_ESTOP high; drive TNV_ALARM_X high; drive TNV_ALARM_Y high
}

setup_vcan() {
  ip link show vcan0 >/dev/null 2>&1 && return 0
  ip link add dev vcan0 type vcan || { fail "ip link add vcan0 type vcan failed"; return 1; }
  ip link set vcan0 txqueuelen 1000
  ip link set vcan0 up || { fail "vcan0 does not come up"; return 1; }
}

# ---- CAN helpers ----------------------------------------------------------
# expect_reply ID_HEX REGEX FRAME...: sends FRAMEs with cansend and waits up
# to 3 s for a frame with identifier ID_HEX whose "ID#DATA" matches REGEX.
expect_reply() {
  local id=$1 regex=$2; shift 2
  local out=$RUN/reply.$id.log
  candump -L -n 1 -T 10000 "vcan0,$id:7FF" > "$out" &
  local dump=$!
  dump_ready "$id" || return 1
  local f
  for f in "$@"; do cansend vcan0 "$f" || { fail "cansend $f failed"; return 1; }; done
  wait "$dump"
  local got
  got=$(awk '{print $3}' "$out")
  [[ -n $got ]] || { fail "no reply with id $id within 10 s to $*"; return 1; }
  [[ $got =~ $regex ]] || { fail "reply to $* was $got, expected /$regex/"; return 1; }
  echo "  $* -> $got"
}

# dump_ready ID_HEX: candump's filter for ID_HEX is installed on vcan0.
dump_ready() {
  wait_for 30 grep -qiE "vcan0 +0*$1 +0*7ff" /proc/net/can/rcvlist_fil \
    || { fail "candump's filter for $1 never appeared: $(cat /proc/net/can/rcvlist_fil)"; return 1; }
}

# frame_field FRAME BYTE_OFFSET LEN: little-endian unsigned field of "ID#HEX".
frame_field() {
  local hex=${1#*#} off=$2 len=$3 v=0 i
  for ((i = len - 1; i >= 0; i--)); do v=$(( (v << 8) | 16#${hex:$(( (off + i) * 2 )):2} )); done
  echo "$v"
}
# Identifier = message id << 5 | node id (protocol 5, firmware/can/can_id.hpp).
hb_id() { printf '%03X' $(( (0x0C << 5) | NODE )); }
fault_id() { printf '%03X' $(( (0x01 << 5) | NODE )); }
last_heartbeat() {  # one HEARTBEAT frame, "ID#HEX"
  candump -L -n 1 -T 10000 "vcan0,$(hb_id):7FF" | awk '{print $3}'
}

ctl() { "$BIN_CTL" --iface vcan0 --node "$NODE" --timeout-ms 10000 "$@"; }

# ---- the rig --------------------------------------------------------------
start_ticker() {
  [[ -n $TICKER_PID ]] && return 0
  [[ -x $BIN_TICKER ]] || { fail "missing $BIN_TICKER (run.sh builds it)"; return 1; }
  rm -f "$RUN/tick.hold" "$RUN/tick.held"
  # nice -10: the edge stands for the FPGA's tick, which no load delays.
  # Not SCHED_FIFO: gpio-sim's edge IRQ thread (FIFO 50) must run first.
  nice -n -10 "$BIN_TICKER" "$SIM_SYS/sim_gpio$(offset_of TNV_TICK)/pull" "$TICK_US" \
    "$RUN/tick.hold" "$RUN/tick.held" &
  TICKER_PID=$!
}
tick_hold() {
  : > "$RUN/tick.hold"
  wait_for 10 test -e "$RUN/tick.held" || { fail "the ticker did not stop"; return 1; }
}
tick_release() { rm -f "$RUN/tick.hold"; }
# tick_step: exactly one rising edge on the tick line (ticker held).
tick_step() { drive TNV_TICK high; nap 0.002; drive TNV_TICK low; }

write_fw_config() {
  cat > "$RUN/fw.toml" <<EOF
[board]
transport = "socket"
path = "$RUN/board.sock"
connect_timeout_ms = 10000
# generous: under TCG on a loaded host the emulator process can be late
reply_timeout_ms = 1000

[can]
interface = "vcan0"
node_id = $NODE

[lines]
tick = { name = "TNV_TICK" }
estop = { name = "TNV_ESTOP", active_low = true }
alarm_x = { name = "TNV_ALARM_X", active_low = true }
alarm_y = { name = "TNV_ALARM_Y", active_low = true }
limit_x_pos = { name = "TNV_LIMIT_XP" }
limit_x_neg = { name = "TNV_LIMIT_XN" }
limit_y_pos = { name = "TNV_LIMIT_YP" }
limit_y_neg = { name = "TNV_LIMIT_YN" }
enable_x = { name = "TNV_ENABLE_X" }
enable_y = { name = "TNV_ENABLE_Y" }

[rt]
priority = 80
cpu = -1
require = true

[tick]
period_us = $PERIOD_US

[params]
file = "$RUN/params.bin"
EOF
}

fw_alive() { [[ -n $FW_PID ]] && kill -0 "$FW_PID" 2>/dev/null; }
need_fw() { fw_alive || { fail "tnv-fw is not running (see fw_start)"; return 1; }; }

stop_everything() {
  local p
  for p in "${FLOOD_PIDS[@]}" $TICKER_PID $FW_PID $EMU_PID; do kill "$p" 2>/dev/null; done
  wait 2>/dev/null
}

# ---- cases ----------------------------------------------------------------
case_stock_can() {
  setup_vcan || return 1
  expect_reply 123 '^123#DEADBEEF$' '123#DEADBEEF'
}

case_stock_gpio() {
  setup_gpio_sim || return 1
  local off out=$RUN/gpiomon.log
  off=$(offset_of TNV_SPARE)
  timeout 5 gpiomon --num-events=1 --rising-edge "$SIM_CHIP" "$off" > "$out" 2>&1 &
  local mon=$!
  wait_for 10 eval 'gpioinfo "$SIM_CHIP" | grep -E "line +$off:" | grep -q used' \
    || { fail "gpiomon never requested line $off"; return 1; }
  drive TNV_SPARE high
  wait "$mon" || { fail "gpiomon saw no rising edge on $SIM_CHIP line $off within 5 s: $(cat "$out")"; return 1; }
  grep -q "RISING EDGE" "$out" || { fail "gpiomon printed: $(cat "$out")"; return 1; }
  echo "  $(cat "$out")"
}

case_fw_start() {
  setup_vcan && setup_gpio_sim || return 1
  [[ -x $BIN_FW && -x $BIN_EMU && -x $BIN_CTL ]] || { fail "missing $BIN_FW, $BIN_EMU or $BIN_CTL"; return 1; }
  write_fw_config
  "$BIN_FW" --config "$RUN/fw.toml" --check-config || { fail "tnv-fw refuses the VM config"; return 1; }
  # nice -10: the emulator stands for the FPGA board, which answers in
  # microseconds whatever the CPU load.
  nice -n -10 "$BIN_EMU" --socket "$RUN/board.sock" --scenario no-cut > "$RUN/emu.log" 2>&1 &
  EMU_PID=$!
  wait_for 30 test -S "$RUN/board.sock" || { fail "tnv-board-emu did not serve $RUN/board.sock: $(cat "$RUN/emu.log")"; return 1; }
  start_ticker || return 1
  "$BIN_FW" --config "$RUN/fw.toml" > "$RUN/fw.out" 2> "$RUN/fw.log" &
  FW_PID=$!
  wait_for 30 grep -q "tnv-fw: running" "$RUN/fw.log" || { fail "tnv-fw did not start: $(cat "$RUN/fw.log")"; return 1; }
  cat "$RUN/fw.log"
  need_fw
}

case_heartbeat() {
  need_fw || return 1
  local out=$RUN/hb.log
  candump -L -n 3 -T 10000 "vcan0,$(hb_id):7FF" > "$out"
  local n
  n=$(wc -l < "$out")
  ((n == 3)) || { fail "candump saw $n HEARTBEAT frames (id $(hb_id)) in 10 s, expected 3"; return 1; }
  local f a
  # HEARTBEAT.axes (byte 7): nothing is homed after a start.
  f=$(sed -n 1p "$out" | awk '{print $3}'); a=$(frame_field "$f" 7 1)
  (( (a & 0x0F) == 0 )) || { fail "HEARTBEAT.axes says an axis is homed after a start ($a)"; return 1; }
  local s0 s2
  s0=$(sed -n 1p "$out" | tr -d '()' | awk '{print $1}'); s2=$(sed -n 3p "$out" | tr -d '()' | awk '{print $1}')
  awk -v a="$s0" -v b="$s2" 'BEGIN{exit !(b > a)}' || { fail "the heartbeats' timestamps do not advance ($s0 -> $s2)"; return 1; }
  metric "heartbeat seconds_per_2_frames=$(awk -v a="$s0" -v b="$s2" 'BEGIN{printf "%.3f", b-a}')"
  cat "$out"
}

case_param_roundtrip() {
  need_fw || return 1
  ctl params set tlm.heartbeat_ms=50 || { fail "tnvctl params set tlm.heartbeat_ms=50 failed"; return 1; }
  # Read back raw: PARAM_REQUEST tag 0x11 (host 1, sequence 1) get 0x0020 -> PARAM_REPLY tag 0x11, ok, id
  # 0x0020, value 50.
  expect_reply 121 '^121#1100200032000000$' 101#1100200000000000 || return 1
  local got
  got=$(ctl params get tlm.heartbeat_ms) || { fail "tnvctl params get failed"; return 1; }
  echo "  tnvctl params get: $got"
  grep -Eq 'tlm\.heartbeat_ms.*\b50\b' <<<"$got" || { fail "tnvctl read back '$got', expected 50"; return 1; }
}

case_malformed() {
  need_fw || return 1
  local ok=0
  # Byte 0 of every request is its tag (host id << 4 | sequence), echoed in byte 0 of the reply.
  # PARAM_REQUEST of 2 bytes: bad_length (6).
  expect_reply 121 '^121#1206' 101#1200 || ok=1
  # get of an unknown parameter id 0x7FFF: unknown_id (1), value 0.
  expect_reply 121 '^121#1301FF7F00000000$' 101#1300FF7F00000000 || ok=1
  # stage tlm.heartbeat_ms = 70000 (range 0..60000): out_of_range (3), value unchanged (50).
  expect_reply 121 '^121#1403200032000000$' 101#1402200070110100 || ok=1
  # stage motion.circle_ramp_s = NaN: not_finite (4).
  expect_reply 121 '^121#15043000' 101#150230000000C07F || ok=1
  # COMMAND with code 0xFF: COMMAND_ACK tag 16, request 2, code FF, unknown_command (7).
  expect_reply 061 '^061#1602FF07' 041#16FF000000000000 || ok=1
  # get from host 0 (anonymous): no_host (17 = 0x11).
  expect_reply 121 '^121#0011' 101#0000200000000000 || ok=1
  # enable from host 2 while nobody holds command ownership: not_owner (18 = 0x12).
  expect_reply 061 '^061#21020012' 041#2100000000000000 || ok=1
  return $ok
}

case_circle() {
  need_fw || return 1
  ctl enable || { fail "tnvctl enable failed"; return 1; }
  wait_for 5 enables_on || { fail "after enable the gpio-sim enable lines read x=$(level TNV_ENABLE_X) y=$(level TNV_ENABLE_Y), expected 1 1"; return 1; }
  ctl params set motion.circle_dwell_s=0.05 motion.circle_ramp_s=0.05 || { fail "could not shorten dwell/ramp"; return 1; }
  local started=$EPOCHREALTIME hb state fault
  # --no-wait, then the heartbeat: tnvctl's own wait budgets real time at
  # 1 kHz ticks, and the VM's gpio-sim tick runs at TICK_HZ.
  ctl circle --radius-mm 0.2 --feed-mm-s 5 --no-wait || { fail "tnvctl circle refused"; return 1; }
  hb=$(last_heartbeat); state=$(frame_field "$hb" 0 1)
  ((state == 1 || state == 2)) || { fail "heartbeat after the circle started: $hb (state $state, expected dwell 1 or moving 2)"; return 1; }
  local end=$((SECONDS + 90))
  while ((SECONDS < end)); do
    hb=$(last_heartbeat); state=$(frame_field "$hb" 0 1); fault=$(frame_field "$hb" 1 1)
    ((state == 3 || state == 4)) && break
  done
  ((state == 3 && fault == 0)) || { fail "circle did not end holding without fault: last heartbeat $hb (state $state, fault $fault)"; return 1; }
  metric "circle radius_mm=0.2 feed_mm_s=5 wall_s=$(awk -v u="$(usec_since "$started")" 'BEGIN{printf "%.2f", u/1e6}')"
  local st
  st=$(ctl status) || { fail "tnvctl status failed"; return 1; }
  echo "  status: $st"
}

enables_safe() { [[ $(level TNV_ENABLE_X) == 0 && $(level TNV_ENABLE_Y) == 0 ]]; }
enables_on() { [[ $(level TNV_ENABLE_X) == 1 && $(level TNV_ENABLE_Y) == 1 ]]; }

# The e-stop line is pressed with the ticker held, then exactly one tick
# edge is made: the enable lines must be off after that one tick (however
# long TCG takes to run it), and the FAULT_EVENT must say estop.
case_estop_gpio() {
  need_fw || return 1
  enables_on || ctl enable || { fail "tnvctl enable failed"; return 1; }
  enables_on || { fail "enable lines x=$(level TNV_ENABLE_X) y=$(level TNV_ENABLE_Y) before the e-stop, expected 1 1"; return 1; }
  candump -L -n 1 -T 10000 "vcan0,$(fault_id):7FF" > "$RUN/fault.log" &
  local dump=$!
  dump_ready "$(fault_id)" || return 1
  tick_hold || return 1
  drive TNV_ESTOP low   # active low: pressed
  nap 0.3
  local before_tick="on"
  enables_on || before_tick="x=$(level TNV_ENABLE_X) y=$(level TNV_ENABLE_Y)"
  local stepped=$EPOCHREALTIME
  tick_step
  wait_for 5 enables_safe || { tick_release; fail "enable lines x=$(level TNV_ENABLE_X) y=$(level TNV_ENABLE_Y) one tick after the e-stop, expected 0 0"; return 1; }
  metric "estop_gpio outputs_safe_after_ticks=1 wall_us=$(usec_since "$stepped") enables_before_the_tick=$before_tick"
  tick_release
  wait "$dump"
  local f
  f=$(awk '{print $3}' "$RUN/fault.log")
  [[ $f =~ ^$(fault_id)#04 ]] || { fail "FAULT_EVENT after the e-stop line was '$f', expected reason 04 (estop)"; return 1; }
  echo "  FAULT_EVENT $f"
  if ctl clear-faults; then fail "clear-faults accepted while the e-stop line is still pressed"; return 1; fi
  drive TNV_ESTOP high
  nap 0.2
  ctl clear-faults || { fail "clear-faults refused after the e-stop line was released"; return 1; }
  ctl enable || { fail "enable refused after clearing the e-stop"; return 1; }
}

case_bus_flood() {
  need_fw || return 1
  command -v cangen >/dev/null || { fail "cangen missing"; return 1; }
  [[ $(level TNV_ENABLE_X) == 1 ]] || ctl enable || { fail "tnvctl enable failed"; return 1; }
  local before
  before=$(last_heartbeat)
  [[ -n $before ]] || { fail "no heartbeat before the flood"; return 1; }
  # Flood at full load: other nodes' requests (valid and random lengths),
  # frames of unknown ids, and malformed requests to our node (2-byte
  # PARAM_REQUEST gets: each is answered with bad_length).
  # The circle first: during the flood tnvctl could not tell its replies from
  # the answers to the flood's own requests to our node (same PARAM_REPLY id).
  ctl circle --radius-mm 0.5 --feed-mm-s 2 --no-wait || { fail "circle refused"; return 1; }
  local frames_before flood_start=$EPOCHREALTIME
  frames_before=$(can_frames)
  # (nice 19: the flooder stands for other machines on the bus, not for load on this board.)
  local g
  for g in "-I 202 -L r -D r" "-I 7FF -L 8 -D r" "-I 085 -L r -D i" "-I 201 -L 2 -D 0000"; do
    # shellcheck disable=SC2086
    nice -n 19 cangen vcan0 -g 0 $g > /dev/null 2>&1 & FLOOD_PIDS+=($!)
  done
  # The e-stop goes out only once the flood is on the bus: a guest the host
  # starves for a moment (TCG on a busy machine) starts its flooders late.
  wait_for 10 frames_since "$frames_before" 1000 || { stop_flood; fail "the flooders put under 1000 frames on vcan0 in 10 s"; return 1; }
  nap 0.5
  candump -L -n 1 -T 5000 "vcan0,$(fault_id):7FF" > "$RUN/fault.log" &
  local dump=$!
  dump_ready "$(fault_id)" || { stop_flood; return 1; }
  local raised=$EPOCHREALTIME
  cansend vcan0 "$(printf '%03X' "$NODE")#"   # ESTOP (0x00) to our node, DLC 0
  wait_for 5 enables_safe || { stop_flood; fail "enable lines still on 5 s after a CAN e-stop under flood"; return 1; }
  metric "bus_flood estop_to_outputs_safe_us=$(usec_since "$raised") tick_us=$TICK_US"
  wait "$dump"
  local f after
  f=$(awk '{print $3}' "$RUN/fault.log")
  after=$(last_heartbeat)
  local frames_after
  frames_after=$(can_frames)
  stop_flood
  metric "bus_flood frames_on_vcan0=$((frames_after - frames_before)) seconds=$(awk -v u="$(usec_since "$flood_start")" 'BEGIN{printf "%.2f", u/1e6}')"
  # A flood that never happened proves nothing: at least 200 frames/s (the
  # node's own traffic is ~20/s; cangen -g 0 reaches 1000-11000/s under TCG,
  # depending on the host's load).
  local flood_frames=$((frames_after - frames_before)) flood_ms=$(( $(usec_since "$flood_start") / 1000 ))
  ((flood_frames * 1000 >= 200 * flood_ms)) || { fail "only $flood_frames frames in $flood_ms ms: no flood"; return 1; }
  [[ $f =~ ^$(fault_id)#(04|0C) ]] || { fail "FAULT_EVENT under flood was '$f', expected estop"; return 1; }
  [[ -n $after ]] || { fail "no heartbeat after the flood"; return 1; }
  local o0 o1
  o0=$(frame_field "$before" 4 1); o1=$(frame_field "$after" 4 1)  # HEARTBEAT.overruns: u8 at byte 4 (protocol 3)
  metric "bus_flood heartbeat_overruns_before=$o0 after=$o1"
  echo "  heartbeat before $before after $after"
  ((o1 == o0)) || { fail "heartbeat overruns went from $o0 to $o1 during the flood (missed/late ticks)"; return 1; }
  ctl clear-faults && ctl enable || { fail "could not clear the e-stop after the flood"; return 1; }
}
can_frames() { awk '/received frames/{print $1; exit}' /proc/net/can/stats; }
frames_since() { (( $(can_frames) - $1 >= $2 )); }
stop_flood() {
  local p
  for p in "${FLOOD_PIDS[@]}"; do kill "$p" 2>/dev/null; wait "$p" 2>/dev/null; done
  FLOOD_PIDS=()
}

case_sigterm() {
  need_fw || return 1
  ctl clear-faults >/dev/null 2>&1   # whatever an earlier case left latched
  [[ $(level TNV_ENABLE_X) == 1 ]] || ctl enable || { fail "tnvctl enable failed"; return 1; }
  [[ $(level TNV_ENABLE_X) == 1 && $(level TNV_ENABLE_Y) == 1 ]] || { fail "enable lines not 1 before SIGTERM"; return 1; }
  kill -TERM "$FW_PID"
  local rc=0
  wait "$FW_PID" || rc=$?
  FW_PID=""
  tail -n 3 "$RUN/fw.log"
  ((rc == 0)) || { fail "tnv-fw exited $rc after SIGTERM: $(tail -n 3 "$RUN/fw.log")"; return 1; }
  grep -q "stopped (SIGTERM)" "$RUN/fw.log" || { fail "tnv-fw did not report the SIGTERM stop"; return 1; }
  # Lines released by tnv-fw read back the simulated pull (down): 0.
  [[ $(level TNV_ENABLE_X) == 0 && $(level TNV_ENABLE_Y) == 0 ]] \
    || { fail "enable lines x=$(level TNV_ENABLE_X) y=$(level TNV_ENABLE_Y) after SIGTERM, expected 0 0"; return 1; }
}

case_cyclictest() {
  command -v cyclictest >/dev/null || { fail "cyclictest (rt-tests) missing"; return 1; }
  local out=$RUN/cyclictest.log
  # The VM's tick interval (10 ms), FIFO 80, 5 s: the same as tnv-fw --latency-test below.
  cyclictest -m -q -p 80 -i "$TICK_US" -D 5 -h 100000 > "$out" 2>&1 || { fail "cyclictest failed: $(tail -3 "$out")"; return 1; }
  local mn av mx
  mn=$(awk '/^# Min Latencies:/{print $4}' "$out"); av=$(awk '/^# Avg Latencies:/{print $4}' "$out")
  mx=$(awk '/^# Max Latencies:/{print $4}' "$out")
  [[ -n $mx ]] || { fail "no latency summary in cyclictest output: $(tail -5 "$out")"; return 1; }
  metric "cyclictest interval_us=$TICK_US seconds=5 min_us=$((10#$mn)) avg_us=$((10#$av)) max_us=$((10#$mx))"
}

case_latency_test() {
  [[ -x $BIN_FW ]] || { fail "missing $BIN_FW"; return 1; }
  local out=$RUN/latency.log
  cat > "$RUN/lat.toml" <<EOF
[board]
transport = "socket"
path = "$RUN/unused.sock"
[can]
interface = "vcan0"
[rt]
priority = 80
cpu = -1
require = true
[tick]
period_us = $TICK_US
EOF
  "$BIN_FW" --config "$RUN/lat.toml" --latency-test 5 > "$out" 2>&1 || { fail "tnv-fw --latency-test failed: $(tail -5 "$out")"; return 1; }
  grep -Ev '^ *(>=)?[0-9]+ us: ' "$out"   # everything but the histogram rows
  local line
  line=$(grep -Ei 'max' "$out" | grep -v '^#' | head -1)
  [[ -n $line ]] || { fail "no max figure in the latency-test output"; return 1; }
  metric "latency_test interval_us=$TICK_US seconds=5 $(tr -s ' ' <<<"$line")"
}
