#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""device_shaders.py: the statistics of every program through a device's real compiler.

Reads the logs of `snell-shaderdb compile DUMP HASH` (tests/snell_shaderdb.c) run under each
device's driver (shared/devices/env.sh; bench/device_shaders.sh runs them, one log per program in
a folder per device) and writes OUT/DEVICE.csv and OUT/DEVICE.md per device and OUT/SHADERS.md,
one page of them all. Each program is named by its kernel (the shaders_es/ file its source was
assembled from) and the #defines that tell its variants apart.

  device_shaders.py --shaders shaders_es --out OUT [--strict] [--promises PAGE] [--command CMD]
                    --dump DIR... --device DEVICE LOGS...     (DEVICE: v3d, adreno[-618|-660] or mali)

Exit 1 on a program a device's compiler refused (or whose statistics are missing), with
--strict also on any spill and on a V3D program at 1 thread or (--promises) below the threads
the page's table promises its fragment shader; every offender is printed."""
import argparse
import csv
import os
import re
import sys

COLUMNS = ["program", "name", "stage", "instructions", "threads", "registers", "uniforms", "loops", "spills",
           "fills", "cycles", "half_registers"]


def strip(text):
    """cmake/embed_shaders.cmake's stripping, so that the embedded (stripped) sources match."""
    text = re.sub(r"//[^\n]*", "", text)
    text = re.sub(r"[ \t\r]+", " ", text)
    text = re.sub(r" *\n *", "\n", text)
    text = re.sub(r"\n\n+", "\n", text)
    text = re.sub(r"^\n", "", text)
    text = re.sub(r" ([;,{})=*/<>?:]|\[|\])", r"\1", text)
    return re.sub(r"([;,{}(=*/<>?:]|\[|\]) ", r"\1", text)


def segments(text):
    """The runs of a file's lines between its #include lines (program.c pastes chunks there)."""
    out, run = [], []
    for line in text.split("\n"):
        if line.lstrip().startswith("#include"):
            out.append("\n".join(run))
            run = []
        else:
            run.append(line)
    out.append("\n".join(run))
    return [s for s in out if s.strip()]


def kernels(folders):
    """{file name: [its segments in every form]} of the stage files (.vert, .frag) of the folders:
    shaders_es/ (as written and stripped) and a build's stripped copies, which are what that
    build's programs were made from even where shaders_es/ has changed since."""
    out = {}
    for folder in folders:
        for root, _, files in os.walk(folder):
            for f in files:
                if f.endswith((".vert", ".frag")):
                    with open(os.path.join(root, f)) as fh:
                        text = fh.read()
                    rel = os.path.relpath(os.path.join(root, f), folder)
                    out.setdefault(rel, []).extend([segments(strip(text)), segments(text)])
    return out


def find_kernel(source, files, suffix):
    """The largest file whose segments all appear in order in source; failing that (a program of
    an older or newer file) the one with the most text of its longer lines in source, at least a
    quarter of them and 200 characters, marked with a "~"."""
    best, best_size = None, 0
    lines = set(source.split("\n"))
    near, near_found = None, 0
    for name, forms in files.items():
        if not name.endswith(suffix):
            continue
        for segs in forms:
            at = 0
            for s in segs:
                at = source.find(s, at)
                if at < 0:
                    break
                at += len(s)
            size = sum(len(s) for s in segs)
            if at >= 0 and segs and size > best_size:
                best, best_size = name, size
            own = {l for s in segs for l in s.split("\n") if len(l) > 20}
            total = sum(len(l) for l in own)
            found = sum(len(l) for l in own if l in lines)
            if 4 * found >= total and found >= 200 and found > near_found:
                near, near_found = name + "~", found
    return best or near


def variant_defines(source):
    """The #defines program.c puts after #version, before the kernel's text, but its precision
    policy: the light range where float targets do not blend, then the variant's own."""
    out = []
    for line in source.split("\n")[1:]:
        m = re.match(r"#define (SNELL_\w+)(?:[ \t]+(\S+))?", line)
        if not m:
            break
        if m.group(1) != "SNELL_MEDIUMP":
            out.append(m.group(1)[6:].lower() + ("" if m.group(2) in (None, "1") else "=" + m.group(2)))
    return out


def c_file_of(text, c_files):
    """The C source (src/, tests/) holding a program written inline: the one holding the most of
    its lines (those outside chunks, stripped as program.c leaves them), or None."""
    lines = {l.strip() for l in text.split("\n")[1:] if len(l.strip()) > 12 and not l.startswith("#")}
    best, best_n = None, 0
    for path, code in c_files.items():
        n = sum(1 for l in lines if l in code)
        if n > best_n:
            best, best_n = path, n
    return best


