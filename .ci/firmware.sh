#!/usr/bin/env bash
# Firmware checks under QEMU (called from .ci/run; also runs on its own).
#
# For each board (mps2-an386 Cortex-M4F, mps2-an500 Cortex-M7 (the M4F's build), mps2-an505
# Cortex-M33, mps2-an385 Cortex-M3, micro:bit Cortex-M0, and QEMU's RISC-V `virt` machine for
# RV32IMC and RV32IMAC):
#   * builds the firmware examples in release mode (.cargo/config.toml has the link flags);
#   * fw_nopanic and fw_nopanic_textures must link: their panic handler is an undefined symbol,
#     so any panic path left in the drawing code after optimisation fails the build;
#   * fw_scene and fw_nopanic run under QEMU and must exit with status 0 and print the same
#     checksum as the host build of fw_scene (the test profile's, overflow checks on; its image
#     tests/all/firmware_checksum.rs checks against an independent reference), and
#     fw_nopanic_textures the same textured frames' checksums as its host build;
#   * fw_bench counts instructions with SysTick (RISC-V: minstret) under -icount; its tables go
#     to target/firmware-bench.md, followed by the flash/RAM footprint of the M0, M4 and RV32IMC
#     builds;
#   * fw_texture_bench likewise, and its framebuffers' checksum lines (each case's, random
#     textured triangles', and 50,000 random small 3D faces', which ARMv7-M sets up in
#     assembly) must be the host's (the Cortex-M0 has a texel loop of its own).
# Then the 3D frame (fw_mesh_bench) and band rendering (fw_band on the M4 and RV32IMC, the
# micro:bit showcase fw_band_microbit), each checked against the host's frame.
#
# Every build denies warnings (the host's and the firmware's).
#
# Environment: FIRMWARE_TIMEOUT (seconds per QEMU run, default 600).
set -euo pipefail
cd "$(dirname "$0")/.."
export CARGO_TERM_COLOR=never

# `-D warnings` joined to every target's rustflags (a config, not RUSTFLAGS, which would replace
# any rustflags a user's config has).
deny=(--config "target.'cfg(all())'.rustflags = ['-D', 'warnings']")

REPORT=target/firmware-bench.md
TIMEOUT="${FIRMWARE_TIMEOUT:-600}"
QEMU_FLAGS=(-nographic -semihosting-config enable=on,target=native -icount shift=0,align=off,sleep=off)
# target, QEMU machine, QEMU cpu (the same as the runners in .cargo/config.toml)
# and what runs there: `full`, every check and bench below; `checks`, the checksums, the
# panic-free link and fw_bench's table (the Cortex-M3 runs the ARMv7-M code the Cortex-M33 runs
# in full, without the DSP lanes; RV32IMAC the instructions RV32IMC runs, measured the same;
# the Cortex-M7 the Cortex-M4F build itself, its build a no-op: QEMU counts instructions, so
# its texture and 3D figures are the M4's by construction, as they measured when it ran in
# full); `dsp`, the checks and fw_texture_bench (its checksums and limits) of a build with the
# crate feature named in a fifth field, in a target directory of its own (the Cortex-M33 with
# the DSP extension runs the Cortex-M4's DSP loops: bilinear texels, blends). The limits' key
# is the core (with `+feature`); RISC-V runs on QEMU's `virt` machine, whose cpu is rv32.
BOARDS=(
    "thumbv7em-none-eabihf mps2-an386 cortex-m4 full"
    "thumbv7em-none-eabihf mps2-an500 cortex-m7 checks"
    "thumbv8m.main-none-eabihf mps2-an505 cortex-m33 full"
    "thumbv8m.main-none-eabihf mps2-an505 cortex-m33 dsp dsp"
    "thumbv7m-none-eabi mps2-an385 cortex-m3 checks"
    "thumbv6m-none-eabi microbit cortex-m0 full"
    "riscv32imc-unknown-none-elf virt rv32imc full"
    "riscv32imac-unknown-none-elf virt rv32imac checks"
)
# The targets whose build also links fw_mesh_bench (the 3D frames below) and fw_band (bands), in
# the same cargo build as the rest: two release links (LTO, one codegen unit) at a time.
# (The Cortex-M3's ARMv7-M 3D code is the M33's, which runs the frames and their limits: its own
# fw_mesh_bench run, checksums only, measured 2.97 M and 3.68 M at stop 44 (2.67 M and 3.25 M
# with stop 45's face set-up, which it runs too), is left out for CI time.)
MESH_TARGETS=(thumbv7em-none-eabihf thumbv8m.main-none-eabihf riscv32imc-unknown-none-elf)
BAND_TARGETS=(thumbv7em-none-eabihf riscv32imc-unknown-none-elf)
# The targets whose footprint firmware (fw_size_*) is built and reported.
FOOTPRINT_TARGETS=(thumbv6m-none-eabi thumbv7em-none-eabihf riscv32imc-unknown-none-elf)
SIZE_EXAMPLES=(fw_size_base fw_size_solid fw_size_gouraud fw_size_compact fw_size_textured fw_size_textured3d)
# Goals for the drawing code on thumbv6m (flash bytes over fw_size_base), enforced: the compact
# Gouraud path (`draw_into_compact`, fw_size_compact) under 6 KiB, and the raster-core issue's
# full range, Gouraud and solid through `draw` and `draw_into` (fw_size_gouraud +
# fw_size_solid), within 16 KiB (measured 15,456: a margin of 6 %; the compact path's is 22 %).
GOURAUD_FLASH_GOAL=6144
FULL_FLASH_GOAL=16384

# The 3D bench frames (320×240, fw_mesh_bench) on the Cortex-M4, instructions a frame with the
# vertex scratch, held at the set-up issue's (#29) figures with margins of about 10 %: spot
# 1.88 M (its goal 2.2 M; 1.97 M before stop 53's mesh extent and levels loop, 2.08 M before the
# unclamped rows of stop 52, 2.41 M before the face scan of stop 51, 2.67 M before the Thumb-2
# vertex stage of stop 50, 2.97 M before the Thumb-2 face set-up of stop 45), the most expensive
# pose of spot's turntable 2.07 M, the knot 2.35 M. The Cortex-M7 and M33 are held to the same
# (within 1 % of the M4's).
SPOT_FRAME_LIMIT=2100000
SPOT_TURNTABLE_LIMIT=2300000
MESH_FRAME_LIMIT=2600000
# The knot's hidden-line wireframe (its faces filled unlit into the z-buffer, then their edges as
# depth-tested thin lines: `Pipeline::draw_wireframe`, issue #30): measured 33.9 M, most of it the
# thin line's exact end-pixel tests on edges a few pixels long; a margin of about 10 %.
WIREFRAME_FRAME_LIMIT=37500000
# The same frames in Cortex-M0 code (thumbv6m, run on mps2-an385): spot 7.27 M and the knot
# 8.76 M (under the issue's goals, 7.5 M and 9 M; 7.36 M and 8.86 M before stop 53's mesh
# extent), margins of about 10 %.
M0_SPOT_FRAME_LIMIT=8000000
M0_MESH_FRAME_LIMIT=9650000
# The textured spot frame (nearest, Rgb565 texels in RAM; the texture issue's goal is 3.4 M, TGX
# takes 4.04 M): held where it is (measured 3.285 M at stop 53, 3.395 M at stop 52, 3.71 M at stop 51 with the face
# scan drawing its faces, 4.12 M at stop 50 with the Thumb-2 vertex stage and the set-up's own
# vertex records, 4.54 M at stop 49, 4.77 M at stop 47; a margin of 10 %) so that it only comes
# down.
TEXTURED_FRAME_LIMIT=3650000
# The same with bilinear texels (the issue's goal is 4.0 M, TGX takes 6.10 M; measured 3.930 M at
# stop 53 with the light folded into the blend's one rounding, 3.818 M with the mesh extent and
# the levels loop, 4.154 M before; a margin of 10 %).
BILINEAR_TEXTURED_FRAME_LIMIT=4200000
# The same with a Blinn-Phong highlight (measured 7.09 M at stop 50, 7.05 M at stop 51, 6.88 M
# at stop 52; a margin of 10 %).
SPECULAR_TEXTURED_FRAME_LIMIT=7600000
# The same lit per pixel (Shading::Quadratic, the highlight per pixel; measured 22.09 M, a margin
# of 10 %): held where it is.
QUADRATIC_TEXTURED_FRAME_LIMIT=24300000

