#!/usr/bin/env python3
"""Modelled cycles per pair of the library's hot paths on other CPUs
(docs/performance.md, "Model"). NOT a test; a measurement script.

    mca_model.py --trace-pairs BUILD/bench/trace_pairs [--path v4|v3|native]
                 [--calls default,overlap,...] [--sets random,near] [--classes 0,1,2,3]
                 [--pairs K] [--batch M] [--cpus skylake-avx512,...] [--out FILE.csv]

For every call, set and class it runs trace_pairs (bench/trace_pairs.cpp)
under gdb with LD_BIND_NOW=1, single-steps traced_call on each of K pairs
(the pairs calls: one call on M pairs) and records the dynamic instruction
trace: every instruction executed, in order, with the branches actually
taken. Each trace is given to llvm-mca-14 as one block (-iterations=20, 3
for traces over 6,667 instructions) for
every CPU model: cycles per iteration = modelled cycles of the call when it
is repeated back to back with its branches predicted and its data in L1
(llvm-mca models neither mispredictions nor cache misses nor the front end;
calls and returns are left out of the trace, since llvm-mca would give each
call 100 cycles of latency; jumps stay as plain instructions). LLVM 14
has four scheduling models among these CPUs: Skylake-SP (skylake-avx512,
and sapphirerapids, which has no model of its own there), Ice Lake
(icelake-server, rocketlake), Haswell and Zen 3. Cycles per pair = mean over the K
traces (divided by M for the pairs calls). --path v3 clears the x86-64-v4
bit of the library's CPU-feature word (GCC's __cpu_features2, byte 8, bit 2,
as its __builtin_cpu_supports("x86-64-v4") tests it) after start-up, so the
dispatch takes the x86-64-v3 variants on this AVX-512 CPU; native leaves it
(x86-64-v4 here); a build with -Disa_dispatch=false gives the portable code.
Haswell and Zen 3 rows: AVX-512 instructions are left out of a trace when
they are under 1 % of it (glibc's memset, which glibc picks for this CPU),
else NaN (the x86-64-v4 variants). The pairs calls' traces include the
call's own overhead (OpenMP loop start, buffers) spread over --batch pairs.
Writes one CSV row per call, set, class and CPU: mean modelled cycles per
pair, the mean number of instructions per pair and their IPC.
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

GDB_SCRIPT = r'''
import gdb
gdb.execute("set pagination off")
gdb.execute("set confirm off")
gdb.execute("break main")
gdb.execute("run")
if CLEAR_V4:
    addr = int(gdb.parse_and_eval("(unsigned long)&'__cpu_features2'"))
    b = int(gdb.parse_and_eval("*(unsigned char*)%d" % (addr + 8)))
    gdb.execute("set var *(unsigned char*)%d = %d" % (addr + 8, b & ~4))
gdb.execute("break *traced_call")
gdb.execute("continue")
traces = []
seen = {}
for n in range(NCALLS):
    ret = int(gdb.parse_and_eval("*(unsigned long*)$sp"))
    pcs = []
    while True:
        pc = int(gdb.parse_and_eval("$pc"))
        if pc == ret:
            break
        pcs.append(pc)
        if pc not in seen:
            seen[pc] = gdb.execute("x/i %d" % pc, to_string=True)
        gdb.execute("stepi", to_string=True)
    traces.append(pcs)
    if n + 1 < NCALLS:
        gdb.execute("continue")
with open(OUT, "w") as f:
    for pc, text in seen.items():
        f.write("I %d %s\n" % (pc, text.strip().replace("\n", " ")))
    for pcs in traces:
        f.write("T " + " ".join(str(p) for p in pcs) + "\n")
gdb.execute("kill")
'''


CALL_RET = re.compile(r"^(call|ret)")
AVX512 = re.compile(r"zmm|%k[0-7]|[xy]mm(1[6-9]|2[0-9]|3[01])\b|\{")


def clean(text):
    """AT&T text of gdb's x/i line, without address, symbol and comment."""
    # "=> 0x7ffff7fa1000 <sym+12>:\tmov %rax,%rbx" or "   0x... <sym>:\t..."
    ins = text.split(":", 1)[1] if ":\t" in text or ">:" in text else text
    ins = ins.split("#")[0]
    ins = re.sub(r"<[^>]*>", "", ins)
    ins = ins.replace("\t", " ").strip()
    ins = re.sub(r"\s+", " ", ins)
    # Absolute jump/call targets: llvm-mca needs no symbol; keep the number.
    ins = re.sub(r"^(bnd |notrack )+", "", ins)
    return ins


