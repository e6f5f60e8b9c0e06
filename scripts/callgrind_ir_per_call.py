#!/usr/bin/env python3
"""Instructions per call of each function that criterion's timing loop calls,
read from a callgrind output file (BENCHMARKS.md, "Instruction counts").

For every callee of `Bencher::iter`, print its inclusive instruction count
divided by its number of calls. Each benchmark of benches/decode.rs times one
`#[inline(never)]` function over a whole buffer, so this is the count per
buffer: divide by the frames (1024) or lines (20 000) in it.

    valgrind --tool=callgrind --callgrind-out-file=cg.out \\
        target/release/deps/decode-<hash> --bench --profile-time 1 '^emcy8/owned$'
    python3 scripts/callgrind_ir_per_call.py cg.out
"""
import re
import sys

names = {}


def name(token):
    """Resolve callgrind's name compression: `(id) name` defines, `(id)` refers."""
    m = re.match(r"\((\d+)\)(?: (.*))?", token)
    if not m:
        return token
    if m.group(2):
        names[m.group(1)] = m.group(2)
    return names.get(m.group(1), token)


def main(path):
    caller = callee = None
    calls = None
    totals = {}
    with open(path) as f:
        for line in f:
            line = line.rstrip("\n")
            if line.startswith("fn="):
                caller, callee = name(line[3:]), None
            elif line.startswith("cfn="):
                callee = name(line[4:])
            elif line.startswith("calls="):
                calls = int(line.split()[0][len("calls="):])
            elif calls is not None:
                # The line after `calls=` holds the call's inclusive cost.
                inclusive = int(line.split()[1])
                if caller and "Bencher" in caller and "iter" in caller:
                    n, ir = totals.get(callee, (0, 0))
                    totals[callee] = (n + calls, ir + inclusive)
                calls = None
    for callee, (n, ir) in sorted(totals.items(), key=lambda kv: -kv[1][1]):
        print(f"{ir / n:14.1f} instructions/call  {n:8d} calls  {callee}")


if __name__ == "__main__":
    main(sys.argv[1])
