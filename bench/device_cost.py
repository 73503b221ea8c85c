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
# the fragment kernels the modelled frames draw (each method's, its passes', the background's), whose
# loops the model must price (tests/scripts/test_device_cost_loops.py checks their forms)
PRICED_KERNELS = ("single.frag", "cubemap.frag", "wyman.frag", "oliveira.frag", "layered.frag", "peel.frag",
                  "peel_layer0.frag", "depth_peel.frag", "exact.frag", "skybox.frag", "layered_bake.frag",
                  "ndcube_bake.frag")
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


class ModelError(Exception):
    """A program the model cannot price faithfully: a device loop with no source loop, or a loop that ran
    with no device loop (device_cost.py stops rather than price it at one trip)."""


# Constant trip counts the drivers may unroll fully (NIR's limits are per driver and body size): a loop
# with a constant bound up to this may be missing on the device; any other loop that ran must be there.
UNROLL_MAX = 32
RUN_TIME = "20 to 25 minutes"  # bench/device_cost.sh's whole run, stated on the page
KEYWORDS = ("if", "for", "while", "switch", "return")


def _pp_value(expr, defs):
    """An #if expression's value (C preprocessor rules for what GLSL ES uses: defined, integers,
    comparisons, && || !, arithmetic); an undefined name is 0."""
    expr = re.sub(r'\bdefined\s*\(\s*(\w+)\s*\)|\bdefined\s+(\w+)',
                  lambda m: '1' if (m.group(1) or m.group(2)) in defs else '0', expr)
    for _ in range(8):
        new = re.sub(r'\b[A-Za-z_]\w*\b', lambda t: '(%s)' % (defs.get(t.group(0)) or '0'), expr)
        if new == expr:
            break
        expr = new
    expr = expr.replace('&&', ' and ').replace('||', ' or ').replace('/', '//')
    expr = re.sub(r'!(?!=)', ' not ', expr)
    expr = re.sub(r'(\d+)[uU]\b', r'\1', expr)
    try:
        return int(eval(expr, {"__builtins__": {}}))  # noqa: S307 (numbers and operators only)
    except Exception as e:
        raise ModelError("cannot evaluate #if %r: %s" % (expr, e))


def active_source(src):
    """The comment-free source with the preprocessor applied in place: the lines of inactive #if branches
    and every directive line blanked (offsets and line numbers kept), and the object-like #defines in
    force. GLSL ES 3.00 section 3.4."""
    s = strip_comments(src)
    out, defs, stack = [], {}, []  # stack: [enclosing active, this branch active, a branch taken]
    for ln in s.split('\n'):
        on = not stack or stack[-1][1]
        t = ln.strip()
        if t.startswith('#'):
            m = re.match(r'#\s*(\w+)\s*(.*)$', t)
            kw, rest = (m.group(1), m.group(2).strip()) if m else ("", "")
            if kw in ("if", "ifdef", "ifndef"):
                c = (rest.split()[0] in defs if kw == "ifdef" else rest.split()[0] not in defs if kw == "ifndef"
                     else bool(_pp_value(rest, defs))) if on else False
                stack.append([on, on and c, c])
            elif kw == "elif" and stack:
                top = stack[-1]
                c = top[0] and not top[2] and bool(_pp_value(rest, defs))
                top[1], top[2] = c, top[2] or c
            elif kw == "else" and stack:
                top = stack[-1]
                top[1], top[2] = top[0] and not top[2], True
            elif kw == "endif" and stack:
                stack.pop()
            elif kw == "define" and on:
                d = re.match(r'(\w+)(\()?\s*(.*)$', rest)
                if d:
                    defs[d.group(1)] = None if d.group(2) else d.group(3).strip()
            elif kw == "undef" and on:
                defs.pop(rest.split()[0] if rest else "", None)
            out.append(' ' * len(ln))
        else:
            out.append(ln if on else ' ' * len(ln))
    return '\n'.join(out), {k: v for k, v in defs.items() if v is not None}