def record(binary, call, set_name, cls, count, clear_v4):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "trace.txt")
        script = os.path.join(tmp, "trace.py")
        ncalls = 1 if call.endswith("_pairs") else count
        with open(script, "w") as f:
            f.write("CLEAR_V4 = %s\nNCALLS = %d\nOUT = %r\n" % (clear_v4, ncalls, out))
            f.write(GDB_SCRIPT)
        env = dict(os.environ, LD_BIND_NOW="1")
        subprocess.run(["gdb", "-nx", "-batch", "-x", script, "--args", binary, call, set_name,
                        str(cls), str(count)], check=True, env=env,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        text, traces = {}, []
        with open(out) as f:
            for line in f:
                if line.startswith("I "):
                    _, pc, ins = line.rstrip("\n").split(" ", 2)
                    text[int(pc)] = clean(ins)
                elif line.startswith("T "):
                    traces.append([int(p) for p in line.split()[1:]])
        # llvm-mca models a call as 100 cycles of latency: calls and returns
        # are left out (their stack-pointer updates do not matter here).
        return [[text[p] for p in t if not CALL_RET.match(text[p])] for t in traces]


def mca(instructions, cpu):
    # Enough iterations for the steady state, fewer for long traces.
    iterations = max(3, min(20, 20000 // max(1, len(instructions))))
    src = "\n".join(instructions) + "\n"
    r = subprocess.run(["llvm-mca-14", "-mtriple=x86_64-unknown-linux-gnu", "-mcpu=" + cpu,
                        "-iterations=%d" % iterations],
                       input=src, capture_output=True, text=True)
    if r.returncode:
        raise RuntimeError(r.stderr[:2000])
    m = re.search(r"Total Cycles:\s+(\d+)", r.stdout)
    return int(m.group(1)) / iterations


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--trace-pairs", required=True)
    ap.add_argument("--path", default="native", choices=["native", "v3"])
    ap.add_argument("--label", default=None, help="variant name in the CSV (default: --path)")
    ap.add_argument("--calls", default="default,overlap")
    ap.add_argument("--sets", default="random")
    ap.add_argument("--classes", default="0,1,2,3")
    ap.add_argument("--pairs", type=int, default=8)
    ap.add_argument("--batch", type=int, default=64)
    ap.add_argument("--cpus", default="skylake-avx512,icelake-server,rocketlake,sapphirerapids,znver3,haswell")
    ap.add_argument("--out", default=None)
    a = ap.parse_args()
    label = a.label or a.path
    out = open(a.out, "a") if a.out else sys.stdout
    cpus = a.cpus.split(",")
    for call in a.calls.split(","):
        for set_name in a.sets.split(","):
            for cls in [int(c) for c in a.classes.split(",")]:
                batch = call.endswith("_pairs")
                count = a.batch if batch else a.pairs
                traces = record(a.trace_pairs, call, set_name, cls, count, a.path == "v3")
                per = count if batch else 1
                n_ins = sum(len(t) for t in traces) / len(traces) / per
                for cpu in cpus:
                    # AVX-512 code cannot be modelled on a CPU without it; a
                    # few such instructions (glibc's memset, chosen for this
                    # CPU) are left out, more make the row NaN.
                    use = traces
                    if cpu in ("haswell", "znver3"):
                        use = [[i for i in t if not AVX512.search(i)] for t in traces]
                        dropped = sum(len(t) for t in traces) - sum(len(t) for t in use)
                        if dropped > 0.01 * sum(len(t) for t in traces):
                            use = None
                    if use is None:
                        cyc = float("nan")
                    else:
                        cyc = sum(mca(t, cpu) for t in use) / len(use) / per
                    out.write("%s,%s,%s,%d,%s,%.1f,%.1f,%.2f\n" % (label, call, set_name, cls, cpu,
                                                                 cyc, n_ins, n_ins / cyc if cyc == cyc else float("nan")))
                    out.flush()


if __name__ == "__main__":
    main()