# Band rendering (fw_band, fw_band_microbit; issue #14): the bin's knot frame in 16-row bands on
# the Cortex-M4 at most this many per cent over the frame drawn whole in the same firmware
# (measured +16.3 %; +14.7 % before the frame drawn whole got 1.3 % faster, the issue's goal
# being 15 %: the bin's faces take the whole frame's fill, and
# the faces crossing a band boundary resume from set-ups kept in the bin's spare storage, which
# fw_band has; the limit leaves 1.7 points for compilers, and the same source has measured a
# point apart in two builds; +17.0 % at stop 41, the frame drawn whole 0.14 M faster and the
# bin's frame 0.12 M; +17.7 % at stop 45, the frame drawn whole 0.41 M faster with the Thumb-2
# face set-up and the bin's 0.43 M, a band's copy of the draw's state made a word copy: 0.3
# points left; +19.0 % at stop 50 with the Thumb-2 vertex stage, the same 0.58 M of overhead over
# a frame drawn whole 0.2 M faster, then +18.2 % with the z-buffer cleared by `stm`s, which the
# bands' clears take too: the limit 18 → 21, as the ratio moves with the frame's speed; +36.8 %
# at stop 51, the frame drawn whole 0.35 M faster with the face scan drawing its kept faces,
# which a bin's faces, drawn from its lists, do not take — the bin's frame itself the same
# 3.53 M: the limit 21 → 40, and the bin's 16-row frame held in instructions too, 3.53 M with
# a margin of 10 %; +38.7 % at stop 52, the bin's frame 3.53 → 3.40 M and the frame drawn
# whole 2.58 → 2.45 M with the unclamped rows: the limit 40 → 45, the bin's frame 3.9 → 3.75 M),
# and
# the micro:bit's frame in 8-row bands without a bin at most this many instructions (88.9 M
# measured at stop 41, 130.9 M before the M0's products from limbs).
BAND_BIN_OVERHEAD_LIMIT=45
BAND_BIN_FRAME_LIMIT=3750000
MICROBIT_BAND_FRAME_LIMIT=98000000

# Stack headroom on the micro:bit (16 KiB of RAM, most of it buffers, the stack below them
# growing into the statics unchecked): the firmware run there paints its free stack at the start
# and prints `stack high-water: N bytes of M` at the end (firmware/common/stack.rs); M − N must be
# at least this. Measured (stop 38): fw_texture_bench 3,928 of 4,072 (144 spare: the tightest;
# 3,760 before the chunk length per chunk and the per-pixel light's span loop, whose frames on
# ARMv6-M are now split out of fill_perspective, each kind of light's span loop in a frame of
# its own), fw_band_microbit 4,576 of 6,128, fw_nopanic 6,044 of 8,796, fw_nopanic_textures
# 8,752 of 14,172, fw_scene 1,660 of 10,224 (1,588 before its translucent triangle).
STACK_HEADROOM=96

