#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Issue 49 item 3: snell-bench --compare on hostile JSON. Linear (20,000
results against themselves within a few seconds), JSON numbers only, bounded
columns, control bytes scrubbed, each run's load and device shown with a
warning where they differ. Usage: check_compare.py SNELL_BENCH OUT_DIR"""
import json, os, subprocess, sys, time

bench, out = sys.argv[1], sys.argv[2]
os.makedirs(out, exist_ok=True)
failed = []


def write(name, text):
    path = os.path.join(out, name)
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)
    return path


def run(a, b, limit=10):
    t0 = time.monotonic()
    p = subprocess.run([bench, "--compare", a, b], capture_output=True, timeout=limit)
    return p.returncode, p.stdout.decode("utf-8", "replace"), p.stderr.decode("utf-8", "replace"), time.monotonic() - t0


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failed.append(what)


def result(spec, median):
    return {"spec": spec, "time_ms": {"median": median, "p99": 2.0}, "vs_full": {"psnr_glass_db": 30.0}}


def run_json(results, load="0.10 0.10 0.10", renderer="llvmpipe", profile="none"):
    return json.dumps({"tool": "snell-bench", "gl": {"renderer": renderer}, "device_profile": profile,
                       "loadavg_before": load, "loadavg_after": load, "results": results})


# linear: 20,000 distinct specs against themselves (35-55 s for 2,000 before)
big = write("big.json", run_json([result("single:scene=s%d" % i, 1.0) for i in range(20000)]))
rc, so, se, dt = run(big, big, limit=30)
check(rc == 0 and so.count("\n") > 20000 and dt < 5, "20,000 results against themselves: exit %d in %.2f s" % (rc, dt))
check("warning" not in so, "no warning for one run against itself")

# JSON numbers only: 0x10 is no number, the file no JSON
hexa = write("hex.json", '{"results":[{"spec":"a","time_ms":{"median":0x10}}]}')
rc, so, se, _ = run(hexa, hexa)
check(rc == 1 and "is not JSON" in se, "0x10 refused: exit %d, %s" % (rc, se.strip()))

# bounded columns: 1e308 is no 309-digit number
huge = write("huge.json", run_json([result("a", 1e308)]))
rc, so, se, _ = run(huge, huge)
row = [l for l in so.splitlines() if l.startswith("a ")]
check(rc == 0 and row and len(row[0]) < 140 and "1e+308" in row[0], "1e308 in a bounded column: %r" % row)

# control bytes scrubbed: an ESC and a BEL in a string, a C1 control
ctl = write("ctl.json", '{"tool":"x\x1b]0;T\x07y","gl":{"renderer":"r\u009b2J"},'
            '"results":[{"spec":"s\x1b[2Ja","time_ms":{"median":1}}]}')
rc, so, se, _ = run(ctl, ctl)
check(rc == 0 and "\x1b" not in so and "\x07" not in so and "\u009b" not in so and "x?]0;T?y" in so
      and "s?[2Ja" in so, "control bytes scrubbed: %r" % so[:200])

# each run's load and device, a warning where they differ
a = write("a.json", run_json([result("a", 1.0)], load="0.20 0.10 0.10"))
b = write("b.json", run_json([result("a", 1.7)], load="3.50 1.00 0.50", renderer="V3D 4.2", profile="rpi-v3d"))
rc, so, se, _ = run(a, b)
check(rc == 0 and "load average 0.20 0.10 0.10 before" in so and "load average 3.50 1.00 0.50 before" in so,
      "both loads shown")
check("device profile rpi-v3d" in so and "warning: the runs differ in GL renderer" in so, "device warning")
check("warning: the load averages before the runs differ" in so, "load warning")
sys.exit(1 if failed else 0)
