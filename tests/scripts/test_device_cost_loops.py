#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""bench/device_cost.py's loop matching (bench/devices/COSTS.md): each device loop takes the trip count of
its own source loop, or the model stops. No driver needed.

  test_device_cost_loops.py bench/device_cost.py shaders_es

1. A made-up V3D log and source in the shape of exact's walk (a loop over rays calling a while walk with
   an inner pop loop and a leaf loop; the walk in two #if variants, a macro with parentheses on the line
   before the active one): every device loop matched to its loop and trip count; a device loop with no
   source loop, a loop that ran with no device loop, and a run without loop counts each stop the model.
   Constant loops (cubemap's and layered's shape): a driver's loops are the outer ones, inner ones unrolled.
2. Every loop of every kernel the model prices (device_cost.PRICED_KERNELS, #includes resolved): one the
   model can count (braced body) or one a driver unrolls (constant bound up to device_cost.UNROLL_MAX)."""
import importlib.util
import os
import re
import sys
import tempfile

SOURCE = """#version 300 es
#define WALK 1
#define MAXI 8
precision highp float;
uniform int u_n;
out vec4 o_colour;
float g;
void leaf(int first, int end)
{
    for (int e = first; e < end; e++) {
        g += 1.0;
    }
}
#if !WALK
void closest(int n)
{
    int v = 0;
    while (v < n) {
        v++;
        leaf(0, v);
    }
}
#else
#define POP (-2147483647 - 1)
void closest(int n)
{
    int sp = 1, cur = POP;
    while (sp < n) {
        while (sp > 0) {
            sp--;
        }
        leaf(0, sp);
        sp += 2;
    }
}
#endif
void main()
{
    for (int k = 0; k <= MAXI; k++) {
        closest(u_n + k);
    }
    for (int c = 0; c < 3; c++) {
        g *= 0.5;
    }
    o_colour = vec4(g);
}
"""
# body executions of the source's braced loops in text order (leaf, the stackless walk, the stack walk,
# the pop loop, the ray loop, the constant loop) over 100 fragments
COUNTS = [800, 0, 400, 300, 200, 300]
FRAGMENTS = 100
# device loops as back edges (branch, target) in a 50-instruction program: rays [2, 40] around the walk
# [5, 35] around the pop loop [8, 14] and the leaf loop [20, 30]; the constant loop unrolled
EDGES = [(14, 8), (30, 20), (35, 5), (40, 2)]
WANT = {(2, 40): ("main", 1, 2.0), (5, 35): ("closest", 1, 4.0), (8, 14): ("closest", 2, 3.0),
        (20, 30): ("leaf", 1, 8.0)}

# constant loops only (cubemap's and layered's shape): a loop of 9 around a call holding a loop of 6, and a
# loop of one trip; body executions in text order (the inner, the outer, the one-trip loop)
SOURCE_CONST = """#version 300 es
#define OUTER 9
#define INNER 6
#define ONE 1
precision highp float;
out vec4 o_colour;
float g;
void step_in(int n)
{
    for (int i = 0; i < INNER; i++) {
        g += float(i * n);
    }
}
void main()
{
    for (int k = 0; k < OUTER; k++) {
        for (int u = 0; u < ONE; u++) {
            g *= 0.5;
        }
        step_in(k);
    }
    o_colour = vec4(g);
}
"""
COUNTS_CONST = [600, 100, 100]

failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        failures.append(what)


def v3d_log(folder, edges, n=50):
    """A V3D_DEBUG=shaderdb,qpu listing of program 1 with these back edges (V3D branches land 4
    instructions after the branch plus the offset in bytes / 8)."""
    ins = ["0x0000000000000000 nop                     ; nop"] * n
    for b, t in edges:
        ins[b] = "0x0200000000000000 bu.anyap  %d, r:unif (0x00000000 / 0.000000)" % ((t - b - 4) * 8)
    path = os.path.join(folder, "fixture-v3d.log")
    with open(path, "w") as f:
        f.write("@@LINK+ 1\nMESA_SHADER_FRAGMENT prog 1/1 QPU:\n" + "\n".join(ins) + "\n"
                "SHADER-DB-GLSL1 - MESA_SHADER_FRAGMENT shader: %d inst, 2 threads, %d loops, 9 uniforms, "
                "20 max-temps, 0:0 spills:fills, 0 sfu-stalls, %d inst-and-stalls, 3 nops\n@@LINK- 1 loops 6\n"
                % (n, len(edges), n))
    return path


def trips(dc, folder, edges, counts=COUNTS, source=SOURCE):
    prog = dc.device_programs(v3d_log(folder, edges), "v3d")[1]
    t, match, _ = dc.loop_trips(prog["loops"], source, counts, FRAGMENTS)
    return prog["loops"], t, match


def named(loops, t, match):
    return [(m["name"].split(" `")[0] if m else None, round(x, 3)) for L, x, m in zip(loops, t, match)]


def stops(dc, folder, edges, counts, says, what):
    try:
        trips(dc, folder, edges, counts)
        check(False, what + ": the model went on")
    except dc.ModelError as e:
        check(says in str(e), "%s: stops (%s)" % (what, e))


def resolve(root, path, seen=()):
    out = []
    for ln in open(path):
        m = re.match(r'\s*#\s*include\s+"([^"]+)"', ln)
        if not m:
            out.append(ln)
            continue
        inc = os.path.join(root, m.group(1))
        out.append(resolve(root, inc, seen + (path,)) if inc not in seen else "\n")
    return "".join(out)


def main():
    spec = importlib.util.spec_from_file_location("device_cost", sys.argv[1])
    dc = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(dc)
    shaders = sys.argv[2]
    with tempfile.TemporaryDirectory() as folder:
        loops, t, match = trips(dc, folder, EDGES)
        got = {(L["start"], L["end"]): (m["name"].split("()")[0] if m else None,
                                        int(m["name"].split(" loop ")[1].split(",")[0]) if m else 0, round(x, 3))
               for L, x, m in zip(loops, t, match)}
        for span, want in WANT.items():
            check(got.get(span) == want, "device loop %s: %s loop %d, %.1f a fragment (got %s)" %
                  (span, want[0], want[1], want[2], got.get(span)))
        # the constant loop kept by the driver: a fifth device loop after the rays'
        loops, t, match = trips(dc, folder, EDGES + [(47, 43)])
        kept = [(m["name"].split("()")[0], round(x, 3)) for L, x, m in zip(loops, t, match) if L["start"] == 43]
        check(kept == [("main", 3.0)], "a constant loop the driver kept: main's 2nd loop, 3 a fragment (%s)" % kept)
        # constant loops: a loop goes with the loops inside it, so one device loop is the outer one (its
        # inner loop unrolled), two nested are both; the one-trip loop is never a device loop
        got = named(*trips(dc, folder, [(40, 2)], COUNTS_CONST, SOURCE_CONST))
        check(len(got) == 1 and got[0][0].startswith("main() loop 1") and got[0][1] == 1.0,
              "one device loop around constant loops: the outer, 1 a fragment (%s)" % got)
        got = named(*trips(dc, folder, [(30, 10), (40, 2)], COUNTS_CONST, SOURCE_CONST))
        check(len(got) == 2 and got[0][0].startswith("main() loop 1") and got[0][1] == 1.0 and
              got[1][0].startswith("step_in() loop 1") and got[1][1] == 6.0,
              "two nested device loops: the outer and the called inner, 1 and 6 a fragment (%s)" % got)
        stops(dc, folder, EDGES + [(28, 22)], COUNTS, "no source loop", "a device loop with no source loop")
        stops(dc, folder, [e for e in EDGES if e != (35, 5)], COUNTS, "has no device loop",
              "the walk that ran missing on the device")
        stops(dc, folder, EDGES, [], "SNELL_COST_COUNT=1", "a run without loop counts")
    names = dc.PRICED_KERNELS
    check(len(names) >= 8, "%d kernels priced" % len(names))
    for name in names:
        path = os.path.join(shaders, name)
        if not os.path.exists(path):
            check(False, "%s: priced, not in %s" % (name, shaders))
            continue
        problems = dc.loop_form_problems(resolve(shaders, path))
        check(not problems, "%s: every loop counted or unrolled%s" % (name, (": " + "; ".join(problems)) if problems else ""))
    bad = dc.loop_form_problems("void main()\n{\n    int i = 0;\n    do {\n        i++;\n    } while (i < u_n);\n"
                                "    for (int k = 0; k < u_n; k++) i += k;\n    for (int k = 0; k < 4; k++) i += k;\n}\n")
    check(len(bad) == 2 and "line 4" in bad[0] and "line 7" in bad[1],
          "a do-while and an unbraced loop of unknown bound are reported (%s)" % bad)
    if failures:
        print("%d failed" % len(failures))
        return 1
    print("all passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