# The firmware issue's targets, instructions per covered pixel on large triangles (enforced:
# QEMU's instruction counts are deterministic for a given toolchain and source).
declare -A SOLID_TARGET=([cortex-m4]=3)
# The texture issue's targets for nearest affine texturing (64×64 Rgb565, power of two,
# repeating), enforced: on the Cortex-M4 measured 10.76, a margin of 10 %; on the Cortex-M0
# (its Thumb-1 texel loop) measured 19.96, a margin of 10 %. The other figures of
# fw_texture_bench go to the report (docs/benchmarks.md has them against their targets).
declare -A TEXTURE_TARGET=([cortex-m4]=12 [cortex-m0]=22)
# Perspective-correct nearest texturing, unlit and texture × Gouraud, on the Cortex-M4 (its
# Thumb-2 span loop) and the M0 (the division-free reciprocal, the Thumb-1 chunk loop for unlit
# texels): the issue's targets are 16 and 20, 28 and 36 (out of reach with a depth test and
# 16-pixel chunks: docs/benchmarks.md); held where they are (measured 22.74 and 45.55, 57.84
# and 172.21: margins of 10-14 %; the M0's were 82.16 and 188.03 before its chunk loop, the
# chunks' lengths from thresholds found once a span and the slope's products from limbs). The lit
# figures were 35.63 and 96.36 with chunks of 16 always: the bench's faces are steep (w 1:3
# across 128 or 64 pixels), and the chunks that keep their levels within a quarter step of the
# exact ones (colours within 1 LSB) are 8 and 4 pixels long there.
declare -A PERSPECTIVE_TARGET=([cortex-m4]=25 [cortex-m0]=64)
declare -A PERSPECTIVE_LIT_TARGET=([cortex-m4]=52 [cortex-m0]=191)
declare -A GOURAUD_TARGET=([cortex-m4]=10 [cortex-m0]=17.4)
# Bilinear texels on the Cortex-M4 (the DSP extension's dual products), affine 2D and
# perspective-correct 3D: measured 57.01 and 54.61 (the issue's target for the latter is 28,
# out of reach with exact integers: docs/benchmarks.md; TGX takes 174), margins of 10 %.
declare -A BILINEAR_TARGET=([cortex-m4]=63)
declare -A PERSPECTIVE_BILINEAR_TARGET=([cortex-m4]=60.1)
# Translucent triangles (fw_bench's large set, Rgb565): a solid colour at one opacity (the
# alpha issue's targets are 6 and 12, out of reach: the blend loops' arithmetic alone is 5.5 and
# 11.25 a pixel, the raster core's rows 1.01 and 4.00; measured 6.97 and 17.03 with the Thumb-2
# and Thumb-1 loops, 10.29 and 25.61 before them; margins of 10 %) and an alpha per vertex
# (target 14 on the M4, out of reach with three multiplies, the factor, four planes and the
# fields' extraction and insertion a pixel: the Thumb-2 pair loop is 21.5 instructions a pixel,
# the M0's Thumb-1 loop 31; measured 23.62 and 40.68, margins of 10 %; they were 33.42 and 60.67
# pixel by pixel).
declare -A OPACITY_TARGET=([cortex-m4]=7.7 [cortex-m0]=18.7)
declare -A ALPHA_TARGET=([cortex-m4]=26.0 [cortex-m0]=44.7)
# Anti-aliased solid triangles (large set: the interior is the plain fill, the rest per row and
# per pixel an edge cuts, about 360 instructions each on the M4): measured 29.35 and 80.57
# (174 and 118 before stepping the rows' bounds and the narrow types); margins of 10 %.
declare -A ANTIALIAS_TARGET=([cortex-m4]=32.3 [cortex-m0]=88.6)
# Filled polygons (fw_bench's large set, each triangle as a three-vertex polygon: the same
# pixels): issue #30 asks for the solid triangle's figure plus 20 %, 3.1 and 7.5 here (the
# triangles measure 2.58 and 6.31); measured 2.81 and 6.50, margins of 10 % and 15 %.
declare -A POLYGON_TARGET=([cortex-m4]=3.1 [cortex-m0]=7.5)
# Gradient-filled triangles (fw_bench's large set, `PaintedTriangle` with three stops, Rgb565;
# issue #30's targets are linear 4 on the M4 and 8 on the M0, radial 10 on the M4: out of reach
# with the set-up each span of a gradient has, an exact classification of its first pixel and a
# reciprocal for each run, in 64-bit arithmetic, over the bench's spans of 53 and 26 pixels
# (128×96, 64×48), and the radial chords' square roots; docs/benchmarks.md), held where they
# are, measured 19.74 and 59.74 (linear), 173.53 (radial, M4), margins of 10 %. Dithering
# (#30: +2 over the plain fill; reached on the M4), margins of 10 %: linear dithered 20.98 and
# 68.42 (+1.68 and +9.8), `GouraudTriangle::dithered` 10.16 and 23.22 (+1.19 and +7.6).
declare -A LINEAR_TARGET=([cortex-m4]=21.7 [cortex-m0]=65.7)
declare -A LINEAR_DITHERED_TARGET=([cortex-m4]=23.1 [cortex-m0]=75.3)
declare -A GOURAUD_DITHERED_TARGET=([cortex-m4]=11.2 [cortex-m0]=25.6)
declare -A RADIAL_TARGET=([cortex-m4]=191)
# The other cores (issue #31), held where they are with margins of about 10 %:
# * the Cortex-M7 board runs the Cortex-M4F build: the same instructions, the M4's limits;
# * the Cortex-M33 (thumbv8m.main: the ARMv7-M Thumb-2 loops, without the DSP lanes) measured
#   2.58 solid, 8.95 Gouraud, 2.72 polygons, 10.55 nearest textured, 25.29 and 46.78 perspective;
# * RISC-V (RV32IMC and RV32IMAC run the same instructions, the drawing code using no atomics;
#   `arch::riscv32`'s loops for the lit 3D rows, the opacity blend and the fills, the portable
#   ones elsewhere) measured 2.40 solid, 10.32 Gouraud, 2.59 polygons, 12.59 opacity, 37.54
#   alpha per vertex, 32.57 anti-aliased, 16.78 nearest textured, 31.67 and 63.84 perspective,
#   unlit and lit (2.63, 2.81 and 15.52 with the portable fill and blend); the M33 7.53
#   opacity, 23.60 alpha and 29.71 anti-aliased.
SOLID_TARGET+=([cortex-m7]=3 [cortex-m33]=3 [rv32imc]=2.65 [rv32imac]=2.65)
GOURAUD_TARGET+=([cortex-m7]=10 [cortex-m33]=10 [rv32imc]=11.4 [rv32imac]=11.4)
POLYGON_TARGET+=([cortex-m7]=3.1 [cortex-m33]=3.1 [rv32imc]=2.85 [rv32imac]=2.85)
OPACITY_TARGET+=([cortex-m7]=7.7 [cortex-m33]=8.3 [rv32imc]=13.9 [rv32imac]=13.9)
ALPHA_TARGET+=([cortex-m7]=26.0 [cortex-m33]=26.0 [rv32imc]=41.3 [rv32imac]=41.3)
ANTIALIAS_TARGET+=([cortex-m7]=32.3 [cortex-m33]=32.3 [rv32imc]=35.8 [rv32imac]=35.8)
TEXTURE_TARGET+=([cortex-m7]=12 [cortex-m33]=12 [rv32imc]=18.5 [rv32imac]=18.5)
PERSPECTIVE_TARGET+=([cortex-m7]=25 [cortex-m33]=25 [rv32imc]=35.5 [rv32imac]=35.5)
PERSPECTIVE_LIT_TARGET+=([cortex-m7]=52 [cortex-m33]=52 [rv32imc]=72.7 [rv32imac]=72.7)
# Their 3D frames: the Cortex-M33's and M7's are the M4's limits (spot 3.00 M and the knot
# 3.72 M measured on the M33); RISC-V's spot 3.14 M and knot 3.85 M at stop 53 (3.21 M and
# 3.93 M before the mesh extent, 3.32 M and 4.05 M earlier; 3.50 M and 4.23 M before
# `arch::riscv32`'s lit rows and fills; 4.41 M and 5.50 M while RV32 took the host's reciprocal
# row bounds: three 64-bit library divisions a face).
# The Cortex-M33 with the DSP extension (the `dsp` feature) runs the Cortex-M4's DSP loops, and
# has measured the M4's figures (7.01 opacity, 60.07 and 57.91 bilinear): the M4's limits.
for table in SOLID_TARGET GOURAUD_TARGET POLYGON_TARGET OPACITY_TARGET ALPHA_TARGET ANTIALIAS_TARGET \
    TEXTURE_TARGET PERSPECTIVE_TARGET PERSPECTIVE_LIT_TARGET BILINEAR_TARGET PERSPECTIVE_BILINEAR_TARGET; do
    declare -n limits=$table
    limits[cortex-m33+dsp]=${limits[cortex-m4]}
done
unset -n limits
RISCV_SPOT_FRAME_LIMIT=3500000
RISCV_MESH_FRAME_LIMIT=4300000

fail() {
    echo "FAIL: $*" >&2
    exit 1
}

command -v qemu-system-arm >/dev/null || fail "qemu-system-arm is not installed"
command -v qemu-system-riscv32 >/dev/null || fail "qemu-system-riscv32 (qemu-system-misc) is not installed"
installed_targets=$(rustup target list --installed)
for board in "${BOARDS[@]}"; do
    read -r target _ <<<"$board"
    grep -qx "$target" <<<"$installed_targets" || rustup target add "$target"
done

# Checks fw_bench's "instr/pixel, large" figure of `renderer` against `target` (if any).
check_target() {
    local output=$1 cpu=$2 renderer=$3 target=$4 figure
    [ -n "$target" ] || return 0
    # The summary row (the stack table has one number column, the detail table a set name).
    figure=$(printf '%s\n' "$output" | grep -E "^\| $renderer \| [0-9.]+ \| [0-9.]+ \|" |
        head -n 1 | cut -d'|' -f3 | tr -d ' ')
    [ -n "$figure" ] || fail "fw_bench on $cpu printed no large-triangle figure for $renderer"
    awk -v f="$figure" -v t="$target" 'BEGIN { exit !(f <= t) }' ||
        fail "$renderer on $cpu: $figure instructions a pixel, target $target"
    echo "  ok: $renderer on $cpu: $figure instructions a pixel (target ≤ $target)"
}