def name_programs(sources, files, c_files):
    """{hash: name} of the programs {hash: folder}, and {hash: (fragment file, vertex file, defines)}.
    The name: the kernel's fragment file, joined by its
    vertex file where that is the larger and serves no other fragment file (caustics_photon.vert,
    whose fragment shader only splats), or alone where the fragment shader is none of shaders_es/
    (snell's inline one); the vertex file where the kernel has several; then the defines not
    common to all its variants."""
    def size(name):
        return sum(len(seg) for seg in files[name.rstrip("~")][0]) if name else 0

    found = {}
    for h, folder in sources.items():
        with open(os.path.join(folder, h + ".frag")) as f:
            fs = f.read()
        with open(os.path.join(folder, h + ".vert")) as f:
            vs = f.read()
        frag, vert = find_kernel(fs, files, ".frag"), find_kernel(vs, files, ".vert")
        if not frag and not vert:  # a program of a test's or of snell's own C strings
            frag = "inline in " + (c_file_of(vs + fs, c_files) or "C")
        found[h] = (frag, vert, variant_defines(fs))
    serves = {}
    for frag, vert, _ in found.values():
        serves.setdefault(vert, set()).add(frag)
    info = {}
    for h, (frag, vert, defines) in found.items():
        if not frag or (vert and size(vert) > size(frag) and len(serves[vert]) == 1):
            kernel = "+".join(n for n in (frag, vert) if n)
        else:
            kernel = frag
        info[h] = (kernel or "unknown", vert or "inline", defines)
    out = {}
    for kernel in {k for k, _, _ in info.values()}:
        members = [h for h in info if info[h][0] == kernel]
        common = set.intersection(*(set(info[h][2]) for h in members))
        verts = {info[h][1] for h in members}
        for h in members:
            parts = [kernel] + (["@" + info[h][1]] if len(verts) > 1 else [])
            parts += [d for d in info[h][2] if d not in common]
            out[h] = " ".join(parts)
    return out, found


def read_promises(path):
    """The V3D threads a page promises: the rows of its table headed "V3D 4.2 threads at least",
    [(fragment file, [defines], threads)]; "any" stands for every program."""
    rows, inside = [], False
    with open(path) as f:
        for line in f:
            cells = [c.strip().strip("`") for c in line.strip().strip("|").split("|")]
            if not line.startswith("|"):
                inside = False
            elif len(cells) >= 2 and cells[1] == "V3D 4.2 threads at least":
                inside = True
            elif inside and cells[1].isdigit():
                words = cells[0].split()
                rows.append((words[0], words[1:], int(cells[1])))
    if not rows:
        raise SystemExit(f"device_shaders.py: no table headed 'V3D 4.2 threads at least' in {path}")
    return rows


def promised(rows, frag, defines):
    """The threads the most specific matching row promises: the fragment file's row whose defines
    the program all has (the most of them), else the "any" row; None without one."""
    best, best_n = None, -1
    for kernel, need, threads in rows:
        if kernel in (frag, "any") and all(d in defines for d in need):
            n = len(need) + (kernel != "any") * 100
            if n > best_n:
                best, best_n = threads, n
    return best


def values(text):
    """'2582 inst, 2 threads, 35:59 spills:fills' -> {'inst': '2582', 'threads': '2', 'spills': '35', ...}"""
    out = {}
    for item in text.split(","):
        m = re.match(r"\s*(-?[\d.]+)(?::(-?[\d.]+))?\s+(\S.*?)\s*$", item)
        if not m:
            continue
        if m.group(2) is not None and ":" in m.group(3):
            a, b = m.group(3).split(":", 1)
            out[a], out[b] = m.group(1), m.group(2)
        else:
            out[m.group(3)] = m.group(1)
    return out


# One parser per driver: (stage, the CSV row's statistics) from a line of its output, or None.
V3D_LINE = re.compile(r"^SHADER-DB-(\S+) - MESA_SHADER_(\w+) shader: (.*)$")
FD_LINE = re.compile(r"^@shaderdb debug (B?VERT|FRAG) shader: (.*)$")
PAN_LINE = re.compile(r"^SHADER-DB: MESA_SHADER_(\w+) shader: (.*)$")
# the drivers' stage names; a binning vertex shader is the tiler's position-only copy, Bifrost's
# position and varying shaders the two halves of its vertex shader (IDVS)
STAGES = {"FRAGMENT": "fragment", "FRAG": "fragment", "VERTEX": "vertex", "VERT": "vertex",
          "VERTEX_BIN": "binning vertex", "BVERT": "binning vertex", "POSITION": "vertex position",
          "VARYING": "vertex varying"}


