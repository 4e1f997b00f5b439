#!/usr/bin/env python3
"""Instructions per function from a QEMU `-d in_asm,exec,nochain` log (see .ci/profile.sh).

Usage: qprof.py <elf> <log> [functions] [blocks]
"""
import sys, subprocess, bisect, collections, re
elf, log = sys.argv[1], sys.argv[2]
syms = []
for line in subprocess.run(['llvm-nm', '-n', '--demangle', elf], capture_output=True, text=True).stdout.splitlines():
    parts = line.split(' ', 2)
    # RISC-V objects keep the assembler's local labels (`.L0`, `.Lpcrel_hi3`) as symbols: not
    # functions.
    if len(parts) == 3 and parts[1] in 'tTWw' and not parts[2].startswith('.L'):
        syms.append((int(parts[0], 16) & ~1, parts[2]))
addrs = [a for a, _ in syms]
tb_len = {}
cur = None
counts = collections.Counter()
tbre = re.compile(r'^IN:')
with open(log, errors='replace') as f:
    for line in f:
        if line.startswith('IN:'):
            cur = None
            continue
        m = re.match(r'^0x([0-9a-f]{8}):', line)
        if m:
            a = int(m.group(1), 16)
            if cur is None:
                cur = a
                tb_len[cur] = 0
            tb_len[cur] += 1
            continue
        if line.startswith('Trace'):
            m = re.search(r'/([0-9a-f]{8})/', line)
            if m:
                counts[int(m.group(1), 16)] += 1
            cur = None
per = collections.Counter()
for pc, n in counts.items():
    i = bisect.bisect_right(addrs, pc) - 1
    name = syms[i][1] if i >= 0 else '?'
    per[name] += n * tb_len.get(pc, 0)
total = sum(per.values())
for name, n in per.most_common(int(sys.argv[3]) if len(sys.argv) > 3 else 25):
    print(f'{n:>12} {100*n/total:5.1f}%  {name[:110]}')
print(total, 'total')
if len(sys.argv) > 4:
    tbs = sorted(((n * tb_len.get(pc, 0), pc, n) for pc, n in counts.items()), reverse=True)
    top = tbs[:int(sys.argv[4])]
    locs = iter(subprocess.run(['llvm-addr2line', '-e', elf, '-C'] + [hex(pc) for _, pc, _ in top],
                               capture_output=True, text=True).stdout.splitlines())
    for tot, pc, n in top:
        loc = re.sub(r'.*/(src|library)/', '', next(locs, '?'))
        print(f'  tb {pc:#x} len {tb_len.get(pc,0):3} x {n:8} = {tot:>10}  {loc}')