# Runs the firmware ELF `elf` (called `what` in messages) into $OUTPUT and fails, showing what it
# printed, unless it exits with 0 (QEMU's status 124: timed out).
run_elf() {
    local machine=$1 cpu=$2 elf=$3 what=$4 status=0 qemu
    qemu=(qemu-system-arm -machine "$machine" -cpu "$cpu")
    # RISC-V: machine mode from the start of DRAM, no firmware (the `cpu` is the limits' key).
    [ "$machine" != virt ] || qemu=(qemu-system-riscv32 -machine virt -bios none -cpu rv32)
    OUTPUT=$(timeout "$TIMEOUT" "${qemu[@]}" "${QEMU_FLAGS[@]}" -kernel "$elf") || status=$?
    [ "$status" -eq 0 ] && return
    printf '%s\n' "$OUTPUT" >&2
    [ "$status" -eq 124 ] && fail "$what on $machine timed out after ${TIMEOUT}s"
    fail "$what on $machine exited with status $status"
}

# Runs the release build of `example` for `target` (see run_elf), from the target directory
# $DIR (target unless set).
run_ok() {
    local target=$1 machine=$2 cpu=$3 example=$4
    run_elf "$machine" "$cpu" "${DIR:-target}/$target/release/examples/$example" "$example"
}

# Checks the `textures` lines of fw_nopanic_textures's `output` (`what` in messages) against the host's:
# the 2D and 3D textured frames, the 2D shapes (polygons, lines, strokes), and
# draw_textured_mesh's frame ("3d-mesh") except on the micro:bit (its flash has no room for that
# draw at opt-level 3).
check_textures() {
    local what=$1 output=$2 machine=$3 got kind line want kinds=(2d shapes 3d)
    [ "$machine" = microbit ] || kinds+=(3d-mesh)
    got=$(printf '%s\n' "$output" | grep '^textures ' || true)
    [ "$(printf '%s\n' "$got" | grep -c '^textures ')" -eq "${#kinds[@]}" ] ||
        fail "$what on $machine printed $(printf '%s\n' "$got" | grep -c '^textures ') textures lines, not ${#kinds[@]}"
    for kind in "${kinds[@]}"; do
        line=$(printf '%s\n' "$got" | grep "^textures $kind " || true)
        want=$(printf '%s\n' "$TEXTURES" | grep "^textures $kind " || true)
        [ -n "$line" ] && [ "$line" = "$want" ] ||
            fail "$what on $machine: textured frame '$line', host: '$want'"
    done
    echo "  ok: $what on $machine matches the host's textured frames (${kinds[*]})"
}

# Checks the `stack high-water: N bytes of M` line of `output` (`what` in messages): required on
# the micro:bit, with at least STACK_HEADROOM bytes of M − N; reported on the other boards.
check_stack() {
    local what=$1 output=$2 machine=$3 line used size
    line=$(printf '%s\n' "$output" | grep '^stack high-water: ' | tail -n 1 || true)
    if [ -z "$line" ]; then
        [ "$machine" != microbit ] || fail "$what on $machine printed no stack high-water line"
        return 0
    fi
    read -r used size <<<"$(sed -E 's/^stack high-water: ([0-9]+) bytes of ([0-9]+)$/\1 \2/' <<<"$line")"
    [[ "$used" =~ ^[0-9]+$ && "$size" =~ ^[0-9]+$ ]] || fail "$what on $machine: bad line '$line'"
    if [ "$machine" = microbit ]; then
        [ $((size - used)) -ge "$STACK_HEADROOM" ] ||
            fail "$what on $machine: stack high-water $used bytes of $size, under $STACK_HEADROOM bytes spare"
    fi
    echo "  ok: $what on $machine: stack high-water $used bytes of $size ($((size - used)) spare)"
}

# Runs `example` and checks its exit status and its checksum line against the host's.
check_scene() {
    local target=$1 machine=$2 cpu=$3 example=$4 output line size want
    run_ok "$target" "$machine" "$cpu" "$example"
    output=$OUTPUT
    printf '%s\n' "$output" | sed "s/^/  $example: /"
    line=$(printf '%s\n' "$output" | grep '^scene ' || true)
    [ "$(printf '%s\n' "$line" | grep -c '^scene ')" -eq 1 ] ||
        fail "$example on $machine printed no single checksum line"
    size=$(cut -d' ' -f2 <<<"$line")
    want=$(printf '%s\n' "$EXPECTED" | grep "^scene $size " || true)
    [ -n "$want" ] || fail "the host printed no checksum for size $size"
    [ "$line" = "$want" ] || fail "$example on $machine: '$line', host: '$want'"
    echo "  ok: $example on $machine matches the host ($line)"
    if [ "$example" = fw_scene ]; then
        # The dithered spans it draws over the scene (its second line).
        line=$(printf '%s\n' "$output" | grep "^spans $size " || true)
        want=$(printf '%s\n' "$EXPECTED" | grep "^spans $size " || true)
        [ -n "$want" ] || fail "the host printed no spans checksum for size $size"
        [ "$line" = "$want" ] || fail "$example on $machine: '$line', host: '$want'"
        echo "  ok: $example on $machine matches the host ($line)"
    fi
    check_stack "$example" "$output" "$machine"
}

# The host builds of the firmware examples whose output the boards' must match (the portable
# definitions), in one cargo build: the test profile with every feature and the same flags, which
# `cargo test` in .ci/run has just built (no second build; their release builds, with LTO, took
# CI over a minute), with its overflow checks.
HOST=(--profile test --all-features)
cargo build "${deny[@]}" --quiet "${HOST[@]}" --example fw_scene --example fw_texture_bench \
    --example fw_nopanic_textures --example fw_mesh_bench --example fw_band --example fw_band_microbit

# The size-optimised builds and the Cortex-M0 code linked for MPS2 (below) have target directories
# of their own: their builds run here in the background while the boards' builds and runs use
# target/ (a release build with one codegen unit and LTO keeps one core busy much of the time).
# Their commands, the same, run again where their firmware runs: up to date then (cargo waits for
# the directory's lock), or failing with their messages if they failed here.
warm_up() {
    local level target
    for level in s z; do
        for target in thumbv6m-none-eabi thumbv7em-none-eabihf riscv32imc-unknown-none-elf; do
            CARGO_PROFILE_RELEASE_OPT_LEVEL=$level cargo build "${deny[@]}" --quiet --release --target "$target" \
                --target-dir "target/opt-level-$level" --example fw_nopanic --example fw_nopanic_textures || true
        done
    done
    EMBEDDED_RASTER_FIRMWARE_LAYOUT=mps2 cargo build "${deny[@]}" --quiet --release --target thumbv6m-none-eabi \
        --target-dir target/armv6m-on-mps2 --example fw_mesh_bench || true
}
mkdir -p target
warm_up >target/firmware-warm-up.log 2>&1 &
warm_up_pid=$!
# On failure, the warm-up stops too: its shell and the cargo build it is waiting for.
stop_warm_up() {
    local build
    build=$(pgrep -P "$warm_up_pid" || true)
    # shellcheck disable=SC2086 # none, one or more ids
    kill "$warm_up_pid" $build 2>/dev/null || true
}
trap stop_warm_up EXIT

