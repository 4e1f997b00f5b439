#!/usr/bin/env bash
# Instruction profile of the rasterizer on an emulated Cortex-M or RISC-V (developer tool, not part of CI).
#
#   bash .ci/profile.sh <target> <solid|gouraud|aa|polygon|opacity|linear|radial>[-dithered]-<large|small|tiny> [functions] [blocks]
#   bash .ci/profile.sh <target> mesh-<knot|torus>[-faces] [functions] [blocks]
#   bash .ci/profile.sh thumbv6m-none-eabi gouraud-tiny 20 10
#
# Builds firmware/fw_profile.rs for <target> with that workload (or, for mesh-*, the 3D frame of
# firmware/fw_mesh_bench.rs four times: with the vertex scratch, or per face with -faces; on the
# MPS2 boards, thumbv6m code on mps2-an385's model), runs it under QEMU with its
# execution log (-d in_asm,exec,nochain; -icount as in CI), and prints the executed instructions
# per function and, optionally, the hottest translation blocks (addresses to look up with
# llvm-objdump). Inlined code counts towards its caller.
set -euo pipefail
cd "$(dirname "$0")/.."
target=$1 profile=$2 functions=${3:-20} blocks=${4:-0}
case $target in
    thumbv7em-none-eabihf) machine=(-machine mps2-an386 -cpu cortex-m4) ;;
    thumbv7m-none-eabi) machine=(-machine mps2-an385 -cpu cortex-m3) ;;
    thumbv6m-none-eabi) machine=(-machine microbit -cpu cortex-m0) ;;
    thumbv8m.main-none-eabihf) machine=(-machine mps2-an505 -cpu cortex-m33) ;;
    riscv32imc-unknown-none-elf | riscv32imac-unknown-none-elf) machine=(-machine virt -bios none) ;;
    *) echo "unknown target $target" >&2; exit 2 ;;
esac
export PATH="$PATH:$(rustc --print sysroot)/lib/rustlib/$(rustc -vV | sed -n 's/^host: //p')/bin"
case $profile in
    mesh-*)
        example=fw_mesh_bench dir=target/profile-mesh
        [ "$target" = thumbv6m-none-eabi ] && machine=(-machine mps2-an385 -cpu cortex-m3)
        MESH_PROFILE=${profile#mesh-} EMBEDDED_RASTER_FIRMWARE_LAYOUT=mps2 \
            cargo build -q --release --target "$target" --target-dir "$dir" --example "$example"
        elf=$dir/$target/release/examples/$example
        ;;
    *)
        PROFILE=$profile cargo build -q --release --target "$target" --example fw_profile
        elf=target/$target/release/examples/fw_profile
        ;;
esac
log=$(mktemp)
[ -n "${KEEP_LOG:-}" ] || trap 'rm -f "$log"' EXIT; echo "log: $log" >&2
qemu=qemu-system-arm
[[ $target != riscv32* ]] || qemu=qemu-system-riscv32
"$qemu" "${machine[@]}" -nographic -semihosting-config enable=on,target=native \
    -icount shift=0,align=off,sleep=off -d in_asm,exec,nochain -D "$log" -kernel "$elf" >/dev/null
args=("$elf" "$log" "$functions")
[ "$blocks" -gt 0 ] && args+=("$blocks")
python3 .ci/qprof.py "${args[@]}"
