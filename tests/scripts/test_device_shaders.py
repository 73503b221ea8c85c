#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""bench/device_shaders.py's verdicts, as CI's device leg (device_shaders.sh --ci) relies on them,
on made-up compiler logs: it passes clean programs and fails, naming device and program, on a
spill, a refusal and a V3D fragment shader below the threads the page promises (the most
specific row that fits the kernel and its defines). No driver needed.

  test_device_shaders.py bench/device_shaders.py"""
import os
import subprocess
import sys
import tempfile

KERNELS = {"cheap.frag": "uniform vec3 u_colour_of_the_cheap_kernel;\nvoid main()\n{\n"
                         "    o_colour = vec4(u_colour_of_the_cheap_kernel * 0.5 + 0.25, 1.0);\n}\n",
           "dear.frag": "uniform vec3 u_colour_of_the_dear_kernel_here;\nvoid main()\n{\n"
                        "    o_colour = vec4(sqrt(u_colour_of_the_dear_kernel_here) * 0.75, 1.0);\n}\n"}
PAGE = """# promises

| program | V3D 4.2 threads at least |
| --- | ---: |
| any | 2 |
| `cheap.frag` | 4 |
| `cheap.frag inner_fresnel` | 2 |
"""
VERT = "#version 300 es\nin vec4 a_position;\nvoid main() { gl_Position = a_position; }\n"


def program(folder, name, kernel, inner_fresnel):
    with open(os.path.join(folder, name + ".vert"), "w") as f:
        f.write(VERT)
    with open(os.path.join(folder, name + ".frag"), "w") as f:
        f.write(f"#version 300 es\n#define SNELL_INNER_FRESNEL {inner_fresnel}\nprecision highp float;\n"
                f"out vec4 o_colour;\n{KERNELS[kernel]}")


def v3d_log(folder, name, threads, spills="0:0", error=None):
    body = (f"@shaderdb error {name} link: L0001 made-up refusal\n" if error else
            f"SHADER-DB-GLSL3 - MESA_SHADER_FRAGMENT shader: 100 inst, {threads} threads, 0 loops, 9 uniforms, "
            f"20 max-temps, {spills} spills:fills, 0 sfu-stalls, 100 inst-and-stalls, 3 nops\n")
    with open(os.path.join(folder, name + ".log"), "w") as f:
        f.write(f"@shaderdb device V3D 4.2\n@shaderdb begin {name} GLSL3\n{body}"
                f"@shaderdb end {name} {'failed' if error else 'ok'}\n")


def mali_log(folder, name, spills="0:0"):
    with open(os.path.join(folder, name + ".log"), "w") as f:
        f.write(f"@shaderdb device Mali-G52 (Panfrost)\n@shaderdb begin {name} GLSL3\n"
                f"SHADER-DB: MESA_SHADER_FRAGMENT shader: 80 inst, 60 tuples, 9 clauses, 2.5 cycles, 2.5 arith, "
                f"0 texture, 0 vary, 0 ldst, 40 quadwords, 2 threads, 0 preloads, 0 loops, {spills} spills:fills\n"
                f"@shaderdb end {name} ok\n")


def run(tool, tmp, case, v3d, mali=None):
    """device_shaders.py on programs {hash: (kernel, inner_fresnel)} with V3D logs {hash: kwargs}."""
    root = os.path.join(tmp, case)
    for sub in ("shaders", "dump", "v3d", "mali", "out"):
        os.makedirs(os.path.join(root, sub))
    for name, text in KERNELS.items():
        with open(os.path.join(root, "shaders", name), "w") as f:
            f.write(text)
    page = os.path.join(root, "page.md")
    with open(page, "w") as f:
        f.write(PAGE)
    for h, (kernel, fresnel, log) in v3d.items():
        program(os.path.join(root, "dump"), h, kernel, fresnel)
        v3d_log(os.path.join(root, "v3d"), h, **log)
    for h, spills in (mali or {}).items():
        mali_log(os.path.join(root, "mali"), h, spills)
    args = [sys.executable, tool, "--shaders", os.path.join(root, "shaders"), "--out", os.path.join(root, "out"),
            "--strict", "--promises", page, "--dump", os.path.join(root, "dump"),
            "--device", "v3d", os.path.join(root, "v3d")]
    if mali:
        args += ["--device", "mali", os.path.join(root, "mali")]
    r = subprocess.run(args, capture_output=True, text=True)
    return r.returncode, r.stdout + r.stderr


def main():
    tool = sys.argv[1]
    failed = 0

    def expect(case, rc, out, want_rc, *lines):
        nonlocal failed
        missing = [l for l in lines if l not in out]
        if rc != want_rc or missing:
            failed += 1
            print(f"FAIL {case}: exit {rc} (want {want_rc}); missing {missing}\n{out}")
        else:
            print(f"ok   {case}")

    with tempfile.TemporaryDirectory() as tmp:
        clean = {"00000000000000a1": ("cheap.frag", 0, {"threads": 4}),
                 "00000000000000a2": ("cheap.frag", 1, {"threads": 2}),
                 "00000000000000a3": ("dear.frag", 0, {"threads": 2})}
        rc, out = run(tool, tmp, "clean", clean, {h: "0:0" for h in clean})
        expect("clean programs pass", rc, out, 0, "v3d (V3D 4.2): 3 programs, 0 refused, 0 with spills")
        rc, out = run(tool, tmp, "threads", dict(clean, **{"00000000000000a1": ("cheap.frag", 0, {"threads": 2})}))
        expect("a cheap kernel at 2 threads fails", rc, out, 1,
               "v3d: cheap.frag inner_fresnel=0 (00000000000000a1) fragment: 2 thread(s), 4 promised")
        rc, out = run(tool, tmp, "one", dict(clean, **{"00000000000000a3": ("dear.frag", 0, {"threads": 1})}))
        expect("any kernel at 1 thread fails", rc, out, 1,
               "v3d: dear.frag (00000000000000a3) fragment: 1 thread(s), 2 promised")
        rc, out = run(tool, tmp, "spill", dict(clean, **{"00000000000000a3": ("dear.frag", 0,
                                                                               {"threads": 2, "spills": "3:5"})}))
        expect("a V3D spill fails", rc, out, 1, "v3d: dear.frag (00000000000000a3) fragment: 3:5 spills:fills")
        rc, out = run(tool, tmp, "mali", clean, dict({h: "0:0" for h in clean}, **{"00000000000000a2": "1:4"}))
        expect("a Mali spill fails", rc, out, 1,
               "mali: cheap.frag inner_fresnel (00000000000000a2) fragment: 1:4 spills:fills")
        rc, out = run(tool, tmp, "refused", dict(clean, **{"00000000000000a3": ("dear.frag", 0,
                                                                                 {"threads": 2, "error": True})}))
        expect("a refusal fails", rc, out, 1, "v3d: dear.frag (00000000000000a3): link: L0001 made-up refusal")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