def parse_v3d(line, glsl):
    m = V3D_LINE.match(line)
    if not m:
        return None
    if m.group(1) != glsl:
        raise ValueError(f"statistics of {m.group(1)} inside {glsl}'s compile: {line.strip()}")
    v = values(m.group(3))
    return STAGES.get(m.group(2), m.group(2)), {
        "instructions": v.get("inst"), "threads": v.get("threads"), "uniforms": v.get("uniforms"),
        "loops": v.get("loops"), "spills": v.get("spills"), "fills": v.get("fills")}


def parse_adreno(line, glsl):
    m = FD_LINE.match(line)
    if not m:
        return None
    v = values(m.group(2))
    # uniforms: constlen (vec4s of the constant file); spills/fills: stp/ldp (private memory)
    return STAGES[m.group(1)], {
        "instructions": v.get("inst"), "registers": v.get("full"), "half_registers": v.get("half"),
        "uniforms": v.get("constlen"), "loops": v.get("loops"), "spills": v.get("stp"), "fills": v.get("ldp"),
        "waves": v.get("waves")}


def parse_mali(line, glsl):
    m = PAN_LINE.match(line)
    if not m:
        return None
    v = values(m.group(2))
    # cycles: Bifrost's estimate, the largest of arith, texture, varying and load/store; each
    # instruction counted once, a loop's body not multiplied by its trips
    return STAGES.get(m.group(1), m.group(1)), {
        "instructions": v.get("inst"), "threads": v.get("threads"), "loops": v.get("loops"),
        "spills": v.get("spills"), "fills": v.get("fills"), "cycles": v.get("cycles")}


PARSERS = {"v3d": parse_v3d, "adreno": parse_adreno, "mali": parse_mali, "reference": lambda line, glsl: None}


def read_logs(folder, device):
    """{hash: {"glsl", "status", "errors", "stages": [(stage, stats)]}} and the device's GL_RENDERER,
    from one log per program (the lines of snell-shaderdb and of the driver, in order)."""
    parse = PARSERS[device.split("-")[0]]
    programs, renderer = {}, ""
    for log in sorted(os.listdir(folder)):
        h = log[:-4]
        p = programs[h] = {"glsl": None, "status": None, "errors": [], "stages": [], "cpu": None}
        with open(os.path.join(folder, log), errors="replace") as f:
            for line in f:
                line = line.rstrip("\n")
                word = line.split(" ", 2) + ["", ""]
                if word[0] == "@shaderdb" and word[1] != "debug":
                    if word[1] == "device":
                        renderer = word[2]
                    elif word[1] == "begin":
                        p["glsl"] = word[2].split()[1]
                    elif word[1] == "error":
                        p["errors"].append(word[2].split(" ", 1)[1])
                    elif word[1] == "end" and p["status"] is None:
                        p["status"] = word[2].split()[1]
                    elif word[1] == "cpu":  # the compile's process, user + system seconds
                        p["cpu"] = sum(float(x) for x in word[2].split())
                    elif word[1] in ("timeout", "crash"):
                        p["status"] = word[1]
                        p["errors"].append(word[1] + " " + word[2].split(" ", 1)[1])
                    continue
                if p["glsl"] is None or p["status"] is not None:
                    continue  # the driver's own shaders (clears) before the program, or after it
                try:
                    got = parse(line, p["glsl"])
                except ValueError as e:
                    p["errors"].append(str(e))
                    p["status"] = "misattributed"
                    continue
                if got:
                    p["stages"].append(got)
        if p["status"] is None:
            p["errors"].append("snell-shaderdb stopped before the program's end (see " + log + ")")
    return programs, renderer


def num(x):
    try:
        return float(x)
    except (TypeError, ValueError):
        return 0.0