echo "--- host checksums (cargo run --profile test --example fw_scene)"
EXPECTED=$(cargo run "${deny[@]}" --quiet "${HOST[@]}" --example fw_scene)
printf '%s\n' "$EXPECTED"
[ "$(printf '%s\n' "$EXPECTED" | grep -c '^scene ')" -ge 2 ] || fail "no host checksums"
TEXTURE_EXPECTED=$(cargo run "${deny[@]}" --quiet "${HOST[@]}" --example fw_texture_bench | grep '^texture ')
[ "$(printf '%s\n' "$TEXTURE_EXPECTED" | grep -c '^texture ')" -ge 2 ] || fail "no host texture checksums"
echo "--- host textured frames (cargo run --profile test --example fw_nopanic_textures)"
TEXTURES=$(cargo run "${deny[@]}" --quiet "${HOST[@]}" --example fw_nopanic_textures)
printf '%s\n' "$TEXTURES"
[ "$(printf '%s\n' "$TEXTURES" | grep -c '^textures ')" -eq 4 ] || fail "no host textured frames"

bench=$(mktemp)
trap 'rm -f "$bench"; stop_warm_up' EXIT
{
    echo "# Firmware benchmarks (generated by .ci/firmware.sh)"
    echo
    echo "$(rustc --version); $(qemu-system-arm --version | sed -n 1p)."
    if commit=$(git rev-parse --short HEAD 2>/dev/null); then
        git diff --quiet HEAD -- src Cargo.toml 2>/dev/null || commit="$commit + uncommitted changes"
        echo "Source: commit $commit."
    fi
    echo "Release profile of Cargo.toml. Instructions are counted by QEMU (\`-icount\`), not cycles."
    echo
} >"$bench"

# Whether `word` is one of the remaining arguments.
one_of() {
    local word=$1
    shift
    [[ " $* " == *" $word "* ]]
}