def source_defines(src):
    return active_source(src)[1]


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


def functions(s):
    """Function definitions of preprocessed source s: name -> [(body's open brace, close brace)], found as
    a top-level brace right after "name(...)" (the parenthesis matched backwards, so a macro on the line
    before cannot take the name)."""
    funcs, i = {}, 0
    while i < len(s):
        if s[i] != '{':
            i += 1
            continue
        e = match_brace(s, i)
        j = i - 1
        while j >= 0 and s[j] in ' \t\n':
            j -= 1
        if j >= 0 and s[j] == ')':
            d, k = 0, j
            while k >= 0:
                d += s[k] == ')'
                d -= s[k] == '('
                if d == 0:
                    break
                k -= 1
            m = re.search(r'([A-Za-z_]\w*)\s*$', s[:k])
            if m and m.group(1) not in KEYWORDS:
                funcs.setdefault(m.group(1), []).append((i, e))
        i = e + 1
    return funcs


def source_tree(src):
    """The fragment shader's loops as a driver sees them: the preprocessor applied, every function inlined.
    Returns (loops, instances): loops[i] is source loop i + 1 in device_cost_trace.c's numbering (every
    braced loop of the comment-free text, inactive ones included) with its identity (function, its n-th
    loop there, line, header), constant bound and whether it is active; instances are one per active loop
    and call path from main, in code order: dict(loop, parent)."""
    s = strip_comments(src)
    act, defs = active_source(src)
    funcs = functions(act)
    owner = sorted(((b[0], b[1], n) for n, bs in funcs.items() for b in bs))
    loops, per_func = [], {}
    for a, j, k in list(loop_heads(s))[:63]:
        head = ' '.join(s[a:j + 1].split())
        fn = next((n for f0, f1, n in owner if f0 < a < f1), "?")
        on = act[a] != ' '
        per_func[fn] = per_func.get(fn, 0) + (1 if on else 0)
        bm = re.search(r'<\s*=?\s*(\w+)\s*;', head)
        cp = bool(bm and re.search(r'\bconst\s+int\s+' + bm.group(1) + r'\b', act))
        loops.append(dict(pos=a, body=(k, match_brace(s, k)), line=s.count('\n', 0, a) + 1, head=head,
                          bound=const_bound(head, defs), const_param=cp, active=on, func=fn,
                          ordinal=per_func[fn] if on else 0))
    live = [L for L in loops if L["active"]]
    insts = []

    def expand(lo, hi, parent, stack):
        inner = [L for L in live if lo < L["pos"] < hi]
        top = [L for L in inner if not any(M["pos"] < L["pos"] <= M["body"][1] for M in inner if M is not L)]
        events = [(L["pos"], "loop", loops.index(L)) for L in top]
        for m in re.finditer(r'(?<![\w.])([A-Za-z_]\w*)\s*\(', act[lo:hi]):
            name, at = m.group(1), lo + m.start()
            if name in funcs and name not in stack and not any(L["pos"] <= at <= L["body"][1] for L in top):
                events.append((at, "call", name))
        for at, kind, what in sorted(events, key=lambda e: e[0]):
            if kind == "loop":
                insts.append(dict(loop=what, parent=parent))
                expand(loops[what]["pos"] + 1, loops[what]["body"][1], len(insts) - 1, stack)
            else:
                for f0, f1 in funcs[what]:
                    expand(f0, f1, parent, stack + (what,))

    for f0, f1 in funcs.get("main", []):
        expand(f0, f1, None, ("main",))
    return loops, insts


