#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""profile_tests.py TRACES PROFILES --ran SETTING... --want SETTING: the tests to run under SETTING.

A device profile changes snell only through the answers core/profile.c gives: an extension, a
limit check, a limit's value. With SNELL_PROFILE_TRACE (set for every test by tests/CMakeLists.txt)
each test writes every such question and its driver's own answer; a run under SETTING keeps them
in TRACES/SETTING/<test>. A test takes the same path under SETTING as under a setting it ran
under when its questions there get the same answers under both: this prints a ctest -R regex of
the tests for which no setting of --ran is such (the others would only repeat a run). A test
that asked nothing in any run asks nothing anywhere. The first --ran must be a run of every test.

SETTING is a profile of PROFILES (test_units' profiles.txt: name, limits, extensions), "none"
(the driver's own answers) or "mesa-overrides" (no profile; the extensions in --removed hidden
by Mesa's MESA_EXTENSION_OVERRIDE). Prints "^$" (no test) when none differs.
"""
import argparse
import os
import re
import sys


def read_profiles(path):
    profiles = {}
    with open(path) as f:
        for line in f:
            w = line.split()
            if w:
                profiles[w[0]] = ([int(x) for x in w[1:] if not x.startswith("GL_")],
                                  {x for x in w[1:] if x.startswith("GL_")})
    return profiles


def answers(lines, setting, profiles, removed):
    """The answers a test's questions get under setting, in order."""
    prof = profiles.get(setting)
    out = []
    for line in lines:
        w = line.split()
        if not w:
            continue
        if w[0] == "ext":  # "ext RAW NAME", the name as asked (maybe empty)
            name = line.split(" ", 2)[2] if len(line.split(" ", 2)) > 2 else ""
            has = w[1] == "1" and not (setting == "mesa-overrides" and name in removed)
            out.append(("ext", name, has and (prof is None or name in prof[1])))
            continue
        if w[0] == "limits":
            raw = [int(x) for x in w[1:]]
            out.append(("limits", setting if prof else "none",
                        tuple(min(r, prof[0][i]) if prof else r for i, r in enumerate(raw))))
            continue
        which, raw = int(w[1]), int(w[-1])
        limit = min(raw, prof[0][which]) if prof else raw
        if w[0] == "check":
            value = int(w[2])
            # a failed check's message names the limit and the profile
            out.append(("check", which, value, "ok" if value <= limit else (limit, setting if prof else "none")))
        else:
            sys.exit(f"profile_tests.py: unknown trace line {line!r}")
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("traces")
    ap.add_argument("profiles")
    ap.add_argument("--ran", action="append", default=[], help="a setting the tests ran under already")
    ap.add_argument("--want", required=True)
    ap.add_argument("--removed", default="", help="extensions Mesa hides, space-separated (mesa-overrides)")
    ap.add_argument("--list", action="store_true", help="one test a line, not a regex")
    a = ap.parse_args()
    profiles = read_profiles(a.profiles)
    for s in a.ran + [a.want]:
        if s not in profiles and s not in ("none", "mesa-overrides"):
            ap.error(f"unknown setting {s!r} (known: none, mesa-overrides, {', '.join(profiles)})")
    removed = set(a.removed.split())
    traces = {}
    for s in a.ran:
        folder = os.path.join(a.traces, s)
        if not os.path.isdir(folder):
            sys.exit(f"profile_tests.py: no traces of {s} in {folder}")
        for test in os.listdir(folder):
            with open(os.path.join(folder, test)) as f:
                traces.setdefault(test, {})[s] = f.read().splitlines()
    chosen = sorted(t for t, runs in traces.items()
                    if all(answers(q, a.want, profiles, removed) != answers(q, s, profiles, removed)
                           for s, q in runs.items()))
    if a.list:
        print("\n".join(chosen))
    else:
        print("^(" + "|".join(re.sub(r"([.\[\]()*+?^$|\\])", r"\\\1", t) for t in chosen) + ")$" if chosen else "^$")
    print(f"profile_tests.py: {a.want}: {len(chosen)} of the {len(traces)} tests that asked answer differently "
          f"from {', '.join(a.ran)}", file=sys.stderr)


if __name__ == "__main__":
    main()
