#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""device_cost.py — a cost model per device from compiles and llvmpipe counts (issue 46 item 2).

    python3 bench/device_cost.py LOGDIR [OUT.md]

LOGDIR is what bench/device_cost.sh wrote: per scene and method the llvmpipe trace (every draw's program,
target and shaded fragments, every source loop's body executions) and each device driver's disassembly.
Writes OUT.md (default bench/devices/COSTS.md). Python 3 standard library only. See the page for the model.
"""
import glob
import os
import re
import sys

SCENES = ["sphere", "bunny", "torus"]
METHODS = ["single", "layered", "cubemap", "wyman", "oliveira", "peel", "exact", "auto"]
SIZES = ["1280x720", "1920x1080"]
DEVICES = ["v3d", "adreno", "mali"]
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

# --- device throughput (every number stated in COSTS.md with its source) ---------------------------------
# lanes: fragment lanes issuing one unit (V3D: QPU instruction; Adreno: ir3 issue slot; Mali: clause tuple)
# per clock over the whole GPU; bw: DRAM bytes/s the tile loads and stores share.
DEV = {
    "v3d": dict(name="Raspberry Pi 4 (V3D 4.2)", renderer="V3D 4.2", clock=500e6, lanes=8 * 4,
                lanes_text="8 QPUs (2 slices x 4), each a 16-way SIMD issuing over 4 clocks: 32 lanes a clock",
                bw=4.4e9, bw_text="LPDDR4-3200 x32 (12.8 GB/s peak); 4.4 GB/s sustained (stated assumption: "
                "about a third of peak, the GPU sharing a 32-bit bus with the CPU and the scan-out)",
                unit="QPU instructions", tile="64x64 (32x32 at 4 bytes/pixel with more than one target)"),
    "adreno": dict(name="Adreno 630 (Snapdragon 845)", renderer="FD630", clock=710e6, lanes=512,
                   lanes_text="2 SPs, 512 FP32 ALU lanes in all (727 GFLOPS = 512 x 2 x 710 MHz)",
                   bw=15e9, bw_text="LPDDR4X-3733 4x16-bit (29.9 GB/s peak); 15 GB/s sustained (half of peak)",
                   unit="ir3 issue slots (instructions + their (nopN)/(rptN) cycles)", tile="GMEM bins"),
    "mali": dict(name="Mali-G52 MP2 (2 cores x 2 EE, e.g. Rockchip RK3566/RK3568)", renderer="Mali-G52",
                 clock=800e6, lanes=2 * 2 * 8,
                 lanes_text="2 cores x 2 execution engines x 8-wide warps, one clause tuple (FMA+ADD) a clock "
                 "per warp: 32 lanes a clock",
                 bw=6.4e9, bw_text="LPDDR4-3200 x32 (12.8 GB/s peak); 6.4 GB/s sustained (half of peak)",
                 unit="clause tuples", tile="16x16"),
}


def occupancy_factor(dev, threads, regs):
    """Latency hiding: a stated multiplier on issue time where the compiler ran out of threads."""
    if dev == "v3d":  # V3D_DEBUG: threads 4 best, 1 worst
        return {4: 1.0, 2: 1.25, 1: 1.6}.get(threads, 1.0)
    if dev == "mali":  # Bifrost: 2 threads (<= 32 registers) or 1 (64 registers)
        return {2: 1.0, 1: 1.25}.get(threads, 1.0)
    if dev == "adreno":  # full registers per fibre: waves a SP holds fall as they grow
        if regs <= 16:
            return 1.0
        if regs <= 32:
            return 1.25
        return 1.6
    return 1.0


# --- source programs ---------------------------------------------------------------------------------
def strip_comments(s):
    o = list(s)
    n = len(s)
    i = 0
    while i < n:
        if s[i] == '/' and i + 1 < n and s[i + 1] == '/':
            while i < n and s[i] != '\n':
                o[i] = ' '
                i += 1
        elif s[i] == '/' and i + 1 < n and s[i + 1] == '*':
            o[i] = o[i + 1] = ' '
            i += 2
            while i < n and not (s[i] == '*' and i + 1 < n and s[i + 1] == '/'):
                if s[i] != '\n':
                    o[i] = ' '
                i += 1
            if i + 1 < n:
                o[i] = o[i + 1] = ' '
                i += 1
        i += 1
    return ''.join(o)


def loop_heads(s):
    """The loops with a braced body in comment-free source s, at most 63 (device_cost_trace.c's counters):
    (start of the keyword, index of the header's closing parenthesis, index of the body's brace)."""
    for m in re.finditer(r'(?<![A-Za-z0-9_])(for|while)\s*\(', s):
        j, d = m.end() - 1, 0
        while j < len(s):
            if s[j] == '(':
                d += 1
            elif s[j] == ')':
                d -= 1
                if d == 0:
                    break
            j += 1
        k = j + 1
        while k < len(s) and s[k] in ' \t\n':
            k += 1
        if k < len(s) and s[k] == '{':
            yield m.start(), j, k


def source_loops(src):
    """The loops device_cost_trace.c counts, in its order: (line, header text)."""
    s = strip_comments(src)
    return [(s.count('\n', 0, a) + 1, ' '.join(s[a:j + 1].split())) for a, j, _ in loop_heads(s)][:63]


_FILES = None


def shader_files():
    global _FILES
    if _FILES is None:
        _FILES = {}
        for path in glob.glob(os.path.join(ROOT, "shaders_es", "*.frag")):
            lines = set()
            for ln in strip_comments(open(path).read()).splitlines():
                t = re.sub(r'\s+', '', ln)  # the packed sources are stripped of blanks
                if len(t) > 10 and not t.startswith('#'):
                    lines.add(t)
            _FILES[os.path.basename(path)[:-5]] = lines
    return _FILES


def program_name(frag_src):
    have = set(re.sub(r'\s+', '', t) for t in strip_comments(frag_src).splitlines())
    best, score = "?", 0.0
    for name, lines in shader_files().items():
        if not lines:
            continue
        hit = len(lines & have) / len(lines)
        if hit > score + 1e-9 or (abs(hit - score) < 1e-9 and len(lines) > len(shader_files().get(best, ()))):
            best, score = name, hit
    return best if score >= 0.6 else "?"


# --- llvmpipe traces ------------------------------------------------------------------------------------
DRAW_RE = re.compile(r'@@DRAW\+ (\d+) (\w+) mode (\d+) count (\d+) fbo (\d+) tex (\d+) vp (\d+) (\d+) '
                     r'color_bytes (\d+) buffers (\d+) depth_bytes (\d+) stencil_bytes (\d+) depth_test (\d) '
                     r'depth_write (\d) blend (\d) pass (\d+) cleared (\d)')


def parse_llvmpipe(path):
    """The last frame's draws and the stats' method per glass object."""
    frames, cur, method = [], None, None
    last = None
    blits = []
    for ln in open(path, errors="replace"):
        if ln.startswith("@@FRAME"):
            cur = []
            frames.append(cur)
            blits = []
        elif ln.startswith("@@BLIT"):
            blits.append(tuple(int(x) for x in ln.split()[1:3]))
        elif ln.startswith("@@DRAW+"):
            m = DRAW_RE.match(ln)
            if m and cur is not None:
                g = [int(x) for x in m.groups()[2:]]
                last = dict(prog=int(m.group(1)), vp=(g[4], g[5]), color_bytes=g[6], buffers=g[7],
                            depth_bytes=g[8] + g[9], depth_test=g[10], depth_write=g[11], blend=g[12],
                            fbo=g[2], tex=g[3], pass_id=g[13], cleared=g[14], fragments=None, loops=[])
                cur.append(last)
        elif ln.startswith("@@COUNT") and last is not None:
            f = ln.split()
            last["fragments"] = int(f[3])
            last["loops"] = [int(x) for x in f[5:]]
        elif ln.startswith("stats: glass 0"):
            m = re.search(r'method (\w+)', ln)
            method = m.group(1) if m else None
    return (frames[-1] if frames else []), method, blits


# --- device disassembly ---------------------------------------------------------------------------------
def windows(path):
    """Per program the text its link and draws bracket (a driver compiles at either)."""
    out = {}
    cur = None
    buf = []
    for ln in open(path, errors="replace"):
        if ln.startswith("@@LINK+") or ln.startswith("@@DRAW+"):
            cur = int(ln.split()[1])
            buf = []
        elif ln.startswith("@@LINK-") or ln.startswith("@@DRAW-"):
            if cur is not None and buf:
                out.setdefault(cur, []).append(buf)
            cur = None
        elif cur is not None:
            buf.append(ln.rstrip("\n"))
    return out


def loops_from_edges(n, edges):
    """edges: (branch index, target index) with target <= branch: back edges. Loops as
    [start, end] ranges, merged per start, each with its own (exclusive) size and depth."""
    ranges = {}
    for b, t in edges:
        if t <= b:
            ranges[t] = max(ranges.get(t, t), b)
    loops = sorted(([s, e] for s, e in ranges.items()), key=lambda r: (r[0], -r[1]))
    return loops


def loop_costs(units, loops):
    """units: cost per instruction index; loops: [start, end]. Returns per loop its depth, parent and
    exclusive cost (its body minus its inner loops), plus the cost outside every loop."""
    info = []
    for i, (s, e) in enumerate(loops):
        parent = None
        for j, (s2, e2) in enumerate(loops):
            if j != i and s2 <= s and e <= e2 and (s2, -e2) < (s, -e):
                if parent is None or (loops[parent][0] <= s2 and e2 <= loops[parent][1]):
                    parent = j
        info.append(dict(start=s, end=e, parent=parent, total=sum(units[s:e + 1])))
    for i, L in enumerate(info):
        depth, p = 1, L["parent"]
        while p is not None:
            depth += 1
            p = info[p]["parent"]
        L["depth"] = depth
        L["own"] = L["total"] - sum(c["total"] for c in info if c["parent"] == i)
    outside = sum(units) - sum(L["total"] for L in info if L["parent"] is None)
    return info, outside


def parse_mali(lines):
    """The last fragment shader in the window: tuples per clause, back edges between clauses."""
    starts = [i for i, ln in enumerate(lines) if ln.startswith("SHADER-DB: MESA_SHADER_FRAGMENT")]
    if not starts:
        return None
    end = starts[-1]
    stat = lines[end]
    begin = 0
    for i in range(end - 1, -1, -1):  # the clause listing is the last before the stats line
        if lines[i].startswith("SHADER-DB:"):
            begin = i + 1
            break
    clauses, cur = [], None
    names = {}
    edges_by_clause = []
    for ln in lines[begin:end]:
        m = re.match(r'^clause_(\d+):', ln)
        if m:
            cur = dict(name=int(m.group(1)), tuples=0, jumps=[])
            names[cur["name"]] = len(clauses)
            clauses.append(cur)
            continue
        if cur is None:
            continue
        t = ln.strip()
        if t.startswith('*'):
            cur["tuples"] += 1
        j = re.search(r'(JUMP|BRANCH\S*)\s.*clause_(\d+)', t)
        if j:
            cur["jumps"].append(int(j.group(2)))
    if not clauses:
        return None
    units = [c["tuples"] for c in clauses]
    edges = []
    for i, c in enumerate(clauses):
        for tgt in c["jumps"]:
            if tgt in names:
                edges.append((i, names[tgt]))
    g = {k: float(v) for v, k in re.findall(r'([\d.]+) ([a-z]+)', stat.split("shader:")[1])}
    sp = re.search(r'(\d+):(\d+) spills:fills', stat)
    return dict(units=units, edges=edges, threads=int(g.get("threads", 2)), regs=0, static=sum(units),
                spills=int(sp.group(1)) if sp else 0, fills=int(sp.group(2)) if sp else 0,
                stat=stat.split("shader:")[1].strip(), loops_reported=int(g.get("loops", 0)))


def parse_v3d(lines):
    idx = [i for i, ln in enumerate(lines) if re.match(r'SHADER-DB-GLSL\d+ - MESA_SHADER_FRAGMENT', ln)]
    if not idx:
        return None
    end = idx[-1]
    stat = lines[end]
    begin = None
    for i in range(end - 1, -1, -1):
        if re.match(r'MESA_SHADER_FRAGMENT prog \d+/\d+ QPU:', lines[i]):
            begin = i + 1
            break
    if begin is None:
        return None
    ins = [ln for ln in lines[begin:end] if re.match(r'^0x[0-9a-f]{16} ', ln)]
    edges = []
    for i, ln in enumerate(ins):
        m = re.search(r'\sb[a-z]*\.[a-z]+\s+(-?\d+)', ln)
        if m:
            edges.append((i, i + 4 + int(m.group(1)) // 8))
    th = re.search(r'(\d+) threads', stat)
    sp = re.search(r'(\d+):(\d+) spills:fills', stat)
    lp = re.search(r'(\d+) loops', stat)
    return dict(units=[1] * len(ins), edges=edges, threads=int(th.group(1)) if th else 4, regs=0,
                static=len(ins), spills=int(sp.group(1)) if sp else 0, fills=int(sp.group(2)) if sp else 0,
                stat=stat.split("shader:")[1].strip(), loops_reported=int(lp.group(1)) if lp else 0)


def parse_adreno(lines):
    idx = [i for i, ln in enumerate(lines) if re.search(r'; FRAG prog \d+/\d+: \d+ instr', ln)]
    if not idx:
        return None
    st0 = idx[-1]
    stat = " ".join(l.split(":", 3)[-1].strip() for l in lines[st0:st0 + 4])
    end = st0 - 1  # the listing ends before the "; FRAG: outputs/inputs" lines, begins after its @const/@in
    while end > 0 and lines[end].startswith("MESA: info: ; "):
        end -= 1
    begin = end
    while begin > 0 and not re.match(r'MESA: info: (@|; )|@@', lines[begin - 1]):
        begin -= 1
    units, labels, branches = [], {}, []
    for ln in lines[begin:end + 1]:
        t = ln[len("MESA: info: "):] if ln.startswith("MESA: info: ") else ln
        t = t.strip()
        if not t or t == "end":
            continue
        m = re.match(r'^l(\d+):$', t)
        if m:
            labels[int(m.group(1))] = len(units)
            continue
        c = 1
        for k, v in re.findall(r'\((nop|rpt)(\d)\)', t):
            c += int(v)
        b = re.search(r'(?:^|\))(jump|br[a-z]*|getone|bany|ball|brac|predt|predf)\b.*#l(\d+)', t)
        if b:
            branches.append((len(units), int(b.group(2))))
        units.append(c)
    edges = [(i, labels[l]) for i, l in branches if l in labels]
    rep = re.search(r'(\d+) instr', stat)
    if rep and sum(units):  # ir3's own count of issue slots (nops included) sets the scale; the listing the shares
        f = int(rep.group(1)) / float(sum(units))
        units = [u * f for u in units]
    full = re.search(r'(\d+) half, (\d+) full', stat)
    lp = re.search(r'(\d+) loops', stat)
    return dict(units=units, edges=edges, threads=0, regs=int(full.group(2)) if full else 0, static=sum(units),
                spills=0, fills=0, stat=stat, loops_reported=int(lp.group(1)) if lp else 0)


PARSE = dict(mali=parse_mali, v3d=parse_v3d, adreno=parse_adreno)


def device_programs(path, dev):
    out = {}
    for prog, bufs in windows(path).items():
        best = None
        for b in bufs:  # the last compile of the program's fragment shader (a draw-time variant wins)
            r = PARSE[dev](b)
            if r:
                best = r
        if best:
            loops = loops_from_edges(len(best["units"]), best["edges"])
            best["loops"], best["outside"] = loop_costs(best["units"], loops)
            out[prog] = best
    return out


# --- loops: trips per fragment ------------------------------------------------------------------------
def const_bound(header, defines):
    """The constant trip bound a loop header states (after the source's #defines), None if none."""
    m = re.search(r'<\s*=?\s*([A-Za-z_0-9+\-* ()/]+?)\s*;', header)
    if not m:
        return None
    expr = m.group(1)
    for _ in range(4):
        expr = re.sub(r'[A-Za-z_]\w*', lambda t: defines.get(t.group(0), t.group(0)), expr)
    if re.fullmatch(r'[0-9+\-*/() ]+', expr):
        try:
            return int(eval(expr))  # noqa: S307 (digits and operators only)
        except Exception:
            return None
    return None


def source_defines(src):
    d = {}
    for m in re.finditer(r'^\s*#\s*define\s+(\w+)\s+([^\n]+)$', src, re.M):
        d[m.group(1)] = m.group(2).strip()
    return d


def match_brace(s, i):
    """Index of the brace closing the one at s[i]."""
    d = 0
    for j in range(i, len(s)):
        if s[j] == '{':
            d += 1
        elif s[j] == '}':
            d -= 1
            if d == 0:
                return j
    return len(s) - 1


def source_tree(src):
    """The fragment shader's loops as the driver sees them after inlining: one instance per loop and call
    path from main, in code order, each with its parent instance. Returns (loops, instances) with
    loops[i] = dict(line, head, bound) for source loop i + 1 and instances = [dict(loop, parent)]."""
    s = strip_comments(src)
    defs = source_defines(src)
    loops = []
    for a, j, k in list(loop_heads(s))[:63]:
        head = ' '.join(s[a:j + 1].split())
        bm = re.search(r'<\s*=?\s*(\w+)\s*;', head)
        cp = bool(bm and re.search(r'\bconst\s+int\s+' + bm.group(1) + r'\b', s))
        loops.append(dict(pos=a, body=(k, match_brace(s, k)), line=s.count('\n', 0, a) + 1,
                          head=head, bound=const_bound(head, defs), const_param=cp))
    funcs = {}
    depth, i = 0, 0
    while i < len(s):  # function bodies: a top-level brace after "name(...)"
        c = s[i]
        if c == '{' and depth == 0:
            m = re.search(r'(\w+)\s*\([^;{}]*\)\s*$', s[max(0, i - 400):i])
            e = match_brace(s, i)
            if m and m.group(1) not in ("if", "for", "while", "switch"):
                funcs.setdefault(m.group(1), []).append((i, e))
            i = e + 1
            continue
        i += 1
    insts = []

    def expand(lo, hi, parent, stack):
        events = []
        for li, L in enumerate(loops):
            if lo < L["pos"] < hi and not any(lo < M["pos"] < L["pos"] and L["pos"] < M["body"][1] and
                                              M["body"][1] < hi for M in loops if M is not L):
                events.append((L["pos"], "loop", li))
        inner = [L for L in loops if lo < L["pos"] < hi]
        for m in re.finditer(r'(?<![A-Za-z0-9_.])(\w+)\s*\(', s[lo:hi]):
            name, at = m.group(1), lo + m.start()
            if name in funcs and name not in stack and not any(L["pos"] <= at <= L["body"][1] for L in inner):
                events.append((at, "call", name))
        for at, kind, what in sorted(events, key=lambda e: e[0]):
            if kind == "loop":
                insts.append(dict(loop=what, parent=parent))
                me = len(insts) - 1
                b0, b1 = loops[what]["body"]
                expand(b0, b1, me, stack)
            else:
                for f0, f1 in funcs[what]:
                    expand(f0, f1, parent, stack + (what,))

    for f0, f1 in funcs.get("main", []):
        expand(f0, f1, None, ("main",))
    return loops, insts


def loop_trips(dev_loops, src, counts, fragments):
    """Executions per fragment of each device loop's body, and what each was matched to.

    The source's loops are inlined into a tree of instances (source_tree), one per call path. The
    device's loops (from its back edges, with their nesting) are matched to the instances of the loops
    the frame executed: the subset of instances whose nesting matches the device's best, dropping
    first the loops of constant bound a driver unrolls. A source loop's measured body executions per
    fragment (llvmpipe) then go to its device copies in equal shares. A device loop left unmatched
    counts once per execution of its parent."""
    loops, insts = source_tree(src)
    C = [counts[i] / fragments if i < len(counts) and fragments else 0.0 for i in range(len(loops))]
    def alive(k):  # executed, and so is every loop around it (a dead #if variant's children are not)
        while k is not None:
            if C[insts[k]["loop"]] <= 0:
                return False
            k = insts[k]["parent"]
        return True
    live = [k for k in range(len(insts)) if alive(k)]
    # the device's tree in code order: parents as indices
    order = sorted(range(len(dev_loops)), key=lambda i: dev_loops[i]["start"])
    dpar = [order.index(dev_loops[i]["parent"]) if dev_loops[i]["parent"] is not None else -1 for i in order]
    k = len(order)

    def kept_parents(sub):
        out = []
        for k2 in sub:
            p = insts[k2]["parent"]
            while p is not None and p not in sub:
                p = insts[p]["parent"]
            out.append(sub.index(p) if p is not None else -1)
        return out

    def skip_cost(k2):
        L = loops[insts[k2]["loop"]]
        b = L["bound"]
        if b is None and L.get("const_param"):
            return 0.05
        return 0.01 * b if b is not None and b <= 32 else 10.0

    best, best_sub = None, None
    import itertools
    n = len(live)
    if k and n:
        kk = min(k, n)
        combos = itertools.combinations(live, kk) if _ncr(n, kk) <= 200000 else [tuple(live[:kk])]
        for sub in combos:
            sub = list(sub)
            kp = kept_parents(sub)
            mism = sum(1 for a, b in zip(kp, dpar[:kk]) if a != b)
            cost = mism + sum(skip_cost(x) for x in live if x not in sub)
            if best is None or cost < best:
                best, best_sub = cost, sub
    trips = [None] * len(dev_loops)
    match = [None] * len(dev_loops)
    for pos, i in enumerate(order):
        if best_sub and pos < len(best_sub):
            li = insts[best_sub[pos]]["loop"]
            L = loops[li]
            match[i] = dict(index=li + 1, line=L["line"], head=L["head"])
    # a source loop's measured executions go to its device copies in equal shares: the cost is then
    # C(L) x the copies' mean body, whatever the split between call sites really is
    for li in set(m["index"] for m in match if m):
        copies = [i for i in range(len(dev_loops)) if match[i] and match[i]["index"] == li]
        for i in copies:
            trips[i] = C[li - 1] / len(copies)
    for i in order:  # unmatched: once per execution of the parent (parents come first in code order)
        if trips[i] is None:
            p = dev_loops[i]["parent"]
            trips[i] = trips[p] if p is not None and trips[p] is not None else 1.0
    return trips, match, best


def _ncr(n, r):
    from math import comb
    return comb(n, r)


# --- the frame model ------------------------------------------------------------------------------------
def program_cost(dev, prog, src, ref_draws):
    """Per-fragment device units of a program, its loops weighted by the executions per fragment counted
    in ref_draws (the 720p frame's draws of the program)."""
    frags = sum(d["fragments"] or 0 for d in ref_draws)
    n = max((len(d["loops"]) for d in ref_draws), default=0)
    counts = [sum(d["loops"][i] for d in ref_draws if i < len(d["loops"])) for i in range(n)]
    trips, match, _ = loop_trips(prog["loops"], src, counts, frags)
    units = prog["outside"] + sum(L["own"] * t for L, t in zip(prog["loops"], trips))
    occ = occupancy_factor(dev, prog["threads"], prog["regs"])
    return dict(units=units, static=prog["static"], occ=occ, trips=trips, match=match)


def passes_of(draws):
    """Draws of one render pass (device_cost_trace.c's pass: no framebuffer change between them)."""
    out = []
    for d in draws:
        if out and out[-1]["pass_id"] == d["pass_id"]:
            out[-1]["draws"].append(d)
        else:
            out.append(dict(pass_id=d["pass_id"], cleared=d["cleared"], draws=[d]))
    return out


def pass_bytes(draws, blits):
    """Bytes a tiler moves to and from memory for the frame's render targets: per pass every colour
    target's tiles stored, and loaded first unless the pass began with a clear; depth and stencil stay
    on chip (not loaded, not stored); a blit reads and writes its rectangle once (4 bytes a pixel)."""
    total = 0
    for ps in passes_of(draws):
        d = ps["draws"][0]
        area = d["vp"][0] * d["vp"][1]
        total += d["color_bytes"] * area * (1 if ps["cleared"] else 2)
    for w, h in blits:
        total += 2 * 4 * abs(w * h)
    return total


def frame_cost(dev, draws, blits, progs, srcdir, ref_draws, ref_srcdir):
    """ms of the frame on the device: fragment issue time + tile loads/stores, with its parts."""
    D = DEV[dev]
    parts = []
    alu_s = 0.0
    by_prog, ref_by_prog = {}, {}
    for d in draws:
        by_prog.setdefault(d["prog"], []).append(d)
    for d in ref_draws:
        ref_by_prog.setdefault(d["prog"], []).append(d)
    names, seen = {}, {}
    for p in by_prog:
        path = os.path.join(srcdir, "p%d.frag" % p)
        src = open(path).read() if os.path.exists(path) else ""
        names[p] = (program_name(src) if src else "?", src)
    for p, ds in by_prog.items():
        name, src = names[p]
        nth = seen.get(name, 0)
        seen[name] = nth + 1
        frags = sum(d["fragments"] or 0 for d in ds)
        if p not in progs:
            parts.append(dict(prog=p, name=name, missing=True, fragments=frags))
            continue
        # the loop counts: this program's own, else the same-named program's in the reference run
        # (V3D's at 720p: the same shader source, the same loops)
        rd = ref_by_prog.get(p) if ref_srcdir == srcdir else None
        if not rd or not any(d["loops"] for d in rd):
            rd = None
            k = 0
            for q, qds in ref_by_prog.items():
                qp = os.path.join(ref_srcdir, "p%d.frag" % q)
                if os.path.exists(qp) and program_name(open(qp).read()) == name:
                    if k == nth:
                        rd = qds
                        break
                    k += 1
        c = program_cost(dev, progs[p], src, rd or ds)
        t = frags * c["units"] * c["occ"] / (D["lanes"] * D["clock"])
        alu_s += t
        parts.append(dict(prog=p, name=name, draws=len(ds), fragments=frags, units=c["units"],
                          static=c["static"], occ=c["occ"], ms=t * 1e3, trips=c["trips"], match=c["match"],
                          spills=progs[p]["spills"], fills=progs[p]["fills"], threads=progs[p]["threads"],
                          regs=progs[p]["regs"], loops=progs[p]["loops"]))
    mem_bytes = pass_bytes(draws, blits)
    mem_s = mem_bytes / D["bw"]
    return dict(ms=(alu_s + mem_s) * 1e3, alu_ms=alu_s * 1e3, mem_ms=mem_s * 1e3, mem_bytes=mem_bytes,
                parts=parts, passes=len(passes_of(draws)))


def run(logdir):
    res = {}
    for dev in DEVICES:
        for scene in SCENES:
            for method in METHODS:
                tag = "%s-%s-%s" % (scene, method, dev)
                dlog = os.path.join(logdir, tag + ".log")
                ref_log = os.path.join(logdir, "%s-%s.llvmpipe.log" % (tag, SIZES[0]))
                if not os.path.exists(dlog) or not os.path.exists(ref_log):
                    continue
                progs = device_programs(dlog, dev)
                ref_draws, _, _ = parse_llvmpipe(ref_log)
                ref_dir = os.path.join(logdir, "%s-%s.src" % (tag, SIZES[0]))
                if not any(d["loops"] for d in ref_draws):  # fragments only: V3D's 720p run counted the loops
                    v3d_log = os.path.join(logdir, "%s-%s-v3d-%s.llvmpipe.log" % (scene, method, SIZES[0]))
                    if os.path.exists(v3d_log):
                        ref_draws, _, _ = parse_llvmpipe(v3d_log)
                        ref_dir = os.path.join(logdir, "%s-%s-v3d-%s.src" % (scene, method, SIZES[0]))
                for size in SIZES:
                    llog = os.path.join(logdir, "%s-%s.llvmpipe.log" % (tag, size))
                    if not os.path.exists(llog):
                        continue
                    draws, used, blits = parse_llvmpipe(llog)
                    if not draws or any(d["fragments"] is None for d in draws):
                        continue
                    fc = frame_cost(dev, draws, blits, progs, os.path.join(logdir, "%s-%s.src" % (tag, size)),
                                    ref_draws, ref_dir)
                    fc["used"] = used
                    res[(dev, scene, method, size)] = fc
    return res


# --- the glmark2 anchor -------------------------------------------------------------------------------
def glmark2_units(logdir, dev):
    """Per-fragment units of glmark2's two programs on the device (no loops in either)."""
    path = os.path.join(logdir, "glmark2-%s.log" % dev)
    out = {}
    if not os.path.exists(path):
        return out
    names = {}
    for ln in open(path, errors="replace"):
        if ln.startswith("@@LINK-"):
            f = ln.split()
            if len(f) >= 3:
                names[int(f[1])] = f[2]
    for p, r in device_programs(path, dev).items():
        if p in names:
            out[names[p]] = r
    return out


def glmark2_cost(logdir, dev, res):
    """glmark2 refract on the bunny's pixels: pass 1 the back faces into an RGBA8 normal map and a depth
    texture (both stored), pass 2 the front faces with light-refract into the RGBA8 screen (cleared)."""
    g = glmark2_units(logdir, dev)
    D = DEV[dev]
    out = {}
    if "glmark2-depth" not in g or "glmark2-refract" not in g:
        return out
    for size in SIZES:
        single = res.get((dev, "bunny", "single", size))
        if not single:
            continue
        kern = [p for p in single["parts"] if p.get("name") == "single"]
        px = kern[0]["fragments"] if kern else 0
        w, h = (int(x) for x in size.split("x"))
        alu = 0.0
        for name in ("glmark2-depth", "glmark2-refract"):
            r = g[name]
            alu += px * r["static"] * occupancy_factor(dev, r["threads"], r["regs"]) / (D["lanes"] * D["clock"])
        mem = (8 + 4) * w * h / D["bw"]
        out[size] = dict(ms=(alu + mem) * 1e3, alu_ms=alu * 1e3, mem_ms=mem * 1e3, px=px,
                         units={k: g[k]["static"] for k in g})
    return out


# --- the page ---------------------------------------------------------------------------------------------
ENUM = ["auto", "single", "cubemap", "wyman", "oliveira", "peel", "exact", "layered"]  # snell_method order
CLASSES = [("sphere", "convex"), ("bunny", "closed concave the cubemap serves"),
           ("torus", "closed concave the cubemap does not serve")]


def fmt(x):
    if x is None:
        return "-"
    return "%.1f" % x if x < 100 else "%.0f" % x


def write_page(logdir, out_md, res):
    version = ""
    vpath = os.path.join(logdir, "version.txt")
    if os.path.exists(vpath):
        version = open(vpath).read().strip()
    L = []
    w = L.append
    w("# What each method would cost on three mobile GPUs: a model")
    w("")
    w("**This is a model, not a measurement.** No GPU ran anything here: the shaders were compiled by each GPU's "
      "real Mesa 22.3.6 compiler over drm-shim (`../../../shared/devices/README.md`), the pixels and loop trips "
      "were counted on llvmpipe, and the two were put together with the clocks and widths stated below. Use it "
      "to rank methods on a device and to size budgets, not as frame times to quote.")
    w("")
    w("Regenerate (about 20 minutes on a 2-core box): `bench/device_cost.sh [BUILD_DIR] [DEVICES_DIR]` "
      "(it writes this page through `bench/device_cost.py`). Built from: %s." % (version or "unknown"))
    w("")
    w("## The model, in short")
    w("")
    w("- A frame is what snell-render draws for one glass object (sphere: the default scene; bunny: "
      "`/usr/share/glmark2/models/bunny.obj`; torus), camera 30/20/3.5, fov 45, procedural environment, "
      "the method's default parameters, its second frame (bakes and other once-per-mesh work are not in it).")
    w("- Each device's frame is the frame snell draws *on that device*: llvmpipe ran it with the device's "
      "profile (`SNELL_DEVICE_PROFILE`) and GL_RENDERER, so it took the device's decisions (a tiler shades "
      "forward where llvmpipe would use screen space; AUTO's pick), and the device's driver compiled the same programs.")
    w("- Per draw: **fragments** shaded, counted on llvmpipe (an atomic counter at the top of the fragment shader, "
      "early depth test on where the shader neither discards nor writes depth): the real pixels of that pass, "
      "overdraw included, at 1280x720 and 1920x1080.")
    w("- Per program: **cost per fragment** in the device's own unit (V3D: QPU instructions; Adreno: ir3 issue "
      "slots, nops included; Mali: clause tuples) from its disassembly. Each loop's body (found from the "
      "disassembly's back edges: V3D branches, ir3 jumps, Bifrost clause jumps) counts as many times per fragment "
      "as it ran: every source loop's body executions were counted on llvmpipe (a counter in each loop body, "
      "1280x720), the device's loops were matched to the source loops by their nesting after inlining, and a "
      "loop the driver unrolled is already in the static count. Branches count both sides (a warp runs both "
      "where its pixels differ). Spill and fill instructions count as instructions; the time their memory "
      "accesses take does not (only the occupancy factor): the detail below gives every program's spills:fills.")
    w("- **Issue time** = fragments x cost x occupancy factor / (lanes x clock). The occupancy factor stands for "
      "latency hiding lost when the compiler runs out of threads: V3D 4 threads 1.0, 2 threads 1.25, 1 thread "
      "1.6; Mali 2 threads 1.0, 1 thread 1.25; Adreno up to 16 full registers 1.0, up to 32 1.25, more 1.6. "
      "These factors are assumptions, not measured.")
    w("- **Memory time** = the render targets' bytes a tiler moves / sustained bandwidth: per render pass "
      "(a framebuffer change starts one) every colour target's tiles are stored, and loaded first unless the "
      "pass began with a clear; depth and stencil stay on chip. Texture reads (environment, cube maps, BVH) are "
      "taken as cached and not counted.")
    w("- Frame time = issue time + memory time (no overlap assumed); vertex shading, triangle setup, "
      "the CPU and the display are left out.")
    w("")
    w("## Devices (assumed configurations)")
    w("")
    w("| device | clock | fragment lanes | unit | sustained bandwidth |")
    w("| --- | --- | --- | --- | --- |")
    for dev in DEVICES:
        D = DEV[dev]
        w("| %s | %d MHz | %s | %s | %s |" % (D["name"], D["clock"] / 1e6, D["lanes_text"], D["unit"], D["bw_text"]))
    w("")
    w("Sources: Raspberry Pi 4: `v3d_freq=500` (the firmware's default core clock for V3D on the Pi 4), "
      "VideoCore VI = V3D 4.2 with 2 slices of 4 QPUs, each QPU 16-way SIMD over 4 cycles (Broadcom's V3D "
      "documentation in Mesa: `src/broadcom/`), LPDDR4-3200 on a 32-bit bus. Adreno 630: Snapdragon 845, 710 MHz, "
      "512 ALUs (Qualcomm's 727 GFLOPS figure), LPDDR4X-1866 4x16-bit. Mali-G52: the G52 in the RK3566/RK3568 "
      "boards Panfrost runs on, taken here as 2 cores of 2 execution engines at 800 MHz (Arm: 1-4 cores, "
      "2-3 engines each, 8-wide warps, one FMA+ADD tuple a clock); a phone's G52 MC2 (Helio G85: 1 GHz) scales by "
      "its clock and engine count. Sustained bandwidth is an assumption (a fraction of peak, stated above).")
    w("")
    # tables
    for dev in DEVICES:
        D = DEV[dev]
        w("## %s" % D["name"])
        w("")
        g = glmark2_cost(logdir, dev, res)
        w("Estimated ms per frame (issue + memory); in brackets what AUTO drew. glmark2's refract on the bunny's "
          "pixels (the anchor): %s." % ", ".join("%s %s ms" % (sz, fmt(g[sz]["ms"])) for sz in SIZES if sz in g))
        w("")
        w("| scene | size | " + " | ".join(METHODS) + " | glmark2 refract |")
        w("| --- | --- | " + " | ".join("---:" for _ in METHODS) + " | ---: |")
        for scene in SCENES:
            for size in SIZES:
                row = []
                for m in METHODS:
                    r = res.get((dev, scene, m, size))
                    cell = fmt(r["ms"]) if r else "-"
                    if r and m == "auto":
                        cell += " (%s)" % (r["used"] or "?")
                    row.append(cell)
                an = fmt(g[size]["ms"]) if (scene == "bunny" and size in g) else ""
                w("| %s | %s | %s | %s |" % (scene, size, " | ".join(row), an))
        w("")
    missing = ["%s %s on %s" % (sc, m, DEV[dv]["renderer"]) for dv in DEVICES for sc in SCENES for m in METHODS
               if (dv, sc, m, SIZES[0]) not in res]
    if missing:
        w("Not modelled (\"-\"): %s: no compile log for them (left out with SKIP: Mesa 22.3.6 compiling exact "
          "for Mali spills heavily and took over 15 minutes a program on the 2-core box)." % ", ".join(missing))
        w("")
    # relative costs
    w("## Cost of each method relative to single, per mesh class (1280x720)")
    w("")
    w("Frame time over single's on the same device and mesh (the model's, 1280x720). Classes as the budget's "
      "(`render/budget.h`): 0 convex (the sphere), 1 closed concave the cubemap serves (the bunny), 2 closed "
      "concave it does not (the torus); 3 (open, non-manifold) is not modelled (0).")
    w("")
    rel = relative(res)
    w("| device | class | " + " | ".join(m for m in METHODS if m != "auto") + " |")
    w("| --- | --- | " + " | ".join("---:" for m in METHODS if m != "auto") + " |")
    for dev in DEVICES:
        for ci, (scene, cname) in enumerate(CLASSES):
            w("| %s | %d %s | %s |" % (DEV[dev]["renderer"], ci, scene, " | ".join(
                "%.2f" % rel[dev][m][ci] if rel[dev][m][ci] else "-" for m in METHODS if m != "auto")))
    w("")
    w("As C (`snell__device_cost`, rows in `snell_method` order: auto, single, cubemap, wyman, oliveira, peel, "
      "exact, layered; columns the 4 classes):")
    w("")
    w("```c")
    w(c_table(rel))
    w("```")
    w("")
    # per pass detail
    w("## Where the time goes (1280x720)")
    w("")
    w("Per device, scene and method: each program's fragments, its cost per fragment (loop-weighted; the "
      "static count beside it), the occupancy factor, and the loops with their executions per fragment and "
      "the source loop each was matched to.")
    w("")
    for dev in DEVICES:
        w("<details><summary>%s</summary>" % DEV[dev]["name"])
        w("")
        w("| scene | method | program | fragments | cost/fragment | static | occupancy | spills:fills | ms | loops: own size x executions (source line) |")
        w("| --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | --- |")
        for scene in SCENES:
            for m in METHODS:
                r = res.get((dev, scene, m, SIZES[0]))
                if not r:
                    continue
                for p in r["parts"]:
                    if p.get("missing"):
                        w("| %s | %s | %s | %d | (not compiled on the device) | | | | | |" % (scene, m, p["name"], p["fragments"]))
                        continue
                    loops = "; ".join("%.0f x %.2f (%s)" % (Lp["own"], t, ("L%d `%s`" % (mm["line"], mm["head"])) if mm else "unmatched")
                                      for Lp, t, mm in zip(p["loops"], p["trips"], p["match"]))
                    w("| %s | %s | %s | %d | %.0f | %.0f | %.2f | %s | %.2f | %s |" % (
                        scene, m, p["name"], p["fragments"], p["units"], p["static"], p["occ"],
                        "%d:%d" % (p["spills"], p["fills"]) if dev != "adreno" else "-", p["ms"], loops))
                w("| %s | %s | (render targets) | | | | | | %.2f | %d passes, %.1f MB |" % (
                    scene, m, r["mem_ms"], r["passes"], r["mem_bytes"] / 1e6))
        w("")
        w("</details>")
        w("")
    w("## What is weakest")
    w("")
    w("- Throughput is issue-bound only: texture fetches and their latency (the BVH walk of exact, the cube and "
      "layer look-ups) are one slot each, and the occupancy factors are guesses; exact and peel, which fetch "
      "most, are the least trustworthy rows.")
    w("- The loop matching is a heuristic (nesting after inlining, constant-bound loops taken as unrolled); the "
      "detail tables show every match so that a wrong one can be seen. Both sides of every branch are counted.")
    w("- The device clocks, engine counts and sustained bandwidths are assumptions about typical boards.")
    w("- Tile memory counts colour only; depth kept on chip and texture reads cached flatter the multi-pass methods (peel).")
    w("- No GPU ran: real frame times need the boards (bench/regen.sh on each).")
    w("")
    os.makedirs(os.path.dirname(os.path.abspath(out_md)), exist_ok=True)
    with open(out_md, "w") as f:
        f.write("\n".join(L))


def relative(res):
    rel = {}
    for dev in DEVICES:
        rel[dev] = {}
        for m in METHODS:
            row = []
            for scene, _ in CLASSES:
                a = res.get((dev, scene, m, SIZES[0]))
                b = res.get((dev, scene, "single", SIZES[0]))
                row.append(a["ms"] / b["ms"] if a and b and b["ms"] > 0 and a.get("used") == m else 0.0)
            row.append(0.0)
            rel[dev][m] = row
    return rel


def c_table(rel):
    out = []
    out.append("static const snell__device_cost device_costs[] = {")
    for dev in DEVICES:
        out.append('    {"%s", {' % DEV[dev]["renderer"])
        for m in ENUM:
            row = rel[dev].get(m, [0.0] * 4) if m != "auto" else [0.0] * 4
            out.append("        {%s}, /* %s */" % (", ".join("%.2ff" % x for x in row), m))
        out.append("    }},")
    out.append("};")
    return "\n".join(out)


if __name__ == "__main__":
    logdir = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build-h4", "device_cost")
    out_md = sys.argv[2] if len(sys.argv) > 2 else os.path.join(ROOT, "bench", "devices", "COSTS.md")
    res = run(logdir)
    write_page(logdir, out_md, res)
    if os.environ.get("DEVICE_COST_VERBOSE"):
      for k, v in sorted(res.items()):
        print(k, v["used"], "%.2f ms (alu %.2f, mem %.2f)" % (v["ms"], v["alu_ms"], v["mem_ms"]))
        for p in v["parts"]:
            if p.get("missing"):
                print("   prog", p["prog"], p["name"], "MISSING on device")
                continue
            print("   prog %d %-14s frags %8d units %7.1f static %5d occ %.2f ms %.3f trips %s" % (
                p["prog"], p["name"], p["fragments"], p["units"], p["static"], p["occ"], p["ms"],
                ["%.2f@L%s" % (t, m["line"] if m else "-") for t, m in zip(p["trips"], p["match"])]))
    print("wrote", out_md)