def loop_form_problems(src, host_defines=None):
    """The loops of a kernel's source (every #if branch, its #includes resolved) the model could not price,
    as "line N: what": a do-while (device_cost_trace.c counts no do-while body), or a loop whose body is not
    a braced block (not counted) and whose bound is not a constant up to UNROLL_MAX after the source's and
    the host's #defines (a driver keeps such a loop, and nothing would say how often it runs)."""
    s = strip_comments(src)
    defs = dict(host_defines or {})
    for m in re.finditer(r'^\s*#\s*define\s+(\w+)\s+([^\n]+)$', s, re.M):
        defs.setdefault(m.group(1), m.group(2).strip())
    braced = set(a for a, _, _ in loop_heads(s))
    out = []
    for m in re.finditer(r'(?<![A-Za-z0-9_])(for|while|do)\b', s):
        a, line = m.start(), s.count('\n', 0, m.start()) + 1
        if m.group(1) == "do" and re.match(r'do\s*\{', s[a:]):
            out.append("line %d: a do-while loop (its body executions are not counted)" % line)
        elif m.group(1) != "do" and re.match(r'(for|while)\s*\(', s[a:]) and a not in braced:
            head = s[a:s.find('\n', a)].strip()
            if m.group(1) == "while" and s[:a].rstrip().endswith('}'):
                continue  # the end of a do-while, reported at its do
            b = const_bound(head, defs)
            if b is None or b > UNROLL_MAX:
                out.append("line %d: `%s`: no braced body and no constant bound up to %d" % (line, head, UNROLL_MAX))
    return out


def loop_name(L):
    return "%s() loop %d, L%d `%s`" % (L["func"], L["ordinal"], L["line"], L["head"])


def match_loops(dev_loops, loops, insts, C):
    """Each device loop's source loop instance, by nesting and code order: the device's loop forest must
    be the source's instance forest with some loops removed (those a driver unrolled or found dead) with
    the loops inside them (a loop of one trip only is removed alone, its inner loops moved up). An
    ordered-forest inclusion (dynamic programming); removing a loop of constant
    bound up to UNROLL_MAX costs a hundredth of its bound (a loop of one trip is never a device loop),
    one that never ran here costs 1, one that ran 100, and a device loop left without a source loop 1000. Returns ({device loop: instance}, [unmatched device loops],
    [source loops that ran, with no constant bound, and kept no device copy])."""
    order = sorted(range(len(dev_loops)), key=lambda i: dev_loops[i]["start"])
    dch, sch = {None: []}, {None: []}
    for i in order:
        dch.setdefault(dev_loops[i]["parent"], []).append(i)
        dch.setdefault(i, [])
    for k, I in enumerate(insts):
        sch.setdefault(I["parent"], []).append(k)
        sch.setdefault(k, [])

    def unrollable(k):  # NIR unrolls a loop of constant bound once no loop is left inside it
        L = loops[insts[k]["loop"]]
        const = (L["bound"] is not None and L["bound"] <= UNROLL_MAX) or L["const_param"]
        return const and all(unrollable(c) for c in sch[k])

    def remove_cost(k):  # the likelier a driver drops the loop, the cheaper: short constant loops first
        L = loops[insts[k]["loop"]]
        if unrollable(k):
            return 0.05 if L["bound"] is None else 0.01 * L["bound"]
        return 1.0 if C[insts[k]["loop"]] <= 0 else 100.0

    def single_trip(k):  # a loop of one iteration is no loop to any driver
        b = loops[insts[k]["loop"]]["bound"]
        return b is not None and b <= 1

    def removed(k):  # a loop goes with every loop inside it (NIR unrolls inner loops first)
        return (0.0 if single_trip(k) else remove_cost(k)) + sum(removed(c) for c in sch[k])

    memo = {}
    sys.setrecursionlimit(max(10000, sys.getrecursionlimit()))

    def f(S, D):
        key = (S, D)
        if key in memo:
            return memo[key]
        if not S and not D:
            r = (0.0, ())
        elif not D:
            c, p = f(S[1:], D)
            r = (c + removed(S[0]), p)
        else:
            d = D[0]
            c, p = f(S, tuple(dch[d]) + D[1:])  # the device loop unmatched
            best = (c + 1000.0, p + ((d, None),))
            if S:
                s = S[0]
                if single_trip(s):  # its body is straight code: the loops inside stay
                    c, p = f(tuple(sch[s]) + S[1:], D)
                else:  # removed with the loops inside it
                    c, p = f(S[1:], D)
                    c += removed(s)
                if c < best[0]:
                    best = (c, p)
                if not single_trip(s):  # matched: inner with inner, the rest with the rest
                    c1, p1 = f(tuple(sch[s]), tuple(dch[d]))
                    c2, p2 = f(S[1:], D[1:])
                    if c1 + c2 < best[0]:
                        best = (c1 + c2, ((d, s),) + p1 + p2)
            r = best
        memo[key] = r
        return r

    _, pairs = f(tuple(sch[None]), tuple(dch[None]))
    got = {d: s for d, s in pairs if s is not None}
    unmatched = [d for d, s in pairs if s is None]
    kept = set(insts[k]["loop"] for k in got.values())
    lost = sorted(set(insts[k]["loop"] for k in range(len(insts)) if insts[k]["loop"] not in kept and
                      not unrollable(k) and C[insts[k]["loop"]] > 0))
    return got, unmatched, lost


