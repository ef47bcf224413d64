#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# modcp — receive-path cost per byte under callgrind (nothing asserted), as key=value:
#   rx_instr_per_byte=       modcp_link_on_byte() (link + framing), per received byte
#   rx_t15_instr_per_byte=   the same with the t1.5 check on
#   rx_timer_instr_per_byte= modcp_link_on_timer() while the frames arrive and at their
#                            end, spread over the bytes (the timer interrupt's share)
#   rx_cp_instr_per_byte=    modcp_cp_on_rx() (the port's entry, CP hooks included)
#   rx_modem_instr_per_byte= modcp_link_on_byte() in interference suppression (modem
#                            mode: the frame ends at its CRC, without t3.5)
#   rx_block_instr_per_byte= modcp_link_on_block(): the frame in one block (characters
#                            back to back, DMA / FIFO), per byte
#   slave_time_us_p50_<mode>_<baud>_cycle<ms>ms= / slave_time_us_model_...=
#                            the slave time with the injected clock (bench_rx slave-time)
# Frames: FC16 with 123 registers (255 bytes), 9600 baud, see bench_rx.c.
#   tests/bench/bench_rx.sh [BUILD_DIR]     default build/host (built if needed)
set -euo pipefail
cd "$(dirname "$0")/../.."
B=${1:-build/host}
FRAMES=${BENCH_RX_FRAMES:-200}
command -v valgrind >/dev/null || { echo "bench_rx.sh: valgrind is needed" >&2; exit 2; }
if [ -z "${1:-}" ]; then
  cmake --preset host >/dev/null
  cmake --build --preset host --target bench_rx >/dev/null
fi
X=$B/tests/bench/bench_rx
per_byte() { # mode function -> instructions per byte
  local out bytes coll
  out=$(valgrind --tool=callgrind --callgrind-out-file=/dev/null --toggle-collect="$2" \
        "$X" "$1" "$FRAMES" 2>&1)
  bytes=$(sed -n 's/^bytes=\([0-9]*\).*/\1/p' <<<"$out")
  coll=$(sed -n 's/.*Collected : \([0-9]*\).*/\1/p' <<<"$out")
  awk -v c="$coll" -v b="$bytes" 'BEGIN { printf "%.1f\n", c / b }'
}
echo "rx_instr_per_byte=$(per_byte link modcp_link_on_byte)"
echo "rx_t15_instr_per_byte=$(per_byte link-t15 modcp_link_on_byte)"
echo "rx_timer_instr_per_byte=$(per_byte link modcp_link_on_timer)"
echo "rx_cp_instr_per_byte=$(per_byte cp modcp_cp_on_rx)"
echo "rx_modem_instr_per_byte=$(per_byte link-modem modcp_link_on_byte)"
echo "rx_block_instr_per_byte=$(per_byte link-block modcp_link_on_block)"
"$X" slave-time "${BENCH_SLAVE_N:-200}"
