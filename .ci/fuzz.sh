#!/usr/bin/env bash
# Builds the libFuzzer target for the protocol decoder with clang (separate build dir)
# and runs it for a short time. Exits non-zero if the build fails or the fuzzer finds a
# crash, a sanitizer report or a leak.
#   .ci/fuzz.sh [seconds]        (default 30; FUZZ_BUILD_DIR overrides the build dir)
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
seconds="${1:-30}"
build="${FUZZ_BUILD_DIR:-$here/build-fuzz}"
jobs="${FUZZ_JOBS:-1}"

cmake -S "$here" -B "$build" -G Ninja \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined" \
  -DFTS_FUZZ=ON -DFTS_BUILD_TESTS=OFF >/dev/null
cmake --build "$build" -j"$jobs" --target fts_fuzz_decode

corpus="$build/fuzz-corpus"
mkdir -p "$corpus"
# Seeds: a JSON ping and a few header shapes (version 2, 21-byte header), so the fuzzer
# starts past the header.
printf 'FTSP\x00\x03\x00\x00\x00\x00\x00\x00\x01\x00\x00\x00\x00\x00\x00\x00\x00[{"t":"ping"}]' >"$corpus/ping.json.bin"
printf 'FTSP\x00\x03\x00\x00\x00\x00\x00\x00\x01\x00\x00\x00\x00\x00\x00\x00\x00[{"t":"input","ack":3,"f":[[1,1,-1,0]]}]' >"$corpus/input.json.bin"
printf 'FTSP\x00\x03\x01\x00\x00\x00\x00\x00\x01\x00\x00\x00\x00\x00\x00\x00\x00\x91\x81\xa1t\xa4ping' >"$corpus/ping.msgpack.bin"
printf 'FTSP\x00\x03\x00\x00\x00\x00\x00\x00\x01\x00\x00\x00\x00\x00\x00\x00\x00[{"t":"snap","tick":5,"base":4,"part":0,"parts":1,"phase":"play","level":1,"hz":100,"balls":[[3,1,2,3,4,16,16,0,0]],"mv":[[1,2,3,4,5]],"players":[{"i":1,"c":5}],"gone":[2],"events":[[1,4,0,1,2,3]]}]' >"$corpus/snap.json.bin"
# A MessagePack delta whose motion entries are the packed bits of "mv" (PROTOCOL.md 8.2).
printf 'FTSP\x00\x03\x01\x00\x00\x00\x00\x00\x01\x00\x00\x00\x00\x00\x00\x00\x00\x91\x8b\xa1\x74\xa4\x73\x6e\x61\x70\xa4\x74\x69\x63\x6b\x05\xa4\x62\x61\x73\x65\x04\xa2\x68\x7a\x64\xa4\x70\x61\x72\x74\x00\xa5\x70\x61\x72\x74\x73\x01\xa5\x70\x68\x61\x73\x65\xa4\x70\x6c\x61\x79\xa5\x6c\x65\x76\x65\x6c\x01\xa5\x62\x61\x6c\x6c\x73\x90\xa2\x6d\x76\xc4\x05\x90\x00\x00\x00\x3e\xa7\x70\x6c\x61\x79\x65\x72\x73\x90' >"$corpus/snap-mv.msgpack.bin"

# The handshake and control messages (each read by its field table), JSON and MessagePack.
printf 'FTSP\x00\x02\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00[{"t":"hello","name":"ann","token":"","cookie":"","pad":"..","nonce":"5eed0fa11c0ffee5","join":"join","room":"KXBQT"}]' >"$corpus/hello.json.bin"
printf 'FTSP\x00\x02\x00\x00\x00\x00\x00\x00\x01\x00\x00\x00\x00\x00\x00\x00\x00[{"t":"welcome","player_id":1,"token":"bcf8ef0b804a8357ee42dd8334a3619d","tick_rate_hz":100,"snapshot_rate_hz":20,"arena_width_u":500,"arena_height_u":300,"max_players":8,"timeout_ms":10000,"reconnect_window_ms":60000,"input_redundancy":3,"server_tick":0,"reconnected":false,"frame_s":0.01,"multiplier_upgrade_factor":1.1,"bank_interest_factor":1.1,"room":"KXBQT","spectator":true}]' >"$corpus/welcome.json.bin"
printf 'FTSP\x00\x02\x00\x00\x00\x00\x00\x00\x01\x00\x00\x00\x00\x00\x00\x00\x00[{"t":"cmd","rid":1,"op":"buy","item":"m"},{"t":"cmd","rid":2,"op":"chat","text":"gg"},{"t":"result","rid":1,"cmd":1,"ok":true,"code":"ok","msg":"m"},{"t":"chat","rid":1,"from":0,"name":"host","text":"hi"},{"t":"error","code":"full","msg":"x"},{"t":"bye","reason":"quit"},{"t":"challenge","cookie":"00000000000003e83c15b96815ccf35a8bb078310802c3e0"}]' >"$corpus/control.json.bin"
# cmd {rid 1, op "buy", item "m"} and result {rid 1, cmd 1, ok true, code "ok", msg ""} in MessagePack.
printf 'FTSP\x00\x02\x01\x00\x00\x00\x00\x00\x01\x00\x00\x00\x00\x00\x00\x00\x00\x92\x84\xa1t\xa3cmd\xa3rid\x01\xa2op\xa3buy\xa4item\xa1m\x86\xa1t\xa6result\xa3rid\x01\xa3cmd\x01\xa2ok\xc3\xa4code\xa2ok\xa3msg\xa0' >"$corpus/control.msgpack.bin"

cd "$build"
UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
  ./protocol/fts_fuzz_decode -max_total_time="$seconds" -max_len=1300 -print_final_stats=1 "$corpus"