def loop_trips(dev_loops, src, counts, fragments):
    """Executions per fragment of each device loop's body, and the source loop each was matched to.

    The source's loops are inlined into a tree of instances (source_tree), one per call path, and the
    device's loops (from its back edges, with their nesting) matched to them (match_loops). A source loop's
    body executions per fragment measured on llvmpipe go to its device copies in equal shares: the cost is
    then C(L) x the copies' mean body, whatever the split between call sites really is. A device loop
    without a source loop, or a loop that ran (no constant bound) without a device loop, raises ModelError."""
    loops, insts = source_tree(src)
    if any(L["active"] for L in loops) and len(counts) < len(loops):
        raise ModelError("%d source loops but %d counted: the 720p run needs SNELL_COST_COUNT=1" %
                         (len(loops), len(counts)))
    C = [counts[i] / fragments if i < len(counts) and fragments else 0.0 for i in range(len(loops))]
    got, unmatched, lost = match_loops(dev_loops, loops, insts, C)
    problems = ["device loop %d (instructions %d-%d) has no source loop" % (i, dev_loops[i]["start"],
                dev_loops[i]["end"]) for i in unmatched]
    problems += ["%s ran %.2f times a fragment but has no device loop" % (loop_name(loops[li]), C[li])
                 for li in lost]
    if problems:
        raise ModelError("; ".join(problems))
    match = [None] * len(dev_loops)
    for i, k in got.items():
        li = insts[k]["loop"]
        L = loops[li]
        match[i] = dict(index=li + 1, line=L["line"], head=L["head"], name=loop_name(L))
    trips = [0.0] * len(dev_loops)
    for li in set(m["index"] for m in match if m):
        copies = [i for i in range(len(dev_loops)) if match[i] and match[i]["index"] == li]
        for i in copies:
            trips[i] = C[li - 1] / len(copies)
    return trips, match, 0.0


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
        # (the same device's 720p run: the same program, the same loops, or the model stops)
        rd = ref_by_prog.get(p) if ref_srcdir == srcdir else None
        if rd is None:
            k = 0
            for q, qds in ref_by_prog.items():
                qp = os.path.join(ref_srcdir, "p%d.frag" % q)
                if os.path.exists(qp) and program_name(open(qp).read()) == name:
                    if k == nth:
                        if source_loops(open(qp).read()) != source_loops(src):
                            raise ModelError("%s: the 720p run's program has other loops" % name)
                        rd = qds
                        break
                    k += 1
        try:
            c = program_cost(dev, progs[p], src, rd or ds)
        except ModelError as e:
            raise ModelError("%s, program %d (%s): %s" % (srcdir, p, name, e))
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
                ref_dir = os.path.join(logdir, "%s-%s.src" % (tag, SIZES[0]))  # its loops counted
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
    w("Made by `bench/device_cost.sh BUILD_DIR DEVICES_DIR` (it writes this page through `bench/device_cost.py`; "
      "DEVICES_DIR: `mesa-22.3.6-devices.tar.xz` unpacked, Debian 12's Mesa 22.3.6; llvmpipe: the system's Mesa "
      "22.3.6). Built from: %s. It takes about %s on the shared 2-core box, most of it llvmpipe counting "
      "the loops of exact and peel at 720p (`KEEP=1` reuses logs, `METHODS=\"peel exact auto\"` narrows the run)."
      % (version or "unknown", RUN_TIME))
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
      "1280x720, on each device's own programs), and each device loop takes its own source loop's count: the "
      "source with its preprocessor applied and every function inlined gives a forest of loops; the device's "
      "loops must be that forest with only the loops a driver unrolls taken out (a constant bound up to %d "
      "and no loop left inside), matched by nesting and code order. A device loop with no source loop, or a "
      "loop that ran with no device loop, stops the model (`device_cost.py` fails, naming it) rather than "
      "price it at one trip. A loop the driver unrolled is already in the static count. Branches count both sides (a warp runs both "
      "where its pixels differ). Spill and fill instructions count as instructions; the time their memory "
      "accesses take does not (only the occupancy factor): the detail below gives every program's spills:fills." % UNROLL_MAX)
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
        w("Not modelled (\"-\"): %s: no logs for them (left out with SKIP or METHODS)." % ", ".join(missing))
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
        w("| scene | method | program | fragments | cost/fragment | static | occupancy | spills:fills | ms | loops: own size x executions (source loop: function, its n-th loop, line) |")
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
                    loops = "; ".join("%.0f x %.2f (%s)" % (Lp["own"], t, mm["name"] if mm else "unmatched")
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
    w("- Loops are matched by nesting and code order, not by name: two sibling loops a driver reorders would "
      "swap their counts (none does here); the detail tables name every match (function, its n-th loop, "
      "line of the program as compiled). A loop's executions are shared evenly between its inlined copies. "
      "Both sides of every branch are counted.")
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


C_NAMES = dict(v3d=("V3D 4.2", "0"), adreno=("Adreno 630", "0"),
               mali=("Mali-G52", "1 /* Panfrost 22.3: local arrays in registers (bench/notes/device_tuning.md) */"))


def c_table(rel):
    """src/core/device_cost.c's g_models, as written there."""
    out = ["static const snell__device_cost g_models[] = {"]
    for dev in DEVICES:
        rows = []
        for m in ENUM[1:]:
            r = rel[dev].get(m, [0.0] * 4)
            rows.append("ROW(%s, %s)" % (m.upper(), ", ".join("1.0f" if m == "single" else
                                                              ("%.2ff" % x if x else "0.0f") for x in r[:3])))
        name, flag = C_NAMES[dev]
        lead = '    {"%s", {' % name
        lines, cur = [], lead
        for i, r in enumerate(rows):
            piece = r + ("," if i + 1 < len(rows) else "},")
            if len(cur) + len(piece) + 1 > 118 and cur.strip() not in ("", lead.strip()):
                lines.append(cur.rstrip())
                cur = " " * len(lead) + piece
            else:
                cur += ("" if cur == lead else " ") + piece
        lines.append(cur)
        out += lines
        out.append("     %s}," % flag)
    out.append("};")
    return "\n".join(out)


if __name__ == "__main__":
    logdir = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build-h4", "device_cost")
    out_md = sys.argv[2] if len(sys.argv) > 2 else os.path.join(ROOT, "bench", "devices", "COSTS.md")
    try:
        res = run(logdir)
    except ModelError as e:
        sys.exit("device_cost.py: %s" % e)
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