for board in "${BOARDS[@]}"; do
    read -r target machine cpu set features <<<"$board"
    key=$cpu DIR=target build=()
    if [ -n "${features:-}" ]; then
        key="$cpu+$features" DIR="target/features-$features"
        build=(--features "$features" --target-dir "$DIR")
    fi
    echo "--- $machine ($key, $target)"
    examples=(--example fw_scene --example fw_bench --example fw_nopanic)
    case $set in
    full) examples+=(--example fw_texture_bench --example fw_nopanic_textures) ;;
    dsp) examples+=(--example fw_texture_bench) ;;
    esac
    footprint=false
    [ "$set" = dsp ] || ! one_of "$target" "${FOOTPRINT_TARGETS[@]}" || footprint=true
    if $footprint; then
        for e in "${SIZE_EXAMPLES[@]}"; do examples+=(--example "$e"); done
    fi
    if [ "$set" != dsp ]; then
        ! one_of "$target" "${MESH_TARGETS[@]}" || examples+=(--example fw_mesh_bench)
        ! one_of "$target" "${BAND_TARGETS[@]}" || examples+=(--example fw_band)
    fi
    log=$(mktemp)
    if ! cargo build "${deny[@]}" --quiet --release --target "$target" "${build[@]}" "${examples[@]}" 2>"$log"; then
        if grep -q 'embedded_raster_drawing_code_can_panic' "$log"; then
            grep -E 'undefined symbol|referenced by|>>>' "$log" >&2 || true
            rm -f "$log"
            fail "fw_nopanic, fw_nopanic_textures or fw_size_* does not link for $target: a panic" \
                "path is left in the drawing code (or in scene.rs/texture_scene.rs). Build fw_scene" \
                "and look for calls to core::panicking."
        fi
        cat "$log" >&2
        rm -f "$log"
        fail "the firmware does not build for $target (or it outgrew the board's memory: the" \
            "micro:bit's 256 KiB of flash)"
    fi
    rm -f "$log"
    if $footprint; then
        for e in "${SIZE_EXAMPLES[@]}"; do
            [ -f "target/$target/release/examples/$e" ] || fail "$e did not link for $target"
        done
        echo "  ok: fw_nopanic and fw_size_* link (no panic paths)"
    else
        echo "  ok: fw_nopanic links (no panic paths)"
    fi

    check_scene "$target" "$machine" "$cpu" fw_scene
    check_scene "$target" "$machine" "$cpu" fw_nopanic
    if [ "$set" = full ]; then
        run_ok "$target" "$machine" "$cpu" fw_nopanic_textures
        check_textures fw_nopanic_textures "$OUTPUT" "$machine"
        check_stack fw_nopanic_textures "$OUTPUT" "$machine"
    fi

    run_ok "$target" "$machine" "$cpu" fw_bench
    output=$OUTPUT
    grep -q '^| GouraudTriangle::draw_into | large |' <<<"$output" ||
        fail "fw_bench on $machine printed no table"
    printf '%s\n\n' "$output" >>"$bench"
    echo "  ok: fw_bench on $machine"
    check_target "$output" "$key" SolidTriangle::draw_into "${SOLID_TARGET[$key]:-}"
    check_target "$output" "$key" GouraudTriangle::draw_into "${GOURAUD_TARGET[$key]:-}"
    check_target "$output" "$key" "GouraudTriangle::dithered draw_into" \
        "${GOURAUD_DITHERED_TARGET[$key]:-}"
    check_target "$output" "$key" "SolidTriangle::with_opacity draw_into" "${OPACITY_TARGET[$key]:-}"
    check_target "$output" "$key" "GouraudTriangle::with_alpha draw_into" "${ALPHA_TARGET[$key]:-}"
    check_target "$output" "$key" "SolidTriangle::anti_aliased draw_into" "${ANTIALIAS_TARGET[$key]:-}"
    check_target "$output" "$key" "Polygon::filled draw_into" "${POLYGON_TARGET[$key]:-}"
    check_target "$output" "$key" "PaintedTriangle linear draw_into" "${LINEAR_TARGET[$key]:-}"
    check_target "$output" "$key" "PaintedTriangle linear dithered draw_into" \
        "${LINEAR_DITHERED_TARGET[$key]:-}"
    check_target "$output" "$key" "PaintedTriangle radial draw_into" "${RADIAL_TARGET[$key]:-}"

    [ "$set" != checks ] || continue
    run_ok "$target" "$machine" "$cpu" fw_texture_bench
    output=$OUTPUT
    printf '%s\n\n' "$(printf '%s\n' "$output" | grep -v '^texture \|^stack high-water')" >>"$bench"
    check_stack fw_texture_bench "$output" "$machine"
    got=$(printf '%s\n' "$output" | grep '^texture ' || true)
    size=$(printf '%s\n' "$got" | head -n 1 | cut -d' ' -f2)
    want=$(printf '%s\n' "$TEXTURE_EXPECTED" | grep "^texture $size " || true)
    [ -n "$got" ] && [ "$got" = "$want" ] ||
        fail "fw_texture_bench on $machine: checksums differ from the host's:\n$got\nhost:\n$want"
    echo "  ok: fw_texture_bench on $machine matches the host ($(printf '%s\n' "$got" | wc -l) checksums)"
    # Each held row must be in the table on every board; its limit, where this core has one.
    for row in "TexturedTriangle::draw_into nearest|${TEXTURE_TARGET[$key]:-}" \
        "draw_textured perspective nearest|${PERSPECTIVE_TARGET[$key]:-}" \
        "draw_textured_lit perspective nearest (texture × Gouraud)|${PERSPECTIVE_LIT_TARGET[$key]:-}" \
        "TexturedTriangle::draw_into bilinear|${BILINEAR_TARGET[$key]:-}" \
        "draw_textured perspective bilinear|${PERSPECTIVE_BILINEAR_TARGET[$key]:-}"; do
        name=${row%|*} limit=${row##*|}
        figure=$(printf '%s\n' "$output" | grep -F "| $name |" | head -n 1 | cut -d'|' -f3 | tr -d ' ')
        [ -n "$figure" ] || fail "fw_texture_bench on $machine printed no row '$name'"
        [ -n "$limit" ] || continue
        awk -v f="$figure" -v t="$limit" 'BEGIN { exit !(f <= t) }' ||
            fail "$name on $key: $figure instructions a pixel, limit $limit"
        echo "  ok: $name on $key: $figure instructions a pixel (limit ≤ $limit)"
    done
done
DIR=target

# ---- size-optimised builds ----------------------------------------------------------------------
# Firmware is often built for size: at opt-level "s" and "z" the drawing code must still have no
# panic path (fw_nopanic links only then: the scene, the other colour formats, the 3D pipeline and
# the texture code — 2D textured triangles with every wrap mode and filter, textured meshes and
# three_d::draw_textured, perspective-correct) and draw the host's pixels (the scene's checksum
# and the textured frames'). Their own target directories keep the release builds above.
echo "--- fw_nopanic at opt-level s and z"
for level in s z; do
    for board in "thumbv6m-none-eabi microbit cortex-m0" "thumbv7em-none-eabihf mps2-an386 cortex-m4" \
        "riscv32imc-unknown-none-elf virt rv32imc"; do
        read -r target machine cpu <<<"$board"
        dir="target/opt-level-$level"
        log=$(mktemp)
        if ! CARGO_PROFILE_RELEASE_OPT_LEVEL=$level cargo build "${deny[@]}" --quiet --release --target "$target" \
            --target-dir "$dir" --example fw_nopanic --example fw_nopanic_textures 2>"$log"; then
            grep -E 'undefined symbol|referenced by|>>>|FLASH|RAM' "$log" >&2 || cat "$log" >&2
            rm -f "$log"
            fail "fw_nopanic does not link for $target at opt-level $level: a panic path is left" \
                "in the drawing code (or the firmware outgrew the board's memory). List the calls to" \
                "core::panicking in its disassembly."
        fi
        rm -f "$log"
        run_elf "$machine" "$cpu" "$dir/$target/release/examples/fw_nopanic" \
            "fw_nopanic at opt-level $level"
        line=$(printf '%s\n' "$OUTPUT" | grep '^scene ' || true)
        want=$(printf '%s\n' "$EXPECTED" | grep "^scene $(cut -d' ' -f2 <<<"$line") " || true)
        [ -n "$line" ] && [ "$line" = "$want" ] ||
            fail "fw_nopanic at opt-level $level on $machine: '$line', host: '$want'"
        echo "  ok: fw_nopanic at opt-level $level links for $target and matches the host on $machine"
        check_stack "fw_nopanic at opt-level $level" "$OUTPUT" "$machine"
        run_elf "$machine" "$cpu" "$dir/$target/release/examples/fw_nopanic_textures" \
            "fw_nopanic_textures at opt-level $level"
        check_textures "fw_nopanic_textures at opt-level $level" "$OUTPUT" "$machine"
        check_stack "fw_nopanic_textures at opt-level $level" "$OUTPUT" "$machine"
    done
done

# ---- 3D frame ---------------------------------------------------------------------------------
# fw_mesh_bench renders the 3D bench scene (320×240, 300 KB of buffers: MPS2 boards only) and must
# print the host's frame lines. The Cortex-M0 code (thumbv6m) runs on the mps2-an385 model, linked
# with the MPS2 memory layout (EMBEDDED_RASTER_FIRMWARE_LAYOUT=mps2: build.rs's link flags):
# ARMv7-M executes the ARMv6-M instruction stream unchanged.
echo "--- 3D frame (fw_mesh_bench)"
FRAMES=$(cargo run "${deny[@]}" --quiet "${HOST[@]}" --example fw_mesh_bench)
printf '%s\n' "$FRAMES"
[ "$(printf '%s\n' "$FRAMES" | grep -c '^frame ')" -ge 4 ] || fail "no host frame lines"
MESH_BOARDS=(
    "thumbv7em-none-eabihf mps2-an386 cortex-m4 target"
    "thumbv8m.main-none-eabihf mps2-an505 cortex-m33 target"
    "riscv32imc-unknown-none-elf virt rv32imc target"
    "thumbv6m-none-eabi mps2-an385 cortex-m3 target/armv6m-on-mps2"
)
# Checks fw_mesh_bench's frame figures in `output` (the "instructions a frame" column of each
# mesh's row) against "mesh limit" pairs; `where` names the code in messages.
check_mesh_frames() {
    local output=$1 where=$2 limit mesh max frame
    shift 2
    for limit in "$@"; do
        read -r mesh max <<<"$limit"
        frame=$(printf '%s\n' "$output" | grep -E "^\\| $mesh \\|" | head -n 1 | cut -d'|' -f6 | tr -d ' ')
        [ -n "$frame" ] || fail "fw_mesh_bench printed no $mesh frame figure ($where)"
        [ "$frame" -le "$max" ] || fail "the 3D $mesh frame takes $frame instructions $where (limit $max)"
        echo "  ok: 3D $mesh frame $where: $frame instructions (limit $max)"
    done
}

for board in "${MESH_BOARDS[@]}"; do
    read -r target machine cpu dir <<<"$board"
    if [ "$dir" = target ]; then
        cargo build "${deny[@]}" --quiet --release --target "$target" --example fw_mesh_bench
    else
        EMBEDDED_RASTER_FIRMWARE_LAYOUT=mps2 \
            cargo build "${deny[@]}" --quiet --release --target "$target" --target-dir "$dir" --example fw_mesh_bench
    fi
    run_elf "$machine" "$cpu" "$dir/$target/release/examples/fw_mesh_bench" "fw_mesh_bench ($target)"
    output=$OUTPUT
    got=$(printf '%s\n' "$output" | grep '^frame ' || true)
    [ "$got" = "$(printf '%s\n' "$FRAMES" | grep '^frame ')" ] ||
        fail "fw_mesh_bench ($target) on $machine: frames differ from the host's:\n$got"
    echo "  ok: fw_mesh_bench ($target) on $machine matches the host"
    if [ "$machine" = mps2-an386 ]; then
        check_mesh_frames "$output" "on the Cortex-M4" "spot $SPOT_FRAME_LIMIT" "knot $MESH_FRAME_LIMIT" \
            "knot-wireframe $WIREFRAME_FRAME_LIMIT"
        for limit in "nearest $TEXTURED_FRAME_LIMIT" "bilinear $BILINEAR_TEXTURED_FRAME_LIMIT" \
            "specular $SPECULAR_TEXTURED_FRAME_LIMIT" \
            "quadratic-specular $QUADRATIC_TEXTURED_FRAME_LIMIT"; do
            read -r kind max <<<"$limit"
            frame=$(printf '%s\n' "$output" | grep -E "^\\| spot-textured-$kind \\|" | head -n 1 | cut -d'|' -f5 | tr -d ' ')
            [ -n "$frame" ] || fail "fw_mesh_bench on $machine printed no textured spot ($kind) frame figure"
            [ "$frame" -le "$max" ] ||
                fail "the textured spot frame ($kind) takes $frame instructions on the Cortex-M4 (limit $max)"
            echo "  ok: textured spot frame ($kind) on cortex-m4: $frame instructions (limit $max)"
        done
        frame=$(printf '%s\n' "$output" | grep -E '^\| instructions a frame \|' | head -n 1 | cut -d'|' -f5 | tr -d ' ')
        [ -n "$frame" ] || fail "fw_mesh_bench on $machine printed no spot turntable figure"
        [ "$frame" -le "$SPOT_TURNTABLE_LIMIT" ] ||
            fail "spot's most expensive turntable pose takes $frame instructions on the Cortex-M4 (limit $SPOT_TURNTABLE_LIMIT)"
        echo "  ok: spot turntable's most expensive pose on cortex-m4: $frame instructions (limit $SPOT_TURNTABLE_LIMIT)"
    fi
    case "$cpu/$target" in
    cortex-m3/thumbv6m-none-eabi)
        check_mesh_frames "$output" "in Cortex-M0 code" "spot $M0_SPOT_FRAME_LIMIT" "knot $M0_MESH_FRAME_LIMIT" ;;
    cortex-m7/* | cortex-m33/*)
        check_mesh_frames "$output" "on the $cpu" "spot $SPOT_FRAME_LIMIT" "knot $MESH_FRAME_LIMIT" ;;
    rv32*)
        check_mesh_frames "$output" "on $cpu" "spot $RISCV_SPOT_FRAME_LIMIT" "knot $RISCV_MESH_FRAME_LIMIT" ;;
    esac
    { echo "Board: $machine."; printf '%s\n\n' "$(printf '%s\n' "$output" | grep -v '^frame ')"; } >>"$bench"
done

# ---- band rendering ---------------------------------------------------------------------------
# fw_band draws the 3D bench frame (the knot) in bands of 8, 16, 32 and 240 rows, without a bin
# (per face; with the vertex scratch) and with one, on the Cortex-M4 (mps2-an386); the
# showcase fw_band_microbit draws it in 8-row bands without a bin on the micro:bit (Cortex-M0,
# 16 KiB of RAM, linked with its memory layout; panic-free link). Every `bands …` line (hashes
# of the colours and depths the display stand-in received) must equal the host's for the frame
# drawn whole; the host runs check the bands too.
echo "--- band rendering (fw_band, fw_band_microbit)"
BAND_LINE=$(cargo run "${deny[@]}" --quiet "${HOST[@]}" --example fw_band)
[ "$(printf '%s\n' "$BAND_LINE" | grep -c '^bands ')" -eq 1 ] || fail "no host bands line"
[ "$(cargo run "${deny[@]}" --quiet "${HOST[@]}" --example fw_band_microbit)" = "$BAND_LINE" ] ||
    fail "the host's micro:bit bands line differs from the frame drawn whole"
printf '%s\n' "$BAND_LINE"
check_bands() {
    local what=$1 output=$2 count=$3 got
    got=$(printf '%s\n' "$output" | grep '^bands ' || true)
    [ "$(printf '%s\n' "$got" | grep -c '^bands ')" -eq "$count" ] ||
        fail "$what printed $(printf '%s\n' "$got" | grep -c '^bands ') bands lines, not $count"
    [ -z "$(printf '%s\n' "$got" | grep -vxF "$BAND_LINE")" ] ||
        fail "$what: bands differ from the frame drawn whole:\n$got"
    echo "  ok: $what: $count band renderings equal the frame drawn whole"
}
cargo build "${deny[@]}" --quiet --release --target thumbv7em-none-eabihf --example fw_band
run_ok thumbv7em-none-eabihf mps2-an386 cortex-m4 fw_band
output=$OUTPUT
check_bands "fw_band on mps2-an386" "$output" 12
# The bin's frame in 16-row bands against the frame drawn whole.
over=$(printf '%s\n' "$output" | grep -E '^\| 16 \|' | head -n 1 | cut -d'|' -f7 | tr -d ' %+')
[ -n "$over" ] || fail "fw_band printed no 16-row figure"
awk -v o="$over" -v l="$BAND_BIN_OVERHEAD_LIMIT" 'BEGIN { exit !(o <= l) }' ||
    fail "the bin's 16-row frame takes $over % more than the whole frame (limit $BAND_BIN_OVERHEAD_LIMIT %)"
echo "  ok: bin, 16-row bands: +$over % over the whole frame (limit $BAND_BIN_OVERHEAD_LIMIT %)"
binned=$(printf '%s\n' "$output" | grep -E '^\| 16 \|' | head -n 1 | cut -d'|' -f6 | tr -d ' ')
[ -n "$binned" ] && [ "$binned" -le "$BAND_BIN_FRAME_LIMIT" ] ||
    fail "the bin's 16-row frame takes $binned instructions (limit $BAND_BIN_FRAME_LIMIT)"
echo "  ok: bin, 16-row bands: $binned instructions (limit $BAND_BIN_FRAME_LIMIT)"
{ echo "Board: mps2-an386."; printf '%s\n\n' "$(printf '%s\n' "$output" | grep -v '^bands ')"; } >>"$bench"
# The same bands on RISC-V (RV32IMC; issue #31).
cargo build "${deny[@]}" --quiet --release --target riscv32imc-unknown-none-elf --example fw_band
run_ok riscv32imc-unknown-none-elf virt rv32imc fw_band
output=$OUTPUT
check_bands "fw_band on virt (rv32imc)" "$output" 12
{ echo "Board: virt (RV32IMC)."; printf '%s\n\n' "$(printf '%s\n' "$output" | grep -v '^bands ')"; } >>"$bench"

if ! cargo build "${deny[@]}" --quiet --release --target thumbv6m-none-eabi --example fw_band_microbit 2>"$bench.log"; then
    grep -E 'undefined symbol|referenced by|>>>|RAM|FLASH|overflow' "$bench.log" >&2 || cat "$bench.log" >&2
    fail "fw_band_microbit does not link: a panic path in the band renderer or 3D pipeline, or" \
        "it does not fit the micro:bit's memory"
fi
run_ok thumbv6m-none-eabi microbit cortex-m0 fw_band_microbit
output=$OUTPUT
check_bands "fw_band_microbit on microbit" "$output" 1
check_stack fw_band_microbit "$output" microbit
frame=$(printf '%s\n' "$output" | grep -E '^\| [0-9]+ \|' | head -n 1 | cut -d'|' -f2 | tr -d ' ')
[ -n "$frame" ] || fail "fw_band_microbit printed no frame figure"
[ "$frame" -le "$MICROBIT_BAND_FRAME_LIMIT" ] ||
    fail "the micro:bit's band frame takes $frame instructions (limit $MICROBIT_BAND_FRAME_LIMIT)"
echo "  ok: micro:bit knot frame in bands: $frame instructions (limit $MICROBIT_BAND_FRAME_LIMIT)"
printf '%s\n\n' "$(printf '%s\n' "$output" | grep -v '^bands \|^stack high-water')" >>"$bench"
rm -f "$bench.log"

# ---- footprint --------------------------------------------------------------------------------
host=$(rustc -vV | sed -n 's/^host: //p')
tools="$(rustc --print sysroot)/lib/rustlib/$host/bin"
if [ ! -x "$tools/llvm-size" ]; then
    rustup component add llvm-tools >/dev/null 2>&1 || true
fi
if [ -x "$tools/llvm-size" ] && [ -x "$tools/llvm-nm" ]; then
    SIZE="$tools/llvm-size" NM="$tools/llvm-nm"
elif command -v arm-none-eabi-size >/dev/null && command -v arm-none-eabi-nm >/dev/null; then
    SIZE=arm-none-eabi-size NM=arm-none-eabi-nm
else
    SIZE="" NM=""
fi

# text data bss of an ELF (Berkeley format), bss without riscv-rt's `.stack` and `.heap`: the
# free RAM its link script reserves as sections (cortex-m-rt's stack is no section).
sizes() {
    local text data bss reserved
    read -r text data bss <<<"$("$SIZE" "$1" | awk 'NR == 2 { print $1, $2, $3 }')"
    reserved=$("$SIZE" -A "$1" | awk '$1 == ".stack" || $1 == ".heap" { s += $2 } END { print s + 0 }')
    echo "$text" "$data" "$((bss - reserved))"
}
# Function symbols of an ELF as "size name" lines, size in decimal (POSIX awk has no hex).
functions() {
    local address size type name
    "$NM" -S -C "$1" | while read -r address size type name; do
        case "$type" in t | T) echo "$((16#$size)) $name" ;; esac
    done
}
# Readable Rust names: legacy mangling escapes that `nm -C` leaves, and no hash suffix.
readable() {
    sed -e 's/\$LT\$/</g; s/\$GT\$/>/g; s/\$u20\$/ /g; s/\$RF\$/\&/g; s/\.\./::/g' \
        -e 's/\$u7b\$/{/g; s/\$u7d\$/}/g; s/::_{/::{/g' \
        -e 's/^\([0-9]* \)_</\1</; s/::h[0-9a-f]\{16\}//'
}
# Sum of the sizes of the functions of the embedded_raster crate (or implemented for its types).
symbol_bytes() {
    functions "$1" | readable | grep -F 'embedded_raster::' | awk '{ s += $1 } END { print s + 0 }' || true
}

gouraud_m0="" compact_m0="" solid_m0=""
if [ -n "$SIZE" ]; then
    {
        echo "## Footprint"
        echo
        echo "Flash = text + data, RAM = data + bss (bss includes the framebuffer: 64×48 Rgb565 ="
        echo "6144 bytes on the micro:bit, 128×96 = 24576 bytes on MPS2 and RISC-V). The drawing code's own"
        echo "flash is the growth of the footprint firmware over \`fw_size_base\` (same skeleton,"
        echo "no triangle), which includes the compiler-builtins it pulls in; \`embedded_raster::\`"
        echo "functions counts only what LTO left un-inlined under the crate's names."
        echo
        echo "| target | firmware | text | data | bss | flash | RAM | flash over fw_size_base | \`embedded_raster::\` functions |"
        echo "|---|---|---:|---:|---:|---:|---:|---:|---:|"
    } >>"$bench"
    for target in "${FOOTPRINT_TARGETS[@]}"; do
        dir="target/$target/release/examples"
        base_flash=$(awk '{ print $1 + $2 }' <<<"$(sizes "$dir/fw_size_base")")
        for e in fw_scene "${SIZE_EXAMPLES[@]}"; do
            read -r text data bss <<<"$(sizes "$dir/$e")"
            flash=$((text + data))
            delta=$((flash - base_flash))
            own=$(symbol_bytes "$dir/$e" 'embedded_raster::')
            echo "| $target | $e | $text | $data | $bss | $flash | $((data + bss)) | $delta | $own |" >>"$bench"
            if [ "$target" = thumbv6m-none-eabi ] && [ "$e" = fw_size_gouraud ]; then
                gouraud_m0=$delta
            fi
            if [ "$target" = thumbv6m-none-eabi ] && [ "$e" = fw_size_compact ]; then
                compact_m0=$delta
            fi
            if [ "$target" = thumbv6m-none-eabi ] && [ "$e" = fw_size_solid ]; then
                solid_m0=$delta
            fi
        done
    done
    {
        echo
        echo "Largest symbols of \`fw_size_gouraud\` on thumbv6m-none-eabi (bytes):"
        echo
        echo '```'
        functions "target/thumbv6m-none-eabi/release/examples/fw_size_gouraud" |
            sort -rn | sed -n 1,8p | readable | awk '{ n = $1; $1 = ""; printf "%6d %s\n", n, $0 }' 
        echo '```'
        echo
        echo "Gouraud drawing code on thumbv6m: $compact_m0 bytes of flash through \`draw_into_compact\`"
        echo "(goal: under $GOURAUD_FLASH_GOAL), $gouraud_m0 bytes through \`draw\` and \`draw_into\` (any size);"
        echo "with solid's $solid_m0, $((gouraud_m0 + solid_m0)) (goal: at most $FULL_FLASH_GOAL)."
        echo
    } >>"$bench"
else
    echo "warning: neither llvm-tools nor arm-none-eabi binutils found; footprint not reported" >&2
fi

mv "$bench" "$REPORT"
wait "$warm_up_pid" || true
trap - EXIT
echo "--- wrote $REPORT"
if [ -n "$compact_m0" ]; then
    echo "Gouraud drawing code on thumbv6m: $compact_m0 bytes of flash compact (goal $GOURAUD_FLASH_GOAL), $gouraud_m0 full range"
    [ "$compact_m0" -lt "$GOURAUD_FLASH_GOAL" ] ||
        fail "the compact Gouraud path needs $compact_m0 bytes of flash on thumbv6m (goal: under $GOURAUD_FLASH_GOAL)"
    full_m0=$((gouraud_m0 + solid_m0))
    echo "Gouraud + solid through draw and draw_into on thumbv6m: $full_m0 bytes of flash (goal $FULL_FLASH_GOAL)"
    [ "$full_m0" -le "$FULL_FLASH_GOAL" ] ||
        fail "Gouraud + solid through draw and draw_into need $full_m0 bytes of flash on thumbv6m (goal: at most $FULL_FLASH_GOAL)"
fi
echo "firmware: all boards OK"