def device_report(device, programs, renderer, names, out, refused_here, want_threads):
    """Writes out/DEVICE.csv and out/DEVICE.md; returns (markdown, failures, spills, too few
    threads: at 1 on V3D, or below want_threads(hash) for a fragment shader). A program the
    suite's own driver refuses too (refused_here: a test's deliberate error) is no failure."""
    rows, failures, spills, single = [], [], [], []
    for h in sorted(programs, key=lambda h: (names.get(h, "?"), h)):
        p = programs[h]
        name = names.get(h, "?")
        if p["status"] != "ok":
            if h not in refused_here:
                failures.append(f"{device}: {name} ({h}): " + ("; ".join(p["errors"]) or "did not finish"))
            continue
        # a stage compiled twice (freedreno's first variant at link, another for the draw's state):
        # the later one, which the draw used
        stages = dict(p["stages"])
        if "fragment" not in stages:
            failures.append(f"{device}: {name} ({h}): linked but no fragment statistics came")
        for stage, st in stages.items():
            rows.append(dict(st, program=h, name=name, stage=stage))
            if num(st.get("spills")) or num(st.get("fills")):
                spills.append(f"{device}: {name} ({h}) {stage}: {st.get('spills')}:{st.get('fills')} spills:fills")
            want = want_threads(h) if device == "v3d" and stage == "fragment" else None
            if device == "v3d" and (st.get("threads") == "1" or (want and num(st.get("threads")) < want)):
                single.append(f"{device}: {name} ({h}) {stage}: {st.get('threads')} thread(s)"
                              + (f", {want} promised" if want else ""))
    with open(os.path.join(out, device + ".csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(COLUMNS)
        for r in rows:
            w.writerow([r.get(c) if r.get(c) is not None else "" for c in COLUMNS])
    md = markdown(device, renderer, programs, rows, names, refused_here)
    with open(os.path.join(out, device + ".md"), "w") as f:
        f.write(md)
    return md, failures, spills, single


def markdown(device, renderer, programs, rows, names, refused_here):
    """One row per program: its fragment shader's figures, then its vertex stages' instructions."""
    frag = {"v3d": ["instructions", "threads", "uniforms", "loops", "spills:fills"],
            "adreno": ["instructions", "full, half registers", "waves", "constlen", "loops", "stp:ldp"],
            "mali": ["instructions", "cycles", "threads", "loops", "spills:fills"]}[device.split("-")[0]]
    by = {}
    for r in rows:
        by.setdefault((r["name"], r["program"]), []).append(r)

    def cell(r, col):
        if col in ("spills:fills", "stp:ldp"):
            return f"{r.get('spills')}:{r.get('fills')}"
        if col == "full, half registers":
            return f"{r.get('registers')}, {r.get('half_registers')}"
        if col == "constlen":
            return r.get("uniforms") or ""
        if col == "cycles":
            return f"{num(r.get('cycles')):.1f}"
        return r.get(col) or ""

    lines = [f"### {renderer or device}", "",
             f"{len(programs)} programs; fragment shader: {', '.join(frag)}; vertex stages: instructions"
             + (", stp:ldp" if device.startswith("adreno") else ", spills:fills") + "; the compile's CPU seconds here", "",
             "| program | hash | " + " | ".join(frag) + " | vertex stages | compile s |",
             "| --- | --- | " + " | ".join("---:" for _ in frag) + " | --- | ---: |"]
    for (name, h), rs in sorted(by.items()):
        f = next((r for r in rs if r["stage"] == "fragment"), {})
        vert = ", ".join(f"{r['stage']} {r.get('instructions')}"
                         + (f" ({r.get('spills')}:{r.get('fills')})" if num(r.get("spills")) or num(r.get("fills")) else "")
                         for r in rs if r["stage"] != "fragment")
        cpu = programs[h]["cpu"]
        lines.append(f"| {name} | {h[:8]} | " + " | ".join(cell(f, c) for c in frag)
                     + f" | {vert} | {'' if cpu is None else f'{cpu:.1f}'} |")
    for h, p in sorted(programs.items(), key=lambda x: (names.get(x[0], "?"), x[0])):
        if p["status"] != "ok":
            why = "; ".join(p["errors"]).replace("|", "/")
            also = " (so does the suite's own driver)" if h in refused_here else ""
            lines.append(f"| {names.get(h, '?')} | {h[:8]} | refused{also}: {why} |")
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--shaders", action="append", required=True,
                    help="shaders_es/ or a build's stripped copies, to name each program by its kernel")
    ap.add_argument("--c-sources", action="append", default=[],
                    help="src/, tests/: where programs written inline in C are looked up by their text")
    ap.add_argument("--out", required=True, help="folder for DEVICE.csv, DEVICE.md and SHADERS.md")
    ap.add_argument("--strict", action="store_true", help="fail on spills and on V3D programs at 1 thread")
    ap.add_argument("--command", default="bash bench/device_shaders.sh", help="what the page says made it")
    ap.add_argument("--mesa", default="Mesa 22.3.6", help="the drivers' version, for the page's header")
    ap.add_argument("--what", default="every program variant of the dump",
                    help="which programs the dumps hold, for the page's header")
    ap.add_argument("--commit", default="", help="the snell commit they came from, for the page's header")
    ap.add_argument("--dump", action="append", required=True, help="a folder of <hash>.vert + .frag")
    ap.add_argument("--device", action="append", nargs=2, required=True, metavar=("DEVICE", "LOGS"))
    ap.add_argument("--promises", metavar="PAGE",
                    help="a page whose table headed 'V3D 4.2 threads at least' V3D's fragment shaders are held to")
    ap.add_argument("--reference", metavar="LOGS",
                    help="logs of the programs some device refused, compiled by the suite's own driver")
    a = ap.parse_args()
    sources = {}
    for folder in a.dump:
        for f in sorted(os.listdir(folder)):
            if f.endswith(".frag") and os.path.exists(os.path.join(folder, f[:-5] + ".vert")):
                sources.setdefault(f[:-5], folder)
    c_files = {}
    for folder in a.c_sources:
        for root, _, fs in os.walk(folder):
            for f in fs:
                if f.endswith((".c", ".h")):
                    with open(os.path.join(root, f), errors="replace") as fh:
                        c_files[os.path.relpath(os.path.join(root, f), os.path.dirname(folder))] = fh.read()
    names, found = name_programs(sources, kernels(a.shaders), c_files)
    promises = read_promises(a.promises) if a.promises else []
    os.makedirs(a.out, exist_ok=True)
    pages, failures, spills, single, summary = [], [], [], [], []
    refused_here = {}
    if a.reference:
        ref, ref_renderer = read_logs(a.reference, "reference")
        refused_here = {h: p for h, p in ref.items() if p["status"] != "ok"}
        if refused_here:
            summary.append(f"{ref_renderer}, the suite's own driver, refuses {len(refused_here)} of them too "
                           "(tests' deliberate errors): " + ", ".join(f"{names.get(h, h)} ({h[:8]})"
                                                                      for h in sorted(refused_here)))
    for device, logs in a.device:
        if device.split("-")[0] not in PARSERS:
            ap.error(f"--device {device}: want one of {', '.join(PARSERS)} (adreno-618 and the like too)")
        programs, renderer = read_logs(logs, device)
        md, fail, sp, one = device_report(device, programs, renderer, names, a.out, refused_here,
                                          lambda h: promised(promises, found[h][0], found[h][2]) if promises else None)
        pages.append(md)
        failures, spills, single = failures + fail, spills + sp, single + one
        threads = {}
        for p in programs.values():
            st = dict(p["stages"]).get("fragment", {}) if p["status"] == "ok" else {}
            if st.get("threads"):
                threads[st["threads"]] = threads.get(st["threads"], 0) + 1
        cpu = {h: p["cpu"] for h, p in programs.items() if p["cpu"] is not None}
        slowest = max(cpu, key=cpu.get) if cpu else None
        summary.append(f"{device} ({renderer}): {len(programs)} programs, {len(fail)} refused, "
                       f"{len({s.split(' (')[1][:16] for s in sp})} with spills"
                       + ("; fragment shaders at " + ", ".join(f"{k} threads: {threads[k]}" for k in sorted(threads))
                          if threads else "")
                       + (f"; compiles {sum(cpu.values()):.0f} CPU s in all, the longest {cpu[slowest]:.1f} s "
                          f"({names.get(slowest, slowest)})" if cpu else ""))
    with open(os.path.join(a.out, "SHADERS.md"), "w") as f:
        f.write(f"# snell's programs through the real device compilers\n\n"
                f"Generated by `{a.command}` ({a.mesa}'s drivers over drm-shim, shared/devices; "
                f"docs/devices.md){' at snell ' + a.commit if a.commit else ''}: {a.what} "
                f"({len(sources)} programs in all), compiled, linked and drawn once by each device's driver. "
                f"Do not edit: run it again.\n\n"
                + "\n".join(f"- {s}" for s in summary) + "\n\n" + "\n".join(pages))
    for s in summary:
        print(s)
    for what, items in (("refused", failures), ("spills", spills), ("V3D below its threads", single)):
        if items:
            print(f"{what} ({len(items)}):")
            for i in items:
                print("  " + i)
    bad = failures or (a.strict and (spills or single))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
